//! The exact basic solution `x_B(L) = a / da + L b / db` of one basis, found
//! either by p-adic lifting (modular.rs) or read off the integer tableau
//! (tableau.rs), and what the certificate asks of it.
//!
//! Numerators share one positive denominator per right-hand side and are not
//! reduced: reducing each of `O(p + n)` fractions of thousands of bits by a
//! `gcd` would cost more than the solve. Signs, comparisons and the rounding
//! to `f64` do not need reduced fractions; only reported values are reduced.

use super::modular::{self, Cols};
use super::tableau::{col_of, var_of, Tableau};
use crate::path::Var;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

/// The problem's scaled integer rows by columns, for the lifting.
pub(crate) struct Scaled {
    /// Columns `u`, `z`, `w`.
    cols: Vec<Vec<(usize, BigInt)>>,
    q: Vec<BigInt>,
    d: Vec<BigInt>,
}

impl Scaled {
    /// From a tableau that has not pivoted yet (`[A | q | d]` itself).
    pub fn new(t: &Tableau) -> Self {
        let stored = t.p + 2 * t.n;
        let cols = (0..stored)
            .map(|c| {
                t.rows
                    .iter()
                    .enumerate()
                    .filter(|(_, row)| !row[c].is_zero())
                    .map(|(i, row)| (i, row[c].clone()))
                    .collect()
            })
            .collect();
        Scaled {
            cols,
            q: t.rows.iter().map(|row| row[t.qc()].clone()).collect(),
            d: t.rows.iter().map(|row| row[t.dc()].clone()).collect(),
        }
    }

    /// The columns `target` (one per row) as a square matrix, if all are
    /// stored columns.
    fn square(&self, target: &[usize]) -> Option<Vec<Vec<(usize, BigInt)>>> {
        if target.len() != self.q.len() {
            return None;
        }
        target.iter().map(|&c| self.cols.get(c).cloned()).collect()
    }

    /// The right-hand side `q` (scaled rows).
    pub fn q(&self) -> &[BigInt] {
        &self.q
    }

    /// Column `c` of `[u | z | w | z0 | L]` in the tableau's numbering, with
    /// `L` as a variable (its column `-d`, `lam` its number): `None` for `z0`,
    /// artificials and beyond.
    pub fn column(&self, c: usize, lam: usize) -> Option<Vec<(usize, BigInt)>> {
        if c == lam {
            return Some(
                self.d
                    .iter()
                    .enumerate()
                    .filter(|(_, v)| !v.is_zero())
                    .map(|(i, v)| (i, -v))
                    .collect(),
            );
        }
        self.cols.get(c).cloned()
    }

    /// The free block `M[0..p, 0..p]` (scaled rows) is nonsingular modulo a
    /// prime, which proves it nonsingular; false says nothing.
    pub fn free_block_nonsingular(&self, p: usize) -> bool {
        let cols: Vec<Vec<(usize, BigInt)>> = self.cols[..p]
            .iter()
            .map(|col| col.iter().filter(|(i, _)| *i < p).cloned().collect())
            .collect();
        modular::nonsingular(&cols)
    }
}

/// The exact basic solution of one basis (see the module documentation).
pub(crate) struct Solution {
    pub p: usize,
    pub n: usize,
    /// The column basic in each row (`ncol() + r` for the artificial of
    /// equality row `r`).
    pub basis: Vec<usize>,
    /// Stored columns that are basic.
    pub basic: Vec<bool>,
    /// Row `r` was multiplied by `2^-row_exp[r]` (the stored `w_i` is
    /// `2^-row_exp[p + i] w_i`).
    row_exp: Vec<i32>,
    a: Vec<BigInt>,
    da: BigInt,
    b: Vec<BigInt>,
    db: BigInt,
}

impl Solution {
    /// Solves the square basis `target` (stored columns, one per row) by
    /// p-adic lifting; `None` when it is not square, not provably
    /// nonsingular modulo the primes tried, or the lifting fails.
    pub fn modular(scaled: &Scaled, t: &Tableau, target: &[usize]) -> Option<Self> {
        let cols: Vec<Vec<(usize, BigInt)>> = scaled.square(target)?;
        let cols: &Cols = &cols;
        let mut sol = modular::solve(cols, &[scaled.q.clone(), scaled.d.clone()])?;
        let (b, db) = sol.pop()?;
        let (a, da) = sol.pop()?;
        let mut basic = vec![false; t.ncol()];
        for &c in target {
            basic[c] = true;
        }
        Some(Solution {
            p: t.p,
            n: t.n,
            basis: target.to_vec(),
            basic,
            row_exp: t.row_exp.clone(),
            a,
            da,
            b,
            db,
        })
    }

    /// The basic solution of the tableau's current basis.
    pub fn from_tableau(t: &Tableau) -> Self {
        let s = if t.det.is_negative() {
            -BigInt::one()
        } else {
            BigInt::one()
        };
        let col = |c: usize| -> Vec<BigInt> { t.rows.iter().map(|row| &row[c] * &s).collect() };
        let det = t.det.abs();
        Solution {
            p: t.p,
            n: t.n,
            basis: t.basis.clone(),
            basic: t.basic.clone(),
            row_exp: t.row_exp.clone(),
            a: col(t.qc()),
            da: det.clone(),
            b: col(t.dc()),
            db: det,
        }
    }

    pub fn ncol(&self) -> usize {
        self.p + 2 * self.n + 4
    }
    /// True for `z`, `w` and `z0`: the variables that must stay nonnegative.
    pub fn signed(&self, c: usize) -> bool {
        c >= self.p && c <= self.p + 2 * self.n
    }
    pub fn col_of(&self, v: Var) -> Option<usize> {
        col_of(self.p, self.n, v)
    }
    pub fn var_of(&self, c: usize) -> Option<Var> {
        var_of(self.p, self.n, c)
    }
    pub fn is_basic(&self, c: usize) -> bool {
        self.basic.get(c).copied().unwrap_or(false)
    }

    /// The basic variable of row `i` as `a + L b` (exact, not reduced).
    pub fn affine(&self, i: usize) -> (BigRational, BigRational) {
        (
            BigRational::new_raw(self.a[i].clone(), self.da.clone()),
            BigRational::new_raw(self.b[i].clone(), self.db.clone()),
        )
    }

    /// The numerators `(a_i, b_i)` of row `i` (signs, and ratios between rows:
    /// the denominators are common and positive).
    pub fn numerators(&self, i: usize) -> (&BigInt, &BigInt) {
        (&self.a[i], &self.b[i])
    }

    /// A rate `r` per unit of the stored variable of column `c` as a rate per
    /// unit of the variable itself (a stored `w_i` is `2^-row_exp w_i`).
    pub fn per_unit(&self, c: usize, r: BigRational) -> BigRational {
        let (p, n) = (self.p, self.n);
        if c >= p + n && c < p + 2 * n {
            let e = self.row_exp[c - n];
            let two = BigRational::from_integer(BigInt::from(2));
            return r * num_traits::pow::Pow::pow(two, -e);
        }
        r
    }

    /// The sign of the basic variable of row `i` at `L = l` (`-1`, `0`, `1`;
    /// the row scaling is a positive power of two and keeps it).
    pub fn sign_at(&self, i: usize, l: &BigRational) -> i32 {
        let v = &self.a[i] * &self.db * l.denom() + &self.b[i] * &self.da * l.numer();
        sign(&v)
    }

    /// The sign of the slope `d x / dL` of the basic variable of row `i`.
    pub fn slope_sign(&self, i: usize) -> i32 {
        sign(&self.b[i])
    }

    /// `-a_i / b_i` for the numerators `(a_i, b_i)` of a row: the root of that
    /// row, exact and reduced.
    pub fn root(&self, a: &BigInt, b: &BigInt) -> BigRational {
        BigRational::new(-(a * &self.db), b * &self.da)
    }

    /// `2^row_exp` of the `w` of column `c`, or one.
    fn unscale(&self, c: usize, num: BigInt, den: BigInt) -> BigRational {
        let (p, n) = (self.p, self.n);
        if c >= p + n && c < p + 2 * n {
            let e = self.row_exp[c - n];
            if e >= 0 {
                return BigRational::new_raw(num << e as usize, den);
            }
            return BigRational::new_raw(num, den << (-e) as usize);
        }
        BigRational::new_raw(num, den)
    }

    /// The value of the variable of column `c` at `L = l`, unscaled, not
    /// reduced: zero when it is not basic.
    pub fn value(&self, c: usize, l: &BigRational) -> BigRational {
        let Some(i) = self.basis.iter().position(|&b| b == c) else {
            return BigRational::zero();
        };
        let (ln, ld) = (l.numer(), l.denom());
        let num = &self.a[i] * &self.db * ld + &self.b[i] * &self.da * ln;
        let den = &self.da * &self.db * ld;
        self.unscale(c, num, den)
    }

    /// The slope `d x / dL` of the variable of column `c`, unscaled, not
    /// reduced: zero when it is not basic.
    pub fn slope(&self, c: usize) -> BigRational {
        let Some(i) = self.basis.iter().position(|&b| b == c) else {
            return BigRational::zero();
        };
        self.unscale(c, self.b[i].clone(), self.db.clone())
    }
}

/// The sign of an integer as `-1`, `0`, `1`.
pub(crate) fn sign(v: &BigInt) -> i32 {
    if v.is_positive() {
        1
    } else if v.is_negative() {
        -1
    } else {
        0
    }
}
