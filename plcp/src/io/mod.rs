//! Reading and writing problems: plcp's JSON format (`json`, with the `json`
//! feature), the Siconos `.dat` format ([`siconos`]), and `M` from a Matrix
//! Market ([`mtx`]) or NumPy ([`npy`]) file.
//!
//! Every reader parses numbers as `f64` and converts them to the working
//! precision `T` afterwards. A value that is not finite, or that overflows `T`
//! (say `1e300` read as `f32`), or a nonzero value that underflows it (zero or
//! subnormal in `T`: `1e-150` read as `f32`, or a subnormal `f64`), is an
//! error that names the entry. Every error is
//! a [`PlcpError`] whose `Display` is one line naming the file and, for syntax
//! errors, the 1-based line and column.
//!
//! Every reader is strict: a key it does not know is an error that names the
//! key, its line and column, and the accepted keys (annotate with a `comment`
//! key, which is read and ignored), and a file that is not valid UTF-8
//! anywhere, comments included, is an error that names the byte offset, line
//! and column of the first bad byte ([`utf8`]).

#[cfg(feature = "json")]
pub mod json;
pub mod mtx;
pub mod npy;
pub mod siconos;
#[cfg(feature = "json")]
pub mod sparse_json;

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

/// Where a byte sequence stops being UTF-8: the first bad byte, by offset
/// (0-based) and by line and column (1-based; the column counts characters).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct InvalidUtf8 {
    /// Offset of the first byte that is not part of a valid UTF-8 sequence.
    pub offset: usize,
    /// Its 1-based line.
    pub line: usize,
    /// Its 1-based column, in characters of the valid text before it.
    pub column: usize,
    /// The byte itself.
    pub byte: u8,
}

impl InvalidUtf8 {
    /// The message without the line and column, for a caller that prints
    /// them in its own `file:line:column:` prefix.
    pub fn brief(&self) -> String {
        format!(
            "invalid UTF-8 at byte offset {}: byte 0x{:02X} begins no valid UTF-8 character (the input must be UTF-8 throughout, comments included)",
            self.offset, self.byte
        )
    }
}

impl core::fmt::Display for InvalidUtf8 {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "line {}, column {}: {}",
            self.line,
            self.column,
            self.brief()
        )
    }
}

/// The bytes as text, or where they stop being UTF-8. Every reader of a text
/// format decodes through this: a lossy decoding would turn a stray byte into
/// U+FFFD silently, and a JSON parser skips unread strings without checking them.
///
/// ```
/// assert_eq!(plcp::io::utf8(b"ok").unwrap(), "ok");
/// let e = plcp::io::utf8(b"1 2\n3 \xff 4").unwrap_err();
/// assert_eq!((e.offset, e.line, e.column, e.byte), (6, 2, 3, 0xff));
/// ```
pub fn utf8(bytes: &[u8]) -> Result<&str, InvalidUtf8> {
    std::str::from_utf8(bytes).map_err(|e| {
        let offset = e.valid_up_to();
        // the prefix is valid UTF-8 by construction
        let before = std::str::from_utf8(&bytes[..offset]).unwrap_or_default();
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        InvalidUtf8 {
            offset,
            line: before.matches('\n').count() + 1,
            column: before[line_start..].chars().count() + 1,
            byte: bytes[offset],
        }
    })
}

/// [`utf8`], with the failure as a [`PlcpError::Parse`] naming `file`.
pub(crate) fn utf8_in<'a>(bytes: &'a [u8], file: &str) -> Result<&'a str, PlcpError> {
    utf8(bytes).map_err(|e| PlcpError::Parse {
        file: file.to_string(),
        line: e.line,
        column: e.column,
        message: e.brief(),
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

/// [`convert`] with the position formatted only when the value is rejected:
/// a reader that converts millions of entries formatted a position string
/// for each (a fifth of the reading time of `plcp sequence` at n = 50).
#[cfg(feature = "json")]
#[inline]
pub(crate) fn convert_with<T: Scalar>(
    what: &str,
    position: impl FnOnce() -> String,
    v: f64,
) -> Result<T, PlcpError> {
    if v.is_finite() {
        let t = T::from_f64(v);
        // exactly what `convert` accepts
        if t.is_finite() && (v == 0.0 || (t != T::zero() && t.to_f64().abs() >= T::min_normal())) {
            return Ok(t);
        }
    }
    convert(what, &position(), v)
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
