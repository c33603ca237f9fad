//! The moves only Wolfe's long form makes: free variables (`u`) placed in
//! degenerate rows, `L` unlocked from the basis by a free variable, and the
//! vertical move of a free variable where no complementary one can replace `L`.

use super::*;

impl<'a, T: Scalar> Engine<'a, T> {
    /// After an artificial left the basis: bring a free variable in for `L`, so that
    /// `L` can drive again. Returns false if none can.
    pub(super) fn free_for_lambda(&mut self) -> Result<bool, String> {
        let Some(l) = self.row_of(Var::Lambda) else {
            return Ok(true);
        };
        let mut best: Option<(usize, Col<T>)> = None;
        for j in 0..self.p {
            if self.row_of(Var::U(j)).is_some() {
                continue;
            }
            let col = self.column(Var::U(j));
            let colmax = col_max_abs(&col);
            if col[l].abs() > self.noise * colmax
                && best.as_ref().is_none_or(|(_, c)| col[l].abs() > c[l].abs())
            {
                best = Some((j, col));
            }
        }
        match best {
            Some((j, col)) => {
                // L leaves at its current value (now nonbasic); u_j enters at zero.
                self.pivot(l, Var::U(j), &col, T::zero())?;
                Ok(true)
            }
            None => Ok(false),
        }
    }

    /// After the driver took an equality row (an artificial variable left), `L` is
    /// basic and something must take its place so that `L` can drive again: a
    /// nonbasic free variable (a redundant member force, say); else an admissible
    /// complementary variable (its complement nonbasic: a section at yield that
    /// may flow); else first free a complementary variable by moving a free one
    /// (a zero-length step) and try again. Returns false if nothing can.
    pub(super) fn unlock_lambda(&mut self) -> Result<bool, String> {
        for _ in 0..=self.p + 1 {
            if self.free_for_lambda()? {
                return Ok(true);
            }
            let Some(l) = self.row_of(Var::Lambda) else {
                return Ok(true);
            };
            let mut e = Col::<T>::zeros(self.dim);
            e[l] = T::one();
            let rho = self.factor.solve_transpose(&e);
            let mut best: Option<(Var, T)> = None;
            for i in 0..self.n {
                for v in [Var::Z(i), Var::W(i)] {
                    if !self.admissible(v, Var::Lambda) {
                        continue;
                    }
                    let a = var_column(self.m, &self.d, self.p, v);
                    let mut dot = T::zero();
                    let mut anorm = T::one();
                    for k in 0..self.dim {
                        dot += rho[k] * a[k];
                        anorm = anorm.max(a[k].abs());
                    }
                    let score = dot.abs() / anorm;
                    if dot.abs() > self.noise * anorm && best.is_none_or(|(_, s)| score > s) {
                        best = Some((v, score));
                    }
                }
            }
            if let Some((v, _)) = best {
                let y = self.column(v);
                let ymax = col_max_abs(&y);
                if y[l].abs() > self.noise * ymax {
                    // L leaves at its current value; v enters at zero
                    self.degenerate_pivots += 1;
                    self.pivot(l, v, &y, T::zero())?;
                    return Ok(true);
                }
            }
            if self.place_free_in_degenerate_rows()? > 0 {
                continue;
            }
            if !self.free_vertical_move(&rho, Var::Lambda)? {
                return Ok(false);
            }
        }
        Ok(false)
    }

    /// When an artificial row (with left vector `rho`) can only be served by a
    /// complementary variable whose complement is basic, move a nonbasic free
    /// variable (the problem's solutions are not unique along it) at fixed `L`
    /// until that complement, or another sign-constrained variable, reaches zero,
    /// and pivot the free variable in. A zero-length step in `L`; finite, since
    /// each such move makes one more free variable basic.
    pub(super) fn free_vertical_move(&mut self, rho: &Col<T>, driver: Var) -> Result<bool, String> {
        for i in 0..self.n {
            for e in [Var::Z(i), Var::W(i)] {
                if e == driver || self.row_of(e).is_some() {
                    continue;
                }
                let c = e.complement().expect("complementary");
                let Some(rc) = self.row_of(c) else {
                    continue;
                };
                let a = var_column(self.m, &self.d, self.p, e);
                let mut dot = T::zero();
                let mut anorm = T::one();
                for k in 0..self.dim {
                    dot += rho[k] * a[k];
                    anorm = anorm.max(a[k].abs());
                }
                if dot.abs() <= self.noise * anorm {
                    continue;
                }
                for j in 0..self.p {
                    if self.row_of(Var::U(j)).is_some() {
                        continue;
                    }
                    let ytrue = self.column(Var::U(j));
                    let ymax = col_max_abs(&ytrue);
                    let ptol = self.noise * ymax;
                    if ytrue[rc].abs() <= ptol {
                        continue;
                    }
                    // a vertical move keeps L where it is
                    if let Some(l) = self.row_of(Var::Lambda) {
                        if ytrue[l].abs() > ptol {
                            continue;
                        }
                    }
                    let dir = if ytrue[rc] > T::zero() {
                        T::one()
                    } else {
                        -T::one()
                    };
                    let y = Col::from_fn(self.dim, |k| dir * ytrue[k]);
                    // ratio test over sign-constrained variables; artificials must not move
                    let mut best: Option<(usize, T)> = None;
                    let mut art_moves = false;
                    for r in 0..self.dim {
                        match self.basis[r] {
                            Var::Artificial(_) if y[r].abs() > ptol => art_moves = true,
                            Var::W(_) | Var::Z(_) if y[r] > ptol => {
                                let t = self.x[r].max(T::zero()) / y[r];
                                if best.is_none_or(|(br, bt)| {
                                    t < bt || (t == bt && r == rc && br != rc)
                                }) {
                                    best = Some((r, t));
                                }
                            }
                            _ => {}
                        }
                    }
                    if art_moves {
                        continue;
                    }
                    let Some((rb, theta)) = best else {
                        continue;
                    };
                    for k in 0..self.dim {
                        let v = self.x[k] - theta * y[k];
                        self.x[k] = v;
                    }
                    self.degenerate_pivots += 1;
                    self.pivot(rb, Var::U(j), &ytrue, dir * theta)?;
                    return Ok(true);
                }
            }
        }
        Ok(false)
    }

    /// Brings nonbasic free variables into the basis in place of slacks `w_i` that
    /// sit at zero (a swap that leaves the point unchanged). Returns how many.
    pub(crate) fn place_free_in_degenerate_rows(&mut self) -> Result<usize, String> {
        let mut placed = 0;
        let scale = self.xscale();
        for j in 0..self.p {
            if self.row_of(Var::U(j)).is_some() {
                continue;
            }
            let y = self.column(Var::U(j));
            let ymax = col_max_abs(&y);
            let mut best: Option<usize> = None;
            for r in 0..self.dim {
                if matches!(self.basis[r], Var::W(_))
                    && self.x[r].abs() <= self.tie_tol * scale
                    && y[r].abs() > self.noise * ymax
                    && best.is_none_or(|b| y[r].abs() > y[b].abs())
                {
                    best = Some(r);
                }
            }
            if let Some(r) = best {
                self.x[r] = T::zero();
                self.pivot(r, Var::U(j), &y, T::zero())?;
                placed += 1;
            }
        }
        Ok(placed)
    }
}
