//! Which big-integer crate for plcp's exact mode: the same exact work timed on
//! two pure-Rust crates, `num-bigint` (0.4, the `num` family) and `dashu-int`
//! (0.4). Both are MIT OR Apache-2.0 like this workspace (malachite, the
//! fastest pure-Rust one, is LGPL and left out).
//!
//! The work is the kernel of `plcp::exact`: fraction-free (Bareiss) Gaussian
//! elimination of a dense PLCP matrix `M = B B'/n + I` given in `f64`, each
//! row scaled by a power of two to integers (exact), with the two right-hand
//! sides `q` and `d`: what certifying one segment of a path costs. Entries
//! grow to the size of the minors (about `k * 60` bits at step `k`), so the
//! time is dominated by multiplying and exactly dividing large integers.
//!
//! ```sh
//! cargo run --release -q --example exact_crates
//! ```

use dashu_int::ops::BitTest;
use plcp::exact::decode;
use rand::{Rng, SeedableRng};
use std::time::Instant;

trait Big: Clone {
    fn from_scaled(mantissa: i64, shift: u32) -> Self;
    fn mul_sub_div(a: &Self, b: &Self, c: &Self, d: &Self, div: &Self) -> Self;
    fn is_zero(&self) -> bool;
    fn bits(&self) -> u64;
}

impl Big for num_bigint::BigInt {
    fn from_scaled(m: i64, s: u32) -> Self {
        num_bigint::BigInt::from(m) << s
    }
    fn mul_sub_div(a: &Self, b: &Self, c: &Self, d: &Self, div: &Self) -> Self {
        (a * b - c * d) / div
    }
    fn is_zero(&self) -> bool {
        num_traits::Zero::is_zero(self)
    }
    fn bits(&self) -> u64 {
        self.bits()
    }
}

impl Big for dashu_int::IBig {
    fn from_scaled(m: i64, s: u32) -> Self {
        dashu_int::IBig::from(m) << s as usize
    }
    fn mul_sub_div(a: &Self, b: &Self, c: &Self, d: &Self, div: &Self) -> Self {
        (a * b - c * d) / div
    }
    fn is_zero(&self) -> bool {
        *self == dashu_int::IBig::ZERO
    }
    fn bits(&self) -> u64 {
        dashu_int::ops::UnsignedAbs::unsigned_abs(self.clone()).bit_len() as u64
    }
}

/// Bareiss elimination of `[M | q | d]` (rows scaled to integers); returns
/// the determinant's bit length.
fn bareiss<B: Big>(rows: &[Vec<f64>]) -> u64 {
    let n = rows.len();
    let mut a: Vec<Vec<B>> = rows
        .iter()
        .map(|r| {
            let emin = r
                .iter()
                .filter(|v| **v != 0.0)
                .map(|v| decode(*v).1)
                .min()
                .unwrap_or(0);
            r.iter()
                .map(|v| {
                    let (m, e) = decode(*v);
                    B::from_scaled(m, (e - emin) as u32)
                })
                .collect()
        })
        .collect();
    let mut prev = B::from_scaled(1, 0);
    for k in 0..n {
        let p = (k..n).find(|&i| !a[i][k].is_zero()).expect("nonsingular");
        a.swap(k, p);
        for i in k + 1..n {
            for j in k + 1..a[i].len() {
                a[i][j] = B::mul_sub_div(&a[i][j], &a[k][k], &a[i][k], &a[k][j], &prev);
            }
        }
        prev = a[k][k].clone();
    }
    prev.bits()
}

fn problem(n: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let b: Vec<Vec<f64>> = (0..n)
        .map(|_| (0..n).map(|_| rng.gen_range(-1.0..1.0)).collect())
        .collect();
    (0..n)
        .map(|i| {
            let mut row: Vec<f64> = (0..n)
                .map(|j| {
                    let s: f64 = (0..n).map(|k| b[i][k] * b[j][k]).sum::<f64>() / n as f64;
                    s + if i == j { 1.0 } else { 0.0 }
                })
                .collect();
            row.push(rng.gen_range(-1.0..1.0));
            row.push(rng.gen_range(-1.0..1.0));
            row
        })
        .collect()
}

fn time<B: Big>(rows: &[Vec<f64>]) -> (f64, u64) {
    let t = Instant::now();
    let bits = bareiss::<B>(rows);
    (t.elapsed().as_secs_f64(), bits)
}

fn main() {
    println!("exact Bareiss elimination of [M | q | d], M = B B'/n + I dense in f64");
    println!(
        "{:>5} {:>10} {:>16} {:>16} {:>8}",
        "n", "det bits", "num-bigint 0.4", "dashu-int 0.4", "ratio"
    );
    for n in [25, 50, 100, 200] {
        let rows = problem(n, 7);
        let (tn, bits) = time::<num_bigint::BigInt>(&rows);
        let (td, bits2) = time::<dashu_int::IBig>(&rows);
        assert_eq!(bits, bits2);
        println!(
            "{n:>5} {bits:>10} {:>14.3} s {:>14.3} s {:>8.2}",
            tn,
            td,
            tn / td
        );
    }
}
