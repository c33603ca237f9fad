//! frames (in progress)
#![warn(missing_docs)]
pub mod analysis;
pub mod assemble;
pub mod error;
pub mod hinge;
pub mod integrate;
mod kernel;
pub mod model;
pub mod plot;
pub mod report;
pub mod response;
pub mod solve;
pub mod stress;
pub use analysis::{Analysis, AnalysisOptions};
pub use assemble::System;
pub use error::FramesError;
pub use model::{Frame, History, Scene};
pub use solve::SolveOptions;
