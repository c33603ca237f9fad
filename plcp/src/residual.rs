//! Residuals of a point against a problem: equation, feasibility, complementarity.

use crate::matrix::MatrixRef;
use crate::path::{visible_max, Path, Point, Residual, Segment};
use crate::problem::Plcp;
use crate::scalar::Scalar;
use crate::tolerance::residual_unit;
use faer::{ColRef, MatRef};

/// The residuals of `point` for `problem`, each relative to the data's scale
/// (the rule and its reasons: [`residual_unit`]):
///
/// * equation: `max_r |(M x + q + L d)_r - (0 or w_r)| / max(s_r, U)`, with
///   `s_r = max(|q_r|, |L d_r|, |w_r|, max_j |M_rj x_j|)` the row's own terms
///   and `U` the data's unit;
/// * feasibility: `max(0, -min_i z_i / sz, -min_i w_i / sw)`,
///   `sz = max(U / max |M_ij|, max |z|)` (`M_ij` over the columns of nonzero
///   `z`), `sw = max(U, max |w|)`;
/// * complementarity: `max_i |z_i w_i| / (sz sw)`.
///
/// A uniform scaling of `(M, q, d)` (and of `w` with it) leaves all three
/// unchanged (bit for bit under a power of two).
pub fn residual<T: Scalar>(problem: &Plcp<T>, point: &Point<T>) -> Residual {
    residual_matrix(
        problem.matrix(),
        problem.q(),
        problem.d(),
        problem.free(),
        point,
    )
}

/// [`residual`] on the raw data: `M` of order `p + n`, `q`, `d`, `p` free variables.
pub fn residual_parts<T: Scalar>(
    m: MatRef<'_, T>,
    q: ColRef<'_, T>,
    d: ColRef<'_, T>,
    p: usize,
    point: &Point<T>,
) -> Residual {
    residual_matrix(m.into(), q, d, p, point)
}

/// [`residual_parts`] for a dense or sparse `M` (a sparse one costs `O(nnz)`).
pub fn residual_matrix<T: Scalar>(
    m: MatrixRef<'_, T>,
    q: ColRef<'_, T>,
    d: ColRef<'_, T>,
    p: usize,
    point: &Point<T>,
) -> Residual {
    let [r] = residuals_matrix(m, q, d, p, [point]);
    r
}

/// [`residual`] of several points in one sweep over `M` (the column indices
/// and entries read once for all of them): each point's accumulators see
/// the operations of its own [`residual`] in the same order, so the results
/// are those of `N` calls, bit for bit.
pub fn residuals<T: Scalar, const N: usize>(
    problem: &Plcp<T>,
    points: [&Point<T>; N],
) -> [Residual; N] {
    residuals_matrix(
        problem.matrix(),
        problem.q(),
        problem.d(),
        problem.free(),
        points,
    )
}

fn residuals_matrix<T: Scalar, const N: usize>(
    m: MatrixRef<'_, T>,
    q: ColRef<'_, T>,
    d: ColRef<'_, T>,
    p: usize,
    points: [&Point<T>; N],
) -> [Residual; N] {
    let n = m.nrows() - p;
    let dim = p + n;
    // column-major sweep over the nonzero entries of x (contiguous columns,
    // written over slices so that it vectorises), in the working precision
    // (over slices where `q` and `d` are contiguous, so that it vectorises)
    let (qv, dv): (Vec<T>, Vec<T>);
    let (qs, ds) = match (q.try_as_col_major(), d.try_as_col_major()) {
        (Some(q), Some(d)) => (q.as_slice(), d.as_slice()),
        _ => {
            qv = q.iter().copied().collect();
            dv = d.iter().copied().collect();
            (&qv[..], &dv[..])
        }
    };
    let (qs, ds) = (&qs[..dim], &ds[..dim]);
    let mut acc: [Vec<T>; N] = points.map(|pt| {
        qs.iter()
            .zip(ds)
            .map(|(&q, &d)| q + pt.lambda * d)
            .collect()
    });
    let mut big: [Vec<T>; N] = points.map(|pt| {
        qs.iter()
            .zip(ds)
            .map(|(&q, &d)| q.abs().max((pt.lambda * d).abs()))
            .collect()
    });
    let mut colbuf: Vec<T> = Vec::new();
    // the largest |M_ij| over the columns of nonzero z (z's unit is U / that)
    let mut mz = [T::zero(); N];
    let (us, zs): ([&[T]; N], [&[T]; N]) = (
        std::array::from_fn(|k| slice(&points[k].u)),
        std::array::from_fn(|k| slice(&points[k].z)),
    );
    for j in 0..dim {
        let mut x = [T::zero(); N];
        for k in 0..N {
            x[k] = if j < p { us[k][j] } else { zs[k][j - p] };
        }
        if x.iter().all(|&xj| xj == T::zero()) {
            continue;
        }
        let mut xa = [T::zero(); N];
        for k in 0..N {
            xa[k] = x[k].abs();
        }
        let m = match m {
            MatrixRef::Dense(m) => m,
            MatrixRef::Sparse(s) => {
                let (rows, vals) = s.col(j);
                for (&i, &mij) in rows.iter().zip(vals) {
                    for k in 0..N {
                        if x[k] != T::zero() {
                            acc[k][i] += mij * x[k];
                            big[k][i] = big[k][i].max(mij.abs() * xa[k]);
                        }
                    }
                }
                if j >= p {
                    for k in 0..N {
                        if x[k] != T::zero() {
                            mz[k] = vals.iter().fold(mz[k], |a, v| a.max(v.abs()));
                        }
                    }
                }
                continue;
            }
        };
        let col: &[T] = match m.col(j).try_as_col_major() {
            Some(c) => c.as_slice(),
            None => {
                colbuf.clear();
                colbuf.extend(m.col(j).iter().copied());
                &colbuf
            }
        };
        for k in 0..N {
            let (xj, xa) = (x[k], xa[k]);
            if xj == T::zero() {
                continue;
            }
            for ((a, s), &mij) in acc[k].iter_mut().zip(big[k].iter_mut()).zip(col) {
                *a += mij * xj;
                *s = (*s).max(mij.abs() * xa);
            }
            if j >= p {
                mz[k] = col.iter().fold(mz[k], |a, v| a.max(v.abs()));
            }
        }
    }
    let unit = residual_unit(q, d);
    std::array::from_fn(|k| {
        let point = points[k];
        let (acc, big, w) = (&acc[k][..dim], &big[k][..dim], slice(&point.w));
        let mut eq = 0.0f64;
        // the free rows, then the rows of w (the same operations on each
        // row as one loop with a branch: the same bits)
        for (&v, &scale) in acc[..p].iter().zip(&big[..p]) {
            eq = eq.max(v.to_f64().abs() / scale.to_f64().max(unit));
        }
        for ((&a, &scale), &wr) in acc[p..].iter().zip(&big[p..]).zip(&w[..n]) {
            let mut v = a;
            v -= wr;
            let scale = scale.to_f64().max(wr.to_f64().abs());
            eq = eq.max(v.to_f64().abs() / scale.max(unit));
        }
        // w is in the rows' unit; z is `U / max |M_ij|` in size (an LCP with `q`
        // of 1e-4 has `z` of 1e-4: against an absolute 1 its violations went
        // unseen); with no nonzero z the unit of z divides only zeros
        let mz = mz[k].to_f64();
        let z_unit = if mz > 0.0 { unit / mz } else { unit };
        signs_in_units(eq, point, z_unit, unit)
    })
}

/// The residual of `point` with the equation part `equation` (which depends
/// on the form: measured by the caller) and the sign parts measured here:
/// feasibility `max(-z_i / sz, -w_i / sw, 0)` and complementarity
/// `max |z_i w_i| / (sz sw)`, `sz = max(z_unit, max |z|)`,
/// `sw = max(w_unit, max |w|)` (the units: [`residual_unit`]).
pub(crate) fn signs_in_units<T: Scalar>(
    equation: f64,
    point: &Point<T>,
    z_unit: f64,
    w_unit: f64,
) -> Residual {
    // one pass; the divisions once (a correctly rounded division by a
    // positive number keeps the order: the same bits as dividing each entry)
    let (mut sz, mut sw) = (z_unit, w_unit);
    let (mut zmin, mut wmin, mut prod) = (0.0f64, 0.0f64, 0.0f64);
    let (z, w) = (slice(&point.z), slice(&point.w));
    for (&zi, &wi) in z.iter().zip(&w[..z.len()]) {
        let (zi, wi) = (zi.to_f64(), wi.to_f64());
        sz = sz.max(zi.abs());
        sw = sw.max(wi.abs());
        zmin = zmin.min(zi);
        wmin = wmin.min(wi);
        prod = prod.max((zi * wi).abs());
    }
    Residual {
        equation,
        feasibility: (-zmin / sz).max(-wmin / sw).max(0.0),
        complementarity: prod / (sz * sw),
    }
}

/// Measures a whole path on `problem` and stores the result: every breakpoint
/// gets the residuals of the point where it lies (the end of the segment before
/// it, or the start), and `path.info.residual` becomes the largest residual over
/// the start, the end of every bounded segment (with `both_ends`, the start of
/// every segment too: for paths whose segments were computed independently) and
/// the end point. One residual per breakpoint, `O(dim nnz(x))` each: as much
/// work as tracing the path again. [`crate::solve`] does this only for Lemke on a
/// Schur reduction; otherwise breakpoints carry the residuals of the basic
/// solution measured during the trace (on the scaled system) and the ends of
/// every segment and the end point are measured on `problem`
/// ([`measure_ends`]).
pub fn measure_path<T: Scalar>(problem: &Plcp<T>, path: &mut Path<T>, both_ends: bool) {
    let mut worst = Residual::default();
    let mut at_end: Vec<Option<Residual>> = vec![None; path.segments.len()];
    let start = path
        .segments
        .first()
        .map(|s| residual(problem, &s.eval(s.lambda_from)));
    if let Some(r) = start {
        worst = r;
    }
    for (k, seg) in path.segments.iter().enumerate() {
        if both_ends && k > 0 {
            worst = worst.max(residual(problem, &seg.eval(seg.lambda_from)));
        }
        if !seg.unbounded && seg.lambda_to.is_finite() {
            let r = residual(problem, &seg.eval(seg.lambda_to));
            worst = worst.max(r);
            at_end[k] = Some(r);
        }
    }
    let end = path
        .end
        .lambda
        .is_finite()
        .then(|| residual(problem, &path.end));
    if let Some(r) = end {
        worst = worst.max(r);
    }
    for b in &mut path.breakpoints {
        b.residual = match b.segment {
            0 => start.or(end).unwrap_or_default(),
            k => at_end
                .get(k - 1)
                .copied()
                .flatten()
                .or(end)
                .unwrap_or_default(),
        };
    }
    path.info.residual = worst;
}

/// What the sign parts of a point's residual are measured against, from the
/// data once per path: the data's unit `U` ([`residual_unit`]) and each
/// column's largest `|M_ij|` (`z`'s unit is `U` over the largest of those
/// over the columns of nonzero `z`, as in [`residual`]).
#[derive(Clone, Debug)]
pub struct SignUnits {
    unit: f64,
    col_max: Vec<f64>,
}

impl SignUnits {
    /// The units of `problem` (one pass over `M`).
    pub fn new<T: Scalar>(problem: &Plcp<T>) -> Self {
        let m = problem.matrix();
        let (p, dim) = (problem.free(), problem.dim());
        let col_max = (p..dim)
            .map(|j| match m {
                // in four chains over the contiguous column (the same maximum:
                // `M` is finite, and rounding to f64 keeps the order)
                MatrixRef::Dense(m) => match m.col(j).try_as_col_major() {
                    Some(c) => crate::pivoting::max_abs(c.as_slice()).to_f64(),
                    None => m.col(j).iter().fold(0.0f64, |a, v| a.max(v.to_f64().abs())),
                },
                MatrixRef::Sparse(s) => s
                    .col(j)
                    .1
                    .iter()
                    .fold(0.0f64, |a, v| a.max(v.to_f64().abs())),
            })
            .collect();
        Self {
            unit: residual_unit(problem.q(), problem.d()),
            col_max,
        }
    }

    /// Feasibility and complementarity of `point` (the equation part zero),
    /// the same numbers as [`residual`]'s, in `O(n)`.
    pub fn signs<T: Scalar>(&self, point: &Point<T>) -> Residual {
        let n = point.z.nrows();
        let mz = (0..n)
            .filter(|&i| point.z[i] != T::zero())
            .fold(0.0f64, |a, i| a.max(self.col_max[i]));
        let z_unit = if mz > 0.0 { self.unit / mz } else { self.unit };
        signs_in_units(0.0, point, z_unit, self.unit)
    }
}

/// The entries of an owned (contiguous) column.
pub(crate) fn slice<T: Scalar>(c: &faer::Col<T>) -> &[T] {
    c.as_ref()
        .try_as_col_major()
        .expect("an owned column is contiguous")
        .as_slice()
}

/// The sign parts (feasibility, complementarity) of a segment at its two
/// ends (the end only if the segment is bounded): what a delivered segment
/// gives where it meets the next, `O(p + n)`. The one measure of a segment,
/// for the stored path ([`measure_ends`]) and for the segments a streamed
/// trace hands to its observer and drops ([`crate::solve_observed`]): the
/// same bits either way.
pub fn segment_ends<T: Scalar>(units: &SignUnits, seg: &Segment<T>) -> Residual {
    let mut r = units.signs_on(seg, seg.lambda_from);
    if !seg.unbounded && seg.lambda_to.is_finite() {
        r = r.max(units.signs_on(seg, seg.lambda_to));
    }
    r
}

impl SignUnits {
    /// `self.signs(&seg.eval(lambda))` without the point: two passes over the
    /// segment's columns (the clamp's scale, then the values with the sign
    /// measure), no allocation. The same operations on every entry, so the
    /// same bits: a maximum does not depend on where it starts as long as
    /// the start is below every entry (`sz = max(z_unit, max |z_i|)` folded
    /// as `max(z_unit, max(0, max |z_i|))`).
    fn signs_on<T: Scalar>(&self, seg: &Segment<T>, lambda: T) -> Residual {
        if T::NATIVE {
            if let Some(r) = pulp::Arch::new().dispatch(SignsPass {
                units: self,
                seg,
                lambda,
            }) {
                return r;
            }
        }
        self.signs_on_plain(seg, lambda)
    }

    /// [`Self::signs_on`] entry by entry in the order of the vectors (the
    /// reference the lane pass [`SignsPass`] gives the bits of, and the
    /// way where that one declines).
    fn signs_on_plain<T: Scalar>(&self, seg: &Segment<T>, lambda: T) -> Residual {
        let dl = lambda - seg.lambda_from;
        let (zf, dz) = (slice(&seg.z_from), slice(&seg.dz));
        let (wf, dw) = (slice(&seg.w_from), slice(&seg.dw));
        let n = zf.len();
        let (dz, wf, dw, col_max) = (&dz[..n], &wf[..n], &dw[..n], &self.col_max[..n]);
        let at = |f: &[T], s: &[T]| {
            let it = f.iter().zip(s).map(move |(&f, &s)| f + s * dl);
            visible_max(it)
        };
        // the clamp needs `-v > sqrt(eps) max(1, max |v|)`: with no entry
        // below `-sqrt(eps)` it changes nothing, and its scale is not needed
        let floor = -T::eps().sqrt();
        let below = |f: &[T], s: &[T]| f.iter().zip(s).any(|(&f, &s)| f + s * dl < floor);
        let rule = (seg.contains(lambda) && (below(zf, dz) || below(wf, dw)))
            .then(|| seg.clamp_rule(lambda, at(zf, dz), at(wf, dw)));
        let (mut mz, mut az, mut aw) = (0.0f64, 0.0f64, 0.0f64);
        let (mut zmin, mut wmin, mut prod) = (0.0f64, 0.0f64, 0.0f64);
        for i in 0..n {
            let (mut z, mut w) = (zf[i] + dz[i] * dl, wf[i] + dw[i] * dl);
            if let Some(rule) = &rule {
                z = rule.z(z, zf[i], dz[i]);
                w = rule.w(w, wf[i], dw[i]);
            }
            // (a select rather than a branch on the sign pattern; `mz >= 0`)
            mz = mz.max(if z != T::zero() { col_max[i] } else { 0.0 });
            let (zi, wi) = (z.to_f64(), w.to_f64());
            az = az.max(zi.abs());
            aw = aw.max(wi.abs());
            zmin = zmin.min(zi);
            wmin = wmin.min(wi);
            prod = prod.max((zi * wi).abs());
        }
        let z_unit = if mz > 0.0 { self.unit / mz } else { self.unit };
        let (sz, sw) = (z_unit.max(az), self.unit.max(aw));
        Residual {
            equation: 0.0,
            feasibility: (-zmin / sz).max(-wmin / sw).max(0.0),
            complementarity: prod / (sz * sw),
        }
    }
}

/// The sign parts of a segment end in one pass of four lanes (the maxima
/// and minima in independent chains, vectorised through pulp's dispatch),
/// for `f32`/`f64`: [`SignUnits::signs_on_plain`]'s bits, or `None` where
/// they are not sure to be the same and the plain pass runs instead.
///
/// A maximum or minimum of a set does not depend on the order it is taken
/// in (NaNs are skipped either way), except for the sign of a zero: the
/// values' maxima fold absolute values (no `-0`), and the minima start at
/// `+0` and take an entry only when it is below (strictly), which is the
/// plain fold's `min` as long as no entry is `-0` (checked: `None`). The
/// clamp of [`Segment::eval`] applies only where an entry is below
/// `-sqrt(eps)` at a `lambda` inside the segment: the pass sees that from
/// its minima and declines (`None`), so the plain pass's pre-scan for it is
/// not needed here. At `n = 100` (seed-1 instance of
/// `docs/performance.md`) the plain measure was 14 % of a solve's
/// instructions.
struct SignsPass<'a, T: Scalar> {
    units: &'a SignUnits,
    seg: &'a Segment<T>,
    lambda: T,
}

impl<T: Scalar> pulp::WithSimd for SignsPass<'_, T> {
    type Output = Option<Residual>;

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> Self::Output {
        let Self { units, seg, lambda } = self;
        let dl = lambda - seg.lambda_from;
        let (zf, dz) = (slice(&seg.z_from), slice(&seg.dz));
        let (wf, dw) = (slice(&seg.w_from), slice(&seg.dw));
        let n = zf.len();
        let (dz, wf, dw, col_max) = (&dz[..n], &wf[..n], &dw[..n], &units.col_max[..n]);
        const L: usize = 4;
        let (mut mz, mut az, mut aw) = ([0.0f64; L], [0.0f64; L], [0.0f64; L]);
        let (mut zmin, mut wmin, mut prod) = ([0.0f64; L], [0.0f64; L], [0.0f64; L]);
        let mut negzero = [false; L];
        let nz = |v: f64| v == 0.0 && v.is_sign_negative();
        // selects on strict comparisons (NaNs skipped; for the maxima, of
        // values >= +0 from +0, the same as `max`)
        #[inline(always)]
        fn up(acc: f64, v: f64) -> f64 {
            if v > acc {
                v
            } else {
                acc
            }
        }
        #[inline(always)]
        fn down(acc: f64, v: f64) -> f64 {
            if v < acc {
                v
            } else {
                acc
            }
        }
        // f64: the same lanes in explicit vector operations (LLVM's SLP
        // vectoriser packed the loop below as (z, w) pairs with scalar
        // negative-zero tests and branches, about 34 instructions an entry)
        if let Some(s) = (seg as &dyn std::any::Any).downcast_ref::<Segment<f64>>() {
            let lanes = SignLanesF64 {
                zf: slice(&s.z_from),
                dz: slice(&s.dz),
                wf: slice(&s.w_from),
                dw: slice(&s.dw),
                col_max,
                dl: dl.to_f64(),
            };
            let [mz, az, aw, zmin, wmin, prod] = pulp::Arch::new().dispatch(lanes)?;
            return finish_signs(units, seg, lambda, [mz, az, aw, prod], zmin, wmin);
        }
        // (chunks of the five vectors: no index checks in the lanes' body)
        let chunks = zf
            .chunks_exact(L)
            .zip(dz.chunks_exact(L))
            .zip(wf.chunks_exact(L).zip(dw.chunks_exact(L)))
            .zip(col_max.chunks_exact(L));
        for (((zf, dz), (wf, dw)), cm) in chunks {
            for l in 0..L {
                let (z, w) = (zf[l] + dz[l] * dl, wf[l] + dw[l] * dl);
                mz[l] = up(mz[l], if z != T::zero() { cm[l] } else { 0.0 });
                let (zi, wi) = (z.to_f64(), w.to_f64());
                az[l] = up(az[l], zi.abs());
                aw[l] = up(aw[l], wi.abs());
                zmin[l] = down(zmin[l], zi);
                wmin[l] = down(wmin[l], wi);
                prod[l] = up(prod[l], (zi * wi).abs());
                negzero[l] |= nz(zi) | nz(wi);
            }
        }
        for i in n - n % L..n {
            let (z, w) = (zf[i] + dz[i] * dl, wf[i] + dw[i] * dl);
            mz[0] = up(mz[0], if z != T::zero() { col_max[i] } else { 0.0 });
            let (zi, wi) = (z.to_f64(), w.to_f64());
            az[0] = up(az[0], zi.abs());
            aw[0] = up(aw[0], wi.abs());
            zmin[0] = down(zmin[0], zi);
            wmin[0] = down(wmin[0], wi);
            prod[0] = up(prod[0], (zi * wi).abs());
            negzero[0] |= nz(zi) | nz(wi);
        }
        if negzero.iter().any(|&b| b) {
            return None;
        }
        let fold = |v: [f64; L], f: fn(f64, f64) -> f64| v.into_iter().fold(v[0], f);
        let low = |a: f64, b: f64| if b < a { b } else { a };
        let (zmin, wmin) = (fold(zmin, low), fold(wmin, low));
        let maxima = [
            fold(mz, f64::max),
            fold(az, f64::max),
            fold(aw, f64::max),
            fold(prod, f64::max),
        ];
        finish_signs(units, seg, lambda, maxima, zmin, wmin)
    }
}

/// The sign parts from [`SignsPass`]'s folded lanes (`maxima`: `mz`, `az`,
/// `aw`, `prod`), or `None` where the clamp of [`Segment::eval`] applies.
fn finish_signs<T: Scalar>(
    units: &SignUnits,
    seg: &Segment<T>,
    lambda: T,
    maxima: [f64; 4],
    zmin: f64,
    wmin: f64,
) -> Option<Residual> {
    let floor = -T::eps().sqrt().to_f64();
    if seg.contains(lambda) && (zmin < floor || wmin < floor) {
        return None;
    }
    let [mz, az, aw, prod] = maxima;
    let z_unit = if mz > 0.0 {
        units.unit / mz
    } else {
        units.unit
    };
    let (sz, sw) = (z_unit.max(az), units.unit.max(aw));
    Some(Residual {
        equation: 0.0,
        feasibility: (-zmin / sz).max(-wmin / sw).max(0.0),
        complementarity: prod / (sz * sw),
    })
}

/// [`SignsPass`]'s lanes for `f64` in explicit vector operations: per
/// entry `z = zf + dz dL`, `w = wf + dw dL` (a product, then a sum: no
/// fused multiply-add, the plain pass's roundings), the maxima by a select
/// on `v > acc` and the minima on `v < acc` (NaNs skipped, as `max`/`min`
/// skip them), `z != 0` picking the column's `max |M_ij|`. Gives `[mz, az,
/// aw, zmin, wmin, prod]` folded over the lanes (no accumulator is NaN or
/// `-0`, so any order of the fold gives the same value), or `None` where an
/// entry of `z` or `w` is `-0` (tested by its bits).
struct SignLanesF64<'a> {
    zf: &'a [f64],
    dz: &'a [f64],
    wf: &'a [f64],
    dw: &'a [f64],
    col_max: &'a [f64],
    dl: f64,
}

impl pulp::WithSimd for SignLanesF64<'_> {
    type Output = Option<[f64; 6]>;

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, simd: S) -> Self::Output {
        let n = self.zf.len();
        let (zf, dz, wf, dw, cm) = (
            &self.zf[..n],
            &self.dz[..n],
            &self.wf[..n],
            &self.dw[..n],
            &self.col_max[..n],
        );
        let (zf_v, zf_t) = S::as_simd_f64s(zf);
        let (dz_v, dz_t) = S::as_simd_f64s(dz);
        let (wf_v, wf_t) = S::as_simd_f64s(wf);
        let (dw_v, dw_t) = S::as_simd_f64s(dw);
        let (cm_v, cm_t) = S::as_simd_f64s(cm);
        let zero = simd.splat_f64s(0.0);
        let dl = simd.splat_f64s(self.dl);
        let neg0 = simd.splat_u64s(0x8000_0000_0000_0000);
        let up =
            |acc: S::f64s, v: S::f64s| simd.select_f64s(simd.greater_than_f64s(v, acc), v, acc);
        let down = |acc: S::f64s, v: S::f64s| simd.select_f64s(simd.less_than_f64s(v, acc), v, acc);
        let (mut mz, mut az, mut aw) = (zero, zero, zero);
        let (mut zmin, mut wmin, mut prod) = (zero, zero, zero);
        // (a lane set to one where a -0 was seen: the masks' layout differs
        // between instruction sets, a u64 lane does not)
        let (no, yes) = (simd.splat_u64s(0), simd.splat_u64s(1));
        let mut negzero = no;
        let body = zf_v.iter().zip(dz_v).zip(wf_v.iter().zip(dw_v)).zip(cm_v);
        for (((&zf, &dz), (&wf, &dw)), &cm) in body {
            let z = simd.add_f64s(zf, simd.mul_f64s(dz, dl));
            let w = simd.add_f64s(wf, simd.mul_f64s(dw, dl));
            mz = up(mz, simd.select_f64s(simd.equal_f64s(z, zero), zero, cm));
            az = up(az, simd.abs_f64s(z));
            aw = up(aw, simd.abs_f64s(w));
            zmin = down(zmin, z);
            wmin = down(wmin, w);
            prod = up(prod, simd.abs_f64s(simd.mul_f64s(z, w)));
            let zb = simd.equal_u64s(simd.transmute_u64s_f64s(z), neg0);
            let wb = simd.equal_u64s(simd.transmute_u64s_f64s(w), neg0);
            negzero = simd.select_u64s(simd.or_m64s(zb, wb), yes, negzero);
        }
        let neg_any = pulp::bytemuck::cast_slice::<S::u64s, u64>(std::slice::from_ref(&negzero))
            .iter()
            .any(|&b| b != 0);
        let fold = |v: &S::f64s, f: fn(f64, f64) -> f64| {
            let l = pulp::bytemuck::cast_slice::<S::f64s, f64>(std::slice::from_ref(v));
            l.iter().fold(l[0], |a, &b| f(a, b))
        };
        let hi = |a: f64, b: f64| if b > a { b } else { a };
        let lo = |a: f64, b: f64| if b < a { b } else { a };
        let (mut mz, mut az, mut aw) = (fold(&mz, hi), fold(&az, hi), fold(&aw, hi));
        let (mut zmin, mut wmin, mut prod) = (fold(&zmin, lo), fold(&wmin, lo), fold(&prod, hi));
        let mut neg_any = neg_any;
        let tail = zf_t.iter().zip(dz_t).zip(wf_t.iter().zip(dw_t)).zip(cm_t);
        for (((&zf, &dz), (&wf, &dw)), &cm) in tail {
            let (z, w) = (zf + dz * self.dl, wf + dw * self.dl);
            mz = hi(mz, if z != 0.0 { cm } else { 0.0 });
            az = hi(az, z.abs());
            aw = hi(aw, w.abs());
            zmin = lo(zmin, z);
            wmin = lo(wmin, w);
            prod = hi(prod, (z * w).abs());
            neg_any |= z.to_bits() == 0x8000_0000_0000_0000 || w.to_bits() == 0x8000_0000_0000_0000;
        }
        if neg_any {
            return None;
        }
        Some([mz, az, aw, zmin, wmin, prod])
    }
}

/// Measures the path's start and end point on `problem` (all three parts)
/// and the sign parts at both ends of every segment ([`segment_ends`]);
/// `path.info.residual` becomes the largest of those and of the breakpoints'
/// residuals (kept as the trace measured them, of the basic values on the
/// scaled system). Under [`crate::solve_observed`] with segments not kept,
/// the segments the observer saw were measured as they were handed over and
/// count here too. The equation part at the segments' inner ends is not
/// measured: two `O(nnz)` passes per segment, measured at 62% of a dense
/// `n = 150` solve's instructions (143 pivots); the sign parts cost `O(n)`.
pub fn measure_ends<T: Scalar>(problem: &Plcp<T>, path: &mut Path<T>) {
    let mut worst = path
        .breakpoints
        .iter()
        .fold(Residual::default(), |a, b| a.max(b.residual));
    if let Some(r) = crate::observe::emitted_ends::<T>() {
        worst = worst.max(r);
    }
    // on a dense `M` without free variables, the blocked pass of the
    // solver's end residual: [`residual`]'s operations in its order on
    // every row, so its bits (`solver.rs`, test
    // `blocked_end_residual_gives_the_plain_bits`), compiled for the
    // machine's vector width; `residual`'s sweep is not vectorised at the
    // crate's baseline target (n = 100: about 68 k instructions a point
    // against 21 k)
    let mut blocked = crate::solver::EndResidual::<T>::default();
    let mut measure = |point: &Point<T>| match problem.matrix() {
        MatrixRef::Dense(m) if problem.free() == 0 => {
            blocked.measure(m, problem.q(), problem.d(), point)
        }
        _ => residual(problem, point),
    };
    // (one point's buffers for both evaluations; the end point is not
    // measured again where it is the last segment's end to the bit, as on
    // the fast path)
    let mut pt = Point {
        lambda: T::zero(),
        z: faer::Col::zeros(0),
        w: faer::Col::zeros(0),
        u: faer::Col::zeros(0),
    };
    // (bitwise, in `f64`: exact for the native types; others always measured)
    let bits = |x: T| x.to_f64().to_bits();
    let same = |a: &faer::Col<T>, b: &faer::Col<T>| {
        T::NATIVE
            && a.nrows() == b.nrows()
            && a.iter().zip(b.iter()).all(|(&x, &y)| bits(x) == bits(y))
    };
    let mut end_measured = false;
    if let Some(s) = path.segments.first() {
        s.eval_into(s.lambda_from, &mut pt);
        worst = worst.max(measure(&pt));
    }
    if let Some(s) = path.segments.last() {
        if !s.unbounded && s.lambda_to.is_finite() {
            s.eval_into(s.lambda_to, &mut pt);
            worst = worst.max(measure(&pt));
            let e = &path.end;
            end_measured = bits(e.lambda) == bits(pt.lambda)
                && same(&e.z, &pt.z)
                && same(&e.w, &pt.w)
                && same(&e.u, &pt.u);
        }
    }
    if !path.segments.is_empty() {
        let units = SignUnits::new(problem);
        for seg in &path.segments {
            worst = worst.max(segment_ends(&units, seg));
        }
    }
    if path.end.lambda.is_finite() && !end_measured {
        worst = worst.max(measure(&path.end));
    }
    path.info.residual = worst;
}

/// The row scales a trace ran with, as [`measure_for_guard`] reads them.
#[derive(Clone, Copy, Debug)]
pub(crate) enum RowScales<'a> {
    /// Not known here (a spliced path).
    Unknown,
    /// All one: the trace ran on the unscaled problem.
    Ones,
    /// The trace's row scales `R` (length `p + n`).
    Scaled(&'a [f64]),
}

/// [`measure_ends`], and where its numbers cannot decide the residual guard,
/// the whole path on `problem` ([`measure_path`], both ends of every segment):
/// the guard then reads the documented residual of every point the user gets.
///
/// [`measure_ends`] measures the start, the end and the sign parts of every
/// segment end on `problem`, but the equation part at the segments' inner
/// ends only as the trace measured it, on the scaled system and relative to
/// a floor of one there. The same point's equation residual by
/// [`residual`]'s rule (relative to `max(U, own terms)`, `U` the data's unit)
/// is at most `kappa` times that, `kappa = max(2, max_r 1 / (R_r U))`
/// (`R_r` the row scales the trace ran with, all one on an unscaled trace;
/// the `2`: the trace's row terms hold `|(B x)_r| = |q_r + L d_r|`, at most
/// twice the larger of `|q_r|`, `|L d_r|`). So the cheap measure decides
/// when [`crate::tolerance::GUARD_SLACK`] times `kappa` times the breakpoints'
/// largest equation residual and its other parts are below `sqrt(eps)`; else
/// the path is measured whole and `path.info.residual` is the larger of the
/// two measures. A path the cheap measure already fails is left to fail (the
/// guard only ever becomes stricter). `rows`: the trace's row scales
/// ([`RowScales`]; where unknown, as on a spliced path, `kappa` is the larger
/// of the unscaled one and the one of the Ruiz scales the trace computes). A
/// streamed path whose segments were not kept cannot be measured again:
/// it keeps the cheap measure.
///
/// Found by `prop_path.rs f32_p_matrix` (2026-11-27): the trace reported
/// `3.44e-4`, below f32's `sqrt(eps) = 3.45e-4`, and the delivered start of
/// a segment had residual `3.49e-4` (`1.25e-4` absolute in a row whose own
/// terms are below `U = 0.36`; the trace divided by its floor of one).
pub(crate) fn measure_for_guard<T: Scalar>(
    problem: &Plcp<T>,
    path: &mut Path<T>,
    rows: RowScales<'_>,
) {
    measure_ends(problem, path);
    if crate::observe::emitted_ends::<T>().is_some() {
        return;
    }
    let limit = T::eps().to_f64().sqrt();
    let cheap = path.info.residual;
    let bp_eq = path
        .breakpoints
        .iter()
        .fold(0.0f64, |a, b| a.max(b.residual.equation));
    // (NaN or above the limit: the guard fails the path as it is)
    let worst = cheap.worst();
    if worst.is_nan() || worst > limit || bp_eq == 0.0 {
        return;
    }
    let unit = residual_unit(problem.q(), problem.d());
    let kappa_of = |rows: &[f64]| rows.iter().fold(2.0f64, |a, &r| a.max(1.0 / (r * unit)));
    let slack = crate::tolerance::GUARD_SLACK;
    let decided = |kappa: f64| slack * kappa * bp_eq <= limit;
    let kappa_unscaled = 2.0f64.max(1.0 / unit);
    let whole = match rows {
        // `kappa_of` of `dim` ones, without the vector
        RowScales::Ones => !decided(if problem.dim() == 0 {
            2.0
        } else {
            kappa_unscaled
        }),
        RowScales::Scaled(rows) => !decided(kappa_of(rows)),
        RowScales::Unknown => {
            !decided(kappa_unscaled)
                || !decided(kappa_of(
                    &crate::scaling::Equilibration::ruiz(problem, 8).rows,
                ))
        }
    };
    if whole {
        measure_path(problem, path, true);
        path.info.residual = path.info.residual.max(cheap);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::{col, mat, Col};

    /// The lane pass of the sign measure gives the plain pass's bits (or
    /// declines) on segments of every length mod 4 with negative values
    /// inside and outside the clamp's reach, negative zeros, zero slopes
    /// and an infinite product (NaN), in f64 and f32.
    #[test]
    fn sign_lanes_give_the_plain_bits() {
        fn check<T: Scalar>() -> usize {
            let mut next = crate::test_rng::unit(0x2545_f491_4f6c_dd1d);
            let mut declined = 0;
            for case in 0..400 {
                let n = 1 + case % 23;
                let mut pick = |k: usize| {
                    let u = next();
                    let v = match (case + k) % 7 {
                        0 => 0.0,
                        1 => -1e-9 * u,
                        2 => -8.0 * u,
                        3 if case % 50 == 3 => -0.0,
                        4 if case % 97 == 4 => f64::INFINITY,
                        _ => 4.0 * u,
                    };
                    T::from_f64(v)
                };
                let col = |pick: &mut dyn FnMut(usize) -> T| faer::Col::<T>::from_fn(n, &mut *pick);
                let (z, dz, w, dw) = (
                    col(&mut pick),
                    col(&mut pick),
                    col(&mut pick),
                    col(&mut pick),
                );
                let m = faer::Mat::<T>::from_fn(n, n, |i, j| {
                    T::from_f64(if i == j {
                        2.0
                    } else {
                        0.5 / (1.0 + (i + j) as f64)
                    })
                });
                let q = faer::Col::<T>::from_fn(n, |i| T::from_f64(1.0 + i as f64));
                let d = faer::Col::<T>::from_fn(n, |_| T::from_f64(-0.5));
                let problem = Plcp::new(m.as_ref(), q.as_ref(), d.as_ref()).expect("valid");
                let units = SignUnits::new(&problem);
                let seg = Segment {
                    lambda_from: T::from_f64(0.25),
                    lambda_to: T::from_f64(1.75),
                    unbounded: false,
                    basis: vec![],
                    z_from: z,
                    dz,
                    w_from: w,
                    dw,
                    u_from: faer::Col::zeros(0),
                    du: faer::Col::zeros(0),
                };
                for lambda in [0.25, 1.0, 1.75, 3.0] {
                    let lambda = T::from_f64(lambda);
                    let plain = units.signs_on_plain(&seg, lambda);
                    match pulp::Arch::new().dispatch(SignsPass {
                        units: &units,
                        seg: &seg,
                        lambda,
                    }) {
                        Some(lanes) => {
                            for (a, b) in [
                                (lanes.feasibility, plain.feasibility),
                                (lanes.complementarity, plain.complementarity),
                                (lanes.equation, plain.equation),
                            ] {
                                assert_eq!(a.to_bits(), b.to_bits(), "case {case}: {a:e} vs {b:e}");
                            }
                        }
                        None => declined += 1,
                    }
                }
            }
            declined
        }
        // some cases decline (clamps, negative zeros), a quarter at least do not
        for declined in [check::<f64>(), check::<f32>()] {
            assert!(
                declined > 0 && declined <= 1200,
                "declined {declined} of 1600"
            );
        }
    }

    /// Several points measured in one sweep give the bits of measuring each
    /// alone: dense and sparse `M`, mixed form, points whose nonzeros differ
    /// (a column skipped by one point and not by the other), a negative `z`.
    #[test]
    fn residuals_of_several_points_match_single_calls() {
        let m = mat![
            [2.0, 1.0, 0.0, -1.0],
            [1.0, 3.0, 0.5, 0.0],
            [0.0, 0.5, 4.0, 1e-3],
            [1.0, 0.0, -2.0, 5.0]
        ];
        let (q, d) = (col![1.0, 0.5, -2.0, 0.25], col![-1.0, -0.25, 0.0, 3.0]);
        let dense = Plcp::mixed(m.as_ref(), q.as_ref(), d.as_ref(), 1).expect("valid");
        let sparse = Plcp::mixed_sparse(
            crate::matrix::Csc::from_dense(m.as_ref()),
            q.as_ref(),
            d.as_ref(),
            1,
        )
        .expect("valid");
        let pt = |lambda: f64, u: f64, z: [f64; 3], w: [f64; 3]| Point {
            lambda,
            u: col![u],
            z: Col::from_fn(3, |i| z[i]),
            w: Col::from_fn(3, |i| w[i]),
        };
        let a = pt(0.5, 0.3, [0.0, 1.25, 2.0], [0.75, 0.0, 0.0]);
        let b = pt(1.7, 0.0, [1e-9, 0.0, -3.0], [0.0, 2.5, 1e-12]);
        let c = pt(-0.2, 1.1, [0.0, 0.0, 0.0], [0.1, 0.2, 0.3]);
        let bits = |r: Residual| {
            [
                r.equation.to_bits(),
                r.feasibility.to_bits(),
                r.complementarity.to_bits(),
            ]
        };
        for problem in [&dense, &sparse] {
            let [ra, rb, rc] = residuals(problem, [&a, &b, &c]);
            assert_eq!(bits(ra), bits(residual(problem, &a)));
            assert_eq!(bits(rb), bits(residual(problem, &b)));
            assert_eq!(bits(rc), bits(residual(problem, &c)));
            assert!(rb.feasibility > 0.0 && ra.equation > 0.0);
        }
    }

    /// The allocation-free sign measure of a segment's ends gives the bits of
    /// measuring the evaluated points, clamped or not.
    #[test]
    fn segment_ends_match_the_evaluated_points() {
        let m = mat![[2.0, 1.0, 0.0], [1.0, 3.0, 0.5], [0.0, 0.5, 4.0]];
        let problem = Plcp::new(
            m.as_ref(),
            col![1.0, 0.5, 2.0].as_ref(),
            col![-1.0, -0.25, 0.0].as_ref(),
        )
        .expect("a valid problem");
        let units = SignUnits::new(&problem);
        let seg = |from: Col<f64>, dz: Col<f64>, w: Col<f64>, dw: Col<f64>, l0, l1| Segment {
            lambda_from: l0,
            lambda_to: l1,
            unbounded: false,
            basis: vec![],
            z_from: from,
            dz,
            w_from: w,
            dw,
            u_from: Col::zeros(0),
            du: Col::zeros(0),
        };
        // z_0 ends at -1e-6 through a slope of -1e10: within rounding, clamped
        let l1 = (1.0 + 1e-6) / 1e10;
        let clamped = seg(
            col![1.0, 0.0, 2.0],
            col![-1e10, 0.0, 1.0],
            col![0.0, 3.0, 0.0],
            col![1.0, -2.0, 0.0],
            0.0,
            l1,
        );
        assert_eq!(clamped.eval(l1).z[0], 0.0, "the case clamps");
        let plain = seg(
            col![0.5, 0.0, 1.5],
            col![-0.25, 0.0, 0.75],
            col![0.0, 1.25, 0.0],
            col![0.5, -0.125, 0.0],
            0.25,
            1.75,
        );
        // past its end a value goes negative and is not clamped
        let past = seg(
            col![0.5, 0.0, 1.5],
            col![-1.0, 0.0, 0.75],
            col![0.0, 1.25, 0.0],
            col![0.5, -0.125, 0.0],
            0.0,
            1.0,
        );
        for s in [&clamped, &plain, &past] {
            let mut old = units.signs(&s.eval(s.lambda_from));
            old = old.max(units.signs(&s.eval(s.lambda_to)));
            let new = segment_ends(&units, s);
            assert_eq!(old.feasibility.to_bits(), new.feasibility.to_bits());
            assert_eq!(old.complementarity.to_bits(), new.complementarity.to_bits());
            assert_eq!(new.equation, 0.0);
            for l in [0.0, 0.5, 2.0, -1.0] {
                let a = units.signs(&s.eval(l));
                let b = units.signs_on(s, l);
                assert_eq!(a.feasibility.to_bits(), b.feasibility.to_bits());
                assert_eq!(a.complementarity.to_bits(), b.complementarity.to_bits());
            }
        }
        assert!(units.signs_on(&past, 2.0).feasibility > 0.0);
    }
}
