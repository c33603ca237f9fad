//! The sparse basis: an LU factorisation of `B` with product-form updates.
//!
//! At a refactorisation `B0 = P' L U Q'` is computed by faer's simplicial
//! sparse LU (COLAMD column order, partial pivoting by rows, Gilbert-Peierls
//! column by column; no dense kernels, so it runs in `fx128` too). Between
//! refactorisations each pivot appends an eta column: replacing the column at
//! position `r` by `a` with `y = B^{-1} a` is `B_new = B E`, `E = I + (y - e_r) e_r'`,
//! so `B_new^{-1} = E^{-1} B^{-1}` and `E^{-1}` needs only `y` (product form).
//!
//! Why product form and not a bordered (Schur-complement) update of `B0`: a
//! pivot of the long form replaces one column and keeps the order of `B`, the
//! product form needs nothing but the entering column that the ratio test has
//! computed anyway, its transpose solve is as simple as the forward one, and
//! the eta file is thrown away at the next refactorisation. A Schur update
//! needs an extra solve with `B0` per pivot (for the bordering row) and a dense
//! Schur block that grows with the pivots. The eta columns are stored sparse;
//! when they hold more nonzeros than the factors, [`SparseLu::replace`] asks
//! for a refactorisation (applying them would cost more than a new factor).
//!
//! The condition number is estimated by Hager's method with Higham's
//! refinements on the factors (`||B||_1 ||B^{-1}||_1`, a lower bound that is
//! almost always within a factor of a few of the truth), five solves at most.

use super::{identity_row, BasisFactor, InverseRows};
use crate::linalg::col_slice_mut;
use crate::matrix::MatrixRef;
use crate::path::Var;
use crate::scalar::Scalar;
use crate::sparse_lu::SparseFactor;
use crate::tolerance::ROW_NOISE_EPS;
use core::cell::RefCell;
use faer::{Col, Mat};

/// One pivot of the product form: the column at position `r` replaced, with
/// `y = B^{-1} a` its nonzeros (`r` excluded) and the pivot `y_r`.
///
/// A column of the inverse of a long-form basis is mostly dense (three
/// quarters of the 1000-element cantilever's): such an eta is stored dense
/// (`y` with `y_r = 0`), and applying it is a contiguous pass rather than a
/// scatter. Either form gives the same results: the entries a dense eta adds
/// are zeros, whose products change no sum.
struct Eta<T: Scalar> {
    r: usize,
    pivot: T,
    /// The sparse form (empty when dense).
    idx: Vec<usize>,
    val: Vec<T>,
    /// The dense form (empty when sparse).
    dense: Vec<T>,
}

impl<T: Scalar> Eta<T> {
    /// `y_j` (`j != r`).
    fn entry(&self, j: usize) -> T {
        if !self.dense.is_empty() {
            return self.dense[j];
        }
        match self.idx.binary_search(&j) {
            Ok(k) => self.val[k],
            Err(_) => T::zero(),
        }
    }
}

/// An eta column with more than this fraction of nonzeros is stored dense.
const DENSE_ETA: f64 = 0.25;

/// A fill-reducing column order and the fill (`nnz(L) + nnz(U)`) of the
/// factorisation it was computed for.
struct ColumnOrder {
    fwd: Vec<usize>,
    inv: Vec<usize>,
    fill: usize,
}

/// A refactorisation reuses the previous column order (COLAMD's symbolic
/// phase costs several numeric factorisations of a basis of the long form)
/// until the factors exceed this multiple of the fill COLAMD gave (the next
/// one then orders afresh): a pivot replaces one column, and the order of the
/// others stays good.
const REORDER_FILL: f64 = 1.25;

/// The sparse basis representation (see the module docs).
pub(crate) struct SparseLu<T: Scalar> {
    dim: usize,
    factor: Option<SparseFactor<T>>,
    etas: Vec<Eta<T>>,
    eta_nnz: usize,
    /// The column order of the last factorisation, reused while the factors
    /// it gives stay within [`REORDER_FILL`] of the fill right after COLAMD.
    order: Option<ColumnOrder>,
    /// Workspace for the CSC form of `B`.
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    val: Vec<T>,
    /// Workspaces kept between pivots (no `dim`-long allocation per solve):
    /// the two right-hand sides of [`BasisFactor::solve2`] in the factors'
    /// row order, and the rows of `B^-T e_r` of [`BasisFactor::inverse_rows`]
    /// (all zero between uses).
    solve2_tmp: RefCell<Vec<T>>,
    unit_tmp: RefCell<Vec<T>>,
    /// The rows of [`BasisFactor::inverse_rows`], one after the other
    /// (lent to the lexicographic rule; rezeroed at each use).
    rows_tmp: RefCell<Vec<T>>,
}

impl<T: Scalar> SparseLu<T> {
    pub(crate) fn new(dim: usize) -> Self {
        Self {
            dim,
            factor: None,
            etas: Vec::new(),
            eta_nnz: 0,
            order: None,
            col_ptr: Vec::new(),
            row_idx: Vec::new(),
            val: Vec::new(),
            solve2_tmp: RefCell::new(Vec::new()),
            unit_tmp: RefCell::new(Vec::new()),
            rows_tmp: RefCell::new(Vec::new()),
        }
    }

    fn apply_etas(&self, x: &mut Col<T>) {
        let x = x
            .as_mut()
            .try_as_col_major_mut()
            .expect("a column is contiguous")
            .as_slice_mut();
        for e in &self.etas {
            let xr = x[e.r] / e.pivot;
            x[e.r] = xr;
            if xr != T::zero() {
                if e.dense.is_empty() {
                    for (&i, &v) in e.idx.iter().zip(&e.val) {
                        let t = x[i] - v * xr;
                        x[i] = t;
                    }
                } else {
                    for (xi, &v) in x.iter_mut().zip(&e.dense) {
                        *xi -= v * xr;
                    }
                }
            }
        }
    }

    /// [`Self::apply_etas`] on two vectors in one pass over the eta file
    /// (each sees the operations of its own pass).
    fn apply_etas2(&self, x: &mut [T], y: &mut [T]) {
        for e in &self.etas {
            let xr = x[e.r] / e.pivot;
            x[e.r] = xr;
            let yr = y[e.r] / e.pivot;
            y[e.r] = yr;
            let (onx, ony) = (xr != T::zero(), yr != T::zero());
            if e.dense.is_empty() {
                if onx {
                    for (&i, &v) in e.idx.iter().zip(&e.val) {
                        let t = x[i] - v * xr;
                        x[i] = t;
                    }
                }
                if ony {
                    for (&i, &v) in e.idx.iter().zip(&e.val) {
                        let t = y[i] - v * yr;
                        y[i] = t;
                    }
                }
            } else if onx && ony {
                for ((xi, yi), &v) in x.iter_mut().zip(y.iter_mut()).zip(&e.dense) {
                    *xi -= v * xr;
                    *yi -= v * yr;
                }
            } else if onx || ony {
                let (z, zr) = if onx { (&mut *x, xr) } else { (&mut *y, yr) };
                for (zi, &v) in z.iter_mut().zip(&e.dense) {
                    *zi -= v * zr;
                }
            }
        }
    }

    fn apply_etas_transpose(&self, c: &mut Col<T>) {
        let c = c
            .as_mut()
            .try_as_col_major_mut()
            .expect("a column is contiguous")
            .as_slice_mut();
        for e in self.etas.iter().rev() {
            let mut s = c[e.r];
            if e.dense.is_empty() {
                for (&i, &v) in e.idx.iter().zip(&e.val) {
                    s -= v * c[i];
                }
            } else {
                for (&ci, &v) in c.iter().zip(&e.dense) {
                    s -= v * ci;
                }
            }
            c[e.r] = s / e.pivot;
        }
    }

    /// [`Self::apply_etas_transpose`] on a unit vector `e_k` (`c` zero on
    /// entry): it stays zero but at `k` and at the eta positions, so each eta
    /// costs a product per nonzero (in ascending order: the same sums as the
    /// full pass). Returns the positions it wrote, ascending.
    fn apply_etas_transpose_unit(&self, k: usize, c: &mut [T]) -> Vec<usize> {
        let mut nz: Vec<usize> = vec![k];
        c[k] = T::one();
        for e in self.etas.iter().rev() {
            let mut s = c[e.r];
            for &j in &nz {
                if j != e.r {
                    s -= e.entry(j) * c[j];
                }
            }
            c[e.r] = s / e.pivot;
            if let Err(at) = nz.binary_search(&e.r) {
                nz.insert(at, e.r);
            }
        }
        nz
    }
}

impl<T: Scalar> BasisFactor<T> for SparseLu<T> {
    fn refactor(
        &mut self,
        m: MatrixRef<'_, T>,
        d: &Col<T>,
        p: usize,
        basis: &[Var],
    ) -> Option<f64> {
        let dim = self.dim;
        self.col_ptr.clear();
        self.row_idx.clear();
        self.val.clear();
        self.col_ptr.push(0);
        for v in basis {
            let (rows, vals) = (&mut self.row_idx, &mut self.val);
            let mut push = |i: usize, x: T| {
                if x != T::zero() {
                    rows.push(i);
                    vals.push(-x);
                }
            };
            match *v {
                Var::U(j) => m.for_col(j, &mut push),
                Var::Z(j) => m.for_col(p + j, &mut push),
                Var::Lambda => (0..dim).for_each(|i| push(i, d[i])),
                Var::W(_) | Var::Artificial(_) => {
                    let i = identity_row(p, *v).expect("identity column");
                    rows.push(i);
                    vals.push(T::one());
                }
            }
            self.col_ptr.push(self.row_idx.len());
        }
        self.etas.clear();
        self.eta_nnz = 0;
        self.factor = None;
        let reused = self.order.as_ref().and_then(|o| {
            SparseFactor::with_order(
                dim,
                &self.col_ptr,
                &self.row_idx,
                &self.val,
                Some((&o.fwd, &o.inv)),
            )
        });
        if let (Some(f), Some(o)) = (&reused, &self.order) {
            // the order has aged: a fresh one at the next refactorisation
            if f.factor_nnz() as f64 > REORDER_FILL * o.fill as f64 {
                self.order = None;
            }
        }
        let f = match reused {
            Some(f) => f,
            None => {
                let f = SparseFactor::new(dim, &self.col_ptr, &self.row_idx, &self.val)?;
                self.order = Some(ColumnOrder {
                    fwd: f.col_fwd.clone(),
                    inv: f.col_inv.clone(),
                    fill: f.factor_nnz(),
                });
                f
            }
        };
        let cond = f.condition();
        // numerically singular: no digit of a solve would be right
        if !cond.is_finite() || cond * T::eps().to_f64() * (dim.max(1) as f64) >= 1.0 {
            return None;
        }
        self.factor = Some(f);
        Some(cond)
    }

    fn solve(&self, a: &Col<T>) -> Col<T> {
        let mut x = a.clone();
        if let Some(f) = &self.factor {
            f.solve_in_place(&mut x);
        }
        self.apply_etas(&mut x);
        x
    }

    fn solve2(&self, mut x: Col<T>, mut y: Col<T>) -> (Col<T>, Col<T>) {
        let xs = col_slice_mut(&mut x);
        let ys = col_slice_mut(&mut y);
        if let Some(f) = &self.factor {
            f.solve2_in_place(xs, ys, &mut self.solve2_tmp.borrow_mut());
        }
        self.apply_etas2(xs, ys);
        (x, y)
    }

    fn unit(&self, k: usize) -> Col<T> {
        let mut e = Col::zeros(self.dim);
        e[k] = T::one();
        self.solve(&e)
    }

    fn inverse_rows(&self, rows: &[usize]) -> Option<InverseRows<'_, T>> {
        // row r of B^{-1} is (B^{-T} e_r)': all rows in one sweep over the
        // etas and two columns per sweep over the factors (each column sees
        // the operations of its own solve). The etas leave e_r sparse: its
        // nonzeros go straight to their places in the factors' column order;
        // the solved rows stay in the factors' row order, and the rule reads
        // the few entries it compares through that order
        let dim = self.dim;
        let factor = self.factor.as_ref();
        let mut data = self.rows_tmp.borrow_mut();
        data.resize(dim * rows.len(), T::zero());
        data.fill(T::zero());
        {
            let mut c = self.unit_tmp.borrow_mut();
            c.resize(dim, T::zero());
            for (t, &r) in rows.iter().enumerate() {
                let nz = self.apply_etas_transpose_unit(r, &mut c);
                let dst = &mut data[t * dim..(t + 1) * dim];
                for &j in &nz {
                    dst[factor.map_or(j, |f| f.col_inv[j])] = c[j];
                    c[j] = T::zero();
                }
            }
        }
        if let Some(f) = factor {
            f.solve_transpose_permuted_cols(&mut data);
        }
        Some(InverseRows::new(dim, data, factor.map(|f| &f.row_inv[..])))
    }

    fn inverse_rows_full(&self, rows: &[usize]) -> Option<Vec<Col<T>>> {
        // row r of B^{-1} is (B^{-T} e_r)': all rows in one sweep over the etas
        // and the factors (each column sees the operations of its own solve).
        // The etas leave e_r sparse: its nonzeros go straight to their places
        // in the factors' column order, and the solutions are read back
        // through their row order (no permutation passes; the same numbers)
        let dim = self.dim;
        let factor = self.factor.as_ref();
        let mut x = Mat::<T>::zeros(dim, rows.len());
        let mut c = self.unit_tmp.borrow_mut();
        c.resize(dim, T::zero());
        for (col, &r) in rows.iter().enumerate() {
            let nz = self.apply_etas_transpose_unit(r, &mut c);
            let dst = x
                .col_mut(col)
                .try_as_col_major_mut()
                .expect("a column is contiguous")
                .as_slice_mut();
            for &j in &nz {
                dst[factor.map_or(j, |f| f.col_inv[j])] = c[j];
                c[j] = T::zero();
            }
        }
        if let Some(f) = factor {
            f.solve_transpose_permuted_mat(x.as_mut());
        }
        Some(
            (0..rows.len())
                .map(|col| {
                    let src = x
                        .col(col)
                        .try_as_col_major()
                        .expect("a column is contiguous")
                        .as_slice();
                    // the row's largest entry taken as it is gathered (the
                    // same entries in the same order: the same maximum)
                    let mut big = T::zero();
                    let mut row = match factor {
                        Some(f) => Col::<T>::from_fn(dim, |i| {
                            let v = src[f.row_inv[i]];
                            big = big.max(v.abs());
                            v
                        }),
                        None => Col::<T>::from_fn(dim, |i| {
                            let v = src[i];
                            big = big.max(v.abs());
                            v
                        }),
                    };
                    let out = col_slice_mut(&mut row);
                    // entries at the rounding level of the row are zeros of the
                    // exact inverse (the lexicographic rule compares them exactly)
                    let tol = T::from_f64(ROW_NOISE_EPS) * T::eps() * big;
                    for o in out.iter_mut() {
                        if o.abs() <= tol {
                            *o = T::zero();
                        }
                    }
                    row
                })
                .collect(),
        )
    }

    fn solve_transpose(&self, c: &Col<T>) -> Col<T> {
        let mut x = c.clone();
        self.apply_etas_transpose(&mut x);
        if let Some(f) = &self.factor {
            f.solve_transpose_in_place(&mut x);
        }
        x
    }

    fn replace(
        &mut self,
        _m: MatrixRef<'_, T>,
        _d: &Col<T>,
        _p: usize,
        r: usize,
        _leaving: Var,
        _entering: Var,
        y: &Col<T>,
    ) -> bool {
        let Some(f) = &self.factor else {
            return false;
        };
        let pivot = y[r];
        if pivot == T::zero() || !pivot.is_finite() {
            return false;
        }
        let ys = y
            .as_ref()
            .try_as_col_major()
            .expect("a column is contiguous")
            .as_slice();
        let nnz = ys
            .iter()
            .enumerate()
            .filter(|&(i, &v)| i != r && v != T::zero())
            .count();
        let (mut idx, mut val) = (Vec::new(), Vec::new());
        let dense = if nnz as f64 > DENSE_ETA * self.dim as f64 {
            let mut v = ys.to_vec();
            v[r] = T::zero();
            v
        } else {
            idx.reserve(nnz);
            val.reserve(nnz);
            for (i, &v) in ys.iter().enumerate() {
                if i != r && v != T::zero() {
                    idx.push(i);
                    val.push(v);
                }
            }
            Vec::new()
        };
        self.eta_nnz += nnz + 1;
        self.etas.push(Eta {
            r,
            pivot,
            idx,
            val,
            dense,
        });
        // applying the eta file now costs more than a fresh factor would: refactorise
        self.eta_nnz <= 4 * f.nnz + self.dim
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::basis::var_column;
    use crate::matrix::Csc;

    /// The rows [`SparseLu::inverse_rows`] lends the lexicographic rule read
    /// the same bits, entry by entry, as the rows computed in full
    /// ([`BasisFactor::inverse_rows_full`], the code before issue 15's
    /// change), right after a factorisation and through eta files of up to
    /// eight pivots, one to four rows at a time.
    #[test]
    fn lent_rows_read_as_the_full_rows() {
        let mut next = crate::test_rng::unit(0x9e37_79b9_7f4a_7c15);
        let mut compared = 0usize;
        for case in 0..40 {
            let n = 3 + case % 17;
            // a random sparse M with a dominant diagonal, p = 0
            let mut m = faer::Mat::<f64>::zeros(n, n);
            for j in 0..n {
                for i in 0..n {
                    if i == j {
                        m[(i, j)] = 2.0 + next();
                    } else if next() < 0.3 {
                        m[(i, j)] = 2.0 * next() - 1.0;
                    }
                }
            }
            let csc = Csc::from_dense(m.as_ref());
            let mr = csc.as_ref();
            let d = faer::Col::<f64>::from_fn(n, |_| next() - 0.5);
            let mut basis: Vec<Var> = (0..n)
                .map(|i| if next() < 0.5 { Var::Z(i) } else { Var::W(i) })
                .collect();
            let mut lu = SparseLu::<f64>::new(n);
            if lu.refactor(mr, &d, 0, &basis).is_none() {
                continue;
            }
            for pivot in 0..=(case % 9) {
                // compare, then pivot one variable in (a z for a w or back)
                let k = 1 + (case + pivot) % 4;
                let rows: Vec<usize> = (0..k.min(n)).map(|t| (t * 7 + pivot) % n).collect();
                let mut rows = rows;
                rows.sort_unstable();
                rows.dedup();
                let lent = lu.inverse_rows(&rows).expect("rows");
                let full = lu.inverse_rows_full(&rows).expect("rows");
                for (t, row) in full.iter().enumerate() {
                    for c in 0..n {
                        assert_eq!(
                            lent.get(t, c).to_bits(),
                            row[c].to_bits(),
                            "case {case}, pivot {pivot}, row {}, entry {c}",
                            rows[t]
                        );
                        compared += 1;
                    }
                }
                drop(lent);
                let r = (case * 3 + pivot) % n;
                let entering = match basis[r] {
                    Var::Z(i) => Var::W(i),
                    Var::W(i) => Var::Z(i),
                    v => v,
                };
                let y = lu.solve(&var_column(mr, &d, 0, entering));
                if y[r].abs() < 1e-3 {
                    break;
                }
                let leaving = basis[r];
                basis[r] = entering;
                if !lu.replace(mr, &d, 0, r, leaving, entering, &y) {
                    break;
                }
            }
        }
        assert!(compared > 2000, "{compared} entries compared");
    }
}
