//! The complementary pivoting core shared by both methods.
//!
//! The system is written with one column per variable,
//!
//! ```text
//! sum_v a_v v = q,    a_{u_j} = -M[:, j],  a_{z_i} = -M[:, p+i],  a_{w_i} = e_{p+i},
//!                     a_{art_k} = e_k,     a_L = -d,
//! ```
//!
//! so that `M x + q + L d - (0, w) = 0`. A basis holds `p + n` variables. The
//! path is followed by moving one nonbasic *driver* (the parameter `L`, or the
//! complement of the variable that left last) while `L` is basic; every step ends
//! with the lexicographic minimum-ratio rule choosing who leaves. Artificial
//! variables (dependent equality rows, Wolfe long form) are fixed at zero: they
//! block any step that would move them and, once out, never return.

/// The pivot tolerance relative to the z/w rows (see `ratio_test`): off.
const PIVOT_TOL_ON_COMP_ROWS: bool = false;
/// The covering vector brought to the right-hand side's power of two: off.
const SCALE_COVERING: bool = false;

use crate::basis::{apply, var_column, BasisFactor, BlockInverse, DenseInverse, SparseLu};
use crate::matrix::MatrixRef;
use crate::path::{Breakpoint, Point, Residual, Segment, Var};
use crate::scalar::Scalar;
use crate::settings::Settings;
use core::cell::RefCell;
use faer::Col;

/// How a trace ended.
pub(crate) enum TraceEnd<T: Scalar> {
    /// `lambda_end` reached; the driver sits at `theta` (nonbasic, mid-step).
    Reached { driver: Var, theta: T },
    /// No blocking variable and `L` rises along the ray.
    UnboundedRay { driver: Var, col: Col<T>, rate: T },
    /// No blocking variable and `L` does not rise: no solution beyond here on this path.
    SecondaryRay { driver: Var, col: Col<T>, rate: T },
    /// Pivot limit.
    PivotLimit,
    /// Evidence of ill-conditioning.
    IllConditioned(String),
    /// No admissible continuation (no free variable can replace `L`).
    Stalled(String),
}

/// What a trace records of the path (phase 2 only).
pub(crate) struct Recorder<T: Scalar> {
    pub segments: Vec<Segment<T>>,
    pub breakpoints: Vec<Breakpoint<T>>,
    pub turning_points: usize,
    last_sign: i8,
}

impl<T: Scalar> Recorder<T> {
    pub(crate) fn new() -> Self {
        Self {
            segments: Vec::new(),
            breakpoints: Vec::new(),
            turning_points: 0,
            last_sign: 0,
        }
    }
}

pub(crate) struct Engine<'a, T: Scalar> {
    m: MatrixRef<'a, T>,
    pub p: usize,
    pub n: usize,
    dim: usize,
    /// Right-hand side and parameter direction of the system being traced.
    pub q: Col<T>,
    pub d: Col<T>,
    /// `(max_i |q_i|, max_i |d_i|)` ([`Self::xscale`]).
    data_max: (T, T),
    /// The rows where `d` is nonzero: the residual passes visit only these
    /// of the column of `L` (a product with a zero entry changes no sum; a
    /// load direction is often a single entry, the basis thousands of rows).
    d_rows: Vec<usize>,
    pub basis: Vec<Var>,
    pos: Vec<Option<usize>>,
    factor: Box<dyn BasisFactor<T>>,
    pub x: Col<T>,
    /// Current value of `L` (kept in step with `x` when `L` is basic).
    pub lambda: T,
    settings: &'a Settings<T>,
    pub max_pivots: usize,
    pub pivots: usize,
    pub degenerate_pivots: usize,
    pub refactorisations: usize,
    /// Iterative-refinement steps taken (at breakpoints and on entering columns).
    pub refinements: usize,
    since_refactor: usize,
    /// The last condition estimate says entering columns need a refinement step.
    refine_columns: bool,
    /// The last condition estimate says the basic values need residuals in the
    /// wide type ([`crate::tolerance::WIDE_REFINE_COND_EPS`]).
    refine_wide: bool,
    /// The basis representation refines its own solves (cheaper than
    /// [`Engine::refine_column`]: the block basis refines on `S` alone).
    refine_inside: bool,
    pub max_cond: f64,
    pivot_tol: T,
    /// Print every pivot to stderr (environment variable `PLCP_TRACE` set).
    pub(crate) trace_pivots: bool,
    /// The pivot tolerance times the basis condition estimate (clamped to
    /// `[1, 1e6]`): entries of `B^{-1} a` below `noise * max|B^{-1} a|` are rounding.
    noise: T,
    tie_tol: T,
    /// The last recorded breakpoint still owes its residual (measured with the
    /// next entering column, in the same pass over the basic columns).
    residual_owed: bool,
    /// The accumulators of [`Self::wide_residual_pair`], kept between pivots
    /// (two vectors of `p + n` wide values each time were a tenth of the
    /// trace in page faults and zeroing).
    wide_acc: RefCell<WideAccumulators<T>>,
}

/// The two accumulators of [`Engine::wide_residual_pair`] (values, column).
type WideAccumulators<T> = (Vec<<T as Scalar>::Wide>, Vec<<T as Scalar>::Wide>);

/// A residual `r` accumulated in the wide type and rounded once, `B x` as
/// `rhs - r`, and the largest term `max_j abs(B_ij x_j)` of each row.
type WideResidual<T> = (Col<T>, Col<T>, Col<T>);

/// Mixed-precision refinement of basic values stops once the correction is
/// within this many roundings (`eps`) of the largest basic value.
const WIDE_REFINE_EPS: f64 = 4.0;

/// At most this many mixed-precision refinement steps per breakpoint.
const WIDE_REFINE_STEPS: usize = 3;

/// `max_i |v_i|` (zero for an empty slice) in four independent chains: a
/// single chain of compares waits on each one, and the engine takes this
/// maximum of vectors of length `p + n` several times per pivot.
fn max_abs<T: Scalar>(v: &[T]) -> T {
    let mut m = [T::zero(); 4];
    let mut chunks = v.chunks_exact(4);
    for c in &mut chunks {
        for k in 0..4 {
            m[k] = m[k].max(c[k].abs());
        }
    }
    for &x in chunks.remainder() {
        m[0] = m[0].max(x.abs());
    }
    m[0].max(m[1]).max(m[2].max(m[3]))
}

/// [`max_abs`] of a column.
fn col_max_abs<T: Scalar>(c: &Col<T>) -> T {
    match c.as_ref().try_as_col_major() {
        Some(c) => max_abs(c.as_slice()),
        None => c.iter().fold(T::zero(), |a, v| a.max(v.abs())),
    }
}

/// The entries of a (contiguous) column.
fn col_slice<T: Scalar>(c: &Col<T>) -> &[T] {
    c.as_ref()
        .try_as_col_major()
        .expect("a column is contiguous")
        .as_slice()
}

/// The entries of a (contiguous) column, mutable.
fn col_slice_mut<T: Scalar>(c: &mut Col<T>) -> &mut [T] {
    c.as_mut()
        .try_as_col_major_mut()
        .expect("a column is contiguous")
        .as_slice_mut()
}

fn is_comp(v: Var) -> bool {
    matches!(v, Var::W(_) | Var::Z(_))
}

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
    fn var_index(&self, v: Var) -> usize {
        let (n, p) = (self.n, self.p);
        match v {
            Var::W(i) => i,
            Var::Z(i) => n + i,
            Var::U(j) => 2 * n + j,
            Var::Artificial(k) => 2 * n + p + k,
            Var::Lambda => 3 * n + 2 * p,
        }
    }

    /// A new engine on the basis `basis` with `L` nonbasic at `lambda`.
    pub(crate) fn new(
        m: MatrixRef<'a, T>,
        p: usize,
        q: Col<T>,
        d: Col<T>,
        basis: Vec<Var>,
        lambda: T,
        settings: &'a Settings<T>,
    ) -> Result<Self, String> {
        let dim = m.nrows();
        let n = dim - p;
        let data_max = Self::data_max(&q, &d);
        let d_rows = Self::nonzero_rows(&d);
        let mut e = Self {
            m,
            p,
            n,
            dim,
            q,
            d,
            data_max,
            d_rows,
            basis: basis.clone(),
            pos: vec![None; 3 * n + 2 * p + 1],
            factor: match settings.basis {
                crate::settings::BasisKind::Block => Box::new(BlockInverse::new(dim)),
                crate::settings::BasisKind::Dense => Box::new(DenseInverse::new(dim)),
                crate::settings::BasisKind::Sparse => Box::new(SparseLu::new(dim)),
            },
            x: Col::zeros(dim),
            lambda,
            settings,
            max_pivots: settings.max_pivots.unwrap_or(50 * dim + 1000),
            pivots: 0,
            degenerate_pivots: 0,
            refactorisations: 0,
            refinements: 0,
            since_refactor: 0,
            refine_columns: false,
            refine_wide: false,
            refine_inside: false,
            max_cond: 1.0,
            pivot_tol: T::from_f64(settings.pivot_tol_eps) * T::eps(),
            noise: T::from_f64(settings.pivot_tol_eps) * T::eps(),
            trace_pivots: std::env::var_os("PLCP_TRACE").is_some(),
            tie_tol: T::from_f64(settings.tie_tol_eps) * T::eps(),
            residual_owed: false,
            wide_acc: RefCell::new((Vec::new(), Vec::new())),
        };
        for (r, v) in basis.iter().enumerate() {
            let k = e.var_index(*v);
            e.pos[k] = Some(r);
        }
        e.refactor()?;
        e.refactorisations = 0;
        Ok(e)
    }

    pub(crate) fn row_of(&self, v: Var) -> Option<usize> {
        self.pos[self.var_index(v)]
    }

    /// `B^{-1} a_v`: the change of the basic values per unit increase of `v` is its negative.
    pub(crate) fn column(&self, v: Var) -> Col<T> {
        self.factor.column(self.m, &self.d, self.p, v)
    }

    /// Rebuilds the factorisation and the basic values (drift correction).
    pub(crate) fn refactor(&mut self) -> Result<(), String> {
        let cond = self
            .factor
            .refactor(self.m, &self.d, self.p, &self.basis)
            .ok_or_else(|| {
                format!(
                    "the basis became numerically singular at L = {:e} after {} pivots",
                    self.lambda.to_f64(),
                    self.pivots
                )
            })?;
        self.refactorisations += 1;
        self.since_refactor = 0;
        self.max_cond = self.max_cond.max(cond);
        self.refine_columns = cond * T::eps().to_f64() > self.settings.refine_cond_eps;
        // on a sparse M the wide residual is a pass over the stored entries
        // (cheap): from the same threshold as the columns; on a dense M it
        // costs O(n k) per use, and waits for WIDE_REFINE_COND_EPS
        self.refine_wide = self.refine_columns
            && (matches!(self.m, MatrixRef::Sparse(_))
                || cond * T::eps().to_f64() > crate::tolerance::WIDE_REFINE_COND_EPS);
        // off for every solve but the entering column's (see trace_steps)
        self.refine_inside = self.factor.set_refine(false);
        self.noise = self.pivot_tol * T::from_f64(cond.clamp(1.0, 1e6));
        let rhs = self.rhs();
        let xnew = self.factor.solve(&rhs);
        // snap tiny negatives of sign-constrained basics (drift) to zero
        let scale = self.xscale();
        for r in 0..self.dim {
            let mut v = xnew[r];
            if is_comp(self.basis[r]) && v < T::zero() && -v <= self.tie_tol * scale {
                v = T::zero();
            }
            if matches!(self.basis[r], Var::Artificial(_)) && v.abs() <= self.tie_tol * scale {
                v = T::zero();
            }
            self.x[r] = v;
        }
        if let Some(l) = self.row_of(Var::Lambda) {
            // L stays the path's exact parameter; the recomputed value measures drift
            self.x[l] = self.lambda;
        }
        if cond * T::eps().to_f64() > self.settings.max_cond_eps {
            return Err(format!(
                "basis condition number estimate {cond:.3e} at L = {:e} exceeds {:.1e}/eps ({}): results would not be accurate in this precision; use a higher precision",
                self.lambda.to_f64(),
                self.settings.max_cond_eps,
                T::NAME
            ));
        }
        Ok(())
    }

    /// Why the current basic solution is not a feasible start (a basic `z` or `w`
    /// negative, or an artificial variable nonzero, beyond the tie tolerance), or
    /// `None` if it is one.
    pub(crate) fn infeasibility(&self) -> Option<String> {
        let scale = self.xscale();
        let tol = self.tie_tol * scale;
        (0..self.dim).find_map(|r| {
            let v = self.basis[r];
            let x = self.x[r];
            let bad = match v {
                Var::W(_) | Var::Z(_) => !x.is_finite() || x < -tol,
                Var::Artificial(_) => !x.is_finite() || x.abs() > tol,
                _ => !x.is_finite(),
            };
            bad.then(|| format!("{v} = {:e} at L = {:e}", x.to_f64(), self.lambda.to_f64()))
        })
    }

    /// `q + L d` when `L` is nonbasic, `q` when it is basic.
    fn rhs(&self) -> Col<T> {
        if self.row_of(Var::Lambda).is_some() {
            self.q.clone()
        } else {
            Col::from_fn(self.dim, |i| self.q[i] + self.lambda * self.d[i])
        }
    }

    /// The scale of the basic values: `max(1, |q_i|, |L d_i|, |x_i|)` over
    /// every row (`x` without `L`'s own position). `max_i |L d_i|` is
    /// `|L| max_i |d_i|` exactly (rounding is monotone), so `q` and `d`
    /// contribute their cached maxima and the pass is over `x` alone.
    fn xscale(&self) -> T {
        let s = T::one()
            .max(self.data_max.0)
            .max(self.lambda.abs() * self.data_max.1);
        let x = self.x.as_ref().try_as_col_major().expect("contiguous");
        let x = x.as_slice();
        match self.row_of(Var::Lambda) {
            Some(l) => s.max(max_abs(&x[..l])).max(max_abs(&x[l + 1..])),
            None => s.max(max_abs(x)),
        }
    }

    /// The rows `i` with `v_i != 0`.
    fn nonzero_rows(v: &Col<T>) -> Vec<usize> {
        (0..v.nrows()).filter(|&i| v[i] != T::zero()).collect()
    }

    /// `(max_i |q_i|, max_i |d_i|)`, cached for [`Self::xscale`].
    fn data_max(q: &Col<T>, d: &Col<T>) -> (T, T) {
        (col_max_abs(q), col_max_abs(d))
    }

    /// Values of `(z, w, u)` now, with `driver` at `theta`.
    pub(crate) fn point(&self, driver: Option<(Var, T)>) -> Point<T> {
        let mut z = Col::zeros(self.n);
        let mut w = Col::zeros(self.n);
        let mut u = Col::zeros(self.p);
        let mut set = |v: Var, val: T| match v {
            Var::W(i) => w[i] = val,
            Var::Z(i) => z[i] = val,
            Var::U(j) => u[j] = val,
            _ => {}
        };
        for (r, v) in self.basis.iter().enumerate() {
            set(*v, self.x[r]);
        }
        if let Some((v, t)) = driver {
            set(v, t);
        }
        Point {
            lambda: self.lambda,
            z,
            w,
            u,
        }
    }

    /// Slopes in `L` of `(z, w, u)` along a step of the driver with column `col` and `L`-rate `rate`.
    fn slopes(&self, driver: Var, col: &Col<T>, rate: T) -> (Col<T>, Col<T>, Col<T>) {
        let mut dz = Col::zeros(self.n);
        let mut dw = Col::zeros(self.n);
        let mut du = Col::zeros(self.p);
        let mut set = |v: Var, val: T| match v {
            Var::W(i) => dw[i] = val,
            Var::Z(i) => dz[i] = val,
            Var::U(j) => du[j] = val,
            _ => {}
        };
        for (r, v) in self.basis.iter().enumerate() {
            set(*v, -col[r] / rate);
        }
        set(driver, T::one() / rate);
        (dz, dw, du)
    }

    fn segment_basis(&self, driver: Var) -> Vec<Var> {
        let mut b = Vec::with_capacity(self.n + self.p);
        for i in 0..self.n {
            if self.row_of(Var::W(i)).is_some() || driver == Var::W(i) {
                b.push(Var::W(i));
            } else {
                b.push(Var::Z(i));
            }
        }
        for j in 0..self.p {
            if self.row_of(Var::U(j)).is_some() {
                b.push(Var::U(j));
            }
        }
        b
    }

    fn record_segment(
        &self,
        rec: &mut Recorder<T>,
        driver: Var,
        col: &Col<T>,
        rate: T,
        lambda_to: T,
        unbounded: bool,
    ) {
        // a segment starts with the driver at zero
        let start = self.point(Some((driver, T::zero())));
        let (dz, dw, du) = self.slopes(driver, col, rate);
        crate::observe::record(
            &mut rec.segments,
            &rec.breakpoints,
            self.pivots,
            Segment {
                lambda_from: self.lambda,
                lambda_to,
                unbounded,
                basis: self.segment_basis(driver),
                z_from: start.z,
                dz,
                w_from: start.w,
                dw,
                u_from: start.u,
                du,
            },
        );
    }

    /// The minimum-ratio test with the lexicographic rule. Returns the row and the step.
    fn ratio_test(&self, col: &Col<T>) -> Option<(usize, T)> {
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
        let mut cands: Vec<(usize, T)> = Vec::new();
        for r in 0..self.dim {
            if is_comp(self.basis[r]) && col[r] > ptol {
                let ratio = self.x[r].max(T::zero()) / col[r];
                cands.push((r, ratio));
                best = Some(best.map_or(ratio, |b| b.min(ratio)));
            }
        }
        let tmin = best?;
        let mut tied: Vec<usize> = cands
            .iter()
            .filter(|(r, t)| *t - tmin <= self.tie_tol * (tmin.abs() + xnorm / col[*r]))
            .map(|(r, _)| *r)
            .collect();
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
        let r = *tied.first().unwrap_or(&cands[0].0);
        let theta = self.x[r].max(T::zero()) / col[r];
        Some((r, theta))
    }

    /// Pivot `entering` (column `col = B^{-1} a`, value `value`) into row `r`.
    fn pivot(&mut self, r: usize, entering: Var, col: &Col<T>, value: T) -> Result<(), String> {
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

    /// After an artificial left the basis: bring a free variable in for `L`, so that
    /// `L` can drive again. Returns false if none can.
    fn free_for_lambda(&mut self) -> Result<bool, String> {
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
    fn refine_values(&mut self, mut bx: Col<T>) -> Residual {
        if self.refine_wide {
            return self.refine_values_wide(None);
        }
        let mut res = self.residual_of(&bx);
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
            bx = bxn;
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
    fn refine_values_wide(&mut self, first: Option<Col<T>>) -> Residual {
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
            let (mut dnorm, mut xnorm) = (0.0f64, 0.0f64);
            for k in 0..self.dim {
                if Some(k) != l {
                    dnorm = dnorm.max(dx[k].to_f64().abs());
                    xnorm = xnorm.max(self.x[k].to_f64().abs());
                }
            }
            if !dnorm.is_finite() || dnorm >= 0.5 * last {
                break;
            }
            for k in 0..self.dim {
                if Some(k) != l {
                    self.x[k] += dx[k];
                }
            }
            last = dnorm;
            if dnorm <= WIDE_REFINE_EPS * T::eps().to_f64() * xnorm || step + 1 == WIDE_REFINE_STEPS
            {
                // no further step: the residual is only reported, and the
                // working precision measures it as it measures points
                // (`crate::residual`: within a few roundings of the row's
                // largest term, the scale it is reported against)
                measured = Some(self.plain_residual(&self.x));
                break;
            }
            let (rn, bx, big) = self.wide_residual(&self.x, None);
            r = Some(rn);
            measured = Some((bx, big));
        }
        let (bx, big) = measured.unwrap_or_else(|| self.plain_residual(&self.x));
        // relative to the terms of each row as well (a row whose terms cancel
        // to a small B x keeps the rounding of its largest term)
        self.residual_of_scaled(&bx, &self.x, Some(&big))
    }

    /// `B x` in the working precision and `max_j abs(B_ij x_j)` per row, in
    /// one pass over the basic columns.
    fn plain_residual(&self, x: &Col<T>) -> (Col<T>, Col<T>) {
        let dim = self.dim;
        let mut bx_col: Col<T> = Col::zeros(dim);
        let mut big_col: Col<T> = Col::zeros(dim);
        let (bx, big) = (col_slice_mut(&mut bx_col), col_slice_mut(&mut big_col));
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
        (bx_col, big_col)
    }

    /// `r = rhs - B x` accumulated in [`Scalar::Wide`] and rounded once,
    /// `B x` as `rhs - r` (so that [`Self::residual_of`] reads the wide
    /// residual), and `max_j abs(B_ij x_j)` per row (the scale of the
    /// cancellation in row `i`: the Oettli-Prager backward error's). `rhs` is
    /// the basic right-hand side (`v = None`) or the column `a_v` of the
    /// entering variable `v` (the residual of `x = B^{-1} a_v`).
    fn wide_residual(&self, x: &Col<T>, v: Option<Var>) -> WideResidual<T> {
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
    fn wide_residual_pair(&self, x: &Col<T>, v: Var, col: &Col<T>) -> (Col<T>, Col<T>) {
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
    fn wide_residual_pair_with<const FMA: bool>(
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
    fn refine_column(&mut self, v: Var, col: &mut Col<T>, correction: Option<Col<T>>) {
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
    fn apply_column_correction(&mut self, col: &mut Col<T>, dc: &Col<T>) {
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
    fn residual_of(&self, bx: &Col<T>) -> Residual {
        self.residual_of_values(bx, &self.x)
    }

    fn residual_of_values(&self, bx: &Col<T>, x: &Col<T>) -> Residual {
        self.residual_of_scaled(bx, x, None)
    }

    /// [`Self::residual_of_values`], each equation row also relative to
    /// `big[i]` if given (`max_j abs(B_ij x_j)`, as [`crate::residual::residual`]
    /// scales the residuals of points).
    fn residual_of_scaled(&self, bx: &Col<T>, x: &Col<T>, big: Option<&Col<T>>) -> Residual {
        let mut eq = 0.0f64;
        // rows with r <= bound * s cannot raise eq (bound a hair below eq,
        // far beyond the rounding of r / s): the division only where one may
        let mut bound = T::zero();
        let l_nonbasic = self.row_of(Var::Lambda).is_none();
        let (q, d, bx) = (col_slice(&self.q), col_slice(&self.d), col_slice(bx));
        let big = big.map(col_slice);
        for i in 0..self.dim {
            let ld = self.lambda * d[i];
            // the basic right-hand side (see Self::rhs)
            let rhs = if l_nonbasic { q[i] + ld } else { q[i] };
            let r = (rhs - bx[i]).abs();
            let mut s = T::one().max(q[i].abs()).max(ld.abs()).max(bx[i].abs());
            if let Some(big) = big {
                s = s.max(big[i]);
            }
            if r > bound * s {
                let v = (r / s).to_f64();
                if v > eq {
                    eq = v;
                    bound = T::from_f64(v * (1.0 - 1e-9));
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

    fn trace_steps(
        &mut self,
        lambda_end: Option<T>,
        mut rec: Option<&mut Recorder<T>>,
    ) -> TraceEnd<T> {
        let mut driver = Var::Lambda;
        if self.row_of(Var::Lambda).is_some() {
            return TraceEnd::Stalled("internal: trace must start with L nonbasic".into());
        }
        loop {
            if self.pivots >= self.max_pivots || crate::observe::stop_requested() {
                return TraceEnd::PivotLimit;
            }
            // the entering column refined inside its solve, where the basis can
            // (the block basis refines on S alone: no extra pass over the matrix)
            let refine_here = self.refine_columns && self.refine_inside;
            if refine_here {
                self.factor.set_refine(true);
            }
            // the entering column's wide residual, when a pass for the values computed it
            // and its correction (solved with the values' first correction)
            let mut col_correction: Option<Col<T>> = None;
            let mut col = match rec.as_deref_mut() {
                Some(rec) if self.residual_owed => {
                    let (col, res) = if self.refine_wide {
                        // the wide residuals recompute B x: no working-precision
                        // product; the first residual of the values and the
                        // entering column's share one pass over the basic columns
                        let col = self.column(driver);
                        if refine_here {
                            self.factor.set_refine(false);
                        }
                        let first = if self.refine_inside {
                            None
                        } else {
                            // the two corrections are independent: one sweep
                            // over the factors for both
                            let (values, column) = self.wide_residual_pair(&self.x, driver, &col);
                            let (dx, dc) = self.factor.solve2(values, column);
                            col_correction = Some(dc);
                            Some(dx)
                        };
                        (col, self.refine_values_wide(first))
                    } else {
                        let a = var_column(self.m, &self.d, self.p, driver);
                        let (col, bx) = self.factor.solve_and_apply(
                            self.m,
                            &self.d,
                            self.p,
                            &self.basis,
                            &a,
                            &self.x,
                        );
                        if refine_here {
                            self.factor.set_refine(false);
                        }
                        (col, self.refine_values(bx))
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
                        return TraceEnd::IllConditioned(format!(
                            "the basic solution at the breakpoint L = {:e} has residual {worst:.3e} (equation {:.1e}, feasibility {:.1e}, complementarity {:.1e}) above sqrt(eps) = {limit:.1e} in {} after refinement (basis condition estimate up to {:.1e}): the path is not continued; use a higher precision",
                            self.lambda.to_f64(),
                            res.equation,
                            res.feasibility,
                            res.complementarity,
                            T::NAME,
                            self.max_cond
                        ));
                    }
                    col
                }
                _ => self.column(driver),
            };
            if refine_here {
                self.factor.set_refine(false);
            }
            if self.refine_columns {
                if self.refine_inside {
                    // refined inside the solve above (unless the basis found
                    // its refinement idle, see tolerance::REFINE_IDLE_EPS)
                    self.refinements += usize::from(self.factor.last_solve_refined());
                } else {
                    self.refine_column(driver, &mut col, col_correction.take());
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
            let rising = rate > rate_tol;
            let moving = rate.abs() > rate_tol;
            if !(0..self.dim).all(|i| col[i].is_finite() && self.x[i].is_finite()) {
                return TraceEnd::IllConditioned(format!(
                    "non-finite values at L = {:e} (overflow in the working precision {})",
                    self.lambda.to_f64(),
                    T::NAME
                ));
            }
            let block = self.ratio_test(&col);
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
                    for r in 0..self.dim {
                        let v = self.x[r] - theta_end * col[r];
                        self.x[r] = v;
                    }
                    self.lambda = end;
                    if let Some(l) = self.row_of(Var::Lambda) {
                        self.x[l] = end;
                    }
                    return TraceEnd::Reached {
                        driver,
                        theta: theta_end,
                    };
                }
            }
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
            for i in 0..self.dim {
                let v = self.x[i] - theta * col[i];
                self.x[i] = v;
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
                    Ok(true) => driver = Var::Lambda,
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
        }
    }

    /// Whether `v` may enter the basis under restricted entry (its complement nonbasic),
    /// given the current driver.
    fn admissible(&self, v: Var, driver: Var) -> bool {
        if v == driver || self.row_of(v).is_some() {
            return false;
        }
        match v.complement() {
            Some(c) => c != driver && self.row_of(c).is_none(),
            None => matches!(v, Var::U(_)),
        }
    }

    /// After the driver took an equality row (an artificial variable left), `L` is
    /// basic and something must take its place so that `L` can drive again: a
    /// nonbasic free variable (a redundant member force, say); else an admissible
    /// complementary variable (its complement nonbasic: a section at yield that
    /// may flow); else first free a complementary variable by moving a free one
    /// (a zero-length step) and try again. Returns false if nothing can.
    fn unlock_lambda(&mut self) -> Result<bool, String> {
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
    fn free_vertical_move(&mut self, rho: &Col<T>, driver: Var) -> Result<bool, String> {
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

    pub(crate) fn tie_tol_value(&self) -> T {
        self.tie_tol
    }

    fn note_direction(&self, rec: &mut Recorder<T>, sign: i8) {
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
    /// at its current value).
    pub(crate) fn settle(&mut self, driver: Var, theta: T) -> Result<(), String> {
        if driver == Var::Lambda {
            return Ok(());
        }
        let Some(l) = self.row_of(Var::Lambda) else {
            return Ok(());
        };
        let col = self.column(driver);
        self.pivot(l, driver, &col, theta)
    }

    /// Replaces the system's right-hand side and direction (phase change) and
    /// recomputes the basic values with `L` nonbasic at `lambda`.
    pub(crate) fn reset_system(&mut self, q: Col<T>, d: Col<T>, lambda: T) -> Result<(), String> {
        self.data_max = Self::data_max(&q, &d);
        self.d_rows = Self::nonzero_rows(&d);
        self.q = q;
        self.d = d;
        self.lambda = lambda;
        self.refactor()
    }
}

/// Why the start phase failed.
pub(crate) struct StartFailure {
    pub status: crate::path::Status,
    pub message: String,
}

/// The start phase: after the basis `eng` holds (all `w` basic, free variables as
/// far as the rank allows), find a complementary basis feasible at `lambda0` by
/// Lemke's method with an artificial variable and covering vector `c`.
///
/// Lemke's method is itself a parametric path: with `a = max_i (-x_i / c_i)` the
/// system `q + lambda0 d + (a - s) c` is trivially solved at `s = 0`, and `s = a`
/// gives back the problem at `lambda0`. The artificial variable is `z0 = a - s`;
/// "`z0` leaves the basis" is "`s` reaches `a`", which wins every tie.
pub(crate) fn start_phase<T: Scalar>(
    eng: &mut Engine<'_, T>,
    q: &Col<T>,
    d: &Col<T>,
    lambda0: T,
    covering: Option<&Col<T>>,
) -> Result<(), StartFailure> {
    use crate::path::Status;
    let (p, n) = (eng.p, eng.n);
    let dim = p + n;
    // equality rows left to artificial variables must hold already
    // relative to the data alone (no floor at one: q may be tiny)
    let mut scale = T::zero();
    for r in 0..dim {
        scale = scale.max(q[r].abs()).max((lambda0 * d[r]).abs());
    }
    if scale == T::zero() {
        scale = T::one();
    }
    // the covering vector in the units of the right-hand side: only its
    // direction matters (a factor rescales the artificial variable), so it is
    // brought by a power of two (exactly) to within a factor of two of
    // max |q + L0 d|. The artificial variable's start value `a` (and the
    // parameter of the start phase's trace) is then dimensionless, of the
    // order of one for any scale of the data, and the trace's tolerances
    // (floors of one) act on it as on `L`; a uniform scaling of the data by
    // `2^k` leaves the start phase's arithmetic unchanged but for the factor
    let cmax = (0..n).fold(T::zero(), |m, i| {
        m.max(covering.map_or(T::one(), |c| c[i]).abs())
    });
    let cunit = T::from_f64(crate::scaling::exp2i(
        crate::scaling::exponent(scale.to_f64()) - crate::scaling::exponent(cmax.to_f64()),
    ));
    // (the power of two is switched off: it let Siconos enum_fails in f32
    // trace to `reached` with error 1.04; see `scaling` on defect 7)
    let cunit = if SCALE_COVERING { cunit } else { T::one() };
    let c = |i: usize| covering.map_or(T::one(), |c| c[i]) * cunit;
    let tol = eng.tie_tol_value() * scale * T::from_f64(dim.max(1) as f64);
    // equality rows left to artificial variables (fixed at zero) that do not hold
    // at the start: their residual h is removed from the right-hand side at s = 0
    // and brought back as s rises, so the path must find variables that satisfy them
    let mut h = Col::<T>::zeros(dim);
    let mut repair = false;
    for r in 0..dim {
        if let Var::Artificial(k) = eng.basis[r] {
            if eng.x[r].abs() > tol {
                h[k] = -eng.x[r];
                repair = true;
            }
        }
    }
    let mut a = T::zero();
    for r in 0..dim {
        if let Var::W(i) = eng.basis[r] {
            let need = -eng.x[r] / c(i);
            if eng.x[r] < -tol && need > a {
                a = need;
            }
        }
    }
    if a == T::zero() && !repair {
        return Ok(());
    }
    if a == T::zero() {
        a = T::one();
    }
    let mut qa = Col::zeros(dim);
    let mut da = Col::zeros(dim);
    for r in 0..dim {
        qa[r] = q[r] + lambda0 * d[r] + h[r];
        da[r] = -h[r] / a;
    }
    // the covering vector acts on the rows whose slack is basic: B^{-1} (c on
    // those rows) = c on those slacks exactly, even where free variables have
    // taken other complementary rows
    for i in 0..n {
        if eng.row_of(Var::W(i)).is_some() {
            qa[p + i] += a * c(i);
            da[p + i] -= c(i);
        }
    }
    let ill = |m: String| StartFailure {
        status: Status::IllConditioned,
        message: m,
    };
    eng.reset_system(qa, da, T::zero()).map_err(ill)?;
    match eng.trace(Some(a), None) {
        TraceEnd::Reached { driver, theta } => {
            eng.settle(driver, theta).map_err(ill)?;
            if eng.trace_pivots {
                eprintln!(
                    "start phase end: basis {:?} x {:?}",
                    eng.basis,
                    (0..dim).map(|r| eng.x[r].to_f64()).collect::<Vec<_>>()
                );
            }
            eng.reset_system(q.clone(), d.clone(), lambda0)
                .map_err(ill)?;
            if eng.trace_pivots {
                eprintln!(
                    "after reset: x {:?}",
                    (0..dim).map(|r| eng.x[r].to_f64()).collect::<Vec<_>>()
                );
            }
            Ok(())
        }
        TraceEnd::SecondaryRay { driver, col, .. } | TraceEnd::UnboundedRay { driver, col, .. } => {
            Err(ray_evidence(eng, q, d, lambda0, driver, &col))
        }
        TraceEnd::Stalled(m) => Err(StartFailure {
            status: Status::Infeasible,
            message: m,
        }),
        TraceEnd::PivotLimit => Err(StartFailure {
            status: Status::PivotLimit,
            message: format!(
                "pivot limit ({}) reached in the start phase at L = {:e}",
                eng.max_pivots,
                lambda0.to_f64()
            ),
        }),
        TraceEnd::IllConditioned(m) => Err(ill(m)),
    }
}

/// What the start phase's ray at `lambda0` proves ([`crate::evidence`]):
/// `infeasible` with the certificate when its direction is a Farkas
/// certificate; `ill_conditioned` when `M`'s symmetric part is positive
/// definite (a P-matrix: a solution exists, the ray is rounding's doing);
/// otherwise `infeasible` saying that no solution was found and that this is
/// not a proof that none exists.
fn ray_evidence<T: Scalar>(
    eng: &Engine<'_, T>,
    q: &Col<T>,
    d: &Col<T>,
    lambda0: T,
    driver: Var,
    col: &Col<T>,
) -> StartFailure {
    use crate::path::Status;
    let (p, n) = (eng.p, eng.n);
    let at = lambda0.to_f64();
    let head = format!(
        "Lemke's method with the covering vector ended on a secondary ray at L = {at:e}: no solution was found at the start value"
    );
    if p > 0 {
        return StartFailure {
            status: Status::Infeasible,
            message: format!(
                "{head}; with free variables no certificate is checked, so this does not prove that none exists"
            ),
        };
    }
    // the ray's z part: the driver rises by one, basic variables by -col
    let mut v = Col::<T>::zeros(n);
    for (r, b) in eng.basis.iter().enumerate() {
        if let Var::Z(i) = *b {
            v[i] = -col[r];
        }
    }
    if let Var::Z(i) = driver {
        v[i] = T::one();
    }
    let r = Col::from_fn(n, |i| q[i] + lambda0 * d[i]);
    if let Some(why) = crate::evidence::farkas(eng.m, &r, &v) {
        return StartFailure {
            status: Status::Infeasible,
            message: format!("{head}; {why}"),
        };
    }
    if crate::evidence::symmetric_part_positive_definite(eng.m) {
        return StartFailure {
            status: Status::IllConditioned,
            message: format!(
                "{head}, which cannot happen for this M in exact arithmetic: its symmetric part is positive definite, so M is a P-matrix and a solution exists; the ray is an artefact of rounding in {}: use a higher precision",
                T::NAME
            ),
        };
    }
    StartFailure {
        status: Status::Infeasible,
        message: format!(
            "{head}; this does not prove that none exists: the ray's direction is no certificate of infeasibility (v >= 0, M'v <= 0, (q + L0 d)'v < 0 fails), and M's class is not known (a copositive-plus M would give one)"
        ),
    }
}

/// Traces the whole path: start phase at `lambda0`, then `L` rising to `lambda_max`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn run_path<T: Scalar>(
    m: MatrixRef<'_, T>,
    p: usize,
    q: &Col<T>,
    d: &Col<T>,
    lambda0: T,
    lambda_max: Option<T>,
    start: Vec<Var>,
    settings: &Settings<T>,
    method: &'static str,
    free_block: crate::path::FreeBlockInfo,
) -> crate::path::Path<T> {
    use crate::path::{Info, Path, Status};
    let timer = std::time::Instant::now();
    let dim = m.nrows();
    let n = dim - p;
    let mut info = Info {
        method,
        precision: T::NAME,
        free_block,
        ..Info::default()
    };
    let empty = |status: Status, message: String, info: Info| Path {
        status,
        lambda0,
        lambda_max,
        lambda_reached: lambda0,
        breakpoints: Vec::new(),
        segments: Vec::new(),
        end: Point {
            lambda: lambda0,
            z: Col::zeros(n),
            w: Col::zeros(n),
            u: Col::zeros(p),
        },
        ray: None,
        message,
        info,
        final_basis: None,
    };
    // a warm start: the given basis, if nonsingular and feasible at lambda0
    let mut warm_note = String::new();
    let mut warm: Option<Engine<'_, T>> = None;
    if let Some(wb) = &settings.warm_basis {
        let mut wb = wb.clone();
        if wb.len() != dim {
            // a mixed problem's basis for its Schur reduction: z and w only
            wb.retain(|v| matches!(v, Var::W(_) | Var::Z(_)));
        }
        let fits = wb.len() == dim
            && wb.iter().all(|v| match *v {
                Var::W(i) | Var::Z(i) => i < n,
                Var::U(j) | Var::Artificial(j) => j < p,
                Var::Lambda => false,
            });
        if !fits {
            warm_note = "the warm basis does not fit this problem's rows".into();
        } else {
            match Engine::new(m, p, q.clone(), d.clone(), wb, lambda0, settings) {
                Err(msg) => warm_note = format!("warm basis not used: {msg}"),
                Ok(e) => match e.infeasibility() {
                    Some(why) => warm_note = format!("warm basis not used: {why}"),
                    None => warm = Some(e),
                },
            }
        }
    }
    info.warm_start = warm.is_some();
    info.warm_start_note = warm_note;
    if let Some(mut eng) = warm {
        let rec = Recorder::new();
        return finish_path(&mut eng, rec, lambda0, lambda_max, info, timer, true);
    }
    let mut eng = match Engine::new(m, p, q.clone(), d.clone(), start, lambda0, settings) {
        Ok(e) => e,
        Err(msg) => {
            info.solve_seconds = timer.elapsed().as_secs_f64();
            return empty(Status::IllConditioned, msg, info);
        }
    };
    let fill = |info: &mut Info, eng: &Engine<'_, T>| {
        info.pivots = eng.pivots;
        info.degenerate_pivots = eng.degenerate_pivots;
        info.refactorisations = eng.refactorisations;
        info.refinements = eng.refinements;
        info.max_condition = eng.max_cond;
    };
    let started = if method == "wolfe" {
        eng.place_free_in_degenerate_rows()
            .map(|_| ())
            .map_err(|message| StartFailure {
                status: Status::IllConditioned,
                message,
            })
    } else {
        Ok(())
    };
    if let Err(f) =
        started.and_then(|_| start_phase(&mut eng, q, d, lambda0, settings.covering.as_ref()))
    {
        fill(&mut info, &eng);
        info.start_pivots = eng.pivots;
        info.solve_seconds = timer.elapsed().as_secs_f64();
        let mut path = empty(f.status, f.message, info);
        path.end = eng.point(None);
        path.end.lambda = lambda0;
        return path;
    }
    info.start_pivots = eng.pivots;
    // residuals are measured once the path is complete, on the original problem
    // (crate::residual::measure_path)
    let rec = Recorder::new();
    finish_path(&mut eng, rec, lambda0, lambda_max, info, timer, false)
}

/// Traces from the engine's basis (after the start phase, or a warm start) to
/// `lambda_max` and assembles the path.
fn finish_path<T: Scalar>(
    eng: &mut Engine<'_, T>,
    mut rec: Recorder<T>,
    lambda0: T,
    lambda_max: Option<T>,
    mut info: crate::path::Info,
    timer: std::time::Instant,
    warm: bool,
) -> crate::path::Path<T> {
    use crate::path::{Path, Ray, Status};
    let (n, p) = (eng.n, eng.p);
    let fill = |info: &mut crate::path::Info, eng: &Engine<'_, T>| {
        info.pivots = eng.pivots;
        info.degenerate_pivots = eng.degenerate_pivots;
        info.refactorisations = eng.refactorisations;
        info.refinements = eng.refinements;
        info.max_condition = eng.max_cond;
    };
    if warm {
        info.start_pivots = 0;
    }
    let end = eng.trace(lambda_max, Some(&mut rec));
    let ray_of = |eng: &Engine<'_, T>, driver: Var, col: &Col<T>, rate: T| {
        let mut dz = Col::zeros(n);
        let mut dw = Col::zeros(n);
        let mut du = Col::zeros(p);
        let mut set = |v: Var, val: T| match v {
            Var::W(i) => dw[i] = val,
            Var::Z(i) => dz[i] = val,
            Var::U(j) => du[j] = val,
            _ => {}
        };
        for (r, v) in eng.basis.iter().enumerate() {
            set(*v, -col[r]);
        }
        set(driver, T::one());
        Ray {
            start: eng.point(None),
            dz,
            dw,
            du,
            dlambda: rate,
        }
    };
    let mut final_basis = None;
    let (status, end_point, lambda_reached, ray, message) = match end {
        TraceEnd::Reached { driver, theta } => {
            let pt = eng.point(Some((driver, theta)));
            // the end as a vertex at L fixed: the driver takes L's position
            let mut fb = eng.basis.clone();
            if let Some(l) = eng.row_of(Var::Lambda) {
                fb[l] = driver;
            }
            final_basis = Some(fb);
            let l = pt.lambda;
            (Status::Reached, pt, l, None, String::new())
        }
        TraceEnd::UnboundedRay { driver, col, rate } => {
            let r = ray_of(eng, driver, &col, rate);
            (
                Status::UnboundedRay,
                eng.point(None),
                crate::scalar::infinity(),
                Some(r),
                format!(
                    "the last segment, from L = {:e}, holds for every larger L",
                    eng.lambda.to_f64()
                ),
            )
        }
        TraceEnd::SecondaryRay { driver, col, rate } => {
            let r = ray_of(eng, driver, &col, rate);
            let l = eng.lambda;
            (
                Status::SecondaryRay,
                eng.point(None),
                l,
                Some(r),
                format!(
                    "secondary ray at L* = {:e}: the path has no continuation beyond it",
                    l.to_f64()
                ),
            )
        }
        TraceEnd::Stalled(msg) => {
            let l = eng.lambda;
            (Status::SecondaryRay, eng.point(None), l, None, msg)
        }
        TraceEnd::PivotLimit => {
            let l = eng.lambda;
            (
                Status::PivotLimit,
                eng.point(None),
                l,
                None,
                format!(
                    "pivot limit ({}) reached at L = {:e}",
                    eng.max_pivots,
                    l.to_f64()
                ),
            )
        }
        TraceEnd::IllConditioned(msg) => {
            let l = eng.lambda;
            (Status::IllConditioned, eng.point(None), l, None, msg)
        }
    };
    fill(&mut info, eng);
    info.turning_points = rec.turning_points;
    info.solve_seconds = timer.elapsed().as_secs_f64();
    Path {
        status,
        lambda0,
        lambda_max,
        lambda_reached,
        breakpoints: rec.breakpoints,
        segments: rec.segments,
        end: end_point,
        ray,
        message,
        info,
        final_basis,
    }
}
