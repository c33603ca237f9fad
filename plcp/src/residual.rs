//! Residuals of a point against a problem: equation, feasibility, complementarity.

use crate::matrix::MatrixRef;
use crate::path::{Path, Point, Residual};
use crate::problem::Plcp;
use crate::scalar::Scalar;
use faer::{ColRef, MatRef};

/// The residuals of `point` for `problem`, each relative to the data's scale
/// (never to an absolute floor such as 1, which made the residuals of data of
/// order `1e-30` look small whatever the point: issue 14):
///
/// * equation: `max_r |(M x + q + L d)_r - (0 or w_r)| / s_r`, with
///   `s_r = max(|q_r|, max(1, |L|) |d_r|, |w_r|, max_{j: x_j != 0} |M_rj| xmax)`,
///   `xmax = max |x|` (the row's normwise backward error on the point's
///   support; a row whose scale is zero has residual zero if it holds exactly
///   and one otherwise);
/// * feasibility: the backward error of clipping a negative entry to zero:
///   `|w_i| / s_(p+i)` for a negative `w_i`, and for a negative `z_i`
///   `|z_i| max_r |M_r,p+i| / s_r` (what setting it to zero changes in the
///   equations; a zero column of `M` compares `z_i` with `max |z|`);
/// * complementarity: `max_i` of the smaller of those two measures of
///   `|z_i|` and `|w_i|` (the backward error of zeroing one of them).
///
/// Each is invariant under a uniform scaling of `(M, q, d)` (with `w` scaled
/// and `z` kept), as the path is.
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
    let n = m.nrows() - p;
    let dim = p + n;
    // column-major sweep over the nonzero entries of x (contiguous columns,
    // written over slices so that it vectorises), in the working precision
    let mut acc: Vec<T> = (0..dim).map(|r| q[r] + point.lambda * d[r]).collect();
    // L is unchanged by a uniform scaling of the data and carries an error of
    // its own unit (a breakpoint at 5.6e-17 for an exact 0): `d_r` counts
    // with `max(1, |L|)`
    let lunit = T::one().max(point.lambda.abs());
    let mut big: Vec<T> = (0..dim)
        .map(|r| q[r].abs().max((lunit * d[r]).abs()))
        .collect();
    let xmax = (0..dim).fold(T::zero(), |a, j| {
        let xj = if j < p { point.u[j] } else { point.z[j - p] };
        a.max(xj.abs())
    });
    let mut colbuf: Vec<T> = Vec::new();
    for j in 0..dim {
        let xj = if j < p { point.u[j] } else { point.z[j - p] };
        if xj == T::zero() {
            continue;
        }
        let m = match m {
            MatrixRef::Dense(m) => m,
            MatrixRef::Sparse(s) => {
                let (rows, vals) = s.col(j);
                for (&i, &mij) in rows.iter().zip(vals) {
                    acc[i] += mij * xj;
                    big[i] = big[i].max(mij.abs() * xmax);
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
        for ((a, s), &mij) in acc.iter_mut().zip(big.iter_mut()).zip(col) {
            *a += mij * xj;
            *s = (*s).max(mij.abs() * xmax);
        }
    }
    let mut scale: Vec<f64> = big.iter().map(|s| s.to_f64()).collect();
    // `v / s` with `0 / 0 = 0` (an exact zero row) and `v / 0 = 1` (a row that
    // should be zero and is not); `s` overflowing f64 is handled by `ratio`
    let ratio = |v: f64, s: f64| {
        if v == 0.0 {
            0.0
        } else if s > 0.0 && s.is_finite() {
            (v / s).min(f64::MAX)
        } else if s > 0.0 {
            0.0
        } else {
            1.0
        }
    };
    let mut eq = 0.0f64;
    for r in 0..dim {
        let mut v = acc[r];
        if r >= p {
            v -= point.w[r - p];
            scale[r] = scale[r].max(point.w[r - p].to_f64().abs());
        }
        eq = eq.max(ratio(v.to_f64().abs(), scale[r]));
    }
    let sz = (0..n).fold(0.0f64, |a, i| a.max(point.z[i].to_f64().abs()));
    // what setting `z_i` to zero would cost the equations: `|z_i|` times the
    // largest `|M_ri| / s_r` (relative to `max |z|` if column `i` is zero);
    // read only for a negative `z_i` or a `z_i w_i != 0`, O(dim) each
    let zcost = |i: usize, zi: f64| -> f64 {
        let j = p + i;
        let mut worst = 0.0f64;
        let mut any = false;
        let mut see = |r: usize, mrj: f64| {
            if mrj != 0.0 {
                any = true;
                worst = worst.max(ratio(mrj.abs() * zi, scale[r]));
            }
        };
        match m {
            MatrixRef::Dense(m) => (0..dim).for_each(|r| see(r, m[(r, j)].to_f64())),
            MatrixRef::Sparse(s) => {
                let (rows, vals) = s.col(j);
                rows.iter().zip(vals).for_each(|(&r, v)| see(r, v.to_f64()));
            }
        }
        if any {
            worst
        } else {
            ratio(zi, sz)
        }
    };
    let mut feas = 0.0f64;
    let mut comp = 0.0f64;
    for i in 0..n {
        let zi = point.z[i].to_f64();
        let wi = point.w[i].to_f64();
        let sw = scale[p + i];
        if zi < 0.0 {
            feas = feas.max(zcost(i, -zi));
        }
        feas = feas.max(ratio(-wi.min(0.0), sw));
        if zi != 0.0 && wi != 0.0 {
            comp = comp.max(zcost(i, zi.abs()).min(ratio(wi.abs(), sw)));
        }
    }
    Residual {
        equation: eq,
        feasibility: feas.max(0.0),
        complementarity: comp,
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
/// solution measured during the trace (on the scaled system) and the start and
/// end points are measured on `problem` ([`measure_ends`]).
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

/// Measures the start of the path and its end point on `problem`;
/// `path.info.residual` becomes the largest of those and of the breakpoints'
/// residuals (kept as the trace measured them).
pub fn measure_ends<T: Scalar>(problem: &Plcp<T>, path: &mut Path<T>) {
    let mut worst = path
        .breakpoints
        .iter()
        .fold(Residual::default(), |a, b| a.max(b.residual));
    if let Some(s) = path.segments.first() {
        worst = worst.max(residual(problem, &s.eval(s.lambda_from)));
    }
    if let Some(s) = path.segments.last() {
        if !s.unbounded && s.lambda_to.is_finite() {
            worst = worst.max(residual(problem, &s.eval(s.lambda_to)));
        }
    }
    if path.end.lambda.is_finite() {
        worst = worst.max(residual(problem, &path.end));
    }
    path.info.residual = worst;
}
