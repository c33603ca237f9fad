//! Reading plcp's JSON problem files (see the module documentation of
//! [`super`] for the format).

use super::super::{check_order, convert, convert_with, read_bytes, utf8_in};
use crate::error::PlcpError;
use crate::problem::Plcp;
use crate::scalar::Scalar;
use faer::{Col, Mat};
use serde::Deserialize;

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
            let mtx = crate::io::npy::read_matrix_file(&crate::io::mtx::beside(file, &name))?;
            check_order("the order of M", mtx.rows.max(mtx.cols)).map_err(|why| {
                PlcpError::Invalid {
                    what: "M".into(),
                    why,
                }
            })?;
            let (rows, cols) = (mtx.rows, mtx.cols);
            let values = match mtx.data {
                crate::io::mtx::MtxData::Dense(v) => v,
                crate::io::mtx::MtxData::Triplets(t) => {
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

/// Parses a problem file's bytes (see the [module docs](super)); `file` is the
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

/// Reads a problem file (see the [module docs](super)).
pub fn read_plcp<T: Scalar>(path: &std::path::Path) -> Result<Plcp<T>, PlcpError> {
    let bytes = read_bytes(path)?;
    parse_plcp(&bytes, &path.display().to_string())
}
