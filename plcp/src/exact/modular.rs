//! The exact solution of a nonsingular integer system by p-adic lifting.
//!
//! # The math
//!
//! For a square integer matrix `B` and integer right-hand sides `b`, Dixon's
//! method factors `B = P L U` once modulo a word-size prime `p` (which proves
//! `det B != 0`: `det B mod p != 0`), then lifts: with `r_0 = b`,
//!
//! ```text
//! x_i = B^-1 r_i  (mod p),      r_{i+1} = (r_i - B x_i) / p   (an exact division)
//! ```
//!
//! so that `X = sum x_i p^i` satisfies `B X = b (mod p^k)`. The residuals stay
//! as small as `B`'s row sums, so each step costs `O(dim^2)` word operations
//! (two triangular solves) and `O(nnz(B))` for the update. Once `p^k > 2 N D`
//! for bounds `N`, `D` on the numerators and the denominator of `B^-1 b`
//! (Hadamard's bound on the minors by Cramer's rule), rational reconstruction
//! recovers `B^-1 b = num / den` (one common denominator: each component only
//! needs a reconstruction when its value times the denominator found so far is
//! not already small). Reconstruction is tried early (at doubling step counts)
//! because the bound is pessimistic.
//!
//! Whatever the lifting does, the answer is **verified exactly**:
//! `B num = den b` over the integers. That product check, and the nonzero
//! determinant modulo `p`, are what make the result a proof; the modular work
//! only has to be right with high probability, and a failure (a prime dividing
//! `det B`, a reconstruction that does not verify) returns `None`, on which the
//! caller falls back to fraction-free elimination.
//!
//! Primes are below `2^27`: products of residues fit in 54 bits, so dot
//! products accumulate 256 terms in a `u64` before one reduction (and
//! vectorize). `B x_i` is formed in `i128` from `B`'s 64-bit digits (one
//! digit for most rows: a row scaled to integers has 53 bits plus the spread
//! of its exponents); the residuals are `i128` when `B` has one digit and the
//! right-hand side's large entries have been divided down, big integers
//! otherwise.

use num_bigint::BigInt;
use num_integer::Integer;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// An integer matrix by columns: `(row, value)` for each nonzero.
pub(crate) type Cols = [Vec<(usize, BigInt)>];

/// `B` by 64-bit digits: `B = sum_t 2^(64 t) D_t`, each `D_t` by columns.
type Digits = [Vec<Vec<(usize, i128)>>];

/// Residuals are kept as `i128` once all are below `2^100`.
const SMALL_BITS: u64 = 100;

/// Terms a `u64` accumulator takes before a reduction (`256 * 2^54 < 2^63`).
const CHUNK: usize = 256;

/// How many primes are tried before giving up (a prime divides `det B` with
/// probability about `bits(det B) / 2^27 * ln 2^27`).
const TRIES: usize = 3;

/// The largest primes below `2^27`, by trial division.
fn primes() -> impl Iterator<Item = u64> {
    ((1u64 << 26)..(1u64 << 27)).rev().filter(|&c| {
        c % 2 == 1
            && (3..)
                .step_by(2)
                .take_while(|d| d * d <= c)
                .all(|d| c % d != 0)
    })
}

/// Arithmetic modulo a prime `p < 2^27` (Barrett reduction of `x < 2^64`).
#[derive(Clone, Copy)]
struct Modp {
    p: u64,
    /// `floor(2^64 / p)`
    m: u64,
}

impl Modp {
    fn new(p: u64) -> Self {
        Modp {
            p,
            m: (u128::from(u64::MAX) / u128::from(p)) as u64,
        }
    }
    #[inline]
    fn reduce(self, x: u64) -> u64 {
        let q = ((u128::from(x) * u128::from(self.m)) >> 64) as u64;
        let mut r = x - q * self.p;
        while r >= self.p {
            r -= self.p;
        }
        r
    }
    #[inline]
    fn mul(self, a: u64, b: u64) -> u64 {
        self.reduce(a * b)
    }
    fn pow(self, mut a: u64, mut e: u64) -> u64 {
        let mut r = 1;
        while e > 0 {
            if e & 1 == 1 {
                r = self.mul(r, a);
            }
            a = self.mul(a, a);
            e >>= 1;
        }
        r
    }
    fn inv(self, a: u64) -> u64 {
        self.pow(a, self.p - 2)
    }
    /// `sum a_t b_t mod p` for residues `a_t, b_t < p`.
    #[inline]
    fn dot(self, a: &[u32], b: &[u32]) -> u64 {
        let mut total = 0u64;
        for (ca, cb) in a.chunks(CHUNK).zip(b.chunks(CHUNK)) {
            let s: u64 = ca
                .iter()
                .zip(cb)
                .map(|(&x, &y)| u64::from(x) * u64::from(y))
                .sum();
            total = self.reduce(total + self.reduce(s));
        }
        total
    }
    fn of_i128(self, v: i128) -> u32 {
        v.rem_euclid(i128::from(self.p)) as u32
    }
    fn of_big(self, v: &BigInt) -> u32 {
        v.mod_floor(&BigInt::from(self.p))
            .to_u32()
            .expect("a residue")
    }
}

/// `B = P L U` modulo a prime: `L` unit lower by rows, `U` upper by rows,
/// `perm[i]` the row of `B` that is row `i` of `L U`.
struct Lu {
    md: Modp,
    dim: usize,
    l: Vec<u32>,
    u: Vec<u32>,
    /// The inverses of `U`'s diagonal.
    uinv: Vec<u64>,
    perm: Vec<usize>,
}

impl Lu {
    /// Crout's order (every entry is one dot product, reduced once); `None`
    /// when `B` is singular modulo `p`.
    fn factor(cols: &Cols, dim: usize, md: Modp) -> Option<Self> {
        // a: B by rows (residues)
        let mut a = vec![0u32; dim * dim];
        for (j, col) in cols.iter().enumerate() {
            for (i, v) in col {
                a[i * dim + j] = md.of_big(v);
            }
        }
        let mut l = vec![0u32; dim * dim]; // by rows, unit diagonal implied
        let mut ut = vec![0u32; dim * dim]; // U by columns
        let mut perm: Vec<usize> = (0..dim).collect();
        let mut uinv = vec![0u64; dim];
        let p = md.p;
        for k in 0..dim {
            // column k of the Schur complement, rows k..
            let uk = &ut[k * dim..k * dim + k];
            let mut piv = None;
            let mut s = vec![0u64; dim];
            for (i, si) in s.iter_mut().enumerate().skip(k) {
                let dot = md.dot(&l[i * dim..i * dim + k], uk);
                *si = md.reduce(u64::from(a[perm[i] * dim + k]) + p - dot);
                if piv.is_none() && *si != 0 {
                    piv = Some(i);
                }
            }
            let r = piv?;
            if r != k {
                perm.swap(r, k);
                s.swap(r, k);
                for t in 0..k {
                    l.swap(r * dim + t, k * dim + t);
                }
            }
            let inv = md.inv(s[k]);
            uinv[k] = inv;
            ut[k * dim + k] = s[k] as u32;
            for i in k + 1..dim {
                l[i * dim + k] = md.mul(s[i], inv) as u32;
            }
            // row k of U right of the diagonal
            let lk = l[k * dim..k * dim + k].to_vec();
            let rowk = perm[k];
            for j in k + 1..dim {
                let dot = md.dot(&lk, &ut[j * dim..j * dim + k]);
                ut[j * dim + k] = md.reduce(u64::from(a[rowk * dim + j]) + p - dot) as u32;
            }
        }
        // U by rows for the back substitution
        let mut u = vec![0u32; dim * dim];
        for j in 0..dim {
            for i in 0..=j {
                u[i * dim + j] = ut[j * dim + i];
            }
        }
        Some(Lu {
            md,
            dim,
            l,
            u,
            uinv,
            perm,
        })
    }

    /// `x = B^-1 r (mod p)` for residues `r`.
    fn solve(&self, r: &[u32], x: &mut [u32]) {
        let (md, dim, p) = (self.md, self.dim, self.md.p);
        let mut y = vec![0u32; dim];
        for i in 0..dim {
            let dot = md.dot(&self.l[i * dim..i * dim + i], &y[..i]);
            y[i] = md.reduce(u64::from(r[self.perm[i]]) + p - dot) as u32;
        }
        for i in (0..dim).rev() {
            let dot = md.dot(&self.u[i * dim + i + 1..(i + 1) * dim], &x[i + 1..]);
            let v = md.reduce(u64::from(y[i]) + p - dot);
            x[i] = md.mul(v, self.uinv[i]) as u32;
        }
    }
}

/// True if the square matrix `cols` is nonsingular modulo one of a few primes
/// (a proof that it is nonsingular); false says nothing.
pub(crate) fn nonsingular(cols: &Cols) -> bool {
    primes()
        .take(TRIES)
        .any(|p| Lu::factor(cols, cols.len(), Modp::new(p)).is_some())
}

/// `log2` of an upper bound on the Euclidean norm of a vector whose entries
/// have at most these bit lengths.
fn log2_norm(bits: impl Iterator<Item = u64>) -> f64 {
    let (mut count, mut max) = (0usize, 0u64);
    for b in bits {
        count += 1;
        max = max.max(b);
    }
    if count == 0 {
        0.0
    } else {
        max as f64 + 0.5 * (count as f64).log2()
    }
}

/// The residual vector: big integers until every entry fits the `i128` range
/// the lifting works in.
enum Residual {
    Big(Vec<BigInt>),
    Small(Vec<i128>),
}

/// `p^-1 mod 2^128` for odd `p` (Newton's iteration): `(p q) * inv = q` for
/// every `q`, the exact division by `p` as a multiplication.
fn inverse_2_128(p: u64) -> u128 {
    let p = u128::from(p);
    let mut inv = p;
    for _ in 0..7 {
        inv = inv.wrapping_mul(2u128.wrapping_sub(p.wrapping_mul(inv)));
    }
    inv
}

/// `sum_i digits[i] p^i` by halves (products of balanced sizes).
fn from_digits(digits: &[u32], pows: &[BigInt]) -> BigInt {
    if digits.len() <= 2 {
        return digits
            .iter()
            .rev()
            .fold(BigInt::zero(), |acc, &d| acc * &pows[0] + d);
    }
    // the largest power of two below len
    let level = (usize::BITS - 1 - (digits.len() - 1).leading_zeros()) as usize;
    let half = 1usize << level;
    let lo = from_digits(&digits[..half], pows);
    let hi = from_digits(&digits[half..], pows);
    lo + hi * &pows[level]
}

/// `u = n / d (mod m)` with `2 n^2, 2 d^2 < m` (`|n|, d <= bound`, see
/// [`reconstruct_all`]), by the Euclidean remainder sequence; `None` when no
/// such fraction exists.
fn reconstruct(u: &BigInt, m: &BigInt, bound: &BigInt) -> Option<(BigInt, BigInt)> {
    let (mut r0, mut r1) = (m.clone(), u.mod_floor(m));
    let (mut t0, mut t1) = (BigInt::zero(), BigInt::one());
    let small = |r: &BigInt| r.magnitude() <= bound.magnitude();
    while !small(&r1) {
        let (q, r) = r0.div_rem(&r1);
        r0 = std::mem::replace(&mut r1, r);
        let t = &t0 - &q * &t1;
        t0 = std::mem::replace(&mut t1, t);
    }
    if t1.is_zero() || !small(&t1) {
        return None;
    }
    if t1.is_negative() {
        Some((-r1, -t1))
    } else {
        Some((r1, t1))
    }
}

/// The common-denominator reconstruction of every component of `x mod m`.
/// `x(i)` is the `i`-th component modulo `m`, formed only when needed: a
/// lifting stopped too early fails on its first components, at little cost.
///
/// `den0` is a first guess of the common denominator (the previous
/// right-hand side's, with the same `B`: both divide `det B`), which spares
/// the Euclidean reconstruction when it is a multiple of this one's.
fn reconstruct_all(
    len: usize,
    x: impl Fn(usize) -> BigInt,
    m: &BigInt,
    den0: &BigInt,
) -> Option<(Vec<BigInt>, BigInt)> {
    let half = m >> 1usize;
    // 2 r^2 < m  <=>  |r| <= floor(sqrt((m - 1) / 2))
    let bound = ((m - 1u32) >> 1usize).sqrt();
    if den0.magnitude() > bound.magnitude() {
        return None;
    }
    let mut den = den0.clone();
    let mut num: Vec<BigInt> = Vec::with_capacity(len);
    for i in 0..len {
        let mut w = (x(i) * &den).mod_floor(m);
        if w > half {
            w -= m;
        }
        if w.magnitude() <= bound.magnitude() {
            num.push(w);
            continue;
        }
        let (n, d) = reconstruct(&w, m, &bound)?;
        for v in num.iter_mut() {
            *v *= &d;
        }
        den *= d;
        if den.magnitude() > bound.magnitude() {
            return None;
        }
        num.push(n);
    }
    Some((num, den))
}

/// `B num = den b` exactly.
fn verify(cols: &Cols, num: &[BigInt], den: &BigInt, b: &[BigInt]) -> bool {
    let mut acc = vec![BigInt::zero(); b.len()];
    for (col, x) in cols.iter().zip(num) {
        if x.is_zero() {
            continue;
        }
        for (i, v) in col {
            acc[*i] += x * v;
        }
    }
    acc.iter().zip(b).all(|(a, bi)| *a == den * bi)
}

/// The exact solutions `num / den` (`den > 0`) of `B x = b` for each
/// right-hand side, verified; `None` if `B` is singular modulo the primes
/// tried (perhaps singular), or the lifting failed to verify.
pub(crate) fn solve(cols: &Cols, rhs: &[Vec<BigInt>]) -> Option<Vec<(Vec<BigInt>, BigInt)>> {
    let dim = cols.len();
    let ndig = cols
        .iter()
        .flatten()
        .map(|(_, v)| v.bits().div_ceil(64) as usize)
        .max()
        .unwrap_or(1)
        .max(1);
    let mut bdig: Vec<Vec<Vec<(usize, i128)>>> = vec![vec![Vec::new(); dim]; ndig];
    for (j, col) in cols.iter().enumerate() {
        for (i, v) in col {
            let neg = v.is_negative();
            for (t, d) in v.magnitude().iter_u64_digits().enumerate() {
                if d != 0 {
                    let d = i128::from(d);
                    bdig[t][j].push((*i, if neg { -d } else { d }));
                }
            }
        }
    }
    primes().take(TRIES).find_map(|p| {
        let lu = Lu::factor(cols, dim, Modp::new(p))?;
        let mut out: Vec<(Vec<BigInt>, BigInt)> = Vec::with_capacity(rhs.len());
        for b in rhs {
            let den0 = out.last().map_or_else(BigInt::one, |s| s.1.clone());
            out.push(lift(cols, &bdig, &lu, b, &den0)?);
        }
        Some(out)
    })
}

/// Dixon's lifting for one right-hand side (see the module documentation);
/// `den0` is a guess of the denominator (see [`reconstruct_all`]).
fn lift(
    cols: &Cols,
    bdig: &Digits,
    lu: &Lu,
    b: &[BigInt],
    den0: &BigInt,
) -> Option<(Vec<BigInt>, BigInt)> {
    let dim = cols.len();
    let md = lu.md;
    let p = md.p;
    if b.iter().all(Zero::is_zero) {
        return Some((vec![BigInt::zero(); dim], BigInt::one()));
    }
    // Hadamard: |det B| <= prod ||col_j||; a numerator (B with column j
    // replaced by b) <= prod ||col_j|| * ||b|| (every nonzero integer column
    // has norm >= 1)
    let log_det: f64 = cols
        .iter()
        .map(|c| log2_norm(c.iter().map(|(_, v)| v.bits())))
        .sum();
    let log_b = log2_norm(b.iter().filter(|v| !v.is_zero()).map(|v| v.bits()));
    // balanced reconstruction (|num|, den <= sqrt(p^k / 2)) needs p^k above
    // twice the square of the larger bound
    let need_bits = 2.0 * (log_det + log_b) + 8.0;
    let log_p = (p as f64).log2();
    let kmax = (need_bits / log_p).ceil() as usize + 1;

    let inv128 = inverse_2_128(p);
    let mut res = Residual::Big(b.to_vec());
    let mut digits: Vec<Vec<u32>> = vec![Vec::with_capacity(kmax); dim];
    let mut rmod = vec![0u32; dim];
    let mut x = vec![0u32; dim];
    // powers p^(2^j)
    let mut pows = vec![BigInt::from(p)];
    let mut next_try = 16usize;
    for k in 1..=kmax {
        match &res {
            Residual::Big(r) => rmod.iter_mut().zip(r).for_each(|(m, v)| *m = md.of_big(v)),
            Residual::Small(r) => rmod
                .iter_mut()
                .zip(r)
                .for_each(|(m, &v)| *m = md.of_i128(v)),
        }
        lu.solve(&rmod, &mut x);
        for (d, &xi) in digits.iter_mut().zip(&x) {
            d.push(xi);
        }
        // r <- (r - B x) / p, with B x = sum_t 2^(64 t) D_t x
        let bx: Vec<Vec<i128>> = bdig
            .iter()
            .map(|dt| {
                let mut bx = vec![0i128; dim];
                for (col, &xj) in dt.iter().zip(&x) {
                    if xj == 0 {
                        continue;
                    }
                    let xj = i128::from(xj);
                    for &(i, v) in col {
                        bx[i] += v * xj;
                    }
                }
                bx
            })
            .collect();
        res = match res {
            Residual::Small(mut r) => {
                for (ri, bi) in r.iter_mut().zip(&bx[0]) {
                    *ri = (ri.wrapping_sub(*bi) as u128).wrapping_mul(inv128) as i128;
                }
                Residual::Small(r)
            }
            Residual::Big(r) => {
                let r: Vec<BigInt> = r
                    .into_iter()
                    .enumerate()
                    .map(|(i, mut ri)| {
                        for (t, bt) in bx.iter().enumerate() {
                            if bt[i] != 0 {
                                ri -= BigInt::from(bt[i]) << (64 * t);
                            }
                        }
                        ri / p
                    })
                    .collect();
                if bdig.len() == 1 && r.iter().all(|v| v.bits() < SMALL_BITS) {
                    Residual::Small(r.iter().map(|v| v.to_i128().expect("small")).collect())
                } else {
                    Residual::Big(r)
                }
            }
        };
        if k == next_try || k == kmax {
            next_try *= 2;
            while (1usize << pows.len()) <= k {
                let last = pows.last().expect("p");
                let sq = last * last;
                pows.push(sq);
            }
            let m = BigInt::from(p).pow(k as u32);
            let x = |i: usize| from_digits(&digits[i], &pows);
            if let Some((num, den)) = reconstruct_all(dim, x, &m, den0) {
                if verify(cols, &num, &den, b) {
                    return Some((num, den));
                }
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn primes_are_prime_and_large() {
        let ps: Vec<u64> = primes().take(3).collect();
        assert_eq!(ps.len(), 3);
        for p in ps {
            assert!(p > 1 << 26 && p < 1 << 27);
            assert!((2..p).take_while(|d| d * d <= p).all(|d| p % d != 0));
        }
    }

    #[test]
    fn exact_division_by_multiplication() {
        let p = primes().next().unwrap();
        let inv = inverse_2_128(p);
        for q in [0i128, 1, -1, 12345678901234567890, -(1 << 100)] {
            let x = q * i128::from(p);
            assert_eq!((x as u128).wrapping_mul(inv) as i128, q);
        }
    }

    #[test]
    fn solves_a_small_system_exactly() {
        // B = [[2, 1], [1, 3]], b = (1, 2): x = (1/5, 3/5)
        let big = |c: Vec<Vec<(usize, i64)>>| -> Vec<Vec<(usize, BigInt)>> {
            c.into_iter()
                .map(|col| col.into_iter().map(|(i, v)| (i, BigInt::from(v))).collect())
                .collect()
        };
        let cols = big(vec![vec![(0, 2), (1, 1)], vec![(0, 1), (1, 3)]]);
        let b = vec![BigInt::from(1), BigInt::from(2)];
        let sol = solve(&cols, &[b]).unwrap();
        let (num, den) = &sol[0];
        assert_eq!(num[0].clone() * 5, den.clone());
        assert_eq!(num[1].clone() * 5, den.clone() * 3);
        // a singular matrix: no answer
        let cols = big(vec![vec![(0, 2), (1, 4)], vec![(0, 1), (1, 2)]]);
        assert!(solve(&cols, &[vec![BigInt::from(1), BigInt::from(2)]]).is_none());
        assert!(!nonsingular(&cols));
    }

    #[test]
    fn a_determinant_every_tried_prime_divides_gives_no_answer() {
        // det B = the product of the primes tried: singular modulo each, so
        // the caller falls back to the tableau (B is nonsingular)
        let det = primes()
            .take(TRIES)
            .fold(BigInt::one(), |a, p| a * BigInt::from(p));
        let cols = vec![vec![(0, det.clone())], vec![(1, BigInt::one())]];
        assert!(solve(&cols, &[vec![BigInt::one(), BigInt::one()]]).is_none());
        assert!(!nonsingular(&cols));
        // det + 2 is 2 modulo each of them: solved by the first
        let cols = vec![vec![(0, det + 2)], vec![(1, BigInt::one())]];
        assert!(solve(&cols, &[vec![BigInt::one(), BigInt::one()]]).is_some());
    }

    #[test]
    fn the_exact_check_rejects_a_wrong_solution() {
        let cols: Vec<Vec<(usize, BigInt)>> = vec![
            vec![(0, BigInt::from(2)), (1, BigInt::from(1))],
            vec![(0, BigInt::from(1)), (1, BigInt::from(3))],
        ];
        let b = vec![BigInt::from(1), BigInt::from(2)];
        let (num, den) = solve(&cols, std::slice::from_ref(&b)).unwrap().remove(0);
        assert!(verify(&cols, &num, &den, &b));
        let mut wrong = num.clone();
        wrong[1] += 1;
        assert!(!verify(&cols, &wrong, &den, &b));
        assert!(!verify(&cols, &num, &(den + 1), &b));
    }

    #[test]
    fn large_right_hand_sides_and_many_digits() {
        // a 12 x 12 matrix with two-digit entries and a 300-bit right-hand side
        let dim = 12;
        let mut s = 0x9e3779b97f4a7c15u64;
        let mut rnd = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 4) as i64 - (1 << 59)
        };
        // entries of 60 bits, and of 60 + 70 bits in every third column
        let cols: Vec<Vec<(usize, BigInt)>> = (0..dim)
            .map(|j| {
                let shift = if j % 3 == 0 { 70usize } else { 0 };
                (0..dim)
                    .map(|i| (i, BigInt::from(rnd()) << shift))
                    .collect()
            })
            .collect();
        let b: Vec<BigInt> = (0..dim).map(|_| BigInt::from(rnd()) << 240usize).collect();
        let sol = solve(&cols, std::slice::from_ref(&b)).unwrap();
        assert!(verify(&cols, &sol[0].0, &sol[0].1, &b));
    }
}
