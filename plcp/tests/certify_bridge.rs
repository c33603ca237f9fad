//! Certification across events closer than the float path's rounding.
//!
//! Two variables that reach zero `1e-16` apart are one degenerate breakpoint
//! for a float path (two pivots, no segment between them); the exact path
//! has a segment of that length between them, so the previous segment's
//! exact end lies just outside the next segment's exact interval. The
//! certificate bridges such a gap with exact bases (`Certificate::bridges`)
//! when it is within the float path's trust level, and still rejects a
//! path that skips a real segment.

use faer::{Col, Mat};
use plcp::exact::{self, Engine};
use plcp::{Method, Plcp, Settings, Status};

/// `w = q + L d + z` with `M = I`: `w_1` reaches zero at `L = 1`, `w_2` at
/// `1 / (1 + k 2^-52)`, `k` units of rounding before it.
fn close_events(k: f64) -> Plcp<f64> {
    let m = Mat::<f64>::identity(2, 2);
    let q = Col::<f64>::from_fn(2, |_| 1.0);
    let d = Col::<f64>::from_fn(2, |i| {
        if i == 0 {
            -1.0
        } else {
            -(1.0 + k * f64::EPSILON)
        }
    });
    Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
        .unwrap()
        .with_range(0.0, Some(3.0))
        .unwrap()
}

/// The float path takes both events as one breakpoint (two segments); it is
/// right, and certified with one exact basis bridging the two events, by both
/// engines, for both methods. Before bridges it was rejected ("the basis is
/// infeasible where the segment starts").
#[test]
fn events_closer_than_rounding_are_bridged_exactly() {
    for k in [1.0, 4.0, 64.0, 256.0] {
        let problem = close_events(k);
        for method in [Method::Lemke, Method::Wolfe] {
            let settings = Settings::<f64> {
                method,
                ..Settings::default()
            };
            let path = plcp::solve(&problem, &settings).unwrap();
            assert_eq!(path.status, Status::Reached);
            for engine in [Engine::Modular, Engine::Bareiss] {
                let c = exact::certify_with(&problem, &path, engine);
                assert!(c.certified(), "k = {k}, {method:?}: {}", c.summary());
                if path.segments.len() == 2 {
                    assert_eq!(c.bridges, 1, "k = {k}");
                    // the bridge spans the exact gap 1 - 1/(1 + k eps)
                    let gap = k * f64::EPSILON / (1.0 + k * f64::EPSILON);
                    assert!(
                        (c.bridge_span - gap).abs() <= 1e-3 * gap,
                        "{}",
                        c.bridge_span
                    );
                    assert!(c.summary().contains("bridging"));
                }
            }
        }
    }
}

/// A path whose middle segment is removed (events at 1 and 1.5: the float
/// path has three segments) leaves a gap of 0.5 between two exact bases: a
/// real segment missed, far beyond rounding. The certificate rejects it
/// (the bridge would span 1/3 relative, above sqrt(eps)).
#[test]
fn a_skipped_real_segment_is_not_bridged() {
    let m = Mat::<f64>::identity(2, 2);
    let q = Col::<f64>::from_fn(2, |i| [1.0, 1.5][i]);
    let d = Col::<f64>::from_fn(2, |_| -1.0);
    let problem = Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
        .unwrap()
        .with_range(0.0, Some(3.0))
        .unwrap();
    let mut path = plcp::solve(&problem, &Settings::default()).unwrap();
    assert_eq!(path.segments.len(), 3);
    assert!(exact::certify(&problem, &path).certified());
    // drop the middle segment and its breakpoint
    path.segments.remove(1);
    path.segments[1].lambda_from = path.segments[0].lambda_to;
    path.breakpoints.remove(1);
    for b in path.breakpoints.iter_mut().skip(1) {
        b.segment -= 1;
    }
    let c = exact::certify(&problem, &path);
    assert!(!c.certified());
    assert_eq!(c.bridges, 0);
    assert_eq!(c.failure.as_ref().unwrap().segment, 1, "{}", c.summary());
}

/// The Fibonacci block `[[F77, F76], [F76, F75]]` (determinant 1, every
/// entry exact in f64), `q = (1, 2)`, `d = -1`: its exact path has a
/// segment `3.6e-31` long after `L = 3.618...`, which f64 and fx128 take as
/// one degenerate breakpoint. Both paths are certified, with one bridge
/// (before bridges: rejected, the next basis infeasible by `2.2e-31` at the
/// rounded start, and `--certify` reported the path `ill_conditioned`).
#[test]
fn the_fibonacci_block_is_certified_across_its_short_segment() {
    let mut f = vec![0.0f64, 1.0];
    for i in 2..=77 {
        let next = f[i - 1] + f[i - 2];
        f.push(next);
    }
    assert_eq!(f[77], 5527939700884757.0);
    let m = Mat::<f64>::from_fn(2, 2, |i, j| f[77 - i - j]);
    let q = Col::<f64>::from_fn(2, |i| [1.0, 2.0][i]);
    let d = Col::<f64>::from_fn(2, |_| -1.0);
    let problem = Plcp::new(m.as_ref(), q.as_ref(), d.as_ref()).unwrap();
    let path = plcp::solve(&problem, &Settings::default()).unwrap();
    assert_eq!(path.status, Status::UnboundedRay);
    let c = exact::certify(&problem, &path);
    assert!(c.certified(), "{}", c.summary());
    assert_eq!(c.bridges, 1);
    let wide = problem.cast::<faer::fx128>();
    let path = plcp::solve(&wide, &Settings::default()).unwrap();
    let c = exact::certify(&wide, &path);
    assert!(c.certified(), "fx128: {}", c.summary());
    assert_eq!(c.bridges, 1);
}

/// A rounding-level slack that rounding puts on the other side of zero: the
/// float path of `w_1 = 1e-20 + 2 z_1` (`w_1` basic, constant) certified
/// against the same problem with `q_1 = -1e-20`, where that basis is
/// infeasible for every `L`. The rejection names the variable's own value,
/// `-1e-20`; it named its row's, scaled by a power of two to integers
/// (`2^119` times too large here; the rotated 3D run of `frames/tests/space.rs`
/// reported `w430 = -2.9e-4` for `-1.6e-20`).
#[test]
fn a_rounding_level_negative_slack_is_reported_with_its_own_value() {
    let m = Mat::<f64>::from_fn(2, 2, |i, j| if i == j { 2.0 } else { 0.0 });
    let d = Col::<f64>::from_fn(2, |i| if i == 0 { -1.0 } else { 0.0 });
    let problem = |q1: f64| {
        let q = Col::<f64>::from_fn(2, |i| if i == 0 { 1.0 } else { q1 });
        Plcp::new(m.as_ref(), q.as_ref(), d.as_ref()).unwrap()
    };
    let path = plcp::solve(&problem(1e-20), &Settings::default()).unwrap();
    assert_eq!(path.status, Status::UnboundedRay, "{}", path.message);
    assert!(path.certify(&problem(1e-20)).certified());
    for engine in [Engine::Modular, Engine::Bareiss] {
        let c = exact::certify_with(&problem(-1e-20), &path, engine);
        let f = c.failure.as_ref().expect("rejected");
        assert!(
            f.reason.contains("w1 = -1e-20 < 0 for every L"),
            "{engine:?}: {}",
            f.reason
        );
    }
}
