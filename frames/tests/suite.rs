//! All integration tests of this package in one test binary: one link and
//! one instantiation of the generic engine instead of one per file (the
//! release build of some fifty binaries was most of CI's time). Each file
//! is a module; run one with `cargo test --release --test suite NAME::`.

mod common {
    pub mod reference;
    pub mod timestep;
}

mod certify;
#[cfg(feature = "cli")]
mod cli;
mod grillage;
mod grillage_timestep;
mod moments;
mod output_bounds;
mod space;
mod space_report;
mod stiffest;
mod targets;
#[cfg(feature = "cli")]
mod timestep;
