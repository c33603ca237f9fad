//! The everyday parametric paths (LASSO, efficient frontier, MPC homotopy)
//! against Clarabel's interior-point QP at many parameter values. Clarabel
//! converges to about 1e-6 near degenerate points, so the unknowns are
//! compared loosely and the objective tightly: plcp's must never be worse.

#[path = "../examples/common/everyday_checks.rs"]
mod everyday_checks;
#[path = "../examples/common/qp.rs"]
mod qp;

use plcp::{Method, Status};
use plcp_workspace::everyday;

#[test]
fn lasso_wide_and_tall_against_clarabel() {
    for (n, p, seed) in [(20, 60, 1), (30, 90, 2), (60, 20, 3)] {
        let (x, y) = everyday::lasso_data(n, p, seed, false);
        let (c, t_max) = everyday_checks::lasso(x.as_ref(), y.as_ref(), 15);
        assert_eq!(c.path.status, Status::Reached, "{}", c.path.message);
        assert!(
            c.worst_x < 1e-5,
            "{n}x{p}: coefficients differ by {:.2e}",
            c.worst_x
        );
        assert!(
            c.excess < 1e-10,
            "{n}x{p}: objective excess {:.2e}",
            c.excess
        );
        // every knot is an event of one pair: a coefficient enters or leaves
        for b in &c.path.breakpoints {
            assert_eq!(b.entering.complement(), Some(b.leaving));
        }
        // b = 0 at t_max
        let b0 = everyday::lasso_coef(&c.path, t_max, t_max).unwrap();
        assert!(b0.iter().all(|v| *v == 0.0));
    }
}

#[test]
fn lasso_collinear_against_clarabel() {
    // the coefficients need not be unique; the objective is
    let (x, y) = everyday::lasso_data(25, 75, 4, true);
    let (c, _) = everyday_checks::lasso(x.as_ref(), y.as_ref(), 15);
    assert_eq!(c.path.status, Status::Reached, "{}", c.path.message);
    assert!(c.excess < 1e-10, "objective excess {:.2e}", c.excess);
}

#[test]
fn efficient_frontier_against_clarabel() {
    for seed in [3, 4] {
        let (s, mu) = everyday::portfolio(10, seed);
        let c = everyday_checks::frontier(s.as_ref(), mu.as_ref(), 30);
        assert_eq!(c.path.status, Status::UnboundedRay, "{}", c.path.message);
        assert!(c.path.breakpoints.len() >= 3);
        assert!(c.worst_x < 1e-4, "weights differ by {:.2e}", c.worst_x);
        assert!(c.excess < 1e-12, "objective excess {:.2e}", c.excess);
        // the budget holds on every corner
        for b in &c.path.breakpoints {
            let w = c.path.at(b.lambda).unwrap().z;
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-13);
        }
    }
}

#[test]
fn mpc_homotopy_against_clarabel() {
    let mpc = everyday::Mpc::double_integrator(10, 0.2, 1.0);
    for method in [Method::Lemke, Method::Wolfe] {
        let c = everyday_checks::mpc(&mpc, [-1.0, -0.5], [0.6, 0.8], method, 41);
        assert_eq!(c.path.status, Status::Reached, "{}", c.path.message);
        assert!(c.path.breakpoints.len() >= 5);
        assert_eq!(c.points, 41);
        assert!(
            c.worst_x < 1e-4,
            "{method:?}: inputs differ by {:.2e}",
            c.worst_x
        );
        assert!(
            c.excess < 1e-12,
            "{method:?}: objective excess {:.2e}",
            c.excess
        );
    }
}
