//! The scalar trait: one bound that covers `f32`, `f64` and faer's double-double `fx128`.
//!
//! `fx128` has neither `num_traits::Float` nor `Display`, so the bound is built on
//! [`faer::traits::RealField`] and adds only what all three types have.

use faer::traits::math_utils;
use faer::traits::RealField;

/// A real floating-point type the solvers run in: `f32`, `f64` or [`faer::fx128`].
///
/// Implemented for these three types only: its hidden methods are the
/// entry points of the engine, compiled once in this crate for each of them
/// (`entry.rs`), so that a caller's build does not compile the engine again.
pub trait Scalar: RealField + Copy + Send + Sync + core::ops::Neg<Output = Self> + 'static {
    /// A short name: `"f32"`, `"f64"`, `"f128"`.
    const NAME: &'static str;

    /// True for hardware types (`f32`, `f64`), on which faer's SIMD kernels run.
    const NATIVE: bool;

    /// The wider type residuals of iterative refinement are accumulated in:
    /// `f64` for `f32`, `fx128` for `f64`, and `fx128` itself for `fx128` (it
    /// has no wider type: there the refinement is in the working precision).
    type Wide: Scalar;

    /// Converts to `f64` (rounding for `fx128`).
    fn to_f64(self) -> f64;

    /// The smallest positive normal number of the type (of its leading `f64`
    /// for `fx128`): a nonzero datum below it is subnormal (digits lost) or
    /// zero in this type, and the problem is rejected ([`crate::PlcpError::Underflow`]).
    fn min_normal() -> f64;

    /// Converts to the wide type (exact).
    fn widen(self) -> Self::Wide;

    /// Rounds a wide value to the working precision.
    fn narrow(w: Self::Wide) -> Self;

    /// The product `a b` in the wide type: exact for `f32` and `f64` (for `f64`
    /// the error-free product `fl(a b) + fma(a, b, -fl(a b))`), rounded in the
    /// working precision for `fx128`.
    #[inline]
    fn mul_wide(a: Self, b: Self) -> Self::Wide {
        a.widen() * b.widen()
    }

    /// `acc + a b` accumulated in the wide type. For `f64` a compensated sum
    /// (Ogita, Rump and Oishi's Dot2: the error-free product and sum of each
    /// term collected in the low part, normalised only by [`Scalar::narrow`]),
    /// as accurate as a sum in twice the working precision at a fraction of
    /// double-double arithmetic's cost; a sum of such terms is only to be
    /// read through [`Scalar::narrow`].
    #[inline]
    fn wide_mul_add(acc: Self::Wide, a: Self, b: Self) -> Self::Wide {
        acc + Self::mul_wide(a, b)
    }

    /// True if [`Scalar::wide_mul_add_fma`] differs from
    /// [`Scalar::wide_mul_add`] (`f64`): worth a kernel compiled with the
    /// `fma` target feature where the CPU has it (`fma_detected`).
    const FMA_KERNEL: bool = false;

    /// [`Scalar::wide_mul_add`] with the error-free product taken by a fused
    /// multiply-add (`f64`): the same result (the error of a product is a
    /// unique number; both ways are exact), but a library call unless inlined
    /// into code compiled with the `fma` target feature.
    #[inline(always)]
    fn wide_mul_add_fma(acc: Self::Wide, a: Self, b: Self) -> Self::Wide {
        Self::wide_mul_add(acc, a, b)
    }

    /// The value as an unevaluated sum of two `f64` (exact): `(x, 0)` for
    /// `f32` and `f64`, the two halves of a double-double. [`crate::exact`]
    /// reads every number of a problem through it.
    #[inline]
    fn parts(self) -> (f64, f64) {
        (self.to_f64(), 0.0)
    }

    /// Converts from `f64` (exact for `f64` and `fx128`, rounded for `f32`).
    #[inline]
    fn from_f64(x: f64) -> Self {
        math_utils::from_f64::<Self>(x)
    }

    /// Machine epsilon of the type.
    #[inline]
    fn eps() -> Self {
        math_utils::eps::<Self>()
    }

    /// Absolute value.
    #[inline]
    fn abs(self) -> Self {
        math_utils::abs(&self)
    }

    /// Square root.
    #[inline]
    fn sqrt(self) -> Self {
        math_utils::sqrt(&self)
    }

    /// True unless NaN or infinite.
    #[inline]
    fn is_finite(self) -> bool {
        math_utils::is_finite(&self)
    }

    /// The larger of two values.
    #[inline]
    fn max(self, other: Self) -> Self {
        if self >= other {
            self
        } else {
            other
        }
    }

    /// The smaller of two values.
    #[inline]
    fn min(self, other: Self) -> Self {
        if self <= other {
            self
        } else {
            other
        }
    }

    /// The largest finite value of the type.
    #[inline]
    fn max_value() -> Self {
        math_utils::max_positive::<Self>()
    }

    // the engine's entry points, compiled in this crate (`entry.rs`)
    crate::entry::entry_points!(declare);
}

impl Scalar for f32 {
    crate::entry::entry_points!(define);
    const NAME: &'static str = "f32";
    const NATIVE: bool = true;
    type Wide = f64;
    #[inline]
    fn min_normal() -> f64 {
        f32::MIN_POSITIVE as f64
    }

    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline]
    fn widen(self) -> f64 {
        self as f64
    }
    #[inline]
    fn narrow(w: f64) -> Self {
        w as f32
    }
    #[inline]
    fn from_f64(x: f64) -> Self {
        x as f32
    }
}

impl Scalar for f64 {
    crate::entry::entry_points!(define);
    const NAME: &'static str = "f64";
    const NATIVE: bool = true;
    type Wide = faer::fx128;
    #[inline]
    fn min_normal() -> f64 {
        f64::MIN_POSITIVE
    }

    fn to_f64(self) -> f64 {
        self
    }
    #[inline]
    fn widen(self) -> faer::fx128 {
        faer::fx128 { 0: self, 1: 0.0 }
    }
    #[inline]
    fn narrow(w: faer::fx128) -> Self {
        w.0 + w.1
    }
    #[inline]
    fn wide_mul_add(acc: faer::fx128, a: Self, b: Self) -> faer::fx128 {
        let (p, e) = two_product(a, b);
        add_product(acc, p, e)
    }
    const FMA_KERNEL: bool = true;
    #[inline(always)]
    fn wide_mul_add_fma(acc: faer::fx128, a: Self, b: Self) -> faer::fx128 {
        let p = a * b;
        let e = a.mul_add(b, -p);
        add_product(acc, p, e)
    }
    #[inline]
    fn mul_wide(a: Self, b: Self) -> faer::fx128 {
        // |fma(a, b, -p)| <= ulp(p) / 2: already a normalised double-double
        let (p, e) = two_product(a, b);
        faer::fx128 { 0: p, 1: e }
    }
    #[inline]
    fn from_f64(x: f64) -> Self {
        x
    }
}

impl Scalar for faer::fx128 {
    crate::entry::entry_points!(define);
    const NAME: &'static str = "f128";
    const NATIVE: bool = false;
    type Wide = faer::fx128;
    #[inline]
    fn min_normal() -> f64 {
        f64::MIN_POSITIVE
    }

    fn to_f64(self) -> f64 {
        self.0 + self.1
    }
    #[inline]
    fn parts(self) -> (f64, f64) {
        (self.0, self.1)
    }
    #[inline]
    fn widen(self) -> Self {
        self
    }
    #[inline]
    fn narrow(w: Self) -> Self {
        w
    }
}

/// `acc + (p + e)` for an exact product `a b = p + e`: `two_sum(acc.0, p)`
/// (`s + t == acc.0 + p` exactly), the low parts summed into the tail.
#[inline(always)]
fn add_product(acc: faer::fx128, p: f64, e: f64) -> faer::fx128 {
    let s = acc.0 + p;
    let bb = s - acc.0;
    let t = (acc.0 - (s - bb)) + (p - bb);
    faer::fx128 {
        0: s,
        1: acc.1 + (t + e),
    }
}

/// Dekker's error-free product: `p + e == a b` exactly, `p = fl(a b)`
/// (Veltkamp's splitting, no fused multiply-add: without the `fma` target
/// feature `f64::mul_add` is a library call that costs more than these 17
/// flops and stops vectorisation). Exact unless `abs(a)` or `abs(b)` exceeds
/// about `2^996` or the product under- or overflows.
#[inline]
fn two_product(a: f64, b: f64) -> (f64, f64) {
    const SPLIT: f64 = 134_217_729.0; // 2^27 + 1
    let split = |x: f64| {
        let c = SPLIT * x;
        let hi = c - (c - x);
        (hi, x - hi)
    };
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    let e = al * bl - (((p - ah * bh) - al * bh) - ah * bl);
    (p, e)
}

/// Whether the CPU has fused multiply-add (x86-64: detected once and cached
/// by the standard library; other targets: false).
#[inline]
pub(crate) fn fma_detected() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::is_x86_feature_detected!("fma")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// The precision a caller asks for at run time (command line, settings files).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Precision {
    /// Single precision.
    F32,
    /// Double precision (the default).
    #[default]
    F64,
    /// Double-double (`faer::fx128`, about 32 significant digits).
    F128,
}

impl core::str::FromStr for Precision {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "f32" => Ok(Self::F32),
            "f64" => Ok(Self::F64),
            "f128" | "fx128" => Ok(Self::F128),
            other => Err(format!(
                "unknown precision '{other}': expected f32, f64 or f128"
            )),
        }
    }
}

/// Positive infinity in `T`.
pub fn infinity<T: Scalar>() -> T {
    math_utils::infinity::<T>()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn roundtrip<T: Scalar>() {
        let x = T::from_f64(1.5);
        assert_eq!(x.to_f64(), 1.5);
        assert!(T::eps() > T::zero());
        assert_eq!((-x).abs().to_f64(), 1.5);
        assert!(!T::from_f64(f64::NAN).is_finite());
    }

    /// `r = c - sum_k a_k b_k` with heavy cancellation, accumulated with
    /// `wide_mul_add` and rounded once, against the exact value.
    fn cancelling_residual<T: Scalar>() -> (T, f64) {
        // (1 + u)(1 - u) = 1 - u^2: the product's rounding error is all of the residual
        let u = T::eps().to_f64().sqrt() * 0.75;
        let (a, b) = (T::from_f64(1.0 + u), T::from_f64(1.0 - u));
        // the inputs are exact in T only up to its rounding: the exact residual of
        // what T holds, computed from the rounded inputs in f64 pairs
        let (ar, br) = (a.to_f64(), b.to_f64());
        let mut acc = T::one().widen();
        acc = T::wide_mul_add(acc, -a, b);
        let (p, e) = two_product(ar, br);
        let exact = (1.0 - p) - e;
        (T::narrow(acc), exact)
    }

    #[test]
    fn wide_residual_is_exact_where_the_working_one_is_not() {
        // f64: 1 - fl((1+u)(1-u)) loses u^2 entirely in f64 arithmetic
        let (r, exact) = cancelling_residual::<f64>();
        assert!(exact != 0.0);
        assert!(
            (r - exact).abs() <= 1e-16 * exact.abs(),
            "{r:e} vs {exact:e}"
        );
        let u = f64::EPSILON.sqrt() * 0.75;
        let naive = 1.0 - (1.0 + u) * (1.0 - u);
        assert!(
            (naive - exact).abs() > 1e-3 * exact.abs(),
            "the working precision already had it"
        );
        // f32 through f64: exact
        let (r, exact) = cancelling_residual::<f32>();
        assert!(
            ((r as f64) - exact).abs() <= 1e-7 * exact.abs(),
            "{r:e} vs {exact:e}"
        );
        // fx128 has no wider type: its own precision
        let (r, exact) = cancelling_residual::<faer::fx128>();
        assert!((r.to_f64() - exact).abs() <= 1e-10 * exact.abs().max(1e-31));
    }

    #[test]
    fn dot2_sum_matches_double_double() {
        // a long sum with cancellation: Dot2 in f64 against fx128 arithmetic
        let n = 1000;
        let a: Vec<f64> = (0..n)
            .map(|k| ((k * 7919) % 1013) as f64 / 1013.0 - 0.5)
            .collect();
        let b: Vec<f64> = (0..n)
            .map(|k| ((k * 104729) % 997) as f64 / 997.0 - 0.5)
            .collect();
        let mut acc = 0.0f64.widen();
        let mut dd = faer::fx128::from_f64(0.0);
        for k in 0..n {
            acc = f64::wide_mul_add(acc, a[k], b[k]);
            dd += a[k].widen() * b[k].widen();
        }
        // cancel the sum against its own f64 rounding: only the tail is left
        let s = f64::narrow(acc);
        let tail_dot2 = f64::narrow(f64::wide_mul_add(acc, -s, 1.0));
        let tail_dd = (dd - s.widen()).to_f64();
        assert!((s - dd.to_f64()).abs() <= f64::EPSILON * s.abs());
        assert!(
            // Dot2: about eps^2 times the sum of |a b| (250 here); a sum in
            // f64 would be off by about eps times it
            (tail_dot2 - tail_dd).abs() <= 1e-26,
            "{tail_dot2:e} vs {tail_dd:e}"
        );
    }

    #[test]
    fn fma_product_is_the_split_product() {
        // the error of a product is unique: Veltkamp's splitting and fma agree bitwise
        let mut acc = 0.5f64.widen();
        let mut acc_fma = acc;
        for k in 1..2000u64 {
            let a = ((k * 7919) % 1013) as f64 / 1013.0 - 0.5 + 1e-9 * k as f64;
            let b = (((k * 104729) % 997) as f64 / 997.0 - 0.5) * 2f64.powi((k % 40) as i32 - 20);
            acc = f64::wide_mul_add(acc, a, b);
            acc_fma = f64::wide_mul_add_fma(acc_fma, a, b);
            assert_eq!(
                (acc.0.to_bits(), acc.1.to_bits()),
                (acc_fma.0.to_bits(), acc_fma.1.to_bits())
            );
        }
    }

    #[test]
    fn all_three_types() {
        roundtrip::<f32>();
        roundtrip::<f64>();
        roundtrip::<faer::fx128>();
        assert!(faer::fx128::eps().to_f64() < 1e-30);
    }
}
