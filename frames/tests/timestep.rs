//! The time-stepping integrator (`frames::timestep`) against the exact PLCP
//! response of system (9): first-order convergence, activation times, the
//! rigid phase, warm against cold steps, and the deactivation verdict of every
//! scene in `scenes/`.

use frames::timestep::{
    compare, mean_load, path_state, Continuation, ModeEventKind, StepOptions, StepResponse,
    StepState, TimeStepping,
};
use frames::{Analysis, History};

use crate::common;
use common::timestep::{analysis, run};

const NO_DEACTIVATION: [&str; 6] = [
    "cantilever",
    "cantilever-halftip",
    "portal-sway",
    "portal-vertical",
    "portal-combined",
    "two-storey",
];

fn response_time(a: &Analysis) -> f64 {
    *a.response.time.times.last().unwrap()
}

fn relative_error(a: &Analysis, r: &StepResponse) -> f64 {
    let c = compare(a, r);
    c.displacement_error / c.displacement_scale
}

#[test]
fn cantilever_converges_to_first_order() {
    let a = analysis("cantilever");
    let t_end = response_time(&a);
    let errors: Vec<f64> = [50.0, 100.0, 200.0, 400.0]
        .iter()
        .map(|n| relative_error(&a, &run(&a, t_end / n, t_end)))
        .collect();
    for w in errors.windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!(
            (0.9..=1.1).contains(&order),
            "order {order} from errors {errors:?}"
        );
    }
    // first order with a constant of order one (the pulse is 18 time units long)
    assert!(errors[3] < 0.01, "{errors:?}");
}

#[test]
fn displacement_error_shrinks_with_h_on_every_scene() {
    for name in NO_DEACTIVATION.iter().chain(&["two-storey-sway"]) {
        let a = analysis(name);
        let t_end = response_time(&a);
        let errors: Vec<f64> = [1e-1, 1e-2, 1e-3]
            .iter()
            .map(|rel| relative_error(&a, &run(&a, rel * t_end, t_end)))
            .collect();
        assert!(
            errors[1] < 0.2 * errors[0] && errors[2] < 0.2 * errors[1],
            "{name}: {errors:?}"
        );
        assert!(errors[2] < 0.02, "{name}: {errors:?}");
    }
}

#[test]
fn activation_times_are_the_plcp_ones_to_a_few_steps() {
    for name in NO_DEACTIVATION.iter().chain(&["two-storey-sway"]) {
        let a = analysis(name);
        let t_end = response_time(&a);
        let h = 1e-3 * t_end;
        let r = run(&a, h, t_end);
        let c = compare(&a, &r);
        assert!(c.hinges_compared > 0, "{name}");
        assert!(
            c.activation_error <= 3.0 * h,
            "{name}: activation error {} for h = {h}",
            c.activation_error
        );
        assert_eq!(
            c.extra_activations, 0,
            "{name}: hinges the path does not have"
        );
    }
}

#[test]
fn rigid_below_the_collapse_load_from_rest() {
    // portal-sway collapses at Lambda = t = 4: up to t = 3.9 nothing moves,
    // though M_q is singular (rotations carry no mass) and the free block too
    let a = analysis("portal-sway");
    let r = run(&a, 0.01, 3.9);
    let moved = r
        .end
        .q
        .iter()
        .chain(&r.end.v)
        .fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(moved < 1e-12, "{moved}");
    assert!(r.events.is_empty(), "{:?}", r.events);
    // and just beyond it, it does
    let r = run(&a, 0.01, 4.2);
    assert!(r.end.v.iter().any(|v| v.abs() > 1e-3));
    assert_eq!(
        r.activations().count(),
        4,
        "the four hinges of the sway mechanism"
    );
}

#[test]
fn warm_steps_agree_with_cold_steps_and_pivot_less() {
    let a = analysis("two-storey");
    let t_end = response_time(&a);
    let warm = run(&a, 0.01 * t_end, t_end);
    let cold_options = StepOptions {
        h: 0.01 * t_end,
        t_end,
        warm: false,
        ..StepOptions::default()
    };
    let cold = TimeStepping::new(&a.system, &a.scene.history, &cold_options)
        .unwrap()
        .run(&StepState::rest(&a.system))
        .unwrap();
    assert!(warm.steps.iter().skip(1).all(|s| s.warm));
    assert!(cold.steps.iter().all(|s| !s.warm));
    let scale = warm.end.q.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for (w, c) in warm.end.q.iter().zip(&cold.end.q) {
        assert!((w - c).abs() <= 1e-9 * scale, "{w} vs {c}");
    }
    assert_eq!(
        warm.activations()
            .map(|e| (e.t, e.mode))
            .collect::<Vec<_>>(),
        cold.activations()
            .map(|e| (e.t, e.mode))
            .collect::<Vec<_>>()
    );
    assert!(
        warm.pivots() * 5 < cold.pivots(),
        "warm {} cold {}",
        warm.pivots(),
        cold.pivots()
    );
}

#[test]
fn no_deactivation_where_the_path_has_none() {
    for name in NO_DEACTIVATION {
        let a = analysis(name);
        assert!(a.reading.deactivations().is_empty(), "{name}");
        let t_end = response_time(&a);
        let r = run(&a, 1e-3 * t_end, t_end);
        assert!(
            r.deactivations().is_empty(),
            "{name}: {:?}",
            r.deactivations()
        );
        assert!(
            r.decelerations().is_empty(),
            "{name}: {:?}",
            r.decelerations()
        );
    }
}

#[test]
fn two_storey_sway_deactivation_is_real() {
    let a = analysis("two-storey-sway");
    let plcp_unloaded: Vec<usize> = a
        .reading
        .deactivations()
        .iter()
        .map(|(_, e)| e.group)
        .collect();
    let (lambda_d, t_d) = frames::timestep::plcp_valid_until(&a).unwrap();
    assert!((lambda_d - 6.0).abs() < 1e-9);
    let t_end = response_time(&a);
    let mut stop_times = Vec::new();
    for rel in [1e-3, 2e-4] {
        let h = rel * t_end;
        let r = run(&a, h, t_end);
        // the hinges the path reads as unloading decelerate from Lambda = 6 on ...
        let dec = r.decelerations();
        assert!(!dec.is_empty());
        for e in &dec {
            assert!((e.t - t_d).abs() <= 3.0 * h, "deceleration at {}", e.t);
        }
        // ... and stop, off yield or at it with zero rate: a real deactivation
        let stops = r.deactivations();
        let mut groups: Vec<usize> = stops
            .iter()
            .map(|e| a.reading.group_of[e.section].unwrap())
            .collect();
        groups.sort();
        let mut expected = plcp_unloaded.clone();
        expected.sort();
        assert_eq!(groups, expected, "the same two column-top hinges");
        assert!(stops.iter().all(|e| e.t > t_d + 1.0));
        stop_times.push(stops[0].t);
    }
    // the stop time converges (first order: the two estimates differ by O(h))
    assert!(
        (stop_times[0] - stop_times[1]).abs() < 5e-3 * t_end,
        "{stop_times:?}"
    );
}

#[test]
fn continuation_starts_from_the_exact_state_and_matches_stepping_from_rest() {
    let mut a = analysis("two-storey-sway");
    let t_end = response_time(&a);
    assert!(a.continue_by_time_stepping(5e-4).unwrap());
    let c = a.time_stepping.clone().unwrap();
    let exact = path_state(&a, c.t);
    assert_eq!(c.run.start, exact);
    assert!(
        exact.v.iter().any(|v| v.abs() > 0.1),
        "moving at Lambda = 6"
    );
    assert!((c.run.end.t - t_end).abs() < 1e-9 * t_end);
    // the same response as stepping all the way from rest, to O(h)
    let from_rest = run(&a, 5e-4 * t_end, t_end);
    let scale = from_rest.end.q.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let diff = c
        .run
        .end
        .q
        .iter()
        .zip(&from_rest.end.q)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    assert!(diff < 5e-3 * scale, "{diff} vs {scale}");
    assert_eq!(c.run.deactivations().len(), 2);
    let json = c.to_json(&a);
    let lambda = json["plcp_valid_up_to_lambda"].as_f64().unwrap();
    assert!((lambda - 6.0).abs() < 1e-9, "{lambda}");
    assert_eq!(json["status"], "completed");
    // nothing to continue where the path has no deactivation
    let mut b = analysis("portal-combined");
    assert!(!b.continue_by_time_stepping(1e-3).unwrap());
    assert!(b.time_stepping.is_none());
    assert!(
        Continuation::after_deactivation(&b, &StepOptions::default())
            .unwrap()
            .is_none()
    );
}

#[test]
fn path_state_is_the_exact_response() {
    let a = analysis("cantilever");
    let times = &a.response.time.times;
    let k = times.len() / 2;
    let s = path_state(&a, times[k]);
    let d = &a.response.time.displacement[k];
    for (j, c) in a.system.coordinates.iter().enumerate() {
        let want = d[c.node][c.component.index()];
        assert!((s.q[j] - want).abs() <= 1e-12 * want.abs().max(1.0));
    }
    // the root hinge has flowed: positive rate, positive plastic rotation
    assert!(s.rate.iter().any(|&r| r > 0.0));
    assert!(s.plastic.iter().all(|&p| p >= 0.0));
}

#[test]
fn mean_load_is_exact() {
    let histories = [
        History::Ramp { rate: 2.0 },
        History::Table {
            points: vec![(0.0, 0.0), (1.0, 3.0), (2.5, 3.0), (4.0, 1.0)],
        },
        History::Saturating {
            peak: 5.0,
            tau: 0.7,
        },
    ];
    for h in &histories {
        for (a, b) in [(0.0, 0.3), (0.8, 1.3), (2.0, 3.1), (0.0, 1e-6), (3.9, 5.0)] {
            // composite Simpson with many panels as the reference
            let n = 20000;
            let dx = (b - a) / n as f64;
            let mut sum = h.lambda(a) + h.lambda(b);
            for i in 1..n {
                let w = if i % 2 == 1 { 4.0 } else { 2.0 };
                sum += w * h.lambda(a + i as f64 * dx);
            }
            let reference = sum * dx / 3.0 / (b - a);
            let m = mean_load(h, a, b);
            assert!(
                (m - reference).abs() < 1e-6 * reference.abs().max(1e-3),
                "{h:?} [{a}, {b}]: {m} vs {reference}"
            );
        }
    }
}

#[test]
fn bad_options_and_states_are_errors() {
    let a = analysis("cantilever");
    for o in [
        StepOptions {
            h: 0.0,
            ..StepOptions::default()
        },
        StepOptions {
            t_end: f64::NAN,
            ..StepOptions::default()
        },
        StepOptions {
            rate_tol: 0.0,
            ..StepOptions::default()
        },
        StepOptions {
            decel_tol: 1.5,
            ..StepOptions::default()
        },
    ] {
        assert!(TimeStepping::new(&a.system, &a.scene.history, &o).is_err());
    }
    let ts = TimeStepping::new(&a.system, &a.scene.history, &StepOptions::default()).unwrap();
    let mut wrong = StepState::rest(&a.system);
    wrong.v.pop();
    assert!(ts.run(&wrong).is_err());
    let mut b = analysis("two-storey-sway");
    assert!(b.continue_by_time_stepping(0.0).is_err());
    assert!(b.continue_by_time_stepping(2.0).is_err());
}

#[test]
fn events_name_the_kind() {
    assert_eq!(ModeEventKind::FlowStopped.as_str(), "flow_stopped");
}

#[test]
fn cli_warns_and_continues_by_time_stepping() {
    let scene = format!(
        "{}/../scenes/two-storey-sway.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let frames = || std::process::Command::new(env!("CARGO_BIN_EXE_frames"));
    let plain = frames().args(["run", &scene, "--json"]).output().unwrap();
    assert!(plain.status.success());
    let err = String::from_utf8_lossy(&plain.stderr);
    assert!(err.contains("NOT VALID beyond it"), "{err}");
    let doc: serde_json::Value = serde_json::from_slice(&plain.stdout).unwrap();
    assert!((doc["plcp_valid_up_to_lambda"].as_f64().unwrap() - 6.0).abs() < 1e-9);
    assert!(doc.get("time_stepping").is_none());
    let cont = frames()
        .args([
            "run",
            &scene,
            "--json",
            "--timestep-after",
            "--step",
            "0.01",
        ])
        .output()
        .unwrap();
    assert!(cont.status.success());
    let doc: serde_json::Value = serde_json::from_slice(&cont.stdout).unwrap();
    let ts = &doc["time_stepping"];
    assert_eq!(ts["status"], "completed");
    let kinds: Vec<&str> = ts["events"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["kind"].as_str().unwrap())
        .collect();
    assert!(kinds.contains(&"flow_stopped"), "{kinds:?}");
    // no warning and no time stepping where the path has no deactivation
    let other = format!(
        "{}/../scenes/portal-combined.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let quiet = frames()
        .args(["run", &other, "--json", "--timestep-after"])
        .output()
        .unwrap();
    assert!(quiet.status.success());
    assert!(!String::from_utf8_lossy(&quiet.stderr).contains("NOT VALID"));
    let doc: serde_json::Value = serde_json::from_slice(&quiet.stdout).unwrap();
    assert!(doc.get("time_stepping").is_none());
    // a step out of range is bad input
    let bad = frames()
        .args(["run", &scene, "--timestep-after", "--step", "0"])
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
}

#[test]
fn tiny_steps_keep_the_rigid_phase_exact() {
    // two-storey collapses at Lambda = 4, t = ln 2 = 0.69: 10^4 steps of 5e-5
    // up to t = 0.5 (h / T = 1e-5) must see no motion and no flow
    let a = analysis("two-storey");
    let r = run(&a, 5e-5, 0.5);
    assert_eq!(r.steps.len(), 10_000);
    assert!(
        r.events.is_empty(),
        "{:?}",
        &r.events[..r.events.len().min(3)]
    );
    let moved = r
        .end
        .q
        .iter()
        .chain(&r.end.v)
        .fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(moved < 1e-12, "{moved}");
    // every warm step stays warm: its residual is far below plcp's guard
    assert_eq!(r.cold_restarts, 0);
    // plcp measures a step's residual against the data's unit
    // (`plcp::tolerance::residual_unit`): for a warm step the increment `d`
    // of the right-hand side, 2.7e-4 of its size here, not an absolute 1.
    // The rows of the rigid velocities carry 3e-18 .. 1e-15 of rounding
    // (0.01 .. 4 eps of the data, drifting over the 10^4 steps), which reads
    // 7.5e-12 against the increment (it read 1e-15 against the floor of 1)
    assert!(r.worst_residual() < 1e-10, "{}", r.worst_residual());
}
