//! Independent references for system (9), shared by the tests of `frames`
//! and of the workspace (`tests/frames_checks.rs` includes this file with
//! `#[path]`): limit analysis as an LP and the accelerations as the convex QP
//! of the notes, both solved by Clarabel (an interior-point method, so
//! nothing is shared with plcp's pivoting).
//!
//! * Lower-bound theorem: `max L` s.t. `A' X = a_o L`, `(T N)' X <= X*`.
//! * The QP: `min 1/2 a' M_q a - L a_o' a + X*' x` s.t. `A a = T N x`,
//!   `x >= 0`; its minimiser's `a` are the accelerations at `L`.

#![allow(dead_code)] // each including test uses what it needs

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
    SupportedConeT, ZeroConeT,
};
use frames::System;

/// Clarabel's gap and feasibility tolerances (absolute and relative) used
/// for both references.
pub const TOL: f64 = 1e-11;

/// Triplets `(rows, cols, values)` of a sparse matrix.
pub type Triplets = (Vec<usize>, Vec<usize>, Vec<f64>);

/// `min 1/2 x'Px + q'x` s.t. `A x + s = b`, the first `zero` rows of `s` zero
/// and the rest nonnegative; panics (a test failure) unless Clarabel says
/// `Solved`.
pub fn conic(
    p: CscMatrix<f64>,
    q: Vec<f64>,
    a: Triplets,
    b: Vec<f64>,
    zero: usize,
    n: usize,
) -> Vec<f64> {
    let rows = b.len();
    let a = CscMatrix::new_from_triplets(rows, n, a.0, a.1, a.2);
    let cones: Vec<SupportedConeT<f64>> = vec![ZeroConeT(zero), NonnegativeConeT(rows - zero)];
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .tol_gap_abs(TOL)
        .tol_gap_rel(TOL)
        .tol_feas(TOL)
        .build()
        .unwrap();
    let mut solver = DefaultSolver::new(&p, &q, &a, &b, &cones, settings).unwrap();
    solver.solve();
    assert!(
        matches!(solver.solution.status, SolverStatus::Solved),
        "{:?}",
        solver.solution.status
    );
    solver.solution.x.clone()
}

/// The static collapse load by the lower-bound theorem with the system's own
/// yield modes (polygons and polyhedra included).
pub fn lp_collapse_load(sys: &System) -> f64 {
    let (nb, ns, np) = (sys.coordinates.len(), sys.forces.len(), sys.modes.len());
    let n = ns + 1;
    let (mut ii, mut jj, mut vv, mut b) = (vec![], vec![], vec![], vec![]);
    for j in 0..nb {
        for r in 0..ns {
            if sys.a[(r, j)] != 0.0 {
                ii.push(j);
                jj.push(r);
                vv.push(sys.a[(r, j)]);
            }
        }
        ii.push(j);
        jj.push(ns);
        vv.push(-sys.load[j]);
        b.push(0.0);
    }
    for k in 0..np {
        for r in 0..ns {
            if sys.tn[(r, k)] != 0.0 {
                ii.push(nb + k);
                jj.push(r);
                vv.push(sys.tn[(r, k)]);
            }
        }
        b.push(sys.capacities[k]);
    }
    let mut q = vec![0.0; n];
    q[ns] = -1.0;
    conic(CscMatrix::zeros((n, n)), q, (ii, jj, vv), b, nb, n)[ns]
}

/// The accelerations (one per kept coordinate) at `lambda`, by the QP.
pub fn qp_accelerations(sys: &System, lambda: f64) -> Vec<f64> {
    let (nb, ns, np) = (sys.coordinates.len(), sys.forces.len(), sys.modes.len());
    let n = nb + np;
    let (p, a, b) = qp_blocks(sys, 1.0);
    let mut q: Vec<f64> = sys.load.iter().map(|l| -lambda * l).collect();
    q.extend(sys.capacities.iter().cloned());
    conic(p, q, a, b, ns, n)[..nb].to_vec()
}

/// The blocks of the QP in the unknowns `(a, x)`, `nb + np` of them: `P` the
/// mass diagonal divided by `dt` (1 for the accelerations; a step `dt` for
/// the velocity-level step of `examples/pipe_whip.rs`), and the constraints
/// `A a - T N x = 0` (the first `s` rows, zero cone) and `x >= 0` (`-x + s =
/// 0`, `s` nonnegative) as `(triplets, b)`.
pub fn qp_blocks(sys: &System, dt: f64) -> (CscMatrix<f64>, Triplets, Vec<f64>) {
    let (nb, ns, np) = (sys.coordinates.len(), sys.forces.len(), sys.modes.len());
    let n = nb + np;
    let p = CscMatrix::new_from_triplets(
        n,
        n,
        (0..nb).collect(),
        (0..nb).collect(),
        sys.mass.iter().map(|m| m / dt).collect(),
    );
    let (mut ii, mut jj, mut vv, mut b) = (vec![], vec![], vec![], vec![]);
    for r in 0..ns {
        for j in 0..nb {
            if sys.a[(r, j)] != 0.0 {
                ii.push(r);
                jj.push(j);
                vv.push(sys.a[(r, j)]);
            }
        }
        for k in 0..np {
            if sys.tn[(r, k)] != 0.0 {
                ii.push(r);
                jj.push(nb + k);
                vv.push(-sys.tn[(r, k)]);
            }
        }
        b.push(0.0);
    }
    for k in 0..np {
        ii.push(ns + k);
        jj.push(nb + k);
        vv.push(-1.0);
        b.push(0.0);
    }
    (p, (ii, jj, vv), b)
}
