//! The block basis's matrix-vector product on the calling thread, over
//! slices, compiled for the machine's vector width through pulp's runtime
//! dispatch (issue 20).
//!
//! faer's matrix-vector product pays a fixed cost per call (dispatch,
//! checks) that shows at the orders of an everyday block (tens): on the MPC
//! loop of `docs/performance.md` (a block of order about 25 in 50 rows) a
//! `solve_into` took 9.6 k instructions with it and 7.7 k with this loop
//! (callgrind, 363 calls). Rows go in blocks of 16 whose sums stay in registers
//! over all the columns; each entry is `y_i = ((a_i0 x_0) + a_i1 x_1) +
//! ...` in the order of the columns, fixed by the code, so the result does
//! not depend on the vector width (no FMA contraction: Rust does not
//! contract). (Two right-hand sides stay with faer's product: its small
//! kernels beat both a two-column version of these loops and a
//! column-by-column `axpy`, measured 2.7 k against 3.0 k and 4.6 k
//! instructions a call.)

use super::super::*;

/// Column `j` of a column-major view, as a slice.
#[inline(always)]
fn col<'a, T: Scalar>(a: MatRef<'a, T>, j: usize) -> &'a [T] {
    a.col(j)
        .try_as_col_major()
        .expect("the block basis's matrices are column-major")
        .as_slice()
}

/// `y = A x` (`y` of `A.nrows()` entries, `x` of `A.ncols()`).
pub(super) fn gemv<T: Scalar>(a: MatRef<'_, T>, x: &[T], y: &mut [T]) {
    pulp::Arch::new().dispatch(Gemv { a, x, y });
}

struct Gemv<'a, T: Scalar> {
    a: MatRef<'a, T>,
    x: &'a [T],
    y: &'a mut [T],
}

impl<T: Scalar> pulp::WithSimd for Gemv<'_, T> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let Gemv { a, x, y } = self;
        let (m, k) = (a.nrows(), a.ncols());
        let x = &x[..k];
        // rows in blocks of `R` with their sums in registers over all
        // columns (a column-by-column axpy loads and stores `y` per column)
        const R: usize = 16;
        let mut i0 = 0;
        while i0 + R <= m {
            let mut acc = [T::zero(); R];
            for (j, &f) in x.iter().enumerate() {
                let c = &col(a, j)[i0..i0 + R];
                for l in 0..R {
                    acc[l] += c[l] * f;
                }
            }
            y[i0..i0 + R].copy_from_slice(&acc);
            i0 += R;
        }
        // the last rows column by column (the same order of operations)
        let tail = &mut y[i0..m];
        tail.fill(T::zero());
        for (j, &f) in x.iter().enumerate() {
            for (d, &v) in tail.iter_mut().zip(&col(a, j)[i0..m]) {
                *d += v * f;
            }
        }
    }
}
