//! Targets: when a node, moving along a given direction, first closes a gap
//! (a pipe whip restraint, a wall, a neighbouring component), how fast it is
//! moving there and how much kinetic energy the whole structure carries then
//! (what the restraint must absorb).
//!
//! For a target at node `k` with unit direction `d` and gap `g > 0`, let
//! `u(t) = d . r_k(t)`, `r_k` the node's translation (the rotations take no
//! part). The answer is the first `t*` in the analysed range `[0, t_end]` with
//!
//! ```text
//! f(t) = u(t) - g >= 0,      velocity  u'(t*),      T(t*) = 1/2 q_dot' M_q q_dot
//! ```
//!
//! or "never reached" when `f < 0` on the whole range.
//!
//! **Exactly from the piecewise response.** Time is cut, as in
//! [`crate::integrate`], at the history's knots and where `lambda(t)` crosses
//! a breakpoint. On a cut piece starting at `t_a`, with the accelerations
//! `q_dd = b + s lambda(t)` and `tau = t - t_a`,
//!
//! ```text
//! f(tau)   = u_a + v_a tau + b_d tau^2/2 + s_d I2(tau) - g
//! f'(tau)  = v_a + b_d tau + s_d I1(tau)
//! f''(tau) = b_d + s_d lambda(t_a + tau)
//! ```
//!
//! (`b_d = d . b`, `s_d = d . s` over the node's translations; `I1`, `I2` the
//! first and second integrals of `lambda` over the piece). For a ramp or a
//! table, `f` is a cubic in `tau`; for the saturating history it is a cubic
//! plus an exponential. Either way `lambda` is monotone, so `f''` is monotone
//! on the piece and changes sign at most once: `f'` has at most two zeros and
//! `f` at most three monotone stretches. The search uses just that:
//!
//! 1. the zero of `f''` (bisection, where its ends differ in sign) splits the
//!    piece into stretches where `f'` is monotone;
//! 2. the zero of `f'` on each (bisection) splits it into stretches where `f`
//!    is monotone;
//! 3. the first stretch, in time order, whose end value has `f >= 0` holds the
//!    first arrival; `f` rises there from a negative value, and bisection
//!    finds the crossing.
//!
//! No root is missed (a tangential touch `f = 0, f' = 0` is the end of a
//! monotone stretch and is found), and no later root is reported before an
//! earlier one. **Tolerance:** every bisection runs until its two ends are
//! adjacent doubles (at most 64 halvings of the piece as floats; see
//! `bisect`), and returns the end where `f >= 0`. The reported time is
//! therefore the first double at which the evaluated `f` is nonnegative; its
//! error is the rounding error of evaluating `f` (a few ulp of the
//! displacement scale `g`) divided by the speed `|u'(t*)|`, and
//! `O(sqrt(ulp))` relative for a tangential arrival where `u'(t*) = 0`.
//!
//! The response is that of the PLCP path (system (9)), valid up to the first
//! deactivation the path shows (see [`crate::hinge`]); an arrival after it is
//! flagged (`after_deactivation`).

use crate::assemble::System;
use crate::integrate::integrals;
use crate::model::{Component, History};
use crate::response::Response;

/// A `[[target]]` of the scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Target {
    /// Index of the node.
    pub node: usize,
    /// Unit direction in global `[x, y, z]` (in the model's translations: `z`
    /// is zero for a planar scene, `x` and `y` for a grillage).
    pub direction: [f64; 3],
    /// The gap to close, positive.
    pub gap: f64,
}

/// The first arrival of a node at its target.
#[derive(Clone, Debug, PartialEq)]
pub struct Arrival {
    /// The target as given.
    pub target: Target,
    /// True when the gap closes within the analysed range.
    pub reached: bool,
    /// Time of the first arrival (`None` when not reached).
    pub time: Option<f64>,
    /// `lambda(time)`.
    pub lambda: Option<f64>,
    /// Velocity along the direction at that time.
    pub velocity: Option<f64>,
    /// Kinetic energy of the whole structure at that time, `1/2 q_dot' M_q q_dot`.
    pub kinetic_energy: Option<f64>,
    /// The end of the analysed range.
    pub t_end: f64,
    /// True when the arrival comes after the first deactivation of the path,
    /// where the PLCP response is no longer valid (a time-stepping
    /// continuation is then the better answer).
    pub after_deactivation: bool,
}

impl Target {
    /// The displacement (or velocity) of the target's node along its
    /// direction, from a vector over the system's kept coordinates.
    pub fn project(&self, system: &System, q: &[f64]) -> f64 {
        system
            .coordinates
            .iter()
            .zip(q)
            .filter(|(c, _)| c.node == self.node)
            .map(|(c, v)| v * along(&self.direction, c.component))
            .sum()
    }
}

/// The direction's component along a generalised coordinate's axis (zero for rotations).
pub fn along(direction: &[f64; 3], c: Component) -> f64 {
    match c {
        Component::X => direction[0],
        Component::Y => direction[1],
        Component::Z => direction[2],
        Component::Rx | Component::Ry | Component::Rz => 0.0,
    }
}

/// Bisection of `[lo, hi]` with `bad(lo)` and `!bad(hi)`, down to adjacent
/// doubles (or 200 halvings, more than enough for any double interval): the
/// smallest `hi` found with `!bad(hi)`.
pub(crate) fn bisect(mut lo: f64, mut hi: f64, bad: impl Fn(f64) -> bool) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if bad(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi
}

/// The zero of a monotone function on `[0, len]` where its end values differ
/// in sign (strictly), if any.
fn monotone_zero(len: f64, h: impl Fn(f64) -> f64) -> Option<f64> {
    let (h0, h1) = (h(0.0), h(len));
    if h0 == 0.0 || h1 == 0.0 || (h0 > 0.0) == (h1 > 0.0) {
        return None;
    }
    let up = h1 > 0.0;
    Some(bisect(0.0, len, |x| (h(x) > 0.0) != up))
}

/// The first `tau` in `[0, len]` with `f(tau) >= 0`, if any, for `f` with
/// derivative `fd` and second derivative `fdd`, `fdd` monotone: the stretches
/// where `fd`, then `f`, is monotone, and bisection on the first stretch whose
/// end reaches zero (the module's steps 1 to 3).
fn first_root(
    len: f64,
    f: impl Fn(f64) -> f64,
    fd: impl Fn(f64) -> f64,
    fdd: impl Fn(f64) -> f64,
) -> Option<f64> {
    let mut ends = vec![0.0];
    let mut split1 = vec![0.0];
    split1.extend(monotone_zero(len, fdd));
    split1.push(len);
    for w in split1.windows(2) {
        let (a, c) = (w[0], w[1]);
        if let Some(z) = monotone_zero(c - a, |x| fd(a + x)) {
            ends.push(a + z);
        }
        ends.push(c);
    }
    for w in ends.windows(2) {
        let (a, c) = (w[0], w[1]);
        if f(a) >= 0.0 {
            return Some(a);
        }
        if c > a && f(c) >= 0.0 {
            return Some(bisect(a, c, |x| f(x) < 0.0));
        }
    }
    None
}

/// One cut piece of time: the projected state at its start and the affine
/// accelerations on it.
struct Cut {
    ta: f64,
    tb: f64,
    /// Index of the interval of the response.
    interval: usize,
}

/// The first arrival of every target, from the response's intervals (the
/// accelerations affine in `Lambda`), the history and the end time of the
/// analysed range.
pub fn arrivals(
    system: &System,
    response: &Response,
    history: &History,
    deactivation_lambda: Option<f64>,
    targets: &[Target],
) -> Vec<Arrival> {
    let t_end = response.time.times.last().copied().unwrap_or(0.0);
    let nq = system.coordinates.len();
    let ivs = &response.intervals;
    // per interval, accelerations of the kept coordinates: base and slope
    let acc: Vec<(Vec<f64>, Vec<f64>)> = ivs
        .iter()
        .map(|iv| {
            let pick = |k: usize| {
                system
                    .coordinates
                    .iter()
                    .map(|c| iv.accelerations[c.node][c.component.index()][k])
                    .collect::<Vec<f64>>()
            };
            (pick(0), pick(1))
        })
        .collect();
    // the cuts of time, as in crate::integrate
    let mut knots = vec![0.0, t_end];
    knots.extend(history.knots(t_end));
    for iv in ivs {
        if let Some(t) = history.time_at(iv.lambda_from) {
            if t > 0.0 && t < t_end {
                knots.push(t);
            }
        }
    }
    knots.sort_by(f64::total_cmp);
    knots.dedup();
    let interval_at = |l: f64| -> usize {
        ivs.iter()
            .position(|iv| l >= iv.lambda_from && l <= iv.lambda_to)
            .unwrap_or(ivs.len().saturating_sub(1))
    };
    let cuts: Vec<Cut> = knots
        .windows(2)
        .filter(|w| w[1] > w[0])
        .map(|w| Cut {
            ta: w[0],
            tb: w[1],
            interval: interval_at(history.lambda(0.5 * (w[0] + w[1]))),
        })
        .collect();
    let kinetic = |v: &[f64]| {
        0.5 * v
            .iter()
            .zip(&system.mass)
            .map(|(v, m)| m * v * v)
            .sum::<f64>()
    };
    let mut out = Vec::with_capacity(targets.len());
    for target in targets {
        let d: Vec<f64> = system
            .coordinates
            .iter()
            .map(|c| {
                if c.node == target.node {
                    along(&target.direction, c.component)
                } else {
                    0.0
                }
            })
            .collect();
        let dot = |x: &[f64]| x.iter().zip(&d).map(|(a, b)| a * b).sum::<f64>();
        let mut q = vec![0.0; nq];
        let mut v = vec![0.0; nq];
        let mut found = None;
        if !ivs.is_empty() && d.iter().any(|&x| x != 0.0) {
            for cut in &cuts {
                let (base, slope) = &acc[cut.interval];
                let (ua, va, bd, sd) = (dot(&q), dot(&v), dot(base), dot(slope));
                let len = cut.tb - cut.ta;
                let f = |tau: f64| {
                    let (_, i2) = integrals(history, cut.ta, tau);
                    ua + va * tau + 0.5 * bd * tau * tau + sd * i2 - target.gap
                };
                let fd = |tau: f64| {
                    let (i1, _) = integrals(history, cut.ta, tau);
                    va + bd * tau + sd * i1
                };
                let fdd = |tau: f64| bd + sd * history.lambda(cut.ta + tau);
                if let Some(tau) = first_root(len, f, fd, fdd) {
                    let (i1, _) = integrals(history, cut.ta, tau);
                    let vel: Vec<f64> = (0..nq)
                        .map(|j| v[j] + base[j] * tau + slope[j] * i1)
                        .collect();
                    found = Some((cut.ta + tau, fd(tau), kinetic(&vel)));
                    break;
                }
                // the exact step to the end of the cut (as crate::integrate)
                let (i1, i2) = integrals(history, cut.ta, len);
                for j in 0..nq {
                    let (b, s) = (base[j], slope[j]);
                    q[j] += v[j] * len + 0.5 * b * len * len + s * i2;
                    v[j] += b * len + s * i1;
                }
            }
        }
        out.push(match found {
            Some((t, vel, ke)) => {
                let l = history.lambda(t);
                Arrival {
                    target: target.clone(),
                    reached: true,
                    time: Some(t),
                    lambda: Some(l),
                    velocity: Some(vel),
                    kinetic_energy: Some(ke),
                    t_end,
                    after_deactivation: deactivation_lambda.is_some_and(|ld| l > ld),
                }
            }
            None => Arrival {
                target: target.clone(),
                reached: false,
                time: None,
                lambda: None,
                velocity: None,
                kinetic_energy: None,
                t_end,
                after_deactivation: false,
            },
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A hump that rises above zero and falls back inside one piece (both
    /// ends negative): found, at its first root, not its second.
    #[test]
    fn first_root_inside_a_hump() {
        // f = -0.1 + tau - tau^2 on [0, 1]: roots (1 -+ sqrt(0.6)) / 2
        let r = first_root(1.0, |t| -0.1 + t - t * t, |t| 1.0 - 2.0 * t, |_| -2.0).unwrap();
        let exact = (1.0 - 0.6f64.sqrt()) / 2.0;
        assert!((r - exact).abs() < 4.0 * f64::EPSILON, "{r} vs {exact}");
        // a cubic dipping first: f = t^3 - 1.5 t^2 + 0.5 t - 0.01, f'' = 6 t - 3
        // (sign change inside): first root near t = 0.0204
        let f = |t: f64| t * t * t - 1.5 * t * t + 0.5 * t - 0.01;
        let r = first_root(1.2, f, |t| 3.0 * t * t - 3.0 * t + 0.5, |t| 6.0 * t - 3.0).unwrap();
        assert!(f(r) >= 0.0 && f(r - 1e-12) < 0.0, "{r}");
        assert!(r < 0.1);
        // a tangential touch: f = -(t - 0.5)^2, zero only at 0.5
        let r = first_root(
            1.0,
            |t| -(t - 0.5) * (t - 0.5),
            |t| -2.0 * (t - 0.5),
            |_| -2.0,
        );
        assert_eq!(r, Some(0.5));
        // never reached
        assert_eq!(first_root(1.0, |t| -1.0 + 0.5 * t, |_| 0.5, |_| 0.0), None);
    }
}
