//! The JSON report's bounded defaults: a large scene gets moment distributions
//! and node series at a bounded, documented sample (and says so), a small one
//! gets everything, and `OutputSelection` asks for more or for specific ones.

use frames::report::{
    sample_indices, MomentPick, NodePick, OutputSelection, DEFAULT_SAMPLES, SMALL_SCENE,
};
use frames::{Analysis, AnalysisOptions, Scene, SolveOptions};

fn cantilever(elements: usize) -> Analysis {
    let (scene, options) = cantilever_scene(elements);
    Analysis::run(scene, &options).unwrap()
}

fn cantilever_scene(elements: usize) -> (Scene, AnalysisOptions) {
    let src = format!(
        r#"
title = "uniform cantilever"
[[node]]
id = "A"
x = 0.0
y = 0.0
[[node]]
id = "B"
x = 1.0
y = 0.0
[[member]]
id = "AB"
from = "A"
to = "B"
plastic_moment = 1.0
elements = {elements}
mass_per_length = 1.0
[[support]]
node = "A"
fix = ["x", "y", "rz"]
[[load]]
node = "B"
fy = 1.0
[history]
kind = "ramp"
rate = 1.0
"#
    );
    let scene = Scene::from_toml(&src, "cantilever.toml").unwrap();
    let options = AnalysisOptions {
        solve: SolveOptions {
            lambda_max: Some(12.0),
            ..SolveOptions::default()
        },
        ..AnalysisOptions::default()
    };
    (scene, options)
}

fn count(doc: &serde_json::Value) -> (usize, usize, usize, usize) {
    let intervals = doc["intervals"].as_array().unwrap();
    let with_pieces = intervals
        .iter()
        .filter(|i| !i["pieces"].as_array().unwrap().is_empty())
        .count();
    let acc_nodes = intervals[0]["accelerations"].as_object().unwrap().len();
    (
        doc["moments_at_breakpoints"].as_array().unwrap().len(),
        with_pieces,
        acc_nodes,
        doc["response"]["nodes"].as_object().unwrap().len(),
    )
}

#[test]
fn sampling_keeps_the_ends_and_the_count() {
    assert_eq!(sample_indices(5, 20), vec![0, 1, 2, 3, 4]);
    let s = sample_indices(1000, 20);
    assert_eq!(s.len(), 20);
    assert_eq!((s[0], s[19]), (0, 999));
    assert!(s.windows(2).all(|w| w[0] < w[1]));
    assert!(sample_indices(7, 0).is_empty());
}

#[test]
fn a_large_scene_is_bounded_by_default_and_everything_on_request() {
    let a = cantilever(SMALL_SCENE + 50);
    let nodes = a.scene.frame.nodes.len();
    assert!(nodes > SMALL_SCENE);
    let bps = a.reading.breakpoints.len();
    let doc = a.to_json();
    let (diagrams, pieces, acc, series) = count(&doc);
    assert!((2..=DEFAULT_SAMPLES).contains(&diagrams), "{diagrams}");
    assert!(pieces <= DEFAULT_SAMPLES, "{pieces}");
    assert_eq!((acc, series), (DEFAULT_SAMPLES, DEFAULT_SAMPLES));
    // every breakpoint's events, every interval's hinge sets: always
    assert_eq!(doc["breakpoints"].as_array().unwrap().len(), bps);
    assert_eq!(
        doc["intervals"].as_array().unwrap().len(),
        a.reading.intervals.len()
    );
    assert!(doc["output"]["moments"]
        .as_str()
        .unwrap()
        .contains("sampled"));
    // everything on request
    let all = a.to_json_selected(&OutputSelection::all()).unwrap();
    let (d_all, p_all, acc_all, s_all) = count(&all);
    assert_eq!(d_all, a.response.moments_at_breakpoints.len());
    assert!(d_all > diagrams && p_all > pieces);
    assert_eq!((acc_all, s_all), (nodes, nodes));
    assert!(all["output"]["moments"].as_str().unwrap().contains("all"));
    // particular values and nodes
    let some = OutputSelection {
        moments: MomentPick::At(vec![3.0, 5.0]),
        nodes: NodePick::Ids(vec!["B".into(), "A".into()]),
    };
    let doc = a.to_json_selected(&some).unwrap();
    let (d, _, acc, series) = count(&doc);
    assert!((1..=2).contains(&d));
    assert_eq!((acc, series), (2, 2));
    assert!(doc["response"]["nodes"]["B"].is_object());
    let bad = OutputSelection {
        moments: MomentPick::All,
        nodes: NodePick::Ids(vec!["nowhere".into()]),
    };
    assert!(a.to_json_selected(&bad).unwrap_err().contains("nowhere"));
}

#[test]
fn a_small_scene_reports_everything() {
    let a = cantilever(20);
    let doc = a.to_json();
    let (d, _, acc, series) = count(&doc);
    assert_eq!(d, a.response.moments_at_breakpoints.len());
    let nodes = a.scene.frame.nodes.len();
    assert_eq!((acc, series), (nodes, nodes));
}

/// The report written part by part (`Analysis::json_report`, what `frames run
/// --json` streams) gives the bytes of the document built whole, compact and
/// pretty, with the default and the full selection, and with keys added.
#[test]
fn streamed_json_equals_the_document_built_whole() {
    for (a, sel) in [
        (cantilever(8), OutputSelection::all()),
        (
            cantilever(300),
            OutputSelection::default_for(&cantilever(300)),
        ),
        (cantilever(300), OutputSelection::all()),
    ] {
        let mut report = a.json_report(&sel).unwrap();
        let mut whole = a.to_json_selected(&sel).unwrap();
        // keys that sort before, between and after the report's own
        for (k, v) in [("aaa", 1), ("plcp_valid_up_to_lambda", 2), ("zzz", 3)] {
            report.insert(k, v.into());
            whole[k] = v.into();
        }
        let streamed = serde_json::to_vec(&report).unwrap();
        assert_eq!(streamed, serde_json::to_vec(&whole).unwrap());
        let pretty = serde_json::to_vec_pretty(&report).unwrap();
        assert_eq!(pretty, serde_json::to_vec_pretty(&whole).unwrap());
        // written twice, the same (every lazy part starts over)
        assert_eq!(serde_json::to_vec(&report).unwrap(), streamed);
    }
}

/// A large scene analysed in two passes (`frames::stream`, what `frames run`
/// does above 200 nodes) gives the reports of the analysis that keeps every
/// piece, byte for byte, for the selection it was asked for (the default, a
/// count, a list of Lambda values, node ids, everything); a selection asking
/// for more than it kept is an `Err`, and it keeps only the selected pieces.
#[test]
fn two_passes_give_the_reports_of_the_whole_analysis() {
    let (scene, options) = cantilever_scene(SMALL_SCENE + 50);
    let whole = Analysis::run(scene.clone(), &options).unwrap();
    assert!(frames::stream::applies(&scene, &whole.system, &options));
    let default = OutputSelection::default_for(&whole);
    let picks = [
        (None, None, default.clone()),
        (
            Some(MomentPick::Count(3)),
            Some(NodePick::Ids(vec!["B".into(), "A".into()])),
            OutputSelection {
                moments: MomentPick::Count(3),
                nodes: NodePick::Ids(vec!["B".into(), "A".into()]),
            },
        ),
        (
            Some(MomentPick::At(vec![4.0, 6.5])),
            Some(NodePick::Count(7)),
            OutputSelection {
                moments: MomentPick::At(vec![4.0, 6.5]),
                nodes: NodePick::Count(7),
            },
        ),
        (
            Some(MomentPick::All),
            Some(NodePick::All),
            OutputSelection::all(),
        ),
    ];
    let json = |a: &Analysis, sel: &OutputSelection| {
        serde_json::to_string(&a.json_report(sel).unwrap()).unwrap()
    };
    for (moments, nodes, sel) in picks {
        let what = format!("{sel:?}");
        let lean = frames::stream::run(scene.clone(), &options, moments, nodes, None).unwrap();
        assert!(
            lean.response.nodes.is_some(),
            "{what}: not analysed in two passes"
        );
        assert_eq!(lean.to_text(), whole.to_text(), "{what}");
        assert_eq!(json(&lean, &sel), json(&whole, &sel), "{what}");
        assert_eq!(lean.reading, whole.reading, "{what}");
        let kept = lean
            .solution
            .pieces
            .iter()
            .filter(|p| !p.du.is_empty())
            .count();
        if sel != OutputSelection::all() {
            assert!(
                kept < whole.solution.pieces.len() / 4,
                "{what}: kept {kept} of {} pieces",
                whole.solution.pieces.len()
            );
            assert!(lean.json_report(&OutputSelection::all()).is_err(), "{what}");
        }
    }
}

/// Where the two passes do not apply (here: a small system on the dense
/// route), `frames::stream::run` runs the whole analysis.
#[test]
fn two_passes_fall_back_to_the_whole_analysis() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cantilever.toml");
    let scene = Scene::from_file(file).unwrap();
    let options = AnalysisOptions::default();
    let whole = Analysis::run(scene.clone(), &options).unwrap();
    assert!(!frames::stream::applies(&scene, &whole.system, &options));
    let lean = frames::stream::run(scene, &options, None, None, None).unwrap();
    assert!(lean.response.nodes.is_none());
    assert_eq!(lean.to_text(), whole.to_text());
    assert_eq!(lean.solution.pieces, whole.solution.pieces);
}
