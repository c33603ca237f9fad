//! A fixed-base two-storey, one-bay frame, under two load cases:
//!
//! * scenes/two-storey.toml: floor loads and midspan loads with a saturating
//!   (blowdown-like) history; hinges spread in four stages, none unloads;
//! * scenes/two-storey-sway.toml: horizontal loads only; system (9) predicts a
//!   deactivation (a flowing hinge that no admissible stress state can keep at
//!   yield), which frames reports loudly.
//!
//! ```sh
//! cargo run --release -q --example two_storey
//! ```

use frames::{Analysis, AnalysisOptions, Scene};
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for name in ["two-storey", "two-storey-sway"] {
        let scene = Scene::from_file(root.join("scenes").join(format!("{name}.toml")))?;
        let a = Analysis::run(scene, &AnalysisOptions::default())?;
        let dir = root.join("out").join(name);
        frames::plot::write_all(&a, &dir)?;
        std::fs::write(
            dir.join("report.json"),
            serde_json::to_string_pretty(&a.to_json())?,
        )?;
        println!("==== {name} ====");
        print!("{}", a.to_text());
        println!("deactivations: {}", a.reading.deactivations().len());
        println!("plots, CSV and JSON in {}\n", dir.display());
    }
    Ok(())
}
