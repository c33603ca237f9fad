//! The basis factorisation behind one small interface.
//!
//! A basis holds one variable per position; its columns are `-M[:, j]` for free
//! and complementary `z` variables, `-d` for the parameter (the *matrix*
//! columns), and unit vectors for slacks `w` and artificial variables (the
//! *identity* columns). The pivoting core asks four things of it: solve
//! `B y = a_v` for an entering column, solve `B y = e_k` (the lexicographic rule
//! reads the basis inverse column by column), replace the variable at one
//! position (a pivot), and rebuild from scratch (a refactorisation, which also
//! estimates the condition number).
//!
//! Two representations:
//!
//! * [`DenseInverse`]: the explicit `(p+n) x (p+n)` inverse, updated in product
//!   form; `O((p+n)^2)` per pivot whatever the basis. Simple, used as the
//!   reference in tests.
//! * [`BlockInverse`]: after permutation `B = [[S, 0], [C, I]]`, where the
//!   identity columns cover their own rows and `S` is the small square block of
//!   the matrix columns on the uncovered rows. Only `S^{-1}` (order `k`, the
//!   number of basic matrix columns) is kept and updated by bordering and
//!   Sherman-Morrison formulas; `B^{-1} a = (S^{-1} a_R, a_I - C S^{-1} a_R)` costs
//!   `O(k^2 + (p+n) k)`. A pivot's rank-one update of `S^{-1}` is applied by
//!   the next solve in the same pass over `S^{-1}` (see `Pending`). For a PLCP
//!   whose active set stays small this is far cheaper than the dense inverse.
//!   This is the default.
//! * [`SparseLu`]: a sparse LU factorisation of `B` (faer's simplicial LU with
//!   a COLAMD column order and partial pivoting), refactorised on the period,
//!   with product-form (eta) updates in between; for sparse problems
//!   ([`crate::Plcp::mixed_sparse`]) whose basis keeps many matrix columns
//!   (Wolfe's long form keeps every free variable basic). See [`sparse`].

mod block;
mod dense;
pub(crate) mod lex;
mod sparse;

pub(crate) use block::BlockInverse;
pub(crate) use dense::DenseInverse;
pub(crate) use lex::InverseRows;
pub(crate) use sparse::SparseLu;

use crate::linalg::{matmul_par_into, matvec, matvec_into, matvec_into_mut, par_for};
use crate::matrix::MatrixRef;
use crate::path::Var;
use crate::scalar::Scalar;
use crate::scaling::pow2;
use crate::settings::DEFAULT_REFACTOR_PERIOD;
use crate::tolerance::{REFINE_IDLE_EPS, REFINE_IDLE_RUN};
use core::cell::{Cell, RefCell};
use faer::reborrow::ReborrowMut;
use faer::{Col, Mat, MatMut, MatRef};

/// The column of variable `v` in the system `sum_v a_v v = q` (see [`crate::pivoting`]).
pub(crate) fn var_column<T: Scalar>(m: MatrixRef<'_, T>, d: &Col<T>, p: usize, v: Var) -> Col<T> {
    let mut a = Col::zeros(m.nrows());
    var_column_into(m, d, p, v, &mut a);
    a
}

/// [`var_column`] written into `a` (resized to `p + n` if it is not: no
/// allocation when it is; the pivoting core keeps one such buffer).
pub(crate) fn var_column_into<T: Scalar>(
    m: MatrixRef<'_, T>,
    d: &Col<T>,
    p: usize,
    v: Var,
    a: &mut Col<T>,
) {
    let dim = m.nrows();
    if a.nrows() != dim {
        *a = Col::zeros(dim);
    }
    let a = a
        .as_mut()
        .try_as_col_major_mut()
        .expect("an owned column is contiguous")
        .as_slice_mut();
    var_column_slice(m, d, p, v, a);
}

/// [`var_column`] written into a slice of length `p + n`.
pub(crate) fn var_column_slice<T: Scalar>(
    m: MatrixRef<'_, T>,
    d: &Col<T>,
    p: usize,
    v: Var,
    a: &mut [T],
) {
    let dim = m.nrows();
    match v {
        Var::U(j) | Var::Z(j) => {
            a.fill(T::zero());
            let col = if let Var::U(_) = v { j } else { p + j };
            m.for_col(col, |i, x| a[i] = -x);
        }
        Var::W(i) => {
            a.fill(T::zero());
            a[p + i] = T::one();
        }
        Var::Artificial(k) => {
            a.fill(T::zero());
            a[k] = T::one();
        }
        Var::Lambda => {
            for i in 0..dim {
                a[i] = -d[i];
            }
        }
    }
}

/// `B x = sum_r x_r a_{basis[r]}`, by system row.
pub(crate) fn apply<T: Scalar>(
    m: MatrixRef<'_, T>,
    d: &Col<T>,
    p: usize,
    basis: &[Var],
    x: &Col<T>,
) -> Col<T> {
    let dim = m.nrows();
    let mut y = Col::<T>::zeros(dim);
    let axpy = |y: &mut Col<T>, col: faer::ColRef<'_, T>, f: T| {
        for i in 0..dim {
            let v = y[i] - col[i] * f;
            y[i] = v;
        }
    };
    let axpy_m = |y: &mut Col<T>, j: usize, f: T| match m {
        MatrixRef::Dense(m) => axpy(y, m.col(j), f),
        MatrixRef::Sparse(_) => m.for_col(j, |i, mij| {
            let v = y[i] - mij * f;
            y[i] = v;
        }),
    };
    for (r, v) in basis.iter().enumerate() {
        let xr = x[r];
        if xr == T::zero() {
            continue;
        }
        match *v {
            Var::U(j) => axpy_m(&mut y, j, xr),
            Var::Z(j) => axpy_m(&mut y, p + j, xr),
            Var::Lambda => axpy(&mut y, d.as_ref(), xr),
            Var::W(i) => y[p + i] += xr,
            Var::Artificial(k) => y[k] += xr,
        }
    }
    y
}

/// The row an identity-column variable covers, or `None` for a matrix column.
fn identity_row(p: usize, v: Var) -> Option<usize> {
    match v {
        Var::W(i) => Some(p + i),
        Var::Artificial(k) => Some(k),
        _ => None,
    }
}

/// What a basis representation offers the pivoting core.
pub(crate) trait BasisFactor<T: Scalar> {
    /// Rebuilds for `basis` (one variable per position); returns a 1-norm
    /// condition number estimate, or `None` if the basis is numerically singular.
    fn refactor(&mut self, m: MatrixRef<'_, T>, d: &Col<T>, p: usize, basis: &[Var])
        -> Option<f64>;
    /// `B^{-1} a`, indexed by basis position.
    fn solve(&self, a: &Col<T>) -> Col<T>;
    /// [`Self::solve`] written into `out` (of length `p + n`). The block basis
    /// overrides it to solve with buffers it keeps: a pivot then allocates
    /// nothing (faer's aligned allocations were a third of a small path).
    fn solve_into(&self, a: &Col<T>, out: &mut Col<T>) {
        *out = self.solve(a);
    }
    /// `B^{-1} a_v`.
    fn column(&self, m: MatrixRef<'_, T>, d: &Col<T>, p: usize, v: Var) -> Col<T> {
        self.solve(&var_column(m, d, p, v))
    }
    /// [`Self::column`] written into `out` (see [`Self::solve_into`]).
    fn column_into(&self, m: MatrixRef<'_, T>, d: &Col<T>, p: usize, v: Var, out: &mut Col<T>) {
        *out = self.column(m, d, p, v);
    }
    /// `B^{-1} a` and `B x` together (`x` indexed by basis position, `B x` by
    /// system row). Representations that keep the basic columns override it and
    /// stream them once for both products (the residual at a breakpoint then
    /// costs no extra pass over the matrix).
    #[allow(clippy::too_many_arguments)]
    fn solve_and_apply(
        &self,
        m: MatrixRef<'_, T>,
        d: &Col<T>,
        p: usize,
        basis: &[Var],
        a: &Col<T>,
        x: &Col<T>,
    ) -> (Col<T>, Col<T>) {
        (self.solve(a), apply(m, d, p, basis, x))
    }
    /// [`Self::solve_and_apply`] written into `sol` and `bx` (see [`Self::solve_into`]).
    #[allow(clippy::too_many_arguments)]
    fn solve_and_apply_into(
        &self,
        m: MatrixRef<'_, T>,
        d: &Col<T>,
        p: usize,
        basis: &[Var],
        a: &Col<T>,
        x: &Col<T>,
        sol: &mut Col<T>,
        bx: &mut Col<T>,
    ) {
        (*sol, *bx) = self.solve_and_apply(m, d, p, basis, a, x);
    }
    /// `B^{-1} a` and `B^{-1} b` into `out_a`, `out_b` (resized to `dim`
    /// if they are not): representations that can override it solve both in
    /// one sweep (the block basis: two-column products; the results then
    /// differ from [`Self::solve_into`]'s in the rounding).
    fn solve2_into(&self, a: &Col<T>, b: &Col<T>, out_a: &mut Col<T>, out_b: &mut Col<T>) {
        self.solve_into(a, out_a);
        self.solve_into(b, out_b);
    }
    /// `(B^{-1} a, B^{-1} b)`, consuming `a` and `b`: representations that
    /// can override it to solve both in one sweep, in place (each result as
    /// from its own [`Self::solve`]).
    fn solve2(&self, a: Col<T>, b: Col<T>) -> (Col<T>, Col<T>) {
        (self.solve(&a), self.solve(&b))
    }
    /// `B^{-1} e_k`.
    fn unit(&self, k: usize) -> Col<T>;
    /// Rows `rows` of `B^{-1}` (read by system row, see [`InverseRows`]), if
    /// this representation computes them cheaper than the columns `B^{-1}
    /// e_k` the lexicographic rule otherwise reads one by one; `None`: read
    /// columns.
    fn inverse_rows(&self, rows: &[usize]) -> Option<InverseRows<'_, T>> {
        let _ = rows;
        None
    }
    /// [`Self::inverse_rows`] as they were computed before issue 15's
    /// change (each row in full, in system order, through faer's solves,
    /// its noise set to zero): the reference of the lexicographic check
    /// ([`lex`]). `None` where [`Self::inverse_rows`] is `None`.
    fn inverse_rows_full(&self, rows: &[usize]) -> Option<Vec<Col<T>>> {
        let _ = rows;
        None
    }
    /// Asks the representation to refine its solves itself (one step of
    /// iterative refinement inside every `B^{-1} a`) while `on`; returns true
    /// if it does, false if the caller must refine (the default: never).
    fn set_refine(&mut self, on: bool) -> bool {
        let _ = on;
        false
    }
    /// Whether a refactorisation is due after `since` pivots of updates, with
    /// the user's refactorisation period `period` (`None`: the default, see
    /// [`crate::Settings::refactor_period`]).
    fn refactor_due(&self, since: usize, period: Option<usize>) -> bool {
        since >= period.unwrap_or(DEFAULT_REFACTOR_PERIOD)
    }
    /// Whether the last solve was refined inside, when [`Self::set_refine`]
    /// asked for it (a representation may skip refinement that does nothing).
    /// Default: true.
    fn last_solve_refined(&self) -> bool {
        true
    }
    /// `B^{-T} c` for `c` indexed by basis position; the result is indexed by system row.
    fn solve_transpose(&self, c: &Col<T>) -> Col<T>;
    /// An estimate of `cond_1(B D)` for the current (possibly updated)
    /// factor, `D` scaling the basic columns to 1-norm about one as
    /// [`Self::refactor`] does: Hager's estimate of `|(B D)^{-1}|_1`
    /// (Higham's variant, [`crate::sparse_lu::hager_inverse_norm1`]) from at
    /// most six solves and five transpose solves, times `|B D|_1`. A lower
    /// bound, where [`Self::refactor`]'s block estimate is an upper one; the
    /// two agree within a small factor. Not finite if a solve is not.
    fn condition(&self, m: MatrixRef<'_, T>, d: &Col<T>, p: usize, basis: &[Var]) -> f64 {
        let dim = basis.len();
        // D^{-1} = diag(scale): the basic columns' 1-norms rounded to powers of two
        let norms: Vec<f64> = basis
            .iter()
            .map(|&v| match v {
                Var::W(_) | Var::Artificial(_) => 1.0,
                Var::Lambda => (0..dim).map(|i| d[i].to_f64().abs()).sum(),
                Var::U(j) | Var::Z(j) => {
                    let col = if let Var::U(_) = v { j } else { p + j };
                    let mut s = 0.0f64;
                    m.for_col(col, |_, x| s += x.to_f64().abs());
                    s
                }
            })
            .collect();
        let scale: Vec<T> = norms.iter().map(|&s| T::from_f64(pow2(s))).collect();
        let norm_bd = norms
            .iter()
            .zip(&scale)
            .fold(0.0f64, |a, (&s, c)| a.max(s / c.to_f64()));
        // (B D)^{-1} x = D^{-1} B^{-1} x; its transpose s -> B^{-T} (D^{-1} s)
        // (the solves into a kept buffer: no allocation with the block basis)
        let buf = RefCell::new(Col::<T>::zeros(dim));
        let inv_norm = crate::sparse_lu::hager_inverse_norm1(
            dim,
            |x: &mut Col<T>| {
                let mut y = buf.borrow_mut();
                self.solve_into(x, &mut y);
                core::mem::swap(x, &mut *y);
                for (v, c) in x.iter_mut().zip(&scale) {
                    *v *= *c;
                }
            },
            |s: &mut Col<T>| {
                for (v, c) in s.iter_mut().zip(&scale) {
                    *v *= *c;
                }
                *s = self.solve_transpose(s);
            },
        );
        norm_bd * inv_norm
    }
    /// The variable at position `r` (now `leaving`) is replaced by `entering`,
    /// with `y = B^{-1} a_entering` (so `y[r]` is the pivot).
    #[allow(clippy::too_many_arguments)]
    fn replace(
        &mut self,
        m: MatrixRef<'_, T>,
        d: &Col<T>,
        p: usize,
        r: usize,
        leaving: Var,
        entering: Var,
        y: &Col<T>,
    ) -> bool;
}

fn norm1<T: Scalar>(a: MatRef<'_, T>) -> f64 {
    col_norms1(a).into_iter().fold(0.0f64, f64::max)
}

/// `f` on the entries of column `j` in order, over a slice when the column
/// is contiguous (the same values either way: the refactorisations' passes
/// without faer's index checks, issue 20).
#[inline]
fn for_col<T: Scalar>(a: MatRef<'_, T>, j: usize, mut f: impl FnMut(usize, T)) {
    match a.col(j).try_as_col_major() {
        Some(c) => c.as_slice().iter().enumerate().for_each(|(i, &v)| f(i, v)),
        None => (0..a.nrows()).for_each(|i| f(i, a[(i, j)])),
    }
}

/// Inverts a square matrix by LU with partial pivoting after scaling its
/// columns by `1 / scale[j]` (powers of two, exact); `None` if numerically
/// singular. Returns `B^{-1}` and the 1-norm condition number of the scaled
/// matrix `B D`, `D = diag(1 / scale)`.
///
/// Why the scaled matrix: a basis mixes columns of very different sizes (the
/// parameter column `-d` has a 1-norm of order `n`, a unit column 1), and
/// `cond(B)` grows with that ratio although no solve loses accuracy to it
/// (partial pivoting is blind to column scaling; `x = D (B D)^{-1} a` and the
/// relative error of each component is governed by `cond(B D)`). With columns
/// of unit 1-norm, `cond_1(B D)` is within a factor `dim` of the smallest over
/// all column scalings (van der Sluis). The singularity test on the pivots of
/// `U` is made on the scaled matrix for the same reason.
fn invert<T: Scalar>(b: MatRef<'_, T>, scale: &[f64]) -> Option<(Mat<T>, f64)> {
    invert_par(b, scale, par_for(crate::linalg::inverse_flops(b.nrows())))
}

/// [`invert`] with the given parallelism (see [`crate::linalg::inverse_par`]).
fn invert_par<T: Scalar>(b: MatRef<'_, T>, scale: &[f64], par: faer::Par) -> Option<(Mat<T>, f64)> {
    let dim = b.nrows();
    let sc: Vec<T> = scale.iter().map(|&s| T::from_f64(pow2(s))).collect();
    let mut bs = Mat::<T>::zeros(dim, dim);
    for (j, &s) in sc.iter().enumerate() {
        let dst = slice_mut_of_mat(bs.as_mut(), j);
        for_col(b, j, |i, v| dst[i] = v / s);
    }
    let (mut inv, umax, umin) = crate::linalg::inverse_par(bs.as_ref(), par)?;
    if dim > 0 && umin <= umax * T::eps().to_f64() * dim as f64 {
        return None;
    }
    let cond = norm1(bs.as_ref()) * norm1(inv.as_ref());
    if !cond.is_finite() {
        return None;
    }
    // B^{-1} = D (B D)^{-1}: row j divided by scale[j]
    for c in 0..dim {
        for (v, s) in slice_mut_of_mat(inv.as_mut(), c).iter_mut().zip(&sc) {
            *v /= *s;
        }
    }
    Some((inv, cond))
}

/// The 1-norm of each column.
fn col_norms1<T: Scalar>(a: MatRef<'_, T>) -> Vec<f64> {
    (0..a.ncols())
        .map(|j| {
            let mut s = 0.0f64;
            for_col(a, j, |_, v| s += v.to_f64().abs());
            s
        })
        .collect()
}

/// Column `j` of an owned (column-major) matrix, as a mutable slice.
#[inline]
fn slice_mut_of_mat<T: Scalar>(m: MatMut<'_, T>, j: usize) -> &mut [T] {
    m.col_mut(j)
        .try_as_col_major_mut()
        .expect("an owned matrix is column-major")
        .as_slice_mut()
}

/// `m[0..k, col] += u[0..k] * f`, over a contiguous column (vectorises).
#[inline]
fn col_axpy<T: Scalar>(m: &mut Mat<T>, col: usize, u: &[T], f: T) {
    let k = u.len();
    let dst = m
        .col_mut(col)
        .subrows_mut(0, k)
        .try_as_col_major_mut()
        .expect("an owned matrix is column-major")
        .as_slice_mut();
    for (d, &x) in dst.iter_mut().zip(u) {
        *d += x * f;
    }
}
