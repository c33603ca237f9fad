//! Equilibration: the problem is scaled before pivoting and the answer unscaled.
//!
//! Rows and columns of `M` are scaled by powers of two (so the scaling itself is
//! exact in floating point): `M~ = R M C`, `q~ = R q`, `d~ = R d`. A solution of
//! the scaled problem gives `x = C x~` and `w = R^{-1} w~`; complementarity is
//! unchanged because `w~_i z~_i = (r_i / c_i) w_i z_i`. The scales come from a
//! few sweeps of Ruiz's method (each row and column divided by the square root
//! of its largest entry).

use crate::path::{Path, Residual};
use crate::problem::Plcp;
use crate::residual::residual;
use crate::scalar::Scalar;
use faer::{Col, Mat};

/// Row and column scales of a problem.
#[derive(Clone, Debug)]
pub struct Equilibration {
    /// Row scales `r` (length `p + n`).
    pub rows: Vec<f64>,
    /// Column scales `c` (length `p + n`).
    pub cols: Vec<f64>,
}

fn pow2(x: f64) -> f64 {
    if !(x.is_finite() && x > 0.0) {
        return 1.0;
    }
    let e = x.log2().round().clamp(-1000.0, 1000.0);
    2f64.powi(e as i32)
}

impl Equilibration {
    /// Ruiz equilibration of `M` in `sweeps` sweeps, scales rounded to powers of two.
    pub fn ruiz<T: Scalar>(problem: &Plcp<T>, sweeps: usize) -> Self {
        let dim = problem.dim();
        let m = problem.m();
        let a: Vec<f64> = (0..dim * dim)
            .map(|k| m[(k % dim, k / dim)].to_f64().abs())
            .collect();
        let mut r = vec![1.0f64; dim];
        let mut c = vec![1.0f64; dim];
        for _ in 0..sweeps {
            let mut rmax = vec![0.0f64; dim];
            let mut cmax = vec![0.0f64; dim];
            for j in 0..dim {
                for i in 0..dim {
                    let v = a[i + j * dim] * r[i] * c[j];
                    rmax[i] = rmax[i].max(v);
                    cmax[j] = cmax[j].max(v);
                }
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
        Self {
            rows: r.into_iter().map(pow2).collect(),
            cols: c.into_iter().map(pow2).collect(),
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
        let m = Mat::from_fn(dim, dim, |i, j| r[i] * problem.m()[(i, j)] * c[j]);
        let q = Col::from_fn(dim, |i| r[i] * problem.q()[i]);
        let d = Col::from_fn(dim, |i| r[i] * problem.d()[i]);
        // `None` when the scaled data leave the range of the type (overflow)
        Plcp::mixed(m.as_ref(), q.as_ref(), d.as_ref(), problem.free())
            .and_then(|pr| pr.with_range(problem.lambda0(), problem.lambda_max()))
            .ok()
    }

    /// Maps a path of the scaled problem back to the original one and measures its
    /// residuals on the original problem.
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
        let mut res = Residual::default();
        for seg in &mut path.segments {
            fix(&mut seg.z_from, &mut seg.w_from, &mut seg.u_from);
            fix(&mut seg.dz, &mut seg.dw, &mut seg.du);
            res = res.max(residual(problem, &seg.eval(seg.lambda_from)));
            if !seg.unbounded {
                res = res.max(residual(problem, &seg.eval(seg.lambda_to)));
            }
        }
        fix(&mut path.end.z, &mut path.end.w, &mut path.end.u);
        if path.end.lambda.is_finite() {
            res = res.max(residual(problem, &path.end));
        }
        if let Some(ray) = &mut path.ray {
            fix(&mut ray.start.z, &mut ray.start.w, &mut ray.start.u);
            fix(&mut ray.dz, &mut ray.dw, &mut ray.du);
        }
        path.info.residual = res;
    }
}
