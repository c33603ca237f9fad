//! Exact rational arithmetic: certifying a path, and tracing one exactly.
//!
//! # The math
//!
//! Every number of a problem in `f32`, `f64` or `fx128` is a dyadic rational
//! (`fx128` is the unevaluated sum of two `f64`, [`crate::Scalar::parts`]), so
//! the problem is a rational one that floats only approximate. With the rows
//! written as
//!
//! ```text
//! -(M x)_r + w_r + a_r = q_r + L d_r       (w_r only on the p + i rows, a_r only on the p equality rows)
//! ```
//!
//! and each row multiplied by a power of two (`2^-e_r`, exact) so that its
//! entries are integers, a basis `B` (one column per row) gives the basic
//! solution `x_B(L) = B^-1 q + L B^-1 d`, affine in `L`. We keep the tableau
//! `T = det(B) B^-1 [A | q | d]` in integers (Edmonds' integer pivoting, the
//! tableau form of Bareiss' elimination): pivoting on `(r, c)` maps every
//! entry to `(T_rc T_ij - T_ic T_rj) / det_old`, an exact division (Sylvester's
//! identity), and the entries stay minors of the data, so they grow only
//! linearly in the basis order. A basic variable is then
//! `(T_iq + L T_id) / det`, and the exact breakpoint where it reaches zero is
//! `L = -T_iq / T_id`.
//!
//! * [`certify`] (`certify/`) takes a float path and, segment by segment,
//!   solves the segment's basis exactly (by p-adic lifting, modular.rs, with
//!   an exact check of the solution; on the tableau above where the basis is
//!   not square, solution.rs holds either answer), checks that it is
//!   complementary, that the equality rows hold, that every basic `z`, `w` is
//!   nonnegative on the segment's exact interval, that the exact breakpoints
//!   chain (each segment starts where the previous one ended exactly), and that
//!   the path ends as its status claims: a [`Certificate`].
//! * [`trace`] and [`trace_from`] (trace.rs) run Lemke's method with `L` as
//!   the driving variable on the same integer tableau, with the exact
//!   lexicographic rule, and return the path rounded to `f64` plus its exact
//!   breakpoints (`--precision exact`).
//!
//! Big integers: `num-bigint` (with `num-rational` for the reported
//! breakpoints), chosen by measurement against `dashu-int` on this
//! elimination (`examples/exact_crates.rs`, `docs/certification.md`): equal
//! within 10% from `n = 50` on, `num-bigint` ahead at `n = 25, 100, 200`.

mod certify;
mod modular;
mod solution;
mod tableau;
mod trace;

pub use certify::{certify, certify_with, Certificate, Engine, Failure};
pub use trace::{trace, trace_from, ExactPath, EXACT_MAX_DIM};
// the bodies the entry points call (`crate::entry`)
pub(crate) use certify::certify_here;
pub(crate) use trace::{trace_from_here, trace_here};

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

/// `x = mantissa * 2^exp` exactly, for a finite `f64` (`(0, 0)` for zero).
pub fn decode(x: f64) -> (i64, i32) {
    if x == 0.0 {
        return (0, 0);
    }
    let bits = x.to_bits();
    let sign = if bits >> 63 == 0 { 1 } else { -1 };
    let e = ((bits >> 52) & 0x7ff) as i32;
    let frac = (bits & 0xf_ffff_ffff_ffff) as i64;
    let (m, e) = if e == 0 {
        (frac, -1074)
    } else {
        (frac | (1 << 52), e - 1075)
    };
    (sign * m, e)
}

/// A finite float of any working precision as an exact rational.
pub fn to_rational<T: crate::Scalar>(x: T) -> BigRational {
    let (hi, lo) = x.parts();
    f64_to_rational(hi) + f64_to_rational(lo)
}

/// A finite `f64` as an exact rational.
pub fn f64_to_rational(x: f64) -> BigRational {
    let (m, e) = decode(x);
    if e >= 0 {
        BigRational::from_integer(BigInt::from(m) << e as usize)
    } else {
        BigRational::new(BigInt::from(m), BigInt::from(1) << (-e) as usize)
    }
}

/// A rational as the nearest `f64` (`inf` beyond its range).
pub fn rational_to_f64(x: &BigRational) -> f64 {
    x.to_f64().unwrap_or_else(|| {
        if x.is_negative() {
            f64::NEG_INFINITY
        } else {
            f64::INFINITY
        }
    })
}

/// A rational as the nearest value of `T`: its nearest `f64` plus the
/// nearest `f64` of the remainder (an `fx128` to double-double accuracy; one
/// rounding for `f64`, the remainder being below half an ulp).
pub(crate) fn rational_to<T: crate::Scalar>(x: &BigRational) -> T {
    let hi = rational_to_f64(x);
    if !hi.is_finite() || T::eps().to_f64() >= f64::EPSILON {
        return T::from_f64(hi);
    }
    let lo = rational_to_f64(&(x - f64_to_rational(hi)));
    T::from_f64(hi) + T::from_f64(lo)
}

/// A rational for people: `4`, `13/3` when numerator and denominator have at
/// most 9 digits, else the nearest `f64` in Rust's shortest form (`0.1013...`).
pub fn short(x: &BigRational) -> String {
    let (n, d) = (x.numer(), x.denom());
    let small = |v: &BigInt| v.abs() < BigInt::from(1_000_000_000u64);
    if small(n) && small(d) {
        if d == &BigInt::from(1) {
            format!("{n}")
        } else {
            format!("{n}/{d}")
        }
    } else {
        format!("{:e}", rational_to_f64(x))
    }
}

/// `|f - e| / max(|e|, |from|)` (`|f|` when both are zero): the relative
/// difference of a float breakpoint `f` and the exact one `e` of a segment
/// that starts at `from`.
pub(crate) fn rel_diff(f: f64, e: &BigRational, from: &BigRational) -> f64 {
    if !f.is_finite() {
        return f64::INFINITY;
    }
    let scale = e.abs().max(from.abs());
    let diff = (f64_to_rational(f) - e).abs();
    if scale.is_zero() {
        rational_to_f64(&diff)
    } else {
        rational_to_f64(&(diff / scale))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_convert_exactly() {
        assert_eq!(f64_to_rational(0.75), BigRational::new(3.into(), 4.into()));
        assert_eq!(
            f64_to_rational(-3.0),
            BigRational::from_integer((-3).into())
        );
        assert_eq!(rational_to_f64(&f64_to_rational(0.1)), 0.1);
        let tiny = f64::from_bits(1); // the smallest subnormal
        assert_eq!(rational_to_f64(&f64_to_rational(tiny)), tiny);
        // a double-double: 1 + 2^-80 is not an f64 but is exact here
        let x = faer::fx128 {
            0: 1.0,
            1: 2f64.powi(-80),
        };
        let r = to_rational(x);
        assert_eq!(
            r - BigRational::from_integer(1.into()),
            BigRational::new(1.into(), BigInt::from(1) << 80)
        );
    }

    #[test]
    fn short_fractions() {
        assert_eq!(short(&BigRational::new(12.into(), 1.into())), "12");
        assert_eq!(short(&BigRational::new(26.into(), 6.into())), "13/3");
        let long = BigRational::new(1.into(), BigInt::from(3) << 100);
        assert!(short(&long).contains('e'), "{}", short(&long));
    }
}
