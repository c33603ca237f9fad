//! The system matrix `M`, dense or sparse, behind one small view.
//!
//! The pivoting core touches `M` only column by column: the column of an
//! entering variable, and `B x` as a sum of basic columns. [`MatrixRef`] offers
//! exactly that for a dense `M` ([`faer::MatRef`]) and for a sparse one in
//! compressed sparse column form ([`Csc`]), so that on a sparse problem both
//! cost `O(nnz)` of the columns involved instead of `O(p + n)` per column.
//!
//! ```
//! use plcp::matrix::Csc;
//! // [[2, 0], [1, 3]] from (row, column, value) triplets; duplicates are summed
//! let m = Csc::try_from_triplets(2, 2, &[(0, 0, 2.0), (1, 0, 1.0), (1, 1, 1.0), (1, 1, 2.0)]).unwrap();
//! assert_eq!(m.nnz(), 3);
//! assert_eq!(m.get(1, 1), 3.0);
//! assert!(Csc::try_from_triplets(2, 2, &[(2, 0, 1.0)]).is_err()); // row out of range
//! ```

use crate::error::PlcpError;
use crate::scalar::Scalar;
use faer::{Mat, MatRef};

/// A sparse matrix in compressed sparse column form: the row indices of each
/// column are sorted and unique, and every stored value is finite and nonzero.
#[derive(Clone, Debug, PartialEq)]
pub struct Csc<T: Scalar> {
    nrows: usize,
    ncols: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    val: Vec<T>,
}

impl<T: Scalar> Csc<T> {
    /// Builds from `(row, column, value)` triplets in any order; duplicates
    /// are summed and entries that sum to zero dropped. An index out of range or
    /// a non-finite value is an `Err` naming the triplet.
    pub fn try_from_triplets(
        nrows: usize,
        ncols: usize,
        triplets: &[(usize, usize, T)],
    ) -> Result<Self, PlcpError> {
        for (k, &(i, j, v)) in triplets.iter().enumerate() {
            if i >= nrows || j >= ncols {
                return Err(PlcpError::Dimension {
                    what: format!("M (sparse), triplet {k}"),
                    expected: format!("row < {nrows} and column < {ncols}"),
                    found: format!("({i}, {j})"),
                });
            }
            crate::problem::check_entry("M", || format!("({i}, {j})"), v)?;
        }
        let mut count = vec![0usize; ncols + 1];
        for &(_, j, _) in triplets {
            count[j + 1] += 1;
        }
        for j in 0..ncols {
            count[j + 1] += count[j];
        }
        let mut next = count.clone();
        let mut rows = vec![0usize; triplets.len()];
        let mut vals = vec![T::zero(); triplets.len()];
        for &(i, j, v) in triplets {
            rows[next[j]] = i;
            vals[next[j]] = v;
            next[j] += 1;
        }
        let mut col_ptr = Vec::with_capacity(ncols + 1);
        let mut row_idx = Vec::with_capacity(triplets.len());
        let mut val = Vec::with_capacity(triplets.len());
        col_ptr.push(0);
        let mut order: Vec<usize> = Vec::new();
        for j in 0..ncols {
            order.clear();
            order.extend(count[j]..count[j + 1]);
            order.sort_by_key(|&k| rows[k]);
            let mut k = 0;
            while k < order.len() {
                let i = rows[order[k]];
                let mut s = T::zero();
                while k < order.len() && rows[order[k]] == i {
                    s += vals[order[k]];
                    k += 1;
                }
                if !s.is_finite() {
                    return Err(PlcpError::NonFinite {
                        what: "M (sum of duplicate triplets)".into(),
                        position: format!("({i}, {j})"),
                        value: s.to_f64(),
                    });
                }
                if s != T::zero() {
                    row_idx.push(i);
                    val.push(s);
                }
            }
            col_ptr.push(row_idx.len());
        }
        Ok(Self {
            nrows,
            ncols,
            col_ptr,
            row_idx,
            val,
        })
    }

    /// The nonzero entries of a dense matrix.
    pub fn from_dense(m: MatRef<'_, T>) -> Self {
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        let mut val = Vec::new();
        for j in 0..m.ncols() {
            for i in 0..m.nrows() {
                let v = m[(i, j)];
                if v != T::zero() {
                    row_idx.push(i);
                    val.push(v);
                }
            }
            col_ptr.push(row_idx.len());
        }
        Self {
            nrows: m.nrows(),
            ncols: m.ncols(),
            col_ptr,
            row_idx,
            val,
        }
    }

    /// Number of rows.
    pub fn nrows(&self) -> usize {
        self.nrows
    }
    /// Number of columns.
    pub fn ncols(&self) -> usize {
        self.ncols
    }
    /// Number of stored (nonzero) entries.
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }
    /// Row indices and values of column `j`.
    pub fn col(&self, j: usize) -> (&[usize], &[T]) {
        let r = self.col_ptr[j]..self.col_ptr[j + 1];
        (&self.row_idx[r.clone()], &self.val[r])
    }
    /// The arrays: column pointers (`ncols + 1`), row indices, values.
    pub fn parts(&self) -> (&[usize], &[usize], &[T]) {
        (&self.col_ptr, &self.row_idx, &self.val)
    }
    /// Entry `(i, j)` (zero if not stored).
    pub fn get(&self, i: usize, j: usize) -> T {
        let (rows, vals) = self.col(j);
        rows.binary_search(&i).map_or(T::zero(), |k| vals[k])
    }
    /// The dense matrix.
    pub fn to_dense(&self) -> Mat<T> {
        let mut m = Mat::zeros(self.nrows, self.ncols);
        for j in 0..self.ncols {
            let (rows, vals) = self.col(j);
            for (&i, &v) in rows.iter().zip(vals) {
                m[(i, j)] = v;
            }
        }
        m
    }
    /// The same pattern with each value mapped by `f(row, column, value)`
    /// (entries mapped to zero are kept).
    pub fn map(&self, f: impl Fn(usize, usize, T) -> T) -> Self {
        let mut val = self.val.clone();
        for j in 0..self.ncols {
            for k in self.col_ptr[j]..self.col_ptr[j + 1] {
                val[k] = f(self.row_idx[k], j, self.val[k]);
            }
        }
        Self {
            val,
            ..self.clone()
        }
    }
    /// Converts to another precision (through `f64`).
    pub fn cast<U: Scalar>(&self) -> Csc<U> {
        Csc {
            nrows: self.nrows,
            ncols: self.ncols,
            col_ptr: self.col_ptr.clone(),
            row_idx: self.row_idx.clone(),
            val: self.val.iter().map(|v| U::from_f64(v.to_f64())).collect(),
        }
    }
    /// The block of rows `rows` and columns `cols` (half-open ranges).
    pub fn block(&self, rows: core::ops::Range<usize>, cols: core::ops::Range<usize>) -> Self {
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        let mut val = Vec::new();
        for j in cols.clone() {
            let (ri, vs) = self.col(j);
            for (&i, &v) in ri.iter().zip(vs) {
                if rows.contains(&i) {
                    row_idx.push(i - rows.start);
                    val.push(v);
                }
            }
            col_ptr.push(row_idx.len());
        }
        Self {
            nrows: rows.len(),
            ncols: cols.len(),
            col_ptr,
            row_idx,
            val,
        }
    }
    /// The 1-norm condition number estimate of a square matrix from its sparse
    /// LU factorisation (faer's simplicial LU, Hager/Higham estimator):
    /// `None` if the matrix is not square, or structurally or numerically
    /// singular. A lower bound of the true condition number, in practice
    /// within a small factor of it.
    ///
    /// ```
    /// use plcp::matrix::Csc;
    /// let m = Csc::try_from_triplets(2, 2, &[(0, 0, 2.0), (1, 1, 1e-3)]).unwrap();
    /// assert!((m.lu_condition().unwrap() - 2e3).abs() < 1e-9);
    /// let singular = Csc::try_from_triplets(2, 2, &[(0, 0, 1.0), (0, 1, 1.0)]).unwrap();
    /// assert!(singular.lu_condition().is_none());
    /// ```
    pub fn lu_condition(&self) -> Option<f64> {
        if self.nrows != self.ncols {
            return None;
        }
        let f = crate::sparse_lu::SparseFactor::new(
            self.nrows,
            &self.col_ptr,
            &self.row_idx,
            &self.val,
        )?;
        let cond = f.condition();
        (cond.is_finite() && cond * T::eps().to_f64() < 1.0).then_some(cond)
    }

    /// A view.
    pub fn as_ref(&self) -> MatrixRef<'_, T> {
        MatrixRef::Sparse(self)
    }
}

/// A view of the system matrix: dense, or sparse by columns.
#[derive(Clone, Copy, Debug)]
pub enum MatrixRef<'a, T: Scalar> {
    /// A dense matrix.
    Dense(MatRef<'a, T>),
    /// A sparse matrix.
    Sparse(&'a Csc<T>),
}

impl<'a, T: Scalar> From<MatRef<'a, T>> for MatrixRef<'a, T> {
    fn from(m: MatRef<'a, T>) -> Self {
        MatrixRef::Dense(m)
    }
}

impl<'a, T: Scalar> MatrixRef<'a, T> {
    /// Number of rows.
    pub fn nrows(&self) -> usize {
        match self {
            MatrixRef::Dense(m) => m.nrows(),
            MatrixRef::Sparse(m) => m.nrows(),
        }
    }
    /// Number of columns.
    pub fn ncols(&self) -> usize {
        match self {
            MatrixRef::Dense(m) => m.ncols(),
            MatrixRef::Sparse(m) => m.ncols(),
        }
    }
    /// Calls `f(i, m_ij)` for the entries of column `j` (every entry of a dense
    /// column, the stored ones of a sparse column). Always inlined with `f`
    /// (the wide residual pass, compiled with fma, needs its products inline).
    #[inline(always)]
    pub fn for_col(&self, j: usize, mut f: impl FnMut(usize, T)) {
        match self {
            MatrixRef::Dense(m) => {
                let c = m.col(j);
                for i in 0..c.nrows() {
                    f(i, c[i]);
                }
            }
            MatrixRef::Sparse(m) => {
                let (rows, vals) = m.col(j);
                for (&i, &v) in rows.iter().zip(vals) {
                    f(i, v);
                }
            }
        }
    }
    /// Entry `(i, j)`.
    pub fn get(&self, i: usize, j: usize) -> T {
        match self {
            MatrixRef::Dense(m) => m[(i, j)],
            MatrixRef::Sparse(m) => m.get(i, j),
        }
    }
    /// True for a sparse view.
    pub fn is_sparse(&self) -> bool {
        matches!(self, MatrixRef::Sparse(_))
    }
}
