//! The trace: phase 2 follows the path from a complementary basis feasible at
//! the start value while `L` rises (or falls, past a turning point), one
//! segment per basis, until `lambda_max`, a ray, or a status.
//!
//! `trace_steps` is one loop of about 165 lines, over the 150 the house style
//! asks for: the driver, its column, the owed residual and the direction of `L`
//! live in locals that every part of a step (ratio test, recording, the long
//! form's moves) reads and updates; cut further apart, each piece would take
//! most of them as arguments, and the order of their updates is the algorithm.
//! The entering column, its refinement and the owed breakpoint residual are
//! `entering_column`.

use super::*;

impl<'a, T: Scalar> Engine<'a, T> {
    /// Follows the path from the current basis (`L` nonbasic, driving) until
    /// `lambda_end`, a ray, or a limit.
    pub(crate) fn trace(
        &mut self,
        lambda_end: Option<T>,
        mut rec: Option<&mut Recorder<T>>,
    ) -> TraceEnd<T> {
        let end = self.trace_steps(lambda_end, rec.as_deref_mut());
        if self.residual_owed {
            // only a pivot limit ends the trace between a breakpoint and the next
            // column: the values are still those of the breakpoint
            self.residual_owed = false;
            let bx = apply(self.m, &self.d, self.p, &self.basis, &self.x);
            let res = self.residual_of(&bx);
            if let Some(b) = rec.and_then(|r| r.breakpoints.last_mut()) {
                b.residual = res;
            }
        }
        end
    }

    pub(super) fn trace_steps(
        &mut self,
        lambda_end: Option<T>,
        mut rec: Option<&mut Recorder<T>>,
    ) -> TraceEnd<T> {
        let mut driver = Var::Lambda;
        if self.row_of(Var::Lambda).is_some() {
            return TraceEnd::Stalled("internal: trace must start with L nonbasic".into());
        }
        self.cycle.start(self.basis_fingerprint());
        // a column solved ahead for the first step (`retarget`), if any
        let mut held = self.col_of.take();
        loop {
            if self.pivots >= self.max_pivots || crate::observe::stop_requested() {
                return TraceEnd::PivotLimit;
            }
            if let Some(k) = self.cycle.visit(self.pivots) {
                return TraceEnd::IllConditioned(self.cycle_message(k));
            }
            // the entering column refined inside its solve, where the basis can
            // (the block basis refines on S alone: no extra pass over the matrix)
            // the entering column, in the engine's buffer (put back at the
            // end of the step)
            let mut col = Self::take_buf(&mut self.col_buf);
            let ahead = held.take() == Some((driver, self.pivots, self.refactorisations))
                && !self.residual_owed
                && col.nrows() == self.dim;
            if !ahead {
                if let Err(msg) = self.entering_column(driver, rec.as_deref_mut(), &mut col) {
                    return TraceEnd::IllConditioned(msg);
                }
            }
            let colmax = col_max_abs(&col);
            let rate = match driver {
                Var::Lambda => T::one(),
                _ => match self.row_of(Var::Lambda) {
                    Some(l) => -col[l],
                    None => T::zero(),
                },
            };
            // (L driving itself has rate one; a column whose noise level reaches
            // that (f32 at condition ~1e5) is not trusted to rise either: its
            // ratio test could not see a block, so it ends as a stop)
            let rate_tol = self.noise * colmax.max(T::one());
            let mut rising = rate > rate_tol;
            let mut moving = rate.abs() > rate_tol;
            // a small rate must also stand above its entry's componentwise
            // rounding (the pivots' test, ratio.rs): a skew 4 x 4 problem
            // had an exact zero computed as 7.8e-14 against a tolerance of
            // 7.6e-14, and f64 claimed a ray on a singular basis
            if moving && driver != Var::Lambda && rate.abs() <= T::eps().sqrt() * colmax {
                if let Some(l) = self.row_of(Var::Lambda) {
                    if rate.abs() <= self.pivot_tol * self.entry_rounding(l, &col) {
                        rising = false;
                        moving = false;
                    }
                }
            }
            if !col_slice(&col)
                .iter()
                .zip(col_slice(&self.x))
                .all(|(c, x)| c.is_finite() && x.is_finite())
            {
                return TraceEnd::IllConditioned(format!(
                    "non-finite values at L = {:e} (overflow in the working precision {})",
                    self.lambda.to_f64(),
                    T::NAME
                ));
            }
            // the step at which L reaches its end (small entries are read
            // for a block before it, ratio.rs)
            let cap = match (rising, lambda_end) {
                (true, Some(end)) => Some(((end - self.lambda) / rate).max(T::zero())),
                _ => None,
            };
            let block = self.ratio_test(&col, driver, cap);
            if let Some(msg) = self.tie_alarm.take() {
                // a near tie the precision cannot order (ratio.rs)
                self.col_buf = col;
                return TraceEnd::IllConditioned(msg);
            }
            if let (true, Some(end)) = (rising, lambda_end) {
                let theta_end = (end - self.lambda) / rate;
                // a block at the end value (within the tie tolerance relative to
                // the end value: no floor, the start phase's end may be tiny) is
                // a tie, and ties go to the end: the start phase's artificial
                // leaves, L_max is reached
                let end_tol = self.tie_tol * end.abs().max(self.lambda.abs());
                if block.as_ref().is_none_or(|(_, tb)| {
                    theta_end <= *tb || end - (self.lambda + *tb * rate) <= end_tol
                }) {
                    let theta_end = theta_end.max(T::zero());
                    if let Some(rec) = rec.as_deref_mut() {
                        if theta_end > T::zero() {
                            self.note_direction(rec, 1);
                            self.record_segment(rec, driver, &col, rate, end, false);
                        }
                    }
                    for (x, &c) in col_slice_mut(&mut self.x).iter_mut().zip(col_slice(&col)) {
                        let v = *x - theta_end * c;
                        *x = v;
                    }
                    self.lambda = end;
                    if let Some(l) = self.row_of(Var::Lambda) {
                        self.x[l] = end;
                    }
                    self.col_buf = col;
                    // the driver's column on this basis, for `settle`
                    self.col_of = Some((driver, self.pivots, self.refactorisations));
                    return TraceEnd::Reached {
                        driver,
                        theta: theta_end,
                    };
                }
            }
            // no block while L rises with no end: the small entries are read
            // again before a ray is claimed (ratio.rs; f32 claimed one
            // segment early, on a rate of 3.1e-4 in a column of 0.475)
            let block = match block {
                None if rising => {
                    let read = self.read_ray_end(&col, driver);
                    if let Some(msg) = self.tie_alarm.take() {
                        self.col_buf = col;
                        return TraceEnd::IllConditioned(msg);
                    }
                    read
                }
                b => b,
            };
            let Some((r, theta)) = block else {
                if rising {
                    if let Some(rec) = rec.as_deref_mut() {
                        self.note_direction(rec, 1);
                        self.record_segment(
                            rec,
                            driver,
                            &col,
                            rate,
                            crate::scalar::infinity(),
                            true,
                        );
                    }
                    return TraceEnd::UnboundedRay { driver, col, rate };
                }
                // not rising is a claim that the rate of L is zero or less:
                // a positive rate that is not small against its column (the
                // small-rate test above, sqrt(eps) max|col|) and still below
                // the basis's noise means the noise exceeds sqrt(eps) of the
                // column, and the precision cannot tell a rising ray from a
                // secondary one (f32 at condition ~7e4: a rate of 1.39e4, the
                // column's largest entry, against a tolerance of 1.47e4)
                if rate > T::eps().sqrt() * colmax {
                    self.col_buf = col;
                    return TraceEnd::IllConditioned(format!(
                        "no block at L = {:e} and a rate of L of {:e}, not small against \
                         its column ({:e}) but below the basis's noise {:e}: {} cannot \
                         tell an unbounded ray from a secondary ray",
                        self.lambda.to_f64(),
                        rate.to_f64(),
                        colmax.to_f64(),
                        rate_tol.to_f64(),
                        T::NAME
                    ));
                }
                return TraceEnd::SecondaryRay { driver, col, rate };
            };
            // the step; L is the path's independent variable, kept exactly as the
            // segments record it (a drift of the basic L would open gaps)
            // a change of L at the rounding level is no change (ties within the
            // tie tolerance are ties): it would fake turning points
            let dl = theta * rate;
            let moving = moving && dl.abs() > self.tie_tol * self.lambda.abs().max(T::one());
            let lambda_to = if moving {
                self.lambda + dl
            } else {
                self.lambda
            };
            if let Some(rec) = rec.as_deref_mut() {
                if moving && theta > T::zero() {
                    let sign = if rate > T::zero() { 1 } else { -1 };
                    self.note_direction(rec, sign);
                    self.record_segment(rec, driver, &col, rate, lambda_to, false);
                }
            }
            for (x, &c) in col_slice_mut(&mut self.x).iter_mut().zip(col_slice(&col)) {
                let v = *x - theta * c;
                *x = v;
            }
            self.lambda = lambda_to;
            if let Some(l) = self.row_of(Var::Lambda) {
                self.x[l] = lambda_to;
            }
            let degenerate = theta == T::zero() || !moving;
            if theta == T::zero() {
                self.degenerate_pivots += 1;
            }
            let leaving = self.basis[r];
            // the entering variable's value: the step length, or for L its level
            let value = if driver == Var::Lambda {
                self.lambda
            } else {
                theta
            };
            if let Err(msg) = self.pivot(r, driver, &col, value) {
                return TraceEnd::IllConditioned(msg);
            }
            self.cycle
                .pivot(self.var_index(leaving), self.var_index(driver));
            match leaving {
                Var::W(_) | Var::Z(_) => {
                    let next = leaving.complement().expect("complementary");
                    if let Some(rec) = rec.as_deref_mut() {
                        rec.breakpoints.push(Breakpoint {
                            lambda: self.lambda,
                            entering: next,
                            leaving,
                            degenerate,
                            turning: false,
                            segment: rec.segments.len(),
                            residual: Residual::default(),
                        });
                        self.residual_owed = true;
                    }
                    driver = next;
                }
                Var::Artificial(_) => match self.unlock_lambda() {
                    Ok(true) => {
                        // (its pivots are not seen by the guard's updates)
                        self.cycle.rekey(self.basis_fingerprint());
                        driver = Var::Lambda;
                    }
                    Ok(false) => {
                        return TraceEnd::Stalled(format!(
                            "at L = {:e} an equality row blocks the path and no free variable can take over: the path cannot be continued",
                            self.lambda.to_f64()
                        ))
                    }
                    Err(msg) => return TraceEnd::IllConditioned(msg),
                },
                Var::U(_) | Var::Lambda => {
                    return TraceEnd::Stalled("internal: a free variable blocked".into())
                }
            }
            self.col_buf = col;
        }
    }

    /// The entering column of `driver` into `col`, refined as the settings
    /// ask; where a breakpoint's residual is owed (`rec`), the values are
    /// refined in the same pass and the residual recorded. `Err`: the
    /// breakpoint's residual is above the guard (the path is not continued).
    fn entering_column(
        &mut self,
        driver: Var,
        rec: Option<&mut Recorder<T>>,
        col: &mut Col<T>,
    ) -> Result<(), String> {
        let refine_here = self.refine_columns && self.refine_inside;
        if refine_here {
            self.factor.set_refine(true);
        }
        // the entering column's wide residual, when a pass for the values computed it
        // and its correction (solved with the values' first correction)
        let mut col_correction: Option<Col<T>> = None;
        match rec {
            Some(rec) if self.residual_owed => {
                let res = if self.refine_wide {
                    // the wide residuals recompute B x: no working-precision
                    // product; the first residual of the values and the
                    // entering column's share one pass over the basic columns
                    self.column_into(driver, col);
                    if refine_here {
                        self.factor.set_refine(false);
                    }
                    let first = if self.refine_inside {
                        None
                    } else {
                        // the two corrections are independent: one sweep
                        // over the factors for both
                        let (values, column) = self.wide_residual_pair(&self.x, driver, col);
                        let (dx, dc) = self.factor.solve2(values, column);
                        col_correction = Some(dc);
                        Some(dx)
                    };
                    self.refine_values_wide(first)
                } else {
                    let mut a = Self::take_buf(&mut self.a_buf);
                    let mut bx = Self::take_buf(&mut self.bx_buf);
                    var_column_into(self.m, &self.d, self.p, driver, &mut a);
                    self.factor.solve_and_apply_into(
                        self.m,
                        &self.d,
                        self.p,
                        &self.basis,
                        &a,
                        &self.x,
                        col,
                        &mut bx,
                    );
                    self.a_buf = a;
                    if refine_here {
                        self.factor.set_refine(false);
                    }
                    let res = self.refine_values(&mut bx);
                    self.bx_buf = bx;
                    res
                };
                if let Some(b) = rec.breakpoints.last_mut() {
                    b.residual = res;
                }
                self.residual_owed = false;
                // the residual guard of `crate::solve`, applied where the
                // evidence appears: a path that continued from a breakpoint
                // whose values fail their equations (drift beyond what
                // refinement repairs) could end in a wrong secondary ray,
                // which that guard does not downgrade
                let limit = T::eps().to_f64().sqrt();
                let worst = res.worst();
                if worst.is_nan() || worst > limit {
                    return Err(format!(
                        "the basic solution at the breakpoint L = {:e} has residual {worst:.3e} (equation {:.1e}, feasibility {:.1e}, complementarity {:.1e}) above sqrt(eps) = {limit:.1e} in {} after refinement (basis condition estimate up to {:.1e}): the path is not continued; use a higher precision",
                        self.lambda.to_f64(),
                        res.equation,
                        res.feasibility,
                        res.complementarity,
                        T::NAME,
                        self.max_cond
                    ));
                }
            }
            _ => self.column_into(driver, col),
        }
        if refine_here {
            self.factor.set_refine(false);
        }
        if self.refine_columns {
            if self.refine_inside {
                // refined inside the solve above (unless the basis found
                // its refinement idle, see tolerance::REFINE_IDLE_EPS)
                self.refinements += usize::from(self.factor.last_solve_refined());
            } else {
                self.refine_column(driver, col, col_correction.take());
            }
        }
        Ok(())
    }

    /// The fingerprint of the current basis ([`super::cycle`]).
    fn basis_fingerprint(&self) -> u128 {
        cycle::CycleGuard::fingerprint(self.basis.iter().map(|&v| self.var_index(v)))
    }

    /// The status message of a basis that came back ([`super::cycle`]).
    fn cycle_message(&self, first: usize) -> String {
        format!(
            "at L = {:e} the basis of pivot {first} came back at pivot {}: the path is a closed loop (a singular M can make one; exact arithmetic reports it as secondary_ray) or cycles in the rounding of {} (its steps below the rounding of its values; basis condition estimate up to {:.1e}); the path is not continued; a higher precision or exact arithmetic tells which",
            self.lambda.to_f64(),
            self.pivots,
            T::NAME,
            self.max_cond
        )
    }

    pub(super) fn note_direction(&self, rec: &mut Recorder<T>, sign: i8) {
        if rec.last_sign > 0 && sign < 0 {
            rec.turning_points += 1;
            if let Some(b) = rec.breakpoints.last_mut() {
                b.turning = true;
            }
        }
        rec.last_sign = sign;
    }

    /// After a phase ended with `driver` at `theta` and `L` basic: make the basis
    /// complementary again by pivoting the driver in for `L` (which becomes nonbasic
    /// at its current value). The driver's column is the one the trace
    /// ended with when it is still at hand (`col_of`: the same basis, and
    /// refined as the trace refines entering columns), else solved for.
    pub(crate) fn settle(&mut self, driver: Var, theta: T) -> Result<(), String> {
        if driver == Var::Lambda {
            return Ok(());
        }
        let Some(l) = self.row_of(Var::Lambda) else {
            return Ok(());
        };
        let mut col = Self::take_buf(&mut self.col_buf);
        let held = Some((driver, self.pivots, self.refactorisations));
        if self.col_of.take() != held || col.nrows() != self.dim {
            self.column_into(driver, &mut col);
        }
        let done = self.pivot(l, driver, &col, theta);
        self.col_buf = col;
        done
    }
}
