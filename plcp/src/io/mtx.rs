//! Matrix Market files (`.mtx`): the exchange format of the NIST Matrix
//! Market and the SuiteSparse collection, which numerical tools (SciPy's
//! `scipy.io.mmwrite`, MATLAB, Julia, PETSc) write. plcp reads `M` from one
//! when the problem file names it (`"M": "m.mtx"` in [`super::json`],
//! `"M_sparse": "m.mtx"` in [`super::sparse_json`]).
//!
//! ```text
//! %%MatrixMarket matrix coordinate real symmetric
//! % comments
//! 3 3 4
//! 1 1 4.0
//! 2 1 -1.0
//! 2 2 4.0
//! 3 3 4.0
//! ```
//!
//! Accepted: `matrix` objects in `array` (dense, column by column) or
//! `coordinate` (triplets, 1-based; a repeated position is summed) format,
//! with `real`, `integer` or `pattern` (coordinate only: every entry 1)
//! fields and `general`, `symmetric` or `skew-symmetric` symmetry (the
//! other triangle is filled in). `complex` and `hermitian` files are errors
//! that say so. Numbers are read with Rust's correctly rounded parser; a
//! malformed header, size line or entry is a [`PlcpError::Parse`] with its
//! line and column, and a missing or extra entry an error that says how many
//! were expected.

use super::utf8_in;
use crate::error::PlcpError;

/// How the file stores the matrix.
#[derive(Clone, Debug, PartialEq)]
pub enum MtxData {
    /// Every entry, column-major (`values[i + j * rows]`), the other
    /// triangle filled in for a symmetric file.
    Dense(Vec<f64>),
    /// `(row, column, value)`, 0-based, both triangles for a symmetric file,
    /// in file order (repeated positions are kept: the caller sums them).
    Triplets(Vec<(usize, usize, f64)>),
}

/// A matrix read from a Matrix Market file.
#[derive(Clone, Debug, PartialEq)]
pub struct Mtx {
    /// Number of rows.
    pub rows: usize,
    /// Number of columns.
    pub cols: usize,
    /// The entries.
    pub data: MtxData,
}

#[derive(Clone, Copy, PartialEq)]
enum Symmetry {
    General,
    Symmetric,
    Skew,
}

/// A cursor over the file's lines that names the line and column of what it
/// rejects.
struct Lines<'a> {
    lines: std::iter::Enumerate<std::str::Lines<'a>>,
}

impl<'a> Lines<'a> {
    /// The next line that is neither blank nor a `%` comment: its 1-based
    /// number and text.
    fn next_data(&mut self) -> Option<(usize, &'a str)> {
        self.lines.by_ref().map(|(i, l)| (i + 1, l)).find(|(_, l)| {
            let t = l.trim_start();
            !t.is_empty() && !t.starts_with('%')
        })
    }
}

/// A syntax error at `line`, `column` (1-based) of `file`.
fn error(file: &str, line: usize, column: usize, message: impl Into<String>) -> PlcpError {
    PlcpError::Parse {
        file: file.to_string(),
        line,
        column,
        message: message.into(),
    }
}

/// The whitespace-separated fields of a line, each with its 1-based column.
fn fields(line: &str) -> impl Iterator<Item = (usize, &str)> {
    line.split_ascii_whitespace().map(move |f| {
        // the field is a subslice of the line: its offset is its column
        let offset = f.as_ptr() as usize - line.as_ptr() as usize;
        (line[..offset].chars().count() + 1, f)
    })
}

/// Parses a Matrix Market file's bytes; `file` names it in error messages.
///
/// ```
/// use plcp::io::mtx::{parse_mtx, MtxData};
/// let text = "%%MatrixMarket matrix array real symmetric\n2 2\n4\n-1\n4\n";
/// let m = parse_mtx(text.as_bytes(), "m.mtx").unwrap();
/// assert_eq!(m.data, MtxData::Dense(vec![4.0, -1.0, -1.0, 4.0]));
/// let bad = "%%MatrixMarket matrix coordinate real general\n2 2 1\n1 3 1.0\n";
/// let e = parse_mtx(bad.as_bytes(), "m.mtx").unwrap_err().to_string();
/// assert!(e.contains("m.mtx:3:3") && e.contains("column index 3"), "{e}");
/// ```
pub fn parse_mtx(bytes: &[u8], file: &str) -> Result<Mtx, PlcpError> {
    let text = utf8_in(bytes, file)?;
    let mut lines = Lines {
        lines: text.lines().enumerate(),
    };
    let header = lines.lines.next().map(|(_, l)| l).unwrap_or("");
    let h = parse_header(header, file)?;
    let (rows, cols, nnz) = parse_sizes(&mut lines, text, file, &h)?;
    let body = Body {
        file,
        text,
        rows,
        cols,
        symmetry: h.symmetry,
        name: &h.name,
    };
    let data = if h.dense {
        MtxData::Dense(body.array(&mut lines)?)
    } else {
        MtxData::Triplets(body.coordinate(&mut lines, nnz, h.pattern)?)
    };
    Ok(Mtx { rows, cols, data })
}

/// The header line `%%MatrixMarket matrix <format> <field> <symmetry>`.
struct Header {
    /// `array` (else `coordinate`).
    dense: bool,
    /// `pattern`: every entry 1.
    pattern: bool,
    symmetry: Symmetry,
    /// The symmetry as written (lower case), for messages.
    name: String,
}

/// Reads the header line (line 1).
fn parse_header(header: &str, file: &str) -> Result<Header, PlcpError> {
    let words: Vec<String> = header
        .split_ascii_whitespace()
        .map(|w| w.to_ascii_lowercase())
        .collect();
    if words.first().map(String::as_str) != Some("%%matrixmarket") || words.len() != 5 {
        return Err(error(
                file,
            1,
            1,
            "not a Matrix Market file: the first line must be \"%%MatrixMarket matrix <array|coordinate> <real|integer|pattern> <general|symmetric|skew-symmetric>\"",
        ));
    }
    let word_column = |k: usize| fields(header).nth(k).map_or(1, |(c, _)| c);
    if words[1] != "matrix" {
        return Err(error(
            file,
            1,
            word_column(1),
            format!("object \"{}\": only \"matrix\" is read", words[1]),
        ));
    }
    let dense = match words[2].as_str() {
        "array" => true,
        "coordinate" => false,
        other => {
            return Err(error(
                file,
                1,
                word_column(2),
                format!("format \"{other}\": expected \"array\" or \"coordinate\""),
            ))
        }
    };
    let pattern = match words[3].as_str() {
        "real" | "integer" | "double" => false,
        "pattern" if !dense => true,
        other => {
            return Err(error(
                file,
                1,
                word_column(3),
                format!(
                    "field \"{other}\": plcp reads real and integer matrices (and pattern in coordinate format)"
                ),
            ))
        }
    };
    let symmetry = match words[4].as_str() {
        "general" => Symmetry::General,
        "symmetric" => Symmetry::Symmetric,
        "skew-symmetric" => Symmetry::Skew,
        other => {
            return Err(error(
                file,
                1,
                word_column(4),
                format!(
                "symmetry \"{other}\": expected \"general\", \"symmetric\" or \"skew-symmetric\""
            ),
            ))
        }
    };
    Ok(Header {
        dense,
        pattern,
        symmetry,
        name: words[4].clone(),
    })
}

/// Reads the size line: `(rows, cols, entries)` (`entries` 0 for an array).
fn parse_sizes(
    lines: &mut Lines<'_>,
    text: &str,
    file: &str,
    h: &Header,
) -> Result<(usize, usize, usize), PlcpError> {
    let (dense, symmetry) = (h.dense, h.symmetry);
    let Some((size_line, size)) = lines.next_data() else {
        return Err(error(
            file,
            text.lines().count().max(1),
            1,
            "no size line (rows columns [entries])",
        ));
    };
    let want = if dense { 2 } else { 3 };
    let mut dims = Vec::with_capacity(3);
    for (column, f) in fields(size) {
        if dims.len() == want {
            return Err(error(
                file,
                size_line,
                column,
                format!("the size line has more than {want} numbers"),
            ));
        }
        dims.push(f.parse::<usize>().map_err(|_| {
            error(
                file,
                size_line,
                column,
                format!("\"{f}\" is not a size (a nonnegative integer)"),
            )
        })?);
    }
    if dims.len() != want {
        return Err(error(
            file,
            size_line,
            1,
            format!(
                "the size line needs {want} numbers ({}), found {}",
                if dense {
                    "rows columns"
                } else {
                    "rows columns entries"
                },
                dims.len()
            ),
        ));
    }
    let (rows, cols) = (dims[0], dims[1]);
    if symmetry != Symmetry::General && rows != cols {
        return Err(error(
            file,
            size_line,
            1,
            format!("a {} matrix must be square, got {rows} x {cols}", h.name),
        ));
    }
    Ok((rows, cols, if dense { 0 } else { dims[2] }))
}

/// A number at `line`, `column` of `file`.
fn value(file: &str, line: usize, column: usize, f: &str) -> Result<f64, PlcpError> {
    f.parse::<f64>()
        .map_err(|_| error(file, line, column, format!("\"{f}\" is not a number")))
}

/// What reading the entries needs to know.
struct Body<'a> {
    file: &'a str,
    /// The whole file (its line count places an error at the end).
    text: &'a str,
    rows: usize,
    cols: usize,
    symmetry: Symmetry,
    /// The symmetry as written.
    name: &'a str,
}

impl Body<'_> {
    /// The entries of an `array` file, column-major, the other triangle
    /// filled in.
    fn array(&self, lines: &mut Lines<'_>) -> Result<Vec<f64>, PlcpError> {
        let Body {
            file,
            text,
            rows,
            cols,
            symmetry,
            name,
        } = *self;
        let mut values = vec![0.0; rows * cols];
        // the entries stored: all of them, or the lower triangle (with the
        // diagonal unless skew-symmetric), column by column
        let mut slots = (0..cols).flat_map(|j| {
            let first = match symmetry {
                Symmetry::General => 0,
                Symmetry::Symmetric => j,
                Symmetry::Skew => j + 1,
            };
            (first..rows).map(move |i| (i, j))
        });
        let expected = match symmetry {
            Symmetry::General => rows * cols,
            Symmetry::Symmetric => rows * (rows + 1) / 2,
            Symmetry::Skew => rows * rows.saturating_sub(1) / 2,
        };
        let mut read = 0;
        while let Some((line, text)) = lines.next_data() {
            for (column, f) in fields(text) {
                let v = value(file, line, column, f)?;
                let Some((i, j)) = slots.next() else {
                    return Err(error(
                        file,
                        line,
                        column,
                        format!(
                            "more entries than the {expected} a {rows} x {cols} {} array holds",
                            name
                        ),
                    ));
                };
                read += 1;
                values[i + j * rows] = v;
                match symmetry {
                    Symmetry::General => {}
                    Symmetry::Symmetric => values[j + i * rows] = v,
                    Symmetry::Skew => values[j + i * rows] = -v,
                }
            }
        }
        if read != expected {
            return Err(error(
                file,
                text.lines().count().max(1),
                1,
                format!(
                    "{read} entries, but a {rows} x {cols} {} array holds {expected}",
                    name
                ),
            ));
        }
        Ok(values)
    }

    /// The entries of a `coordinate` file, `nnz` of them announced.
    fn coordinate(
        &self,
        lines: &mut Lines<'_>,
        nnz: usize,
        pattern: bool,
    ) -> Result<Vec<(usize, usize, f64)>, PlcpError> {
        let Body {
            file,
            text,
            rows,
            cols,
            symmetry,
            name,
        } = *self;
        let mut triplets = Vec::with_capacity(match symmetry {
            Symmetry::General => nnz,
            _ => 2 * nnz,
        });
        let mut read = 0;
        while let Some((line, text)) = lines.next_data() {
            let mut f = fields(text);
            let mut index = |name: &str, bound: usize| -> Result<usize, PlcpError> {
                let Some((column, s)) = f.next() else {
                    return Err(error(
                        file,
                        line,
                        text.len() + 1,
                        format!("missing {name} index"),
                    ));
                };
                match s.parse::<usize>() {
                    Ok(k) if (1..=bound).contains(&k) => Ok(k - 1),
                    _ => Err(error(
                        file,
                        line,
                        column,
                        format!("{name} index {s}: expected 1..={bound} (1-based)"),
                    )),
                }
            };
            let i = index("row", rows)?;
            let j = index("column", cols)?;
            let v = if pattern {
                1.0
            } else {
                let Some((column, s)) = f.next() else {
                    return Err(error(file, line, text.len() + 1, "missing value"));
                };
                value(file, line, column, s)?
            };
            if let Some((column, s)) = f.next() {
                return Err(error(
                    file,
                    line,
                    column,
                    format!("unexpected \"{s}\" after the entry (a complex file is not read)"),
                ));
            }
            if read == nnz {
                return Err(error(
                    file,
                    line,
                    1,
                    format!("more entries than the {nnz} the size line announces"),
                ));
            }
            read += 1;
            match symmetry {
                Symmetry::General => triplets.push((i, j, v)),
                Symmetry::Symmetric | Symmetry::Skew => {
                    if i < j || (symmetry == Symmetry::Skew && i == j) {
                        return Err(error(
                            file,
                            line,
                            1,
                            format!(
                                "entry ({}, {}) of a {} file must lie below the diagonal{}",
                                i + 1,
                                j + 1,
                                name,
                                if symmetry == Symmetry::Symmetric {
                                    " or on it"
                                } else {
                                    ""
                                }
                            ),
                        ));
                    }
                    triplets.push((i, j, v));
                    if i != j {
                        let mirrored = if symmetry == Symmetry::Skew { -v } else { v };
                        triplets.push((j, i, mirrored));
                    }
                }
            }
        }
        if read != nnz {
            return Err(error(
                file,
                text.lines().count().max(1),
                1,
                format!("{read} entries, but the size line announces {nnz}"),
            ));
        }
        Ok(triplets)
    }
}

/// Reads a Matrix Market file ([`parse_mtx`]).
pub fn read_mtx(path: &std::path::Path) -> Result<Mtx, PlcpError> {
    let bytes = super::read_bytes(path)?;
    parse_mtx(&bytes, &path.display().to_string())
}

/// Writes a dense matrix (column-major `values`, `rows x cols`) as a Matrix
/// Market `array real general` file, every number in the shortest form that
/// reads back to the same `f64`.
pub fn write_mtx_dense(
    out: &mut impl std::io::Write,
    rows: usize,
    cols: usize,
    values: &[f64],
) -> std::io::Result<()> {
    use std::io::Write;
    let mut out = std::io::BufWriter::new(out);
    writeln!(out, "%%MatrixMarket matrix array real general")?;
    writeln!(out, "{rows} {cols}")?;
    for v in values.iter().take(rows * cols) {
        writeln!(out, "{v:?}")?;
    }
    out.flush()
}

/// Resolves a matrix file named inside a problem file: relative to the
/// directory of the problem file `file` (as named in messages).
#[cfg(feature = "json")]
pub(crate) fn beside(file: &str, name: &str) -> std::path::PathBuf {
    let named = std::path::Path::new(name);
    match std::path::Path::new(file).parent() {
        Some(dir) if named.is_relative() => dir.join(named),
        _ => named.to_path_buf(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        parse_mtx(text.as_bytes(), "m.mtx").unwrap_err().to_string()
    }

    #[test]
    fn coordinate_symmetric_fills_both_triangles() {
        let t = "%%MatrixMarket matrix coordinate real symmetric\n% c\n\n3 3 3\n1 1 4\n2 1 -1.5\n3 3 2e0\n";
        let m = parse_mtx(t.as_bytes(), "m.mtx").unwrap();
        assert_eq!((m.rows, m.cols), (3, 3));
        assert_eq!(
            m.data,
            MtxData::Triplets(vec![(0, 0, 4.0), (1, 0, -1.5), (0, 1, -1.5), (2, 2, 2.0)])
        );
    }

    #[test]
    fn skew_and_pattern() {
        let t = "%%MatrixMarket matrix coordinate pattern skew-symmetric\n2 2 1\n2 1\n";
        let m = parse_mtx(t.as_bytes(), "m.mtx").unwrap();
        assert_eq!(m.data, MtxData::Triplets(vec![(1, 0, 1.0), (0, 1, -1.0)]));
        let t = "%%MatrixMarket matrix array real skew-symmetric\n2 2\n3\n";
        let m = parse_mtx(t.as_bytes(), "m.mtx").unwrap();
        assert_eq!(m.data, MtxData::Dense(vec![0.0, 3.0, -3.0, 0.0]));
    }

    #[test]
    fn dense_round_trip_is_exact() {
        let values: Vec<f64> = (0..12).map(|k| (k as f64 * 0.7).sin() / 3.0).collect();
        let mut text = Vec::new();
        write_mtx_dense(&mut text, 3, 4, &values).unwrap();
        let m = parse_mtx(&text, "m.mtx").unwrap();
        assert_eq!((m.rows, m.cols), (3, 4));
        assert_eq!(m.data, MtxData::Dense(values));
    }

    #[test]
    fn errors_name_line_and_column() {
        assert!(err("hello\n").contains("m.mtx:1:1: not a Matrix Market file"));
        let e = err("%%MatrixMarket matrix coordinate complex general\n1 1 1\n1 1 1 0\n");
        assert!(e.contains("m.mtx:1:34") && e.contains("complex"), "{e}");
        let e = err("%%MatrixMarket matrix array real general\n2 2\n1\n2\nx\n4\n");
        assert!(
            e.contains("m.mtx:5:1") && e.contains("\"x\" is not a number"),
            "{e}"
        );
        let e = err("%%MatrixMarket matrix array real general\n2 2\n1 2 3\n");
        assert!(e.contains("3 entries") && e.contains("holds 4"), "{e}");
        let e = err("%%MatrixMarket matrix array real general\n1 1\n1 2\n");
        assert!(e.contains("m.mtx:3:3") && e.contains("more entries"), "{e}");
        let e = err("%%MatrixMarket matrix coordinate real general\n2 2 1\n1 1 1\n2 2 2\n");
        assert!(
            e.contains("m.mtx:4:1") && e.contains("more entries than the 1"),
            "{e}"
        );
        let e = err("%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 2 1\n");
        assert!(e.contains("below the diagonal"), "{e}");
        let e = err("%%MatrixMarket matrix coordinate real general\n2 2 1\n0 1 1\n");
        assert!(e.contains("m.mtx:3:1") && e.contains("row index 0"), "{e}");
        let e = err("%%MatrixMarket matrix array real symmetric\n2 3\n");
        assert!(e.contains("must be square"), "{e}");
        let e = err("%%MatrixMarket matrix array real general\n");
        assert!(e.contains("no size line"), "{e}");
        let e = parse_mtx(
            b"%%MatrixMarket matrix array real general\n1 1\n\xff\n",
            "m.mtx",
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("invalid UTF-8"), "{e}");
    }
}
