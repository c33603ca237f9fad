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
//! [`LcpSolution::as_path`]), so one reader handles both. Numbers
//! are written through `f64` (an `fx128` value is rounded to the nearest
//! `f64`). **A number that is not finite (NaN, an infinity) is written as
//! `null`**, so the output is always valid JSON: `lambda_to` of an unbounded
//! last segment and `lambda_max` when infinite are `null` by design.

use super::{check_order, convert, convert_with, read_bytes, utf8_in};
use crate::error::PlcpError;
use crate::lemke::LcpSolution;
use crate::path::{Path, Point, Residual, Status};
use crate::problem::{Lcp, Plcp};
use crate::residual::residual;
use crate::scalar::Scalar;
use faer::{Col, Mat};
use serde::{Deserialize, Serialize};

// ---------------------------------------------------------------- input

/// A number as written in the file: a JSON number, or a string naming one.
#[derive(Clone, Copy, Debug)]
struct Num(f64);

impl<'de> Deserialize<'de> for Num {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl serde::de::Visitor<'_> for V {
            type Value = Num;
            fn expecting(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                f.write_str("a number")
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<Num, E> {
                Ok(Num(v))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<Num, E> {
                Ok(Num(v as f64))
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<Num, E> {
                Ok(Num(v as f64))
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Num, E> {
                v.trim()
                    .parse::<f64>()
                    .map(Num)
                    .map_err(|_| E::invalid_value(serde::de::Unexpected::Str(v), &"a number"))
            }
        }
        d.deserialize_any(V)
    }
}

/// `M` as written: rows of numbers (read into one row-major buffer as they
/// are parsed, no vector per row), or the name of a `.npy` or Matrix Market file.
enum MatrixIn {
    Rows {
        /// The entries, row by row.
        values: Vec<f64>,
        /// The number of rows.
        rows: usize,
        /// The length of row 0.
        cols: usize,
        /// The first row whose length differs from row 0's: index, length.
        ragged: Option<(usize, usize)>,
    },
    File(String),
}

impl<'de> Deserialize<'de> for MatrixIn {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::{DeserializeSeed, SeqAccess, Visitor};
        /// One row, appended to the buffer; its value is the row's length.
        struct Row<'a>(&'a mut Vec<f64>);
        impl<'de> DeserializeSeed<'de> for Row<'_> {
            type Value = usize;
            fn deserialize<D: serde::Deserializer<'de>>(self, d: D) -> Result<usize, D::Error> {
                d.deserialize_seq(self)
            }
        }
        impl<'de> Visitor<'de> for Row<'_> {
            type Value = usize;
            fn expecting(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                f.write_str("a row of numbers")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<usize, A::Error> {
                let mut len = 0;
                while let Some(Num(v)) = seq.next_element()? {
                    self.0.push(v);
                    len += 1;
                }
                Ok(len)
            }
        }
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = MatrixIn;
            fn expecting(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                f.write_str("a list of rows, or the name of a .npy or Matrix Market file")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<MatrixIn, E> {
                Ok(MatrixIn::File(v.to_string()))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<MatrixIn, A::Error> {
                let mut values = Vec::new();
                let (mut rows, mut cols, mut ragged) = (0, 0, None);
                while let Some(len) = seq.next_element_seed(Row(&mut values))? {
                    if rows == 0 {
                        // the first row gives the order: reserve the square
                        cols = len;
                        values.reserve(len.saturating_mul(len.saturating_sub(1)).min(1 << 28));
                    } else if len != cols && ragged.is_none() {
                        ragged = Some((rows, len));
                    }
                    rows += 1;
                }
                Ok(MatrixIn::Rows {
                    values,
                    rows,
                    cols,
                    ragged,
                })
            }
        }
        d.deserialize_any(V)
    }
}

/// A dense `M` from a [`MatrixIn`]; `file` is the problem file (a Matrix
/// Market file is named relative to its directory).
fn dense_m<T: Scalar>(m: MatrixIn, file: &str) -> Result<Mat<T>, PlcpError> {
    let (values, rows, cols, column_major) = match m {
        MatrixIn::Rows {
            values,
            rows,
            cols,
            ragged,
        } => {
            if let Some((i, len)) = ragged {
                return Err(PlcpError::Dimension {
                    what: "M".into(),
                    expected: format!("{cols} entries in every row (as in row 0)"),
                    found: format!("row {i} with {len} entries"),
                });
            }
            (values, rows, cols, false)
        }
        MatrixIn::File(name) => {
            let mtx = super::npy::read_matrix_file(&super::mtx::beside(file, &name))?;
            check_order("the order of M", mtx.rows.max(mtx.cols)).map_err(|why| {
                PlcpError::Invalid {
                    what: "M".into(),
                    why,
                }
            })?;
            let (rows, cols) = (mtx.rows, mtx.cols);
            let values = match mtx.data {
                super::mtx::MtxData::Dense(v) => v,
                super::mtx::MtxData::Triplets(t) => {
                    let mut v = vec![0.0; rows * cols];
                    for (i, j, x) in t {
                        v[i + j * rows] += x;
                    }
                    v
                }
            };
            (values, rows, cols, true)
        }
    };
    if rows == 0 {
        return Err(PlcpError::Invalid {
            what: "M".into(),
            why: "M is empty (a problem of order 0)".into(),
        });
    }
    if cols != rows {
        return Err(PlcpError::Dimension {
            what: "M".into(),
            expected: "a square matrix".into(),
            found: format!("{rows} rows of {cols} entries ({rows} x {cols})"),
        });
    }
    check_order("the order of M", rows).map_err(|why| PlcpError::Invalid {
        what: "M".into(),
        why,
    })?;
    let mut m = Mat::<T>::zeros(rows, cols);
    for j in 0..cols {
        for i in 0..rows {
            let v = if column_major {
                values[i + j * rows]
            } else {
                values[i * cols + j]
            };
            m[(i, j)] = convert_with("M", || format!("({i}, {j})"), v)?;
        }
    }
    Ok(m)
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPlcp {
    #[serde(rename = "M", alias = "m")]
    m: MatrixIn,
    q: Vec<Num>,
    d: Vec<Num>,
    #[serde(default)]
    lambda_max: Option<Num>,
    #[serde(default)]
    free: usize,
    #[serde(default)]
    lambda0: Option<Num>,
    /// An annotation: any JSON value, read and ignored.
    #[serde(default, rename = "comment")]
    _comment: Option<serde::de::IgnoredAny>,
}

fn parse_error(text: &str, file: &str, e: serde_json::Error) -> PlcpError {
    let full = e.to_string();
    let suffix = format!(" at line {} column {}", e.line(), e.column());
    let mut message = full.strip_suffix(&suffix).unwrap_or(&full).to_string();
    let (line, mut column) = (e.line().max(1), e.column().max(1));
    if let Some(rest) = message.strip_prefix("unknown field `") {
        // serde_json stops just past the key: point at its opening quote
        let key = rest.split('`').next().unwrap_or("");
        column = key_column(text, line, column, key);
        let accepted = rest
            .split_once(", expected one of ")
            .map_or("", |(_, list)| list);
        message = format!(
            "unknown key \"{key}\": the accepted keys are {accepted} (a typo would change the problem silently; annotate with \"comment\")"
        );
    }
    PlcpError::Parse {
        file: file.to_string(),
        line,
        column,
        message,
    }
}

/// The 1-based column of the opening quote of `"key"` when it ends at or just
/// before `column` on `line` (as serde_json reports an unknown key), else `column`.
fn key_column(text: &str, line: usize, column: usize, key: &str) -> usize {
    let Some(l) = text.split('\n').nth(line - 1) else {
        return column;
    };
    let quoted = format!("\"{key}\"");
    // serde_json's column counts bytes; search the line up to it
    let end = column.min(l.len());
    match l.get(..end).and_then(|head| head.rfind(&quoted)) {
        Some(b) => l[..b].chars().count() + 1,
        None => column,
    }
}

/// Parses a problem file's bytes (see the [module docs](self)); `file` is the
/// name used in error messages. Values are read as `f64` and converted to `T`.
pub fn parse_plcp<T: Scalar>(bytes: &[u8], file: &str) -> Result<Plcp<T>, PlcpError> {
    let text = utf8_in(bytes, file)?;
    let raw: RawPlcp = serde_json::from_str(text).map_err(|e| parse_error(text, file, e))?;
    let m = dense_m::<T>(raw.m, file)?;
    let dim = m.nrows();
    for (what, v) in [("q", &raw.q), ("d", &raw.d)] {
        if v.len() != dim {
            return Err(PlcpError::Dimension {
                what: what.into(),
                expected: format!("{dim} entries (the order of M)"),
                found: format!("{} entries", v.len()),
            });
        }
    }
    if raw.free > dim {
        return Err(PlcpError::Invalid {
            what: "free".into(),
            why: format!("{} free variables but M has order {dim}", raw.free),
        });
    }
    let col = |what: &str, v: &[Num]| -> Result<Col<T>, PlcpError> {
        let mut c = Col::<T>::zeros(v.len());
        for (i, x) in v.iter().enumerate() {
            c[i] = convert_with(what, || format!("[{i}]"), x.0)?;
        }
        Ok(c)
    };
    let q = col("q", &raw.q)?;
    let d = col("d", &raw.d)?;
    let lambda0 = match raw.lambda0 {
        None => T::zero(),
        Some(Num(v)) if v.is_finite() => convert("lambda0", "", v)?,
        Some(Num(v)) => {
            return Err(PlcpError::Invalid {
                what: "lambda0".into(),
                why: format!("must be a finite number, got {v}"),
            })
        }
    };
    let lambda_max = lambda_max_from_f64(raw.lambda_max.map(|n| n.0))?;
    Plcp::mixed(m.as_ref(), q.as_ref(), d.as_ref(), raw.free)?.with_range(lambda0, lambda_max)
}

/// The file of `plcp sequence`: one matrix and the targets `g_0 .. g_K`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSequence {
    #[serde(rename = "M", alias = "m")]
    m: MatrixIn,
    targets: Vec<Vec<Num>>,
    /// An annotation: any JSON value, read and ignored.
    #[serde(default, rename = "comment")]
    _comment: Option<serde::de::IgnoredAny>,
}

/// Reads the file of `plcp sequence`, `{"M": [[...]], "targets": [[...], ...]}`:
/// a square `M` and at least one target of its order.
pub fn read_sequence(path: &std::path::Path) -> Result<(Mat<f64>, Vec<Col<f64>>), PlcpError> {
    let bytes = read_bytes(path)?;
    let file = path.display().to_string();
    let text = utf8_in(&bytes, &file)?;
    let raw: RawSequence = serde_json::from_str(text).map_err(|e| parse_error(text, &file, e))?;
    let m = dense_m::<f64>(raw.m, &file)?;
    let dim = m.nrows();
    if raw.targets.is_empty() {
        return Err(PlcpError::Invalid {
            what: "targets".into(),
            why: "no target (at least g_0 is needed)".into(),
        });
    }
    let mut targets = Vec::with_capacity(raw.targets.len());
    for (k, g) in raw.targets.iter().enumerate() {
        if g.len() != dim {
            return Err(PlcpError::Dimension {
                what: format!("targets[{k}]"),
                expected: format!("{dim} entries (the order of M)"),
                found: format!("{} entries", g.len()),
            });
        }
        let mut c = Col::<f64>::zeros(dim);
        for (i, x) in g.iter().enumerate() {
            c[i] = convert_with("targets", || format!("[{k}][{i}]"), x.0)?;
        }
        targets.push(c);
    }
    Ok((m, targets))
}

/// Converts a requested end of the parameter range: `None` or `+inf` is
/// infinity, NaN and `-inf` are errors, a finite value must fit `T`.
pub fn lambda_max_from_f64<T: Scalar>(v: Option<f64>) -> Result<Option<T>, PlcpError> {
    match v {
        None => Ok(None),
        Some(v) if v == f64::INFINITY => Ok(None),
        Some(v) if v.is_finite() => Ok(Some(convert("lambda_max", "", v)?)),
        Some(v) => Err(PlcpError::Invalid {
            what: "lambda_max".into(),
            why: format!("must be a number or infinity, got {v}"),
        }),
    }
}

/// Reads a problem file (see the [module docs](self)).
pub fn read_plcp<T: Scalar>(path: &std::path::Path) -> Result<Plcp<T>, PlcpError> {
    let bytes = read_bytes(path)?;
    parse_plcp(&bytes, &path.display().to_string())
}

// ---------------------------------------------------------------- output
//
// The output is serialised from views of the path (no copy of its columns)
// straight into the writer: at n = 2000 a path of 1000 segments is 109 MB of
// JSON, and building it as owned vectors and one `String` first cost more
// than the solve (`docs/performance.md`, Input).

type Num64 = Option<f64>;

fn num<T: Scalar>(x: T) -> Num64 {
    f(x.to_f64())
}

fn f(v: f64) -> Num64 {
    v.is_finite().then_some(v)
}

/// A column written as a JSON array of numbers (`null` where not finite).
struct ColOut<'a, T: Scalar>(&'a Col<T>);

impl<T: Scalar> Serialize for ColOut<'_, T> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq((0..self.0.nrows()).map(|i| num(self.0[i])))
    }
}

/// `from + slope * dl`, element by element as [`crate::path::Segment::z0`]
/// computes it (the same numbers), written without storing the column.
struct AffineOut<'a, T: Scalar> {
    from: &'a Col<T>,
    slope: &'a Col<T>,
    dl: T,
}

impl<T: Scalar> Serialize for AffineOut<'_, T> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let (from, slope, dl) = (self.from, self.slope, self.dl);
        s.collect_seq((0..from.nrows()).map(|i| num(from[i] + slope[i] * dl)))
    }
}

/// `Some(column)` in the mixed form, `None` (key omitted) in the standard form.
fn free_col<T: Scalar>(free: usize, c: &Col<T>) -> Option<ColOut<'_, T>> {
    (free > 0).then_some(ColOut(c))
}

#[derive(Serialize)]
#[serde(bound = "")]
struct PointOut<'a, T: Scalar> {
    lambda: Num64,
    z: ColOut<'a, T>,
    w: ColOut<'a, T>,
    #[serde(skip_serializing_if = "Option::is_none")]
    u: Option<ColOut<'a, T>>,
}

impl<'a, T: Scalar> PointOut<'a, T> {
    fn new(free: usize, p: &'a Point<T>) -> Self {
        Self {
            lambda: num(p.lambda),
            z: ColOut(&p.z),
            w: ColOut(&p.w),
            u: free_col(free, &p.u),
        }
    }
}

#[derive(Serialize)]
#[serde(bound = "")]
struct AtOut<'a, T: Scalar> {
    lambda: Num64,
    #[serde(skip_serializing_if = "Option::is_none")]
    z: Option<ColOut<'a, T>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    w: Option<ColOut<'a, T>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    u: Option<ColOut<'a, T>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    residual: Option<ResidualOut>,
    #[serde(skip_serializing_if = "Option::is_none")]
    error: Option<String>,
}

#[derive(Serialize)]
struct BreakpointOut {
    lambda: Num64,
    entering: String,
    leaving: String,
    degenerate: bool,
    turning: bool,
}

/// Names written as a JSON array of strings.
struct NamesOut<'a>(&'a [crate::path::Var]);

impl Serialize for NamesOut<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeSeq;
        // each name written through its `Display`, without a `String` each
        struct Name<'a>(&'a crate::path::Var);
        impl Serialize for Name<'_> {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.collect_str(self.0)
            }
        }
        let mut seq = s.serialize_seq(Some(self.0.len()))?;
        for v in self.0 {
            seq.serialize_element(&Name(v))?;
        }
        seq.end()
    }
}

#[derive(Serialize)]
#[serde(bound = "")]
struct SegmentOut<'a, T: Scalar> {
    lambda_from: Num64,
    lambda_to: Num64,
    unbounded: bool,
    basis: NamesOut<'a>,
    z0: AffineOut<'a, T>,
    dz: ColOut<'a, T>,
    w0: AffineOut<'a, T>,
    dw: ColOut<'a, T>,
    #[serde(skip_serializing_if = "Option::is_none")]
    u0: Option<AffineOut<'a, T>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    du: Option<ColOut<'a, T>>,
}

/// The segments, each built as it is written.
struct SegmentsOut<'a, T: Scalar> {
    free: usize,
    segments: &'a [crate::path::Segment<T>],
}

impl<T: Scalar> Serialize for SegmentsOut<'_, T> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let p = self.free;
        s.collect_seq(self.segments.iter().map(|s| {
            let dl = -s.lambda_from;
            SegmentOut {
                lambda_from: num(s.lambda_from),
                lambda_to: if s.unbounded { None } else { num(s.lambda_to) },
                unbounded: s.unbounded,
                basis: NamesOut(&s.basis),
                z0: AffineOut {
                    from: &s.z_from,
                    slope: &s.dz,
                    dl,
                },
                dz: ColOut(&s.dz),
                w0: AffineOut {
                    from: &s.w_from,
                    slope: &s.dw,
                    dl,
                },
                dw: ColOut(&s.dw),
                u0: (p > 0).then_some(AffineOut {
                    from: &s.u_from,
                    slope: &s.du,
                    dl,
                }),
                du: free_col(p, &s.du),
            }
        }))
    }
}

#[derive(Serialize, Clone, Copy)]
struct ResidualOut {
    equation: Num64,
    feasibility: Num64,
    complementarity: Num64,
}

impl From<Residual> for ResidualOut {
    fn from(r: Residual) -> Self {
        Self {
            equation: f(r.equation),
            feasibility: f(r.feasibility),
            complementarity: f(r.complementarity),
        }
    }
}

#[derive(Serialize)]
struct TimingOut {
    solve_seconds: Num64,
}

#[derive(Serialize)]
struct FreeBlockOut {
    rank: usize,
    nonbasic_free: Vec<usize>,
    dependent_rows: Vec<usize>,
}

#[derive(Serialize)]
struct InfoOut {
    method: &'static str,
    precision: &'static str,
    pivots: usize,
    start_pivots: usize,
    degenerate_pivots: usize,
    refactorisations: usize,
    turning_points: usize,
    max_condition: Num64,
    free_block: FreeBlockOut,
}

impl InfoOut {
    fn new<T: Scalar>(info: &crate::path::Info) -> Self {
        Self {
            method: info.method,
            precision: if info.precision.is_empty() {
                T::NAME
            } else {
                info.precision
            },
            pivots: info.pivots,
            start_pivots: info.start_pivots,
            degenerate_pivots: info.degenerate_pivots,
            refactorisations: info.refactorisations,
            turning_points: info.turning_points,
            max_condition: f(info.max_condition),
            free_block: FreeBlockOut {
                rank: info.free_block.rank,
                nonbasic_free: info.free_block.nonbasic_free.clone(),
                dependent_rows: info.free_block.dependent_rows.clone(),
            },
        }
    }
}

#[derive(Serialize)]
#[serde(bound = "")]
struct RayOut<'a, T: Scalar> {
    start: PointOut<'a, T>,
    dlambda: Num64,
    dz: ColOut<'a, T>,
    dw: ColOut<'a, T>,
    #[serde(skip_serializing_if = "Option::is_none")]
    du: Option<ColOut<'a, T>>,
}

/// The keys `plcp solve` and `plcp lcp` share, in both outputs in this order
/// (one reader handles both): `lambda_reached`, `pivots`, `breakpoints`,
/// `segments`, `end`.
#[derive(Serialize)]
#[serde(bound = "")]
struct TraceOut<'a, T: Scalar> {
    lambda_reached: Num64,
    pivots: usize,
    breakpoints: Vec<BreakpointOut>,
    segments: SegmentsOut<'a, T>,
    end: PointOut<'a, T>,
}

impl<'a, T: Scalar> TraceOut<'a, T> {
    /// `free` is the number of free variables (`u` is written when positive).
    fn new(free: usize, path: &'a Path<T>) -> Self {
        Self {
            lambda_reached: num(path.lambda_reached),
            pivots: path.info.pivots,
            breakpoints: path
                .breakpoints
                .iter()
                .map(|b| BreakpointOut {
                    lambda: num(b.lambda),
                    entering: b.entering.to_string(),
                    leaving: b.leaving.to_string(),
                    degenerate: b.degenerate,
                    turning: b.turning,
                })
                .collect(),
            segments: SegmentsOut {
                free,
                segments: &path.segments,
            },
            end: PointOut::new(free, &path.end),
        }
    }
}

#[derive(Serialize)]
#[serde(bound = "")]
struct PathOut<'a, T: Scalar> {
    status: &'static str,
    n: usize,
    free: usize,
    lambda0: Num64,
    lambda_max: Num64,
    #[serde(flatten)]
    trace: TraceOut<'a, T>,
    at: Vec<AtOut<'a, T>>,
    residual: ResidualOut,
    timing: TimingOut,
    info: InfoOut,
    message: &'a str,
    #[serde(skip_serializing_if = "Option::is_none")]
    ray: Option<RayOut<'a, T>>,
    #[serde(flatten)]
    extra: &'a serde_json::Map<String, serde_json::Value>,
}

/// The JSON report of a solved path (one line, no trailing newline): what
/// [`write_path_json`] writes, as a `String`.
///
/// Keys, in order: `status` ([`Status::as_str`]), `n`, `free`, `lambda0`,
/// `lambda_max` (`null`: infinity), `lambda_reached`, `pivots`, `breakpoints`
/// (each `lambda`, `entering`, `leaving` (variable names `"z3"`, `"w3"`,
/// `"u0"`, `"L"`, 0-based), `degenerate`, `turning`), `segments` (each
/// `lambda_from`, `lambda_to` (`null` when unbounded), `unbounded`, `basis`
/// (names), `z0`, `dz`, `w0`, `dw` and, when `free > 0`, `u0`, `du`: the
/// solution on the segment is `z0 + L dz` etc.), `end` (`lambda`, `z`, `w`,
/// and `u` when `free > 0`), `at` (one entry per value of `at`: `lambda`, `z`,
/// `w`, (`u`), `residual`; or `lambda` and `error` when the value lies outside
/// the traced range), `residual` (`equation`, `feasibility`, `complementarity`:
/// the largest of the solver's own record over its breakpoints and a fresh
/// evaluation at `end` and at every `at` point, each relative as in
/// [`crate::residual::residual`]), `timing` (`solve_seconds`, as passed in),
/// `info` (`method`, `precision`, `pivots`, `start_pivots`,
/// `degenerate_pivots`, `refactorisations`, `turning_points`, `max_condition`,
/// `free_block` {`rank`, `nonbasic_free`, `dependent_rows`}), `message`, and
/// `ray` (`start` point, `dlambda`, `dz`, `dw`, (`du`)) when the path ended on one.
/// Non-finite numbers are `null`.
pub fn path_json<T: Scalar>(
    problem: &Plcp<T>,
    path: &Path<T>,
    at: &[f64],
    solve_seconds: f64,
) -> String {
    let mut out = Vec::new();
    let written = write_path_json(
        &mut out,
        problem,
        path,
        at,
        solve_seconds,
        true,
        &serde_json::Map::new(),
    );
    match written.map(|_| String::from_utf8(out)) {
        Ok(Ok(text)) => text,
        // Serialising these plain structs into memory cannot fail, and
        // serde_json writes UTF-8; keep the output valid JSON anyway.
        Ok(Err(e)) => serde_json::json!({"status": "error", "message": e.to_string()}).to_string(),
        Err(e) => serde_json::json!({"status": "error", "message": e.to_string()}).to_string(),
    }
}

/// Writes the report of [`path_json`] to `out` as it is built (the path's
/// columns are read in place, nothing of the size of the output is held),
/// followed by the fields of `extra` (for example a `certificate`), in order.
/// With `with_segments` false the `segments` array is written empty (the
/// breakpoints, the end point and the `at` values are all there; at n = 2000
/// the segments are 100 MB of the output and most of its writing time).
/// An error is the writer's.
pub fn write_path_json<T: Scalar, W: std::io::Write>(
    out: W,
    problem: &Plcp<T>,
    path: &Path<T>,
    at: &[f64],
    solve_seconds: f64,
    with_segments: bool,
    extra: &serde_json::Map<String, serde_json::Value>,
) -> std::io::Result<()> {
    let p = problem.free();
    let mut res = path.info.residual.max(residual(problem, &path.end));
    let points: Vec<Option<(Point<T>, Residual)>> = at
        .iter()
        .map(|&l| {
            let point = if l.is_finite() {
                path.at(T::from_f64(l))
            } else {
                None
            };
            point.map(|pt| {
                let r = residual(problem, &pt);
                res = res.max(r);
                (pt, r)
            })
        })
        .collect();
    let at: Vec<AtOut<'_, T>> = at
        .iter()
        .zip(&points)
        .map(|(&l, point)| match point {
            Some((pt, r)) => AtOut {
                lambda: f(l),
                z: Some(ColOut(&pt.z)),
                w: Some(ColOut(&pt.w)),
                u: free_col(p, &pt.u),
                residual: Some((*r).into()),
                error: None,
            },
            None => AtOut {
                lambda: f(l),
                z: None,
                w: None,
                u: None,
                residual: None,
                error: Some(format!(
                    "lambda = {l} lies outside the traced range [{}, {}] (status {})",
                    path.lambda0.to_f64(),
                    path.lambda_reached.to_f64(),
                    path.status.as_str()
                )),
            },
        })
        .collect();
    let mut trace = TraceOut::new(p, path);
    if !with_segments {
        trace.segments.segments = &[];
    }
    let report = PathOut {
        status: path.status.as_str(),
        n: problem.n(),
        free: p,
        lambda0: num(path.lambda0),
        lambda_max: path.lambda_max.and_then(num),
        trace,
        at,
        residual: res.into(),
        timing: TimingOut {
            solve_seconds: f(solve_seconds),
        },
        info: InfoOut::new::<T>(&path.info),
        message: &path.message,
        ray: path.ray.as_ref().map(|r| RayOut {
            start: PointOut::new(p, &r.start),
            dlambda: num(r.dlambda),
            dz: ColOut(&r.dz),
            dw: ColOut(&r.dw),
            du: free_col(p, &r.du),
        }),
        extra,
    };
    let mut out = std::io::BufWriter::with_capacity(1 << 16, out);
    serde_json::to_writer(&mut out, &report).map_err(std::io::Error::other)?;
    std::io::Write::flush(&mut out)
}

#[derive(Serialize)]
#[serde(bound = "")]
struct LcpOut<'a, T: Scalar> {
    status: &'static str,
    n: usize,
    z: ColOut<'a, T>,
    w: ColOut<'a, T>,
    #[serde(flatten)]
    trace: TraceOut<'a, T>,
    residual: ResidualOut,
    siconos_error: Num64,
    timing: TimingOut,
    info: InfoOut,
    message: &'a str,
}

/// The name of an LCP outcome: `"solved"` for [`Status::Reached`] (and for an
/// unbounded ray, which cannot end a plain LCP but would mean the same), else
/// [`Status::as_str`].
pub fn lcp_status(status: Status) -> &'static str {
    if status.is_success() {
        "solved"
    } else {
        status.as_str()
    }
}

/// `w = q + M z`, recomputed in `T` (the Siconos measure does the same).
fn fresh_w<T: Scalar>(lcp: &Lcp<T>, z: &Col<T>) -> Col<T> {
    let (m, q) = (lcp.m(), lcp.q());
    Col::from_fn(lcp.n(), |i| {
        (0..lcp.n()).fold(q[i], |acc, j| acc + m[(i, j)] * z[j])
    })
}

/// The JSON report of a plain LCP (one line): `status` ([`lcp_status`]), `n`,
/// `z`, `w`, then the keys shared with [`path_json`], written by the same code
/// from [`LcpSolution::as_path`] (the single point `L = 0`): `lambda_reached`
/// (0), `pivots`, `breakpoints` (empty), `segments` (empty), `end` (`lambda` 0,
/// `z`, `w`), then `residual` (as in [`path_json`]: the solver's record and
/// a fresh evaluation of `(z, w)`), `siconos_error`
/// ([`super::siconos::siconos_error`] of `z` and `w = q + M z` recomputed from
/// `z`, as Siconos does), `timing` (`solve_seconds`), `info`,
/// `message`. Non-finite numbers are `null`.
pub fn lcp_json<T: Scalar>(lcp: &Lcp<T>, sol: &LcpSolution<T>, solve_seconds: f64) -> String {
    let n = lcp.n();
    let zero = Col::<T>::zeros(n);
    let fresh = Plcp::new(lcp.m(), lcp.q(), zero.as_ref())
        .map(|p| {
            residual(
                &p,
                &Point {
                    lambda: T::zero(),
                    z: sol.z.clone(),
                    w: sol.w.clone(),
                    u: Col::zeros(0),
                },
            )
        })
        .unwrap_or_default();
    let as_path = sol.as_path();
    let out = LcpOut {
        status: lcp_status(sol.status),
        n,
        z: ColOut(&sol.z),
        w: ColOut(&sol.w),
        trace: TraceOut::new(0, &as_path),
        residual: sol.info.residual.max(fresh).into(),
        siconos_error: f(super::siconos::siconos_error(
            lcp.q(),
            sol.z.as_ref(),
            fresh_w(lcp, &sol.z).as_ref(),
        )),
        timing: TimingOut {
            solve_seconds: f(solve_seconds),
        },
        info: InfoOut::new::<T>(&sol.info),
        message: &sol.message,
    };
    serde_json::to_string(&out).unwrap_or_else(|e| {
        serde_json::json!({"status": "error", "message": e.to_string()}).to_string()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        parse_plcp::<f64>(text.as_bytes(), "p.json")
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn reads_all_keys() {
        let p = parse_plcp::<f64>(
            br#"{"M": [[1, 0, 0], [0, 2, 1], [0, 1, 2]], "q": [0, 1, "2"], "d": [1, -1, -1],
                "lambda_max": 5.5, "free": 1, "lambda0": -1, "comment": "ignored"}"#,
            "p.json",
        )
        .unwrap();
        assert_eq!((p.dim(), p.n(), p.free()), (3, 2, 1));
        assert_eq!(p.lambda_max(), Some(5.5));
        assert_eq!(p.lambda0(), -1.0);
        assert_eq!(p.m()[(1, 2)], 1.0);
        assert_eq!(p.q()[2], 2.0);
        for lm in ["null", "\"inf\"", "\"Infinity\""] {
            let text = format!(r#"{{"M": [[1]], "q": [1], "d": [1], "lambda_max": {lm}}}"#);
            let p = parse_plcp::<f32>(text.as_bytes(), "p.json").unwrap();
            assert_eq!(p.lambda_max(), None, "{lm}");
        }
    }

    /// A misspelt key used to be skipped (`lambda_mx`: traced to infinity).
    #[test]
    fn unknown_keys_are_errors_with_position() {
        let e = err("{\"M\": [[1]], \"q\": [1],\n  \"d\": [1], \"lambda_mx\": 2}");
        assert!(
            e.starts_with("p.json:2:13: unknown key \"lambda_mx\""),
            "{e}"
        );
        for key in [
            "`M`",
            "`q`",
            "`d`",
            "`lambda_max`",
            "`free`",
            "`lambda0`",
            "`comment`",
        ] {
            assert!(e.contains(key), "{key} not listed: {e}");
        }
        // a key with a non-ASCII name, after non-ASCII text on its line: columns count characters
        let e = err("{\"M\": [[1]], \"comment\": \"é\", \"λ\": 1, \"q\": [1], \"d\": [1]}");
        assert!(e.starts_with("p.json:1:30: unknown key \"λ\""), "{e}");
        // `comment` takes any JSON value
        for c in [
            "\"text\"",
            "1",
            "null",
            "[1, \"x\"]",
            "{\"by\": \"me\", \"lambda_max\": 3}",
        ] {
            let text = format!(r#"{{"comment": {c}, "M": [[1]], "q": [1], "d": [1]}}"#);
            let p = parse_plcp::<f64>(text.as_bytes(), "p.json").unwrap();
            assert_eq!(p.lambda_max(), None, "{c}");
        }
    }

    #[test]
    fn invalid_utf8_is_an_error_naming_the_offset() {
        // in an ignored string (serde_json would skip it unchecked), in a key, outside strings
        for (bytes, offset, line, column) in [
            (
                &b"{\"M\": [[1]], \"q\": [1], \"d\": [1], \"comment\": \"\xff\"}"[..],
                45,
                1,
                46,
            ),
            (
                &b"{\"M\": [[1]],\n\"q\": [1], \"d\": [1], \"\xc3\": 1}"[..],
                34,
                2,
                22,
            ),
            (
                &b"{\"M\": [[1]], \"q\": [1], \"d\": [1]}\xe9"[..],
                32,
                1,
                33,
            ),
        ] {
            let e = parse_plcp::<f64>(bytes, "p.json").unwrap_err().to_string();
            let want = format!("p.json:{line}:{column}: invalid UTF-8 at byte offset {offset}:");
            assert!(e.starts_with(&want), "{e} (want {want})");
        }
    }

    #[test]
    fn named_errors() {
        let e = err(r#"{"M": [[1, 2], [3]], "q": [1, 1], "d": [1, 1]}"#);
        assert!(e.contains("M") && e.contains("row 1 with 1 entries"), "{e}");
        let e = err(r#"{"M": [[1, 2, 3], [3, 4, 5]], "q": [1, 1], "d": [1, 1]}"#);
        assert!(e.contains("square") && e.contains("2 x 3"), "{e}");
        let e = err(r#"{"M": [[1, 2], [3, 4]], "q": [1], "d": [1, 1]}"#);
        assert!(e.contains("q has 1 entries"), "{e}");
        let e = err(r#"{"M": [[1, 2], [3, 4]], "q": [1, "NaN"], "d": [1, 1]}"#);
        assert!(e.contains("non-finite entry in q at [1]"), "{e}");
        let e = err(r#"{"M": [[1, 2], [3, 4]], "q": [1, 1], "d": [1, 1], "free": 3}"#);
        assert!(e.contains("free") && e.contains("order 2"), "{e}");
        let e = err("{\"M\": [[1, 2],\n [3, 4]], \"q\": [1, 1], \"d\": [1, 1");
        assert!(e.starts_with("p.json:2:"), "{e}");
        let e = err(r#"{"M": [[1, 2], [3, 4]], "q": [1, 1]}"#);
        assert!(e.contains("missing field `d`"), "{e}");
        let e = err(r#"{"M": [[1, 2], [3, 4]], "q": [1, "x"], "d": [1, 1]}"#);
        assert!(e.contains("p.json:1:") && e.contains("\"x\""), "{e}");
        let e = err(r#"{"M": [[1, 2], [3, 4]], "q": [1, 1], "d": [1, 1], "lambda_max": "NaN"}"#);
        assert!(e.contains("lambda_max"), "{e}");
        let e = err(r#"{"M": [], "q": [], "d": []}"#);
        assert!(e.contains("empty"), "{e}");
        let e = parse_plcp::<f32>(br#"{"M": [[1e300]], "q": [1], "d": [1]}"#, "p.json")
            .unwrap_err()
            .to_string();
        assert!(e.contains("overflows") && e.contains("f32"), "{e}");
    }
}
