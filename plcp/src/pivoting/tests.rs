//! The condition estimate a path reports ([`Engine::estimate_end_condition`]).

use crate::path::Status;
use crate::settings::{BasisKind, Settings};
use crate::Plcp;
use faer::{mat, Col};

/// `w = q + L d + M z` with `M = [[1, 1], [1, 1 + delta]]` (`cond_1(M)`
/// about `4 / delta`), whose path ends at `L = 1` on the basis `{z1, z2}`
/// (`z = (1/2, 1/2)`) after a few pivots, far fewer than the
/// refactorisation period: before the end estimate the path reported the
/// starting identity basis, `max_condition = 1`.
fn near_rank_one(delta: f64) -> Plcp<f64> {
    let m = mat![[1.0, 1.0], [1.0, 1.0 + delta]];
    let q = Col::from_fn(2, |_| 1.0);
    let d = Col::from_fn(2, |i| if i == 0 { -2.0 } else { -2.0 - delta / 2.0 });
    Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
        .and_then(|p| p.with_range(0.0, Some(1.0)))
        .unwrap()
}

#[test]
fn a_short_path_reports_its_end_basis_condition() {
    let delta = 1e-11;
    for basis in [BasisKind::Block, BasisKind::Dense, BasisKind::Sparse] {
        let settings = Settings::<f64> {
            basis,
            ..Settings::default()
        };
        let path = crate::solve(&near_rank_one(delta), &settings).unwrap();
        println!(
            "{basis:?}: {} after {} pivots, {} refactorisations, max_condition {:.3e}, end {:?}",
            path.status.as_str(),
            path.info.pivots,
            path.info.refactorisations,
            path.info.max_condition,
            path.end.z
        );
        assert_eq!(path.status, Status::Reached, "{}", path.message);
        assert!(path.info.pivots < crate::DEFAULT_REFACTOR_PERIOD);
        assert_eq!(path.info.refactorisations, 0);
        // the end basis holds both columns of M: cond_1 about 4 / delta (the
        // estimate is a lower bound within a small factor)
        assert!(
            path.info.max_condition > 0.1 / delta,
            "{basis:?}: max_condition {:.3e}",
            path.info.max_condition
        );
        assert!(path.info.max_condition < 100.0 / delta);
    }
}

#[test]
fn a_short_ill_conditioned_path_escalates() {
    // cond * eps about 1e-4: above ESCALATE_COND_EPS, below max_cond_eps
    // (at 1e-12 the refinement at the end refactorises: no longer short)
    let delta = 1e-11;
    let problem = near_rank_one(delta);
    let settings = Settings::<f64> {
        escalate: true,
        ..Settings::default()
    };
    let path = crate::solve(&problem, &settings).unwrap();
    println!(
        "escalated: {} {}, escalation {:?}",
        path.status.as_str(),
        path.message,
        path.info.escalation
    );
    assert!(
        path.info.escalation.is_some(),
        "not escalated: max_condition {:.3e}",
        path.info.max_condition
    );
    assert_eq!(path.status, Status::Reached, "{}", path.message);
    // a well-conditioned neighbour is not escalated
    let well = crate::solve(&near_rank_one(0.5), &settings).unwrap();
    assert_eq!(well.status, Status::Reached, "{}", well.message);
    assert!(well.info.escalation.is_none(), "{:?}", well.info.escalation);
}
