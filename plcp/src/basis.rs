//! The basis factorisation behind one small interface.
//!
//! The pivoting core asks only four things of a basis: solve `B y = a` for an
//! entering column, read a row of `B^{-1}` (the lexicographic rule), replace one
//! column (a pivot), and rebuild from scratch (a refactorisation, which also
//! estimates the condition number). This file holds the dense explicit-inverse
//! implementation: `O(m^2)` per pivot, an LU with partial pivoting (faer) at every
//! refactorisation.

use crate::scalar::Scalar;
use faer::linalg::solvers::DenseSolveCore;
use faer::{Col, Mat, MatRef};

/// What a basis representation offers the pivoting core.
pub(crate) trait BasisFactor<T: Scalar> {
    /// Rebuilds from the basis matrix; returns the 1-norm condition number
    /// estimate, or `None` if the matrix is numerically singular.
    fn refactor(&mut self, b: MatRef<'_, T>) -> Option<f64>;
    /// `B^{-1} a`.
    fn solve(&self, a: &Col<T>) -> Col<T>;
    /// `B^{-1} M[:, j]` for a column of a dense matrix.
    fn solve_mat_col(&self, m: MatRef<'_, T>, j: usize) -> Col<T>;
    /// `B^{-1} e_k`.
    fn solve_unit(&self, k: usize) -> Col<T>;
    /// Entry `(i, k)` of `B^{-1}`.
    fn inv_entry(&self, i: usize, k: usize) -> T;
    /// Replaces the basic column at position `r`, given `y = B^{-1} a_new`.
    fn replace(&mut self, r: usize, y: &Col<T>);
}

/// Dense explicit inverse with product-form (rank-one) updates.
pub(crate) struct DenseInverse<T: Scalar> {
    inv: Mat<T>,
}

impl<T: Scalar> DenseInverse<T> {
    pub(crate) fn new(dim: usize) -> Self {
        Self {
            inv: Mat::identity(dim, dim),
        }
    }
}

fn norm1<T: Scalar>(a: MatRef<'_, T>) -> f64 {
    let mut best = 0.0f64;
    for j in 0..a.ncols() {
        let mut s = 0.0f64;
        for i in 0..a.nrows() {
            s += a[(i, j)].to_f64().abs();
        }
        best = best.max(s);
    }
    best
}

impl<T: Scalar> BasisFactor<T> for DenseInverse<T> {
    fn refactor(&mut self, b: MatRef<'_, T>) -> Option<f64> {
        let dim = b.nrows();
        if dim == 0 {
            self.inv = Mat::zeros(0, 0);
            return Some(1.0);
        }
        let lu = b.partial_piv_lu();
        // a zero (or non-finite) pivot of U means a singular basis
        let u = lu.U();
        let umax = (0..dim).fold(0.0f64, |a, k| a.max(u[(k, k)].to_f64().abs()));
        for k in 0..dim {
            let v = u[(k, k)].to_f64().abs();
            if !v.is_finite() || v == 0.0 || v <= umax * T::eps().to_f64() * dim as f64 {
                return None;
            }
        }
        let inv = lu.inverse();
        let cond = norm1(b) * norm1(inv.as_ref());
        if !cond.is_finite() {
            return None;
        }
        self.inv = inv;
        Some(cond)
    }

    fn solve(&self, a: &Col<T>) -> Col<T> {
        self.inv.as_ref() * a.as_ref()
    }

    fn solve_mat_col(&self, m: MatRef<'_, T>, j: usize) -> Col<T> {
        self.inv.as_ref() * m.col(j)
    }

    fn solve_unit(&self, k: usize) -> Col<T> {
        self.inv.col(k).to_owned()
    }

    fn inv_entry(&self, i: usize, k: usize) -> T {
        self.inv[(i, k)]
    }

    fn replace(&mut self, r: usize, y: &Col<T>) {
        let dim = self.inv.nrows();
        let piv = y[r];
        for j in 0..dim {
            let f = self.inv[(r, j)] / piv;
            if f != T::zero() {
                for i in 0..dim {
                    if i != r {
                        let v = self.inv[(i, j)] - y[i] * f;
                        self.inv[(i, j)] = v;
                    }
                }
            }
            self.inv[(r, j)] = f;
        }
    }
}
