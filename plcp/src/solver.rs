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
use crate::pivoting::{finish_path, run_path, start_phase, Engine, Recorder};
use crate::scalar::Scalar;
use crate::settings::{Method, Settings};
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
        Ok(Self {
            m,
            settings,
            engine: None,
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
        let n = self.m.nrows();
        for (what, v) in [("q", q), ("d", d)] {
            if v.nrows() != n {
                return Err(PlcpError::Dimension {
                    what: what.into(),
                    expected: format!("{n} entries"),
                    found: format!("{} entries", v.nrows()),
                });
            }
            for i in 0..n {
                crate::problem::check_entry(what, || format!("[{i}]"), v[i])?;
            }
        }
        let timer = std::time::Instant::now();
        let (q, d) = (q.to_owned(), d.to_owned());
        let mut info = Info {
            method: "lemke",
            precision: T::NAME,
            ..Info::default()
        };
        // where the last path ended, if that is a feasible start for these data
        let mut warm = self.engine.take().and_then(|mut eng| {
            match eng.retarget(q.clone(), d.clone(), T::zero()) {
                None => Some(eng),
                Some(why) => {
                    info.warm_start_note = format!("the last basis not used: {why}");
                    None
                }
            }
        });
        let was_warm = warm.is_some();
        if warm.is_none() {
            let start: Vec<Var> = (0..n).map(Var::W).collect();
            let cold = Engine::new(
                self.m.into(),
                0,
                q.clone(),
                d.clone(),
                start,
                T::zero(),
                self.settings,
            )
            .ok()
            .and_then(|mut eng| {
                start_phase(&mut eng, &q, &d, T::zero(), self.settings.covering.as_ref())
                    .ok()
                    .map(|_| eng)
            });
            match cold {
                Some(eng) => {
                    info.start_pivots = eng.pivots;
                    warm = Some(eng);
                }
                None => {
                    // the start failed: the whole path as one call reports how
                    let mut path = run_path(
                        self.m.into(),
                        0,
                        &q,
                        &d,
                        T::zero(),
                        Some(lambda_max),
                        (0..n).map(Var::W).collect(),
                        self.settings,
                        Method::Lemke,
                        "lemke",
                        Default::default(),
                    );
                    self.measure(&mut path, &q, &d);
                    path.info.solve_seconds = timer.elapsed().as_secs_f64();
                    return Ok(path);
                }
            }
        }
        let mut eng = warm.expect("a warm or cold engine");
        info.warm_start = was_warm;
        let mut path = finish_path(
            &mut eng,
            Recorder::new(),
            T::zero(),
            Some(lambda_max),
            info,
            timer,
            was_warm,
        );
        self.measure(&mut path, &q, &d);
        // keep the engine where the path ended, as a complementary basis with
        // L nonbasic: the driver takes L's place (one pivot, no refactorisation)
        if path.status == Status::Reached {
            if let Some(driver) = eng.row_of(Var::Lambda).map(|l| {
                path.final_basis
                    .as_ref()
                    .expect("a reached path has its end basis")[l]
            }) {
                let theta = value_of(&path.end, driver);
                if eng.settle(driver, theta).is_ok() {
                    self.engine = Some(eng);
                }
            } else {
                self.engine = Some(eng);
            }
        }
        path.info.solve_seconds = timer.elapsed().as_secs_f64();
        Ok(path)
    }

    /// The end residual on the data, and the guard of [`crate::solve`].
    fn measure(&self, path: &mut Path<T>, q: &Col<T>, d: &Col<T>) {
        path.info.residual =
            crate::residual::residual_parts(self.m, q.as_ref(), d.as_ref(), 0, &path.end);
        crate::trace::guard_residual(path);
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
