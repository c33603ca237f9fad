//! Equilibration: the problem is scaled before pivoting and the answer unscaled.
//!
//! Rows and columns of `M` are scaled by powers of two (so the scaling itself is
//! exact in floating point): `M~ = R M C`, `q~ = R q`, `d~ = R d`. A solution of
//! the scaled problem gives `x = C x~` and `w = R^{-1} w~`; complementarity is
//! unchanged because `w~_i z~_i = (r_i / c_i) w_i z_i`. The scales come from a
//! few sweeps of Ruiz's method (each row and column divided by the square root
//! of its largest entry). Two more steps equilibrate the right-hand side
//! `g_i = max(abs(q_i), abs(d_i))` with `M`, so that the tolerances' floors of
//! one (see [`crate::tolerance`]) are relative to the data, not absolute:
//!
//! * a uniform factor `gamma` (`R = gamma R'`, `C = C' / gamma` leave
//!   `R M C = R' M C'` and give `R q = gamma R' q`) brings the largest scaled
//!   `g_i` to one when it lies outside `[max(2^-40, 1e4 eps), 2^40]` ([`RHS_BAND`]) (and no entry exceeds
//!   `2^900`, where double-double residual checks overflow): data scaled by `1e-150`,
//!   or `M` by `1e150` and `q`, `d` by `1e-150`, reach the pivoting as the
//!   unscaled data would;
//! * a row whose scaled `g_i` stays below `2^-26` (Ruiz balances maxima only:
//!   in `diag(3e38, 1e-37)` with `q = (3e38, 2e-37)` the second row's `q` ends
//!   at `3e-38`) is raised against its column (`r_i t`, `c_i / t`, `t > 1`) as
//!   far as the row's off-diagonal entries allow (they stay at most one, `M_ii`
//!   is unchanged, column `i` only shrinks).
//!
//! Typical data (right-hand side within `2^40` of `M`, no row's below `2^-26`
//! of the largest) keep exactly the scaling of Ruiz on `M`.
//!
//! Every step reads the data divided by `sigma = 2^e`, `e` the middle of the
//! binary exponents of the largest and smallest nonzero `|M_ij|` (rounded up),
//! and folds `sigma` into the row scales: data scaled as a whole by `2^k` reach
//! the pivoting as the very same scaled problem (a bit-identical path, `z`
//! equal and `w` times `2^k`); by `10^k`, as the same problem up to the
//! rounding of the data. Ruiz's sweeps (square roots) are not equivariant by
//! themselves. Data with `|e|` at most [`NORMALISE_BAND`] (entries that
//! straddle one, such as the frames systems) keep the scales they had before,
//! and normalised data always have their right-hand side brought to one.

/// Whether Ruiz reads the data divided by their own power of two (see
/// `Equilibration::ruiz` and [`NORMALISE_BAND`]).
const NORMALISE_BY_DATA_EXPONENT: bool = true;

/// Data whose middle binary exponent `e` (of the largest and smallest nonzero
/// `|M_ij|`) lies within `+-NORMALISE_BAND` of zero are not normalised
/// (`e = 0`: the scales they had before); beyond it the data are read divided
/// by `2^e` and the right-hand side is always brought to one (the factor
/// `gamma`). Two reasons, both measured (issue 14, defect 7):
///
/// * normalising every problem changed frames' system (9) of the
///   60-element cantilever (`e = -1`) by a uniform factor of two, and its
///   dense Wolfe path then ends `ill_conditioned` at `L = 4.618` (a chain of
///   degenerate pivots, residual 2.7e-8) where the sparse and block routes
///   reach the ray: that route is not invariant under a factor of two
///   (`tests/sparse_frames.rs`; the same data times 2 or 0.5 failed before
///   too), so data near one keep the scaling the frames suite was measured on;
/// * Ruiz fixes `R M C` but not the split of a uniform factor between `R` and
///   `C` when `M` is (nearly) of the form `D M0 D`: normalised, the random
///   "huge" #9 case (`M` from 1e47 to 1e60, `tests/stiff.rs`) kept its
///   right-hand side at 1e-10 of `M`, inside [`RHS_BAND`], where the
///   tolerances' floors of one swallowed it and a false unbounded ray was
///   reported; normalised data therefore always get `gamma`.
///
/// Data scaled by `2^k` far enough (`|e + k| > NORMALISE_BAND`) reach the
/// pivoting as one and the same problem (bit-identical paths); within the
/// band, the same path up to rounding.
pub const NORMALISE_BAND: i32 = 8;

use crate::matrix::MatrixRef;

/// The right-hand side is brought to one by a uniform factor when its largest
/// entry after Ruiz lies outside `[max(2^-RHS_BAND, 1e4 eps), 2^RHS_BAND]`
/// (about `1e+-12` in f64; from `1.2e-3` in f32).
/// Beyond it the floors of one in the tolerances start to act on data that
/// are all small (or all large): uniform scaling by `1e-30` or `1e30` traced a
/// different path (`examples/stiff_hunt.rs`, family `huge`). Within it,
/// typical data keep Ruiz's scales exactly (a band of `2^10` changed the
/// f32 path of the suite's near tie at `1e6`).
pub const RHS_BAND: i32 = 40;
use crate::path::Path;
use crate::problem::Plcp;
use crate::scalar::Scalar;
use faer::{Col, Mat, MatRef};

/// Column pointers and row indices of a sparse `M`.
type SparsePattern<'a> = (&'a [usize], &'a [usize]);

/// Row and column scales of a problem.
#[derive(Clone, Debug)]
pub struct Equilibration {
    /// Row scales `r` (length `p + n`).
    pub rows: Vec<f64>,
    /// Column scales `c` (length `p + n`).
    pub cols: Vec<f64>,
}

/// A row whose scaled right-hand side stays below this (the largest being
/// about one) is raised against its column: `2^-26`, about `sqrt(eps)` of
/// `f64`, where the tolerances' floor of one starts to swallow it.
const SMALL_RHS: f64 = 1.0 / 67_108_864.0;

/// The power of two nearest `x` (one for a zero or non-finite `x`; exponent
/// clamped to `+-1000`): scaling by it is exact. Also the column scales of the
/// basis condition estimate ([`crate::basis`]).
/// `floor(log2 x)` of a finite positive `x`, read from its bits (so that
/// `exponent(2^k x) = k + exponent(x)` exactly, which a rounded `log2` does
/// not guarantee); zero for zero or non-finite `x`.
pub(crate) fn exponent(x: f64) -> i32 {
    if !(x.is_finite() && x > 0.0) {
        return 0;
    }
    // a subnormal is raised first (exactly) so that its exponent field is read
    let (x, shift) = if x < f64::MIN_POSITIVE {
        (x * exp2i(64), -64)
    } else {
        (x, 0)
    };
    ((x.to_bits() >> 52) & 0x7ff) as i32 - 1023 + shift
}

/// `2^e` exactly, for `e` in `[-1074, 1023]` (clamped: `2^-1074` is the
/// smallest subnormal, which `powi` does not reach: it divides by `2^1074`).
pub(crate) fn exp2i(e: i32) -> f64 {
    let e = e.clamp(-1074, 1023);
    if e >= -1022 {
        f64::from_bits(((e + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (e + 1074))
    }
}

pub(crate) fn pow2(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return 1.0;
    }
    let e = x.log2().round().clamp(-1000.0, 1000.0);
    2f64.powi(e as i32)
}

/// The largest and smallest nonzero finite `|M_ij|` (`(0, inf)` when there is
/// none). A maximum and a minimum do not depend on the order of the entries,
/// so the dense pass keeps [`LANES`] partial results (vectorised through
/// pulp's dispatch) and folds them at the end: the same numbers as the plain
/// fold.
fn matrix_extremes<T: Scalar>(m: MatrixRef<'_, T>) -> (f64, f64) {
    let fold = |(hi, lo): (f64, f64), v: f64| {
        let v = v.abs();
        if v > 0.0 && v.is_finite() {
            (hi.max(v), lo.min(v))
        } else {
            (hi, lo)
        }
    };
    match m {
        MatrixRef::Dense(m) => pulp::Arch::new().dispatch(DenseExtremes { m }),
        MatrixRef::Sparse(m) => m
            .parts()
            .2
            .iter()
            .fold((0.0f64, f64::INFINITY), |acc, v| fold(acc, v.to_f64())),
    }
}

/// The partial results the dense passes keep: two AVX2 vectors of `f64`.
const LANES: usize = 8;

/// [`matrix_extremes`] of a dense `M`, for pulp's dispatch.
struct DenseExtremes<'a, T: Scalar> {
    m: MatRef<'a, T>,
}

impl<T: Scalar> pulp::WithSimd for DenseExtremes<'_, T> {
    type Output = (f64, f64);

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> Self::Output {
        let m = self.m;
        let mut hi = [0.0f64; LANES];
        let mut lo = [f64::INFINITY; LANES];
        let mut buf = Vec::new();
        // `v > hi` and `0 < v < lo` as selects (NaN compares false, an
        // infinity is excluded): the plain fold's `max`, `min` over the
        // nonzero finite entries
        for j in 0..m.ncols() {
            let col = col_slice(m, j, &mut buf);
            let split = col.len() - col.len() % LANES;
            for ch in col[..split].chunks_exact(LANES) {
                for ((x, h), lw) in ch.iter().zip(&mut hi).zip(&mut lo) {
                    let v = x.to_f64().abs();
                    if v > *h && v < f64::INFINITY {
                        *h = v;
                    }
                    if v > 0.0 && v < *lw {
                        *lw = v;
                    }
                }
            }
            for x in &col[split..] {
                let v = x.to_f64().abs();
                if v > hi[0] && v < f64::INFINITY {
                    hi[0] = v;
                }
                if v > 0.0 && v < lo[0] {
                    lo[0] = v;
                }
            }
        }
        let hi = hi.iter().fold(0.0f64, |a, &b| a.max(b));
        let lo = lo.iter().fold(f64::INFINITY, |a, &b| a.min(b));
        (hi, lo)
    }
}

/// Column `j` of `m` as a slice (copied into `buf` when it is not contiguous).
#[inline(always)]
fn col_slice<'a, T: Scalar>(m: MatRef<'a, T>, j: usize, buf: &'a mut Vec<T>) -> &'a [T] {
    match m.col(j).try_as_col_major() {
        Some(c) => c.as_slice(),
        None => {
            buf.clear();
            buf.extend(m.col(j).iter().copied());
            buf
        }
    }
}

/// `|M| / sigma` as Ruiz's sweeps read it: a dense `M` in place (a copy of
/// `|M|` was an allocation of `dim^2` doubles per solve), a sparse one as
/// `|M_ij| / sigma` over its stored entries with their rows.
enum AbsMatrix<'a, T: Scalar> {
    Dense {
        m: MatRef<'a, T>,
        inv_sigma: f64,
    },
    Sparse {
        a: Vec<f64>,
        pattern: SparsePattern<'a>,
    },
}

impl<'a, T: Scalar> AbsMatrix<'a, T> {
    fn new(m: MatrixRef<'a, T>, inv_sigma: f64) -> Self {
        match m {
            MatrixRef::Dense(m) => Self::Dense { m, inv_sigma },
            MatrixRef::Sparse(m) => {
                let (col_ptr, row_idx, val) = m.parts();
                Self::Sparse {
                    a: val.iter().map(|v| v.to_f64().abs() * inv_sigma).collect(),
                    pattern: (col_ptr, row_idx),
                }
            }
        }
    }

    /// Ruiz's sweeps: the row and column scales `r`, `c` (starting at one),
    /// each sweep dividing every row and column by the square root of its
    /// largest scaled entry; stops early once every maximum lies within a
    /// factor of two of one (the power-of-two scales would not change).
    fn sweeps(&self, dim: usize, sweeps: usize) -> (Vec<f64>, Vec<f64>) {
        let mut r = vec![1.0f64; dim];
        let mut c = vec![1.0f64; dim];
        let mut rmax = vec![0.0f64; dim];
        let mut cmax = vec![0.0f64; dim];
        for _ in 0..sweeps {
            rmax.iter_mut().for_each(|v| *v = 0.0);
            self.maxima(&r, &c, &mut rmax, &mut cmax);
            // every row and column maximum within a factor of two of one: the
            // power-of-two scales would not change any more
            let settled = |v: &f64| *v == 0.0 || (0.5..=2.0).contains(v);
            if rmax.iter().all(settled) && cmax.iter().all(settled) {
                break;
            }
            for i in 0..dim {
                if rmax[i] > 0.0 && rmax[i].is_finite() {
                    r[i] /= rmax[i].sqrt();
                }
            }
            for j in 0..dim {
                if cmax[j] > 0.0 && cmax[j].is_finite() {
                    c[j] /= cmax[j].sqrt();
                }
            }
        }
        (r, c)
    }

    /// The largest scaled entry `|M_ij| / sigma * r_i * c_j` of every row
    /// (into `rmax`, which starts at zero) and column (`cmax`). NaN compares
    /// false and is skipped; infinities are caught by the caller.
    fn maxima(&self, r: &[f64], c: &[f64], rmax: &mut [f64], cmax: &mut [f64]) {
        match self {
            Self::Dense { m, inv_sigma } => pulp::Arch::new().dispatch(DenseMaxima {
                m: *m,
                inv_sigma: *inv_sigma,
                r,
                c,
                rmax,
                cmax,
            }),
            Self::Sparse {
                a,
                pattern: (col_ptr, row_idx),
            } => {
                for j in 0..c.len() {
                    let cj = c[j];
                    let mut cm = 0.0f64;
                    for k in col_ptr[j]..col_ptr[j + 1] {
                        let i = row_idx[k];
                        let v = a[k] * r[i] * cj;
                        if v > rmax[i] {
                            rmax[i] = v;
                        }
                        if v > cm {
                            cm = v;
                        }
                    }
                    cmax[j] = cm;
                }
            }
        }
    }

    /// Raises every row `i` whose right-hand side (after `gamma`) stays far
    /// below one against its column: `r_i t`, `c_i / t`, `t > 1`, as far as
    /// the row's off-diagonal entries allow (they stay at most one, `M_ii` is
    /// unchanged, column `i` only shrinks). Ruiz balances maxima only: in
    /// `diag(3e38, 1e-37)` with `q = (3e38, 2e-37)` the second row's `q` ends
    /// at `3e-38`. Independent for every `i`; no pass over `M` when no row
    /// needs it (typical data).
    fn raise_small_rows(&self, g: &[f64], gmax: f64, gamma: f64, r: &mut [f64], c: &mut [f64]) {
        let dim = r.len();
        let small =
            |gi: f64| gi > 0.0 && gi < SMALL_RHS * (gmax * gamma).max(1.0) && gi.is_finite();
        if !(0..dim).any(|i| small(g[i] * r[i] * gamma)) {
            return;
        }
        let mut rowoff = vec![0.0f64; dim];
        let mut entry = |i: usize, j: usize, aij: f64| {
            if i != j {
                let v = aij * r[i] * c[j];
                if v > rowoff[i] {
                    rowoff[i] = v;
                }
            }
        };
        match self {
            Self::Dense { m, inv_sigma } => {
                let mut buf = Vec::new();
                for j in 0..dim {
                    let col = col_slice(*m, j, &mut buf);
                    for (i, v) in col.iter().enumerate() {
                        entry(i, j, v.to_f64().abs() * inv_sigma);
                    }
                }
            }
            Self::Sparse {
                a,
                pattern: (col_ptr, row_idx),
            } => {
                for j in 0..dim {
                    for k in col_ptr[j]..col_ptr[j + 1] {
                        entry(row_idx[k], j, a[k]);
                    }
                }
            }
        }
        for i in 0..dim {
            let gi = g[i] * r[i] * gamma;
            if small(gi) && rowoff[i].is_finite() {
                let t = if rowoff[i] > 0.0 {
                    (1.0 / gi).min(1.0 / rowoff[i])
                } else {
                    1.0 / gi
                };
                if t > 1.0 && t.is_finite() {
                    r[i] *= t;
                    c[i] /= t;
                }
            }
        }
    }
}

/// [`AbsMatrix::maxima`] of a dense `M`, for pulp's dispatch (the machine's
/// vector width; the crate is compiled for baseline x86-64). Every scaled
/// entry is `((|M_ij| / sigma) r_i) c_j`, the same operations in the same
/// order as the plain loop; the column's maximum is kept in [`LANES`]
/// partial maxima folded at the end (a maximum does not depend on the
/// order), so the scales are the same to the last bit.
struct DenseMaxima<'a, T: Scalar> {
    m: MatRef<'a, T>,
    inv_sigma: f64,
    r: &'a [f64],
    c: &'a [f64],
    rmax: &'a mut [f64],
    cmax: &'a mut [f64],
}

impl<T: Scalar> pulp::WithSimd for DenseMaxima<'_, T> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let Self {
            m,
            inv_sigma,
            r,
            c,
            rmax,
            cmax,
        } = self;
        let mut buf = Vec::new();
        for (j, (&cj, cmj)) in c.iter().zip(cmax.iter_mut()).enumerate() {
            let col = col_slice(m, j, &mut buf);
            let mut lanes = [0.0f64; LANES];
            let split = col.len() - col.len() % LANES;
            for ((a, ri), rm) in col[..split]
                .chunks_exact(LANES)
                .zip(r[..split].chunks_exact(LANES))
                .zip(rmax[..split].chunks_exact_mut(LANES))
            {
                for l in 0..LANES {
                    let v = a[l].to_f64().abs() * inv_sigma * ri[l] * cj;
                    if v > rm[l] {
                        rm[l] = v;
                    }
                    if v > lanes[l] {
                        lanes[l] = v;
                    }
                }
            }
            for ((a, &ri), rm) in col[split..].iter().zip(&r[split..]).zip(&mut rmax[split..]) {
                let v = a.to_f64().abs() * inv_sigma * ri * cj;
                if v > *rm {
                    *rm = v;
                }
                if v > lanes[0] {
                    lanes[0] = v;
                }
            }
            let mut cm = 0.0f64;
            for &v in &lanes {
                if v > cm {
                    cm = v;
                }
            }
            *cmj = cm;
        }
    }
}

impl Equilibration {
    /// Ruiz equilibration of `M` in `sweeps` sweeps, then the right-hand side
    /// balanced against it (module docs), scales rounded to powers of two.
    ///
    /// On a sparse problem the sweeps run over the stored entries only.
    pub fn ruiz<T: Scalar>(problem: &Plcp<T>, sweeps: usize) -> Self {
        let dim = problem.dim();
        // the size of the right-hand side per row
        let graw: Vec<f64> = (0..dim)
            .map(|i| {
                let v = problem.q()[i]
                    .to_f64()
                    .abs()
                    .max(problem.d()[i].to_f64().abs());
                if v.is_finite() {
                    v
                } else {
                    0.0
                }
            })
            .collect();
        // the data's own scale, `sigma = 2^e`, `e` the middle of the binary
        // exponents of the largest and smallest nonzero `|M_ij|`, rounded up (of the
        // right-hand side if M is zero): everything below reads the data
        // divided by sigma (exact), so that data scaled as a whole by `2^k`
        // give the very same scaled problem, the factor going to the rows'
        // scales (`z` is invariant, `w` scales with the data). Data whose
        // entries straddle one (`e = 0`) keep the scales they had without it.
        let (mmax, mmin) = matrix_extremes(problem.matrix());
        let gmax_raw = graw.iter().fold(0.0f64, |a, &b| a.max(b));
        // (see NORMALISE_BAND for why data near one are left alone)
        let e = if NORMALISE_BY_DATA_EXPONENT && mmax > 0.0 {
            (exponent(mmax) + exponent(mmin) + 1).div_euclid(2)
        } else if NORMALISE_BY_DATA_EXPONENT {
            exponent(gmax_raw)
        } else {
            0
        };
        // data near one keep the scales they had (see NORMALISE_BAND)
        let e = if e.abs() <= NORMALISE_BAND { 0 } else { e };
        let inv_sigma = exp2i(-e);
        let abs_m = AbsMatrix::new(problem.matrix(), inv_sigma);
        let g: Vec<f64> = graw.iter().map(|&v| v * inv_sigma).collect();
        let (mut r, mut c) = abs_m.sweeps(dim, sweeps);
        // the right-hand side after Ruiz: a uniform factor brings its largest
        // entry to one, if it lies outside [2^-RHS_BAND, 2^RHS_BAND] (typical data keep
        // exactly the scaling of Ruiz on M)
        let gmax = (0..dim).fold(0.0f64, |m, i| m.max(g[i] * r[i]));
        // not for data beyond 2^900 (about 1e271): there the residual check
        // (products in double-double) overflows, and the path stays unclaimed
        // (a pass over M: only when the factor would apply)
        let huge = || {
            let big = 2f64.powi(900);
            gmax_raw > big || mmax > big
        };
        // from below, the floors act once the data near the tolerances
        // (`1e3 eps`): in f32 that is already at 1e-4
        let low = 2f64.powi(-RHS_BAND).max(1e4 * T::eps().to_f64());
        let gamma = if gmax > 0.0
            && gmax.is_finite()
            && (!(low..=2f64.powi(RHS_BAND)).contains(&gmax) || e != 0)
            && !huge()
        {
            1.0 / gmax
        } else {
            1.0
        };
        abs_m.raise_small_rows(&g, gmax, gamma, &mut r, &mut c);
        // fold gamma into the rows and columns: R = gamma R', C = C' / gamma,
        // and the data's scale into the rows
        Self {
            rows: r.into_iter().map(|v| pow2(v * gamma) * inv_sigma).collect(),
            cols: c.into_iter().map(|v| pow2(v / gamma)).collect(),
        }
    }

    /// True if every scale is one.
    pub fn is_identity(&self) -> bool {
        self.rows.iter().chain(self.cols.iter()).all(|&s| s == 1.0)
    }

    /// The scaled problem `R M C`, `R q`, `R d`, or `None` if it overflows.
    pub fn scale<T: Scalar>(&self, problem: &Plcp<T>) -> Option<Plcp<T>> {
        let dim = problem.dim();
        let r: Vec<T> = self.rows.iter().map(|&v| T::from_f64(v)).collect();
        let c: Vec<T> = self.cols.iter().map(|&v| T::from_f64(v)).collect();
        let q = Col::from_fn(dim, |i| r[i] * problem.q()[i]);
        let d = Col::from_fn(dim, |i| r[i] * problem.d()[i]);
        // `None` when the scaled data leave the range of the type (overflow)
        let scaled = match problem.matrix() {
            MatrixRef::Dense(m) => {
                // column by column over slices (`Mat::from_fn` indexed with
                // bounds checks): the same products `(r_i M_ij) c_j`
                // and each entry checked as `Plcp::mixed` checks it (finite,
                // zero or normal) in the same pass, the copy handed over whole
                let mut out = Mat::<T>::zeros(dim, dim);
                let mut buf = Vec::new();
                let mut ok = true;
                let min_normal = T::min_normal();
                for (j, &cj) in c.iter().enumerate() {
                    let src = col_slice(m, j, &mut buf);
                    let dst = out.col_mut(j).try_as_col_major_mut().expect("owned");
                    for ((o, &ri), &mij) in dst.as_slice_mut().iter_mut().zip(&r).zip(src) {
                        let v = ri * mij * cj;
                        *o = v;
                        ok &= v.is_finite() & ((v == T::zero()) | (v.to_f64().abs() >= min_normal));
                    }
                }
                if !ok {
                    return None;
                }
                Plcp::mixed_owned_checked(out, q.as_ref(), d.as_ref(), problem.free())
            }
            MatrixRef::Sparse(m) => {
                let m = m.map(|i, j, v| r[i] * v * c[j]);
                if m.parts().2.iter().any(|v| !v.is_finite()) {
                    return None;
                }
                Plcp::mixed_sparse(m, q.as_ref(), d.as_ref(), problem.free())
            }
        };
        scaled
            .and_then(|pr| pr.with_range(problem.lambda0(), problem.lambda_max()))
            .ok()
    }

    /// Maps a path of the scaled problem back to the original one (its residuals
    /// are measured afterwards, on the original problem).
    pub fn unscale<T: Scalar>(&self, problem: &Plcp<T>, path: &mut Path<T>) {
        let p = problem.free();
        let n = problem.n();
        let cu: Vec<T> = (0..p).map(|j| T::from_f64(self.cols[j])).collect();
        let cz: Vec<T> = (0..n).map(|i| T::from_f64(self.cols[p + i])).collect();
        let rw: Vec<T> = (0..n).map(|i| T::from_f64(self.rows[p + i])).collect();
        let fix = |z: &mut Col<T>, w: &mut Col<T>, u: &mut Col<T>| {
            for i in 0..z.nrows() {
                z[i] *= cz[i];
            }
            for i in 0..w.nrows() {
                w[i] /= rw[i];
            }
            for j in 0..u.nrows() {
                u[j] *= cu[j];
            }
        };
        for seg in &mut path.segments {
            fix(&mut seg.z_from, &mut seg.w_from, &mut seg.u_from);
            fix(&mut seg.dz, &mut seg.dw, &mut seg.du);
        }
        fix(&mut path.end.z, &mut path.end.w, &mut path.end.u);
        if let Some(ray) = &mut path.ray {
            fix(&mut ray.start.z, &mut ray.start.w, &mut ray.start.u);
            fix(&mut ray.dz, &mut ray.dw, &mut ray.du);
        }
    }
}
