//! Mixed-precision refinement: residuals `r = q + L d - B x` accumulated in the
//! scalar's wide type, the refinement of basic values at breakpoints and of
//! entering columns, and the residual recorded with each breakpoint.

use super::*;

/// A residual `r` accumulated in the wide type and rounded once, `B x` as
/// `rhs - r`, and the largest term `max_j abs(B_ij x_j)` of each row.
type WideResidual<T> = (Col<T>, Col<T>, Col<T>);

/// Mixed-precision refinement of basic values stops once the correction is
/// within this many roundings (`eps`) of the largest basic value.
const WIDE_REFINE_EPS: f64 = 4.0;

/// At most this many mixed-precision refinement steps per breakpoint.
const WIDE_REFINE_STEPS: usize = 3;

/// [`Engine::wide_residual_pair`] with fused multiply-add (see there).
struct WidePairFma<'e, 'a, T: Scalar> {
    engine: &'e Engine<'a, T>,
    x: &'e Col<T>,
    v: Var,
    col: &'e Col<T>,
}

impl<T: Scalar> pulp::WithSimd for WidePairFma<'_, '_, T> {
    type Output = (Col<T>, Col<T>);

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> Self::Output {
        self.engine
            .wide_residual_pair_with::<true>(self.x, self.v, self.col)
    }
}

impl<'a, T: Scalar> Engine<'a, T> {
    /// Iterative refinement of the basic values at a breakpoint, on evidence.
    ///
    /// While the basis condition estimate is small (`cond * eps <=
    /// refine_cond_eps`): given `B x`, while the equation residual exceeds
    /// `refine_tol_eps * eps` (at most two steps), `x += B^{-1} (rhs - B x)` in
    /// the working precision. The explicit inverse is not backward stable (its
    /// residuals grow like `cond(B) eps`); one step brings them back to the
    /// order of `eps` whenever `cond(B) eps < 1`.
    ///
    /// Beyond that the residual is computed in the wide type
    /// ([`Scalar::Wide`]) and refinement goes on while the correction exceeds
    /// the rounding of `x` (see [`Self::refine_values_wide`]). Returns the
    /// residuals after refinement.
    pub(super) fn refine_values(&mut self, bx: &mut Col<T>) -> Residual {
        if self.refine_wide {
            return self.refine_values_wide(None);
        }
        let mut res = self.residual_of(bx);
        let tol = self.settings.refine_tol_eps * T::eps().to_f64();
        let l = self.row_of(Var::Lambda);
        for _ in 0..2 {
            if res.equation.is_nan() || res.equation <= tol {
                break;
            }
            let rhs = self.rhs();
            let r = Col::from_fn(self.dim, |i| rhs[i] - bx[i]);
            let dx = self.factor.solve(&r);
            let mut xn = self.x.clone();
            for k in 0..self.dim {
                xn[k] += dx[k];
            }
            if let Some(l) = l {
                // L is the path's parameter: kept exact
                xn[l] = self.lambda;
            }
            let bxn = apply(self.m, &self.d, self.p, &self.basis, &xn);
            let resn = self.residual_of_values(&bxn, &xn);
            self.refinements += 1;
            if resn.equation.is_nan() || resn.equation >= res.equation {
                break;
            }
            self.x = xn;
            *bx = bxn;
            res = resn;
        }
        res
    }

    /// Mixed-precision refinement of the basic values (basis condition
    /// `cond * eps > refine_cond_eps`): `r = rhs - B x` accumulated in
    /// [`Scalar::Wide`], `x += B^{-1} r` with the existing factorisation, while
    /// the correction exceeds `WIDE_REFINE_EPS` roundings of `x` and shrinks (at
    /// most `WIDE_REFINE_STEPS` steps; the last correction is applied even
    /// when small: `4 eps max|x|` can still be large for a row of small terms).
    /// With `cond * eps < 1` this converges to a forward error at the working
    /// precision's level (Higham, *Accuracy and Stability*, ch. 12), where
    /// residuals in the working precision stall at `cond * eps`: a degenerate
    /// basic variable (zero in exact arithmetic) then comes out at `eps`
    /// rather than at `cond * eps`.
    ///
    /// `first`: the first correction `B^{-1} r` of the current values if
    /// already computed (from [`Self::wide_residual_pair`]).
    pub(super) fn refine_values_wide(&mut self, first: Option<Col<T>>) -> Residual {
        let l = self.row_of(Var::Lambda);
        // B x and the row scales of the current values, once measured
        let (mut r, mut measured, mut first_dx) = match first {
            Some(dx) => (None, None, Some(dx)),
            None => {
                let (r, bx, big) = self.wide_residual(&self.x, None);
                (Some(r), Some((bx, big)), None)
            }
        };
        let mut last = f64::INFINITY;
        for step in 0..WIDE_REFINE_STEPS {
            let dx = match first_dx.take() {
                Some(dx) => dx,
                None => self.factor.solve(r.as_ref().expect("a residual")),
            };
            self.refinements += 1;
            // over slices, the row of L (kept exact) cut out: the same
            // entries in the same order as a loop that skips it
            let dim = self.dim;
            let (lo, hi) = match l {
                Some(l) => (l, l + 1),
                None => (dim, dim),
            };
            let (mut dnorm, mut xnorm) = (0.0f64, 0.0f64);
            {
                let (dxs, xs) = (&col_slice(&dx)[..dim], &col_slice(&self.x)[..dim]);
                for range in [0..lo, hi..dim] {
                    for (d, x) in dxs[range.clone()].iter().zip(&xs[range]) {
                        dnorm = dnorm.max(d.to_f64().abs());
                        xnorm = xnorm.max(x.to_f64().abs());
                    }
                }
            }
            if !dnorm.is_finite() || dnorm >= 0.5 * last {
                break;
            }
            {
                let dxs = &col_slice(&dx)[..dim];
                let xs = &mut col_slice_mut(&mut self.x)[..dim];
                for range in [0..lo, hi..dim] {
                    for (x, &d) in xs[range.clone()].iter_mut().zip(&dxs[range]) {
                        *x += d;
                    }
                }
            }
            last = dnorm;
            if dnorm <= WIDE_REFINE_EPS * T::eps().to_f64() * xnorm || step + 1 == WIDE_REFINE_STEPS
            {
                // no further step: the residual is only reported, and the
                // working precision measures it as it measures points
                // (`crate::residual`: within a few roundings of the row's
                // largest term, the scale it is reported against)
                measured = None;
                break;
            }
            let (rn, bx, big) = self.wide_residual(&self.x, None);
            r = Some(rn);
            measured = Some((bx, big));
        }
        match measured {
            // relative to the terms of each row as well (a row whose terms
            // cancel to a small B x keeps the rounding of its largest term)
            Some((bx, big)) => self.residual_of_scaled(&bx, &self.x, Some(&big)),
            None => self.plain_residual_measured(),
        }
    }

    /// `residual_of_scaled` of [`Self::plain_residual_into`] of the current values
    /// without allocating: `B x` and the row scales accumulated in the
    /// engine's buffers (`plain_acc`), the same operations in the same order.
    fn plain_residual_measured(&self) -> Residual {
        let mut scratch = self.plain_acc.borrow_mut();
        let (bx, big) = &mut *scratch;
        self.plain_residual_into(&self.x, bx, big);
        self.residual_of_rows(bx, &self.x, Some(big))
    }

    /// `B x` in the working precision and `max_j abs(B_ij x_j)` per row, in
    /// one pass over the basic columns, into `bx` and `big` (cleared and
    /// zeroed to length `p + n` first).
    fn plain_residual_into(&self, x: &Col<T>, bx: &mut Vec<T>, big: &mut Vec<T>) {
        let dim = self.dim;
        bx.clear();
        bx.resize(dim, T::zero());
        big.clear();
        big.resize(dim, T::zero());
        let (bx, big) = (&mut bx[..], &mut big[..]);
        let (m, p) = (self.m, self.p);
        // the column of a matrix variable is -M[:, j] (of L: -d)
        for (k, b) in self.basis.iter().enumerate() {
            let xk = x[k];
            if xk == T::zero() {
                continue;
            }
            let xa = xk.abs();
            let mut add = |i: usize, a: T| {
                bx[i] -= a * xk;
                big[i] = big[i].max(a.abs() * xa);
            };
            match *b {
                Var::U(j) => m.for_col(j, add),
                Var::Z(j) => m.for_col(p + j, add),
                Var::Lambda => self.d_rows.iter().for_each(|&i| add(i, self.d[i])),
                Var::W(i) => add(p + i, -T::one()),
                Var::Artificial(i) => add(i, -T::one()),
            }
        }
    }

    /// `r = rhs - B x` accumulated in [`Scalar::Wide`] and rounded once,
    /// `B x` as `rhs - r` (so that [`Self::residual_of`] reads the wide
    /// residual), and `max_j abs(B_ij x_j)` per row (the scale of the
    /// cancellation in row `i`: the Oettli-Prager backward error's). `rhs` is
    /// the basic right-hand side (`v = None`) or the column `a_v` of the
    /// entering variable `v` (the residual of `x = B^{-1} a_v`).
    pub(super) fn wide_residual(&self, x: &Col<T>, v: Option<Var>) -> WideResidual<T> {
        let rhs: Col<T> = match v {
            Some(v) => var_column(self.m, &self.d, self.p, v),
            None => self.rhs(),
        };
        let mut acc: Vec<T::Wide> = (0..self.dim).map(|i| rhs[i].widen()).collect();
        let mut big: Col<T> = Col::zeros(self.dim);
        let (m, p) = (self.m, self.p);
        // the column of a matrix variable is -M[:, j] (of L: -d), so r += M x
        for (k, b) in self.basis.iter().enumerate() {
            let xk = x[k];
            if xk == T::zero() {
                continue;
            }
            let xa = xk.abs();
            let mut add = |i: usize, a: T| {
                acc[i] = T::wide_mul_add(acc[i], a, xk);
                big[i] = big[i].max(a.abs() * xa);
            };
            match *b {
                Var::U(j) => m.for_col(j, add),
                Var::Z(j) => m.for_col(p + j, add),
                Var::Lambda => self.d_rows.iter().for_each(|&i| add(i, self.d[i])),
                Var::W(i) => add(p + i, -T::one()),
                Var::Artificial(i) => add(i, -T::one()),
            }
        }
        let r = Col::from_fn(self.dim, |i| T::narrow(acc[i]));
        let bx = Col::from_fn(self.dim, |i| rhs[i] - r[i]);
        (r, bx, big)
    }

    /// The residuals of [`Self::wide_residual`] (`r` alone) of the basic
    /// values `x` and of the entering column `col = B^{-1} a_v` (`a_v - B
    /// col`) in one pass over the basic columns (each accumulator sees the
    /// same operations in the same order as in its own pass: the results are
    /// identical).
    pub(super) fn wide_residual_pair(&self, x: &Col<T>, v: Var, col: &Col<T>) -> (Col<T>, Col<T>) {
        if T::FMA_KERNEL && crate::scalar::fma_detected() {
            // compiled inside pulp's target-feature functions (AVX2 and FMA),
            // where `mul_add` is one instruction: the error-free products by
            // `fma` rather than Veltkamp's splitting (the same numbers, see
            // [`Scalar::wide_mul_add_fma`]); safe runtime dispatch
            return pulp::Arch::new().dispatch(WidePairFma {
                engine: self,
                x,
                v,
                col,
            });
        }
        self.wide_residual_pair_with::<false>(x, v, col)
    }

    #[inline(always)]
    pub(super) fn wide_residual_pair_with<const FMA: bool>(
        &self,
        x: &Col<T>,
        v: Var,
        col: &Col<T>,
    ) -> (Col<T>, Col<T>) {
        let dim = self.dim;
        let (m, p) = (self.m, self.p);
        let mut scratch = self.wide_acc.borrow_mut();
        let (acc, acc_c) = &mut *scratch;
        // the basic right-hand side (Self::rhs) and the column a_v (var_column)
        acc.clear();
        if self.row_of(Var::Lambda).is_some() {
            acc.extend((0..dim).map(|i| self.q[i].widen()));
        } else {
            acc.extend((0..dim).map(|i| (self.q[i] + self.lambda * self.d[i]).widen()));
        }
        acc_c.clear();
        acc_c.resize(dim, T::zero().widen());
        match v {
            Var::U(j) => m.for_col(j, |i, a| acc_c[i] = (-a).widen()),
            Var::Z(j) => m.for_col(p + j, |i, a| acc_c[i] = (-a).widen()),
            Var::W(i) => acc_c[p + i] = T::one().widen(),
            Var::Artificial(k) => acc_c[k] = T::one().widen(),
            Var::Lambda => {
                for (i, c) in acc_c.iter_mut().enumerate() {
                    *c = (-self.d[i]).widen();
                }
            }
        }
        for (k, b) in self.basis.iter().enumerate() {
            let (xk, ck) = (x[k], col[k]);
            let (on_x, on_c) = (xk != T::zero(), ck != T::zero());
            if !on_x && !on_c {
                continue;
            }
            let mut add = |i: usize, a: T| {
                if on_x {
                    acc[i] = if FMA {
                        T::wide_mul_add_fma(acc[i], a, xk)
                    } else {
                        T::wide_mul_add(acc[i], a, xk)
                    };
                }
                if on_c {
                    acc_c[i] = if FMA {
                        T::wide_mul_add_fma(acc_c[i], a, ck)
                    } else {
                        T::wide_mul_add(acc_c[i], a, ck)
                    };
                }
            };
            // (MatrixRef::for_col is always inlined: a kernel compiled with fma must inline the
            // closure, or its products are library calls)
            match *b {
                Var::U(j) => m.for_col(j, add),
                Var::Z(j) => m.for_col(p + j, add),
                Var::Lambda => self.d_rows.iter().for_each(|&i| add(i, self.d[i])),
                Var::W(i) => add(p + i, -T::one()),
                Var::Artificial(i) => add(i, -T::one()),
            }
        }
        let r = Col::from_fn(dim, |i| T::narrow(acc[i]));
        let rc = Col::from_fn(dim, |i| T::narrow(acc_c[i]));
        (r, rc)
    }

    /// One refinement step of an entering column `col = B^{-1} a_v`, when the
    /// basis condition estimate says the factorisation loses digits
    /// (`cond * eps > refine_cond_eps`); its residual `a_v - B col` is
    /// accumulated in [`Scalar::Wide`] beyond
    /// [`crate::tolerance::WIDE_REFINE_COND_EPS`], in the working precision
    /// below.
    /// `correction`: `B^{-1}` of the wide residual `a_v - B col` if already
    /// computed.
    pub(super) fn refine_column(&mut self, v: Var, col: &mut Col<T>, correction: Option<Col<T>>) {
        if let Some(dc) = correction {
            self.apply_column_correction(col, &dc);
            return;
        }
        let r = if self.refine_wide {
            self.wide_residual(col, Some(v)).0
        } else {
            // below the wide threshold the working precision's residual
            // (a pass in plain arithmetic) does as well
            let a = var_column(self.m, &self.d, self.p, v);
            let bc = apply(self.m, &self.d, self.p, &self.basis, col);
            Col::from_fn(self.dim, |i| a[i] - bc[i])
        };
        let dc = self.factor.solve(&r);
        self.apply_column_correction(col, &dc);
    }

    /// `col += dc`, entries at the rounding level of `col` set to zero.
    pub(super) fn apply_column_correction(&mut self, col: &mut Col<T>, dc: &Col<T>) {
        let colmax = col_max_abs(col);
        // the correction spreads rounding noise over every entry: entries below
        // one rounding of the column are zeros (the sparse basis stores the
        // column as an eta, and a dense one would force refactorisations)
        let floor = T::eps() * colmax;
        for k in 0..self.dim {
            let c = col[k] + dc[k];
            col[k] = if c.abs() <= floor { T::zero() } else { c };
        }
        self.refinements += 1;
    }

    /// The residuals of the basic solution from `B x` (see [`Residual`]): the
    /// equation `sum_v a_v v = q` relative to `max(1, |q_r|, |L d_r|, |(B x)_r|)`
    /// per row, which is at least the componentwise (Oettli-Prager) backward
    /// error up to the floor of 1; feasibility and complementarity of the basic
    /// `z`, `w`.
    pub(super) fn residual_of(&self, bx: &Col<T>) -> Residual {
        self.residual_of_values(bx, &self.x)
    }

    pub(super) fn residual_of_values(&self, bx: &Col<T>, x: &Col<T>) -> Residual {
        self.residual_of_scaled(bx, x, None)
    }

    /// [`Self::residual_of_values`], each equation row also relative to
    /// `big[i]` if given (`max_j abs(B_ij x_j)`, as [`crate::residual::residual`]
    /// scales the residuals of points).
    pub(super) fn residual_of_scaled(
        &self,
        bx: &Col<T>,
        x: &Col<T>,
        big: Option<&Col<T>>,
    ) -> Residual {
        self.residual_of_rows(col_slice(bx), x, big.map(col_slice))
    }

    /// [`Self::residual_of_scaled`] on slices.
    fn residual_of_rows(&self, bx: &[T], x: &Col<T>, big: Option<&[T]>) -> Residual {
        let mut eq = 0.0f64;
        // rows with r <= bound * s cannot raise eq (bound a hair below eq,
        // far beyond the rounding of r / s): the division only where one may
        let mut bound = T::zero();
        let l_nonbasic = self.row_of(Var::Lambda).is_none();
        let dim = self.dim;
        let (q, d, bx) = (
            &col_slice(&self.q)[..dim],
            &col_slice(&self.d)[..dim],
            &bx[..dim],
        );
        let big = big.map(|b| &b[..dim]);
        // one row's measure; the loop below is written out per case (the
        // branches on `l_nonbasic` and `big` out of it), the same operations
        let mut row = |q: T, d: T, bx: T, big: Option<T>| {
            let ld = self.lambda * d;
            // the basic right-hand side (see Self::rhs)
            let rhs = if l_nonbasic { q + ld } else { q };
            let r = (rhs - bx).abs();
            // most rows end here, before the chain of `max` below, which
            // would skip them too: with `r <= bound` no term is NaN but
            // perhaps `big` (`r` holds `q`, `bx` and, with L nonbasic,
            // `L d`; with L basic `L d` is asked to be finite), so `s` is
            // NaN (skipped below) or at least one, and then `bound * s >=
            // bound >= r` (rounding is monotone in f32 and f64; not relied
            // on for the double-double f128)
            if T::NATIVE && r <= bound && (l_nonbasic || ld.is_finite()) {
                return;
            }
            let mut s = T::one().max(q.abs()).max(ld.abs()).max(bx.abs());
            if let Some(big) = big {
                s = s.max(big);
            }
            if r > bound * s {
                let v = (r / s).to_f64();
                if v > eq {
                    eq = v;
                    bound = T::from_f64(v * (1.0 - 1e-9));
                }
            }
        };
        match big {
            Some(big) => {
                for (((&q, &d), &bx), &b) in q.iter().zip(d).zip(bx).zip(big) {
                    row(q, d, bx, Some(b));
                }
            }
            None => {
                for ((&q, &d), &bx) in q.iter().zip(d).zip(bx) {
                    row(q, d, bx, None);
                }
            }
        }
        // feasibility and complementarity of the basic z and w (nonbasic ones are zero)
        let (mut sz, mut sw) = (1.0f64, 1.0f64);
        for (r, v) in self.basis.iter().enumerate() {
            match *v {
                Var::Z(_) => sz = sz.max(x[r].to_f64().abs()),
                Var::W(_) => sw = sw.max(x[r].to_f64().abs()),
                _ => {}
            }
        }
        let (mut feas, mut comp) = (0.0f64, 0.0f64);
        for (r, v) in self.basis.iter().enumerate() {
            match *v {
                Var::Z(i) => {
                    let z = x[r].to_f64();
                    feas = feas.max(-z / sz);
                    if let Some(rw) = self.row_of(Var::W(i)) {
                        comp = comp.max((z * x[rw].to_f64()).abs() / (sz * sw));
                    }
                }
                Var::W(_) => feas = feas.max(-x[r].to_f64() / sw),
                _ => {}
            }
        }
        Residual {
            equation: eq,
            feasibility: feas.max(0.0),
            complementarity: comp,
        }
    }
}

/// A row of the minimum-ratio test read again with refined values
/// ([`Engine::refined_ratios`]): the ratio `x_r / col_r` in the wide type and
/// a bound on its error (`f64::INFINITY`: not decided), and the refined
/// column entry `col_r` (zero where not decided).
pub(super) struct RefinedRatio<W> {
    pub ratio: W,
    pub err: f64,
    pub entry: f64,
}

impl<T: Scalar> Engine<'_, T> {
    /// The ratios `x_r / col_r` of the rows `rows` with the basic values `x`
    /// and the entering column `col = B^{-1} a_v` refined by one step whose
    /// residual is accumulated in [`Scalar::Wide`] (the right-hand side
    /// `q + L d` formed there too), each sum `x_r + dx_r` kept in the wide
    /// type, and a first-order bound on each ratio's error:
    ///
    /// `err(x_r) <= 2 |B^{-1}|_r (g eps_w (|rhs| + |B| |x|) + (1 + cond) eps |r|
    ///   + g eps |B| |dx|) + eps_w |x_r|`
    ///
    /// (the wide residual's accumulation, its rounding to the working type,
    /// the solve of the correction: backward error `g eps |B| |dx|`, or
    /// `cond eps` of `|B^{-1}| |r|` for an explicit inverse; `g` =
    /// [`crate::tolerance::TIE_ERROR_GAMMA`]), the same for `col_r`, and the
    /// ratio's from both. One pass over the basic columns for the residuals,
    /// one for `|B| |dx|`, a two-column solve and a transpose solve per row:
    /// spent on ties only.
    pub(super) fn refined_ratios(
        &self,
        v: Var,
        col: &Col<T>,
        rows: &[usize],
    ) -> Vec<RefinedRatio<T::Wide>> {
        use crate::tolerance::{TIE_ERROR_GAMMA, TIE_REFINE_MAX_COND_EPS};
        let dim = self.dim;
        let (m, p) = (self.m, self.p);
        let eps = T::eps().to_f64();
        let eps_w = <T::Wide as Scalar>::eps().to_f64();
        let g = TIE_ERROR_GAMMA;
        let undecided = || {
            rows.iter()
                .map(|_| RefinedRatio {
                    ratio: T::zero().widen(),
                    err: f64::INFINITY,
                    entry: 0.0,
                })
                .collect()
        };
        if self.cond.is_nan() || self.cond * eps > TIE_REFINE_MAX_COND_EPS {
            return undecided();
        }
        let l_basic = self.row_of(Var::Lambda).is_some();
        let a = var_column(m, &self.d, p, v);
        let mut acc: Vec<T::Wide> = (0..dim)
            .map(|i| {
                if l_basic {
                    self.q[i].widen()
                } else {
                    self.q[i].widen() + T::mul_wide(self.lambda, self.d[i])
                }
            })
            .collect();
        let mut acc_c: Vec<T::Wide> = (0..dim).map(|i| a[i].widen()).collect();
        // |rhs| + |B| |x| and |a_v| + |B| |col|: the terms of each row
        let mut sx: Vec<f64> = (0..dim)
            .map(|i| {
                let l = if l_basic {
                    0.0
                } else {
                    (self.lambda * self.d[i]).to_f64().abs()
                };
                self.q[i].to_f64().abs() + l
            })
            .collect();
        let mut sc: Vec<f64> = (0..dim).map(|i| a[i].to_f64().abs()).collect();
        for (k, b) in self.basis.iter().enumerate() {
            let (xk, ck) = (self.x[k], col[k]);
            if xk == T::zero() && ck == T::zero() {
                continue;
            }
            let (xa, ca) = (xk.to_f64().abs(), ck.to_f64().abs());
            // the column of a matrix variable is -M[:, j] (of L: -d), so r += M x
            let mut add = |i: usize, e: T| {
                acc[i] = T::wide_mul_add(acc[i], e, xk);
                acc_c[i] = T::wide_mul_add(acc_c[i], e, ck);
                let ea = e.to_f64().abs();
                sx[i] += ea * xa;
                sc[i] += ea * ca;
            };
            match *b {
                Var::U(j) => m.for_col(j, add),
                Var::Z(j) => m.for_col(p + j, add),
                Var::Lambda => self.d_rows.iter().for_each(|&i| add(i, self.d[i])),
                Var::W(i) => add(p + i, -T::one()),
                Var::Artificial(i) => add(i, -T::one()),
            }
        }
        let r = Col::from_fn(dim, |i| T::narrow(acc[i]));
        let rc = Col::from_fn(dim, |i| T::narrow(acc_c[i]));
        let (dx, dc) = self.factor.solve2(r.clone(), rc.clone());
        // |B| |dx| and |B| |dc|
        let (mut sdx, mut sdc) = (vec![0.0f64; dim], vec![0.0f64; dim]);
        for (k, b) in self.basis.iter().enumerate() {
            let (xa, ca) = (dx[k].to_f64().abs(), dc[k].to_f64().abs());
            if xa == 0.0 && ca == 0.0 {
                continue;
            }
            let mut add = |i: usize, e: T| {
                let ea = e.to_f64().abs();
                sdx[i] += ea * xa;
                sdc[i] += ea * ca;
            };
            match *b {
                Var::U(j) => m.for_col(j, add),
                Var::Z(j) => m.for_col(p + j, add),
                Var::Lambda => self.d_rows.iter().for_each(|&i| add(i, self.d[i])),
                Var::W(i) => add(p + i, -T::one()),
                Var::Artificial(i) => add(i, -T::one()),
            }
        }
        let solve_eps = (1.0 + self.cond) * eps;
        let l_row = self.row_of(Var::Lambda);
        // the rows of B^{-1} at once where the factorisation hands them over
        // (a sparse LU: one sweep for two rows), else one transpose solve each
        let batch = self.factor.inverse_rows(rows);
        rows.iter()
            .enumerate()
            .map(|(t, &row)| {
                let inv = match &batch {
                    Some(_) => None,
                    None => {
                        let mut e = Col::<T>::zeros(dim);
                        e[row] = T::one();
                        Some(self.factor.solve_transpose(&e))
                    }
                };
                let (mut bx, mut bc) = (0.0f64, 0.0f64);
                for i in 0..dim {
                    let w = match (&batch, &inv) {
                        (Some(b), _) => b.get_raw(t, i),
                        (None, Some(inv)) => inv[i],
                        (None, None) => unreachable!("one of the two"),
                    }
                    .to_f64()
                    .abs();
                    if w == 0.0 {
                        continue;
                    }
                    let rx = r[i].to_f64().abs();
                    let rcx = rc[i].to_f64().abs();
                    bx += w * (g * eps_w * sx[i] + solve_eps * rx + g * eps * sdx[i]);
                    bc += w * (g * eps_w * sc[i] + solve_eps * rcx + g * eps * sdc[i]);
                }
                // (L, if basic, is the path's parameter: its row is exact)
                let fixed = Some(row) == l_row;
                let xw = if fixed {
                    self.x[row].widen()
                } else {
                    self.x[row].widen() + dx[row].widen()
                };
                let cw = col[row].widen() + dc[row].widen();
                let ex = 2.0 * bx + eps_w * xw.to_f64().abs();
                let ec = 2.0 * bc + eps_w * cw.to_f64().abs();
                let zero = T::zero().widen();
                let xw = if xw > zero { xw } else { zero };
                let c = cw.to_f64();
                if c.is_nan() || c <= ec || !ex.is_finite() || !ec.is_finite() {
                    return RefinedRatio {
                        ratio: zero,
                        err: f64::INFINITY,
                        entry: 0.0,
                    };
                }
                let ratio = xw / cw;
                let t = ratio.to_f64();
                let err = (ex + t * ec) / (c - ec) + 4.0 * eps_w * t;
                RefinedRatio {
                    ratio,
                    err,
                    entry: c,
                }
            })
            .collect()
    }
}
