//! Lemke-style complementary pivoting with `L` as the driving variable.
use crate::{error::PlcpError, path::*, problem::*, scalar::Scalar, settings::Settings};
use faer::Col;

/// The answer to a plain LCP.
#[derive(Clone, Debug)]
pub struct LcpSolution<T: Scalar> {
    /// `Reached` when solved; `SecondaryRay` when Lemke's method with the covering vector ended on a ray.
    pub status: Status,
    /// The solution (the last point reached otherwise).
    pub z: Col<T>,
    /// `w = q + M z`.
    pub w: Col<T>,
    /// Diagnostics.
    pub message: String,
    /// Counts, residuals, timing.
    pub info: Info,
}

pub(crate) fn solve<T: Scalar>(_p: &Plcp<T>, _s: &Settings<T>) -> Result<Path<T>, PlcpError> {
    todo!()
}

/// Solves the LCP `w = q + M z`, `w, z >= 0`, `w'z = 0` by Lemke's method with a covering vector.
pub fn solve_lcp<T: Scalar>(_lcp: &Lcp<T>, _s: &Settings<T>) -> Result<LcpSolution<T>, PlcpError> {
    todo!()
}
