//! The Siconos `.dat` format of an LCP `w = M z + q`: dense (storage 0) and
//! sparse-block (storage 1).
//!
//! The file is whitespace-separated text:
//!
//! ```text
//! n                         problem size
//! storage                   0 = dense, 1 = sparse block
//! rows
//! cols
//! -- dense (storage 0):
//! rows cols                 the two sizes once more
//! rows*cols values          COLUMN-MAJOR (each printed line is one column of M)
//! -- sparse block (storage 1):
//! nbblocks                  number of stored blocks
//! blocknumber0 blocknumber1 number of block rows, of block columns
//! row-block ends            blocknumber0 cumulative end indices
//! col-block ends            blocknumber1 cumulative end indices
//! filled1 filled2           blocknumber0 + 1, nbblocks
//! row-block pointer         filled1 values (CSR-like over block rows)
//! block column indices      filled2 values, one per stored block
//! each stored block:        its number k (0-based), then its values column-major
//! -- then for both:
//! q                         n values
//! [free text]               an optional trailing comment, ignored
//! ```
//!
//! The whole file must be UTF-8, the trailing comment included
//! ([`parse_lcp_bytes`], [`read_lcp`]).
//!
//! Errors name the file, the 1-based line and column of the offending token
//! (or the end of the file), and what was expected there.
//!
//! ```
//! let text = "2\n0\n2\n2\n2\t2\n2 1\n1 2\n-5 -6\n\nsome comment\n";
//! let lcp = plcp::io::siconos::parse_lcp::<f64>(text, "deudeu.dat").unwrap();
//! assert_eq!(lcp.m()[(0, 1)], 1.0);
//! assert_eq!(lcp.q()[1], -6.0);
//! ```

use super::{check_order, convert, read_bytes, utf8_in};
use crate::error::PlcpError;
use crate::problem::Lcp;
use crate::scalar::Scalar;
use faer::{Col, ColRef, Mat};

struct Token<'a> {
    text: &'a str,
    line: usize,
    column: usize,
}

/// A cursor over the whitespace-separated tokens of a file, with positions.
struct Reader<'a> {
    file: &'a str,
    tokens: Vec<Token<'a>>,
    next: usize,
    /// Position just past the last character (for "unexpected end of file").
    eof: (usize, usize),
}

impl<'a> Reader<'a> {
    fn new(text: &'a str, file: &'a str) -> Self {
        let mut tokens = Vec::new();
        let mut eof = (1, 1);
        for (li, raw) in text.split('\n').enumerate() {
            let line = li + 1;
            let mut start: Option<(usize, usize)> = None; // (byte, column)
            let mut col = 0;
            for (b, ch) in raw.char_indices() {
                col += 1;
                if ch.is_whitespace() {
                    if let Some((s, c)) = start.take() {
                        tokens.push(Token {
                            text: &raw[s..b],
                            line,
                            column: c,
                        });
                    }
                } else if start.is_none() {
                    start = Some((b, col));
                }
            }
            if let Some((s, c)) = start {
                tokens.push(Token {
                    text: &raw[s..],
                    line,
                    column: c,
                });
            }
            eof = (line, raw.trim_end_matches('\r').chars().count() + 1);
        }
        Self {
            file,
            tokens,
            next: 0,
            eof,
        }
    }

    fn error_at(&self, line: usize, column: usize, message: String) -> PlcpError {
        PlcpError::Parse {
            file: self.file.to_string(),
            line,
            column,
            message,
        }
    }

    fn remaining(&self) -> usize {
        self.tokens.len() - self.next
    }

    fn token(&mut self, what: &dyn Fn() -> String) -> Result<&Token<'a>, PlcpError> {
        if self.next >= self.tokens.len() {
            let (l, c) = self.eof;
            return Err(self.error_at(
                l,
                c,
                format!("unexpected end of file: expected {}", what()),
            ));
        }
        self.next += 1;
        Ok(&self.tokens[self.next - 1])
    }

    /// A non-negative integer; returns it with its position.
    fn int(&mut self, what: &dyn Fn() -> String) -> Result<(usize, usize, usize), PlcpError> {
        let file = self.file;
        let t = self.token(what)?;
        match t.text.parse::<usize>() {
            Ok(v) => Ok((v, t.line, t.column)),
            Err(_) => Err(PlcpError::Parse {
                file: file.to_string(),
                line: t.line,
                column: t.column,
                message: format!(
                    "expected {} (a non-negative integer), found '{}'",
                    what(),
                    t.text
                ),
            }),
        }
    }

    /// A finite real number.
    fn real(&mut self, what: &dyn Fn() -> String) -> Result<f64, PlcpError> {
        let file = self.file;
        let t = self.token(what)?;
        let err = |message: String| PlcpError::Parse {
            file: file.to_string(),
            line: t.line,
            column: t.column,
            message,
        };
        match t.text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(err(format!(
                "non-finite value '{}' for {}: only finite numbers are allowed",
                t.text,
                what()
            ))),
            Err(_) => Err(err(format!(
                "expected a number for {}, found '{}'",
                what(),
                t.text
            ))),
        }
    }
}

/// Parses the text of a Siconos `.dat` file (see the [module docs](self));
/// `file` is the name used in error messages.
pub fn parse_lcp<T: Scalar>(text: &str, file: &str) -> Result<Lcp<T>, PlcpError> {
    let mut r = Reader::new(text, file);
    let (n, nl, nc) = r.int(&|| "the problem size n".into())?;
    if n == 0 {
        return Err(r.error_at(nl, nc, "problem size n = 0: an empty problem".into()));
    }
    if let Err(m) = check_order("problem size n", n) {
        return Err(r.error_at(nl, nc, m));
    }
    let (storage, sl, sc) = r.int(&|| "the storage type (0 = dense, 1 = sparse block)".into())?;
    let (rows, rl, rc) = r.int(&|| "the number of rows of M".into())?;
    if rows != n {
        return Err(r.error_at(rl, rc, format!("M has {rows} rows, expected n = {n}")));
    }
    let (cols, cl, cc) = r.int(&|| "the number of columns of M".into())?;
    if cols != n {
        return Err(r.error_at(
            cl,
            cc,
            format!("M has {cols} columns, expected n = {n} (M must be square)"),
        ));
    }
    let mut m = vec![0.0f64; 0];
    match storage {
        0 => {
            let (rows2, l, c) = r.int(&|| "the number of rows of M (repeated)".into())?;
            if rows2 != rows {
                return Err(r.error_at(
                    l,
                    c,
                    format!("the repeated number of rows {rows2} differs from {rows}"),
                ));
            }
            let (cols2, l, c) = r.int(&|| "the number of columns of M (repeated)".into())?;
            if cols2 != cols {
                return Err(r.error_at(
                    l,
                    c,
                    format!("the repeated number of columns {cols2} differs from {cols}"),
                ));
            }
            // Column-major; grow as values arrive, so a truncated file fails before
            // any large allocation.
            m.reserve(r.remaining().min(n * n));
            for j in 0..n {
                for i in 0..n {
                    m.push(r.real(&|| format!("M({i}, {j}) (column-major, column {j} of {n})"))?);
                }
            }
        }
        1 => m = read_sparse_block(&mut r, n)?,
        other => {
            return Err(r.error_at(
                sl,
                sc,
                format!("unknown storage type {other}: expected 0 (dense) or 1 (sparse block)"),
            ))
        }
    }
    let mut q = Vec::with_capacity(n);
    for i in 0..n {
        q.push(r.real(&|| format!("q[{i}] (entry {} of {n} of q)", i + 1))?);
    }
    // Whatever follows q is a free-text comment.
    build(&m, &q, n)
}

/// Reads the sparse-block part of the file; returns `M` column-major.
fn read_sparse_block(r: &mut Reader<'_>, n: usize) -> Result<Vec<f64>, PlcpError> {
    let (nbblocks, _, _) = r.int(&|| "nbblocks (the number of stored blocks)".into())?;
    let (bn0, l0, c0) = r.int(&|| "blocknumber0 (the number of block rows)".into())?;
    let (bn1, l1, c1) = r.int(&|| "blocknumber1 (the number of block columns)".into())?;
    if bn0 == 0 || bn0 > n {
        return Err(r.error_at(
            l0,
            c0,
            format!("blocknumber0 = {bn0} block rows: expected 1 to n = {n}"),
        ));
    }
    if bn1 == 0 || bn1 > n {
        return Err(r.error_at(
            l1,
            c1,
            format!("blocknumber1 = {bn1} block columns: expected 1 to n = {n}"),
        ));
    }
    let row_end = read_block_ends(r, bn0, n, "row")?;
    let col_end = read_block_ends(r, bn1, n, "column")?;
    let (filled1, l, c) = r.int(&|| "filled1 (the length of the row-block pointer)".into())?;
    if filled1 != bn0 + 1 {
        return Err(r.error_at(
            l,
            c,
            format!(
                "filled1 = {filled1}, expected blocknumber0 + 1 = {}",
                bn0 + 1
            ),
        ));
    }
    let (filled2, l, c) = r.int(&|| "filled2 (the number of stored blocks)".into())?;
    if filled2 != nbblocks {
        return Err(r.error_at(
            l,
            c,
            format!("filled2 = {filled2} stored blocks, but nbblocks = {nbblocks}"),
        ));
    }
    if filled2 > bn0 * bn1 {
        return Err(r.error_at(
            l,
            c,
            format!("{filled2} stored blocks, more than the {bn0} x {bn1} block positions"),
        ));
    }
    let mut row_ptr = Vec::with_capacity(filled1);
    for k in 0..filled1 {
        let (p, l, c) = r.int(&|| format!("row-block pointer entry {k}"))?;
        let prev = row_ptr.last().copied().unwrap_or(0);
        if (k == 0 && p != 0) || p < prev || p > filled2 || (k + 1 == filled1 && p != filled2) {
            return Err(r.error_at(
                l,
                c,
                format!(
                    "row-block pointer entry {k} = {p}: the pointer must start at 0, not decrease, and end at filled2 = {filled2}"
                ),
            ));
        }
        row_ptr.push(p);
    }
    let mut col_idx = Vec::with_capacity(filled2);
    let mut col_pos = Vec::with_capacity(filled2);
    for k in 0..filled2 {
        let (j, l, c) = r.int(&|| format!("the block column index of stored block {k}"))?;
        if j >= bn1 {
            return Err(r.error_at(
                l,
                c,
                format!(
                    "block column index {j} of stored block {k}: expected 0 to {}",
                    bn1 - 1
                ),
            ));
        }
        col_idx.push(j);
        col_pos.push((l, c));
    }
    // Block row of each stored block; reject two blocks at one position.
    let mut block_row = vec![0; filled2];
    for bi in 0..bn0 {
        for k in row_ptr[bi]..row_ptr[bi + 1] {
            block_row[k] = bi;
            if col_idx[row_ptr[bi]..k].contains(&col_idx[k]) {
                let (l, c) = col_pos[k];
                return Err(r.error_at(
                    l,
                    c,
                    format!(
                        "two stored blocks at block position ({bi}, {}) (block {k} repeats it)",
                        col_idx[k]
                    ),
                ));
            }
        }
    }
    let start = |ends: &[usize], b: usize| if b == 0 { 0 } else { ends[b - 1] };
    let mut m = vec![0.0f64; n * n];
    let mut seen = vec![false; filled2];
    for _ in 0..filled2 {
        let (k, l, c) = r.int(&|| "the number of the next stored block".into())?;
        if k >= filled2 || seen[k] {
            return Err(r.error_at(
                l,
                c,
                if k >= filled2 {
                    format!("block number {k}: expected 0 to {}", filled2 - 1)
                } else {
                    format!("block number {k} appears twice")
                },
            ));
        }
        seen[k] = true;
        let (bi, bj) = (block_row[k], col_idx[k]);
        let (r0, r1) = (start(&row_end, bi), row_end[bi]);
        let (c0, c1) = (start(&col_end, bj), col_end[bj]);
        for j in c0..c1 {
            for i in r0..r1 {
                m[i + j * n] = r.real(&|| {
                    format!("M({i}, {j}) (stored block {k} at block position ({bi}, {bj}), column-major)")
                })?;
            }
        }
    }
    Ok(m)
}

/// Reads the `count` end indices of the row or column blocks (`kind`), which
/// must increase strictly from above 0 and end at `n`.
fn read_block_ends(
    r: &mut Reader<'_>,
    count: usize,
    n: usize,
    kind: &str,
) -> Result<Vec<usize>, PlcpError> {
    let mut v = Vec::with_capacity(count);
    let mut prev = 0;
    for k in 0..count {
        let (e, l, c) = r.int(&|| format!("the end index of {kind} block {k}"))?;
        if e <= prev || e > n {
            return Err(r.error_at(
                l,
                c,
                format!(
                    "end index {e} of {kind} block {k}: the ends must increase strictly, from above 0 up to n = {n}"
                ),
            ));
        }
        if k + 1 == count && e != n {
            return Err(r.error_at(
                l,
                c,
                format!("the last {kind} block ends at {e}, expected n = {n}"),
            ));
        }
        prev = e;
        v.push(e);
    }
    Ok(v)
}

fn build<T: Scalar>(m: &[f64], q: &[f64], n: usize) -> Result<Lcp<T>, PlcpError> {
    let mut mt = Mat::<T>::zeros(n, n);
    for j in 0..n {
        for i in 0..n {
            mt[(i, j)] = convert("M", &format!("({i}, {j})"), m[i + j * n])?;
        }
    }
    let mut qt = Col::<T>::zeros(n);
    for i in 0..n {
        qt[i] = convert("q", &format!("[{i}]"), q[i])?;
    }
    Lcp::new(mt.as_ref(), qt.as_ref())
}

/// Parses the bytes of a Siconos `.dat` file: [`parse_lcp`] after checking
/// that they are UTF-8 throughout, the trailing comment included (an error
/// names the byte offset, line and column of the first bad byte).
pub fn parse_lcp_bytes<T: Scalar>(bytes: &[u8], file: &str) -> Result<Lcp<T>, PlcpError> {
    parse_lcp(utf8_in(bytes, file)?, file)
}

/// Reads a Siconos `.dat` file (see the [module docs](self) and [`parse_lcp_bytes`]).
pub fn read_lcp<T: Scalar>(path: &std::path::Path) -> Result<Lcp<T>, PlcpError> {
    let bytes = read_bytes(path)?;
    parse_lcp_bytes(&bytes, &path.display().to_string())
}

/// The Siconos error measure `||z - max(0, z - w)||_2 / ||q||_2` (unnormalised
/// when `q = 0`), computed in `T` and returned as `f64`.
pub fn siconos_error<T: Scalar>(q: ColRef<'_, T>, z: ColRef<'_, T>, w: ColRef<'_, T>) -> f64 {
    let mut e = T::zero();
    let mut qq = T::zero();
    for i in 0..z.nrows() {
        let r = z[i] - (z[i] - w[i]).max(T::zero());
        e += r * r;
    }
    for i in 0..q.nrows() {
        qq += q[i] * q[i];
    }
    let e = e.sqrt();
    let qn = qq.sqrt();
    if qn > T::zero() {
        (e / qn).to_f64()
    } else {
        e.to_f64()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        parse_lcp::<f64>(text, "t.dat").unwrap_err().to_string()
    }

    #[test]
    fn dense_is_column_major() {
        let lcp = parse_lcp::<f64>("2 0 2 2 2 2\n1 3\n2 4\n-1 -1 trailing words 1 2", "t").unwrap();
        assert_eq!(lcp.m()[(0, 0)], 1.0);
        assert_eq!(lcp.m()[(1, 0)], 3.0);
        assert_eq!(lcp.m()[(0, 1)], 2.0);
        assert_eq!(lcp.m()[(1, 1)], 4.0);
    }

    #[test]
    fn sparse_block_matches_dense() {
        // ortiz-like: 2 x 2 blocks, all four stored, given out of order.
        let dense = "4 0 4 4 4 4\n3 -1 0 0\n1 2 1 0\n0 1 3 1\n-1 1 -1 2\n-2 1 -1 1\n";
        let block = "4 1 4 4 4 2 2 2 4 2 4 3 4 0 2 4 0 1 0 1\n\
                     1 0 1 -1 1\n0 3 -1 1 2\n3 3 1 -1 2\n2 0 0 1 0\n-2 1 -1 1\n";
        let a = parse_lcp::<f64>(dense, "d").unwrap();
        let b = parse_lcp::<f64>(block, "b").unwrap();
        for i in 0..4 {
            for j in 0..4 {
                assert_eq!(a.m()[(i, j)], b.m()[(i, j)], "({i}, {j})");
            }
            assert_eq!(a.q()[i], b.q()[i]);
        }
    }

    #[test]
    fn errors_name_line_and_column() {
        let e = err("2\n0\n2\n2\n2 2\n1 x\n");
        assert!(e.starts_with("t.dat:6:3:"), "{e}");
        assert!(e.contains("'x'") && e.contains("M(1, 0)"), "{e}");
        let e = err("2\n0\n2\n2\n2 2\n1 1\n1 1\n-1\n");
        assert!(
            e.contains("unexpected end of file") && e.contains("q[1]"),
            "{e}"
        );
        let e = err("2\n0\n2\n3\n");
        assert!(e.starts_with("t.dat:4:1:") && e.contains("square"), "{e}");
        let e = err("2\n5\n2\n2\n");
        assert!(e.contains("storage"), "{e}");
        let e = err("2 0 2 2 2 2 1 nan 1 1 0 0");
        assert!(e.contains("non-finite") && e.contains("'nan'"), "{e}");
        let e = err("");
        assert!(
            e.starts_with("t.dat:1:1:") && e.contains("end of file"),
            "{e}"
        );
        let e = err("99999999 0 1 1");
        assert!(e.contains("too large"), "{e}");
    }

    /// The trailing comment used to be decoded leniently: a Latin-1 byte there
    /// (or in a number) must be an error naming its offset, line and column.
    #[test]
    fn invalid_utf8_is_an_error_naming_the_offset() {
        let good = "2 0 2 2 2 2\n2 1\n1 2\n-5 -6\nété\n";
        assert!(parse_lcp_bytes::<f64>(good.as_bytes(), "t.dat").is_ok());
        for (bytes, want) in [
            (
                &b"2 0 2 2 2 2\n2 1\n1 2\n-5 -6\n\xe9t\xe9\n"[..],
                "t.dat:5:1: invalid UTF-8 at byte offset 26:",
            ),
            (
                &b"2 0 2 2 2 2\n2 1\n1 2\n-5 -6\n\xc3\xa9t\xe9\n"[..],
                "t.dat:5:3: invalid UTF-8 at byte offset 29:",
            ),
            (
                &b"2 0 2 2 2 2\n2 \xff1\n1 2\n-5 -6\n"[..],
                "t.dat:2:3: invalid UTF-8 at byte offset 14:",
            ),
        ] {
            let e = parse_lcp_bytes::<f64>(bytes, "t.dat")
                .unwrap_err()
                .to_string();
            assert!(e.starts_with(want), "{e} (want {want})");
            assert!(e.contains("0xE9") || e.contains("0xFF"), "{e}");
        }
    }

    #[test]
    fn f32_overflow_is_named() {
        let e = parse_lcp::<f32>("1 0 1 1 1 1 1e300 -1", "t")
            .unwrap_err()
            .to_string();
        assert!(e.contains("M entry (0, 0)") && e.contains("f32"), "{e}");
    }

    #[test]
    fn siconos_error_measure() {
        let q = faer::col![3.0, 4.0];
        let z = faer::col![1.0, 0.0];
        let w = faer::col![0.0, 2.0];
        assert_eq!(siconos_error(q.as_ref(), z.as_ref(), w.as_ref()), 0.0);
        let w = faer::col![0.5, 2.0]; // z0 w0 > 0: r0 = 1 - 0.5
        assert_eq!(siconos_error(q.as_ref(), z.as_ref(), w.as_ref()), 0.5 / 5.0);
    }
}
