//! A sparse LU factorisation of a square CSC matrix (faer's simplicial LU
//! with a COLAMD column order and partial pivoting), its solves, and a
//! condition estimate by Hager's method. A kernel of its own: the sparse
//! basis ([`crate::basis`]) refactorises with it, and [`crate::matrix::Csc`]
//! estimates its condition with it, so the matrix does not know the basis.

use crate::linalg::col_slice_mut;
use crate::scalar::Scalar;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::perm::PermRef;
use faer::sparse::linalg::lu::simplicial::{self, SimplicialLu};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuSymbolicParams};
use faer::sparse::linalg::triangular_solve;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Col, Conj, MatMut, Par};

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
    pub(crate) row_inv: Vec<usize>,
    pub(crate) col_fwd: Vec<usize>,
    pub(crate) col_inv: Vec<usize>,
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
    pub(crate) fn factor_nnz(&self) -> usize {
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
        let xo = col_slice_mut(x);
        // in the factors' row order in a scratch vector (one gather), the
        // solution scattered back through the column order (one pass)
        let mut xs: Vec<T> = self.row_fwd.iter().map(|&p| xo[p]).collect();
        let (l, u) = (self.lu.l_factor_unsorted(), self.lu.u_factor_unsorted());
        {
            let xs = &mut xs[..];
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
        for (o, &p) in xo.iter_mut().zip(&self.col_inv) {
            *o = xs[p];
        }
    }

    /// `x <- A^{-1} x` and `y <- A^{-1} y` in one sweep over the factors:
    /// each column sees the operations of its own [`Self::solve_in_place`]
    /// (the same results), the factors' indices and values are read once.
    pub(crate) fn solve2_in_place(&self, xo: &mut [T], yo: &mut [T], tmp: &mut Vec<T>) {
        debug_assert!(xo.len() == self.dim && yo.len() == self.dim);
        // both vectors in the factors' row order, side by side in `tmp`
        // (one gather each; the solution is scattered back through the
        // column order, one pass each)
        let dim = self.dim;
        tmp.clear();
        tmp.extend(self.row_fwd.iter().map(|&p| xo[p]));
        tmp.extend(self.row_fwd.iter().map(|&p| yo[p]));
        let (x, y) = tmp.split_at_mut(dim);
        let (l, u) = (self.lu.l_factor_unsorted(), self.lu.u_factor_unsorted());
        // unit lower L, its diagonal stored first in each column
        for j in 0..dim {
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
        for j in (0..dim).rev() {
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
        for (o, &p) in xo.iter_mut().zip(&self.col_inv) {
            *o = x[p];
        }
        for (o, &p) in yo.iter_mut().zip(&self.col_inv) {
            *o = y[p];
        }
    }

    /// `x <- A^{-T} x` (the triangular solves as faer's, with the loops of
    /// [`Self::solve_transpose_permuted_cols`]: the same bits).
    pub(crate) fn solve_transpose_in_place(&self, x: &mut Col<T>) {
        let mut tmp = Vec::with_capacity(self.dim);
        Self::permute(x, &self.col_fwd, &mut tmp);
        if self.dim > 0 {
            self.transpose_sweep1(col_slice_mut(x));
        }
        Self::permute(x, &self.row_inv, &mut tmp);
    }

    /// `X <- A^{-T} X`, all columns in one sweep over the factors, without
    /// the permutation passes of [`Self::solve_transpose_in_place`]: `x` holds the
    /// right-hand sides `b` in the factors' column order (`x[i] =
    /// b[col_fwd[i]]`, so `b[j]` at `col_inv[j]`), and on return the
    /// solutions in the factors' row order (`(A^{-T} b)[i] = x[row_inv[i]]`).
    /// For many sparse right-hand sides (the rows of `B^{-1}` the
    /// lexicographic ratio test asks for) the permutations were a quarter of
    /// the solve.
    pub(crate) fn solve_transpose_permuted_mat(&self, mut x: MatMut<'_, T>) {
        debug_assert_eq!(x.nrows(), self.dim);
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
    }

    /// [`Self::solve_transpose_permuted_mat`] on `x`, the right-hand sides
    /// stored one after the other (`x.len()` a multiple of the order), with
    /// loops of its own: two columns per sweep over the factors (indices and
    /// values read once for both). Each column sees the operations of
    /// faer's transposed solves in their order (the products of a column of
    /// `U` or `L` summed from zero in faer's order, then `(x_j - sum) *
    /// recip(u_jj)`): the same bits
    /// (`tests::own_transpose_solve_gives_faers_bits`). faer's generic
    /// kernel cost about 13 instructions per stored entry and column on the
    /// rows of `B^-1` of the lexicographic rule, these loops about 9
    /// (issue 15).
    pub(crate) fn solve_transpose_permuted_cols(&self, x: &mut [T]) {
        let dim = self.dim;
        if dim == 0 {
            return;
        }
        debug_assert_eq!(x.len() % dim, 0);
        let mut rest = x;
        while rest.len() >= 2 * dim {
            let (pair, tail) = rest.split_at_mut(2 * dim);
            let (x0, x1) = pair.split_at_mut(dim);
            self.transpose_sweep2(x0, x1);
            rest = tail;
        }
        if !rest.is_empty() {
            self.transpose_sweep1(rest);
        }
    }

    /// One column of [`Self::solve_transpose_permuted_cols`].
    fn transpose_sweep1(&self, x: &mut [T]) {
        let dim = self.dim;
        assert_eq!(x.len(), dim);
        let (l, u) = (self.lu.l_factor_unsorted(), self.lu.u_factor_unsorted());
        // U' x = b: forward over the columns of U, diagonal stored last
        for j in 0..dim {
            let (rows, vals) = (u.row_idx_of_col_raw(j), u.val_of_col(j));
            let last = vals.len() - 1;
            let mut acc = T::zero();
            for (&i, &uij) in rows[..last].iter().zip(&vals[..last]) {
                acc += uij * x[i];
            }
            let d = <T as faer::traits::ComplexField>::recip_impl(&vals[last]);
            x[j] = (x[j] - acc) * d;
        }
        // L' x = b: backward over the columns of unit L, diagonal stored
        // first, the others summed from the end of the column
        for j in (0..dim).rev() {
            let (rows, vals) = (l.row_idx_of_col_raw(j), l.val_of_col(j));
            let mut acc = T::zero();
            for (&i, &lij) in rows[1..].iter().zip(&vals[1..]).rev() {
                acc += lij * x[i];
            }
            x[j] -= acc;
        }
    }

    /// Two columns of [`Self::solve_transpose_permuted_cols`] in one sweep
    /// (each with the operations of its own [`Self::transpose_sweep1`]).
    fn transpose_sweep2(&self, x0: &mut [T], x1: &mut [T]) {
        let dim = self.dim;
        assert!(x0.len() == dim && x1.len() == dim);
        let (l, u) = (self.lu.l_factor_unsorted(), self.lu.u_factor_unsorted());
        for j in 0..dim {
            let (rows, vals) = (u.row_idx_of_col_raw(j), u.val_of_col(j));
            let last = vals.len() - 1;
            let (mut a0, mut a1) = (T::zero(), T::zero());
            for (&i, &uij) in rows[..last].iter().zip(&vals[..last]) {
                a0 += uij * x0[i];
                a1 += uij * x1[i];
            }
            let d = <T as faer::traits::ComplexField>::recip_impl(&vals[last]);
            x0[j] = (x0[j] - a0) * d;
            x1[j] = (x1[j] - a1) * d;
        }
        for j in (0..dim).rev() {
            let (rows, vals) = (l.row_idx_of_col_raw(j), l.val_of_col(j));
            let (mut a0, mut a1) = (T::zero(), T::zero());
            for (&i, &lij) in rows[1..].iter().zip(&vals[1..]).rev() {
                a0 += lij * x0[i];
                a1 += lij * x1[i];
            }
            x0[j] -= a0;
            x1[j] -= a1;
        }
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
    // (one sign vector for every iteration: the end-of-path estimate of the
    // pivoting core runs this on small bases, where allocations show)
    let mut s = Col::<T>::zeros(dim);
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
        for i in 0..dim {
            s[i] = if x[i] >= T::zero() {
                T::one()
            } else {
                -T::one()
            };
        }
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
        x.fill(T::zero());
        x[j] = T::one();
    }
    // Higham's safeguard: b_i = (-1)^i (1 + i / (n - 1))
    for i in 0..dim {
        let v = 1.0 + i as f64 / (dim.max(2) - 1) as f64;
        x[i] = T::from_f64(if i % 2 == 0 { v } else { -v });
    }
    solve(&mut x);
    let alt = 2.0 * norm1(&x) / (3.0 * dim as f64);
    if !alt.is_finite() {
        return f64::INFINITY;
    }
    est.max(alt)
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

    /// A generator of test numbers (xorshift), in `[0, 1)`.
    fn rng(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed | 1;
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// A random sparse square matrix in CSC form, a nonzero diagonal (so
    /// the factorisation succeeds) and about `fill` other entries a column.
    fn random_csc<T: Scalar>(
        dim: usize,
        fill: f64,
        next: &mut impl FnMut() -> f64,
    ) -> (Vec<usize>, Vec<usize>, Vec<T>) {
        let (mut ptr, mut idx, mut val) = (vec![0], Vec::new(), Vec::new());
        for j in 0..dim {
            for i in 0..dim {
                if i == j || next() < fill / dim as f64 {
                    idx.push(i);
                    let v = if i == j {
                        0.5 + next()
                    } else {
                        4.0 * next() - 2.0
                    };
                    val.push(T::from_f64(v));
                }
            }
            ptr.push(idx.len());
        }
        (ptr, idx, val)
    }

    /// [`SparseFactor::solve_transpose_permuted_cols`] gives faer's bits
    /// ([`SparseFactor::solve_transpose_permuted_mat`]) on random factors and
    /// right-hand sides of one to five columns: dense, sparse (exact zeros
    /// and negative zeros), in f64, f32 and fx128.
    #[test]
    fn own_transpose_solve_gives_faers_bits() {
        fn check<T: Scalar>(seed: u64) -> usize {
            let mut next = rng(seed);
            let mut compared = 0;
            for case in 0..60 {
                let dim = 1 + case % 37;
                let (ptr, idx, val) = random_csc::<T>(dim, 3.0, &mut next);
                let Some(f) = SparseFactor::new(dim, &ptr, &idx, &val) else {
                    continue;
                };
                let k = 1 + case % 5;
                let mut b = Mat::<T>::zeros(dim, k);
                for c in 0..k {
                    for i in 0..dim {
                        let u = next();
                        b[(i, c)] = match (case + c) % 3 {
                            0 => T::from_f64(2.0 * u - 1.0),
                            1 if u < 0.8 => T::zero(),
                            1 if u < 0.85 => -T::zero(),
                            _ => T::from_f64(u - 0.5),
                        };
                    }
                }
                let mut ours: Vec<T> = (0..k)
                    .flat_map(|c| (0..dim).map(move |i| (c, i)))
                    .map(|(c, i)| b[(i, c)])
                    .collect();
                f.solve_transpose_permuted_mat(b.as_mut());
                f.solve_transpose_permuted_cols(&mut ours);
                for c in 0..k {
                    for i in 0..dim {
                        let (a, o) = (b[(i, c)], ours[c * dim + i]);
                        assert!(
                            a == o && same_sign(a, o),
                            "{}: case {case}, column {c}, entry {i}: faer {:e}, ours {:e}",
                            T::NAME,
                            a.to_f64(),
                            o.to_f64()
                        );
                        compared += 1;
                    }
                }
            }
            compared
        }
        assert!(check::<f64>(7) > 1000);
        assert!(check::<f32>(11) > 1000);
        assert!(check::<faer::fx128>(13) > 1000);
    }

    /// The same sign (of a zero too: `to_f64` keeps it).
    fn same_sign<T: Scalar>(a: T, b: T) -> bool {
        a.to_f64().is_sign_negative() == b.to_f64().is_sign_negative()
    }
}
