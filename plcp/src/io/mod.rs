//! Reading and writing problems: plcp's JSON format ([`json`]) and the Siconos
//! `.dat` format ([`siconos`]).
//!
//! Every reader parses numbers as `f64` and converts them to the working
//! precision `T` afterwards. A value that is not finite, or that overflows `T`
//! (say `1e300` read as `f32`), or a nonzero value that underflows it (zero or
//! subnormal in `T`: `1e-150` read as `f32`, or a subnormal `f64`), is an
//! error that names the entry. Every error is
//! a [`PlcpError`] whose `Display` is one line naming the file and, for syntax
//! errors, the 1-based line and column.

pub mod json;
pub mod siconos;

use crate::error::PlcpError;
use crate::scalar::Scalar;

/// Largest order of `M` the readers accept: the solvers are dense, and a
/// sparse-block `.dat` file could otherwise ask for an `n x n` allocation far
/// beyond the machine's memory (which would abort, not fail cleanly).
pub const MAX_ORDER: usize = 8192;

/// Reads a whole file, mapping failures to [`PlcpError::Io`] (which names the file).
pub fn read_bytes(path: &std::path::Path) -> Result<Vec<u8>, PlcpError> {
    std::fs::read(path).map_err(|e| PlcpError::Io {
        file: path.display().to_string(),
        message: format!("cannot read the file: {e}"),
    })
}

/// Converts one input value read as `f64` to `T`, rejecting NaN, infinities and
/// values that overflow `T`. `what` names the input (`"M"`, `"q"`, ...) and
/// `position` the entry (`"(2, 3)"`, `"[4]"`).
pub(crate) fn convert<T: Scalar>(what: &str, position: &str, v: f64) -> Result<T, PlcpError> {
    if !v.is_finite() {
        return Err(PlcpError::NonFinite {
            what: what.into(),
            position: position.into(),
            value: v,
        });
    }
    let t = T::from_f64(v);
    if !t.is_finite() {
        return Err(PlcpError::Invalid {
            what: format!("{what} entry {position}"),
            why: format!("{v:e} overflows the working precision {}", T::NAME),
        });
    }
    // a nonzero value that is zero or subnormal in T (or already subnormal
    // in f64): named with the value as read
    if v != 0.0 && (t == T::zero() || t.to_f64().abs() < T::min_normal()) {
        return Err(PlcpError::Underflow {
            what: what.into(),
            position: position.into(),
            value: v,
            precision: T::NAME.into(),
            min_normal: T::min_normal(),
        });
    }
    Ok(t)
}

/// Rejects an order of `M` above [`MAX_ORDER`].
pub(crate) fn check_order(what: &str, order: usize) -> Result<(), String> {
    if order > MAX_ORDER {
        Err(format!(
            "{what} = {order} is too large for the dense solvers (limit {MAX_ORDER})"
        ))
    } else {
        Ok(())
    }
}
