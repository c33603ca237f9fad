//! The pending rank-one update of the block basis's `S^{-1}` and the one
//! pass over `S^{-1}` that applies it (vectorised through pulp).

use super::super::*;

/// A rank-one update of `S^{-1}` decided by a pivot and not yet applied.
///
/// Each kind changes every column of `S^{-1}` by a multiple of one vector, the
/// multiple read off that column alone, so the update streams `S^{-1}` once,
/// column by column; the next solve `S^{-1} a_R` (always the next thing the
/// pivoting core asks for) accumulates its product in the same pass. Applied
/// eagerly, the update and the solve were three passes over `S^{-1}` (four
/// when the row `c' S^{-1}` had to be formed first); `S^{-1}` of order 500 is
/// 2 MB, beyond the core's L2 cache, so passes are what a pivot costs.
pub(super) enum Pending<T: Scalar> {
    /// Block column `b` replaced; `y = S^{-1} a_new` (old inverse), pivot `y[b]`:
    /// column `j` gets `-y f_j` and then entry `b` set to `f_j`, `f_j = S^{-1}[b, j] / y[b]`.
    Column { b: usize, y: Vec<T> },
    /// Bordered by a new block row and column (order `k - 1` to `k`): `c` is
    /// the new row's entries in the old columns, `y = S^{-1} a_new` (old),
    /// `sigma = s - c' y` the pivot: column `j < k - 1` gets `y g_j / sigma`
    /// and the new row's entry `-g_j / sigma`, `g_j = c' S^{-1}[:, j]`.
    Grow { c: Vec<T>, y: Vec<T>, sigma: T },
    /// Block row `a` now stands for another system row, whose entries in the
    /// block columns are `c`; `u = S^{-1}[:, a]` (old) and `ga = c' u`: column
    /// `j` gets `-u (g_j - [j = a]) / ga`, `g_j = c' S^{-1}[:, j]`.
    Row {
        a: usize,
        c: Vec<T>,
        u: Vec<T>,
        ga: T,
    },
}

/// `y += x f` over two slices of equal length (vectorised in [`FlushPass`]).
#[inline(always)]
pub(super) fn axpy_slice<T: Scalar>(y: &mut [T], x: &[T], f: T) {
    for (d, &v) in y.iter_mut().zip(x) {
        *d += v * f;
    }
}

/// `x' y` with eight partial sums (a single running sum would not vectorise:
/// floating-point addition is not reassociated).
#[inline(always)]
pub(super) fn dot_slice<T: Scalar>(x: &[T], y: &[T]) -> T {
    let mut acc = [T::zero(); 8];
    let (xh, xt) = x.split_at(x.len() - x.len() % 8);
    let (yh, yt) = y.split_at(xh.len());
    for (a, b) in xh.chunks_exact(8).zip(yh.chunks_exact(8)) {
        for l in 0..8 {
            acc[l] += a[l] * b[l];
        }
    }
    let mut s = ((acc[0] + acc[4]) + (acc[1] + acc[5])) + ((acc[2] + acc[6]) + (acc[3] + acc[7]));
    for (a, b) in xt.iter().zip(yt) {
        s += *a * *b;
    }
    s
}

/// The pending update applied in one pass over `S^{-1}` (see [`Pending`]),
/// `acc += S^{-1} ar` accumulated column by column when given.
///
/// Run through pulp's runtime dispatch: the crate is compiled for the baseline
/// target, so these loops would otherwise vectorise at SSE2 width; inlined into
/// pulp's target-feature functions they use the machine's AVX2 (FMA is not
/// contracted: the same products and sums as the plain loops).
/// Only the order of operations is fixed by the code, so the result is the
/// same on every machine. One pass covers the columns `j0..j0 + sinv.ncols()`
/// of `S^{-1}` (`sinv`: those columns, rows `0..k`).
pub(super) struct FlushPass<'a, T: Scalar> {
    pub(super) sinv: MatMut<'a, T>,
    pub(super) j0: usize,
    pub(super) pending: &'a Pending<T>,
    pub(super) k: usize,
    pub(super) ar: Option<&'a [T]>,
    pub(super) acc: Option<&'a mut [T]>,
}

impl<T: Scalar> pulp::WithSimd for FlushPass<'_, T> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let FlushPass {
            mut sinv,
            j0,
            pending,
            k,
            ar,
            mut acc,
        } = self;
        let cols = j0..j0 + sinv.ncols();
        let mut accumulate = |col: &[T], j: usize| {
            if let (Some(acc), Some(ar)) = (acc.as_deref_mut(), ar) {
                axpy_slice(acc, col, ar[j]);
            }
        };
        match pending {
            Pending::Column { b, y } => {
                let piv = y[*b];
                for j in cols {
                    let col = column_slice(sinv.rb_mut(), j - j0);
                    let f = col[*b] / piv;
                    axpy_slice(col, y, -f);
                    col[*b] = f;
                    accumulate(col, j);
                }
            }
            Pending::Grow { c, y, sigma } => {
                let old = k - 1;
                for j in cols {
                    let col = column_slice(sinv.rb_mut(), j - j0);
                    if j < old {
                        let f = dot_slice(c, &col[..old]) / *sigma;
                        axpy_slice(&mut col[..old], y, f);
                        col[old] = -f;
                    } else {
                        // the new column
                        for (e, yb) in col.iter_mut().zip(y.iter()) {
                            *e = -*yb / *sigma;
                        }
                        col[old] = T::one() / *sigma;
                    }
                    accumulate(col, j);
                }
            }
            Pending::Row { a, c, u, ga } => {
                for j in cols {
                    let col = column_slice(sinv.rb_mut(), j - j0);
                    let g = dot_slice(c, col);
                    let f = if j == *a { g - T::one() } else { g } / *ga;
                    axpy_slice(col, u, -f);
                    accumulate(col, j);
                }
            }
        }
    }
}

/// Whether the block basis's column refinement is paused (see
/// Column `j` of a view into an owned (column-major) matrix, as a slice.
#[inline(always)]
pub(super) fn column_slice<T: Scalar>(m: MatMut<'_, T>, j: usize) -> &mut [T] {
    m.col_mut(j)
        .try_as_col_major_mut()
        .expect("an owned matrix is column-major")
        .as_slice_mut()
}
