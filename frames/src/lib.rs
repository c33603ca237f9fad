//! frames (in progress)
#![warn(missing_docs)]
pub mod assemble;
pub mod error;
mod kernel;
pub mod model;
pub use assemble::System;
pub use error::FramesError;
pub use model::{Frame, History, Scene};
