//! The everyday paths of `plcp_workspace::everyday` traced by plcp and
//! checked against Clarabel at many parameter values: shared by the examples
//! (which print the numbers) and `tests/everyday_paths.rs` (which bound them).
//! Include `qp.rs` beside it as `mod qp`.

use faer::{Col, Mat, MatRef};
use plcp::{Method, Path, Settings};
use plcp_workspace::everyday;

use super::qp::{clarabel_qp, objective};

/// How a path compares with the independent solves.
pub struct Check {
    /// The path.
    pub path: Path<f64>,
    /// Where it was compared.
    pub points: usize,
    /// Largest difference of the unknowns (coefficients, weights, inputs).
    pub worst_x: f64,
    /// Largest objective excess of plcp over Clarabel, relative to `max(1, |f|)`
    /// (negative or rounding-small when plcp is at least as good).
    pub excess: f64,
}

fn col(v: &Col<f64>) -> Vec<f64> {
    v.iter().copied().collect()
}

fn empty() -> Mat<f64> {
    Mat::zeros(0, 0)
}

/// The LASSO path of `(X, y)` against Clarabel's QP in `(b+, b-)` at `k` values of `t` in `(0, t_max]`.
pub fn lasso(x: MatRef<'_, f64>, y: faer::ColRef<'_, f64>, k: usize) -> (Check, f64) {
    let (problem, t_max) = everyday::lasso(x, y).expect("valid data");
    let path = plcp::solve(&problem, &Settings::default()).expect("valid settings");
    let p = x.ncols();
    let c = x.transpose() * y;
    let m = problem.m().to_owned();
    let neg = Mat::from_fn(2 * p, 2 * p, |i, j| if i == j { -1.0 } else { 0.0 });
    let (mut worst_x, mut excess) = (0.0f64, f64::NEG_INFINITY);
    let none = empty();
    // t > 0 only: at t = 0 a wide problem (p > n) has many least-squares fits
    for s in 1..=k {
        let t = t_max * s as f64 / k as f64;
        let lin: Vec<f64> = (0..2 * p)
            .map(|i| if i < p { t - c[i] } else { t + c[i - p] })
            .collect();
        let Some(z) = clarabel_qp(
            m.as_ref(),
            &lin,
            none.as_ref(),
            &[],
            neg.as_ref(),
            &vec![0.0; 2 * p],
        ) else {
            continue;
        };
        let b = everyday::lasso_coef(&path, t_max, t).expect("t in the path's range");
        let bc: Vec<f64> = (0..p).map(|i| z[i] - z[p + i]).collect();
        worst_x = worst_x.max((0..p).map(|i| (b[i] - bc[i]).abs()).fold(0.0, f64::max));
        let zp: Vec<f64> = (0..2 * p)
            .map(|i| {
                if i < p {
                    b[i].max(0.0)
                } else {
                    (-b[i - p]).max(0.0)
                }
            })
            .collect();
        let (fp, fc) = (
            objective(m.as_ref(), &lin, &zp),
            objective(m.as_ref(), &lin, &z),
        );
        excess = excess.max((fp - fc) / fc.abs().max(1.0));
    }
    (
        Check {
            path,
            points: k,
            worst_x,
            excess,
        },
        t_max,
    )
}

/// The efficient frontier against Clarabel at `k` values of `L` up to `1.5`
/// times the last corner, and at the corners.
pub fn frontier(s: MatRef<'_, f64>, mu: faer::ColRef<'_, f64>, k: usize) -> Check {
    let n = mu.nrows();
    let problem = everyday::markowitz(s, mu).expect("valid data");
    let path =
        plcp::solve(&problem, &Settings::with_method(Method::Wolfe)).expect("valid settings");
    let last = path.breakpoints.last().map_or(1.0, |b| b.lambda);
    let mut ls: Vec<f64> = (0..k)
        .map(|i| 1.5 * last * i as f64 / (k - 1) as f64)
        .collect();
    ls.extend(path.breakpoints.iter().map(|b| b.lambda));
    let ones = Mat::from_fn(1, n, |_, _| 1.0);
    let neg = Mat::from_fn(n, n, |i, j| if i == j { -1.0 } else { 0.0 });
    let (mut worst_x, mut excess) = (0.0f64, f64::NEG_INFINITY);
    for &l in &ls {
        let lin: Vec<f64> = (0..n).map(|i| -l * mu[i]).collect();
        let wc = clarabel_qp(s, &lin, ones.as_ref(), &[1.0], neg.as_ref(), &vec![0.0; n])
            .expect("clarabel solves it");
        let w = col(&path.at(l).expect("L on the path").z);
        worst_x = worst_x.max((0..n).map(|i| (w[i] - wc[i]).abs()).fold(0.0, f64::max));
        let (fp, fc) = (objective(s, &lin, &w), objective(s, &lin, &wc));
        excess = excess.max((fp - fc) / fc.abs().max(1.0));
    }
    Check {
        path,
        points: ls.len(),
        worst_x,
        excess,
    }
}

/// The MPC homotopy from `x0a` to `x0b` against Clarabel at `k` values of `L` in `[0, 1]`.
pub fn mpc(mpc: &everyday::Mpc, x0a: [f64; 2], x0b: [f64; 2], method: Method, k: usize) -> Check {
    let problem = mpc.homotopy(x0a, x0b).expect("valid data");
    let path = plcp::solve(&problem, &Settings::with_method(method)).expect("valid settings");
    let (n, m) = (mpc.h.nrows(), mpc.a.nrows());
    let (mut worst_x, mut excess) = (0.0f64, f64::NEG_INFINITY);
    let none = empty();
    for i in 0..k {
        let l = i as f64 / (k - 1) as f64;
        let x0 = [
            x0a[0] + l * (x0b[0] - x0a[0]),
            x0a[1] + l * (x0b[1] - x0a[1]),
        ];
        let lin: Vec<f64> = (0..n)
            .map(|r| mpc.f[(r, 0)] * x0[0] + mpc.f[(r, 1)] * x0[1])
            .collect();
        let bb: Vec<f64> = (0..m)
            .map(|r| mpc.b[r] + mpc.e[(r, 0)] * x0[0] + mpc.e[(r, 1)] * x0[1])
            .collect();
        let uc = clarabel_qp(
            mpc.h.as_ref(),
            &lin,
            none.as_ref(),
            &[],
            mpc.a.as_ref(),
            &bb,
        )
        .expect("clarabel solves it");
        let u = col(&path.at(l).expect("L on the path").u);
        worst_x = worst_x.max((0..n).map(|r| (u[r] - uc[r]).abs()).fold(0.0, f64::max));
        let (fp, fc) = (
            objective(mpc.h.as_ref(), &lin, &u),
            objective(mpc.h.as_ref(), &lin, &uc),
        );
        excess = excess.max((fp - fc) / fc.abs().max(1.0));
    }
    Check {
        path,
        points: k,
        worst_x,
        excess,
    }
}
