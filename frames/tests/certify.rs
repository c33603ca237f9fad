//! Exact certification and exact precision through frames: the paper's
//! cantilever has its critical loads at exactly 1, 4, 6 and 12.

use frames::{Analysis, AnalysisOptions, Scene};

fn cantilever(options: &AnalysisOptions) -> Analysis {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cantilever.toml");
    Analysis::run(Scene::from_file(path).unwrap(), options).unwrap()
}

#[test]
fn the_cantilever_is_certified_with_exact_critical_loads() {
    let a = cantilever(&AnalysisOptions {
        certify: true,
        ..AnalysisOptions::default()
    });
    let c = a.solution.info.certificate.as_ref().expect("a certificate");
    assert!(c.certified(), "{}", c.summary());
    assert!(a.solution.status.is_success());
    assert_eq!(a.exact_critical_loads(), ["1", "4", "6", "12"]);
    assert!(a.to_text().contains("exact critical loads: 1, 4, 6, 12"));
    let json = a.to_json();
    assert_eq!(json["solver"]["certificate"]["certified"], true, "{json}");
}

#[test]
fn the_cantilever_in_exact_precision() {
    let a = cantilever(&AnalysisOptions {
        exact: true,
        ..AnalysisOptions::default()
    });
    assert_eq!(a.solution.info.precision, "exact");
    assert!(a.solution.status.is_success(), "{}", a.solution.message);
    assert_eq!(a.exact_critical_loads(), ["1", "4", "6", "12"]);
}

#[test]
fn exact_precision_refuses_a_singular_free_block() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/portal-sway.toml");
    let err = Analysis::run(
        Scene::from_file(path).unwrap(),
        &AnalysisOptions {
            exact: true,
            ..AnalysisOptions::default()
        },
    )
    .unwrap_err();
    assert!(err.to_string().contains("free block"), "{err}");
}

/// `frames run --certify` (issue 14: certification from the command line):
/// the text report says the path is certified and shows the exact critical
/// loads.
#[cfg(feature = "cli")]
#[test]
fn the_command_line_certifies() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cantilever.toml");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_frames"))
        .args(["run", scene, "--certify"])
        .output()
        .expect("run frames");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout} {}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("certified in exact rational arithmetic"),
        "{stdout}"
    );
    assert!(
        stdout.contains("exact critical loads: 1, 4, 6, 12"),
        "{stdout}"
    );
}
