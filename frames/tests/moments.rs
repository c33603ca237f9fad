//! The reported moment fields, read from the JSON document a user reads
//! (`Analysis::to_json`, `frames run --json`), on every scene in `scenes/`
//! and its subdirectories (read at run time):
//!
//! - no reported moment exceeds its section's plastic moment beyond
//!   [`frames::response::force_tolerance`] (relative to the larger of the
//!   section's plastic moment and the largest moment of the field), at the ends of every piece of
//!   every interval and at points inside it;
//! - the field is continuous in `Lambda`: consecutive pieces of an interval
//!   and consecutive intervals agree at their common breakpoint, and
//!   `moments_at_breakpoints` is the field there.
//!
//! An interval's field is its `pieces` (each `[base, slope]` on its own
//! `[lambda_from, lambda_to]`); a reader of the format before pieces were
//! added reads the interval's `moments` on the whole interval, and so does
//! this test when `pieces` is absent.
//!
//! And the fixed-fixed beam of four elements loaded at mid-span
//! (`scenes/fixed-beam.toml`) against its closed form: collapse at
//! `P_c = 8 Mp / l`, and in the rigid phase a field in equilibrium with the
//! load (`M_mid - (M_A + M_B) / 2 = P l / 4`, linear between the nodes).

use frames::{Analysis, AnalysisOptions, Scene};
use serde_json::Value;
use std::path::{Path, PathBuf};

fn scene_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            scene_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "toml") {
            out.push(p);
        }
    }
}

fn all_scenes() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let mut files = Vec::new();
    scene_files(&dir, &mut files);
    files.sort();
    assert!(files.len() >= 17, "{files:?}");
    files
}

fn analyse(path: &Path) -> Analysis {
    let scene = Scene::from_file(path).unwrap();
    Analysis::run(
        scene,
        &AnalysisOptions {
            samples: 21,
            ..AnalysisOptions::default()
        },
    )
    .unwrap()
}

/// One affine field on `[from, to]`: per member, per element end, `[base, slope]`.
struct Field {
    from: f64,
    to: f64,
    members: Value,
}

fn lam(v: &Value) -> f64 {
    v.as_f64().unwrap_or(f64::INFINITY)
}

/// The pieces of an interval's moment field as the JSON gives them.
fn fields(iv: &Value) -> Vec<Field> {
    match iv.get("pieces") {
        Some(ps) => ps
            .as_array()
            .unwrap()
            .iter()
            .map(|p| Field {
                from: lam(&p["lambda_from"]),
                to: lam(&p["lambda_to"]),
                members: p["moments"].clone(),
            })
            .collect(),
        None => vec![Field {
            from: lam(&iv["lambda_from"]),
            to: lam(&iv["lambda_to"]),
            members: iv["moments"].clone(),
        }],
    }
}

/// A moment field at one `Lambda`: (member, element end index, value) per section.
type Values = Vec<(String, usize, f64)>;

/// Every section's moment at `l`.
fn values_at(members: &Value, l: f64) -> Values {
    let mut out = Vec::new();
    for (id, m) in members.as_object().unwrap() {
        for (k, e) in m["along"].as_array().unwrap().iter().enumerate() {
            let [b, s] = [e[1][0].as_f64().unwrap(), e[1][1].as_f64().unwrap()];
            out.push((id.clone(), k, b + s * l));
        }
    }
    out
}

/// The largest `|M|` of a field.
fn largest(x: &[(String, usize, f64)]) -> f64 {
    x.iter().fold(0.0f64, |m, v| m.max(v.2.abs()))
}

/// Per member: the plastic moment of each element end, in `along` order.
fn capacities(a: &Analysis) -> std::collections::HashMap<String, Vec<f64>> {
    let fr = &a.scene.frame;
    fr.members
        .iter()
        .map(|m| {
            let c = m
                .elements
                .clone()
                .flat_map(|e| [fr.elements[e].plastic_moment; 2])
                .collect();
            (m.id.clone(), c)
        })
        .collect()
}

/// Points of `[from, to]` to check: both ends and three inside (an unbounded
/// piece up to twice its start).
fn samples(from: f64, to: f64) -> Vec<f64> {
    let to = if to.is_finite() {
        to
    } else {
        from + 2.0 * from.abs().max(1.0)
    };
    (0..=4)
        .map(|i| from + (to - from) * i as f64 / 4.0)
        .collect()
}

/// Failures of one scene, as readable lines.
fn check_scene(path: &Path) -> Vec<String> {
    let a = analyse(path);
    let v = a.to_json();
    let tol = frames::response::force_tolerance(&a.solution);
    let cap = capacities(&a);
    let mut bad = Vec::new();
    let name = path.file_name().unwrap().to_string_lossy().to_string();
    let ivs = v["intervals"].as_array().unwrap();
    let mut last_end: Option<(f64, Values)> = None;
    let join = |what: String,
                l: f64,
                x: &[(String, usize, f64)],
                y: &[(String, usize, f64)],
                bad: &mut Vec<String>| {
        assert_eq!(x.len(), y.len());
        let s = largest(x).max(largest(y));
        for ((m, k, p), (_, _, q)) in x.iter().zip(y) {
            if (p - q).abs() > tol * cap[m][*k].max(s) {
                bad.push(format!(
                    "{name}: {what} at Lambda = {l}: {m}[{k}] {p} against {q}"
                ));
                return;
            }
        }
    };
    for (i, iv) in ivs.iter().enumerate() {
        for f in fields(iv) {
            if let Some((l, prev)) = &last_end {
                join(
                    format!("interval {i} does not join its predecessor"),
                    *l,
                    prev,
                    &values_at(&f.members, *l),
                    &mut bad,
                );
            }
            for l in samples(f.from, f.to) {
                let at = values_at(&f.members, l);
                let s = largest(&at);
                for (m, k, x) in at {
                    let mp = cap[&m][k];
                    if x.abs() > mp + tol * mp.max(s) {
                        bad.push(format!(
                            "{name}: interval {i} [{}, {}] at Lambda = {l}: |M| of {m}[{k}] = {x} > Mp = {mp}",
                            f.from, f.to
                        ));
                    }
                }
            }
            last_end =
                f.to.is_finite()
                    .then(|| (f.to, values_at(&f.members, f.to)));
        }
    }
    // moments_at_breakpoints: the field at the start of each plastic interval
    let diagrams = v["moments_at_breakpoints"].as_array().unwrap();
    let plastic: Vec<&Value> = ivs.iter().filter(|iv| iv["rigid"] == false).collect();
    assert_eq!(diagrams.len(), plastic.len(), "{name}");
    for (d, iv) in diagrams.iter().zip(plastic) {
        let l = d["lambda"].as_f64().unwrap();
        let at: Values = d["members"]
            .as_object()
            .unwrap()
            .iter()
            .flat_map(|(id, m)| {
                m["along"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .enumerate()
                    .map(|(k, e)| (id.clone(), k, e[1].as_f64().unwrap()))
                    .collect::<Vec<_>>()
            })
            .collect();
        let first = &fields(iv)[0];
        join(
            "moments_at_breakpoints differs from the interval".into(),
            l,
            &at,
            &values_at(&first.members, l),
            &mut bad,
        );
        let s = largest(&at);
        for (m, k, x) in &at {
            if x.abs() > cap[m][*k] + tol * cap[m][*k].max(s) {
                bad.push(format!(
                    "{name}: moments_at_breakpoints at {l}: |M| of {m}[{k}] = {x}"
                ));
            }
        }
    }
    bad
}

#[test]
fn every_reported_moment_is_within_capacity_and_the_intervals_join() {
    let mut bad = Vec::new();
    for f in all_scenes() {
        bad.extend(check_scene(&f));
    }
    assert!(
        bad.is_empty(),
        "{} failure(s):\n{}",
        bad.len(),
        bad.join("\n")
    );
}

#[test]
fn fixed_beam_against_its_closed_form() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/fixed-beam.toml");
    let a = analyse(&path);
    let (l, mp) = (4.0, 1.0);
    // the scene's data, so that the closed form reads them
    assert_eq!(a.scene.frame.members[0].plastic_moment, mp);
    let pc = 8.0 * mp / l;
    let collapse = a.reading.collapse_load().unwrap();
    assert!((collapse - pc).abs() < 1e-12, "{collapse}");
    let v = a.to_json();
    let rigid = &v["intervals"][0];
    assert_eq!(rigid["rigid"], true);
    assert!((lam(&rigid["lambda_to"]) - pc).abs() < 1e-12);
    let tol = frames::response::force_tolerance(&a.solution);
    for f in fields(rigid) {
        for p in samples(f.from, f.to) {
            // the five element ends in order A, quarter, middle, quarter, B
            let m: Vec<f64> = values_at(&f.members, p)
                .into_iter()
                .map(|(_, _, x)| x)
                .collect();
            assert_eq!(m.len(), 8);
            let (ma, mq1, mm, mq2, mb) = (m[0], m[1], m[3], m[5], m[7]);
            for k in [1, 3, 5] {
                // both sections at a node carry the node's moment
                assert!((m[k] - m[k + 1]).abs() < 1e-12, "{m:?}");
            }
            // equilibrium: the free moment of the load, P l / 4 at mid-span
            assert!(
                (mm - 0.5 * (ma + mb) - p * l / 4.0).abs() < 1e-12,
                "Lambda = {p}: {m:?}"
            );
            // no load between the nodes: linear in between
            assert!((mq1 - 0.5 * (ma + mm)).abs() < 1e-12, "{m:?}");
            assert!((mq2 - 0.5 * (mb + mm)).abs() < 1e-12, "{m:?}");
            for x in &m {
                assert!(x.abs() <= mp * (1.0 + tol), "Lambda = {p}: {m:?}");
            }
        }
    }
    // at collapse: the mechanism's field, -Mp at the ends, +Mp at mid-span
    let last = fields(rigid).pop().unwrap();
    let m: Vec<f64> = values_at(&last.members, pc)
        .into_iter()
        .map(|(_, _, x)| x)
        .collect();
    for (x, e) in m.iter().zip([-1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, -1.0]) {
        assert!((x - e * mp).abs() < 1e-12, "{m:?}");
    }
}
