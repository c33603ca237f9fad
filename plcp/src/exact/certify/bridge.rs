//! Bridges: the exact path across events the float path took as one.

use super::super::rational_to_f64;
use super::super::solution::Solution;
use super::bases::Bases;
use super::interval::{interval, within};
use super::{Certificate, Chain};
use crate::scalar::Scalar;
use num_rational::BigRational;
use num_traits::{Signed, Zero};

/// The most exact bases a bridge may insert between two segments.
pub const MAX_BRIDGE: usize = 8;

/// The exact path from basis `from` at `start` (where `from`'s interval
/// ends as `L` rises) to basis `to`, by complementary pivots: at each step
/// the one basic `z` or `w` that reaches zero there leaves and its
/// complement enters, and the new basis must be feasible where the step
/// starts. Returns the number of bases inserted and where `to` takes over,
/// or `None` (no bridge: the caller reports the gap) when a step is not
/// unique, a basis is singular or infeasible there, the span exceeds
/// `limit` relative to `max(1, |start|)`, or [`MAX_BRIDGE`] bases do not
/// reach `to`.
fn bridge(
    from: &[usize],
    to: &[usize],
    start: &BigRational,
    limit: f64,
    solve: &mut dyn FnMut(&[usize], &mut Certificate) -> Solution,
    cert: &mut Certificate,
) -> Option<(usize, BigRational)> {
    let same = |a: &[usize], b: &[usize]| {
        let (mut a, mut b) = (a.to_vec(), b.to_vec());
        a.sort_unstable();
        b.sort_unstable();
        a == b
    };
    let scale = rational_to_f64(start).abs().max(1.0);
    let (mut cur, mut at) = (from.to_vec(), start.clone());
    let mut s = solve(&cur, cert);
    for step in 0..=MAX_BRIDGE {
        // the basic z or w that reaches zero at `at` as L rises
        let mut leaving = (0..s.basis.len()).filter(|&i| {
            let c = s.basis[i];
            c < s.ncol() && s.signed(c) && {
                let (a, b) = s.affine(i);
                b.is_negative() && (a + b * &at).is_zero()
            }
        });
        let (Some(i), None) = (leaving.next(), leaving.next()) else {
            return None;
        };
        let out = s.basis[i];
        let into = s.var_of(out)?.complement().and_then(|v| s.col_of(v))?;
        let pos = cur.iter().position(|&c| c == out)?;
        cur[pos] = into;
        s = solve(&cur, cert);
        if !s.is_basic(into) {
            return None; // singular: the complement cannot enter
        }
        let (lo, hi) = interval(&s).ok()?;
        if lo.as_ref().is_some_and(|l| l > &at) || hi.as_ref().is_some_and(|h| h < &at) {
            return None;
        }
        if same(&cur, to) {
            return Some((step, at));
        }
        at = hi?;
        if !within(rational_to_f64(&(&at - start)).abs() / scale, limit) {
            return None;
        }
    }
    None
}

/// Where the segment's interval misses the chain's start (as `L` rises),
/// follows the exact path from the previous segment's basis across the gap
/// ([`bridge`]) and moves the start to where this basis takes over.
pub(super) fn bridge_to<T: Scalar>(
    bases: &mut Bases<'_, T>,
    chain: &mut Chain,
    target: &[usize],
    (lo, hi): (&Option<BigRational>, &Option<BigRational>),
    up: bool,
    cert: &mut Certificate,
) {
    let outside = |start: &BigRational| {
        lo.as_ref().is_some_and(|l| l > start) || hi.as_ref().is_some_and(|h| h < start)
    };
    if !outside(&chain.start) || !up {
        return;
    }
    let Some(prev) = &chain.prev_target else {
        return;
    };
    let limit = T::eps().to_f64().sqrt();
    let start = &chain.start;
    if let Some((n, at)) = bridge(
        prev,
        target,
        start,
        limit,
        &mut |b, c| bases.solve(b, c),
        cert,
    ) {
        if !outside(&at) {
            let span =
                rational_to_f64(&(&at - start)).abs() / rational_to_f64(start).abs().max(1.0);
            cert.bridges += n;
            cert.bridge_span = cert.bridge_span.max(span);
            chain.start = at;
        }
    }
}
