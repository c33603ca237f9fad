//! A solver object for repeated paths on one matrix: the MPC user's loop.
//!
//! With one `M` and a drifting linear term `g_0, g_1, ..., g_K`, step `k` is
//! the path of `w = g_{k-1} + L (g_k - g_{k-1}) + M z` for `L` in `[0, 1]`,
//! started where step `k - 1` ended: at `L = 0` the data `g_{k-1}` are those
//! the last step ended on (`q + 1 d` of that step), so its end basis is a
//! feasible start and no start phase runs. [`Solver`] keeps the pivoting
//! engine between calls, with its basis factorisation: a step solves the new
//! basic values with the factorisation it holds (`O(n^2)` at most), then
//! pivots at `O(n k)` each (`k` basic `z`); it refactorises only on the
//! period of [`crate::Settings::refactor_period`] or when the numbers ask,
//! as a single path does. A basis that is not a feasible start for the data
//! given (the caller changed more than the step) falls back to the cold start.
//!
//! Standard form only (`p = 0`), Lemke's rule, no equilibration (the matrix
//! is used as given), no escalation: each step's end residual is measured on
//! the data, and a success whose residual exceeds `sqrt(eps)` becomes
//! `IllConditioned` as in [`crate::solve`].

use crate::error::PlcpError;
use crate::path::{Info, Path, Point, Status, Var};
use crate::pivoting::{finish_lean, finish_path, run_path, start_phase, Engine, Recorder};
use crate::scalar::Scalar;
use crate::settings::{Method, Settings};
use crate::tolerance::{FACTOR_KEPT_EPS, VALUES_KEPT_EPS};
use faer::{Col, ColRef, MatRef};

/// Repeated paths on one matrix `M`, each started where the last one ended.
///
/// ```
/// use faer::{col, mat};
/// let m = mat![[2.0f64, 1.0], [1.0, 2.0]];
/// let settings = plcp::Settings::<f64>::default();
/// let mut solver = plcp::Solver::new(m.as_ref(), &settings).unwrap();
/// // the LCP at g_0 = (-1, 1), then the step to g_1 = (1, -1)
/// let first = solver.lcp(col![-1.0, 1.0].as_ref()).unwrap();
/// let z0: f64 = first.end.z[0];
/// assert!((z0 - 0.5).abs() < 1e-15);
/// let step = solver.step(col![-1.0, 1.0].as_ref(), col![2.0, -2.0].as_ref()).unwrap();
/// assert_eq!(step.status, plcp::Status::Reached);
/// let z1: f64 = step.end.z[1];
/// assert!((z1 - 0.5).abs() < 1e-15);
/// ```
pub struct Solver<'a, T: Scalar> {
    m: MatRef<'a, T>,
    settings: &'a Settings<T>,
    /// The engine where the last path ended on a complementary basis with `L`
    /// nonbasic; `None` before the first call and after a path that did not
    /// reach its end.
    engine: Option<Engine<'a, T>>,
    /// The breakpoints of the last lean trace (buffers kept between steps).
    rec: Recorder<T>,
    /// The result of the last lean call ([`Self::step_end`]).
    last: StepEnd<T>,
    /// A zero direction for [`Self::lcp_end`].
    zeros: Col<T>,
    /// The end residual's work vectors (kept between steps).
    res: EndResidual<T>,
    /// The principal-pivoting kernel (`plcp/src/principal.rs`), where the
    /// settings allow it: once a step has ended on a complementary basis,
    /// the next steps run on it (its inverse of `M_BB` kept between steps)
    /// while it decides them; `kernel_live` says whether it holds the
    /// solver's basis (else the engine does).
    kernel: Option<crate::principal::Kernel<'a, T>>,
    kernel_live: bool,
    /// The kernel's basic set at the start of a step (the engine's warm
    /// start when the kernel hands the step back).
    kernel_start: Vec<usize>,
}

/// The lean result of one call of the solver ([`Solver::step_end`],
/// [`Solver::lcp_end`], [`Solver::path_end`]): what the MPC loop reads, no
/// segments or breakpoints. Statuses and the residual guard as in [`Path`].
#[derive(Clone, Debug)]
pub struct StepEnd<T: Scalar> {
    /// How the path ended (a success whose end residual exceeds `sqrt(eps)`
    /// is `IllConditioned`, as in [`crate::solve`]).
    pub status: Status,
    /// Why it ended where it did, when not `Reached` (empty otherwise).
    pub message: String,
    /// The end point (`u` empty: standard form).
    pub end: Point<T>,
    /// Pivots of this call (the start phase's included on a cold start).
    pub pivots: usize,
    /// Pivots of the start phase (0 when the call started warm).
    pub start_pivots: usize,
    /// Whether the call started from where the last one ended.
    pub warm: bool,
    /// The end point's residual on the data ([`crate::residual::residual_parts`]).
    pub residual: crate::path::Residual,
    /// Wall time of the call (seconds).
    pub solve_seconds: f64,
}

impl<'a, T: Scalar> Solver<'a, T> {
    /// A solver for `M` (square, finite entries) with these settings (the
    /// method must be Lemke's; `warm_basis` is not used: the solver keeps its
    /// own basis).
    pub fn new(m: MatRef<'a, T>, settings: &'a Settings<T>) -> Result<Self, PlcpError> {
        if m.nrows() != m.ncols() {
            return Err(PlcpError::Dimension {
                what: "M".into(),
                expected: "a square matrix".into(),
                found: format!("{} x {}", m.nrows(), m.ncols()),
            });
        }
        for j in 0..m.ncols() {
            for i in 0..m.nrows() {
                crate::problem::check_entry("M", || format!("({i}, {j})"), m[(i, j)])?;
            }
        }
        settings.validate(m.nrows())?;
        if settings.method != Method::Lemke {
            return Err(PlcpError::Invalid {
                what: "method".into(),
                why: "the solver object traces by Lemke's rule".into(),
            });
        }
        let n = m.nrows();
        Ok(Self {
            m,
            settings,
            engine: None,
            rec: Recorder::lean(),
            last: StepEnd {
                status: Status::Reached,
                message: String::new(),
                end: Point {
                    lambda: T::zero(),
                    z: Col::zeros(n),
                    w: Col::zeros(n),
                    u: Col::zeros(0),
                },
                pivots: 0,
                start_pivots: 0,
                warm: false,
                residual: Default::default(),
                solve_seconds: 0.0,
            },
            zeros: Col::zeros(n),
            res: EndResidual::default(),
            kernel: None,
            kernel_live: false,
            kernel_start: Vec::new(),
        })
    }

    /// The LCP `w = q + M z`, `w, z >= 0`, `w'z = 0` (a path of one point at
    /// `L = 0`), from where the solver stands; the start of a sequence.
    pub fn lcp(&mut self, q: ColRef<'_, T>) -> Result<Path<T>, PlcpError> {
        let d = Col::<T>::zeros(q.nrows());
        self.path(q, d.as_ref(), T::zero())
    }

    /// One step of the loop: the path of `w = q + L d + M z` for `L` in
    /// `[0, 1]`, started where the last call ended.
    pub fn step(&mut self, q: ColRef<'_, T>, d: ColRef<'_, T>) -> Result<Path<T>, PlcpError> {
        self.path(q, d, T::one())
    }

    /// The path of `w = q + L d + M z` for `L` in `[0, lambda_max]`.
    pub fn path(
        &mut self,
        q: ColRef<'_, T>,
        d: ColRef<'_, T>,
        lambda_max: T,
    ) -> Result<Path<T>, PlcpError> {
        T::entry_solver_path(self, q, d, lambda_max)
    }

    /// [`Self::path`]'s body, instantiated in this crate (`entry.rs`).
    pub(crate) fn path_here(
        &mut self,
        q: ColRef<'_, T>,
        d: ColRef<'_, T>,
        lambda_max: T,
    ) -> Result<Path<T>, PlcpError> {
        self.check_data(q, d)?;
        let timer = std::time::Instant::now();
        if let Some(path) = self.kernel_path(q, d, lambda_max, timer) {
            return Ok(path);
        }
        let mut info = Info {
            method: "lemke",
            precision: T::NAME,
            ..Info::default()
        };
        let Some(was_warm) = self.engine_for(q, d, &mut info) else {
            // the start failed: the whole path as one call reports how
            let (q, d) = (q.to_owned(), d.to_owned());
            let mut path = self.cold_path(&q, &d, lambda_max);
            path.info.solve_seconds = timer.elapsed().as_secs_f64();
            return Ok(path);
        };
        let eng = self.engine.as_mut().expect("engine_for leaves the engine");
        let mut path = finish_path(
            eng,
            Recorder::new(),
            T::zero(),
            Some(lambda_max),
            info,
            timer,
            was_warm,
        );
        self.measure(&mut path, q, d);
        // keep the engine where the path ended, as a complementary basis with
        // L nonbasic: the driver takes L's place (one pivot, no refactorisation)
        let eng = self.engine.as_mut().expect("engine_for leaves the engine");
        let kept = path.status == Status::Reached && {
            let worst = path.info.residual.worst();
            if let Some(driver) = eng.row_of(Var::Lambda).map(|l| {
                path.final_basis
                    .as_ref()
                    .expect("a reached path has its end basis")[l]
            }) {
                let theta = value_of(&path.end, driver);
                eng.settle(driver, theta).is_ok() && keep(self.settings, eng, worst)
            } else {
                keep(self.settings, eng, worst)
            }
        };
        if !kept {
            self.engine = None;
        } else {
            self.engine_to_kernel();
        }
        path.info.solve_seconds = timer.elapsed().as_secs_f64();
        Ok(path)
    }

    /// A full step on the kernel, if it is live and decides the step (the
    /// same pivots and bits as [`Self::kernel_step`]); else the engine takes
    /// the step from the kernel's basis at the step's start (`None`).
    fn kernel_path(
        &mut self,
        q: ColRef<'_, T>,
        d: ColRef<'_, T>,
        lambda_max: T,
        timer: std::time::Instant,
    ) -> Option<Path<T>> {
        if !self.kernel_live || self.kernel.is_none() {
            return None;
        }
        let mut rec: crate::principal::Record<T> = (Vec::new(), Vec::new());
        let run = self.kernel_run(q, d, lambda_max, Some(&mut rec));
        let k = self.kernel.as_mut().expect("a live kernel");
        let path = run.ok().map(|pivots| Path {
            status: Status::Reached,
            lambda0: T::zero(),
            lambda_max: Some(lambda_max),
            lambda_reached: lambda_max,
            breakpoints: rec.1,
            segments: rec.0,
            end: k.point_at(lambda_max),
            ray: None,
            message: String::new(),
            info: Info {
                method: "lemke (principal)",
                precision: T::NAME,
                pivots,
                warm_start: true,
                max_condition: k.max_condition(),
                ..Info::default()
            },
            final_basis: Some(k.basis()),
        });
        if let Some(mut path) = path {
            self.measure(&mut path, q, d);
            if path.status == Status::Reached {
                self.after_kernel_step(path.info.residual.worst());
                path.info.solve_seconds = timer.elapsed().as_secs_f64();
                return Some(path);
            }
        }
        self.kernel_fallback(q, d);
        None
    }

    /// The kernel's step `(q, d)` from `L = 0` to `lambda_max` (it must be
    /// live): its pivots, or why it declined. The step's start set is kept
    /// for [`Self::kernel_fallback`].
    fn kernel_run(
        &mut self,
        q: ColRef<'_, T>,
        d: ColRef<'_, T>,
        lambda_max: T,
        rec: Option<&mut crate::principal::Record<T>>,
    ) -> Result<usize, crate::principal::Decline> {
        let max_pivots = self.settings.max_pivots_for(self.m.nrows());
        let k = self.kernel.as_mut().expect("a live kernel");
        self.kernel_start.clear();
        self.kernel_start.extend_from_slice(k.basic_set());
        k.load(q, d, T::zero())?;
        k.run(lambda_max, max_pivots, rec)
    }

    /// The engine takes the step `(q, d)` the kernel did not decide, from the
    /// kernel's basis at the step's start.
    fn kernel_fallback(&mut self, q: ColRef<'_, T>, d: ColRef<'_, T>) {
        let set = std::mem::take(&mut self.kernel_start);
        self.kernel_to_engine(q, d, &set);
        self.kernel_start = set;
    }

    /// Drift control after a kernel step with end residual `worst`: above
    /// [`FACTOR_KEPT_EPS`] `eps` the inverse is computed afresh (and if that
    /// fails no basis is kept: the next call starts cold).
    fn after_kernel_step(&mut self, worst: f64) {
        if worst <= FACTOR_KEPT_EPS * T::eps().to_f64() {
            return;
        }
        let fresh = self.kernel.as_mut().is_some_and(|k| {
            let set = k.basic_set().to_vec();
            k.set_basis(&set).is_ok()
        });
        if !fresh {
            self.kernel_live = false;
            self.engine = None;
        }
    }

    /// [`Self::lcp`] with the lean result [`StepEnd`] (no [`Path`]).
    pub fn lcp_end(&mut self, q: ColRef<'_, T>) -> Result<&StepEnd<T>, PlcpError> {
        let n = q.nrows();
        if self.zeros.nrows() != n {
            self.zeros = Col::zeros(n);
        }
        let d = core::mem::replace(&mut self.zeros, Col::zeros(0));
        let out = self.path_end_inner(q, d.as_ref(), T::zero());
        self.zeros = d;
        out?;
        Ok(&self.last)
    }

    /// [`Self::step`] with the lean result [`StepEnd`]: the end point, the
    /// pivots, the status and the end residual, no [`Path`] (no segments:
    /// the breakpoints are measured and refined as in [`Self::step`], so the
    /// end is the same to the last bit). The result is kept in the solver
    /// and lent out: a step that makes no pivot allocates only for its basic
    /// values and entering column (the engine's solves) and the end residual.
    pub fn step_end(
        &mut self,
        q: ColRef<'_, T>,
        d: ColRef<'_, T>,
    ) -> Result<&StepEnd<T>, PlcpError> {
        self.path_end_inner(q, d, T::one())?;
        Ok(&self.last)
    }

    /// [`Self::path`] with the lean result [`StepEnd`] (see [`Self::step_end`]).
    pub fn path_end(
        &mut self,
        q: ColRef<'_, T>,
        d: ColRef<'_, T>,
        lambda_max: T,
    ) -> Result<&StepEnd<T>, PlcpError> {
        self.path_end_inner(q, d, lambda_max)?;
        Ok(&self.last)
    }

    fn path_end_inner(
        &mut self,
        q: ColRef<'_, T>,
        d: ColRef<'_, T>,
        lambda_max: T,
    ) -> Result<(), PlcpError> {
        T::entry_solver_path_end(self, q, d, lambda_max)
    }

    /// [`Self::path_end_inner`]'s body, instantiated in this crate
    /// (`entry.rs`).
    pub(crate) fn path_end_here(
        &mut self,
        q: ColRef<'_, T>,
        d: ColRef<'_, T>,
        lambda_max: T,
    ) -> Result<(), PlcpError> {
        self.check_data(q, d)?;
        let timer = std::time::Instant::now();
        let n = q.nrows();
        if self.last.end.z.nrows() != n {
            self.last.end = Point {
                lambda: T::zero(),
                z: Col::zeros(n),
                w: Col::zeros(n),
                u: Col::zeros(0),
            };
        }
        if self.kernel_step(q, d, lambda_max) {
            self.last.solve_seconds = timer.elapsed().as_secs_f64();
            return Ok(());
        }
        let mut info = Info::default();
        let Some(was_warm) = self.engine_for(q, d, &mut info) else {
            let (qo, dout) = (q.to_owned(), d.to_owned());
            let path = self.cold_path(&qo, &dout, lambda_max);
            let last = &mut self.last;
            last.status = path.status;
            last.message = path.message;
            last.pivots = path.info.pivots;
            last.start_pivots = path.info.start_pivots;
            last.warm = false;
            last.residual = path.info.residual;
            last.end = path.end;
            last.solve_seconds = timer.elapsed().as_secs_f64();
            return Ok(());
        };
        // (the engine stays in place: moving it in and out of its `Option`
        // copied the struct several times a step)
        let eng = self.engine.as_mut().expect("engine_for leaves the engine");
        let start_pivots = eng.pivots;
        let lean = finish_lean(eng, &mut self.rec, Some(lambda_max), &mut self.last.end);
        let last = &mut self.last;
        last.status = lean.status;
        last.message = lean.message;
        last.warm = was_warm;
        last.start_pivots = if was_warm { 0 } else { start_pivots };
        last.pivots = eng.pivots;
        last.residual = self.res.measure(self.m, q, d, &last.end);
        let limit = T::eps().to_f64().sqrt();
        let worst = last.residual.worst();
        if last.status.is_success() && (worst.is_nan() || worst > limit) {
            // the guard of crate::solve (see crate::trace::guard_residual)
            last.message = format!(
                "the path's largest residual {worst:.3e} (equation {:.1e}, feasibility {:.1e}, complementarity {:.1e}) exceeds sqrt(eps) = {limit:.1e} in {}: the answer cannot be trusted; try a higher precision. {}",
                last.residual.equation,
                last.residual.feasibility,
                last.residual.complementarity,
                T::NAME,
                last.message
            );
            last.status = Status::IllConditioned;
        }
        let kept = last.status == Status::Reached
            && match lean.reached {
                Some((driver, theta)) if eng.row_of(Var::Lambda).is_some() => {
                    eng.settle(driver, theta).is_ok() && keep(self.settings, eng, worst)
                }
                _ => keep(self.settings, eng, worst),
            };
        if !kept {
            self.engine = None;
        } else {
            self.engine_to_kernel();
        }
        self.last.solve_seconds = timer.elapsed().as_secs_f64();
        Ok(())
    }

    /// Whether the settings let the kernel run the loop (as
    /// [`crate::Settings::principal`] for a path).
    fn kernel_allowed(&self) -> bool {
        self.settings.principal
            && self.settings.basis == crate::settings::BasisKind::Block
            && T::NAME == "f64"
    }

    /// One lean step on the kernel, if it is live and decides the step:
    /// `true` with `self.last` filled. Else the engine takes the step from
    /// the kernel's basis at the step's start (`false`).
    fn kernel_step(&mut self, q: ColRef<'_, T>, d: ColRef<'_, T>, lambda_max: T) -> bool {
        if !self.kernel_live || self.kernel.is_none() {
            return false;
        }
        let run = self.kernel_run(q, d, lambda_max, None);
        let k = self.kernel.as_mut().expect("a live kernel");
        if let Ok(pivots) = run {
            k.point_into(lambda_max, &mut self.last.end);
            let residual = self.res.measure(self.m, q, d, &self.last.end);
            let worst = residual.worst();
            let eps = T::eps().to_f64();
            if !(worst.is_nan() || worst > eps.sqrt()) {
                let last = &mut self.last;
                last.status = Status::Reached;
                last.message.clear();
                last.pivots = pivots;
                last.start_pivots = 0;
                last.warm = true;
                last.residual = residual;
                self.after_kernel_step(worst);
                return true;
            }
        }
        self.kernel_fallback(q, d);
        false
    }

    /// The engine at `L = 0` of `(q, d)` on the basis whose basic `z` are
    /// `set` (the kernel's): `None` where it is singular or infeasible (the
    /// next call starts cold). The kernel is no longer live.
    fn kernel_to_engine(&mut self, q: ColRef<'_, T>, d: ColRef<'_, T>, set: &[usize]) {
        self.kernel_live = false;
        let n = self.m.nrows();
        let mut basis: Vec<Var> = (0..n).map(Var::W).collect();
        for &i in set {
            basis[i] = Var::Z(i);
        }
        self.engine = Engine::new(
            self.m.into(),
            0,
            q.to_owned(),
            d.to_owned(),
            basis,
            T::zero(),
            self.settings,
        )
        .ok()
        .filter(|e| e.infeasibility().is_none());
    }

    /// After an engine step that ended on a complementary basis (kept): the
    /// kernel takes that basis for the next step, where it is allowed and
    /// the block of its basic `z` inverts well.
    fn engine_to_kernel(&mut self) {
        if !self.kernel_allowed() {
            return;
        }
        let Some(eng) = self.engine.as_ref() else {
            return;
        };
        if !eng.basis.iter().all(|v| matches!(v, Var::Z(_) | Var::W(_))) {
            return;
        }
        let set: Vec<usize> = eng
            .basis
            .iter()
            .filter_map(|v| match *v {
                Var::Z(i) => Some(i),
                _ => None,
            })
            .collect();
        if self.kernel.is_none() {
            self.kernel = crate::principal::Kernel::new(self.m);
        }
        if let Some(k) = self.kernel.as_mut() {
            if k.set_basis(&set).is_ok() {
                self.kernel_live = true;
                self.engine = None;
            }
        }
    }

    /// The entries of `q` and `d`: `n` each, finite.
    fn check_data(&self, q: ColRef<'_, T>, d: ColRef<'_, T>) -> Result<(), PlcpError> {
        let n = self.m.nrows();
        for (what, v) in [("q", q), ("d", d)] {
            if v.nrows() != n {
                return Err(PlcpError::Dimension {
                    what: what.into(),
                    expected: format!("{n} entries"),
                    found: format!("{} entries", v.nrows()),
                });
            }
            // the conditions of `check_entry` in one pass (a step of the
            // MPC loop is a few microseconds); the entry that fails, if any,
            // is then found again for its message
            let fine =
                |x: T| x.is_finite() && (x == T::zero() || x.to_f64().abs() >= T::min_normal());
            // (over a slice without stopping early: the compiler vectorises it)
            let all_fine = match v.try_as_col_major() {
                // `f32`/`f64` (exact in `f64`): the same conditions without
                // branches, `|x| < inf` for finite
                Some(s) if T::NATIVE => pulp::Arch::new().dispatch(DataFine(s.as_slice())),
                _ => (0..n).all(|i| fine(v[i])),
            };
            if all_fine {
                continue;
            }
            for i in 0..n {
                crate::problem::check_entry(what, || format!("[{i}]"), v[i])?;
            }
        }
        Ok(())
    }

    /// The engine for data `q`, `d` at `L = 0`, left in `self.engine`:
    /// where the last path ended if that is a feasible start (`true`),
    /// else a cold start by Lemke's start phase (`false`); `None` (and no
    /// engine) if the start failed.
    fn engine_for(&mut self, q: ColRef<'_, T>, d: ColRef<'_, T>, info: &mut Info) -> Option<bool> {
        // (retargeted in place: the engine is not moved out of its `Option`)
        if let Some(eng) = self.engine.as_mut() {
            match eng.retarget(q, d, T::zero()) {
                None => {
                    info.warm_start = true;
                    return Some(true);
                }
                Some(why) => {
                    info.warm_start_note = format!("the last basis not used: {why}");
                    self.engine = None;
                }
            }
        }
        let n = self.m.nrows();
        let (q, d) = (q.to_owned(), d.to_owned());
        let start: Vec<Var> = (0..n).map(Var::W).collect();
        let mut eng = Engine::new(
            self.m.into(),
            0,
            q.clone(),
            d.clone(),
            start,
            T::zero(),
            self.settings,
        )
        .ok()?;
        start_phase(&mut eng, &q, &d, T::zero(), self.settings.covering.as_ref()).ok()?;
        info.start_pivots = eng.pivots;
        self.engine = Some(eng);
        Some(false)
    }

    /// The whole path as one call, after a failed start (it reports how).
    fn cold_path(&self, q: &Col<T>, d: &Col<T>, lambda_max: T) -> Path<T> {
        let n = self.m.nrows();
        let mut path = run_path(
            self.m.into(),
            0,
            q,
            d,
            T::zero(),
            Some(lambda_max),
            (0..n).map(Var::W).collect(),
            self.settings,
            Method::Lemke,
            "lemke",
            Default::default(),
        );
        self.measure(&mut path, q.as_ref(), d.as_ref());
        path
    }

    /// The end residual on the data, and the guard of [`crate::solve`].
    fn measure(&self, path: &mut Path<T>, q: ColRef<'_, T>, d: ColRef<'_, T>) {
        path.info.residual = crate::residual::residual_parts(self.m, q, d, 0, &path.end);
        crate::trace::guard_residual(path);
    }
}

/// Whether to keep the engine for the next call, with the drift control of the
/// loop read off the end residual `worst` just measured on the data
/// (measured growth, not a fixed count): at most [`VALUES_KEPT_EPS`]
/// `eps`, the next step starts from the basic values held (no solve,
/// `Engine::retarget`); at most [`FACTOR_KEPT_EPS`] `eps`, the pivots
/// of this call do not count toward the refactorisation period
/// (`Engine::defer_refactor`, up to a cap); above it the basis is
/// refactorised now, and kept only if that succeeds. (With an explicit
/// [`crate::Settings::refactor_period`] the user's period holds.)
fn keep<T: Scalar>(settings: &Settings<T>, eng: &mut Engine<'_, T>, worst: f64) -> bool {
    let eps = T::eps().to_f64();
    eng.values_trusted = worst <= VALUES_KEPT_EPS * eps;
    let clean = worst <= FACTOR_KEPT_EPS * eps;
    if settings.refactor_period.is_none() {
        if clean {
            eng.defer_refactor();
        } else if eng.refactor().is_err() {
            return false;
        }
    }
    true
}

/// Does the one-time work of a process that its first solve would
/// otherwise pay, and returns whether the small solve it makes reached its end.
///
/// The first call in a process costs several times the next one at small
/// sizes (measured at n = 20: 100..230 us against 27..55 us): the CPU
/// feature detection of the SIMD kernels (`cpuid`, some 60 us under
/// virtualisation, where each `cpuid` traps) and the first touch of the
/// code of the engine and of faer's kernels (page faults). `warm_up` runs a
/// PLCP of order 3 (the default settings in `f64`, the block basis; rows of
/// unequal size, so that it is scaled as most data are) and one step of a
/// [`Solver`] on it. No threads are started.
/// It also inverts a matrix of order 64 on the calling thread
/// (the block basis's refactorisation): faer's products beyond `16^3`
/// multiply-adds go to its large kernel, whose first call reads the cache
/// sizes from `/sys` and touches code and packing buffers the small solve
/// never reaches (measured: the first solve at n = 100 took 2.0 ms with the
/// small warm-up, 0.7 ms with this one, the next solve 0.6 ms).
/// A latency-sensitive caller (one small solve per process, or the first
/// step of a control loop) calls it at start-up; `plcp solve` and `plcp
/// sequence` call it before they read their input. It costs what the small
/// solve and the inversion cost (tens of microseconds) each time it is
/// called, about a millisecond the first time.
pub fn warm_up() -> bool {
    let _ = pulp::Arch::new();
    let _ = crate::scalar::fma_detected();
    let a = faer::Mat::<f64>::from_fn(WARM_ORDER, WARM_ORDER, |i, j| {
        if i == j {
            4.0
        } else {
            1.0 / (1.0 + i as f64 + 2.0 * j as f64)
        }
    });
    let inverted = crate::linalg::inverse_par(a.as_ref(), faer::Par::Seq).is_some();
    // the first row 64 times the others (a P-matrix still): Ruiz's scales are
    // not all one, so the scaled copy and the unscaling run too, as they do
    // on most data
    let m = faer::Mat::<f64>::from_fn(3, 3, |i, j| {
        let v = if i == j { 2.0 } else { 0.5 };
        if i == 0 {
            64.0 * v
        } else {
            v
        }
    });
    let q = faer::Col::<f64>::from_fn(3, |i| 1.0 + i as f64);
    let d = faer::Col::<f64>::from_fn(3, |_| -1.0);
    let settings = Settings::<f64>::default();
    let reached = crate::problem::Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
        .and_then(|p| p.with_range(0.0, Some(3.0)))
        .and_then(|p| crate::solve(&p, &settings))
        .is_ok_and(|path| path.status == Status::Reached);
    let stepped = Solver::new(m.as_ref(), &settings).is_ok_and(|mut s| {
        s.lcp_end(q.as_ref()).is_ok() && s.step_end(q.as_ref(), d.as_ref()).is_ok()
    });
    reached && stepped && inverted
}

/// The order of the inversion in [`warm_up`]: its recursive LU reaches
/// faer's large product kernel (`32^3` multiply-adds and more).
const WARM_ORDER: usize = 64;

/// The end residual of a lean step on the data, in buffers kept between
/// steps: the same operations in the same order as
/// [`crate::residual::residual_parts`] with `p = 0` (so the same numbers to
/// the last bit; test `lean_steps_equal_full_steps_and_cold_solves`), one
/// pass over the columns of `M` at the nonzero entries of `z` (`O(n
/// nnz(z))`), compiled for the machine's vector width through pulp's
/// runtime dispatch and with no allocation once the buffers have grown.
/// The full check stays: it is what makes the step's status honest (the
/// engine's own residuals are of the basic solution it computed, this one of
/// the point handed to the caller). Also the measure of a path's start and
/// end points on a dense `M` without free variables
/// ([`crate::residual::measure_ends`]).
pub(crate) struct EndResidual<T: Scalar> {
    acc: Vec<T>,
    big: Vec<T>,
    colbuf: Vec<T>,
    /// `max_i |M_ij|` of each column `j` (`M` is the solver's, fixed), found
    /// the first time `z_j` is nonzero (`None` before): the largest `|M_ij|`
    /// over the columns of nonzero `z` is the largest of these (a maximum
    /// does not depend on the order, and `M` is finite), without the second
    /// pass over those columns each step.
    colmax: Vec<Option<T>>,
    /// `q` and `d` when the caller's are strided.
    qd: Vec<T>,
    /// The nonzero entries of `z` and their indices.
    nz: Vec<(usize, T)>,
}

impl<T: Scalar> Default for EndResidual<T> {
    fn default() -> Self {
        Self {
            acc: Vec::new(),
            big: Vec::new(),
            colbuf: Vec::new(),
            colmax: Vec::new(),
            qd: Vec::new(),
            nz: Vec::new(),
        }
    }
}

impl<T: Scalar> EndResidual<T> {
    pub(crate) fn measure(
        &mut self,
        m: MatRef<'_, T>,
        q: ColRef<'_, T>,
        d: ColRef<'_, T>,
        point: &Point<T>,
    ) -> crate::path::Residual {
        pulp::Arch::new().dispatch(EndResidualPass {
            bufs: self,
            m,
            q,
            d,
            point,
        })
    }
}

/// [`EndResidual::measure`]'s pass, for pulp's dispatch.
struct EndResidualPass<'b, 'm, T: Scalar> {
    bufs: &'b mut EndResidual<T>,
    m: MatRef<'m, T>,
    q: ColRef<'m, T>,
    d: ColRef<'m, T>,
    point: &'b Point<T>,
}

impl<T: Scalar> pulp::WithSimd for EndResidualPass<'_, '_, T> {
    type Output = crate::path::Residual;

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> Self::Output {
        let Self {
            bufs,
            m,
            q,
            d,
            point,
        } = self;
        let n = m.nrows();
        let lambda = point.lambda;
        let EndResidual {
            acc,
            big,
            colbuf,
            colmax,
            qd,
            nz,
        } = bufs;
        // `q` and `d` as slices (copied only if the caller's are strided)
        let (q_s, d_s) = match (q.try_as_col_major(), d.try_as_col_major()) {
            (Some(q), Some(d)) => (q.as_slice(), d.as_slice()),
            _ => {
                qd.clear();
                qd.extend(q.iter().copied());
                qd.extend(d.iter().copied());
                qd.split_at(n)
            }
        };
        let (q_s, d_s) = (&q_s[..n], &d_s[..n]);
        // every row starts at `q + L d` (and its scale), then adds the columns
        acc.clear();
        acc.extend(q_s.iter().zip(d_s).map(|(&qr, &dr)| qr + lambda * dr));
        big.clear();
        big.extend(
            q_s.iter()
                .zip(d_s)
                .map(|(&qr, &dr)| qr.abs().max((lambda * dr).abs())),
        );
        if colmax.len() != n {
            colmax.clear();
            colmax.resize(n, None);
        }
        // the columns at the nonzero `z`, in order, and the largest `|M_ij|`
        // over them
        let z = crate::residual::slice(&point.z);
        nz.clear();
        let mut mz = T::zero();
        let cm_of = |c: ColRef<'_, T>| c.iter().fold(T::zero(), |a, v| a.max(v.abs()));
        for (j, &xj) in z.iter().enumerate() {
            if xj != T::zero() {
                nz.push((j, xj));
                let cm = *colmax[j].get_or_insert_with(|| cm_of(m.col(j)));
                mz = mz.max(cm);
            }
        }
        // `M` column-major, or the columns at the nonzero `z` copied so
        let mc = m.try_as_col_major();
        if mc.is_none() {
            colbuf.clear();
            for &(j, _) in nz.iter() {
                colbuf.extend(m.col(j).iter().copied());
            }
        }
        let column = |p: usize, j: usize| -> &[T] {
            match mc {
                Some(mc) => mc.col(j).as_slice(),
                None => &colbuf[p * n..(p + 1) * n],
            }
        };
        // rows in blocks of `R` whose sums and maxima stay in registers over
        // the columns; each row is `((q + L d) + m_j1 z_j1) + m_j2 z_j2 ...` in
        // the order of the columns and its maximum is order-free: the bits of
        // the column-by-column pass (`residual::residual_parts`). The columns
        // go in chunks of `C` (their slices on the stack, no allocation).
        const R: usize = 16;
        const C: usize = 32;
        let full = n - n % R;
        let mut slots: [&[T]; C] = [&[]; C];
        for (chunk_no, chunk) in nz.chunks(C).enumerate() {
            for (p, &(j, _)) in chunk.iter().enumerate() {
                slots[p] = &column(chunk_no * C + p, j)[..n];
            }
            let cols = &slots[..chunk.len()];
            let mut i0 = 0;
            while i0 < full {
                let (mut a, mut s) = ([T::zero(); R], [T::zero(); R]);
                a.copy_from_slice(&acc[i0..i0 + R]);
                s.copy_from_slice(&big[i0..i0 + R]);
                for (c, &(_, xj)) in cols.iter().zip(chunk) {
                    let xa = xj.abs();
                    let c = &c[i0..i0 + R];
                    for l in 0..R {
                        a[l] += c[l] * xj;
                        s[l] = s[l].max(c[l].abs() * xa);
                    }
                }
                acc[i0..i0 + R].copy_from_slice(&a);
                big[i0..i0 + R].copy_from_slice(&s);
                i0 += R;
            }
            // the last rows column by column (the same order of operations)
            for (c, &(_, xj)) in cols.iter().zip(chunk) {
                let xa = xj.abs();
                for ((a, s), &mij) in acc[full..]
                    .iter_mut()
                    .zip(big[full..].iter_mut())
                    .zip(&c[full..])
                {
                    *a += mij * xj;
                    *s = (*s).max(mij.abs() * xa);
                }
            }
        }
        let (acc, big) = (&acc[..n], &big[..n]);
        let unit = crate::tolerance::residual_unit(q, d);
        let w = &crate::residual::slice(&point.w)[..n];
        let mut eq = 0.0f64;
        for ((&a, &s), &wr) in acc.iter().zip(big).zip(w) {
            let v = a - wr;
            let scale = s.to_f64().max(wr.to_f64().abs());
            eq = eq.max(v.to_f64().abs() / scale.max(unit));
        }
        let mz = mz.to_f64();
        let z_unit = if mz > 0.0 { unit / mz } else { unit };
        crate::residual::signs_in_units(eq, point, z_unit, unit)
    }
}

/// [`Solver::check_data`]'s test of a slice of `f32`/`f64` data (exact in
/// `f64`): every entry finite and zero or at least the smallest normal
/// number, without branches (`|x| < inf` for finite), compiled for the
/// machine's vector width through pulp's dispatch.
struct DataFine<'a, T: Scalar>(&'a [T]);

impl<T: Scalar> pulp::WithSimd for DataFine<'_, T> {
    type Output = bool;

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) -> bool {
        let min = T::min_normal();
        let bad = self.0.iter().fold(0u64, |bad, &x| {
            let a = x.to_f64().abs();
            let ok = (a < f64::INFINITY) & ((a == 0.0) | (a >= min));
            bad | u64::from(!ok)
        });
        bad == 0
    }
}

/// The value of variable `v` at point `pt` (`L` for the parameter).
fn value_of<T: Scalar>(pt: &Point<T>, v: Var) -> T {
    match v {
        Var::Z(i) => pt.z[i],
        Var::W(i) => pt.w[i],
        Var::U(j) => pt.u[j],
        Var::Lambda => pt.lambda,
        Var::Artificial(_) => T::zero(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

    /// The lean end residual's blocked pass gives the bits of
    /// `residual::residual_parts` (the column-by-column pass it replaces):
    /// orders around the block of 16 rows, no nonzero `z`, more nonzero
    /// columns than a chunk of 32, `M` column-major and with strided columns
    /// (a transposed view), `q` and `d` contiguous and strided (rows of a
    /// matrix).
    #[test]
    fn blocked_end_residual_gives_the_plain_bits() {
        let mut unit = crate::test_rng::unit(0x9e37_79b9_7f4a_7c15);
        let mut next = move || unit() - 0.5;
        let mut res = EndResidual::<f64>::default();
        let mut checked = 0;
        for (case, n) in [1usize, 2, 15, 16, 17, 31, 33, 50, 70]
            .into_iter()
            .enumerate()
        {
            let m = Mat::<f64>::from_fn(n, n, |i, j| if i == j { 3.0 } else { 0.0 });
            let m = Mat::<f64>::from_fn(n, n, |i, j| m[(i, j)] + next());
            let mt = m.transpose().to_owned();
            // row 0: q, row 1: d (strided views); and contiguous copies
            let qd = Mat::<f64>::from_fn(2, n, |r, _| if r == 0 { 1e3 * next() } else { next() });
            let (q_c, d_c) = (
                qd.row(0).transpose().to_owned(),
                qd.row(1).transpose().to_owned(),
            );
            for density in [0usize, 1, 2] {
                let z = faer::Col::<f64>::from_fn(n, |i| {
                    let v = 2.0 * next() + 1.5;
                    match density {
                        0 => 0.0,
                        1 => v,
                        _ if (i + case) % 3 == 0 => v,
                        _ => 0.0,
                    }
                });
                let w = faer::Col::<f64>::from_fn(n, |_| next().abs());
                let point = Point {
                    lambda: 0.75,
                    z,
                    w,
                    u: faer::Col::zeros(0),
                };
                for (mm, strided) in [
                    (m.as_ref(), false),
                    (mt.as_ref().transpose(), false),
                    (m.as_ref(), true),
                    (mt.as_ref().transpose(), true),
                ] {
                    let (q, d) = if strided {
                        (qd.row(0).transpose(), qd.row(1).transpose())
                    } else {
                        (q_c.as_ref(), d_c.as_ref())
                    };
                    // the transposed view has strided columns (the copy path)
                    if n > 1 && mm.col_stride() == 1 {
                        assert!(mm.try_as_col_major().is_none());
                    }
                    let want = crate::residual::residual_parts(mm, q, d, 0, &point);
                    let got = res.measure(mm, q, d, &point);
                    for (g, w) in [
                        (got.equation, want.equation),
                        (got.feasibility, want.feasibility),
                        (got.complementarity, want.complementarity),
                    ] {
                        assert_eq!(
                            g.to_bits(),
                            w.to_bits(),
                            "n = {n}, density {density}, strided {strided}"
                        );
                    }
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 9 * 3 * 4);
    }
}
