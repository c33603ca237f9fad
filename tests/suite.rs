//! All integration tests of this package in one test binary: one link and
//! one instantiation of the generic engine instead of one per file (the
//! release build of some fifty binaries was most of CI's time). Each file
//! is a module; run one with `cargo test --release --test suite NAME::`.

mod common;

mod certify_frames;
mod everyday_paths;
mod frames_checks;
mod fuzz_short;
mod lex_rule;
mod sparse_frames;
mod sparse_precision;
mod stiff;
