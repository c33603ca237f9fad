//! Space scenes (`model = "space"`) and their automatic reduction: every
//! planar and grillage scene of `scenes/` (without arcs) written as a space
//! scene gives the same system, breakpoints, hinges and targets (bit for bit
//! in the plane `z = 0`), and the same to rounding after a rigid rotation of
//! the whole scene in space.

use frames::{Analysis, AnalysisOptions, Scene};
use toml::Value;

fn scenes() -> Vec<(String, String)> {
    let root = format!("{}/../scenes", env!("CARGO_MANIFEST_DIR"));
    let mut out = Vec::new();
    for dir in [root.clone(), format!("{root}/pipe-whip")] {
        let mut names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "toml"))
            .collect();
        names.sort();
        for p in names {
            let src = std::fs::read_to_string(&p).unwrap();
            if !src.contains("[[arc]]") {
                out.push((p.display().to_string(), src));
            }
        }
    }
    out
}

/// A rotation matrix from a unit quaternion.
fn rotation(q: [f64; 4]) -> [[f64; 3]; 3] {
    let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
    let [w, x, y, z] = q.map(|v| v / n);
    [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ]
}

fn apply(r: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| r[i][0] * v[0] + r[i][1] * v[1] + r[i][2] * v[2])
}

fn f(t: &toml::value::Table, k: &str) -> f64 {
    t.get(k).and_then(Value::as_float).unwrap_or(0.0)
}

/// The scene written as a space scene: `z = 0`, `plastic_torque` on planar
/// members (not an unknown of the planar model), and, with `rotate`, the
/// whole scene turned rigidly (supports then fix all three translations or
/// rotations where the scene fixed any: `None` if that changes the scene).
fn as_space(src: &str, rotate: Option<[[f64; 3]; 3]>) -> Option<String> {
    let mut v: toml::value::Table = toml::from_str(src).unwrap();
    let model = v
        .get("model")
        .and_then(Value::as_str)
        .unwrap_or("planar")
        .to_string();
    if model == "space" {
        // already a space scene (the riser runs): nothing to rewrite
        return None;
    }
    v.insert("model".into(), Value::String("space".into()));
    let r = rotate.unwrap_or([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    let set3 = |t: &mut toml::value::Table, keys: [&str; 3], w: [f64; 3]| {
        for (k, x) in keys.into_iter().zip(w) {
            if x != 0.0 || t.contains_key(k) || rotate.is_some() {
                t.insert(k.into(), Value::Float(x));
            }
        }
    };
    for n in v.get_mut("node")?.as_array_mut()? {
        let t = n.as_table_mut()?;
        let p = apply(&r, [f(t, "x"), f(t, "y"), 0.0]);
        if rotate.is_some() {
            set3(t, ["x", "y", "z"], p);
        } else {
            t.insert("z".into(), Value::Float(0.0));
        }
    }
    for m in v.get_mut("member")?.as_array_mut()? {
        let t = m.as_table_mut()?;
        if !t.contains_key("plastic_torque") {
            t.insert("plastic_torque".into(), Value::Float(0.75));
        }
    }
    if let Some(loads) = v.get_mut("load").and_then(Value::as_array_mut) {
        for l in loads {
            let t = l.as_table_mut()?;
            let fv = apply(&r, [f(t, "fx"), f(t, "fy"), f(t, "fz")]);
            let mv = apply(&r, [f(t, "mx"), f(t, "my"), f(t, "mz")]);
            if rotate.is_some() {
                for k in ["fx", "fy", "fz", "mx", "my", "mz"] {
                    t.remove(k);
                }
                set3(t, ["fx", "fy", "fz"], fv);
                set3(t, ["mx", "my", "mz"], mv);
            }
        }
    }
    if let Some(targets) = v.get_mut("target").and_then(Value::as_array_mut) {
        for tg in targets {
            let t = tg.as_table_mut()?;
            let d: Vec<f64> = t["direction"]
                .as_array()?
                .iter()
                .map(|x| x.as_float().unwrap())
                .collect();
            let d = apply(&r, [d[0], d[1], d[2]]);
            t.insert(
                "direction".into(),
                Value::Array(d.iter().map(|&x| Value::Float(x)).collect()),
            );
        }
    }
    if rotate.is_some() {
        if let Some(sups) = v.get_mut("support").and_then(Value::as_array_mut) {
            for s in sups {
                let t = s.as_table_mut()?;
                let fix: Vec<String> = t["fix"]
                    .as_array()?
                    .iter()
                    .map(|x| x.as_str().unwrap().to_string())
                    .collect();
                // the scene's own components, and whether they are all of a kind
                let (trans, rot): (&[&str], &[&str]) = if model == "grillage" {
                    (&["z"], &["rx", "ry"])
                } else {
                    (&["x", "y"], &["rz"])
                };
                let has = |set: &[&str]| set.iter().filter(|c| fix.iter().any(|x| x == *c)).count();
                let mut out = Vec::new();
                for (set, three) in [(trans, ["x", "y", "z"]), (rot, ["rx", "ry", "rz"])] {
                    match has(set) {
                        0 => {}
                        n if n == set.len() => out.extend(three),
                        _ => return None,
                    }
                }
                t.insert(
                    "fix".into(),
                    Value::Array(out.into_iter().map(|c| Value::String(c.into())).collect()),
                );
            }
        }
    }
    Some(toml::to_string(&v).unwrap())
}

fn run(src: &str, file: &str) -> Analysis {
    let scene = Scene::from_toml(src, file).unwrap_or_else(|e| panic!("{file}: {e}"));
    Analysis::run(scene, &AnalysisOptions::default()).unwrap_or_else(|e| panic!("{file}: {e}"))
}

/// The numbers that must agree: breakpoints, hinges (node, section, mode),
/// target arrivals.
fn fingerprint(a: &Analysis) -> Fingerprint {
    let bps = a.reading.breakpoints.iter().map(|b| b.lambda).collect();
    let hinges = a
        .reading
        .hinges
        .iter()
        .map(|h| (a.scene.frame.nodes[h.node].id.clone(), h.section, h.mode))
        .collect();
    let targets = a
        .targets
        .iter()
        .map(|t| [t.time, t.lambda, t.kinetic_energy])
        .collect();
    (bps, hinges, targets)
}

type Fingerprint = (Vec<f64>, Vec<(String, usize, usize)>, Vec<[Option<f64>; 3]>);

/// Breakpoints to `1e-9` of the largest, the same hinge nodes in the same
/// order, target arrivals to `1e-7`.
fn close(fa: &Fingerprint, fb: &Fingerprint, what: &str) {
    assert_eq!(
        fa.0.len(),
        fb.0.len(),
        "{what}: breakpoints {:?} vs {:?}",
        fa.0,
        fb.0
    );
    let scale = fa.0.iter().fold(1.0f64, |s, x| s.max(x.abs()));
    for (x, y) in fa.0.iter().zip(&fb.0) {
        assert!(
            (x - y).abs() <= 1e-9 * scale,
            "{what}: breakpoint {x} vs {y}"
        );
    }
    let nodes = |h: &Vec<(String, usize, usize)>| h.iter().map(|x| x.0.clone()).collect::<Vec<_>>();
    assert_eq!(nodes(&fa.1), nodes(&fb.1), "{what}: hinge nodes");
    assert_eq!(fa.2.len(), fb.2.len(), "{what}: targets");
    for (x, y) in fa.2.iter().zip(&fb.2) {
        for (u, v) in x.iter().zip(y) {
            match (u, v) {
                (Some(u), Some(v)) => {
                    assert!(
                        (u - v).abs() <= 1e-7 * u.abs().max(1.0),
                        "{what}: target {u} vs {v}"
                    )
                }
                (None, None) => {}
                _ => panic!("{what}: target reached in one, not the other"),
            }
        }
    }
}

#[test]
fn planar_and_grillage_scenes_written_as_space_are_the_same_bit_for_bit() {
    let mut count = 0;
    for (file, src) in scenes() {
        let Some(space) = as_space(&src, None) else {
            continue;
        };
        let a = run(&src, &file);
        let b = run(&space, &file);
        let r = b.scene.frame.reduction.as_ref().unwrap();
        if !r.global_axes {
            // a straight grillage: solved as planar in the plane of its loads
            assert_eq!(b.scene.frame.model, frames::model::Model::Planar, "{file}");
            close(&fingerprint(&a), &fingerprint(&b), &file);
            count += 1;
            continue;
        }
        assert_eq!(a.scene.frame.model, b.scene.frame.model, "{file}");
        assert_eq!(a.system.a, b.system.a, "{file}: A");
        assert_eq!(a.system.tn, b.system.tn, "{file}: T N");
        assert_eq!(a.system.load, b.system.load, "{file}: a_o");
        assert_eq!(fingerprint(&a), fingerprint(&b), "{file}");
        assert_eq!(
            a.response.time.displacement, b.response.time.displacement,
            "{file}"
        );
        // the report says what was left out and why
        let lines = b.left_out_summary();
        assert!(
            lines.iter().any(|l| l.starts_with("space scene solved as")),
            "{file}: {lines:?}"
        );
        count += 1;
    }
    assert!(count >= 10, "{count} scenes compared");
}

#[test]
fn rigid_rotation_of_a_space_scene_changes_nothing_but_rounding() {
    let rotations = [
        [0.9, 0.3, -0.2, 0.25],
        [0.2, -0.7, 0.5, 0.45],
        [0.0, 1.0, 0.0, 0.0], // a half turn about x: the plane's normal reversed
    ];
    let mut count = 0;
    for (file, src) in scenes() {
        let Some(base) = as_space(&src, None) else {
            continue;
        };
        let a = run(&base, &file);
        for q in rotations {
            let Some(turned) = as_space(&src, Some(rotation(q))) else {
                continue;
            };
            let b = run(&turned, &file);
            close(&fingerprint(&a), &fingerprint(&b), &format!("{file} {q:?}"));
            count += 1;
        }
    }
    assert!(count >= 10, "{count} rotated scenes compared");
}

const SPACE_L: &str = r#"
model = "space"
[[node]]
id = "A"
x = 0.0
y = 0.0
z = 0.0
[[node]]
id = "B"
x = 1.0
y = 0.0
z = 0.0
[[node]]
id = "C"
x = 1.0
y = 0.0
z = 1.0
[[member]]
id = "AB"
from = "A"
to = "B"
plastic_moment = 1.0
plastic_torque = 0.9
mass_per_length = 1.0
elements = 2
[[member]]
id = "BC"
from = "B"
to = "C"
plastic_moment = 1.0
plastic_torque = 0.9
mass_per_length = 1.0
elements = 2
[[support]]
node = "A"
fix = ["x", "y", "z", "rx", "ry", "rz"]
[[load]]
node = "C"
"#;

#[test]
fn a_vertical_frame_is_planar_or_grillage_by_its_loads() {
    let planar = Scene::from_toml(&format!("{SPACE_L}fx = 1.0\n"), "l.toml").unwrap();
    assert_eq!(planar.frame.model, frames::model::Model::Planar);
    let grillage = Scene::from_toml(&format!("{SPACE_L}fy = 1.0\n"), "l.toml").unwrap();
    assert_eq!(grillage.frame.model, frames::model::Model::Grillage);
    let err = Scene::from_toml(&format!("{SPACE_L}fx = 1.0\nfy = 1.0\n"), "l.toml")
        .unwrap_err()
        .to_string();
    assert!(err.contains("general space model"), "{err}");
    let no_z = SPACE_L.replacen("z = 0.0\n", "", 1);
    let err = Scene::from_toml(&format!("{no_z}fx = 1.0\n"), "l.toml")
        .unwrap_err()
        .to_string();
    assert!(err.contains("needs z"), "{err}");
}

/// The riser run of `scenes/pipe-whip/riser.toml` under a ramp (`lambda = t`).
fn riser_ramp() -> Analysis {
    let path = format!(
        "{}/../scenes/pipe-whip/riser.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let src = std::fs::read_to_string(path).unwrap();
    let cut = src.find("[history]").unwrap();
    run(&src[..cut], "riser.toml")
}

#[test]
fn time_stepping_follows_the_path_on_a_space_scene() {
    use frames::timestep::{compare, plcp_valid_until, StepOptions, StepState, TimeStepping};
    let a = riser_ramp();
    assert!(a.scene.frame.reduction.is_some());
    let (lambda, t) = plcp_valid_until(&a).expect("the path unloads at the elbow");
    let elbow = a.system.sections[a.reading.deactivations()[0].1.section].node;
    assert_eq!(a.scene.frame.nodes[elbow].id, "E");
    let t_end = 1.3 * t;
    let mut errors = Vec::new();
    for steps in [500.0, 1000.0] {
        let h = t_end / steps;
        let options = StepOptions {
            h,
            t_end,
            ..StepOptions::default()
        };
        let r = TimeStepping::new(&a.system, &a.scene.history, &options)
            .unwrap()
            .run(&StepState::rest(&a.system))
            .unwrap();
        assert!(r.outcome.is_completed(), "{:?}", r.outcome);
        let c = compare(&a, &r);
        assert_eq!(c.extra_activations, 0, "h = {h}");
        assert!(
            c.activation_error <= 2.0 * h,
            "h = {h}: {}",
            c.activation_error
        );
        errors.push(c.displacement_error / c.displacement_scale);
        // the non-deactivation check: the elbow hinge the path unloads slows
        // down in the stepped response too, within two steps of the path
        let first = r
            .decelerations()
            .first()
            .map(|e| (e.t, a.system.sections[e.section].node))
            .expect("a deceleration");
        assert_eq!(
            first.1, elbow,
            "h = {h}: first deceleration at another node"
        );
        assert!(
            (first.0 - t).abs() <= 2.0 * h,
            "h = {h}: {} vs {t} (Lambda {lambda})",
            first.0
        );
    }
    assert!(errors[1] < errors[0], "{errors:?}");
    assert!(errors[1] < 1e-2, "{errors:?}");
}

/// Static collapse of a statically determinate space cantilever (legs AB
/// along x and BC along y, clamped at A, a tip force at C with components
/// in and out of the plane) by limit analysis with the yield polyhedron:
/// the section forces are `lambda` times known vectors, so the collapse load
/// is the least load factor over the sections. Lower bounds of the smooth
/// surface's `1 / |u|`, rising to it as `k` doubles. (The general space
/// model's PLCP is not assembled yet: this checks the polyhedron alone.)
#[test]
fn polyhedron_collapse_load_rises_to_the_smooth_surfaces() {
    use frames::yield_surface::Polyhedron;
    let tp = 0.906_899_682_117_108_9;
    let force = [0.3, 0.0, -1.0];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let c = [1.0, 1.0, 0.0];
    // (section point, member axis e1, e2); e3 = e1 x e2
    let sections = [
        ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]),
    ];
    let u: Vec<[f64; 3]> = sections
        .iter()
        .map(|&(p, e1, e2)| {
            let arm = [c[0] - p[0], c[1] - p[1], c[2] - p[2]];
            let m = cross(arm, force);
            let e3 = cross(e1, e2);
            [dot(m, e2), dot(m, e3), dot(m, e1) / tp]
        })
        .collect();
    let smooth = u
        .iter()
        .map(|v| 1.0 / dot(*v, *v).sqrt())
        .fold(f64::INFINITY, f64::min);
    let mut last = 0.0;
    for k in [4, 8, 16, 32, 64] {
        let p = Polyhedron::new(k).unwrap();
        let lambda = u
            .iter()
            .map(|v| p.load_factor(*v))
            .fold(f64::INFINITY, f64::min);
        eprintln!(
            "k = {k:>3}: {:>5} facets per section, collapse load {lambda:.6} (smooth {smooth:.6}, {:.2e} below)",
            p.facets().len(),
            (smooth - lambda) / smooth
        );
        assert!(
            lambda <= smooth * (1.0 + 1e-14),
            "k = {k}: above the smooth surface's"
        );
        assert!(lambda >= last * (1.0 - 1e-14), "k = {k}: not rising");
        assert!(
            (smooth - lambda) / smooth <= 1.0 - (2.0 * std::f64::consts::PI / k as f64).cos(),
            "k = {k}: {lambda} vs {smooth}"
        );
        last = lambda;
    }
    assert!((smooth - last) / smooth < 5e-3, "{last} vs {smooth}");
}
