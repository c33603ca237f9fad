//! The pivot rule: the lexicographic minimum-ratio test that picks who leaves,
//! the pivot itself (basis update, values moved by `theta`), and which
//! entering variables a step may use.

use super::*;

impl<'a, T: Scalar> Engine<'a, T> {
    /// The minimum-ratio test with the lexicographic rule. Returns the row and the step.
    pub(super) fn ratio_test(&self, col: &Col<T>) -> Option<(usize, T)> {
        let colmax = col_max_abs(col);
        if colmax == T::zero() {
            return None;
        }
        // the pivot tolerance of the candidates is relative to the entries of
        // the sign-constrained rows (z, w): a basic L's entry is the rate of
        // the parameter and a free variable's is in its own units; where they
        // are large per unit of the driver (L at 1e9, u at 8e4 in the stiffest
        // frame, issue 14 defect 5) they made an accurate entry of 1e-3 at the
        // blocking row look like rounding, and the path ran past the event
        let compmax = (0..self.dim)
            .filter(|&r| is_comp(self.basis[r]))
            .fold(T::zero(), |a, r| a.max(col[r].abs()));
        // but never below the rounding of the whole column (dim roundings of
        // its largest entry): where every z/w entry is rounding (a ray), the
        // largest of them must not become a block (fx128 found one at
        // L = 1.7e41 there)
        let floor = T::from_f64(self.dim as f64) * T::eps() * colmax;
        // switched off: a z/w entry at the rounding of the whole column then
        // blocked (the 20-element cantilever found a break at L = 3e14 with
        // residual 1.1): the whole column's noise stays the tolerance until
        // the rows' own rounding is estimated (issue 14, defect 5)
        let ptol = if PIVOT_TOL_ON_COMP_ROWS {
            (self.noise * compmax).max(floor)
        } else {
            self.noise * colmax
        };
        // (artificial rows, below, keep the whole column's scale)
        let ptol_all = self.noise * colmax;
        // artificial variables are fixed at zero: any move blocks them
        let mut art: Option<usize> = None;
        for r in 0..self.dim {
            if matches!(self.basis[r], Var::Artificial(_))
                && col[r].abs() > ptol_all
                && art.is_none_or(|a| col[r].abs() > col[a].abs())
            {
                art = Some(r);
            }
        }
        if let Some(r) = art {
            return Some((r, T::zero()));
        }
        let xnorm = self.xscale();
        let mut best: Option<T> = None;
        // the candidates (rows and ratios), recomputed in the second pass
        // rather than collected: no allocation unless several rows tie
        let ratio = |r: usize| {
            (is_comp(self.basis[r]) && col[r] > ptol).then(|| self.x[r].max(T::zero()) / col[r])
        };
        let mut first_cand = None;
        for r in 0..self.dim {
            if let Some(ratio) = ratio(r) {
                first_cand.get_or_insert(r);
                best = Some(best.map_or(ratio, |b| b.min(ratio)));
            }
        }
        let tmin = best?;
        let is_tied = |r: usize| {
            ratio(r).is_some_and(|t| t - tmin <= self.tie_tol * (tmin.abs() + xnorm / col[r]))
        };
        let (mut n_tied, mut first) = (0usize, None);
        for r in 0..self.dim {
            if is_tied(r) {
                n_tied += 1;
                first.get_or_insert(r);
            }
        }
        if n_tied <= 1 {
            let r = first.or(first_cand).expect("a candidate");
            let theta = self.x[r].max(T::zero()) / col[r];
            return Some((r, theta));
        }
        let mut tied: Vec<usize> = (0..self.dim).filter(|&r| is_tied(r)).collect();
        if tied.len() > 1 {
            // lexicographic rule: compare rows of B^{-1} / col_r, complementary columns first
            let order: Vec<usize> = (self.p..self.dim).chain(0..self.p).collect();
            // a factorisation may hand over the tied rows of B^{-1} at once
            // (one transpose solve per tied row instead of a solve per column)
            let inv_rows = self.factor.inverse_rows(&tied);
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
                    None => {
                        // entries of B^{-1} e_k at its rounding level (the
                        // pivot tolerance's noise, relative to the column) are
                        // zeros of the exact inverse: compared as such, else
                        // rounding decides where the exact rule looks further
                        // (tobenna: 29 tied rows whose entries in a column are
                        // all exact zeros, computed as 1e-18 of noise)
                        let inv_k = self.factor.unit(k);
                        let zero = self.noise * col_max_abs(&inv_k);
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
                };
                let vmin = vals.iter().fold(vals[0], |a, &b| a.min(b));
                let vscale = vals.iter().fold(T::zero(), |a, &b| a.max(b.abs()));
                let tol = self.tie_tol * vscale;
                let kept: Vec<usize> = tied
                    .iter()
                    .zip(vals.iter())
                    .filter(|(_, &v)| v - vmin <= tol)
                    .map(|(&r, _)| r)
                    .collect();
                // non-finite entries compare false everywhere: keep the set then
                if !kept.is_empty() {
                    tied = kept;
                }
            }
            // still tied (numerically): the largest pivot is the most stable
            tied.sort_by(|&a, &b| {
                col[b]
                    .partial_cmp(&col[a])
                    .unwrap_or(core::cmp::Ordering::Equal)
            });
        }
        let r = *tied.first().unwrap_or(&first_cand.expect("a candidate"));
        let theta = self.x[r].max(T::zero()) / col[r];
        Some((r, theta))
    }

    /// Pivot `entering` (column `col = B^{-1} a`, value `value`) into row `r`.
    pub(super) fn pivot(
        &mut self,
        r: usize,
        entering: Var,
        col: &Col<T>,
        value: T,
    ) -> Result<(), String> {
        let leaving = self.basis[r];
        if self.trace_pivots {
            eprintln!(
                "pivot {}: {} in for {} at {r}, pivot {:e}, value {:e}, L {:e}",
                self.pivots,
                entering,
                leaving,
                col[r].to_f64(),
                value.to_f64(),
                self.lambda.to_f64()
            );
            eprintln!(
                "   before: {:?}",
                self.basis
                    .iter()
                    .zip(self.x.iter())
                    .map(|(v, x)| format!("{v}={:.4}", x.to_f64()))
                    .collect::<Vec<_>>()
            );
        }
        let li = self.var_index(leaving);
        self.pos[li] = None;
        let ei = self.var_index(entering);
        self.pos[ei] = Some(r);
        self.basis[r] = entering;
        let updated = self
            .factor
            .replace(self.m, &self.d, self.p, r, leaving, entering, col);
        if !updated {
            // the update does not apply (e.g. a row covered twice): rebuild, which
            // reports a singular basis if that is what it is
            self.refactor()?;
        }
        self.x[r] = value;
        self.pivots += 1;
        self.since_refactor += 1;
        if self
            .factor
            .refactor_due(self.since_refactor, self.settings.refactor_period)
        {
            self.refactor()?;
        }
        Ok(())
    }

    /// Whether `v` may enter the basis under restricted entry (its complement nonbasic),
    /// given the current driver.
    pub(super) fn admissible(&self, v: Var, driver: Var) -> bool {
        if v == driver || self.row_of(v).is_some() {
            return false;
        }
        match v.complement() {
            Some(c) => c != driver && self.row_of(c).is_none(),
            None => matches!(v, Var::U(_)),
        }
    }
}
