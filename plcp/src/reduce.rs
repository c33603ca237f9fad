//! Reduction of a mixed PLCP to standard form by a Schur complement on its free block.
//!
//! With `F = M[u, u]` nonsingular, the equality rows give
//! `u = -F^{-1} (M[u, z] z + q_u + L d_u)`, and the complementary rows become
//!
//! ```text
//! w = (M[z,z] - M[z,u] F^{-1} M[u,z]) z + (q_z - M[z,u] F^{-1} q_u) + L (d_z - M[z,u] F^{-1} d_u).
//! ```

use crate::error::PlcpError;
use crate::problem::Plcp;
use crate::scalar::Scalar;
use crate::tolerance::rank_tol;
use faer::{Col, Mat};

/// The reduced problem and what it takes to recover `u`.
pub struct Reduction<T: Scalar> {
    /// The standard-form problem in `z` alone.
    pub reduced: Plcp<T>,
    /// `G = F^{-1} [M[u,z] | q_u | d_u]`: `u = -(G_z z + G_q + L G_d)`.
    g: Mat<T>,
    /// Estimate of the condition number of the free block `F` (ratio of the
    /// largest to the smallest pivot of its full-pivoting LU, a lower bound
    /// within a modest factor): the reduced data carry an error of about
    /// `eps` times this.
    pub cond: f64,
}

/// Numerical rank of a square matrix by full-pivoting LU.
pub fn numerical_rank<T: Scalar>(f: faer::MatRef<'_, T>) -> usize {
    let p = f.nrows();
    if p == 0 {
        return 0;
    }
    let lu = f.full_piv_lu();
    let u = lu.U();
    let k = p.min(u.ncols());
    let largest = (0..k).fold(T::zero(), |a, i| a.max(u[(i, i)].abs()));
    if largest == T::zero() {
        return 0;
    }
    let tol = rank_tol(p, largest);
    (0..k).filter(|&i| u[(i, i)].abs() > tol).count()
}

/// Largest over smallest pivot of a full-pivoting LU of a square matrix
/// (infinite when a pivot is zero): a cheap estimate of its condition number.
pub fn pivot_ratio<T: Scalar>(f: faer::MatRef<'_, T>) -> f64 {
    let p = f.nrows();
    if p == 0 {
        return 1.0;
    }
    let lu = f.full_piv_lu();
    let u = lu.U();
    let k = p.min(u.ncols());
    let (mut hi, mut lo) = (0.0f64, f64::INFINITY);
    for i in 0..k {
        let v = u[(i, i)].abs().to_f64();
        hi = hi.max(v);
        lo = lo.min(v);
    }
    if lo == 0.0 {
        f64::INFINITY
    } else {
        hi / lo
    }
}

impl<T: Scalar> Reduction<T> {
    /// Eliminates the free variables. `Err(SingularFreeBlock)` if the free block is singular.
    pub fn new(problem: &Plcp<T>) -> Result<Self, PlcpError> {
        let p = problem.free();
        let n = problem.n();
        let m = problem.m();
        let f = m.submatrix(0, 0, p, p);
        let rank = numerical_rank(f);
        if rank < p {
            return Err(PlcpError::SingularFreeBlock { p, rank });
        }
        let mut rhs = Mat::<T>::zeros(p, n + 2);
        for i in 0..p {
            for j in 0..n {
                rhs[(i, j)] = m[(i, p + j)];
            }
            rhs[(i, n)] = problem.q()[i];
            rhs[(i, n + 1)] = problem.d()[i];
        }
        let g = crate::linalg::solve(f, rhs.as_ref())
            .ok_or(PlcpError::SingularFreeBlock { p, rank })?;
        let mzu = m.submatrix(p, 0, n, p);
        let prod = crate::linalg::matmul(mzu, g.as_ref());
        // Entries that cancel to the rounding level of the terms that formed them
        // are zero: pivoting on such noise would follow a path that does not exist.
        let absmzu = Mat::from_fn(n, p, |i, j| mzu[(i, j)].abs());
        let absg = Mat::from_fn(p, n + 2, |i, j| g[(i, j)].abs());
        let size = crate::linalg::matmul(absmzu.as_ref(), absg.as_ref());
        let noise = T::from_f64(64.0 * (p + 1) as f64) * T::eps();
        let clean = |v: T, a: T, s: T| {
            if v.abs() <= noise * (a.abs() + s) {
                T::zero()
            } else {
                v
            }
        };
        let mr = Mat::from_fn(n, n, |i, j| {
            let a = m[(p + i, p + j)];
            clean(a - prod[(i, j)], a, size[(i, j)])
        });
        let qr = Col::from_fn(n, |i| {
            let a = problem.q()[p + i];
            clean(a - prod[(i, n)], a, size[(i, n)])
        });
        let dr = Col::from_fn(n, |i| {
            let a = problem.d()[p + i];
            clean(a - prod[(i, n + 1)], a, size[(i, n + 1)])
        });
        for v in mr
            .col_iter()
            .flat_map(|c| c.iter().copied())
            .chain(qr.iter().copied())
        {
            if !v.is_finite() {
                return Err(PlcpError::SingularFreeBlock { p, rank: p - 1 });
            }
        }
        let reduced = Plcp::new(mr.as_ref(), qr.as_ref(), dr.as_ref())?
            .with_range(problem.lambda0(), problem.lambda_max())?;
        let cond = pivot_ratio(f);
        Ok(Self { reduced, g, cond })
    }

    /// `u` at parameter `lambda` for the complementary part `z`.
    pub fn recover_u(&self, z: &Col<T>, lambda: T) -> Col<T> {
        let p = self.g.nrows();
        let n = z.nrows();
        Col::from_fn(p, |i| {
            let mut s = self.g[(i, n)] + lambda * self.g[(i, n + 1)];
            for j in 0..n {
                s += self.g[(i, j)] * z[j];
            }
            -s
        })
    }

    /// `du/dL` for a slope `dz` of `z`.
    pub fn recover_du(&self, dz: &Col<T>) -> Col<T> {
        let p = self.g.nrows();
        let n = dz.nrows();
        Col::from_fn(p, |i| {
            let mut s = self.g[(i, n + 1)];
            for j in 0..n {
                s += self.g[(i, j)] * dz[j];
            }
            -s
        })
    }
}
