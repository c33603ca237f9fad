//! A sparse JSON input for large problems: `M` as triplets or in compressed
//! sparse columns, read in memory linear in `nnz(M) + n`.
//!
//! ```json
//! {"M_sparse": {"order": 3, "triplets": [[0, 0, 4], [0, 1, -1], [1, 0, -1], [1, 1, 4], [2, 2, 4]]},
//!  "q": [-1, -1, -1], "d": [0.1, 0.1, 0.1], "lambda_max": 2, "free": 0, "warm_basis": "z"}
//! ```
//!
//! * `M_sparse`: an object, or the name of a Matrix Market (`"m.mtx"`,
//!   [`super::mtx`], coordinate or array) or NumPy (`"m.npy"`, [`super::npy`])
//!   file, relative to the problem file's directory (explicit zeros dropped);
//! * `M_sparse.order`: the order `p + n` of `M`;
//! * `M_sparse.triplets`: `[row, column, value]` entries (0-based; a repeated
//!   position is summed, explicit zeros are dropped), **or**
//!   `M_sparse.csc`: `{"col_ptr": [...], "row_idx": [...], "values": [...]}`
//!   (compressed sparse columns: column `j`'s entries are
//!   `col_ptr[j]..col_ptr[j + 1]`);
//! * `q`, `d`, `lambda_max`, `free`, `lambda0`, `comment`: as in [`super::json`];
//! * `warm_basis` (optional): the start basis, `"z"` (every `z_i`, and every
//!   `u_j`), `"w"` (every `w_i`, and every `u_j`), or a list of names
//!   (`"u0"`, `"z3"`, `"w7"`, one per row); see [`crate::Settings::warm_basis`].
//!
//! Unknown keys, out-of-range indices, non-finite values and a malformed
//! `col_ptr` are errors that name the entry. No dense `M` is ever built, so
//! the limit [`super::MAX_ORDER`] of the dense readers does not apply.
//!
//! ```
//! let text = r#"{"M_sparse": {"order": 2, "triplets": [[0, 0, 2], [1, 1, 2], [0, 1, 1], [1, 0, 1]]},
//!                "q": [1, 1], "d": [-1, -0.5], "warm_basis": "w"}"#;
//! let (p, warm) = plcp::io::sparse_json::parse_sparse::<f64>(text.as_bytes(), "ex.json").unwrap();
//! assert!(p.is_sparse());
//! assert_eq!(warm.unwrap(), vec![plcp::Var::W(0), plcp::Var::W(1)]);
//! ```

use super::{convert, utf8_in};
use crate::error::PlcpError;
use crate::matrix::Csc;
use crate::path::Var;
use crate::problem::Plcp;
use crate::scalar::Scalar;
use faer::Col;
use serde::Deserialize;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCsc {
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    values: Vec<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSparseM {
    order: usize,
    #[serde(default)]
    triplets: Option<Vec<(usize, usize, f64)>>,
    #[serde(default)]
    csc: Option<RawCsc>,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum RawWarm {
    All(String),
    List(Vec<String>),
}

/// `M_sparse` as written: inline, or the name of a Matrix Market file.
enum SparseIn {
    Inline(RawSparseM),
    File(String),
}

impl<'de> Deserialize<'de> for SparseIn {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> serde::de::Visitor<'de> for V {
            type Value = SparseIn;
            fn expecting(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                f.write_str("an object {\"order\", \"triplets\" or \"csc\"}, or the name of a Matrix Market file")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<SparseIn, E> {
                Ok(SparseIn::File(v.to_string()))
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(self, map: A) -> Result<SparseIn, A::Error> {
                RawSparseM::deserialize(serde::de::value::MapAccessDeserializer::new(map))
                    .map(SparseIn::Inline)
            }
        }
        d.deserialize_any(V)
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSparse {
    #[serde(rename = "M_sparse")]
    m: SparseIn,
    q: Vec<f64>,
    d: Vec<f64>,
    #[serde(default)]
    lambda_max: Option<serde_json::Value>,
    #[serde(default)]
    free: usize,
    #[serde(default)]
    lambda0: Option<f64>,
    #[serde(default)]
    warm_basis: Option<RawWarm>,
    #[serde(default, rename = "comment")]
    _comment: Option<serde::de::IgnoredAny>,
}

fn invalid(file: &str, what: impl Into<String>, why: impl Into<String>) -> PlcpError {
    PlcpError::Invalid {
        what: format!("{file}: {}", what.into()),
        why: why.into(),
    }
}

/// True when the JSON text is the sparse format: the top-level object has an
/// `M_sparse` key before any `M` key.
///
/// Only the top-level keys are read, up to the first `M` or `M_sparse`, and
/// the values of the keys before it skipped: the dense `M` after them (which
/// may be 100 MB) is not read, and an `"M_sparse"` inside a `comment` or a
/// string does not count. Anything that is not such an object is `false`
/// (the dense reader then names the problem).
///
/// ```
/// use plcp::io::sparse_json::is_sparse_json;
/// assert!(is_sparse_json(br#"{"comment": "x", "M_sparse": {"n": 1}}"#));
/// // a key of the comment's value is not a top-level key
/// assert!(!is_sparse_json(br#"{"comment": {"M_sparse": 1}, "M": [[1]]}"#));
/// assert!(!is_sparse_json(b"[1, 2"));
/// ```
pub fn is_sparse_json(bytes: &[u8]) -> bool {
    use serde::de::{Deserializer as _, Error as _, IgnoredAny, MapAccess, Visitor};
    use std::cell::Cell;

    /// Reads keys until `M` or `M_sparse` decides, then stops the parse.
    struct Keys<'a>(&'a Cell<Option<bool>>);

    impl<'de> Visitor<'de> for Keys<'_> {
        type Value = ();

        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("a JSON object")
        }

        fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
            while let Some(key) = map.next_key::<String>()? {
                match key.as_str() {
                    "M_sparse" | "M" => {
                        self.0.set(Some(key == "M_sparse"));
                        // decided: an error ends the parse without reading on
                        return Err(A::Error::custom("decided"));
                    }
                    _ => {
                        map.next_value::<IgnoredAny>()?;
                    }
                }
            }
            Ok(())
        }
    }

    let decided = Cell::new(None);
    let _ = serde_json::Deserializer::from_slice(bytes).deserialize_map(Keys(&decided));
    decided.get().unwrap_or(false)
}

/// Parses the sparse format: the problem and the warm basis, if one is given.
pub fn parse_sparse<T: Scalar>(
    bytes: &[u8],
    file: &str,
) -> Result<(Plcp<T>, Option<Vec<Var>>), PlcpError> {
    let text = utf8_in(bytes, file)?;
    let raw: RawSparse = serde_json::from_str(text).map_err(|e| PlcpError::Parse {
        file: file.to_string(),
        line: e.line().max(1),
        column: e.column().max(1),
        message: e.to_string(),
    })?;
    let inline = match raw.m {
        SparseIn::Inline(m) => m,
        SparseIn::File(name) => {
            let mtx = super::npy::read_matrix_file(&super::mtx::beside(file, &name))?;
            if mtx.rows != mtx.cols {
                return Err(invalid(
                    file,
                    "M_sparse",
                    format!(
                        "{name} holds a {} x {} matrix: M must be square",
                        mtx.rows, mtx.cols
                    ),
                ));
            }
            let triplets = match mtx.data {
                super::mtx::MtxData::Triplets(t) => t,
                super::mtx::MtxData::Dense(v) => (0..mtx.cols)
                    .flat_map(|j| (0..mtx.rows).map(move |i| (i, j)))
                    .zip(v)
                    .filter(|&(_, x)| x != 0.0)
                    .map(|((i, j), x)| (i, j, x))
                    .collect(),
            };
            RawSparseM {
                order: mtx.rows,
                triplets: Some(triplets),
                csc: None,
            }
        }
    };
    let dim = inline.order;
    let mut triplets: Vec<(usize, usize, T)> = Vec::new();
    let mut push = |i: usize, j: usize, v: f64, k: usize| -> Result<(), PlcpError> {
        if i >= dim || j >= dim {
            return Err(invalid(
                file,
                format!("M_sparse entry {k}"),
                format!("position ({i}, {j}) outside the order {dim}"),
            ));
        }
        let v = convert::<T>("M", &format!("({i}, {j})"), v)?;
        if v != T::zero() {
            triplets.push((i, j, v));
        }
        Ok(())
    };
    match (&inline.triplets, &inline.csc) {
        (Some(t), None) => {
            for (k, &(i, j, v)) in t.iter().enumerate() {
                push(i, j, v, k)?;
            }
        }
        (None, Some(c)) => {
            if c.col_ptr.len() != dim + 1
                || c.col_ptr[0] != 0
                || c.col_ptr.windows(2).any(|w| w[0] > w[1])
                || c.col_ptr[dim] != c.row_idx.len()
                || c.row_idx.len() != c.values.len()
            {
                return Err(invalid(
                    file,
                    "M_sparse.csc",
                    format!(
                        "col_ptr must have order + 1 = {} nondecreasing entries from 0 to len(row_idx) = {}, and values as many as row_idx ({})",
                        dim + 1,
                        c.row_idx.len(),
                        c.values.len()
                    ),
                ));
            }
            for j in 0..dim {
                for k in c.col_ptr[j]..c.col_ptr[j + 1] {
                    push(c.row_idx[k], j, c.values[k], k)?;
                }
            }
        }
        _ => {
            return Err(invalid(
                file,
                "M_sparse",
                "give exactly one of \"triplets\" and \"csc\"",
            ))
        }
    }
    let m = Csc::try_from_triplets(dim, dim, &triplets)?;
    let col = |v: &[f64], name: &str| -> Result<Col<T>, PlcpError> {
        let mut c = Col::zeros(v.len());
        for (i, &x) in v.iter().enumerate() {
            c[i] = convert::<T>(name, &format!("[{i}]"), x)?;
        }
        Ok(c)
    };
    let q = col(&raw.q, "q")?;
    let d = col(&raw.d, "d")?;
    let p = raw.free;
    let mut problem = Plcp::mixed_sparse(m, q.as_ref(), d.as_ref(), p)?;
    let lambda_max = match &raw.lambda_max {
        None | Some(serde_json::Value::Null) => None,
        Some(serde_json::Value::String(s)) if s == "inf" => None,
        Some(serde_json::Value::Number(x)) => super::json::lambda_max_from_f64::<T>(x.as_f64())
            .map_err(|e| invalid(file, "lambda_max", e.to_string()))?,
        Some(other) => {
            return Err(invalid(
                file,
                "lambda_max",
                format!("a number, null or \"inf\", got {other}"),
            ))
        }
    };
    let lambda0 = super::convert::<T>("lambda0", "", raw.lambda0.unwrap_or(0.0))?;
    problem = problem.with_range(lambda0, lambda_max)?;
    let n = dim.saturating_sub(p);
    let warm = warm_basis(raw.warm_basis, p, n, file)?;
    Ok((problem, warm))
}

/// The warm basis of the file: `"z"` or `"w"` (the free variables and every
/// `z` or `w`), or a list of names `u<j>`, `z<i>`, `w<i>` (`p` free
/// variables, `n` pairs).
fn warm_basis(
    warm: Option<RawWarm>,
    p: usize,
    n: usize,
    file: &str,
) -> Result<Option<Vec<Var>>, PlcpError> {
    let warm = match warm {
        None => None,
        Some(RawWarm::All(s)) => {
            let pair: fn(usize) -> Var = match s.as_str() {
                "z" => Var::Z,
                "w" => Var::W,
                _ => {
                    return Err(invalid(
                        file,
                        "warm_basis",
                        format!("\"z\", \"w\" or a list of names, got \"{s}\""),
                    ))
                }
            };
            Some((0..p).map(Var::U).chain((0..n).map(pair)).collect())
        }
        Some(RawWarm::List(names)) => {
            let mut b = Vec::with_capacity(names.len());
            for (k, s) in names.iter().enumerate() {
                let bad = || {
                    invalid(
                        file,
                        format!("warm_basis[{k}]"),
                        format!("\"{s}\" is not u<j>, z<i> or w<i> in range"),
                    )
                };
                let (kind, idx) = s.split_at(1.min(s.len()));
                let i: usize = idx.parse().map_err(|_| bad())?;
                b.push(match kind {
                    "u" if i < p => Var::U(i),
                    "z" if i < n => Var::Z(i),
                    "w" if i < n => Var::W(i),
                    _ => return Err(bad()),
                });
            }
            Some(b)
        }
    };
    Ok(warm)
}

/// Reads a sparse problem file ([`parse_sparse`]).
pub fn read_sparse<T: Scalar>(
    path: &std::path::Path,
) -> Result<(Plcp<T>, Option<Vec<Var>>), PlcpError> {
    let bytes = super::read_bytes(path)?;
    parse_sparse(&bytes, &path.display().to_string())
}
