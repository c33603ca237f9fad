//! All integration tests of this package in one test binary: one link and
//! one instantiation of the generic engine instead of one per file (the
//! release build of some fifty binaries was most of CI's time). Each file
//! is a module; run one with `cargo test --release --test suite NAME::`.
//! `threads.rs` is a binary of its own: it counts the process's threads.

mod common;

mod certify_bridge;
mod certify_engines;
mod certify_ray;
#[cfg(feature = "cli")]
mod cli;
mod cycle;
mod escalate;
mod exact;
mod extreme_scale;
mod known_instances;
mod long_ties;
mod mixed;
#[cfg(feature = "cli")]
mod mtx_input;
mod near_ties;
mod observe;
mod principal;
mod prop_path;
mod scale_invariance;
mod sequence;
mod sequence_prop;
mod siconos_corpus;
mod sparse;
#[cfg(feature = "cli")]
mod sparse_input;
mod warm_start;
