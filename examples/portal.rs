//! A fixed-base portal frame under three load cases: a horizontal load at beam
//! level (sway mechanism), horizontal plus vertical (combined mechanism), and
//! a symmetric vertical load at midspan (beam mechanism: three hinges form at
//! once, a degenerate pivot sequence).
//!
//! ```sh
//! cargo run --release -q --example portal
//! ```
//!
//! Columns h = 1, beam l = 2, Mp = 1: the textbook collapse loads (Neal, The
//! Plastic Methods of Structural Analysis, ch. 2) are sway 4 Mp / (H h) = 4,
//! beam 8 Mp / (V l) = 4, combined 6 Mp / (H h + V l / 2) = 3. Plots and JSON
//! go to out/portal/<case>/.

use frames::{Analysis, AnalysisOptions, Scene};
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for (case, textbook) in [("sway", 4.0), ("combined", 3.0), ("vertical", 4.0)] {
        let scene = Scene::from_file(root.join("scenes").join(format!("portal-{case}.toml")))?;
        let a = Analysis::run(scene, &AnalysisOptions::default())?;
        let dir = root.join("out").join("portal").join(case);
        frames::plot::write_all(&a, &dir)?;
        std::fs::write(
            dir.join("report.json"),
            serde_json::to_string_pretty(&a.to_json())?,
        )?;
        println!("==== portal, {case} ====");
        print!("{}", a.to_text());
        let got = a.reading.collapse_load().unwrap_or(f64::NAN);
        println!(
            "first critical Lambda {got} against the textbook collapse load {textbook}: {}",
            if (got - textbook).abs() < 1e-9 * textbook {
                "agree"
            } else {
                "DISAGREE"
            }
        );
        println!("plots, CSV and JSON in {}\n", dir.display());
    }
    Ok(())
}
