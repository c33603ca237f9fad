//! Reports of an analysis: a readable text and the JSON document.
//!
//! ```
//! let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/portal-sway.toml");
//! let a = frames::Analysis::run(
//!     frames::Scene::from_file(file).unwrap(),
//!     &frames::AnalysisOptions::default(),
//! )
//! .unwrap();
//! let text = a.to_text(); // what `frames run SCENE` prints
//! assert!(text.starts_with(&a.scene.frame.title));
//! let json = a.to_json(); // what `frames run SCENE --json` prints
//! assert_eq!(json["status"], "unbounded_ray");
//! assert_eq!(frames::report::format_number(0.5), "0.5");
//! ```
//!
//! One concern per file: [`OutputSelection`] and the sampling of large
//! scenes (`selection`), the names and summaries both reports share
//! (`wording`), the facet changes at a breakpoint (`facets`), the text
//! report (`text`) and the JSON document with [`JsonReport`] (`json`).

mod facets;
#[cfg(feature = "json")]
mod json;
mod selection;
mod text;
mod wording;

#[cfg(feature = "json")]
pub use json::JsonReport;
pub use selection::{
    sample_indices, spread, HingeSets, MomentPick, NodePick, OutputSelection, DEFAULT_SAMPLES,
    SMALL_SCENE,
};

#[cfg(feature = "json")]
use serde_json::{json, Value};

#[cfg(feature = "json")]
fn num(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}

fn fmt_g(x: f64) -> String {
    if !x.is_finite() {
        return "inf".into();
    }
    if x == 0.0 {
        return "0".into();
    }
    let a = x.abs();
    if (1e-4..1e6).contains(&a) {
        let s = format!("{x:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    } else {
        format!("{x:.6e}")
    }
}

/// Formats a number compactly (six significant digits).
pub fn format_number(x: f64) -> String {
    fmt_g(x)
}
