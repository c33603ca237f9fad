//! Dense kernels: faer for `f32`/`f64`; for `fx128`, where faer 0.24's matrix
//! multiply micro-kernel panics on non-native types outside its own tests (so its
//! LU `inverse()` and `solve()` do too), the same operations written plainly.

use crate::scalar::Scalar;
use faer::linalg::solvers::Solve;
use faer::reborrow::ReborrowMut;
use faer::{Col, Mat, MatRef};

/// The entries of a contiguous column (an owned `Col` always is): the
/// kernels read and write columns over slices, since faer's checked
/// indexing costs an assert per entry.
pub(crate) fn col_slice<T: Scalar>(c: &Col<T>) -> &[T] {
    c.as_ref()
        .try_as_col_major()
        .expect("a column is contiguous")
        .as_slice()
}

/// The entries of a contiguous column, mutable ([`col_slice`]).
pub(crate) fn col_slice_mut<T: Scalar>(c: &mut Col<T>) -> &mut [T] {
    c.as_mut()
        .try_as_col_major_mut()
        .expect("a column is contiguous")
        .as_slice_mut()
}

/// `A^{-1}` by LU with partial pivoting, with the largest and smallest pivot
/// magnitudes of `U`; `None` if a pivot is zero or non-finite.
/// On faer's global parallelism from order 645 ([`inverse_flops`]), on the
/// calling thread below.
pub fn inverse<T: Scalar>(a: MatRef<'_, T>) -> Option<(Mat<T>, f64, f64)> {
    inverse_par(a, par_for(inverse_flops(a.nrows())))
}

/// The work of an inversion of order `n` in units of [`PAR_MIN_ENTRIES`]'s
/// entries: `n^3 / 512`, so that inversions go parallel from order 645. (It
/// was `n^3 / 64`, from order 322: at n = 1000 on the everyday family only
/// the refactorisations of blocks of order 322..500 used the pool, and the
/// default ran 10..20 % slower than one thread on the 2-core machine of
/// `docs/performance.md`.)
pub fn inverse_flops(n: usize) -> usize {
    n * n * n / 512
}

/// [`inverse`] with the given parallelism (native types; the others on the
/// calling thread): the block basis passes the one its
/// [`crate::Settings::threads`] asks for.
pub fn inverse_par<T: Scalar>(a: MatRef<'_, T>, par: faer::Par) -> Option<(Mat<T>, f64, f64)> {
    let n = a.nrows();
    if n == 0 {
        return Some((Mat::zeros(0, 0), 1.0, 1.0));
    }
    if T::NATIVE {
        let lu = PivLu::new(a, par);
        let u = lu.u.as_ref();
        let (umax, umin) = (0..n).fold((0.0f64, f64::INFINITY), |(mx, mn), k| {
            let v = u[(k, k)].to_f64().abs();
            (mx.max(v), mn.min(v))
        });
        if !(umin > 0.0 && umax.is_finite()) {
            return None;
        }
        return Some((lu.inverse(), umax, umin));
    }
    // Gauss-Jordan with partial pivoting on [A | I]
    let mut w = a.to_owned();
    let mut inv = Mat::<T>::identity(n, n);
    let (mut umax, mut umin) = (0.0f64, f64::INFINITY);
    for k in 0..n {
        let mut piv = k;
        for i in k + 1..n {
            if w[(i, k)].abs() > w[(piv, k)].abs() {
                piv = i;
            }
        }
        let pv = w[(piv, k)];
        let pa = pv.to_f64().abs();
        if pa == 0.0 || !pa.is_finite() {
            return None;
        }
        umax = umax.max(pa);
        umin = umin.min(pa);
        if piv != k {
            for j in 0..n {
                let t = w[(k, j)];
                w[(k, j)] = w[(piv, j)];
                w[(piv, j)] = t;
                let t = inv[(k, j)];
                inv[(k, j)] = inv[(piv, j)];
                inv[(piv, j)] = t;
            }
        }
        let rp = T::one() / pv;
        for j in 0..n {
            w[(k, j)] *= rp;
            inv[(k, j)] *= rp;
        }
        for i in 0..n {
            if i != k {
                let f = w[(i, k)];
                if f != T::zero() {
                    for j in 0..n {
                        let v = w[(i, j)] - f * w[(k, j)];
                        w[(i, j)] = v;
                        let v = inv[(i, j)] - f * inv[(k, j)];
                        inv[(i, j)] = v;
                    }
                }
            }
        }
    }
    Some((inv, umax, umin))
}

/// `A^{-1} B` for a square nonsingular `A` (checked by the caller).
pub fn solve<T: Scalar>(a: MatRef<'_, T>, b: MatRef<'_, T>) -> Option<Mat<T>> {
    if T::NATIVE {
        return Some(a.partial_piv_lu().solve(b));
    }
    let (inv, _, _) = inverse(a)?;
    Some(matmul(inv.as_ref(), b))
}

/// `A B`.
pub fn matmul<T: Scalar>(a: MatRef<'_, T>, b: MatRef<'_, T>) -> Mat<T> {
    if T::NATIVE {
        return a * b;
    }
    matmul_plain(a, b)
}

/// Products of at least this many matrix entries per pivot run on faer's
/// global parallelism ([`faer::get_global_parallelism`]; by default every
/// core, `faer::set_global_parallelism(faer::Par::Seq)` keeps one); smaller
/// ones stay on the calling thread, where waking the pool would cost more
/// than it saves. A pass over `2^19` doubles (4 MB) takes about 250 us.
/// (It was `2^16`: on the 2-core machine of `docs/performance.md` the default
/// then ran slower than one thread at n = 500 and 1000, 24 against 17 ms
/// and 144 against 112 ms, in the same quiet run; from `2^19` the passes of
/// the pivots stay on the calling thread up to n = 1000 on that family, and
/// the refactorisations of blocks of order 322 and more still use the pool.)
pub const PAR_MIN_ENTRIES: usize = 1 << 19;

/// Products of fewer entries than this stay on the calling thread even when
/// [`crate::Settings::threads`] asks for more than one: below it (a pass over
/// `2^16` doubles, 512 KB, some 30 us) splitting the work costs more than the
/// pass. Between this and [`PAR_MIN_ENTRIES`] only an explicit setting
/// spreads the work: the default's measured threshold is the higher one.
pub const PAR_SPLIT_MIN: usize = 1 << 16;

/// The parallelism for a pass over `entries` matrix entries (see [`PAR_MIN_ENTRIES`]).
pub fn par_for(entries: usize) -> faer::Par {
    if entries < PAR_MIN_ENTRIES {
        faer::Par::Seq
    } else {
        faer::get_global_parallelism()
    }
}

/// `C = A B` with the given parallelism (native types; the others on the
/// calling thread), written into `c` (`a.nrows() x b.ncols()`): for the block
/// basis's fused product, into a buffer it keeps.
pub fn matmul_par_into<T: Scalar>(
    c: faer::MatMut<'_, T>,
    a: MatRef<'_, T>,
    b: MatRef<'_, T>,
    par: faer::Par,
) {
    if T::NATIVE {
        faer::linalg::matmul::matmul(c, faer::Accum::Replace, a, b, T::one(), par);
        return;
    }
    matmul_plain_into(c, a, b);
}

fn matmul_plain<T: Scalar>(a: MatRef<'_, T>, b: MatRef<'_, T>) -> Mat<T> {
    let mut c = Mat::<T>::zeros(a.nrows(), b.ncols());
    matmul_plain_into(c.as_mut(), a, b);
    c
}

fn matmul_plain_into<T: Scalar>(mut c: faer::MatMut<'_, T>, a: MatRef<'_, T>, b: MatRef<'_, T>) {
    c.fill(T::zero());
    for j in 0..b.ncols() {
        for k in 0..a.ncols() {
            let f = b[(k, j)];
            if f != T::zero() {
                for i in 0..a.nrows() {
                    let v = c[(i, j)] + a[(i, k)] * f;
                    c[(i, j)] = v;
                }
            }
        }
    }
}

/// `A x`, on the calling thread: the pivoting core calls it once or twice per
/// pivot on matrices of order up to a few thousand, where spreading one
/// product over threads costs more than it saves (measured: 30 % slower with
/// faer's default parallelism on 2 cores at n = 1000).
pub fn matvec<T: Scalar>(a: MatRef<'_, T>, x: faer::ColRef<'_, T>) -> Col<T> {
    if T::NATIVE {
        let mut y = Col::<T>::zeros(a.nrows());
        faer::linalg::matmul::matmul(
            y.as_mat_mut(),
            faer::Accum::Replace,
            a,
            x.as_mat(),
            T::one(),
            faer::Par::Seq,
        );
        return y;
    }
    let mut y = Col::<T>::zeros(a.nrows());
    for k in 0..a.ncols() {
        let f = x[k];
        if f != T::zero() {
            for i in 0..a.nrows() {
                let v = y[i] + a[(i, k)] * f;
                y[i] = v;
            }
        }
    }
    y
}

/// [`matvec`] into `y` (of `a.nrows()` entries; no allocation): the same
/// kernel, so the same numbers.
pub fn matvec_into<T: Scalar>(a: MatRef<'_, T>, x: faer::ColRef<'_, T>, y: &mut Col<T>) {
    matvec_into_mut(a, x, y.as_mut());
}

/// [`matvec_into`] into a view (the same operations).
pub fn matvec_into_mut<T: Scalar>(
    a: MatRef<'_, T>,
    x: faer::ColRef<'_, T>,
    mut y: faer::ColMut<'_, T>,
) {
    if T::NATIVE && a.ncols() > 0 {
        faer::linalg::matmul::matmul(
            y.rb_mut().as_mat_mut(),
            faer::Accum::Replace,
            a,
            x.as_mat(),
            T::one(),
            faer::Par::Seq,
        );
        return;
    }
    y.fill(T::zero());
    for k in 0..a.ncols() {
        let f = x[k];
        if f != T::zero() {
            for i in 0..a.nrows() {
                let v = y[i] + a[(i, k)] * f;
                y[i] = v;
            }
        }
    }
}

/// faer's LU with partial pivoting and its inverse, as
/// `Mat::partial_piv_lu().inverse()` computes them but with the parallelism
/// given: faer's own reads the global one, and asking rayon for its number of
/// threads starts the pool (threads spawned on the first call, milliseconds,
/// more than a whole path at n = 100 takes).
struct PivLu<T: Scalar> {
    l: Mat<T>,
    u: Mat<T>,
    fwd: Vec<usize>,
    bwd: Vec<usize>,
    par: faer::Par,
}

impl<T: Scalar> PivLu<T> {
    fn new(a: MatRef<'_, T>, par: faer::Par) -> Self {
        use faer::dyn_stack::{MemBuffer, MemStack};
        use faer::linalg::lu::partial_pivoting::factor;
        let n = a.nrows();
        let mut lu = a.to_owned();
        let mut fwd = vec![0usize; n];
        let mut bwd = vec![0usize; n];
        factor::lu_in_place(
            lu.as_mut(),
            &mut fwd,
            &mut bwd,
            par,
            MemStack::new(&mut MemBuffer::new(
                factor::lu_in_place_scratch::<usize, T>(n, n, par, Default::default()),
            )),
            Default::default(),
        );
        // split as faer's PartialPivLu does: U the upper triangle, L unit lower
        let u = Mat::from_fn(n, n, |i, j| if i <= j { lu[(i, j)] } else { T::zero() });
        let l = Mat::from_fn(n, n, |i, j| match i.cmp(&j) {
            core::cmp::Ordering::Greater => lu[(i, j)],
            core::cmp::Ordering::Equal => T::one(),
            core::cmp::Ordering::Less => T::zero(),
        });
        Self {
            l,
            u,
            fwd,
            bwd,
            par,
        }
    }

    fn inverse(&self) -> Mat<T> {
        use faer::dyn_stack::{MemBuffer, MemStack};
        use faer::linalg::lu::partial_pivoting::inverse;
        let n = self.l.nrows();
        let mut out = Mat::zeros(n, n);
        let perm = faer::perm::PermRef::new_checked(&self.fwd, &self.bwd, n);
        inverse::inverse(
            out.as_mut(),
            self.l.as_ref(),
            self.u.as_ref(),
            perm,
            self.par,
            MemStack::new(&mut MemBuffer::new(inverse::inverse_scratch::<usize, T>(
                n, self.par,
            ))),
        );
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check<T: Scalar>(tol: f64) {
        for n in [1usize, 2, 5, 17, 40] {
            let a = Mat::<T>::from_fn(n, n, |i, j| {
                T::from_f64(if i == j {
                    4.0
                } else {
                    1.0 / (1.0 + i as f64 + 2.0 * j as f64)
                })
            });
            let (inv, _, _) = inverse(a.as_ref()).unwrap();
            let prod = matmul(a.as_ref(), inv.as_ref());
            for i in 0..n {
                for j in 0..n {
                    let e = prod[(i, j)].to_f64() - if i == j { 1.0 } else { 0.0 };
                    assert!(e.abs() < tol, "{} n={n} ({i},{j}) {e}", T::NAME);
                }
            }
            let b = Mat::<T>::from_fn(n, 2, |i, j| T::from_f64((i + j) as f64));
            let x = solve(a.as_ref(), b.as_ref()).unwrap();
            let r = matmul(a.as_ref(), x.as_ref());
            for i in 0..n {
                assert!((r[(i, 1)].to_f64() - (i + 1) as f64).abs() < tol * 10.0);
            }
        }
    }

    #[test]
    fn kernels_in_all_precisions() {
        check::<f32>(1e-5);
        check::<f64>(1e-13);
        check::<faer::fx128>(1e-28);
    }
}
