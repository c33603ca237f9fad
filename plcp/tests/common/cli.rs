//! Runs the `plcp` binary: the command-line half of the input-format tests
//! (`mtx_input`, `sparse_input`). Compiled only with the `cli` feature, which
//! builds the binary.
#![allow(dead_code)]

use std::path::Path;
use std::process::{Command, Output};

/// The `plcp` binary built for the tests.
pub const BIN: &str = env!("CARGO_BIN_EXE_plcp");

/// `plcp solve FILE`, whatever its outcome.
pub fn solve_output(file: &Path) -> Output {
    Command::new(BIN)
        .args(["solve", file.to_str().unwrap()])
        .output()
        .unwrap()
}

/// `plcp solve FILE`, which must succeed: its JSON report.
pub fn solve(file: &Path) -> serde_json::Value {
    let out = solve_output(file);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}
