//! The lexicographic rule of the minimum-ratio test (moved here from
//! `pivoting/ratio.rs` unchanged, issue 15): of the rows tied at the minimum
//! ratio, the one whose row of `B^{-1}`, divided by its entry of the
//! entering column, is lexicographically smallest, the complementary
//! columns (`p..p+n`) compared first, then the free ones.
//!
//! What changed is how the rows reach the comparison. The sparse basis
//! solved every tied row of `B^{-1}` in full (`B^{-T} e_r`), gathered each
//! into system order and set its rounding noise to zero, a pass over the
//! unknowns per row after the solve; the rule then read a few hundred
//! entries. [`InverseRows`] keeps the solved rows in the factors' order and
//! reads an entry through the permutation when the rule asks for it,
//! applying the same noise floor (the row's largest entry, taken in one
//! pass over the solved row: the same maximum). Every entry read is the
//! same number as before, so the rule picks the same row; with the check
//! on ([`check_on`], `PLCP_LEX_CHECK=1`) every tie is also broken the old
//! way (rows in full, through faer's solves) and a different choice, or a
//! different bit in any entry of a row, panics.
//!
//! The bases that do not hand over rows (the dense block basis) are read
//! by columns, one solve `B^{-1} e_k` a column; where a tie outlasts as
//! many columns as rows are tied (at least 4), the rule solves the rows
//! still tied (`B^{-T} e_r`) and reads the remaining columns from them,
//! with the rows' noise floor. On a degenerate dense family this took the
//! engine from 2.5 to 1.0 s at n = 601 and from 12.8..16.8 to 2.4..2.8 s
//! at n = 801, with the same pivots and residual.

use super::BasisFactor;
use crate::scalar::Scalar;
use crate::tolerance::ROW_NOISE_EPS;
use core::cell::{Cell, RefMut};
use core::sync::atomic::{AtomicBool, Ordering};
use faer::Col;
use std::sync::OnceLock;

/// Rows of `B^{-1}` as a basis hands them to the lexicographic rule: entry
/// `(t, k)` is row `rows[t]` at system row `k`, read as zero at or below
/// `ROW_NOISE_EPS * eps * max abs(row)` (rounding noise: a zero of the exact
/// inverse).
pub(crate) struct InverseRows<'a, T: Scalar> {
    dim: usize,
    /// The rows one after the other, each in the order `perm` reads
    /// (entry `k` of row `t` at `data[t * dim + perm[k]]`; no `perm`: in
    /// system order).
    data: RefMut<'a, Vec<T>>,
    perm: Option<&'a [usize]>,
    /// Each row's noise floor.
    tol: Vec<T>,
}

impl<'a, T: Scalar> InverseRows<'a, T> {
    /// The rows in `data` (see the field), their noise floors measured here.
    pub(crate) fn new(dim: usize, data: RefMut<'a, Vec<T>>, perm: Option<&'a [usize]>) -> Self {
        let rows = data.len().checked_div(dim).unwrap_or(0);
        let tol = (0..rows)
            .map(|t| {
                // the largest entry over the same numbers as the row in
                // system order (a maximum does not depend on the order; a
                // comparison rather than `max`, whose NaN handling cost a
                // few instructions an entry: NaN is passed over either way)
                let big = data[t * dim..(t + 1) * dim].iter().fold(T::zero(), |b, v| {
                    let a = v.abs();
                    if a > b {
                        a
                    } else {
                        b
                    }
                });
                T::from_f64(ROW_NOISE_EPS) * T::eps() * big
            })
            .collect();
        Self {
            dim,
            data,
            perm,
            tol,
        }
    }

    /// Entry `k` (a system row) of row `t` as computed (noise included).
    #[inline]
    pub(crate) fn get_raw(&self, t: usize, k: usize) -> T {
        let at = match self.perm {
            Some(p) => p[k],
            None => k,
        };
        self.data[t * self.dim + at]
    }

    /// Entry `k` (a system row) of row `t`, its noise read as zero.
    #[inline]
    pub(crate) fn get(&self, t: usize, k: usize) -> T {
        let at = match self.perm {
            Some(p) => p[k],
            None => k,
        };
        let v = self.data[t * self.dim + at];
        if v.abs() <= self.tol[t] {
            T::zero()
        } else {
            v
        }
    }
}

/// Whether every tie is also broken the old way and compared
/// ([`check_on`]); read once from `PLCP_LEX_CHECK` (`1`) or set by
/// [`set_check`].
static CHECK: AtomicBool = AtomicBool::new(false);
static CHECK_ENV: OnceLock<bool> = OnceLock::new();
thread_local! {
    /// Ties checked so far on this thread.
    static CHECKED: Cell<usize> = const { Cell::new(0) };
}

/// Turns the check of the lexicographic rule on or off for the process
/// (see the module docs); returns the number of ties checked so far on the
/// calling thread. A test hook (`plcp::lex_check`), not part of the API.
pub fn set_check(on: bool) -> usize {
    CHECK.store(on, Ordering::SeqCst);
    CHECKED.with(Cell::get)
}

fn check_on() -> bool {
    CHECK.load(Ordering::Relaxed)
        || *CHECK_ENV.get_or_init(|| std::env::var("PLCP_LEX_CHECK").is_ok_and(|v| v == "1"))
}

/// The rows `tied` (more than one, ascending) left by the lexicographic rule
/// on the basis `factor` and the entering column `col`, the largest pivot
/// first (still tied numerically: the most stable pivot decides). `noise`
/// and `tie_tol` are the engine's (`pivot_tol_eps * eps`, `tie_tol_eps *
/// eps`), `p` the number of free variables, `dim = p + n`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn break_tie<T: Scalar>(
    factor: &dyn BasisFactor<T>,
    col: &Col<T>,
    tied: Vec<usize>,
    p: usize,
    dim: usize,
    tie_tol: T,
    noise: T,
) -> Vec<usize> {
    // a factorisation may hand over the tied rows of B^{-1} at once
    // (one transpose solve per tied row instead of a solve per column)
    let rows = factor.inverse_rows(&tied);
    // the tie as handed over, kept only for the check (off: no copy)
    let checked = (rows.is_some() && check_on()).then(|| tied.clone());
    let out = compare(factor, col, tied, p, dim, tie_tol, noise, rows.as_ref());
    if let Some(tied) = checked {
        let full = factor.inverse_rows_full(&tied);
        if let (Some(new), Some(old)) = (&rows, &full) {
            for (t, row) in old.iter().enumerate() {
                for k in 0..dim {
                    assert_eq!(
                        new.get(t, k).to_f64().to_bits(),
                        row[k].to_f64().to_bits(),
                        "lexicographic check: row {} of B^-1, entry {k}",
                        tied[t]
                    );
                }
            }
        }
        let reference = compare_full(factor, col, tied.clone(), p, dim, tie_tol, noise, full);
        assert_eq!(out, reference, "lexicographic check: tie {tied:?}");
        CHECKED.with(|c| c.set(c.get() + 1));
    }
    out
}

/// The rule itself (the loop that was in `ratio.rs`), on `rows` if the basis
/// handed them over, else on the columns `B^{-1} e_k` one by one.
#[allow(clippy::too_many_arguments)]
fn compare<T: Scalar>(
    factor: &dyn BasisFactor<T>,
    col: &Col<T>,
    mut tied: Vec<usize>,
    p: usize,
    dim: usize,
    tie_tol: T,
    noise: T,
    rows: Option<&InverseRows<'_, T>>,
) -> Vec<usize> {
    // complementary columns first
    let order = (p..dim).chain(0..p);
    match rows {
        Some(rows) => compare_rows(rows, col, &mut tied, order, tie_tol),
        None => {
            for (read, k) in order.enumerate() {
                if tied.len() == 1 {
                    break;
                }
                if read >= columns_before_rows(tied.len()) {
                    // a long tie (a degenerate problem whose tied rows agree
                    // over many columns: each column read is a solve of
                    // order dim): the rows still tied, one transpose solve
                    // each, and the rest of the comparison on them
                    let cell = core::cell::RefCell::new(transpose_rows(factor, &tied, dim));
                    let rows = InverseRows::new(dim, cell.borrow_mut(), None);
                    compare_rows(
                        &rows,
                        col,
                        &mut tied,
                        (p..dim).chain(0..p).skip(read),
                        tie_tol,
                    );
                    break;
                }
                let vals = unit_vals(factor, &tied, col, k, noise);
                tied = keep_smallest(tied, &vals, tie_tol);
            }
        }
    }
    sort_by_pivot(&mut tied, col);
    tied
}

/// Columns of `B^{-1}` the rule reads one by one (a solve each) before it
/// takes the rows still tied instead (a transpose solve each), on a basis
/// that does not hand over rows: the rows cost no more once the columns
/// read outnumber them. Most ties end at the first column, where nothing
/// changes; a degenerate family (`M = B B'/n + 0.1 I` with `B` of low rank
/// at n = 601, 260 degenerate pivots) read about two hundred columns a tie.
fn columns_before_rows(tied: usize) -> usize {
    tied.max(4)
}

/// Rows `tied` of `B^{-1}` (`B^{-T} e_r`), one after the other in system order.
fn transpose_rows<T: Scalar>(factor: &dyn BasisFactor<T>, tied: &[usize], dim: usize) -> Vec<T> {
    let mut data = Vec::with_capacity(tied.len() * dim);
    let mut e = Col::<T>::zeros(dim);
    for &r in tied {
        e[r] = T::one();
        let row = factor.solve_transpose(&e);
        e[r] = T::zero();
        data.extend(row.iter().copied());
    }
    data
}

/// The rule on rows handed over: the tied rows and their places among
/// them, narrowed in place (no allocation per column compared: the rule
/// reads a hundred columns or more on the cantilever).
fn compare_rows<T: Scalar>(
    rows: &InverseRows<'_, T>,
    col: &Col<T>,
    tied: &mut Vec<usize>,
    order: impl Iterator<Item = usize>,
    tie_tol: T,
) {
    let mut at: Vec<usize> = (0..tied.len()).collect();
    let mut vals: Vec<T> = Vec::with_capacity(tied.len());
    for k in order {
        if tied.len() == 1 {
            break;
        }
        vals.clear();
        vals.extend(tied.iter().zip(&at).map(|(&r, &t)| rows.get(t, k) / col[r]));
        keep_smallest_in_place(tied, &mut at, &vals, tie_tol);
    }
}

/// The rule as it was (every tied row in full), for the check.
#[allow(clippy::too_many_arguments)]
fn compare_full<T: Scalar>(
    factor: &dyn BasisFactor<T>,
    col: &Col<T>,
    mut tied: Vec<usize>,
    p: usize,
    dim: usize,
    tie_tol: T,
    noise: T,
    inv_rows: Option<Vec<Col<T>>>,
) -> Vec<usize> {
    let order: Vec<usize> = (p..dim).chain(0..p).collect();
    let first_tied = tied.clone();
    for &k in &order {
        if tied.len() == 1 {
            break;
        }
        let vals: Vec<T> = match &inv_rows {
            Some(rows) => tied
                .iter()
                .map(|&r| {
                    let t = first_tied.iter().position(|&f| f == r).expect("tied row");
                    rows[t][k] / col[r]
                })
                .collect(),
            None => unit_vals(factor, &tied, col, k, noise),
        };
        tied = keep_smallest(tied, &vals, tie_tol);
    }
    sort_by_pivot(&mut tied, col);
    tied
}

/// Entries `k` of the tied rows from the column `B^{-1} e_k` (bases that
/// do not hand over rows).
fn unit_vals<T: Scalar>(
    factor: &dyn BasisFactor<T>,
    tied: &[usize],
    col: &Col<T>,
    k: usize,
    noise: T,
) -> Vec<T> {
    // entries of B^{-1} e_k at its rounding level (the pivot tolerance's
    // noise, relative to the column) are zeros of the exact inverse:
    // compared as such, else rounding decides where the exact rule looks
    // further (tobenna: 29 tied rows whose entries in a column are all exact
    // zeros, computed as 1e-18 of noise)
    let inv_k = factor.unit(k);
    let big = match inv_k.as_ref().try_as_col_major() {
        Some(c) => crate::pivoting::max_abs(c.as_slice()),
        None => inv_k.iter().fold(T::zero(), |a, v| a.max(v.abs())),
    };
    let zero = noise * big;
    tied.iter()
        .map(|&r| {
            if inv_k[r].abs() <= zero {
                T::zero()
            } else {
                inv_k[r] / col[r]
            }
        })
        .collect()
}

/// The rows whose value is within the tie tolerance of the smallest.
fn keep_smallest<T: Scalar>(tied: Vec<usize>, vals: &[T], tie_tol: T) -> Vec<usize> {
    let vmin = vals.iter().fold(vals[0], |a, &b| a.min(b));
    let vscale = vals.iter().fold(T::zero(), |a, &b| a.max(b.abs()));
    let tol = tie_tol * vscale;
    let kept: Vec<usize> = tied
        .iter()
        .zip(vals.iter())
        .filter(|(_, &v)| v - vmin <= tol)
        .map(|(&r, _)| r)
        .collect();
    // non-finite entries compare false everywhere: keep the set then
    if kept.is_empty() {
        tied
    } else {
        kept
    }
}

/// [`keep_smallest`] on `tied` and `at` (its rows' places) side by side,
/// in place: the same rows kept.
fn keep_smallest_in_place<T: Scalar>(
    tied: &mut Vec<usize>,
    at: &mut Vec<usize>,
    vals: &[T],
    tie_tol: T,
) {
    let vmin = vals.iter().fold(vals[0], |a, &b| a.min(b));
    let vscale = vals.iter().fold(T::zero(), |a, &b| a.max(b.abs()));
    let tol = tie_tol * vscale;
    let keep = |v: T| v - vmin <= tol;
    // non-finite entries compare false everywhere: keep the set then
    if !vals.iter().any(|&v| keep(v)) {
        return;
    }
    let mut n = 0;
    for (j, &v) in vals.iter().enumerate() {
        if keep(v) {
            tied[n] = tied[j];
            at[n] = at[j];
            n += 1;
        }
    }
    tied.truncate(n);
    at.truncate(n);
}

/// Still tied (numerically): the largest pivot is the most stable.
fn sort_by_pivot<T: Scalar>(tied: &mut [usize], col: &Col<T>) {
    tied.sort_by(|&a, &b| {
        col[b]
            .partial_cmp(&col[a])
            .unwrap_or(core::cmp::Ordering::Equal)
    });
}
