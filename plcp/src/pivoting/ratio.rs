//! The pivot rule: the lexicographic minimum-ratio test that picks who leaves,
//! the pivot itself (basis update, values moved by `theta`), and which
//! entering variables a step may use.

use super::*;

/// What [`Engine::read_near_tie`] makes of tied rows.
enum NearTie<T> {
    /// One row leaves first (exactly), at this step.
    Separated(usize, T),
    /// These rows stay tied (for the lexicographic rule).
    Tied(Vec<usize>),
}

impl<'a, T: Scalar> Engine<'a, T> {
    /// The minimum-ratio test with the lexicographic rule. Returns the row and the step.
    ///
    /// A pivot small against its column (below `sqrt(eps)` of the largest
    /// entry) must also stand above the rounding of its own entry, measured
    /// before the solve: `pivot_tol_eps * eps * |B^{-1}|_r (|B| |y|)`
    /// ([`crate::tolerance`], "entry rounding"). Else it is a zero of the exact
    /// column and its row is no candidate: the tolerance relative to the
    /// column (times a condition estimate only as fresh as the last
    /// refactorisation) let an entry of `7e-14` of a column of one, whose
    /// exact value is zero, block a secondary ray (`plcp/tests/prop_path.rs`,
    /// `f64_psd_singular_secondary_ray`).
    ///
    /// `v` is the entering variable (`col = B^{-1} a_v`): rows that tie are
    /// read again with refined values ([`Self::read_near_tie`]).
    ///
    /// `cap` is the step at which the trace ends (`L_max`, when `L` rises):
    /// where no regular row blocks, entries below the pivot tolerance are
    /// read for a block before it ([`Self::read_small_entries`]).
    pub(super) fn ratio_test(&self, col: &Col<T>, v: Var, cap: Option<T>) -> Option<(usize, T)> {
        // (the column's largest entry once for the test and its retries)
        let colmax = col_max_abs(col);
        let small = T::eps().sqrt() * colmax;
        // (set again below when a small entry blocks; a test whose block
        // was not pivoted on, L_max first, leaves nothing behind)
        self.refactor_after.set(false);
        self.values_after.set(false);
        let mut excluded: Vec<usize> = Vec::new();
        loop {
            let (r, theta) = self.ratio_test_excluding(col, colmax, v, cap, &excluded)?;
            let entry = col[r].abs();
            // (a small entry that the refined column separates from zero:
            // read_small_entries, which marks its pivot for a refactorisation)
            if entry > small
                || self.refactor_after.get()
                || self.values_after.get()
                || matches!(self.basis[r], Var::Artificial(_))
                || entry > self.pivot_tol * self.entry_rounding(r, col)
            {
                return Some((r, theta));
            }
            // within its own rounding: read again with the refined column
            // where the data are exact as given (issue 14: after an exact
            // tie, the slack `w = delta (2 - L)` of a near-singular block
            // stays basic at zero with a rate of `delta`, and ran negative)
            if self.settings.near_ties == crate::settings::NearTies::Refine {
                let read = &self.refined_ratios(v, col, &[r])[0];
                if read.err.is_finite() {
                    let (resolved, unresolved) = self.near_ties.get();
                    self.near_ties.set((resolved + 1, unresolved));
                    self.refactor_after.set(true);
                    return Some((r, T::narrow(read.ratio).max(T::zero())));
                }
            }
            excluded.push(r);
        }
    }

    /// `|B^{-1}|_r (|B| |y|)`, for `y = B^{-1} a` the entering column: what a
    /// backward-stable solve may get wrong in `y_r`, per unit roundoff
    /// (componentwise, Oettli-Prager). One transpose solve and a pass over the
    /// basic columns, spent only on small pivots.
    pub(super) fn entry_rounding(&self, r: usize, y: &Col<T>) -> T {
        let mut e = Col::<T>::zeros(self.dim);
        e[r] = T::one();
        let row = self.factor.solve_transpose(&e);
        let mut by = Col::<T>::zeros(self.dim);
        for (k, v) in self.basis.iter().enumerate() {
            let yk = y[k].abs();
            if yk == T::zero() {
                continue;
            }
            match *v {
                Var::U(j) => self.m.for_col(j, |i, mij| by[i] += mij.abs() * yk),
                Var::Z(j) => self.m.for_col(self.p + j, |i, mij| by[i] += mij.abs() * yk),
                Var::Lambda => {
                    for i in 0..self.dim {
                        by[i] += self.d[i].abs() * yk;
                    }
                }
                Var::W(i) => by[self.p + i] += yk,
                Var::Artificial(k) => by[k] += yk,
            }
        }
        (0..self.dim).fold(T::zero(), |s, i| s + row[i].abs() * by[i])
    }

    /// [`Self::ratio_test`] with the rows `excluded` no candidates
    /// (`colmax`: `col`'s largest absolute entry).
    fn ratio_test_excluding(
        &self,
        col: &Col<T>,
        colmax: T,
        v: Var,
        cap: Option<T>,
        excluded: &[usize],
    ) -> Option<(usize, T)> {
        if colmax == T::zero() {
            return None;
        }
        // the rows as slices (the same operations as faer's checked
        // indexing, without its checks: this test runs at every step of a
        // trace, the MPC loop's most frequent pass over `dim`)
        let dim = self.dim;
        let (cs, xs, basis) = (
            &col_slice(col)[..dim],
            &col_slice(&self.x)[..dim],
            &self.basis[..dim],
        );
        // (artificial rows, below, keep the whole column's scale)
        let ptol_all = self.noise * colmax;
        // artificial variables are fixed at zero: any move blocks them;
        // in the same pass as the z/w rows' largest entry (each the same
        // fold in the same order as a pass of its own)
        let mut compmax = T::zero();
        let mut art: Option<usize> = None;
        for (r, (&c, v)) in cs.iter().zip(basis).enumerate() {
            match v {
                Var::W(_) | Var::Z(_) => compmax = compmax.max(c.abs()),
                Var::Artificial(_)
                    if c.abs() > ptol_all && art.is_none_or(|a| c.abs() > cs[a].abs()) =>
                {
                    art = Some(r);
                }
                _ => {}
            }
        }
        // the pivot tolerance of the candidates is relative to the entries of
        // the sign-constrained rows (z, w): a basic L's entry is the rate of
        // the parameter and a free variable's is in its own units; where they
        // are large per unit of the driver (L at 1e9, u at 8e4 in the stiffest
        // frame, issue 14 defect 5) they made an accurate entry of 1e-3 at the
        // blocking row look like rounding, and the path ran past the event
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
        if let Some(r) = art {
            return Some((r, T::zero()));
        }
        let xnorm = self.xscale();
        let mut best: Option<T> = None;
        // the candidates (rows and ratios), recomputed in the tie pass
        // rather than collected: no allocation unless several rows tie
        let candidate = |r: usize, c: T, v: Var| is_comp(v) && c > ptol && !excluded.contains(&r);
        let mut first_cand = None;
        for (r, ((&c, &x), &v)) in cs.iter().zip(xs).zip(basis).enumerate() {
            if candidate(r, c, v) {
                let ratio = x.max(T::zero()) / c;
                first_cand.get_or_insert(r);
                best = Some(best.map_or(ratio, |b| b.min(ratio)));
            }
        }
        // a row whose entry is below the tolerance may still block first
        // (issue 14): read again where the data are exact as given, before
        // the first regular block or, where none blocks, before the end of
        // the trace (`cap`, L_max). On a ray with no end the trace reads
        // them with a floor instead (`read_ray_end`): with no step bound,
        // refined entries near the wide type's own resolution would turn
        // the ray into a block far along it (a random system (9) read one
        // at L = 2.9e31, 1.6e-30 against a bound of 7.5e-31, where the same
        // basis's ray is certified exactly)
        if self.settings.near_ties == crate::settings::NearTies::Refine {
            if let Some(bound) = best.or(cap) {
                if let Some(block) = self.read_small_entries(col, v, ptol, Some(bound), excluded) {
                    return Some(block);
                }
            }
        }
        let tmin = best?;
        let tied_at = |r: usize, c: T, x: T, v: Var| {
            candidate(r, c, v) && {
                let t = x.max(T::zero()) / c;
                t - tmin <= self.tie_tol * (tmin.abs() + xnorm / c)
            }
        };
        let is_tied = |r: usize| tied_at(r, cs[r], xs[r], basis[r]);
        let (mut n_tied, mut first) = (0usize, None);
        for (r, ((&c, &x), &v)) in cs.iter().zip(xs).zip(basis).enumerate() {
            if tied_at(r, c, x, v) {
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
        // the tie window is wide (it absorbs the rounding of values that may
        // have lost digits): the rows are read again with refined values,
        // and those the refinement separates leave in their exact order
        if self.settings.near_ties == crate::settings::NearTies::Refine {
            match self.read_near_tie(v, col, &tied, xnorm, colmax) {
                NearTie::Separated(r, theta) => return Some((r, theta)),
                NearTie::Tied(rows) => tied = rows,
            }
        }
        if tied.len() > 1 {
            // lexicographic rule (crate::basis::lex)
            tied = crate::basis::lex::break_tie(
                &*self.factor,
                col,
                tied,
                self.p,
                self.dim,
                self.tie_tol,
                self.noise,
            );
        }
        let r = *tied.first().unwrap_or(&first_cand.expect("a candidate"));
        let theta = self.x[r].max(T::zero()) / col[r];
        Some((r, theta))
    }

    /// Rows `tied` of the minimum-ratio test (within the tie tolerance) read
    /// again with refined values and column entries ([`Self::refined_ratios`],
    /// each ratio with an error bound; issue 14: the block
    /// `[[1, 1], [1, 1 + 2^-46]]` has two breakpoints `1.4e-14` apart, well
    /// inside f64's tie window, and the lexicographic rule took the later one
    /// first: a wrong path that nothing flagged).
    ///
    /// * The smallest ratio separated from every other beyond both bounds:
    ///   its row leaves (the exact order), at the refined step.
    /// * Else the rows within the bounds of the smallest are a tie for the
    ///   lexicographic rule when the bound, as a step of `L`, is within
    ///   [`crate::tolerance::TIE_RESOLUTION_EPS`] roundings of `L` (the
    ///   precision cannot tell the breakpoints apart);
    /// * a larger bound leaves the order undecided: counted, and the trace
    ///   stops `ill_conditioned` naming the rows and the gap (`tie_alarm`).
    fn read_near_tie(
        &self,
        v: Var,
        col: &Col<T>,
        tied: &[usize],
        xnorm: T,
        colmax: T,
    ) -> NearTie<T> {
        let reads = self.refined_ratios(v, col, tied);
        let decided = |k: usize| reads[k].err.is_finite();
        let mut best: Option<usize> = None;
        for k in 0..reads.len() {
            if decided(k) && best.is_none_or(|b| reads[k].ratio < reads[b].ratio) {
                best = Some(k);
            }
        }
        let (resolved, unresolved) = self.near_ties.get();
        let (keep, tb, eb) = match best {
            Some(b) => {
                let (tb, eb) = (reads[b].ratio, reads[b].err);
                let keep: Vec<usize> = (0..reads.len())
                    .filter(|&k| {
                        k == b || !decided(k) || (reads[k].ratio - tb).to_f64() - reads[k].err <= eb
                    })
                    .collect();
                if keep.len() == 1 {
                    self.near_ties.set((resolved + 1, unresolved));
                    // the refined step (the working value of a row that
                    // lost digits can be off by a factor, e.g. 2^-43 read
                    // as 2^-42); the values are recomputed after the pivot
                    let r = tied[b];
                    // (on a sparse LU by one solve with the updated
                    // factor unless the pivot entry is small: a sparse
                    // refactorisation after every separated tie made a
                    // grid with symmetric contacts eight times slower)
                    let small = col[r].abs() <= T::eps().sqrt() * colmax;
                    let sparse_lu =
                        matches!(self.settings.basis, crate::settings::BasisKind::Sparse);
                    if small || !sparse_lu {
                        self.refactor_after.set(true);
                    } else {
                        self.values_after.set(true);
                    }
                    return NearTie::Separated(r, T::narrow(tb).max(T::zero()));
                }
                (keep, tb.to_f64(), eb)
            }
            // nothing could be read again (the basis is too ill-conditioned
            // for one refinement step): the tie window's verdict stands, as
            // before the reading (the condition guards of the trace see it)
            None => return NearTie::Tied(tied.to_vec()),
        };
        let emax = keep.iter().fold(eb, |a, &k| a.max(reads[k].err));
        let first = tied[best.unwrap_or(0)];
        let tau = self.tie_resolution(col, tb, first, xnorm);
        let rows: Vec<usize> = keep.iter().map(|&k| tied[k]).collect();
        if emax <= tau {
            return NearTie::Tied(rows);
        }
        self.near_ties.set((resolved, unresolved + 1));
        let mut alarm = self.tie_alarm.borrow_mut();
        if alarm.is_none() {
            let names: Vec<String> = keep
                .iter()
                .map(|&k| {
                    format!(
                        "{} (step {:e} +- {:.1e})",
                        self.basis[tied[k]],
                        reads[k].ratio.to_f64(),
                        reads[k].err
                    )
                })
                .collect();
            let gap = keep
                .iter()
                .fold(0.0f64, |a, &k| a.max((reads[k].ratio.to_f64() - tb).abs()));
            *alarm = Some(format!(
                "near tie at L = {:e}: {} reach zero within the error bounds of their refined ratios (gap {gap:.2e}, bound {emax:.2e}, above {} roundings of L) in {} (condition estimate at the last refactorisation {:.1e}): which leaves first is not decided in this precision; the path is not continued; use a higher precision or exact arithmetic",
                self.lambda.to_f64(),
                names.join(", "),
                crate::tolerance::TIE_RESOLUTION_EPS,
                T::NAME,
                self.cond
            ));
        }
        NearTie::Tied(rows)
    }

    /// The error bound (as a step of the entering variable) under which two
    /// refined ratios near `tb` are one event for the working precision:
    /// [`crate::tolerance::TIE_RESOLUTION_EPS`] roundings of `L` over the
    /// rate of `L`, or, where `L` does not move, of the step and
    /// `max(1, |x|) / |col_first|`.
    fn tie_resolution(&self, col: &Col<T>, tb: f64, first: usize, xnorm: T) -> f64 {
        let k_eps = crate::tolerance::TIE_RESOLUTION_EPS * T::eps().to_f64();
        let rate = match self.row_of(Var::Lambda) {
            None => 1.0,
            Some(l) => col[l].to_f64().abs(),
        };
        let colmax = col_max_abs(col).to_f64();
        if rate > self.noise.to_f64() * colmax.max(1.0) {
            let lam = self.lambda.to_f64();
            k_eps * 1f64.max(lam.abs()).max((lam + tb * rate).abs()) / rate
        } else {
            k_eps * (tb.abs() + xnorm.to_f64().max(1.0) / col[first].to_f64().abs())
        }
    }

    /// Rows whose entry of the entering column is positive but at or below
    /// the pivot tolerance `ptol` (no candidates of the ratio test) and whose
    /// ratio would block before `bound` (the first regular block, or the
    /// end of the trace), read again with the refined column
    /// ([`Self::refined_ratios`]; issue 14: in the block
    /// `[[1, 1], [1, 1 + 2^-46]]` with `z_1` basic, the slack
    /// `w_2 = 2^-46 (s + 1 - L)` falls at the rate `2^-46`, below the noise
    /// of a column of one, and f64 ran past its zero: `reached` on a wrong
    /// path). An entry the refinement separates from zero beyond its error
    /// bound, whose ratio stays below `bound` beyond its error bound, is the
    /// block; the basis is then refactorised after the pivot (its update on
    /// an entry that small is not trusted), which also estimates its
    /// condition afresh. An entry within its bound is rounding, as before.
    /// At most [`crate::tolerance::SMALL_ENTRY_READS`] rows (the smallest
    /// ratios) are read; nothing is read, and nothing allocated, where no
    /// row qualifies.
    ///
    /// `bound` `None`: a ray with no end ([`Self::read_ray_end`]). No step
    /// bounds the reading there, so the entry itself must stand above a
    /// floor that does not grow with `L`: a few roundings of the working
    /// column ([`crate::tolerance::RAY_ENTRY_EPS`] `eps |col|_max`), in the
    /// working entry (which rows are read) and in the refined one (which
    /// block). Below that a refined zero can survive its bound, a
    /// first-order estimate (a random system (9) read `1.6e-30` against a bound of
    /// `7.5e-31` at `L = 2.9e31`, where the same basis's ray is certified
    /// exactly); above it the working precision holds the rate to a few
    /// digits, and f32 lost a real event at `L = 108.8` (`z6` falling at
    /// `3.1e-4` against rates up to `0.475`, `scale_invariance.rs`).
    fn read_small_entries(
        &self,
        col: &Col<T>,
        v: Var,
        ptol: T,
        bound: Option<T>,
        excluded: &[usize],
    ) -> Option<(usize, T)> {
        // a row can block before `bound` with an entry at most `ptol` only if
        // its value is below `bound * ptol`; its working entry may be any
        // rounding of a small one, zero or negative included (after a
        // refactorisation the block's `2^-46` came out as an exact zero)
        // (and the working value itself may be a rounding of a small one:
        // the pivot noise of the values' scale on top)
        let floor = match bound {
            Some(_) => T::zero(),
            None => T::from_f64(crate::tolerance::RAY_ENTRY_EPS) * T::eps() * col_max_abs(col),
        };
        let reach = bound.map(|b| b * ptol + self.noise * self.xscale());
        let qualifies = |r: usize| {
            let c = col[r];
            let candidate = is_comp(self.basis[r]) && !excluded.contains(&r);
            let x = self.x[r].max(T::zero());
            match reach {
                Some(reach) => (candidate && c.abs() <= ptol && self.x[r] <= reach).then_some(x),
                // (on a ray every entry is below the tolerance or was read
                // as rounding by the ratio test) the working ratio, for
                // the order of the reads
                None => (candidate && c > floor && x.is_finite()).then(|| x / c),
            }
        };
        if !(0..self.dim).any(|r| qualifies(r).is_some()) {
            return None;
        }
        let mut rows: Vec<(T, usize)> = (0..self.dim)
            .filter_map(|r| qualifies(r).map(|t| (t, r)))
            .collect();
        rows.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(core::cmp::Ordering::Equal));
        rows.truncate(crate::tolerance::SMALL_ENTRY_READS);
        let rows: Vec<usize> = rows.into_iter().map(|(_, r)| r).collect();
        let reads = self.refined_ratios(v, col, &rows);
        let (bound, floor) = (bound.map_or(f64::INFINITY, |b| b.to_f64()), floor.to_f64());
        let mut best: Option<(usize, T::Wide, f64)> = None;
        for (k, read) in reads.iter().enumerate() {
            // (an infinite bound: the entry is not separated from zero)
            if !read.err.is_finite() || read.entry <= floor {
                continue;
            }
            // (a refined step of zero is a block too: after the exact tie
            // of near_ties.rs at L = 2.5 the slack w = 2^-43 (2.5 - L)
            // stays basic at -2.5e-29 on an entry of 4.5e-13, step 0 +-
            // 1.4e-16, and runs negative if it is not taken)
            let t = read.ratio.to_f64();
            if t + read.err >= bound || !T::narrow(read.ratio).is_finite() {
                continue;
            }
            if best.is_none_or(|(_, b, _)| read.ratio < b) {
                best = Some((rows[k], read.ratio, read.err));
            }
        }
        let (resolved, unresolved) = self.near_ties.get();
        let (r, ratio, err) = best?;
        // small entries within each other's bounds: one event where the
        // bounds are within the precision's resolution of L (the row with
        // the largest working entry pivots), else which leaves first is not
        // decided in this precision (counted; the trace stops)
        let rivals: Vec<usize> = (0..reads.len())
            .filter(|&k| {
                let read = &reads[k];
                rows[k] != r
                    && read.err.is_finite()
                    && read.entry > floor
                    && (read.ratio - ratio).to_f64() - read.err <= err
            })
            .collect();
        let mut r = r;
        if let Some(&k) = rivals.first() {
            let emax = rivals.iter().fold(err, |a, &k| a.max(reads[k].err));
            let tau = self.tie_resolution(col, ratio.to_f64(), r, self.xscale());
            if emax <= tau {
                for &k in &rivals {
                    if col[rows[k]] > col[r] {
                        r = rows[k];
                    }
                }
            } else {
                let read = &reads[k];
                self.near_ties.set((resolved, unresolved + 1));
                let mut alarm = self.tie_alarm.borrow_mut();
                if alarm.is_none() {
                    *alarm = Some(format!(
                        "near tie at L = {:e}: {} (step {:e} +- {:.1e}) and {} (step {:e} +- {:.1e}) block within the error bounds of their refined ratios, on column entries below the pivot tolerance, in {}: which leaves first is not decided in this precision; the path is not continued; use a higher precision or exact arithmetic",
                        self.lambda.to_f64(),
                        self.basis[r],
                        ratio.to_f64(),
                        err,
                        self.basis[rows[k]],
                        read.ratio.to_f64(),
                        read.err,
                        T::NAME
                    ));
                }
                return None;
            }
        }
        self.near_ties.set((resolved + 1, unresolved));
        self.refactor_after.set(true);
        Some((r, T::narrow(ratio).max(T::zero())))
    }

    /// Where the ratio test found no block and `L` rises with no end
    /// (`lambda_max` none): the positive entries of the entering column
    /// `col` of `v` read again before the trace claims an unbounded ray
    /// ([`Self::read_small_entries`] with no step bound). `Some`: the row
    /// that blocks after all, at its refined step. Only with
    /// [`crate::settings::NearTies::Refine`]; once per ray, and nothing is
    /// read where no entry stands above the floor.
    pub(super) fn read_ray_end(&self, col: &Col<T>, v: Var) -> Option<(usize, T)> {
        if self.settings.near_ties != crate::settings::NearTies::Refine {
            return None;
        }
        // (no tolerance: every entry of the right sign above the floor)
        self.read_small_entries(col, v, T::zero(), None, &[])
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
        self.cond_stale = true;
        let updated = self
            .factor
            .replace(self.m, &self.d, self.p, r, leaving, entering, col);
        if !updated {
            // the update does not apply (e.g. a row covered twice): rebuild, which
            // reports a singular basis if that is what it is
            self.refactor()?;
        }
        self.x[r] = value;
        if self.refactor_after.take() {
            // (a pivot on an entry below the noise: read_small_entries)
            self.refactor()?;
        } else if self.values_after.take() {
            // (a separated near tie on a sparse basis: read_near_tie)
            self.values_from_factor();
        }
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
