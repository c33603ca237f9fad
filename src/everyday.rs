//! The parametric paths people compute every day, each as a monotone PLCP.
//!
//! * **LASSO** `min_b 1/2 |y - X b|^2 + t |b|_1` for `t` from `t_max = max |X'y|`
//!   down to 0. With `b = b+ - b-`, `G = X'X`, `c = X'y` and `t = t_max - L`:
//!   `w = q + L d + M z`, `z = (b+, b-)`, `M = [[G, -G], [-G, G]]` (positive
//!   semidefinite), `q = (t_max 1 - c, t_max 1 + c) >= 0`, `d = -1`; `L` rises
//!   from 0 to `t_max`. Every breakpoint is a LARS/LASSO knot.
//! * **Markowitz efficient frontier** `min_w 1/2 w'S w - L mu'w`, `1'w = 1`,
//!   `w >= 0`, `L = 1/gamma` the risk tolerance from 0 to infinity. With the
//!   budget multiplier `nu` free: `0 = 1'w - 1`, `s = S w - nu 1 - L mu >= 0`
//!   `⊥ w`, i.e. `x = (nu, w)`, `M = [[0, 1'], [-1, S]]`, `q = (-1, 0)`,
//!   `d = (0, -mu)`, one free variable; its free block is zero, so it is traced
//!   by Wolfe's long form. The breakpoints are the corner portfolios.
//! * **Parametric QP** (an active-set MPC homotopy) `min_x 1/2 x'H x + (f + L g)'x`
//!   subject to `A x <= b + L e`: with multipliers `y >= 0`,
//!   `0 = H x + A'y + f + L g`, `s = -A x + b + L e >= 0 ⊥ y`, i.e.
//!   `M = [[H, A'], [-A, 0]]` with `x` free (`H` positive definite: both Lemke
//!   and Wolfe trace it). The breakpoints are the changes of the active set.
//!
//! The Python package's examples (`python/examples/`) hold the same
//! formulations; `examples/lasso_path.rs`, `efficient_frontier.rs` and
//! `mpc_homotopy.rs` run them and `tests/everyday_paths.rs` checks them
//! against Clarabel.

use faer::{Col, ColRef, Mat, MatRef};
use plcp::{Path, Plcp, PlcpError};

/// The LASSO path's PLCP and `t_max = max |X'y|` (module doc).
pub fn lasso(x: MatRef<'_, f64>, y: ColRef<'_, f64>) -> Result<(Plcp<f64>, f64), PlcpError> {
    let g = x.transpose() * x;
    let c = x.transpose() * y;
    let p = x.ncols();
    let t_max = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let m = Mat::from_fn(2 * p, 2 * p, |i, j| {
        let s = if (i < p) == (j < p) { 1.0 } else { -1.0 };
        s * g[(i % p, j % p)]
    });
    let q = Col::from_fn(2 * p, |i| {
        if i < p {
            t_max - c[i]
        } else {
            t_max + c[i - p]
        }
    });
    let d = Col::from_fn(2 * p, |_| -1.0);
    let problem = Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())?.with_range(0.0, Some(t_max))?;
    Ok((problem, t_max))
}

/// The LASSO coefficients `b = b+ - b-` at `t` from the path of [`lasso`].
pub fn lasso_coef(path: &Path<f64>, t_max: f64, t: f64) -> Option<Col<f64>> {
    let pt = path.at(t_max - t)?;
    let p = pt.z.nrows() / 2;
    Some(Col::from_fn(p, |i| pt.z[i] - pt.z[p + i]))
}

/// The efficient frontier's mixed PLCP (module doc): trace it with
/// [`plcp::Method::Wolfe`]; `u[0]` is the budget multiplier, `z` the weights.
pub fn markowitz(s: MatRef<'_, f64>, mu: ColRef<'_, f64>) -> Result<Plcp<f64>, PlcpError> {
    let n = mu.nrows();
    let m = Mat::from_fn(n + 1, n + 1, |i, j| match (i, j) {
        (0, 0) => 0.0,
        (0, _) => 1.0,
        (_, 0) => -1.0,
        _ => s[(i - 1, j - 1)],
    });
    let q = Col::from_fn(n + 1, |i| if i == 0 { -1.0 } else { 0.0 });
    let d = Col::from_fn(n + 1, |i| if i == 0 { 0.0 } else { -mu[i - 1] });
    Plcp::mixed(m.as_ref(), q.as_ref(), d.as_ref(), 1)
}

/// The parametric QP's mixed PLCP (module doc): `x` is `u`, the multipliers `z`.
pub fn parametric_qp(
    h: MatRef<'_, f64>,
    f: ColRef<'_, f64>,
    g: ColRef<'_, f64>,
    a: MatRef<'_, f64>,
    b: ColRef<'_, f64>,
    e: ColRef<'_, f64>,
) -> Result<Plcp<f64>, PlcpError> {
    let (nx, m) = (h.nrows(), a.nrows());
    let big = Mat::from_fn(nx + m, nx + m, |i, j| match (i < nx, j < nx) {
        (true, true) => h[(i, j)],
        (true, false) => a[(j - nx, i)],
        (false, true) => -a[(i - nx, j)],
        (false, false) => 0.0,
    });
    let q = Col::from_fn(nx + m, |i| if i < nx { f[i] } else { b[i - nx] });
    let d = Col::from_fn(nx + m, |i| if i < nx { g[i] } else { e[i - nx] });
    Plcp::mixed(big.as_ref(), q.as_ref(), d.as_ref(), nx)
}

/// The condensed MPC problem of a double integrator (position, velocity;
/// input = acceleration) over `n` steps of `dt`, with `|u_k| <= 1` and every
/// position `<= p_max`: `H`, `F` (the linear term is `F x0`), `A`, `b`, `E`
/// (the bounds are `A U <= b + E x0`). A path of initial states
/// `x0(L) = x0a + L (x0b - x0a)` makes `f + L g` and `b + L e` of
/// [`parametric_qp`] with `g = F dx0`, `e = E dx0`.
pub struct Mpc {
    /// Hessian `Gamma' Qbar Gamma + 0.1 I`.
    pub h: Mat<f64>,
    /// Linear term per unit initial state, `Gamma' Qbar Phi` (`n x 2`).
    pub f: Mat<f64>,
    /// Constraint rows (`3n x n`).
    pub a: Mat<f64>,
    /// Constraint bounds at `x0 = 0`.
    pub b: Col<f64>,
    /// Bound change per unit initial state (`3n x 2`).
    pub e: Mat<f64>,
}

impl Mpc {
    /// The problem over `n` steps of `dt` with position limit `p_max`.
    pub fn double_integrator(n: usize, dt: f64, p_max: f64) -> Self {
        // x_{k+1} = Ad x_k + Bd u_k; the state after step k+1 from x0 and u_0..u_k
        let ad = |k: usize| -> [[f64; 2]; 2] { [[1.0, dt * k as f64], [0.0, 1.0]] }; // Ad^k
        let bd = [0.5 * dt * dt, dt];
        let phi = Mat::from_fn(2 * n, 2, |r, c| ad(r / 2 + 1)[r % 2][c]);
        let gamma = Mat::from_fn(2 * n, n, |r, j| {
            let k = r / 2;
            if j > k {
                return 0.0;
            }
            let a = ad(k - j);
            a[r % 2][0] * bd[0] + a[r % 2][1] * bd[1]
        });
        let qbar = Col::from_fn(2 * n, |r| if r % 2 == 0 { 10.0 } else { 1.0 });
        let h = Mat::from_fn(n, n, |i, j| {
            let s: f64 = (0..2 * n)
                .map(|r| gamma[(r, i)] * qbar[r] * gamma[(r, j)])
                .sum();
            s + if i == j { 0.1 } else { 0.0 }
        });
        let f = Mat::from_fn(n, 2, |i, c| {
            (0..2 * n)
                .map(|r| gamma[(r, i)] * qbar[r] * phi[(r, c)])
                .sum()
        });
        let a = Mat::from_fn(3 * n, n, |r, j| match r / n {
            0 => f64::from(u8::from(r == j)),
            1 => -f64::from(u8::from(r - n == j)),
            _ => gamma[(2 * (r - 2 * n), j)],
        });
        let b = Col::from_fn(3 * n, |r| if r < 2 * n { 1.0 } else { p_max });
        let e = Mat::from_fn(3 * n, 2, |r, c| {
            if r < 2 * n {
                0.0
            } else {
                -phi[(2 * (r - 2 * n), c)]
            }
        });
        Self { h, f, a, b, e }
    }

    /// The homotopy's PLCP from initial state `x0a` (`L = 0`) to `x0b` (`L = 1`).
    pub fn homotopy(&self, x0a: [f64; 2], x0b: [f64; 2]) -> Result<Plcp<f64>, PlcpError> {
        let dx = [x0b[0] - x0a[0], x0b[1] - x0a[1]];
        let lin = |m: &Mat<f64>, x: [f64; 2]| {
            Col::from_fn(m.nrows(), |i| m[(i, 0)] * x[0] + m[(i, 1)] * x[1])
        };
        let f = lin(&self.f, x0a);
        let g = lin(&self.f, dx);
        let shift = lin(&self.e, x0a);
        let b = Col::from_fn(self.b.nrows(), |i| self.b[i] + shift[i]);
        let e = lin(&self.e, dx);
        parametric_qp(
            self.h.as_ref(),
            f.as_ref(),
            g.as_ref(),
            self.a.as_ref(),
            b.as_ref(),
            e.as_ref(),
        )?
        .with_range(0.0, Some(1.0))
    }
}

/// A seeded LASSO problem `(X, y)`, `n x p` Gaussian, `y = X b + noise/2` with
/// five nonzero `b`; with `collinear`, column 1 copies column 0, column 2 is
/// `-2` times column 3 and column 5 the sum of columns 6 and 7 (`p >= 8`).
pub fn lasso_data(n: usize, p: usize, seed: u64, collinear: bool) -> (Mat<f64>, Col<f64>) {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut x = Mat::from_fn(n, p, |_, _| crate::random::gaussian(&mut rng));
    if collinear {
        for i in 0..n {
            x[(i, 1)] = x[(i, 0)];
            x[(i, 2)] = -2.0 * x[(i, 3)];
            x[(i, 5)] = x[(i, 6)] + x[(i, 7)];
        }
    }
    let mut b = Col::<f64>::zeros(p);
    for _ in 0..5 {
        b[rng.gen_range(0..p)] = 3.0 * crate::random::gaussian(&mut rng);
    }
    let y = Col::from_fn(n, |i| {
        (0..p).map(|j| x[(i, j)] * b[j]).sum::<f64>() + 0.5 * crate::random::gaussian(&mut rng)
    });
    (x, y)
}

/// A seeded portfolio: covariance `F F' + diag` (three factors) and means in
/// `[0.02, 0.12]`.
pub fn portfolio(n: usize, seed: u64) -> (Mat<f64>, Col<f64>) {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let f = Mat::from_fn(n, 3, |_, _| 0.1 * crate::random::gaussian(&mut rng));
    let diag: Vec<f64> = (0..n).map(|_| rng.gen_range(0.01..0.04)).collect();
    let s = Mat::from_fn(n, n, |i, j| {
        (0..3).map(|k| f[(i, k)] * f[(j, k)]).sum::<f64>() + if i == j { diag[i] } else { 0.0 }
    });
    let mu = Col::from_fn(n, |_| rng.gen_range(0.02..0.12));
    (s, mu)
}
