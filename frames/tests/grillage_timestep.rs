//! The time-stepping integrator (`frames::timestep`) on the pipe-whip scenes
//! (`scenes/pipe-whip/`): the straight out-of-plane cantilever (grillage model)
//! agrees with the PLCP path to first order in `h` and never deactivates; the
//! in-plane circular quadrant shows a real deceleration of its root hinge at
//! the PLCP path's first unloading.

use frames::model::Model;
use frames::timestep::{compare, plcp_valid_until};
use frames::Analysis;

use crate::common;
use common::timestep::run;

fn analysis(name: &str) -> Analysis {
    common::timestep::analysis(&format!("pipe-whip/{name}"))
}

#[test]
fn straight_grillage_cantilever_follows_the_path_to_first_order() {
    let a = analysis("straight");
    assert_eq!(a.system.model, Model::Grillage);
    assert!(plcp_valid_until(&a).is_none(), "the path has no unloading");
    // past the last hinge (Lambda = 12, lambda = t)
    let t_end = 15.0;
    let mut errors = Vec::new();
    for steps in [250.0, 500.0, 1000.0] {
        let h = t_end / steps;
        let r = run(&a, h, t_end);
        assert!(
            r.decelerations().is_empty(),
            "h = {h}: {:?}",
            r.decelerations()
        );
        assert!(
            r.deactivations().is_empty(),
            "h = {h}: {:?}",
            r.deactivations()
        );
        let c = compare(&a, &r);
        assert_eq!(c.t, r.end.t);
        assert_eq!(c.extra_activations, 0);
        assert_eq!(c.hinges_compared, a.reading.hinges.len());
        // a hinge is seen at the end of the step it starts in, and backward
        // Euler lags the exact state by O(h)
        assert!(
            c.activation_error <= 2.0 * h,
            "h = {h}: {}",
            c.activation_error
        );
        // the scale is the tip deflection z (translations only, no rotations)
        assert!(c.displacement_scale > 1.0, "{}", c.displacement_scale);
        errors.push(c.displacement_error / c.displacement_scale);
    }
    for w in errors.windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!((0.8..1.2).contains(&order), "order {order}: {errors:?}");
    }
    assert!(errors[2] < 5e-3, "{errors:?}");
}

#[test]
fn quadrant_root_hinge_decelerates_at_the_paths_first_unloading() {
    let a = analysis("quadrant");
    let (lambda, t) = plcp_valid_until(&a).expect("the path unloads");
    assert!((lambda - 1.1385).abs() < 1e-3, "{lambda}");
    let root = a
        .scene
        .frame
        .nodes
        .iter()
        .position(|n| n.id == "A")
        .unwrap();
    let t_end = 1.3 * t;
    let mut gaps = Vec::new();
    for steps in [500.0, 1000.0] {
        let h = t_end / steps;
        let r = run(&a, h, t_end);
        let first = r.decelerations()[0].clone();
        // a real deceleration of the root hinge, not a facet switch or noise
        assert_eq!(a.system.sections[first.section].node, root);
        let stopped = r.deactivations();
        assert!(!stopped.is_empty(), "the root hinge stops before 1.3 t");
        assert_eq!(a.system.sections[stopped[0].section].node, root);
        assert!(stopped[0].y_relative > 0.0, "it leaves yield");
        // Tolerance: the event is reported at the end of the step in which the
        // rate first drops (up to one step late), and the backward-Euler state
        // lags the exact one by O(h) (the activation error of the straight
        // cantilever is below 2 h): |gap| <= 2 h.
        let gap = first.t - t;
        assert!(
            gap.abs() <= 2.0 * h,
            "h = {h}: deceleration at {} vs {t}",
            first.t
        );
        gaps.push(gap);
        // nothing decelerates before the path's first unloading
        assert!(r
            .events
            .iter()
            .all(|e| e.t >= first.t || e.kind == frames::timestep::ModeEventKind::FlowStarted));
    }
    // converges: the gap shrinks with h
    assert!(gaps[1].abs() < gaps[0].abs(), "{gaps:?}");
}
