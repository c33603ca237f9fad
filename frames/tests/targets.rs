//! Targets (`[[target]]`): the first arrival against a closed form on a
//! one-element cantilever, and against the response integrated independently
//! ([`frames::integrate`]) on a dense grid of times: the first sample past
//! the gap brackets the reported time, and the state there matches.

use frames::integrate::{integrate, AffinePiece};
use frames::model::Component;
use frames::target::Arrival;
use frames::{Analysis, AnalysisOptions, Scene};

fn scene_file(name: &str) -> String {
    format!("{}/../scenes/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn read(name: &str) -> String {
    std::fs::read_to_string(scene_file(name)).unwrap()
}

fn run(src: &str, samples: usize, t_end: Option<f64>) -> Analysis {
    let scene = Scene::from_toml(src, "test.toml").unwrap();
    let a = Analysis::run(
        scene,
        &AnalysisOptions {
            samples,
            t_end,
            ..AnalysisOptions::default()
        },
    )
    .unwrap();
    assert!(a.solution.status.is_success());
    a
}

/// The response's accelerations as affine pieces over the kept coordinates.
fn pieces(a: &Analysis) -> Vec<AffinePiece> {
    a.response
        .intervals
        .iter()
        .map(|iv| {
            let pick = |k: usize| {
                a.system
                    .coordinates
                    .iter()
                    .map(|c| iv.accelerations[c.node][c.component.index()][k])
                    .collect()
            };
            AffinePiece {
                lambda_from: iv.lambda_from,
                lambda_to: iv.lambda_to,
                base: pick(0),
                slope: pick(1),
            }
        })
        .collect()
}

/// `d . r_node` for a vector over the kept coordinates.
fn project(a: &Analysis, node: usize, d: [f64; 3], q: &[f64]) -> f64 {
    a.system
        .coordinates
        .iter()
        .zip(q)
        .filter(|(c, _)| c.node == node)
        .map(|(c, v)| {
            v * match c.component {
                Component::X => d[0],
                Component::Y => d[1],
                Component::Z => d[2],
                _ => 0.0,
            }
        })
        .sum()
}

/// Checks an arrival against the integrated response: the sampled
/// displacement along the direction first reaches the gap in the sample
/// interval that holds the reported time, and at that time the displacement
/// is the gap, the velocity and the kinetic energy agree.
fn check_against_integration(a: &Analysis, arrival: &Arrival, n: usize) {
    let tg = &arrival.target;
    let p = pieces(a);
    let t_end = arrival.t_end;
    let times: Vec<f64> = (0..=n).map(|i| t_end * i as f64 / n as f64).collect();
    let m = integrate(&p, &a.scene.history, &times);
    let u: Vec<f64> = m
        .displacement
        .iter()
        .map(|q| project(a, tg.node, tg.direction, q))
        .collect();
    let first = u.iter().position(|&x| x >= tg.gap);
    match (first, arrival.time) {
        (None, None) => assert!(!arrival.reached),
        (Some(k), Some(t)) => {
            assert!(arrival.reached);
            assert!(k > 0);
            assert!(
                times[k - 1] < t && t <= times[k],
                "reported t = {t}, first sample past the gap at {} (previous {})",
                times[k],
                times[k - 1]
            );
            let at = integrate(&p, &a.scene.history, &[t]);
            let (q, v) = (&at.displacement[0], &at.velocity[0]);
            let scale = tg.gap;
            let ut = project(a, tg.node, tg.direction, q);
            assert!(
                (ut - tg.gap).abs() <= 1e-9 * scale,
                "{ut} vs gap {}",
                tg.gap
            );
            let vt = project(a, tg.node, tg.direction, v);
            let vel = arrival.velocity.unwrap();
            assert!((vt - vel).abs() <= 1e-9 * (1.0 + vt.abs()), "{vt} vs {vel}");
            let ke: f64 = 0.5
                * v.iter()
                    .zip(&a.system.mass)
                    .map(|(v, m)| m * v * v)
                    .sum::<f64>();
            let e = arrival.kinetic_energy.unwrap();
            assert!((ke - e).abs() <= 1e-9 * (1.0 + ke), "{ke} vs {e}");
            assert_eq!(arrival.lambda, Some(a.scene.history.lambda(t)));
        }
        (s, t) => panic!("sampled first crossing {s:?}, reported {t:?}"),
    }
}

const ONE_ELEMENT: &str = r#"
[[node]]
id = "A"
x = 0.0
y = 0.0
[[node]]
id = "B"
x = 2.0
y = 0.0
[[member]]
id = "AB"
from = "A"
to = "B"
plastic_moment = 1.0
[[support]]
node = "A"
fix = ["x", "y", "rz"]
[[mass]]
node = "B"
m = 0.5
[[load]]
node = "B"
fy = -1.0
[[target]]
node = "B"
direction = [0.0, -2.0, 0.0]
gap = 0.2
[history]
kind = "ramp"
rate = 3.0
"#;

/// A massless cantilever of length L with a tip mass m, tip load lambda = r t:
/// rigid up to t1 = Mp / (L r), then rotating about a root hinge with tip
/// acceleration (lambda - Mp/L) / m, so u = r (t - t1)^3 / (6 m): the gap g
/// closes at t1 + (6 m g / r)^(1/3), with speed r (t - t1)^2 / (2 m).
#[test]
fn cantilever_arrival_matches_closed_form() {
    let a = run(ONE_ELEMENT, 51, Some(2.0));
    let (l, mp, m, r, g): (f64, f64, f64, f64, f64) = (2.0, 1.0, 0.5, 3.0, 0.2);
    let t1 = mp / (l * r);
    let t = t1 + (6.0 * m * g / r).cbrt();
    let v = r * (t - t1).powi(2) / (2.0 * m);
    assert_eq!(a.targets.len(), 1);
    let arr = &a.targets[0];
    assert!(arr.reached);
    assert_eq!(arr.target.direction, [0.0, -1.0, 0.0]);
    let rel = |x: f64, y: f64| (x - y).abs() / y.abs();
    assert!(rel(arr.time.unwrap(), t) < 1e-13, "{:?} vs {t}", arr.time);
    assert!(rel(arr.lambda.unwrap(), r * t) < 1e-13);
    assert!(
        rel(arr.velocity.unwrap(), v) < 1e-12,
        "{:?} vs {v}",
        arr.velocity
    );
    assert!(rel(arr.kinetic_energy.unwrap(), 0.5 * m * v * v) < 1e-12);
    check_against_integration(&a, arr, 4000);
    // the JSON object
    let j = a.to_json();
    let o = &j["targets"][0];
    assert_eq!(o["node"], "B");
    assert_eq!(o["reached"], true);
    assert_eq!(o["time"].as_f64(), arr.time);
    assert_eq!(o["kinetic_energy"].as_f64(), arr.kinetic_energy);
    assert!(a
        .to_text()
        .contains("B along [0, -1, 0], gap 0.2: reached at t = "));
}

/// A gap beyond the analysed range, and the opposite direction (the tip
/// moves away): never reached, and said so.
#[test]
fn unreached_targets_say_so() {
    let src = ONE_ELEMENT.replace(
        "gap = 0.2",
        "gap = 0.2\n[[target]]\nnode = \"B\"\ndirection = [0.0, 1.0, 0.0]\ngap = 1e-6\n[[target]]\nnode = \"B\"\ndirection = [0.0, -1.0, 0.0]\ngap = 1e6",
    );
    let a = run(&src, 51, Some(2.0));
    assert_eq!(a.targets.len(), 3);
    for arr in &a.targets[1..] {
        assert!(!arr.reached);
        assert_eq!(arr.time, None);
        check_against_integration(&a, arr, 2000);
    }
    assert_eq!(a.to_json()["targets"][2]["reached"], false);
    assert!(a.to_text().contains("not reached by t = "));
}

/// The paper's cantilever (four masses, several plastic phases) under a
/// table history with a plateau, and a grillage pipe whip under a saturating
/// thrust: targets at several nodes and gaps, oblique directions, against
/// the dense integration.
#[test]
fn arrivals_bracketed_by_the_integrated_response() {
    let mut src = read("cantilever.toml").replace(
        "[history]\nkind = \"ramp\"\nrate = 1.0",
        "[history]\nkind = \"table\"\npoints = [[0.0, 0.0], [2.0, 5.0], [3.0, 5.0], [4.0, 14.0]]",
    );
    assert!(src.contains("kind = \"table\""));
    for (node, d, gap) in [
        ("B", "[0.0, -1.0, 0.0]", 0.05),
        ("B", "[0.0, -1.0, 0.0]", 0.6),
        ("AB.2", "[0.3, -1.0, 0.0]", 0.1),
        ("AB.1", "[0.0, -1.0, 0.0]", 0.02),
        ("B", "[1.0, 0.0, 0.0]", 0.01),
    ] {
        src += &format!("\n[[target]]\nnode = \"{node}\"\ndirection = {d}\ngap = {gap}\n");
    }
    let a = run(&src, 201, Some(5.0));
    assert!(a.targets[..4].iter().all(|t| t.reached));
    for arr in &a.targets {
        check_against_integration(&a, arr, 20000);
    }
    let mut src = read("pipe-whip/l-shaped.toml");
    src += "\n[history]\nkind = \"saturating\"\npeak = 3.0\ntau = 0.4\n";
    for (node, gap) in [("C", 0.05), ("C", 0.3), ("BC.2", 0.1), ("B", 0.01)] {
        src +=
            &format!("\n[[target]]\nnode = \"{node}\"\ndirection = [0.0, 0.0, 1.0]\ngap = {gap}\n");
    }
    let a = run(&src, 201, Some(2.0));
    assert!(a.targets.iter().any(|t| t.reached));
    for arr in &a.targets {
        check_against_integration(&a, arr, 20000);
    }
}

#[test]
fn bad_targets_are_errors_naming_them() {
    let with = |d: &str, gap: &str| {
        ONE_ELEMENT
            .replace("direction = [0.0, -2.0, 0.0]", d)
            .replace("gap = 0.2", gap)
    };
    let err = |src: String| Scene::from_toml(&src, "t.toml").unwrap_err().to_string();
    let e = err(with("direction = [0.0, -1.0, 0.5]", "gap = 0.2"));
    assert!(
        e.starts_with("t.toml:26: target \"B\" direction: dz must be 0"),
        "{e}"
    );
    let e = err(with("direction = [0.0, 0.0, 0.0]", "gap = 0.2"));
    assert!(
        e.contains("target \"B\" direction: must not be zero"),
        "{e}"
    );
    let e = err(with("direction = [0.0, 1.0]", "gap = 0.2"));
    assert!(
        e.contains("target \"B\" direction: must be three finite numbers"),
        "{e}"
    );
    let e = err(with("direction = [0.0, 1.0, 0.0]", "gap = -0.1"));
    assert!(e.contains("target \"B\" gap: must be positive"), "{e}");
    let e = err(with(
        "direction = [0.0, 1.0, 0.0]",
        "gap = 0.1\nspeed = 2.0",
    ));
    assert!(e.contains("speed"), "{e}");
    let e = err(ONE_ELEMENT.replace("node = \"B\"\ndirection", "node = \"Q\"\ndirection"));
    assert!(e.contains("target node: unknown node \"Q\""), "{e}");
    // a grillage target moves in z only
    let g = read("pipe-whip/l-shaped.toml")
        + "\n[[target]]\nnode = \"C\"\ndirection = [1.0, 0.0, 1.0]\ngap = 0.1\n";
    let e = err(g);
    assert!(
        e.contains("target \"C\" direction: dx and dy must be 0"),
        "{e}"
    );
}

/// The restraint scene (thrust along the broken leg rising to a plateau)
/// against the library's time-stepping integrator (backward Euler at
/// velocity level, an independent integrator and solve): the first step
/// whose displacement along the direction reaches the gap converges to the
/// exact arrival as the step is halved (first order), and so does the
/// velocity there.
#[test]
fn arrival_against_time_stepping() {
    use frames::timestep::{StepOptions, StepState, TimeStepping};
    let a = run(&read("pipe-whip/restraint.toml"), 201, None);
    let arr = &a.targets[0];
    assert!(arr.reached);
    let (t, v) = (arr.time.unwrap(), arr.velocity.unwrap());
    let tg = &arr.target;
    let mut errors = Vec::new();
    for steps in [400.0, 800.0, 1600.0] {
        let t_end = 1.5 * t;
        let options = StepOptions {
            h: t_end / steps,
            t_end,
            ..StepOptions::default()
        };
        let ts = TimeStepping::new(&a.system, &a.scene.history, &options).unwrap();
        let r = ts.run(&StepState::rest(&a.system)).unwrap();
        assert!(r.outcome.is_completed());
        let k = r
            .displacement
            .iter()
            .position(|q| project(&a, tg.node, tg.direction, q) >= tg.gap)
            .unwrap();
        let vk = project(&a, tg.node, tg.direction, &r.velocity[k]);
        errors.push(((r.times[k] - t).abs(), (vk - v).abs() / v, r.h));
    }
    // measured: time error 0.33 h, relative velocity error 0.82 h / t
    for (et, ev, h) in &errors {
        assert!(*et <= *h, "time error {et}, h {h}");
        assert!(*ev <= 2.0 * h / t, "velocity error {ev}, h {h}");
    }
    // first order: a quarter of the step, a quarter of the errors
    assert!(errors[2].0 < 0.3 * errors[0].0, "{errors:?}");
    assert!(errors[2].1 < 0.3 * errors[0].1, "{errors:?}");
}
