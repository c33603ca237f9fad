//! NumPy `.npy` files: the binary format a numerical user hands over with
//! one line (`numpy.save("m.npy", M)`). plcp reads `M` from one when the
//! problem file names it (`"M": "m.npy"`, `"M_sparse": "m.npy"`): the numbers
//! are copied, not parsed, so a dense `M` of order 2000 (32 MB) is read in
//! the time of a memory copy, against about 0.5 s for the same `M` as JSON
//! or Matrix Market text.
//!
//! The format (version 1.0, 2.0 or 3.0): the magic `\x93NUMPY`, the version,
//! the header's length, and a header that is a Python dict literal such as
//! `{'descr': '<f8', 'fortran_order': False, 'shape': (3, 3), }`, then the
//! raw data. Read here: two-dimensional arrays of `f8`, `f4`, `i8` or `i4`,
//! either byte order, in C (row-major) or Fortran order. Anything else
//! (object arrays, complex numbers, more dimensions, a short file) is an
//! error that says what was found.

use super::mtx::{Mtx, MtxData};
use crate::error::PlcpError;

fn bad(file: &str, why: impl Into<String>) -> PlcpError {
    PlcpError::Invalid {
        what: format!("{file} (.npy)"),
        why: why.into(),
    }
}

/// The value of `key` in the header dict: the text after `'key':` up to the
/// next top-level comma (a tuple's commas are inside parentheses).
fn header_value<'a>(header: &'a str, key: &str) -> Option<&'a str> {
    let quoted = [format!("'{key}'"), format!("\"{key}\"")];
    let at = quoted
        .iter()
        .find_map(|q| header.find(q.as_str()).map(|i| i + q.len()))?;
    let rest = header[at..].trim_start().strip_prefix(':')?.trim_start();
    let mut depth = 0usize;
    let end = rest
        .char_indices()
        .find(|&(_, c)| match c {
            '(' => {
                depth += 1;
                false
            }
            ')' => {
                depth = depth.saturating_sub(1);
                false
            }
            ',' | '}' => depth == 0,
            _ => false,
        })
        .map_or(rest.len(), |(i, _)| i);
    Some(rest[..end].trim())
}

/// Parses a `.npy` file's bytes holding a matrix; `file` names it in errors.
///
/// ```
/// // numpy.save of numpy.array([[2.0, 1.0], [1.0, 2.0]])
/// let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
/// let header = "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 2), }";
/// let padded = format!("{header:<117}\n");
/// bytes.extend_from_slice(&(padded.len() as u16).to_le_bytes());
/// bytes.extend_from_slice(padded.as_bytes());
/// for v in [2.0f64, 1.0, 1.0, 2.0] {
///     bytes.extend_from_slice(&v.to_le_bytes());
/// }
/// let m = plcp::io::npy::parse_npy(&bytes, "m.npy").unwrap();
/// assert_eq!((m.rows, m.cols), (2, 2));
/// assert_eq!(m.data, plcp::io::mtx::MtxData::Dense(vec![2.0, 1.0, 1.0, 2.0]));
/// ```
pub fn parse_npy(bytes: &[u8], file: &str) -> Result<Mtx, PlcpError> {
    let rest = bytes
        .strip_prefix(b"\x93NUMPY")
        .ok_or_else(|| bad(file, "not a .npy file (no \\x93NUMPY magic)"))?;
    let (major, rest) = match rest {
        [major, _minor, rest @ ..] => (*major, rest),
        _ => return Err(bad(file, "the file ends inside its preamble")),
    };
    let (header_len, rest) = match (major, rest) {
        (1, [a, b, rest @ ..]) => (u16::from_le_bytes([*a, *b]) as usize, rest),
        (2 | 3, [a, b, c, d, rest @ ..]) => (u32::from_le_bytes([*a, *b, *c, *d]) as usize, rest),
        (1..=3, _) => return Err(bad(file, "the file ends inside its preamble")),
        (v, _) => {
            return Err(bad(
                file,
                format!("format version {v}: versions 1 to 3 are read"),
            ))
        }
    };
    if rest.len() < header_len {
        return Err(bad(file, "the file ends inside its header"));
    }
    let header = std::str::from_utf8(&rest[..header_len])
        .map_err(|_| bad(file, "the header is not text"))?;
    let data = &rest[header_len..];
    let descr = header_value(header, "descr")
        .map(|v| v.trim_matches(|c| c == '\'' || c == '"'))
        .ok_or_else(|| bad(file, format!("no 'descr' in the header {header:?}")))?;
    let fortran = match header_value(header, "fortran_order") {
        Some("True") => true,
        Some("False") => false,
        other => {
            return Err(bad(
                file,
                format!("'fortran_order' must be True or False, got {other:?}"),
            ))
        }
    };
    let shape_text = header_value(header, "shape")
        .ok_or_else(|| bad(file, format!("no 'shape' in the header {header:?}")))?;
    let shape: Vec<usize> = shape_text
        .trim_start_matches('(')
        .trim_end_matches(')')
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse::<usize>())
        .collect::<Result<_, _>>()
        .map_err(|_| bad(file, format!("shape {shape_text} is not a tuple of sizes")))?;
    let [rows, cols] = shape[..] else {
        return Err(bad(
            file,
            format!("shape {shape_text}: a matrix (two dimensions) is expected"),
        ));
    };
    let (little, kind) = {
        let b = descr.as_bytes();
        let little = match b.first() {
            Some(b'<') | Some(b'|') | Some(b'=') => true,
            Some(b'>') => false,
            _ => return Err(bad(file, format!("dtype '{descr}' is not read"))),
        };
        (little, &descr[1..])
    };
    let size = match kind {
        "f8" | "i8" => 8,
        "f4" | "i4" => 4,
        _ => {
            return Err(bad(
                file,
                format!("dtype '{descr}': plcp reads f8, f4, i8 and i4 (save M as float64)"),
            ))
        }
    };
    let count = rows
        .checked_mul(cols)
        .ok_or_else(|| bad(file, format!("shape {shape_text} overflows")))?;
    let need = count
        .checked_mul(size)
        .ok_or_else(|| bad(file, format!("shape {shape_text} overflows")))?;
    if data.len() != need {
        return Err(bad(
            file,
            format!(
                "{} bytes of data, but a {rows} x {cols} array of '{descr}' holds {need}",
                data.len()
            ),
        ));
    }
    let value = |chunk: &[u8]| -> f64 {
        macro_rules! read {
            ($t:ty, $n:literal) => {{
                let mut a = [0u8; $n];
                a.copy_from_slice(chunk);
                if little {
                    <$t>::from_le_bytes(a)
                } else {
                    <$t>::from_be_bytes(a)
                }
            }};
        }
        match kind {
            "f8" => read!(f64, 8),
            "f4" => read!(f32, 4) as f64,
            "i8" => read!(i64, 8) as f64,
            _ => read!(i32, 4) as f64,
        }
    };
    let file_order: Vec<f64> = data.chunks_exact(size).map(value).collect();
    // MtxData::Dense is column-major, as a Fortran-order file
    let values = if fortran {
        file_order
    } else {
        let mut v = vec![0.0; count];
        for i in 0..rows {
            for j in 0..cols {
                v[i + j * rows] = file_order[i * cols + j];
            }
        }
        v
    };
    Ok(Mtx {
        rows,
        cols,
        data: MtxData::Dense(values),
    })
}

/// Reads a `.npy` file ([`parse_npy`]).
pub fn read_npy(path: &std::path::Path) -> Result<Mtx, PlcpError> {
    let bytes = super::read_bytes(path)?;
    parse_npy(&bytes, &path.display().to_string())
}

/// Reads the matrix file a problem file names: `.npy` by its magic bytes,
/// else Matrix Market ([`super::mtx`]).
#[cfg(feature = "json")]
pub(crate) fn read_matrix_file(path: &std::path::Path) -> Result<Mtx, PlcpError> {
    let bytes = super::read_bytes(path)?;
    let file = path.display().to_string();
    if bytes.starts_with(b"\x93NUMPY") {
        parse_npy(&bytes, &file)
    } else {
        super::mtx::parse_mtx(&bytes, &file)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn npy(descr: &str, fortran: bool, shape: &str, data: &[u8]) -> Vec<u8> {
        let header = format!(
            "{{'descr': '{descr}', 'fortran_order': {}, 'shape': {shape}, }}",
            if fortran { "True" } else { "False" }
        );
        let mut out = b"\x93NUMPY\x01\x00".to_vec();
        let padded = format!("{header:<117}\n");
        out.extend_from_slice(&(padded.len() as u16).to_le_bytes());
        out.extend_from_slice(padded.as_bytes());
        out.extend_from_slice(data);
        out
    }

    #[test]
    fn orders_and_types() {
        // [[1, 2, 3], [4, 5, 6]] in C order as f8, Fortran order as big-endian f4
        let c: Vec<u8> = [1.0f64, 2.0, 3.0, 4.0, 5.0, 6.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let f: Vec<u8> = [1.0f32, 4.0, 2.0, 5.0, 3.0, 6.0]
            .iter()
            .flat_map(|v| v.to_be_bytes())
            .collect();
        let i: Vec<u8> = [1i32, 2, 3, 4, 5, 6]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let want = MtxData::Dense(vec![1.0, 4.0, 2.0, 5.0, 3.0, 6.0]);
        for bytes in [
            npy("<f8", false, "(2, 3)", &c),
            npy(">f4", true, "(2, 3)", &f),
            npy("<i4", false, "(2, 3)", &i),
        ] {
            let m = parse_npy(&bytes, "m.npy").unwrap();
            assert_eq!((m.rows, m.cols), (2, 3));
            assert_eq!(m.data, want);
        }
    }

    #[test]
    fn bad_files_say_what_they_are() {
        let e = |b: &[u8]| parse_npy(b, "m.npy").unwrap_err().to_string();
        assert!(e(b"hello").contains("no \\x93NUMPY magic"));
        assert!(e(&npy("<c16", false, "(1, 1)", &[0; 16])).contains("dtype '<c16'"));
        assert!(e(&npy("<f8", false, "(2,)", &[0; 16])).contains("two dimensions"));
        assert!(e(&npy("<f8", false, "(2, 2)", &[0; 24])).contains("24 bytes of data"));
        assert!(e(&npy("|O", false, "(1, 1)", &[0; 8])).contains("dtype '|O'"));
        let mut short = npy("<f8", false, "(1, 1)", &[0; 8]);
        short.truncate(20);
        assert!(e(&short).contains("ends inside its header"));
    }
}
