//! Velocities and displacements from rest for a load history `lambda(t)`, when
//! the accelerations are piecewise affine in `Lambda`.
//!
//! Time is cut at the knots of the history and at the times where `lambda(t)`
//! crosses a breakpoint; on each cut piece `q_dd(t) = b + s lambda(t)` with fixed
//! `b`, `s`, and the step from `(q, q_dot)` at its start is exact:
//!
//! ```text
//! q_dot(t) = q_dot_a + b tau + s I1(tau),     q(t) = q_a + q_dot_a tau + b tau^2/2 + s I2(tau)
//! I1 = integral of lambda over the piece,     I2 = its second integral,    tau = t - t_a
//! ```
//!
//! * ramp and table (piecewise linear): `lambda = lambda_a + r tau`, so
//!   `I1 = lambda_a tau + r tau^2/2`, `I2 = lambda_a tau^2/2 + r tau^3/6`;
//! * saturating `peak (1 - exp(-t/T))`: with `D = peak - lambda_a`, `x = tau/T`,
//!   `I1 = lambda_a tau + D T g2(x)`, `I2 = lambda_a tau^2/2 + D T^2 g3(x)`, where
//!   `g2 = x - 1 + e^-x` and `g3 = x^2/2 - x + 1 - e^-x`, summed as series for
//!   `x < 1/2` (no cancellation).
//!
//! No quadrature is needed for the built-in histories; the method is exact to
//! rounding, and [`METHOD`] states it in the reports.

use crate::model::History;

/// The integration method, as stated in reports.
pub const METHOD: &str = "exact: closed-form integration on pieces cut at the history's knots and at the breakpoint crossings (accelerations affine in lambda, lambda(t) linear or 1-exp on each piece)";

/// Accelerations affine in `Lambda` on `[lambda_from, lambda_to]`: `q_dd = base + slope Lambda`.
#[derive(Clone, Debug, PartialEq)]
pub struct AffinePiece {
    /// Start.
    pub lambda_from: f64,
    /// End (may be infinite).
    pub lambda_to: f64,
    /// Base at `Lambda = 0`.
    pub base: Vec<f64>,
    /// Slope.
    pub slope: Vec<f64>,
}

/// Displacements and velocities at the requested times.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    /// Times.
    pub times: Vec<f64>,
    /// `lambda(t)` at those times.
    pub lambda: Vec<f64>,
    /// `q(t)`, one vector per time.
    pub displacement: Vec<Vec<f64>>,
    /// `q_dot(t)`, one vector per time.
    pub velocity: Vec<Vec<f64>>,
}

/// `x - 1 + e^-x`.
pub(crate) fn g2(x: f64) -> f64 {
    if x < 0.5 {
        // sum_{k>=2} (-x)^k / k!
        let (mut term, mut sum) = (x * x / 2.0, 0.0);
        for k in 3..30 {
            sum += term;
            term *= -x / k as f64;
        }
        sum
    } else {
        x + (-x).exp_m1()
    }
}

/// `x^2/2 - x + 1 - e^-x`.
pub(crate) fn g3(x: f64) -> f64 {
    if x < 0.5 {
        // sum_{k>=3} -(-x)^k / k!
        let (mut term, mut sum) = (x * x * x / 6.0, 0.0);
        for k in 4..30 {
            sum += term;
            term *= -x / k as f64;
        }
        sum
    } else {
        0.5 * x * x - x - (-x).exp_m1()
    }
}

/// First and second integrals of `lambda` over `[ta, ta + tau]`, the history
/// having no knot inside.
pub(crate) fn integrals(history: &History, ta: f64, tau: f64) -> (f64, f64) {
    let la = history.lambda(ta);
    match history {
        History::Saturating { peak, tau: tc } => {
            let d = peak - la;
            let x = tau / tc;
            (
                la * tau + d * tc * g2(x),
                0.5 * la * tau * tau + d * tc * tc * g3(x),
            )
        }
        _ => {
            let r = if tau > 0.0 {
                (history.lambda(ta + tau) - la) / tau
            } else {
                0.0
            };
            (
                la * tau + 0.5 * r * tau * tau,
                0.5 * la * tau * tau + r * tau * tau * tau / 6.0,
            )
        }
    }
}

/// The knots of the integration of accelerations affine on pieces covering
/// `ranges` (`(lambda_from, lambda_to)` of each): every requested time, the
/// history's knots and the times `lambda(t)` reaches a piece's start, sorted,
/// and per window between consecutive knots the piece whose accelerations
/// hold there (`None`: an empty window, skipped). [`integrate`] steps through
/// them; a fold over the pieces ([`crate::stream`]) steps through the same.
pub(crate) fn schedule(
    ranges: &[(f64, f64)],
    history: &History,
    times: &[f64],
) -> (Vec<f64>, Vec<Option<usize>>) {
    let t_end = times.iter().cloned().fold(0.0f64, f64::max);
    let mut knots: Vec<f64> = vec![0.0, t_end];
    knots.extend(times.iter().cloned());
    knots.extend(history.knots(t_end));
    for p in ranges {
        if let Some(t) = history.time_at(p.0) {
            if t > 0.0 && t < t_end {
                knots.push(t);
            }
        }
    }
    knots.sort_by(f64::total_cmp);
    knots.dedup();
    let piece_at = |l: f64| -> usize {
        ranges
            .iter()
            .position(|p| l >= p.0 && l <= p.1)
            .unwrap_or(if ranges.is_empty() {
                0
            } else {
                ranges.len() - 1
            })
    };
    let windows = knots
        .windows(2)
        .map(|w| {
            let (ta, tb) = (w[0], w[1]);
            (tb - ta > 0.0 && !ranges.is_empty()).then(|| piece_at(history.lambda(0.5 * (ta + tb))))
        })
        .collect();
    (knots, windows)
}

/// One exact step of `(q, v)` from `ta` to `tb` under `q_dd = base + slope
/// lambda(t)` (the history having no knot inside).
pub(crate) fn step(
    history: &History,
    (ta, tb): (f64, f64),
    (base, slope): (&[f64], &[f64]),
    q: &mut [f64],
    v: &mut [f64],
) {
    let tau = tb - ta;
    let (i1, i2) = integrals(history, ta, tau);
    for j in 0..q.len() {
        let (b, s) = (base[j], slope[j]);
        q[j] += v[j] * tau + 0.5 * b * tau * tau + s * i2;
        v[j] += b * tau + s * i1;
    }
}

/// Integrates from rest up to the largest requested time. `times` must be
/// nonnegative; `pieces` must cover `[0, lambda(t)]` for every requested `t`
/// (beyond the last piece its affine form is extended).
pub fn integrate(pieces: &[AffinePiece], history: &History, times: &[f64]) -> Motion {
    let nq = pieces.first().map(|p| p.base.len()).unwrap_or(0);
    let ranges: Vec<(f64, f64)> = pieces
        .iter()
        .map(|p| (p.lambda_from, p.lambda_to))
        .collect();
    let (knots, windows) = schedule(&ranges, history, times);
    // the state is written straight into the requested times' slots (a copy
    // at every knot, kept in a map, held two more copies of the series)
    let mut slots: std::collections::HashMap<u64, Vec<usize>> = std::collections::HashMap::new();
    for (k, t) in times.iter().enumerate() {
        slots.entry(t.to_bits()).or_default().push(k);
    }
    let mut displacement: Vec<Vec<f64>> = vec![Vec::new(); times.len()];
    let mut velocity: Vec<Vec<f64>> = vec![Vec::new(); times.len()];
    let mut q = vec![0.0; nq];
    let mut v = vec![0.0; nq];
    let mut record = |t: f64, q: &[f64], v: &[f64]| {
        if let Some(ks) = slots.get(&t.to_bits()) {
            for &k in ks {
                displacement[k] = q.to_vec();
                velocity[k] = v.to_vec();
            }
        }
    };
    record(0.0, &q, &v);
    for (w, piece) in knots.windows(2).zip(windows) {
        let Some(piece) = piece else {
            continue;
        };
        let p = &pieces[piece];
        step(history, (w[0], w[1]), (&p.base, &p.slope), &mut q, &mut v);
        record(w[1], &q, &v);
    }
    // a time no knot reached (none: every time is a knot) reads as rest
    for (d, vv) in displacement.iter_mut().zip(velocity.iter_mut()) {
        if d.len() != nq {
            *d = vec![0.0; nq];
            *vv = vec![0.0; nq];
        }
    }
    Motion {
        times: times.to_vec(),
        lambda: times.iter().map(|&t| history.lambda(t)).collect(),
        displacement,
        velocity,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Gauss-Legendre (5 points) composite quadrature of q_dd, twice, as an independent check.
    fn quadrature(pieces: &[AffinePiece], history: &History, t: f64, n: usize) -> (f64, f64) {
        let acc = |s: f64| {
            let l = history.lambda(s);
            let p = pieces
                .iter()
                .find(|p| l >= p.lambda_from && l <= p.lambda_to)
                .unwrap_or(&pieces[pieces.len() - 1]);
            p.base[0] + p.slope[0] * l
        };
        let xs = [
            0.0,
            -0.538_469_310_105_683_1,
            0.538_469_310_105_683_1,
            -0.906_179_845_938_664,
            0.906_179_845_938_664,
        ];
        let ws = [
            0.568_888_888_888_888_9,
            0.478_628_670_499_366_5,
            0.478_628_670_499_366_5,
            0.236_926_885_056_189_1,
            0.236_926_885_056_189_1,
        ];
        // v(t) = int_0^t a, q(t) = int_0^t (t - s) a(s) ds
        let h = t / n as f64;
        let (mut v, mut q) = (0.0, 0.0);
        for i in 0..n {
            let c = (i as f64 + 0.5) * h;
            for (x, w) in xs.iter().zip(ws) {
                let s = c + 0.5 * h * x;
                let a = acc(s);
                v += 0.5 * h * w * a;
                q += 0.5 * h * w * (t - s) * a;
            }
        }
        (q, v)
    }

    /// Times in any order, repeated, and zero: each gets the state of its own
    /// time, the same bits as the same time asked alone.
    #[test]
    fn times_in_any_order_get_their_own_state() {
        let pieces = vec![AffinePiece {
            lambda_from: 0.0,
            lambda_to: f64::INFINITY,
            base: vec![-1.0, 0.5],
            slope: vec![2.0, 0.25],
        }];
        let h = History::Ramp { rate: 1.5 };
        let times = [1.3, 0.5, 1.3, 0.0, 2.0];
        let m = integrate(&pieces, &h, &times);
        assert_eq!(m.displacement[0], m.displacement[2]);
        assert_eq!(m.velocity[0], m.velocity[2]);
        assert_eq!(m.displacement[3], vec![0.0, 0.0]);
        assert_eq!(m.velocity[3], vec![0.0, 0.0]);
        let sorted = integrate(&pieces, &h, &[0.0, 0.5, 1.3, 2.0]);
        for (k, j) in [(0, 2), (1, 1), (3, 0), (4, 3)] {
            assert_eq!(m.displacement[k], sorted.displacement[j], "{k}");
            assert_eq!(m.velocity[k], sorted.velocity[j], "{k}");
        }
        assert!(m.displacement[4][0] != 0.0);
    }

    #[test]
    fn series_match_direct_formulas() {
        for &x in &[0.3, 0.49, 0.51, 1.0] {
            assert!((g2(x) - (x - 1.0 + (-x).exp())).abs() < 1e-15);
            assert!((g3(x) - (0.5 * x * x - x + 1.0 - (-x).exp())).abs() < 1e-15);
        }
        let x: f64 = 1e-6;
        let r = x.powi(3) / 6.0 - x.powi(4) / 24.0 + x.powi(5) / 120.0;
        assert!((g3(x) - r).abs() < 1e-14 * r);
    }

    #[test]
    fn closed_form_agrees_with_quadrature() {
        // rigid up to 1, then affine with a kink at 2
        let pieces = vec![
            AffinePiece {
                lambda_from: 0.0,
                lambda_to: 1.0,
                base: vec![0.0],
                slope: vec![0.0],
            },
            AffinePiece {
                lambda_from: 1.0,
                lambda_to: 2.0,
                base: vec![-3.0],
                slope: vec![3.0],
            },
            AffinePiece {
                lambda_from: 2.0,
                lambda_to: f64::INFINITY,
                base: vec![-7.0],
                slope: vec![5.0],
            },
        ];
        let histories = [
            History::Ramp { rate: 1.5 },
            History::Table {
                points: vec![(0.0, 0.0), (1.0, 1.5), (2.0, 1.5), (3.0, 4.0)],
            },
            History::Saturating {
                peak: 4.0,
                tau: 0.7,
            },
        ];
        for h in &histories {
            let times = [0.5, 1.3, 2.0, 3.7];
            let m = integrate(&pieces, h, &times);
            for (k, &t) in times.iter().enumerate() {
                let (q, v) = quadrature(&pieces, h, t, 4000);
                assert!(
                    (m.displacement[k][0] - q).abs() < 1e-8 * (1.0 + q.abs()),
                    "{h:?} t={t}: {} vs {q}",
                    m.displacement[k][0]
                );
                assert!(
                    (m.velocity[k][0] - v).abs() < 1e-8 * (1.0 + v.abs()),
                    "{h:?} t={t}: {} vs {v}",
                    m.velocity[k][0]
                );
            }
        }
    }
}
