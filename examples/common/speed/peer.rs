//! The peer inside the same run: Clarabel (interior point, Rust) solving the
//! LCP `w = q + L d + M z >= 0, z >= 0, w'z = 0` with symmetric positive
//! definite `M` as the convex QP
//!
//! ```text
//! min 1/2 z'Mz + (q + L d)'z   s.t.  z >= 0
//! ```
//!
//! (its KKT conditions are the LCP). Clarabel's form is `A z + s = b`, `s` in
//! the nonnegative cone, so `A = -I`, `b = 0`. One solver object is built per
//! problem (the KKT system's symbolic factorisation is done once); each value
//! of `L` overwrites the linear term with `update_q` and solves again from
//! Clarabel's cold start (interior-point methods do not warm start).
//!
//! Shared by `benches/path.rs` and `examples/speed_report.rs` through
//! `#[path]`; not a module of either crate.

#![allow(dead_code)]

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus, SupportedConeT,
};
use plcp::Plcp;

/// Clarabel's tolerances: its defaults (`1e-8`), or tight (`1e-12`, near the
/// limit of what an interior-point method reaches in `f64`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tolerance {
    /// Clarabel's defaults.
    Default,
    /// Gap and feasibility tolerances `1e-12`.
    Tight,
}

/// A Clarabel solver for the QP form of one LCP, reusable across `L`.
pub struct ClarabelPeer {
    solver: DefaultSolver<f64>,
    q: Vec<f64>,
    d: Vec<f64>,
    lin: Vec<f64>,
}

impl ClarabelPeer {
    /// Builds the solver for `problem` (standard form, `M` symmetric).
    pub fn new(problem: &Plcp<f64>, tol: Tolerance) -> Self {
        let n = problem.n();
        assert_eq!(problem.free(), 0, "standard form only");
        let m = problem.m();
        let (mut ii, mut jj, mut vv) = (Vec::new(), Vec::new(), Vec::new());
        for j in 0..n {
            for i in 0..=j {
                ii.push(i);
                jj.push(j);
                vv.push(m[(i, j)]);
            }
        }
        let p = CscMatrix::new_from_triplets(n, n, ii, jj, vv);
        let a =
            CscMatrix::new_from_triplets(n, n, (0..n).collect(), (0..n).collect(), vec![-1.0; n]);
        let b = vec![0.0; n];
        let cones: Vec<SupportedConeT<f64>> = vec![NonnegativeConeT(n)];
        let mut builder = DefaultSettingsBuilder::default();
        builder.verbose(false).presolve_enable(false).max_threads(1);
        if tol == Tolerance::Tight {
            builder
                .tol_gap_abs(1e-12)
                .tol_gap_rel(1e-12)
                .tol_feas(1e-12)
                .tol_ktratio(1e-10);
        }
        let settings = builder.build().expect("valid Clarabel settings");
        let q: Vec<f64> = (0..n).map(|i| problem.q()[i]).collect();
        let d: Vec<f64> = (0..n).map(|i| problem.d()[i]).collect();
        let lin = q.clone();
        let solver =
            DefaultSolver::new(&p, &lin, &a, &b, &cones, settings).expect("valid Clarabel data");
        Self { solver, q, d, lin }
    }

    /// Solves at `lambda`; returns `z` and whether Clarabel reported `Solved`
    /// (or `AlmostSolved`).
    pub fn solve_at(&mut self, lambda: f64) -> (Vec<f64>, bool) {
        for i in 0..self.q.len() {
            self.lin[i] = self.q[i] + lambda * self.d[i];
        }
        self.solver
            .update_q(&self.lin)
            .expect("update_q with presolve off");
        self.solver.solve();
        let ok = matches!(
            self.solver.solution.status,
            SolverStatus::Solved | SolverStatus::AlmostSolved
        );
        (self.solver.solution.x.clone(), ok)
    }
}

/// `K` values of `L` evenly spaced on `(L0, L_max]`: `L0 + (L_max - L0) j / K`,
/// `j = 1..K` (with `K = 1`: `L_max` alone).
pub fn sample_lambdas(lambda0: f64, lambda_max: f64, k: usize) -> Vec<f64> {
    (1..=k)
        .map(|j| lambda0 + (lambda_max - lambda0) * j as f64 / k as f64)
        .collect()
}

/// Clarabel at `K` sampled values of `L` (the path approximated by re-solving):
/// `(L, z, solved)` for each, building the solver once.
pub fn clarabel_samples(
    problem: &Plcp<f64>,
    lambda_max: f64,
    k: usize,
    tol: Tolerance,
) -> Vec<(f64, Vec<f64>, bool)> {
    let mut peer = ClarabelPeer::new(problem, tol);
    sample_lambdas(problem.lambda0(), lambda_max, k)
        .into_iter()
        .map(|l| {
            let (z, ok) = peer.solve_at(l);
            (l, z, ok)
        })
        .collect()
}
