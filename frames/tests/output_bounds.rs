//! The JSON report's bounded defaults: a large scene gets moment distributions
//! and node series at a bounded, documented sample (and says so), a small one
//! gets everything, and `OutputSelection` asks for more or for specific ones.

use frames::report::{
    sample_indices, spread, HingeSets, MomentPick, NodePick, OutputSelection, DEFAULT_SAMPLES,
    SMALL_SCENE,
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
    let v = spread(1.0, 12.0, 20);
    assert_eq!((v.len(), v[0], v[19]), (20, 1.0, 12.0));
    assert!(v.windows(2).all(|w| w[0] < w[1]));
    assert_eq!(spread(5.0, 2.0, 20), vec![5.0]);
    // a large scene's default samples are decided by lambda_max and the
    // first breakpoint (one trace), a small one's are all, and without
    // lambda_max a count over the breakpoints
    let large = OutputSelection::default_for_path(SMALL_SCENE + 1, 7, Some(1.0), Some(12.0));
    assert_eq!(
        large.moments,
        MomentPick::At(spread(1.0, 12.0, DEFAULT_SAMPLES))
    );
    let small = OutputSelection::default_for_path(SMALL_SCENE, 7, Some(1.0), Some(12.0));
    assert_eq!(small.moments, MomentPick::All);
    let open = OutputSelection::default_for_path(SMALL_SCENE + 1, 7, Some(1.0), None);
    assert_eq!(open.moments, MomentPick::Count(DEFAULT_SAMPLES));
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
        hinge_sets: HingeSets::Full,
    };
    let doc = a.to_json_selected(&some).unwrap();
    let (d, _, acc, series) = count(&doc);
    assert!((1..=2).contains(&d));
    assert_eq!((acc, series), (2, 2));
    assert!(doc["response"]["nodes"]["B"].is_object());
    let bad = OutputSelection {
        moments: MomentPick::All,
        nodes: NodePick::Ids(vec!["nowhere".into()]),
        hinge_sets: HingeSets::Changes,
    };
    assert!(a.to_json_selected(&bad).unwrap_err().contains("nowhere"));
}

/// The hinge sets of every interval rebuilt from the changes
/// (`HingeSets::Changes`: `hinge_changes`) in order, as multisets of their
/// JSON entries.
fn rebuilt_sets(doc: &serde_json::Value) -> Vec<[Vec<String>; 2]> {
    let mut sets: [Vec<String>; 2] = [Vec::new(), Vec::new()];
    let mut out = Vec::new();
    for iv in doc["intervals"].as_array().unwrap() {
        let ch = &iv["hinge_changes"];
        assert!(iv.get("accelerating").is_none() && iv.get("constant_rate").is_none());
        for (set, key) in sets.iter_mut().zip(["accelerating", "constant_rate"]) {
            for gone in ch[key]["removed"].as_array().unwrap() {
                let gone = gone.to_string();
                let at = set.iter().position(|e| *e == gone);
                set.remove(at.expect("a removed hinge was in the set"));
            }
            for new in ch[key]["added"].as_array().unwrap() {
                assert!(!set.contains(&new.to_string()), "added twice: {new}");
                set.push(new.to_string());
            }
        }
        out.push(sets.clone().map(|mut s| {
            s.sort();
            s
        }));
    }
    out
}

/// The full lists of every interval, as multisets of their JSON entries.
fn full_sets(doc: &serde_json::Value) -> Vec<[Vec<String>; 2]> {
    let list = |v: &serde_json::Value| {
        let mut s: Vec<String> = v
            .as_array()
            .unwrap()
            .iter()
            .map(|e| e.to_string())
            .collect();
        s.sort();
        s
    };
    doc["intervals"]
        .as_array()
        .unwrap()
        .iter()
        .map(|iv| [list(&iv["accelerating"]), list(&iv["constant_rate"])])
        .collect()
}

/// A large scene writes each interval's hinge sets as changes by default (and
/// says so), a small one the full lists; the lists rebuilt from the changes
/// are the full lists, interval by interval, on every scene in `scenes/` and
/// on a cantilever whose hinge travels; everything else in the document is
/// the same.
#[test]
fn hinge_changes_rebuild_the_full_lists() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes");
    let mut analyses: Vec<Analysis> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| Analysis::run(Scene::from_file(&p).unwrap(), &AnalysisOptions::default()).unwrap())
        .collect();
    assert!(analyses.len() >= 5);
    for a in &analyses {
        assert_eq!(
            OutputSelection::default_for(a).hinge_sets,
            HingeSets::Full,
            "{}",
            a.scene.file
        );
    }
    let large = cantilever(SMALL_SCENE + 50);
    assert_eq!(
        OutputSelection::default_for(&large).hinge_sets,
        HingeSets::Changes
    );
    analyses.push(large);
    let mut grew = false;
    for a in &analyses {
        let full = a.to_json_selected(&OutputSelection::all()).unwrap();
        let changes = OutputSelection {
            hinge_sets: HingeSets::Changes,
            ..OutputSelection::all()
        };
        let mut doc = a.to_json_selected(&changes).unwrap();
        let sets = full_sets(&full);
        assert_eq!(rebuilt_sets(&doc), sets, "{}", a.scene.file);
        grew |= sets.iter().any(|s| s[1].len() > 10);
        assert!(doc["output"]["hinge_sets"]
            .as_str()
            .unwrap()
            .contains("--hinge-sets full"));
        // the rest unchanged
        let mut full = full;
        full["output"].as_object_mut().unwrap().remove("hinge_sets");
        doc["output"].as_object_mut().unwrap().remove("hinge_sets");
        for (d, f) in doc["intervals"]
            .as_array_mut()
            .unwrap()
            .iter_mut()
            .zip(full["intervals"].as_array_mut().unwrap())
        {
            d.as_object_mut().unwrap().remove("hinge_changes");
            let f = f.as_object_mut().unwrap();
            f.remove("accelerating");
            f.remove("constant_rate");
        }
        assert_eq!(doc, full, "{}", a.scene.file);
        assert!(full_sets_absent(
            &a.to_json_selected(&OutputSelection::all()).unwrap()
        ));
    }
    assert!(grew, "no scene with a long constant-rate list");
}

/// The full selection writes the lists and no changes.
fn full_sets_absent(doc: &serde_json::Value) -> bool {
    doc["output"].get("hinge_sets").is_none()
        && doc["intervals"]
            .as_array()
            .unwrap()
            .iter()
            .all(|iv| iv.get("hinge_changes").is_none() && iv["constant_rate"].is_array())
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
                hinge_sets: HingeSets::Changes,
            },
        ),
        (
            Some(MomentPick::At(vec![4.0, 6.5])),
            Some(NodePick::Count(7)),
            OutputSelection {
                moments: MomentPick::At(vec![4.0, 6.5]),
                nodes: NodePick::Count(7),
                hinge_sets: HingeSets::Full,
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
        // the default and a list of values are decided before the trace:
        // one trace; a count or everything need the second
        let one_pass = matches!(sel.moments, MomentPick::At(_));
        let (lean, second) = traced(scene.clone(), &options, moments, nodes);
        assert_eq!(
            second == 0,
            one_pass,
            "{what}: {second} ticks of a second trace"
        );
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

/// [`frames::stream::run_in_passes`] and how many segments its second
/// trace told (none: one trace).
fn traced(
    scene: Scene,
    options: &AnalysisOptions,
    moments: Option<MomentPick>,
    nodes: Option<NodePick>,
) -> (Analysis, usize) {
    let ticks = std::rc::Rc::new(std::cell::Cell::new(0usize));
    let count = ticks.clone();
    let second: frames::solve::Watch =
        std::rc::Rc::new(std::cell::RefCell::new(move |_: &frames::solve::Tick| {
            count.set(count.get() + 1)
        }));
    let a =
        frames::stream::run_in_passes(scene, options, moments, nodes, None, Some(second)).unwrap();
    (a, ticks.get())
}

/// One trace where the end time and the sampled values are known before it
/// (`t_end` given, inside the traced range), two where the guess fails (an
/// end time beyond `lambda_max`: the response is cut to where the path was
/// traced; a last breakpoint below `lambda_max / 1.5`, which sets the default
/// end time): the reports equal the whole analysis's every time.
#[test]
fn one_trace_where_the_guesses_hold_two_where_not() {
    let (scene, options) = cantilever_scene(SMALL_SCENE + 50);
    for (t_end, lambda_max, one) in [
        (Some(7.5), Some(12.0), true),
        (Some(20.0), Some(12.0), false),
        (None, Some(100.0), true),
        // the last breakpoint (the hinge at the tip, near 3 / h) is below
        // lambda_max / 1.5: the default end time is 1.5 times it
        (None, Some(2000.0), false),
    ] {
        let mut options = options.clone();
        options.t_end = t_end;
        options.solve.lambda_max = lambda_max;
        let whole = Analysis::run(scene.clone(), &options).unwrap();
        let sel = OutputSelection::default_for(&whole);
        let (lean, second) = traced(scene.clone(), &options, None, None);
        let what = format!("t_end {t_end:?}, lambda_max {lambda_max:?}");
        assert_eq!(second == 0, one, "{what}: {second} ticks of a second trace");
        assert!(lean.response.nodes.is_some(), "{what}");
        assert_eq!(lean.to_text(), whole.to_text(), "{what}");
        let json = |a: &Analysis| serde_json::to_string(&a.json_report(&sel).unwrap()).unwrap();
        assert_eq!(json(&lean), json(&whole), "{what}");
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
