//! What a start phase that ends on a ray proves.
//!
//! Lemke's method with a covering vector `c > 0` on the LCP `w = r + M z`
//! (`r = q + L0 d`) may end on a secondary ray `(z, w, z0) + t (v, M v - v0 c, v0)`.
//! That proves nothing by itself: for a P-matrix it cannot happen in exact
//! arithmetic (the LCP has a unique solution), for a general `M` it is a
//! failure of the method. Two checks say what is known:
//!
//! * a **Farkas certificate**: `v >= 0`, `v != 0`, `M' v <= 0` and `r' v < 0`
//!   prove that no `z >= 0` has `r + M z >= 0` (for such `z`,
//!   `v'(r + M z) = r' v + (M' v)' z < 0`), so the LCP is infeasible. For a
//!   copositive-plus `M` the ray's `v` is such a certificate (Cottle, Pang and
//!   Stone, Theorem 4.4.13); it is checked, not assumed, up to rounding: each
//!   `(M' v)_j` at most `CERT_EPS * eps * dim * sum_i abs(M_ij) v_i`, and
//!   `r' v` below minus the same bound on `sum_i abs(r_i) v_i`.
//! * a **P-matrix**: if the symmetric part of `M` is positive definite (a
//!   Cholesky factorisation of `(M + M')/2 - delta I` in `f64` succeeds, `delta =
//!   CERT_EPS * dim * eps_64 * max abs(M_ij)`), `M` is a P-matrix and the LCP
//!   has a solution: a ray is the rounding's doing, never an answer.

use crate::matrix::MatrixRef;
use crate::scalar::Scalar;
use faer::{Col, Mat};

/// The rounding allowance of both checks, in units of `eps` (times `dim`).
pub const CERT_EPS: f64 = 1e3;

/// Orders beyond which the positive-definiteness check (a dense Cholesky
/// factorisation) is not tried.
pub const PD_CHECK_MAX_ORDER: usize = 4000;

/// `Some(why)` if `v` (the `z` part of the ray) is a Farkas certificate of the
/// infeasibility of `r + M z >= 0, z >= 0` up to rounding (module docs).
pub(crate) fn farkas<T: Scalar>(m: MatrixRef<'_, T>, r: &Col<T>, v: &Col<T>) -> Option<String> {
    let n = r.nrows();
    let eps = T::eps().to_f64();
    let vmax = (0..n).fold(0.0f64, |a, i| a.max(v[i].to_f64().abs()));
    if !(vmax > 0.0 && vmax.is_finite()) {
        return None;
    }
    let allow = CERT_EPS * eps * n.max(1) as f64;
    // v >= 0 up to rounding, then its negative noise dropped
    if (0..n).any(|i| v[i].to_f64() < -allow * vmax) {
        return None;
    }
    let v: Vec<f64> = (0..n).map(|i| v[i].to_f64().max(0.0)).collect();
    let mut worst_mtv = f64::NEG_INFINITY;
    for j in 0..n {
        let (mut s, mut a) = (0.0f64, 0.0f64);
        m.for_col(j, |i, mij| {
            let t = mij.to_f64() * v[i];
            s += t;
            a += t.abs();
        });
        if s > allow * a {
            return None;
        }
        worst_mtv = worst_mtv.max(if a > 0.0 { s / a } else { 0.0 });
    }
    let (mut rv, mut ra) = (0.0f64, 0.0f64);
    for i in 0..n {
        let t = r[i].to_f64() * v[i];
        rv += t;
        ra += t.abs();
    }
    (rv < -allow * ra).then(|| {
        format!(
            "the ray's direction v >= 0 is a Farkas certificate (M'v <= 0 to rounding, r'v = {rv:.3e} < 0 with r = q + L0 d): no z >= 0 has q + L0 d + M z >= 0, so there is no solution at L0"
        )
    })
}

/// True if the symmetric part of `m` is positive definite beyond rounding
/// (module docs): then `m` is a P-matrix. `false` when it is not, or when the
/// order exceeds [`PD_CHECK_MAX_ORDER`].
pub(crate) fn symmetric_part_positive_definite<T: Scalar>(m: MatrixRef<'_, T>) -> bool {
    let n = m.nrows();
    if n == 0 || n > PD_CHECK_MAX_ORDER {
        return n == 0;
    }
    let mut a = Mat::<f64>::zeros(n, n);
    let mut big = 0.0f64;
    for j in 0..n {
        m.for_col(j, |i, v| {
            let v = v.to_f64();
            a[(i, j)] += 0.5 * v;
            a[(j, i)] += 0.5 * v;
            big = big.max(v.abs());
        });
    }
    if !(big > 0.0 && big.is_finite()) {
        return false;
    }
    let delta = CERT_EPS * n as f64 * f64::EPSILON * big;
    for i in 0..n {
        a[(i, i)] -= delta;
    }
    a.llt(faer::Side::Lower).is_ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positive_definite_symmetric_part() {
        let pd = faer::mat![[2.0, 3.0], [-3.0, 1.0]]; // symmetric part diag(2, 1)
        assert!(symmetric_part_positive_definite(MatrixRef::Dense(
            pd.as_ref()
        )));
        let indefinite = faer::mat![[-1.0, 2.0], [2.0, -1.0]];
        assert!(!symmetric_part_positive_definite(MatrixRef::Dense(
            indefinite.as_ref()
        )));
        // PSD singular: not positive definite beyond rounding
        let psd = faer::mat![[1.0, 1.0], [1.0, 1.0]];
        assert!(!symmetric_part_positive_definite(MatrixRef::Dense(
            psd.as_ref()
        )));
    }

    #[test]
    fn farkas_certificate() {
        // w0 = -1 - z1: v = e0 gives M'v = (0, -1) <= 0, q'v = -1 < 0
        let m = faer::mat![[0.0, -1.0], [1.0, 0.0]];
        let q = faer::col![-1.0, -1.0];
        let mr = MatrixRef::Dense(m.as_ref());
        assert!(farkas(mr, &q, &faer::col![1.0, 0.0]).is_some());
        // v = e1: M'v = (1, 0) has a positive entry
        assert!(farkas(mr, &q, &faer::col![0.0, 1.0]).is_none());
        // a negative v is no certificate
        assert!(farkas(mr, &q, &faer::col![1.0, -0.5]).is_none());
        // q'v >= 0 is none either
        let q = faer::col![1.0, -1.0];
        assert!(farkas(mr, &q, &faer::col![1.0, 0.0]).is_none());
    }
}
