//! The integer tableau `det(B) B^-1 [A | q | d]` and its pivot (see the module
//! above for the math).

use super::decode;
use crate::path::Var;
use crate::problem::Plcp;
use crate::scalar::Scalar;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use rayon::prelude::*;

/// Below this many entries a pivot runs on one thread.
const PAR_MIN_ENTRIES: usize = 4096;

/// The column of variable `v` with `p` free variables and `n` pairs (see
/// [`Tableau`]); artificial variables come after the stored columns.
pub(crate) fn col_of(p: usize, n: usize, v: Var) -> Option<usize> {
    let ncol = p + 2 * n + 4;
    match v {
        Var::U(j) if j < p => Some(j),
        Var::Z(i) if i < n => Some(p + i),
        Var::W(i) if i < n => Some(p + n + i),
        Var::Lambda => Some(p + 2 * n + 1),
        Var::Artificial(r) if r < p => Some(ncol + r),
        _ => None,
    }
}

/// The variable of column `c` (`None` for `z0` and the right-hand sides).
pub(crate) fn var_of(p: usize, n: usize, c: usize) -> Option<Var> {
    let ncol = p + 2 * n + 4;
    if c < p {
        Some(Var::U(c))
    } else if c < p + n {
        Some(Var::Z(c - p))
    } else if c < p + 2 * n {
        Some(Var::W(c - p - n))
    } else if c == p + 2 * n + 1 {
        Some(Var::Lambda)
    } else if c >= ncol {
        Some(Var::Artificial(c - ncol))
    } else {
        None
    }
}

/// Columns: `u` (p), `z` (n), `w` (n), the start phase's artificial `z0`, the
/// parameter `L` as a variable (the tracer's second phase), then the two
/// right-hand sides `q` and `d`. Artificial variables of the equality rows
/// have no stored column: they only ever leave.
pub(crate) struct Tableau {
    pub p: usize,
    pub n: usize,
    pub rows: Vec<Vec<BigInt>>,
    /// The column basic in each row; `ncol() + r` for the artificial of row `r`.
    pub basis: Vec<usize>,
    /// `det(B)` up to the sign convention of the pivots: every basic column is
    /// `det` times a unit vector.
    pub det: BigInt,
    /// Stored columns whose content is current (basic columns are not stored).
    pub basic: Vec<bool>,
    /// Columns a pivot updates (others are left stale).
    pub active: Vec<bool>,
    /// Row `r` was multiplied by `2^-row_exp[r]`, so the stored `w_i` is
    /// `2^-row_exp[p + i] w_i`.
    pub row_exp: Vec<i32>,
}

impl Tableau {
    pub fn ncol(&self) -> usize {
        self.p + 2 * self.n + 4
    }
    pub fn z0(&self) -> usize {
        self.p + 2 * self.n
    }
    pub fn lam(&self) -> usize {
        self.p + 2 * self.n + 1
    }
    pub fn qc(&self) -> usize {
        self.p + 2 * self.n + 2
    }
    pub fn dc(&self) -> usize {
        self.p + 2 * self.n + 3
    }
    pub fn col_of(&self, v: Var) -> Option<usize> {
        col_of(self.p, self.n, v)
    }
    /// The variable of column `c` (`None` for `z0` and the right-hand sides).
    pub fn var_of(&self, c: usize) -> Option<Var> {
        var_of(self.p, self.n, c)
    }
    /// True for `z`, `w` and `z0`: the variables that must stay nonnegative.
    pub fn signed(&self, c: usize) -> bool {
        c >= self.p && c <= self.z0()
    }
    /// The row in which column `c` is basic.
    pub fn row_of(&self, c: usize) -> Option<usize> {
        self.basis.iter().position(|&b| b == c)
    }

    /// The problem's rows, each scaled by a power of two to integers; the start
    /// basis: artificial variables on the equality rows, `w` on the others.
    pub fn new<T: Scalar>(problem: &Plcp<T>) -> Self {
        let (p, n) = (problem.free(), problem.n());
        let dim = p + n;
        let m = problem.m();
        let (q, d) = (problem.q(), problem.d());
        let ncol = p + 2 * n + 4;
        let mut row_exp = vec![0; dim];
        let rows: Vec<Vec<BigInt>> = (0..dim)
            .map(|r| {
                // (column, mantissa, exponent) of every nonzero part of the row
                let mut parts: Vec<(usize, i64, i32)> = Vec::new();
                let mut push = |c: usize, x: T, neg: bool| {
                    let (hi, lo) = x.parts();
                    for v in [hi, lo] {
                        if v != 0.0 {
                            let (mm, e) = decode(if neg { -v } else { v });
                            parts.push((c, mm, e));
                        }
                    }
                };
                for j in 0..dim {
                    push(j, m[(r, j)], true);
                }
                push(p + 2 * n + 2, q[r], false);
                push(p + 2 * n + 3, d[r], false);
                let emin = parts.iter().map(|t| t.2).min().unwrap_or(0);
                row_exp[r] = emin;
                let mut row = vec![BigInt::zero(); ncol];
                for (c, mm, e) in parts {
                    row[c] += BigInt::from(mm) << (e - emin) as usize;
                }
                if r >= p {
                    // w_i (scaled by the row's power of two: the sign is kept)
                    row[p + n + (r - p)] = BigInt::one();
                    // z0 with the covering vector one in scaled rows
                    row[p + 2 * n] = -BigInt::one();
                }
                row
            })
            .collect();
        let basis = (0..dim)
            .map(|r| if r < p { ncol + r } else { p + n + (r - p) })
            .collect();
        let mut basic = vec![false; ncol];
        for i in 0..n {
            basic[p + n + i] = true;
        }
        let mut active = vec![true; ncol];
        active[p + 2 * n + 1] = false; // L: only as a variable in the tracer
        Tableau {
            p,
            n,
            rows,
            basis,
            det: BigInt::one(),
            basic,
            active,
            row_exp,
        }
    }

    /// Pivots column `c` into row `r` (`T_rc != 0`).
    pub fn pivot(&mut self, r: usize, c: usize) {
        debug_assert!(!self.rows[r][c].is_zero());
        let piv = self.rows[r][c].clone();
        let dold = std::mem::replace(&mut self.det, piv.clone());
        let colc: Vec<BigInt> = self.rows.iter().map(|row| row[c].clone()).collect();
        let rowr = self.rows[r].clone();
        let upd: Vec<usize> = (0..self.ncol())
            .filter(|&j| j != c && self.active[j] && !self.basic[j])
            .collect();
        let same = piv == dold;
        let work = |(i, row): (usize, &mut Vec<BigInt>)| {
            if i == r {
                return;
            }
            let ci = &colc[i];
            for &j in &upd {
                if ci.is_zero() {
                    if !same && !row[j].is_zero() {
                        row[j] = &row[j] * &piv / &dold;
                    }
                } else if rowr[j].is_zero() {
                    if !row[j].is_zero() {
                        row[j] = &row[j] * &piv / &dold;
                    }
                } else {
                    row[j] = (&row[j] * &piv - ci * &rowr[j]) / &dold;
                }
            }
        };
        if self.rows.len() * upd.len() >= PAR_MIN_ENTRIES {
            self.rows.par_iter_mut().enumerate().for_each(work);
        } else {
            self.rows.iter_mut().enumerate().for_each(work);
        }
        // the leaving column: -(entering column), det_old in row r
        let leaving = self.basis[r];
        if leaving < self.ncol() {
            for (i, row) in self.rows.iter_mut().enumerate() {
                row[leaving] = if i == r { dold.clone() } else { -&colc[i] };
            }
            self.basic[leaving] = false;
        }
        self.basis[r] = c;
        self.basic[c] = true;
    }

    /// The basic variable of row `i` as `a + L b` (exact).
    pub fn affine(&self, i: usize) -> (BigRational, BigRational) {
        let row = &self.rows[i];
        (
            BigRational::new(row[self.qc()].clone(), self.det.clone()),
            BigRational::new(row[self.dc()].clone(), self.det.clone()),
        )
    }

    /// The sign of `det`: entries times it are those of a tableau with `det > 0`.
    pub fn sign(&self) -> i32 {
        if self.det.is_negative() {
            -1
        } else {
            1
        }
    }

    /// Brings every free variable into the basis that the equality rows allow
    /// (replacing artificials); returns how many could not enter.
    pub fn pivot_in_free(&mut self) -> usize {
        let mut left = 0;
        for j in 0..self.p {
            if self.basic[j] {
                continue;
            }
            let art = (0..self.rows.len())
                .filter(|&r| self.basis[r] >= self.ncol() && !self.rows[r][j].is_zero())
                .min_by_key(|&r| self.rows[r][j].bits());
            match art {
                Some(r) => self.pivot(r, j),
                None => left += 1,
            }
        }
        left
    }
}
