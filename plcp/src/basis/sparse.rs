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

use super::{identity_row, BasisFactor};
use crate::matrix::MatrixRef;
use crate::path::Var;
use crate::scalar::Scalar;
use crate::tolerance::ROW_NOISE_EPS;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::perm::PermRef;
use faer::sparse::linalg::lu::simplicial::{self, SimplicialLu};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuSymbolicParams};
use faer::sparse::linalg::triangular_solve;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Col, Conj, Mat, MatMut, Par};

/// A sparse LU factorisation of a square matrix given in CSC form:
/// `A[row_fwd, col_fwd] = L U` (faer's simplicial factors, unit lower `L`).
///
/// The permutations are applied here rather than by faer's `LuRef` solve,
/// which permutes a single right-hand side row by row through a freshly
/// allocated workspace: measured at 6000 unknowns, that was a quarter of the
/// solve time.
pub(crate) struct SparseFactor<T: Scalar> {
    dim: usize,
    lu: SimplicialLu<usize, T>,
    row_fwd: Vec<usize>,
    row_inv: Vec<usize>,
    col_fwd: Vec<usize>,
    col_inv: Vec<usize>,
    /// Stored entries of the factored matrix.
    pub nnz: usize,
    /// Its 1-norm.
    pub norm1: f64,
}

impl<T: Scalar> SparseFactor<T> {
    /// Factors the square matrix (`col_ptr`, `row_idx` sorted within columns,
    /// `val`); `None` if it is structurally singular or the factorisation fails.
    pub(crate) fn new(dim: usize, col_ptr: &[usize], row_idx: &[usize], val: &[T]) -> Option<Self> {
        Self::with_order(dim, col_ptr, row_idx, val, None)
    }

    /// [`Self::new`] with the column order `(forward, inverse)` given (a
    /// previous factorisation's, see [`SparseLu`]) rather than computed by COLAMD.
    pub(crate) fn with_order(
        dim: usize,
        col_ptr: &[usize],
        row_idx: &[usize],
        val: &[T],
        order: Option<(&[usize], &[usize])>,
    ) -> Option<Self> {
        let sym = SymbolicSparseColMatRef::new_checked(dim, dim, col_ptr, None, row_idx);
        let (col_fwd, col_inv) = match order {
            Some((f, i)) => (f.to_vec(), i.to_vec()),
            None => {
                let params = LuSymbolicParams {
                    supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SIMPLICIAL,
                    ..Default::default()
                };
                // the symbolic phase gives the COLAMD column order
                let symbolic = factorize_symbolic_lu(sym, params).ok()?;
                let (cf, ci) = symbolic.col_perm().arrays();
                (cf.to_vec(), ci.to_vec())
            }
        };
        let mut lu = SimplicialLu::new();
        let mut row_fwd = vec![0usize; dim];
        let mut row_inv = vec![0usize; dim];
        let a = SparseColMatRef::new(sym, val);
        let req = simplicial::factorize_simplicial_numeric_lu_scratch::<usize, T>(dim, dim);
        let mut mem = MemBuffer::try_new(req).ok()?;
        simplicial::factorize_simplicial_numeric_lu(
            &mut row_fwd,
            &mut row_inv,
            &mut lu,
            a,
            PermRef::new_checked(&col_fwd, &col_inv, dim),
            MemStack::new(&mut mem),
        )
        .ok()?;
        let mut norm1 = 0.0f64;
        for j in 0..dim {
            let s: f64 = val[col_ptr[j]..col_ptr[j + 1]]
                .iter()
                .map(|v| v.to_f64().abs())
                .sum();
            norm1 = norm1.max(s);
        }
        Some(Self {
            dim,
            lu,
            row_fwd,
            row_inv,
            col_fwd,
            col_inv,
            nnz: row_idx.len(),
            norm1,
        })
    }

    /// Stored entries of the factors `L` and `U`.
    fn factor_nnz(&self) -> usize {
        self.lu.l_factor_unsorted().compute_nnz() + self.lu.u_factor_unsorted().compute_nnz()
    }

    /// `x[i] <- x[perm[i]]`.
    fn permute(x: &mut Col<T>, perm: &[usize], tmp: &mut Vec<T>) {
        let x = x
            .as_mut()
            .try_as_col_major_mut()
            .expect("a column is contiguous")
            .as_slice_mut();
        tmp.clear();
        tmp.extend(perm.iter().map(|&p| x[p]));
        x.copy_from_slice(tmp);
    }

    /// `x <- A^{-1} x`.
    ///
    /// The triangular solves are column sweeps that skip the columns whose
    /// multiplier is zero: the right-hand sides of the pivoting (a column of
    /// `M` or a unit vector, a residual) start sparse, and `L^{-1} a` stays
    /// sparse over much of the sweep. Otherwise the operations of faer's
    /// single-column solves, in their order: the same results.
    pub(crate) fn solve_in_place(&self, x: &mut Col<T>) {
        debug_assert_eq!(x.nrows(), self.dim);
        let mut tmp = Vec::with_capacity(self.dim);
        Self::permute(x, &self.row_fwd, &mut tmp);
        let (l, u) = (self.lu.l_factor_unsorted(), self.lu.u_factor_unsorted());
        {
            let xs = x
                .as_mut()
                .try_as_col_major_mut()
                .expect("a column is contiguous")
                .as_slice_mut();
            // unit lower L, its diagonal stored first in each column
            for j in 0..self.dim {
                let xj = xs[j];
                if xj == T::zero() {
                    continue;
                }
                let (rows, vals) = (l.row_idx_of_col_raw(j), l.val_of_col(j));
                for (&i, &lij) in rows.iter().zip(vals).skip(1) {
                    xs[i] -= lij * xj;
                }
            }
            // upper U, its diagonal stored last in each column
            for j in (0..self.dim).rev() {
                if xs[j] == T::zero() {
                    continue;
                }
                let (rows, vals) = (u.row_idx_of_col_raw(j), u.val_of_col(j));
                let last = vals.len() - 1;
                debug_assert_eq!(rows[last], j);
                let xj = xs[j] * (T::one() / vals[last]);
                xs[j] = xj;
                for (&i, &uij) in rows[..last].iter().zip(&vals[..last]).rev() {
                    xs[i] -= uij * xj;
                }
            }
        }
        Self::permute(x, &self.col_inv, &mut tmp);
    }

    /// `x <- A^{-1} x` and `y <- A^{-1} y` in one sweep over the factors:
    /// each column sees the operations of its own [`Self::solve_in_place`]
    /// (the same results), the factors' indices and values are read once.
    pub(crate) fn solve2_in_place(&self, x: &mut [T], y: &mut [T], tmp: &mut Vec<T>) {
        debug_assert!(x.len() == self.dim && y.len() == self.dim);
        let permute = |v: &mut [T], perm: &[usize], tmp: &mut Vec<T>| {
            tmp.clear();
            tmp.extend(perm.iter().map(|&p| v[p]));
            v.copy_from_slice(tmp);
        };
        permute(x, &self.row_fwd, tmp);
        permute(y, &self.row_fwd, tmp);
        let (l, u) = (self.lu.l_factor_unsorted(), self.lu.u_factor_unsorted());
        // unit lower L, its diagonal stored first in each column
        for j in 0..self.dim {
            let (xj, yj) = (x[j], y[j]);
            let (onx, ony) = (xj != T::zero(), yj != T::zero());
            if !onx && !ony {
                continue;
            }
            let (rows, vals) = (l.row_idx_of_col_raw(j), l.val_of_col(j));
            if onx && ony {
                for (&i, &lij) in rows.iter().zip(vals).skip(1) {
                    x[i] -= lij * xj;
                    y[i] -= lij * yj;
                }
            } else {
                let (v, vj) = if onx { (&mut *x, xj) } else { (&mut *y, yj) };
                for (&i, &lij) in rows.iter().zip(vals).skip(1) {
                    v[i] -= lij * vj;
                }
            }
        }
        // upper U, its diagonal stored last in each column
        for j in (0..self.dim).rev() {
            let (onx, ony) = (x[j] != T::zero(), y[j] != T::zero());
            if !onx && !ony {
                continue;
            }
            let (rows, vals) = (u.row_idx_of_col_raw(j), u.val_of_col(j));
            let last = vals.len() - 1;
            debug_assert_eq!(rows[last], j);
            let inv = T::one() / vals[last];
            let (rows, vals) = (&rows[..last], &vals[..last]);
            if onx && ony {
                let (xj, yj) = (x[j] * inv, y[j] * inv);
                x[j] = xj;
                y[j] = yj;
                for (&i, &uij) in rows.iter().zip(vals).rev() {
                    x[i] -= uij * xj;
                    y[i] -= uij * yj;
                }
            } else {
                let v = if onx { &mut *x } else { &mut *y };
                let vj = v[j] * inv;
                v[j] = vj;
                for (&i, &uij) in rows.iter().zip(vals).rev() {
                    v[i] -= uij * vj;
                }
            }
        }
        permute(x, &self.col_inv, tmp);
        permute(y, &self.col_inv, tmp);
    }

    /// `x <- A^{-T} x`.
    pub(crate) fn solve_transpose_in_place(&self, x: &mut Col<T>) {
        let mut tmp = Vec::with_capacity(self.dim);
        Self::permute(x, &self.col_fwd, &mut tmp);
        let (l, u) = (self.lu.l_factor_unsorted(), self.lu.u_factor_unsorted());
        triangular_solve::solve_upper_triangular_transpose_in_place(
            u,
            Conj::No,
            x.as_mat_mut(),
            Par::Seq,
        );
        triangular_solve::solve_unit_lower_triangular_transpose_in_place(
            l,
            Conj::No,
            x.as_mat_mut(),
            Par::Seq,
        );
        Self::permute(x, &self.row_inv, &mut tmp);
    }

    /// `X <- A^{-T} X`, all columns in one sweep over the factors.
    pub(crate) fn solve_transpose_in_place_mat(&self, mut x: MatMut<'_, T>) {
        debug_assert_eq!(x.nrows(), self.dim);
        let mut tmp = Vec::with_capacity(self.dim);
        let permute = |x: &mut MatMut<'_, T>, perm: &[usize], tmp: &mut Vec<T>| {
            for c in 0..x.ncols() {
                let col = x
                    .as_mut()
                    .col_mut(c)
                    .try_as_col_major_mut()
                    .expect("a column is contiguous")
                    .as_slice_mut();
                tmp.clear();
                tmp.extend(perm.iter().map(|&p| col[p]));
                col.copy_from_slice(tmp);
            }
        };
        permute(&mut x, &self.col_fwd, &mut tmp);
        let (l, u) = (self.lu.l_factor_unsorted(), self.lu.u_factor_unsorted());
        triangular_solve::solve_upper_triangular_transpose_in_place(
            u,
            Conj::No,
            x.as_mut(),
            Par::Seq,
        );
        triangular_solve::solve_unit_lower_triangular_transpose_in_place(
            l,
            Conj::No,
            x.as_mut(),
            Par::Seq,
        );
        permute(&mut x, &self.row_inv, &mut tmp);
    }

    /// The 1-norm condition number estimate `||A||_1 est(||A^{-1}||_1)`; not
    /// finite if the factors are (a zero pivot).
    pub(crate) fn condition(&self) -> f64 {
        self.norm1
            * hager_inverse_norm1(
                self.dim,
                |x| self.solve_in_place(x),
                |x| self.solve_transpose_in_place(x),
            )
    }
}

/// The entries of a (contiguous) column.
fn col_slice<T: Scalar>(c: &mut Col<T>) -> &mut [T] {
    c.as_mut()
        .try_as_col_major_mut()
        .expect("a column is contiguous")
        .as_slice_mut()
}

/// Hager's estimate of `||A^{-1}||_1` from solves with `A` and `A'` (Higham,
/// "FORTRAN codes for estimating the one-norm", 1988, without the parallel
/// column search): at most five iterations of the gradient ascent on the unit
/// 1-ball, and Higham's alternating-sign vector as a safeguard.
pub(crate) fn hager_inverse_norm1<T: Scalar>(
    dim: usize,
    solve: impl Fn(&mut Col<T>),
    solve_t: impl Fn(&mut Col<T>),
) -> f64 {
    if dim == 0 {
        return 1.0;
    }
    let norm1 = |x: &Col<T>| (0..dim).map(|i| x[i].to_f64().abs()).sum::<f64>();
    let mut x = Col::<T>::from_fn(dim, |_| T::from_f64(1.0 / dim as f64));
    let mut est = 0.0f64;
    let mut last_j = usize::MAX;
    for iter in 0..5 {
        solve(&mut x);
        let e = norm1(&x);
        if !e.is_finite() {
            return f64::INFINITY;
        }
        if iter > 0 && e <= est {
            break;
        }
        est = e;
        let mut s = Col::<T>::from_fn(dim, |i| {
            if x[i] >= T::zero() {
                T::one()
            } else {
                -T::one()
            }
        });
        solve_t(&mut s);
        let (mut j, mut zmax) = (0usize, -1.0f64);
        for i in 0..dim {
            let v = s[i].to_f64().abs();
            if !v.is_finite() {
                return f64::INFINITY;
            }
            if v > zmax {
                zmax = v;
                j = i;
            }
        }
        if j == last_j {
            break;
        }
        last_j = j;
        x = Col::zeros(dim);
        x[j] = T::one();
    }
    // Higham's safeguard: b_i = (-1)^i (1 + i / (n - 1))
    let mut b = Col::<T>::from_fn(dim, |i| {
        let v = 1.0 + i as f64 / (dim.max(2) - 1) as f64;
        T::from_f64(if i % 2 == 0 { v } else { -v })
    });
    solve(&mut b);
    let alt = 2.0 * norm1(&b) / (3.0 * dim as f64);
    if !alt.is_finite() {
        return f64::INFINITY;
    }
    est.max(alt)
}

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

    /// [`Self::apply_etas_transpose`] on a unit vector `e_k`: it stays zero
    /// but at `k` and at the eta positions, so each eta costs a product per
    /// nonzero (in ascending order: the same sums as the full pass).
    fn apply_etas_transpose_unit(&self, k: usize, c: &mut [T]) {
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
        let xs = col_slice(&mut x);
        let ys = col_slice(&mut y);
        if let Some(f) = &self.factor {
            let mut tmp = Vec::with_capacity(self.dim);
            f.solve2_in_place(xs, ys, &mut tmp);
        }
        self.apply_etas2(xs, ys);
        (x, y)
    }

    fn unit(&self, k: usize) -> Col<T> {
        let mut e = Col::zeros(self.dim);
        e[k] = T::one();
        self.solve(&e)
    }

    fn inverse_rows(&self, rows: &[usize]) -> Option<Vec<Col<T>>> {
        // row r of B^{-1} is (B^{-T} e_r)': all rows in one sweep over the etas
        // and the factors (each column sees the operations of its own solve)
        let dim = self.dim;
        let mut x = Mat::<T>::zeros(dim, rows.len());
        for (c, &r) in rows.iter().enumerate() {
            let col = x
                .col_mut(c)
                .try_as_col_major_mut()
                .expect("a column is contiguous")
                .as_slice_mut();
            self.apply_etas_transpose_unit(r, col);
        }
        if let Some(f) = &self.factor {
            f.solve_transpose_in_place_mat(x.as_mut());
        }
        Some(
            (0..rows.len())
                .map(|c| {
                    let src = x
                        .col(c)
                        .try_as_col_major()
                        .expect("a column is contiguous")
                        .as_slice();
                    // entries at the rounding level of the row are zeros of the
                    // exact inverse (the lexicographic rule compares them exactly)
                    let big = src.iter().fold(T::zero(), |a, v| a.max(v.abs()));
                    let tol = T::from_f64(ROW_NOISE_EPS) * T::eps() * big;
                    let mut row = Col::<T>::zeros(dim);
                    for (r, &v) in col_slice(&mut row).iter_mut().zip(src) {
                        *r = if v.abs() <= tol { T::zero() } else { v };
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
