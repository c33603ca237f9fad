//! Plots (stub).
use crate::{Analysis, FramesError};
/// Writes every plot and table.
pub fn write_all(
    _a: &Analysis,
    _dir: &std::path::Path,
) -> Result<Vec<std::path::PathBuf>, FramesError> {
    Ok(vec![])
}
