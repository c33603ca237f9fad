//! Where a basis is feasible, exactly, and the comparisons of float values
//! with exact ones.

use super::super::short;
use super::super::solution::Solution;
use crate::path::Var;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};

/// The exact interval `[lo, hi]` (`None`: unbounded that way) on which every
/// basic `z`, `w` is nonnegative, or the variable that is negative everywhere.
pub(super) type Interval = (Option<BigRational>, Option<BigRational>);

pub(super) fn interval(s: &Solution) -> Result<Interval, String> {
    // the roots -a_i / b_i compared by their numerators (the denominators are
    // common and positive), reduced once at the end
    let mut lo: Option<(&BigInt, &BigInt)> = None;
    let mut hi: Option<(&BigInt, &BigInt)> = None;
    // -a1/b1 > -a2/b2 for the numerators of two roots
    let greater = |x: (&BigInt, &BigInt), y: (&BigInt, &BigInt)| {
        let (l, r) = (-(x.0 * y.1), -(y.0 * x.1));
        // divide by b1 b2: keep the order when b1 b2 > 0
        if x.1.is_positive() == y.1.is_positive() {
            l > r
        } else {
            l < r
        }
    };
    for i in 0..s.basis.len() {
        let c = s.basis[i];
        let (a, b) = s.numerators(i);
        if c >= s.ncol() {
            // an artificial of a dependent equality row: the row must be 0 = 0
            if !a.is_zero() || !b.is_zero() {
                let (a, b) = s.affine(i);
                return Err(format!(
                    "equality row {} cannot hold with this basis (it reads 0 = {} + L {})",
                    c - s.ncol(),
                    short(&a.reduced()),
                    short(&b.reduced())
                ));
            }
            continue;
        }
        if !s.signed(c) {
            continue;
        }
        let var = s.var_of(c).expect("a z or w column");
        if b.is_zero() {
            if a.is_negative() {
                // the variable's own value, not its row's: the row is scaled
                // by a power of two (the rotated 3D run's w430 read -2.9e-4
                // for its value -1.6e-20)
                return Err(format!(
                    "{var} = {} < 0 for every L",
                    short(&s.value(c, &BigRational::zero()).reduced())
                ));
            }
        } else if b.is_positive() {
            if lo.is_none_or(|l| greater((a, b), l)) {
                lo = Some((a, b));
            }
        } else if hi.is_none_or(|h| greater(h, (a, b))) {
            hi = Some((a, b));
        }
    }
    let lo = lo.map(|(a, b)| s.root(a, b));
    let hi = hi.map(|(a, b)| s.root(a, b));
    if let (Some(l), Some(h)) = (&lo, &hi) {
        if l > h {
            return Err(format!(
                "no L makes the basis feasible (its variables need L >= {} and L <= {})",
                short(l),
                short(h)
            ));
        }
    }
    Ok((lo, hi))
}

/// The value of the basic or nonbasic variable `v` at `lambda`.
pub(super) fn value_at(t: &Solution, v: Var, lambda: &BigRational) -> BigRational {
    match t.col_of(v) {
        Some(c) => t.value(c, lambda),
        None => BigRational::zero(),
    }
}

/// `err <= limit`, false for NaN (an unmeasurable difference fails).
pub(super) fn within(err: f64, limit: f64) -> bool {
    err <= limit
}
