//! The paper's example end to end: a uniform cantilever lumped into four point
//! masses, a transverse tip load rising from rest (Section 4, Figures 1 and 2).
//!
//! ```sh
//! cargo run --release -q --example cantilever
//! ```
//!
//! Both lumpings are analysed (the paper does not say which it used):
//! `equal` puts a quarter of the mass at each free node (scenes/cantilever.toml),
//! `halftip` lumps `mu h / 2` to each element end, so the tip carries half a
//! mass (scenes/cantilever-halftip.toml). Units: L = 1, Mp = 1, total mass 1,
//! lambda(t) = t (the scaling of the paper's Figure 2(b) is lost in the scan).
//!
//! Writes, per lumping, into out/cantilever/<lumping>/: report.txt,
//! report.json, and the plots with their CSV (activation, profiles, moments,
//! displacements). Each path is cross-checked: Lemke on the Schur reduction
//! (the cantilever is statically determinate) and Wolfe in double-double
//! precision must give the same critical values.

use frames::{Analysis, AnalysisOptions, Scene, SolveOptions};
use plcp::{Method, Precision};
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = root.join("out").join("cantilever");
    let mut tables = Vec::new();
    for (name, file) in [
        ("equal", "cantilever.toml"),
        ("halftip", "cantilever-halftip.toml"),
    ] {
        let scene = Scene::from_file(root.join("scenes").join(file))?;
        let analysis = Analysis::run(scene.clone(), &AnalysisOptions::default())?;
        let dir = out.join(name);
        std::fs::create_dir_all(&dir)?;
        let text = analysis.to_text();
        std::fs::write(dir.join("report.txt"), &text)?;
        std::fs::write(
            dir.join("report.json"),
            serde_json::to_string_pretty(&analysis.to_json())?,
        )?;
        frames::plot::write_all(&analysis, &dir)?;
        println!("==== lumping: {name} ====");
        print!("{text}");

        // cross-checks: Lemke on the reduction, and Wolfe in fx128
        let critical = |a: &Analysis| {
            a.reading
                .breakpoints
                .iter()
                .map(|b| b.lambda)
                .collect::<Vec<_>>()
        };
        let reference = critical(&analysis);
        for (method, precision) in [
            (Method::Lemke, Precision::F64),
            (Method::Wolfe, Precision::F128),
        ] {
            let options = AnalysisOptions {
                solve: SolveOptions {
                    method,
                    precision,
                    lambda_max: None,
                },
                ..AnalysisOptions::default()
            };
            let other = critical(&Analysis::run(scene.clone(), &options)?);
            let agree = other.len() == reference.len()
                && other
                    .iter()
                    .zip(&reference)
                    .all(|(a, b)| (a - b).abs() <= 1e-9 * b.abs().max(1.0));
            println!(
                "cross-check {method:?} in {precision:?}: {}",
                if agree {
                    "same critical values"
                } else {
                    "DIFFERENT critical values"
                }
            );
            if !agree {
                return Err(format!("{name}: {method:?}/{precision:?} gives {other:?}, Wolfe/f64 gives {reference:?}").into());
            }
        }
        println!("plots, CSV and JSON in {}", dir.display());
        println!();
        let hinges: Vec<(f64, String)> = analysis
            .reading
            .hinges
            .iter()
            .map(|h| (h.lambda, analysis.scene.frame.nodes[h.node].id.clone()))
            .collect();
        tables.push((name, hinges));
    }
    println!("==== hinge order (node where the hinge forms, at Lambda = tip load x L / Mp) ====");
    println!("{:<8} {:>12} {:>12}", "node", "equal", "halftip");
    let (a, b) = (&tables[0].1, &tables[1].1);
    for k in 0..a.len().max(b.len()) {
        let node = a
            .get(k)
            .or(b.get(k))
            .map(|h| h.1.clone())
            .unwrap_or_default();
        let fa = a
            .get(k)
            .map(|h| frames::report::format_number(h.0))
            .unwrap_or_default();
        let fb = b
            .get(k)
            .map(|h| frames::report::format_number(h.0))
            .unwrap_or_default();
        println!("{node:<8} {fa:>12} {fb:>12}");
    }
    println!("(continuum, fact 7: root hinge at 1, plastic zone beyond 3; the front at x reached at 3 / (1 - x))");
    Ok(())
}
