//! The CI share of the fuzz harness (`examples/fuzz.rs` runs a million inputs):
//! 2000 inputs over the readers (JSON, Siconos `.dat`, frames TOML) and the
//! solvers on arbitrary small problems. No call may panic, and no input may
//! take more than a few seconds (the pivot limit must hold).

#[path = "../examples/common/fuzz_core.rs"]
mod fuzz_core;

#[test]
fn two_thousand_hostile_inputs_no_panic_no_hang() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let scenes = fuzz_core::read_scenes(&root.join("scenes"));
    assert!(
        !scenes.is_empty(),
        "no scenes in {}",
        root.join("scenes").display()
    );
    fuzz_core::install_hook();
    let sum = fuzz_core::run_range(7, 0..2000, &scenes, 5.0, None, |_| {});
    let _ = std::panic::take_hook();
    println!("{}", sum.table());
    let mut report = String::new();
    for (count, msg, idx, desc) in sum.distinct.values() {
        report += &format!("\npanic x{count} (input #{idx}): {msg}\ninput: {desc}\n");
    }
    assert_eq!(sum.panics, 0, "panics:{report}");
    assert!(sum.slow.is_empty(), "inputs over 5 s: {:?}", sum.slow);
    // the harness reached the solvers, not only the parsers' error paths
    let solved: u64 = sum
        .statuses
        .iter()
        .filter(|(k, _)| k.starts_with("solve"))
        .map(|(_, v)| v)
        .sum();
    assert!(
        solved > 1000,
        "only {solved} solver calls returned a status"
    );
}
