//! Statically admissible stress states, for the pieces of the path where the
//! member forces are not unique.
//!
//! There the solver holds one stress state among many, and a hinge that has
//! flowed may appear to leave yield only because of that choice (system (9)
//! asks `y*' x*_dd = 0`, not `y* = 0` where the plastic rate is positive). Before a
//! deactivation is reported, a linear feasibility problem asks whether some
//! stress state keeps every flowed section at yield:
//!
//! ```text
//! find X:   A^T X = a_o Lambda - M_q q_dd(Lambda)       (dynamic equilibrium)
//!           y*_k = X*_k - (T N)_k' X = 0   for the mode each flowed section flowed on
//!           y*_k >= 0                      for every yield mode
//! ```
//!
//! solved by Clarabel (an interior-point solver) at the ends of the piece;
//! the feasible set moves affinely with `Lambda`, so feasibility at both ends
//! holds in between.

use crate::assemble::System;
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
    SupportedConeT, ZeroConeT,
};

/// Whether a stress state exists in equilibrium with `rhs` (`a_o Lambda - M_q
/// q_dd`), within yield everywhere and at yield on every `pinned` mode
/// (indices into [`System::modes`]). `None` if the solver could not decide.
pub fn admissible_with(system: &System, rhs: &[f64], pinned: &[usize]) -> Option<bool> {
    let (nb, ns, np) = (
        system.coordinates.len(),
        system.forces.len(),
        system.modes.len(),
    );
    let (mut ii, mut jj, mut vv) = (Vec::new(), Vec::new(), Vec::new());
    let mut b = Vec::new();
    // equilibrium rows: A^T X = rhs
    for (j, &rj) in rhs.iter().enumerate().take(nb) {
        for r in 0..ns {
            let v = system.a[(r, j)];
            if v != 0.0 {
                ii.push(j);
                jj.push(r);
                vv.push(v);
            }
        }
        b.push(rj);
    }
    let mut row = nb;
    let mode_row =
        |row: usize, k: usize, ii: &mut Vec<usize>, jj: &mut Vec<usize>, vv: &mut Vec<f64>| {
            for r in 0..ns {
                let v = system.tn[(r, k)];
                if v != 0.0 {
                    ii.push(row);
                    jj.push(r);
                    vv.push(v);
                }
            }
        };
    for &k in pinned.iter().filter(|&&k| k < np) {
        mode_row(row, k, &mut ii, &mut jj, &mut vv);
        b.push(system.capacities[k]);
        row += 1;
    }
    let zero_rows = row;
    for k in 0..np {
        mode_row(row, k, &mut ii, &mut jj, &mut vv);
        b.push(system.capacities[k]);
        row += 1;
    }
    let a = CscMatrix::new_from_triplets(row, ns, ii, jj, vv);
    let p = CscMatrix::<f64>::zeros((ns, ns));
    let q = vec![0.0; ns];
    let cones: Vec<SupportedConeT<f64>> =
        vec![ZeroConeT(zero_rows), NonnegativeConeT(row - zero_rows)];
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .max_iter(200)
        .build()
        .ok()?;
    let mut solver = DefaultSolver::new(&p, &q, &a, &b, &cones, settings).ok()?;
    solver.solve();
    match solver.solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => Some(true),
        SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => Some(false),
        _ => None,
    }
}
