//! plcp's JSON formats: the problem file read by `plcp solve`, and the output
//! written by `plcp solve` and `plcp lcp`.
//!
//! # Input
//!
//! ```json
//! {"M": [[2, 1], [1, 2]], "q": [1, 1], "d": [-1, -0.5], "lambda_max": null, "free": 0, "lambda0": 0}
//! ```
//!
//! * `M`: the matrix as a list of rows (row-major), square, of order `p + n`;
//!   or the name of a file holding it, relative to the problem file's
//!   directory: NumPy's `.npy` (`"M": "m.npy"`, [`super::npy`]; binary, read
//!   at the speed of a copy: the fast way to hand over a large `M`) or Matrix
//!   Market (`"M": "m.mtx"`, [`super::mtx`]), told apart by their first bytes;
//! * `q`, `d`: vectors of that length;
//! * `lambda_max`: a number, or `null`, absent or the string `"inf"` for infinity;
//! * `free`: the number `p` of free variables (the first `p` unknowns and
//!   rows), default 0;
//! * `lambda0`: the start value of the parameter, default 0.
//!
//! * `comment`: any JSON value, read and ignored (the place for annotations).
//!
//! Entries may also be written as strings that name a number (`"NaN"`, `"inf"`,
//! `"1e-3"`); non-finite entries are then rejected by name (`q[2]`, `M(1, 3)`).
//! Any other key is an error naming it, its line and column and the accepted
//! keys (a misspelt `lambda_max` would otherwise change the problem silently).
//! The file must be UTF-8 throughout. Syntax errors give the file, line and column.
//! Numbers are read correctly rounded (serde_json's `float_roundtrip`: its
//! default reader rounds about one decimal number in ten to a neighbouring
//! `f64`, which would solve a problem next to the one written).
//!
//! ```
//! let text = r#"{"M": [[2, 1], [1, 2]], "q": [1, 1], "d": [-1, -0.5]}"#;
//! let p = plcp::io::json::parse_plcp::<f64>(text.as_bytes(), "ex.json").unwrap();
//! assert_eq!((p.n(), p.free(), p.lambda_max()), (2, 0, None));
//! let bad = r#"{"M": [[2, 1], [1]], "q": [1, 1], "d": [-1, -0.5]}"#;
//! let e = plcp::io::json::parse_plcp::<f64>(bad.as_bytes(), "ex.json").unwrap_err();
//! assert!(e.to_string().contains("row 1 with 1 entries"));
//! ```
//!
//! # Output
//!
//! One JSON object (see [`path_json`] and [`lcp_json`] for the keys). Both
//! share `lambda_reached`, `pivots`, `breakpoints`, `segments` and `end`, written
//! by one piece of code (a plain LCP as the one-point path of
//! [`LcpSolution::as_path`](crate::LcpSolution::as_path)), so one reader handles both. Numbers
//! are written through `f64` (an `fx128` value is rounded to the nearest
//! `f64`). **A number that is not finite (NaN, an infinity) is written as
//! `null`**, so the output is always valid JSON: `lambda_to` of an unbounded
//! last segment and `lambda_max` when infinite are `null` by design.

mod read;
#[cfg(test)]
mod tests;
mod write;

pub use read::{lambda_max_from_f64, parse_plcp, read_plcp, read_sequence};
pub use write::{lcp_json, lcp_status, path_json, write_path_json, PathJsonOptions};
