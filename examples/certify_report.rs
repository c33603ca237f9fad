//! What exact certification costs against the float path it certifies:
//! dense monotone PLCPs (`plcp_workspace::random::dense_monotone`, the
//! README's instances, traced to infinity) and every frames scene (system (9)
//! as `frames run` solves it, Wolfe in f64). For each: the float solve's
//! time, segments and pivots, the certification's time and exact pivots, the
//! outcome and the largest relative difference between the float and exact
//! breakpoints. The table in `docs/certification.md` is its output.
//!
//! ```sh
//! cargo run --release -q --example certify_report             # n = 10, 20, 50, 100 and the scenes
//! cargo run --release -q --example certify_report -- 200      # other sizes (scenes skipped)
//! ```

use frames::{Scene, System};
use plcp::{Method, Settings};
use plcp_workspace::random::dense_monotone;
use std::time::Instant;

fn row(name: &str, problem: &plcp::Plcp<f64>, settings: &Settings<f64>) {
    let t = Instant::now();
    let path = plcp::solve(problem, settings).expect("valid settings");
    let float_s = t.elapsed().as_secs_f64();
    let cert = path.certify(problem);
    let outcome = match &cert.failure {
        None => "certified".to_string(),
        Some(f) => format!("rejected at segment {}", f.segment),
    };
    println!(
        "| {name} | {} | {} | {} | {:.4} | {:.3} | {:.0} | {} | {:.1e} |",
        problem.dim(),
        path.segments.len(),
        path.info.pivots,
        float_s,
        cert.seconds,
        cert.seconds / float_s.max(1e-9),
        outcome,
        cert.max_rel_diff
    );
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let sizes = if args.is_empty() {
        vec![10, 20, 50, 100]
    } else {
        args.clone()
    };
    println!("| problem | p + n | segments | float pivots | float s | certify s | ratio | outcome | max rel. diff |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for n in sizes {
        let inst = dense_monotone(n, 1);
        row(
            &format!("dense n = {n}"),
            &inst.problem,
            &Settings::default(),
        );
    }
    if !args.is_empty() {
        return;
    }
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes");
    let mut files: Vec<std::path::PathBuf> = ["", "stiff", "pipe-whip"]
        .iter()
        .flat_map(|d| {
            std::fs::read_dir(format!("{root}/{d}"))
                .into_iter()
                .flatten()
        })
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    for f in files {
        let scene = Scene::from_file(&f).expect("the shipped scenes read");
        let system = System::assemble(&scene.frame);
        let problem = system.plcp::<f64>(None).expect("system (9) is valid");
        let name = f.strip_prefix(root).unwrap_or(&f).display().to_string();
        row(
            &name,
            &problem,
            &frames::solve::plcp_settings(Method::Wolfe),
        );
    }
}
