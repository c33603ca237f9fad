//! Residuals of a point against a problem: equation, feasibility, complementarity.

use crate::path::{Point, Residual};
use crate::problem::Plcp;
use crate::scalar::Scalar;
use faer::{ColRef, MatRef};

/// The residuals of `point` for `problem`, each relative to the data's scale:
///
/// * equation: `max_r |(M x + q + L d)_r - (0 or w_r)| / s_r`, with
///   `s_r = max(1, |q_r|, |L d_r|, max_j |M_rj x_j|)`;
/// * feasibility: `max(0, -min_i z_i / sz, -min_i w_i / sw)`, `sz = max(1, max |z|)`,
///   `sw = max(1, max |w|)`;
/// * complementarity: `max_i |z_i w_i| / (sz sw)`.
pub fn residual<T: Scalar>(problem: &Plcp<T>, point: &Point<T>) -> Residual {
    residual_parts(problem.m(), problem.q(), problem.d(), problem.free(), point)
}

/// [`residual`] on the raw data: `M` of order `p + n`, `q`, `d`, `p` free variables.
pub fn residual_parts<T: Scalar>(
    m: MatRef<'_, T>,
    q: ColRef<'_, T>,
    d: ColRef<'_, T>,
    p: usize,
    point: &Point<T>,
) -> Residual {
    let n = m.nrows() - p;
    let l = point.lambda.to_f64();
    let x: Vec<f64> = (0..p)
        .map(|j| point.u[j].to_f64())
        .chain((0..n).map(|i| point.z[i].to_f64()))
        .collect();
    // column-major sweep over the nonzero entries of x (contiguous columns)
    let dim = p + n;
    let mut acc: Vec<T> = (0..dim).map(|r| q[r] + point.lambda * d[r]).collect();
    let mut scale: Vec<f64> = (0..dim)
        .map(|r| {
            1.0f64
                .max(q[r].to_f64().abs())
                .max((l * d[r].to_f64()).abs())
        })
        .collect();
    for j in 0..dim {
        let xj = if j < p { point.u[j] } else { point.z[j - p] };
        if xj == T::zero() {
            continue;
        }
        let xf = x[j].abs();
        let col = m.col(j);
        for r in 0..dim {
            let a = col[r];
            acc[r] += a * xj;
            let t = a.to_f64().abs() * xf;
            if t > scale[r] {
                scale[r] = t;
            }
        }
    }
    let mut eq = 0.0f64;
    for r in 0..dim {
        let mut v = acc[r];
        if r >= p {
            v -= point.w[r - p];
            scale[r] = scale[r].max(point.w[r - p].to_f64().abs());
        }
        eq = eq.max(v.to_f64().abs() / scale[r]);
    }
    let sz = (0..n).fold(1.0f64, |a, i| a.max(point.z[i].to_f64().abs()));
    let sw = (0..n).fold(1.0f64, |a, i| a.max(point.w[i].to_f64().abs()));
    let mut feas = 0.0f64;
    let mut comp = 0.0f64;
    for i in 0..n {
        let zi = point.z[i].to_f64();
        let wi = point.w[i].to_f64();
        feas = feas.max(-zi / sz).max(-wi / sw);
        comp = comp.max((zi * wi).abs() / (sz * sw));
    }
    Residual {
        equation: eq,
        feasibility: feas.max(0.0),
        complementarity: comp,
    }
}
