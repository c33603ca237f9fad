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

/// The most pivots [`Engine::defer_refactor`] lets pass without a
/// refactorisation (which also renews the condition estimate that sets the
/// pivot noise level and the refinement).
const DEFER_REFACTOR_CAP: usize = 1000;
/// The pivot tolerance relative to the z/w rows (see `ratio_test`): off.
const PIVOT_TOL_ON_COMP_ROWS: bool = false;
/// The covering vector brought to the right-hand side's power of two: off.
const SCALE_COVERING: bool = true;

mod cycle;
mod free;
mod phases;
mod ratio;
mod refine;
#[cfg(test)]
mod tests;
mod trace;

pub(crate) use phases::{finish_lean, finish_path, run_path, start_phase};

use crate::basis::{
    apply, var_column, var_column_into, BasisFactor, BlockInverse, DenseInverse, SparseLu,
};
use crate::linalg::{col_slice, col_slice_mut};
use crate::matrix::MatrixRef;
use crate::path::{Breakpoint, Point, Residual, Segment, Var};
use crate::scalar::Scalar;
use crate::settings::Settings;
use core::cell::{Cell, RefCell};
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
    /// Whether segments are kept: a lean trace (the solver object's step,
    /// [`crate::solver::Solver::step_end`]) records the breakpoints alone, so
    /// that their residuals are measured and refined as in a full path (the
    /// same numbers) without the six columns a segment allocates.
    keep_segments: bool,
}

impl<T: Scalar> Recorder<T> {
    pub(crate) fn new() -> Self {
        Self {
            // room for two segments (768 bytes in f64): a `Vec`'s first push
            // would reserve four (1.5 kB), a request glibc's malloc serves
            // from its large bins after consolidating the freed small chunks,
            // 5 k instructions of the 54 k a tiny call took (n = 2, one pivot)
            segments: Vec::with_capacity(2),
            breakpoints: Vec::new(),
            turning_points: 0,
            last_sign: 0,
            keep_segments: true,
        }
    }

    /// A recorder of breakpoints alone (see `keep_segments`).
    pub(crate) fn lean() -> Self {
        Self {
            keep_segments: false,
            ..Self::new()
        }
    }

    /// Empties the recorder for another trace (its buffers kept).
    pub(crate) fn clear(&mut self) {
        self.segments.clear();
        self.breakpoints.clear();
        self.turning_points = 0;
        self.last_sign = 0;
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
    /// Pivots whose count toward the refactorisation period was waived by
    /// [`Self::defer_refactor`] since the last refactorisation.
    deferred: usize,
    /// The basic values passed a measure on the data at the solver's tight
    /// level (set by [`crate::solver::Solver`], read once by [`Self::retarget`]).
    pub(crate) values_trusted: bool,
    /// The last condition estimate says entering columns need a refinement step.
    refine_columns: bool,
    /// The last condition estimate says the basic values need residuals in the
    /// wide type ([`crate::tolerance::WIDE_REFINE_COND_EPS`]).
    refine_wide: bool,
    /// The basis representation refines its own solves (cheaper than
    /// [`Engine::refine_column`]: the block basis refines on `S` alone).
    refine_inside: bool,
    /// The largest condition estimate of a basis of the path: at each
    /// refactorisation, and at its end ([`Self::estimate_end_condition`]).
    pub max_cond: f64,
    /// The basis changed since its condition was last estimated (a pivot
    /// since the last refactorisation or end estimate).
    cond_stale: bool,
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
    /// `B x` and the row scales of `plain_residual_into`, kept between
    /// pivots as `wide_acc` (`refine.rs`).
    plain_acc: RefCell<(Vec<T>, Vec<T>)>,
    /// Buffers of length `p + n` kept between pivots (the entering column,
    /// the column `a_v` or right-hand side solved for, `B x`): a pivot
    /// allocates none (see [`crate::basis::BasisFactor::solve_into`]).
    col_buf: Col<T>,
    a_buf: Col<T>,
    bx_buf: Col<T>,
    /// The variable whose column `B^{-1} a_v` `col_buf` holds, with the
    /// pivot and refactorisation counts it was solved at: set where a trace
    /// reaches its end (the driver's entering column), so that
    /// [`Self::settle`] pivots it in without solving for it again while the
    /// basis is the same (the counts unchanged); cleared by what writes
    /// `col_buf` or changes `d` (the values solve, a new trace, new data).
    col_of: Option<(Var, usize, usize)>,
    /// The basic values of [`Self::values_and_lambda_column`] before they
    /// are snapped into `x` (a buffer kept between steps).
    x_buf: Col<T>,
    /// The fingerprints of the bases of the current trace ([`cycle`]).
    cycle: cycle::CycleGuard,
    /// The condition estimate of the last refactorisation (near ties, `ratio.rs`).
    cond: f64,
    /// Near ties of the ratio test read again with refined values: (resolved
    /// into the exact order, left undecided); see `ratio.rs`.
    pub near_ties: Cell<(usize, usize)>,
    /// An undecided near tie of the last ratio test: why the trace stops
    /// `ill_conditioned` (taken by the trace).
    tie_alarm: RefCell<Option<String>>,
    /// Refactorise after the next pivot (one on an entry below the noise).
    refactor_after: Cell<bool>,
    /// Recompute the values from the updated factor after the next pivot
    /// (a separated near tie on a sparse basis, pivot entry not small).
    values_after: Cell<bool>,
}

/// The two accumulators of [`Engine::wide_residual_pair`] (values, column).
type WideAccumulators<T> = (Vec<<T as Scalar>::Wide>, Vec<<T as Scalar>::Wide>);

/// `max_i |v_i|` (zero for an empty slice) in four independent chains: a
/// single chain of compares waits on each one, and the engine takes this
/// maximum of vectors of length `p + n` several times per pivot.
pub(crate) fn max_abs<T: Scalar>(v: &[T]) -> T {
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

fn is_comp(v: Var) -> bool {
    matches!(v, Var::W(_) | Var::Z(_))
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
                crate::settings::BasisKind::Block => {
                    Box::new(BlockInverse::new(dim).with_threads(settings.threads))
                }
                crate::settings::BasisKind::Dense => Box::new(DenseInverse::new(dim)),
                crate::settings::BasisKind::Sparse => Box::new(SparseLu::new(dim)),
            },
            x: Col::zeros(dim),
            lambda,
            settings,
            max_pivots: settings.max_pivots_for(dim),
            pivots: 0,
            degenerate_pivots: 0,
            refactorisations: 0,
            refinements: 0,
            since_refactor: 0,
            deferred: 0,
            values_trusted: false,
            refine_columns: false,
            refine_wide: false,
            refine_inside: false,
            max_cond: 1.0,
            cond_stale: false,
            pivot_tol: T::from_f64(settings.pivot_tol_eps) * T::eps(),
            noise: T::from_f64(settings.pivot_tol_eps) * T::eps(),
            trace_pivots: std::env::var_os("PLCP_TRACE").is_some(),
            tie_tol: T::from_f64(settings.tie_tol_eps) * T::eps(),
            residual_owed: false,
            wide_acc: RefCell::new((Vec::new(), Vec::new())),
            plain_acc: RefCell::new((Vec::new(), Vec::new())),
            // allocated by their first use (see `take_buf`)
            col_buf: Col::zeros(0),
            a_buf: Col::zeros(0),
            bx_buf: Col::zeros(0),
            col_of: None,
            x_buf: Col::zeros(0),
            cycle: cycle::CycleGuard::default(),
            cond: 1.0,
            near_ties: Cell::new((0, 0)),
            tie_alarm: RefCell::new(None),
            refactor_after: Cell::new(false),
            values_after: Cell::new(false),
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

    /// [`Self::column`] into `out` (no allocation with the block basis).
    pub(crate) fn column_into(&self, v: Var, out: &mut Col<T>) {
        self.factor.column_into(self.m, &self.d, self.p, v, out);
    }

    /// The kept buffer `buf` (one of the engine's), taken out to be written
    /// while the engine is borrowed; put back with `self.<buf> = it`.
    fn take_buf(buf: &mut Col<T>) -> Col<T> {
        core::mem::replace(buf, Col::zeros(0))
    }

    /// Rebuilds the factorisation and the basic values (drift correction).
    pub(crate) fn refactor(&mut self) -> Result<(), String> {
        // estimated here; or, if the basis is singular, left as the factor's
        // failure found it (not to be solved with, the path ends there)
        self.cond_stale = false;
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
        self.deferred = 0;
        self.max_cond = self.max_cond.max(cond);
        self.cond = cond.max(1.0); // (an empty block reports 0: B = I)
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
        self.values_from_factor();
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

    /// Estimates the condition of the basis the path ends on, if it changed
    /// since the last estimate, into [`Self::max_cond`]: the refactorisations
    /// alone sample it every `refactor_period` pivots, and a shorter path
    /// reported its starting basis (the identity: 1), which understated how
    /// well the answer is known and let a doubtful path escape escalation
    /// (`escalate.rs`). `O(dim^2)` with the dense inverse, `O(dim k)` with the
    /// block one (about eleven solves, [`crate::basis::BasisFactor::condition`]);
    /// nothing when the last pivot was followed by a refactorisation.
    /// The bases between refactorisations inside the path stay unsampled.
    pub(crate) fn estimate_end_condition(&mut self) {
        if !self.cond_stale {
            return;
        }
        self.cond_stale = false;
        let cond = self.factor.condition(self.m, &self.d, self.p, &self.basis);
        if !cond.is_nan() {
            self.max_cond = self.max_cond.max(cond);
        }
    }

    /// The basic values `x = B^{-1} (q + L d)` from the current factorisation,
    /// tiny negatives of sign-constrained basics (drift) snapped to zero.
    fn values_from_factor(&mut self) {
        let mut rhs = Self::take_buf(&mut self.a_buf);
        self.rhs_into(&mut rhs);
        let mut xnew = Self::take_buf(&mut self.col_buf);
        self.col_of = None;
        self.factor.solve_into(&rhs, &mut xnew);
        self.a_buf = rhs;
        self.set_values(&xnew);
        self.col_buf = xnew;
    }

    /// [`Self::values_from_factor`] and the column of `L` (`B^{-1} a_L`,
    /// left in `col_buf` for the trace's first step, `col_of`) in one
    /// two-column solve ([`BasisFactor::solve2_into`]): the solver's step
    /// after its data changed (issue 20). Only where the trace would not
    /// refine the column (`refine_columns` off).
    fn values_and_lambda_column(&mut self) {
        if self.refine_columns {
            self.values_from_factor();
            return;
        }
        let mut rhs = Self::take_buf(&mut self.a_buf);
        self.rhs_into(&mut rhs);
        let mut a_l = Self::take_buf(&mut self.bx_buf);
        var_column_into(self.m, &self.d, self.p, Var::Lambda, &mut a_l);
        let mut xnew = Self::take_buf(&mut self.x_buf);
        let mut col = Self::take_buf(&mut self.col_buf);
        self.factor.solve2_into(&rhs, &a_l, &mut xnew, &mut col);
        self.a_buf = rhs;
        self.bx_buf = a_l;
        self.set_values(&xnew);
        self.x_buf = xnew;
        self.col_buf = col;
        self.col_of = Some((Var::Lambda, self.pivots, self.refactorisations));
    }

    /// `x` from freshly solved values `xnew`, tiny negatives of
    /// sign-constrained basics (drift) snapped to zero.
    fn set_values(&mut self, xnew: &Col<T>) {
        // snap tiny negatives of sign-constrained basics (drift) to zero
        let tol = self.tie_tol * self.xscale();
        // (over slices: the MPC step's values pass, without index checks)
        let x = col_slice_mut(&mut self.x);
        for ((x, &v), var) in x.iter_mut().zip(col_slice(xnew)).zip(&self.basis) {
            let snap = match var {
                Var::W(_) | Var::Z(_) => v < T::zero() && -v <= tol,
                Var::Artificial(_) => v.abs() <= tol,
                _ => false,
            };
            *x = if snap { T::zero() } else { v };
        }
        if let Some(l) = self.row_of(Var::Lambda) {
            // L stays the path's exact parameter; the recomputed value measures drift
            self.x[l] = self.lambda;
        }
    }

    /// A new right-hand side and direction on the same `M`, the basis and its
    /// factorisation kept (no refactorisation): the basic values are solved
    /// anew with `L` nonbasic at `lambda`, and the counters start again. For
    /// the solver object ([`crate::solver::Solver`]): returns why the basis
    /// is not a feasible start for the new data, `None` if it is one.
    /// The data are copied into the engine's own columns (no allocation).
    pub(crate) fn retarget(
        &mut self,
        q: faer::ColRef<'_, T>,
        d: faer::ColRef<'_, T>,
        lambda: T,
    ) -> Option<String> {
        if self.row_of(Var::Lambda).is_some() {
            return Some("L is basic".into());
        }
        // the new data at `lambda` continue the old at the engine's `L` (the
        // MPC loop: q_k = q_{k-1} + d_{k-1}, to the rounding of that sum):
        // the basic values are those the engine holds, so the solve for them
        // is skipped (its drift correction is the solver's measured policy,
        // see `defer_refactor`)
        let continues = core::mem::take(&mut self.values_trusted) && self.continues(q, d, lambda);
        self.col_of = None;
        self.q.as_mut().copy_from(q);
        self.d.as_mut().copy_from(d);
        self.data_max = Self::data_max(&self.q, &self.d);
        self.d_rows.clear();
        for (i, &v) in col_slice(&self.d).iter().enumerate() {
            if v != T::zero() {
                self.d_rows.push(i);
            }
        }
        self.lambda = lambda;
        self.pivots = 0;
        self.degenerate_pivots = 0;
        self.refactorisations = 0;
        self.refinements = 0;
        self.near_ties.set((0, 0));
        self.residual_owed = false;
        if !continues {
            self.values_and_lambda_column();
        }
        self.infeasibility()
    }

    /// Whether `q + lambda d` equals the engine's right-hand side at its
    /// current `L` (`q_old + L d_old`, `L` nonbasic) entry by entry to one
    /// rounding of the sums (`2 eps` of their largest term: `g_{k-1}` and
    /// `g_{k-2} + (g_{k-1} - g_{k-2})` differ by that): the basic values it holds
    /// solve the new data to within that rounding, a backward error the
    /// fresh solve has too.
    fn continues(&self, q: faer::ColRef<'_, T>, d: faer::ColRef<'_, T>, lambda: T) -> bool {
        if self.x.nrows() != self.dim || q.nrows() != self.dim {
            return false;
        }
        let tol = T::from_f64(2.0) * T::eps();
        let same = |q: T, d: T, a: T, od: T| {
            let new = q + lambda * d;
            let (a, b) = (a, self.lambda * od);
            let old = a + b;
            // one rounding of either sum: relative to its largest term
            let size = new.abs().max(a.abs()).max(b.abs());
            (new == old) | ((new - old).abs() <= tol * size)
        };
        match (q.try_as_col_major(), d.try_as_col_major()) {
            // over slices without stopping early (the compiler vectorises it)
            (Some(q), Some(d)) => {
                let (q, d) = (&q.as_slice()[..self.dim], &d.as_slice()[..self.dim]);
                let (oq, od) = (col_slice(&self.q), col_slice(&self.d));
                q.iter()
                    .zip(d)
                    .zip(oq.iter().zip(od))
                    .fold(true, |ok, ((&q, &d), (&a, &od))| ok & same(q, d, a, od))
            }
            _ => (0..self.dim).all(|i| same(q[i], d[i], self.q[i], self.d[i])),
        }
    }

    /// After a clean measure of the end point on the data (the solver object,
    /// [`crate::solver::Solver`]): the pivots since the last refactorisation
    /// no longer count toward the periodic one, up to
    /// [`DEFER_REFACTOR_CAP`] pivots in all. In the MPC loop a refactorisation
    /// every 50 pivots cost about a tenth of a step; the end residual, measured
    /// every step, is the evidence of drift the period stands in for.
    pub(crate) fn defer_refactor(&mut self) {
        self.deferred += self.since_refactor;
        if self.deferred < DEFER_REFACTOR_CAP {
            self.since_refactor = 0;
        }
    }

    /// Why the current basic solution is not a feasible start (a basic `z` or `w`
    /// negative, or an artificial variable nonzero, beyond the tie tolerance), or
    /// `None` if it is one.
    pub(crate) fn infeasibility(&self) -> Option<String> {
        let scale = self.xscale();
        let tol = self.tie_tol * scale;
        // the common answer (feasible) in one pass over slices; the
        // offending row, if any, is then found again for its message
        let fine = col_slice(&self.x)
            .iter()
            .zip(&self.basis)
            .all(|(&x, v)| match v {
                Var::W(_) | Var::Z(_) => x.is_finite() && x >= -tol,
                Var::Artificial(_) => x.is_finite() && x.abs() <= tol,
                _ => x.is_finite(),
            });
        if fine {
            return None;
        }
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

    /// [`Self::rhs`] into `out` (resized to `p + n` if it is not).
    fn rhs_into(&self, out: &mut Col<T>) {
        if out.nrows() != self.dim {
            *out = Col::zeros(self.dim);
        }
        if self.row_of(Var::Lambda).is_some() {
            out.as_mut().copy_from(self.q.as_ref());
        } else {
            let (q, d, l) = (col_slice(&self.q), col_slice(&self.d), self.lambda);
            for ((o, &q), &d) in col_slice_mut(out).iter_mut().zip(q).zip(d) {
                *o = q + l * d;
            }
        }
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

    /// [`Self::point`] written into `pt` (its columns of the right lengths:
    /// no allocation).
    pub(crate) fn point_into(&self, driver: Option<(Var, T)>, pt: &mut Point<T>) {
        pt.lambda = self.lambda;
        pt.z.as_mut().fill(T::zero());
        pt.w.as_mut().fill(T::zero());
        pt.u.as_mut().fill(T::zero());
        let Point { z, w, u, .. } = pt;
        self.scatter(driver, z, w, u);
    }

    /// The basic values, and `driver` at its value, written into zeroed
    /// `(z, w, u)`.
    fn scatter(&self, driver: Option<(Var, T)>, z: &mut Col<T>, w: &mut Col<T>, u: &mut Col<T>) {
        // over slices (the same stores without faer's checked indexing: the
        // end point of every MPC step)
        let (z, w, u) = (col_slice_mut(z), col_slice_mut(w), col_slice_mut(u));
        let mut set = |v: Var, val: T| match v {
            Var::W(i) => w[i] = val,
            Var::Z(i) => z[i] = val,
            Var::U(j) => u[j] = val,
            _ => {}
        };
        for (v, &x) in self.basis.iter().zip(col_slice(&self.x)) {
            set(*v, x);
        }
        if let Some((v, t)) = driver {
            set(v, t);
        }
    }

    /// Values of `(z, w, u)` now, with `driver` at `theta` ([`Self::point_into`]
    /// on new zero columns, without filling them with zeros again).
    pub(crate) fn point(&self, driver: Option<(Var, T)>) -> Point<T> {
        let (mut z, mut w, mut u) = (Col::zeros(self.n), Col::zeros(self.n), Col::zeros(self.p));
        self.scatter(driver, &mut z, &mut w, &mut u);
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
        {
            // over slices, as `scatter` (faer's checked indexing was an
            // assert per entry of `col` and per store)
            let (z, w, u) = (
                col_slice_mut(&mut dz),
                col_slice_mut(&mut dw),
                col_slice_mut(&mut du),
            );
            let mut set = |v: Var, val: T| match v {
                Var::W(i) => w[i] = val,
                Var::Z(i) => z[i] = val,
                Var::U(j) => u[j] = val,
                _ => {}
            };
            for (v, &c) in self.basis.iter().zip(col_slice(col)) {
                set(*v, -c / rate);
            }
            set(driver, T::one() / rate);
        }
        (dz, dw, du)
    }

    /// The complementary basis of a segment: `W(i)` where `w_i` is basic or
    /// the driver, else `Z(i)`; then the basic free variables.
    fn segment_basis(&self, driver: Var) -> Vec<Var> {
        let (n, p) = (self.n, self.p);
        let mut b = Vec::with_capacity(n + p);
        for (i, r) in self.pos[..n].iter().enumerate() {
            if r.is_some() || driver == Var::W(i) {
                b.push(Var::W(i));
            } else {
                b.push(Var::Z(i));
            }
        }
        for (j, r) in self.pos[2 * n..2 * n + p].iter().enumerate() {
            if r.is_some() {
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
        if !rec.keep_segments {
            return;
        }
        if rec.segments.len() == rec.segments.capacity() {
            // room for about one segment per two rows at once: a path has
            // about that many pivots on everyday problems, and each doubling
            // from the first two was a `realloc` of about 3 k instructions
            // (glibc consolidates its freed small chunks for it), three of
            // them at n = 20 (issue 20)
            let len = rec.segments.len();
            rec.segments.reserve(len.max((self.n + self.p) / 2 + 2));
        }
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

    pub(crate) fn tie_tol_value(&self) -> T {
        self.tie_tol
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
