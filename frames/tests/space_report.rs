//! The report of a general space scene gives each section's bending
//! magnitude, `M2`, the torques and the axial forces (issue 18), checked
//! against statics by hand (cross products of the load about each section,
//! no `A`) and against the smooth yield surface the polyhedron is inscribed
//! in.

use frames::{Analysis, AnalysisOptions, Scene};
use serde_json::Value;

fn run(file: &str) -> (Analysis, Value) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes")
        .join(file);
    let a = Analysis::run(
        Scene::from_file(&path).unwrap(),
        &AnalysisOptions::default(),
    )
    .unwrap();
    let json = a.to_json();
    (a, json)
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// At the static collapse load of the 3D run (a cantilever chain from the
/// clamp A to the break G, loaded at G only, at rest: no inertia forces) every
/// section carries the moment of the load about it, `M_P = (r_G - r_P) x F`:
/// its torque is `M_P . e1`, its bending magnitude the rest of `M_P`, and
/// the element's axial force `F . e1`. The report's values (from the path of
/// system (9), which knows nothing of these cross products) agree.
#[test]
fn first_breakpoint_of_the_3d_run_meets_statics_by_hand() {
    let (a, json) = run("pipe-whip/space-run.toml");
    let fr = &a.scene.frame;
    let d = &json["moments_at_breakpoints"][0];
    let lambda = d["lambda"].as_f64().unwrap();
    assert!((lambda - json["collapse_load"].as_f64().unwrap()).abs() < 1e-15);
    let pos = |i: usize| [fr.nodes[i].x, fr.nodes[i].y, fr.nodes[i].z];
    let g = fr.node_index("G").unwrap();
    let force = [0.0, 0.0, -lambda]; // fz = -1 at G, times Lambda
    let mut checked = 0;
    for m in &fr.members {
        for (j, e) in m.elements.clone().enumerate() {
            let el = &fr.elements[e];
            let e1 = {
                let v = sub(pos(el.to), pos(el.from));
                let n = dot(v, v).sqrt();
                [v[0] / n, v[1] / n, v[2] / n]
            };
            let torque = d["second_forces"][&m.id][j].as_f64().unwrap();
            let axial = d["axial_forces"][&m.id][j].as_f64().unwrap();
            assert!((axial - dot(force, e1)).abs() < 1e-12, "{} N", m.id);
            for (end, node) in [(0, el.from), (1, el.to)] {
                let mp = cross(sub(pos(g), pos(node)), force);
                let t = dot(mp, e1);
                let bend = (dot(mp, mp) - t * t).max(0.0).sqrt();
                let at = &d["bending"][&m.id]["along"][2 * j + end];
                let b = at[1].as_f64().unwrap();
                assert!(
                    (b - bend).abs() < 1e-12 && (torque - t).abs() < 1e-12,
                    "{} element {j} end {end}: bending {b} vs {bend}, torque {torque} vs {t}",
                    m.id
                );
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 2 * fr.elements.len());
}

/// At every breakpoint of the 3D run, every section's `bending` is
/// `hypot(m2, M3)` of the same report and lies, with the torque, inside the
/// smooth surface `(M/Mp)^2 + (T/Tp)^2 <= 1` that the polyhedron is
/// inscribed in; a flowing section is on it to the polyhedron's accuracy
/// (8 longitudes: `cos(pi/8)^2` at worst); and `m2` on an interval's piece,
/// evaluated at the breakpoint that starts it, is the breakpoint's `m2`.
#[test]
fn every_breakpoint_of_the_3d_run_is_inside_the_smooth_surface() {
    let (a, json) = run("pipe-whip/space-run.toml");
    let fr = &a.scene.frame;
    let diagrams = json["moments_at_breakpoints"].as_array().unwrap();
    assert!(diagrams.len() > 50);
    let mut worst: f64 = 0.0;
    for d in diagrams {
        for m in &fr.members {
            let el = &fr.elements[m.elements.start];
            let (mp, tp) = (el.plastic_moment, el.interaction.unwrap().capacity);
            let along = |key: &str| -> Vec<f64> {
                d[key][&m.id]["along"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|p| p[1].as_f64().unwrap())
                    .collect()
            };
            let (m3, m2, b) = (along("members"), along("m2"), along("bending"));
            for i in 0..b.len() {
                assert!((b[i] - m2[i].hypot(m3[i])).abs() <= 1e-15 * (1.0 + b[i]));
                let t = d["second_forces"][&m.id][i / 2].as_f64().unwrap();
                let g = (b[i] / mp).powi(2) + (t / tp).powi(2);
                assert!(g <= 1.0 + 1e-9, "{} at {}: {g}", m.id, d["lambda"]);
                worst = worst.max(g);
            }
        }
    }
    let c = (std::f64::consts::PI / 8.0).cos().powi(2);
    assert!(worst > c && worst <= 1.0 + 1e-9, "largest {worst}");
    // the piece's affine m2 meets the breakpoint's value where it starts
    let mut met = 0;
    for iv in json["intervals"].as_array().unwrap() {
        for p in iv["pieces"].as_array().unwrap() {
            let l = p["lambda_from"].as_f64().unwrap();
            let Some(d) = diagrams.iter().find(|d| d["lambda"].as_f64() == Some(l)) else {
                continue;
            };
            for m in &fr.members {
                let piece = p["m2"][&m.id]["along"].as_array().unwrap();
                let at = d["m2"][&m.id]["along"].as_array().unwrap();
                for (x, y) in piece.iter().zip(at) {
                    let (b, s) = (x[1][0].as_f64().unwrap(), x[1][1].as_f64().unwrap());
                    let v = y[1].as_f64().unwrap();
                    assert!((b + s * l - v).abs() <= 1e-9 * (1.0 + v.abs()));
                }
            }
            met += 1;
        }
    }
    assert!(met > 10, "{met} pieces checked");
}

/// Planar and grillage scenes (and space scenes reduced to them) keep their
/// report: no `m2`, `bending` or `axial_forces` keys.
#[test]
fn reduced_and_planar_scenes_have_no_space_keys() {
    for file in [
        "cantilever.toml",
        "pipe-whip/riser.toml",
        "pipe-whip/semicircle.toml",
    ] {
        let (_, json) = run(file);
        let d = &json["moments_at_breakpoints"][0];
        for key in ["m2", "bending", "axial_forces"] {
            assert!(d.get(key).is_none(), "{file}: {key}");
        }
    }
}
