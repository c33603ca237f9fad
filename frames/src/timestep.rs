//! An independent time-stepping integrator for the rigid-plastic frame: each
//! step a velocity-level LCP solved with plcp, warm-started from the previous
//! step's basis. Hinges may unload here: nothing forces the plastic rates to
//! grow, so it checks the paper's claim (a hinge once active stays active) and
//! continues the response where the PLCP path of system (9) stops being valid.
//!
//! # The step
//!
//! From `(q_n, v_n)` at `t_n`, a step of size `h` (backward Euler at velocity
//! level, Moreau-Jean) finds the velocities `v`, the mean member forces `X` over
//! the step, the plastic rates `xdot` and plastic potentials `y` from
//!
//! ```text
//! (a)  0 = -(M_q / h) v - A^T X + (M_q / h) v_n + a_o lambda_n     impulse balance over the step
//! (b)  0 = -A v + T N xdot                                           rigid members: rates at hinges only
//! (c)  y = X* - N^T T^T X,   y >= 0,  xdot >= 0,  y' xdot = 0
//!      q_{n+1} = q_n + h v,   plastic multipliers x*_{n+1} = x*_n + h xdot
//! ```
//!
//! with `lambda_n = (1/h) * integral of lambda(t) over [t_n, t_n + h]`, exact for
//! the scene's history. It is the KKT system of the convex QP
//! `min 1/2 (v - v_n)' M_q (v - v_n) / h - lambda_n a_o' v + X*' xdot` s.t.
//! `A v = T N xdot`, `xdot >= 0`: the same block structure as system (9), with
//! `M_q / h` for `M_q` and the velocities in place of the accelerations. `M_q`
//! is singular (rotations carry no mass) and, for an indeterminate frame, so is
//! the free block, so the step is solved by Wolfe's long form (plcp's mixed
//! form, [`plcp::Method::Wolfe`]). From rest and below the collapse load the
//! QP's minimum is `v = 0` (no dissipation is worth a mechanism the load cannot
//! drive): the rigid phase is well posed. `X` is not unique while the frame is
//! partly rigid; `v` is unique on the coordinates with mass.
//!
//! plcp solves it in impulse form: row (a) times `h`, the impulse `P = h X`
//! and `h y` as unknowns. The matrix is then exactly system (9)'s, whatever
//! `h` (with `M_q / h` in it, `h = 1e-5` of the response time gave step
//! residuals of 1e-8 and spurious flow in the rigid phase of indeterminate
//! frames), and the right-hand side `(M_q v_n + h lambda_n a_o, 0, h X*)` is
//! divided by its largest entry (the LCP is homogeneous in it) and the answer
//! scaled back.
//!
//! All steps share the matrix, so step `n + 1` is the plcp
//! path from step `n`'s right-hand side (`L = 0`) to its own (`L = 1`),
//! `d = q_{n+1} - q_n`, started from step `n`'s final basis
//! ([`plcp::Settings::warm_basis`]): it pivots only where the set of flowing
//! hinges changes. A warm path that does not reach `L = 1` is redone cold and
//! counted. `h` is adjusted so that the steps end exactly at `t_end`.
//!
//! # What it reads
//!
//! A yield mode *flows* on a step when `xdot > rate_tol * scale` (`scale`: the
//! largest velocity or rate of the step, or the velocity the step's load
//! impulse would give the heaviest mass, whichever is largest). Events per mode:
//! [`ModeEventKind::FlowStarted`] and [`ModeEventKind::FlowStopped`], the
//! latter a deactivation (the rate of a flowing hinge back to zero: system (9)
//! never lets a rate decrease), and [`ModeEventKind::FlowDecelerated`] when a
//! flowing mode's rate first falls below its running peak by more than
//! `decel_tol` (`x*_dd < 0`, which system (9) forbids: where the path of (9)
//! reads an unloading, the physical hinge decelerates). The largest relative
//! drop of each mode's rate below its peak is [`StepResponse::rate_drop`].
//!
//! ```
//! use frames::timestep::{StepOptions, StepState, TimeStepping};
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cantilever.toml");
//! let scene = frames::Scene::from_file(path).unwrap();
//! let system = frames::System::assemble(&scene.frame);
//! let options = StepOptions { h: 0.01, t_end: 5.0, ..StepOptions::default() };
//! let ts = TimeStepping::new(&system, &scene.history, &options).unwrap();
//! let r = ts.run(&StepState::rest(&system)).unwrap();
//! assert!(r.outcome.is_completed());
//! // the root hinge starts to flow at the collapse load Lambda = t = 1, to O(h)
//! let first = r.activations().next().unwrap();
//! assert!((first.t - 1.0).abs() <= 0.011, "{}", first.t);
//! assert!(r.deactivations().is_empty());
//! ```

use crate::analysis::Analysis;
use crate::assemble::{Sign, System};
use crate::error::FramesError;
use crate::integrate::{integrate, AffinePiece};
use crate::model::History;
use crate::report::format_number;
use faer::{Col, Mat};
use plcp::{Method, Plcp, Settings, Status, Var};
use serde_json::{json, Value};

/// Options of a time-stepping run.
#[derive(Clone, Debug, PartialEq)]
pub struct StepOptions {
    /// Step size (adjusted so that a whole number of steps ends exactly at `t_end`).
    pub h: f64,
    /// End time.
    pub t_end: f64,
    /// Relative threshold for a plastic rate to count as flowing (default `1e-9`).
    pub rate_tol: f64,
    /// Keep the state every `record_every` steps (and always the last; `0`:
    /// only the start and the end). Default `1`.
    pub record_every: usize,
    /// Warm-start each step from the previous basis (default `true`; `false`
    /// solves every step cold, for comparison).
    pub warm: bool,
    /// Relative drop of a flowing mode's rate below its running peak that is
    /// reported as [`ModeEventKind::FlowDecelerated`] (default `1e-6`).
    pub decel_tol: f64,
}

impl Default for StepOptions {
    fn default() -> Self {
        Self {
            h: 1e-2,
            t_end: 1.0,
            rate_tol: 1e-9,
            record_every: 1,
            warm: true,
            decel_tol: 1e-6,
        }
    }
}

impl StepOptions {
    /// Checks the ranges: `h`, `t_end` positive and finite, `rate_tol` and
    /// `decel_tol` in `(0, 1)`.
    pub fn validate(&self) -> Result<(), FramesError> {
        if !(self.h.is_finite() && self.h > 0.0) {
            return Err(FramesError::invalid(
                "step size h",
                format!("must be positive and finite, got {}", self.h),
            ));
        }
        if !(self.t_end.is_finite() && self.t_end > 0.0) {
            return Err(FramesError::invalid(
                "t_end",
                format!("must be positive and finite, got {}", self.t_end),
            ));
        }
        if !(self.decel_tol > 0.0 && self.decel_tol < 1.0) {
            return Err(FramesError::invalid(
                "decel_tol",
                format!("must be in (0, 1), got {}", self.decel_tol),
            ));
        }
        if !(self.rate_tol > 0.0 && self.rate_tol < 1.0) {
            return Err(FramesError::invalid(
                "rate_tol",
                format!("must be in (0, 1), got {}", self.rate_tol),
            ));
        }
        Ok(())
    }
}

/// The state between steps, in the coordinates and yield modes of a [`System`].
#[derive(Clone, Debug, PartialEq)]
pub struct StepState {
    /// Time.
    pub t: f64,
    /// Generalised displacements `q`.
    pub q: Vec<f64>,
    /// Generalised velocities `v = q_dot`.
    pub v: Vec<f64>,
    /// Plastic rates `x*_dot`, one per yield mode.
    pub rate: Vec<f64>,
    /// Plastic multipliers `x*` (accumulated plastic rotation), one per yield mode.
    pub plastic: Vec<f64>,
}

impl StepState {
    /// At rest at `t = 0`.
    pub fn rest(system: &System) -> Self {
        let (nb, p) = (system.coordinates.len(), system.modes.len());
        Self {
            t: 0.0,
            q: vec![0.0; nb],
            v: vec![0.0; nb],
            rate: vec![0.0; p],
            plastic: vec![0.0; p],
        }
    }
}

/// What plcp said about one step.
#[derive(Clone, Debug, PartialEq)]
pub struct StepRecord {
    /// Time at the end of the step.
    pub t: f64,
    /// The LCP's status ([`Status::Reached`] when solved).
    pub status: Status,
    /// Pivots (warm path, or cold solve).
    pub pivots: usize,
    /// Worst residual of the step's LCP (equation, feasibility, complementarity).
    pub residual: f64,
    /// Whether the step was solved from the previous basis.
    pub warm: bool,
}

/// Whether a mode started or stopped flowing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ModeEventKind {
    /// The plastic rate became positive.
    FlowStarted,
    /// The plastic rate of a flowing mode returned to zero: a deactivation.
    FlowStopped,
    /// The rate of a flowing mode fell below its running peak by more than
    /// [`StepOptions::decel_tol`] (relative): `x*_dd < 0`, which system (9)
    /// forbids; reported once per spell of flow.
    FlowDecelerated,
}

impl ModeEventKind {
    /// `flow_started` or `flow_stopped`.
    pub fn as_str(self) -> &'static str {
        match self {
            ModeEventKind::FlowStarted => "flow_started",
            ModeEventKind::FlowStopped => "flow_stopped",
            ModeEventKind::FlowDecelerated => "flow_decelerated",
        }
    }
}

/// An event of one yield mode.
#[derive(Clone, Debug, PartialEq)]
pub struct ModeEvent {
    /// Time at the end of the step where it was seen.
    pub t: f64,
    /// `lambda(t)`.
    pub lambda: f64,
    /// What happened.
    pub kind: ModeEventKind,
    /// The yield mode (index into [`System::modes`]).
    pub mode: usize,
    /// Its critical section (index into [`System::sections`]).
    pub section: usize,
    /// Its sign.
    pub sign: Sign,
    /// The plastic potential `y` after the step, relative to the capacity (mean
    /// stress over the step; not unique where the stress is not).
    pub y_relative: f64,
}

/// How a run ended.
#[derive(Clone, Debug, PartialEq)]
pub enum StepOutcome {
    /// Every step was solved.
    Completed,
    /// A step's LCP was not solved, even cold: the run stopped before it.
    Stopped {
        /// Time at the start of the failed step.
        t: f64,
        /// plcp's status.
        status: Status,
        /// plcp's message.
        message: String,
    },
}

impl StepOutcome {
    /// Every step solved.
    pub fn is_completed(&self) -> bool {
        matches!(self, StepOutcome::Completed)
    }
}

/// The result of a run.
#[derive(Clone, Debug)]
pub struct StepResponse {
    /// The step size used.
    pub h: f64,
    /// The start state.
    pub start: StepState,
    /// The last state reached.
    pub end: StepState,
    /// Recorded times (the start, every `record_every` steps, the end).
    pub times: Vec<f64>,
    /// `q` at the recorded times.
    pub displacement: Vec<Vec<f64>>,
    /// `v` at the recorded times.
    pub velocity: Vec<Vec<f64>>,
    /// One record per step.
    pub steps: Vec<StepRecord>,
    /// Flow events per mode, in time order.
    pub events: Vec<ModeEvent>,
    /// Per mode, the largest relative drop of its rate below its running peak
    /// while flowing (`0`: never decreased; `1`: stopped).
    pub rate_drop: Vec<f64>,
    /// Steps that had to be redone cold (the warm path did not reach the new
    /// right-hand side).
    pub cold_restarts: usize,
    /// How the run ended.
    pub outcome: StepOutcome,
    /// Wall time of the run in seconds.
    pub seconds: f64,
}

impl StepResponse {
    /// `FlowStarted` events.
    pub fn activations(&self) -> impl Iterator<Item = &ModeEvent> {
        self.events
            .iter()
            .filter(|e| e.kind == ModeEventKind::FlowStarted)
    }
    /// `FlowDecelerated` events: flowing hinges whose rate decreases.
    pub fn decelerations(&self) -> Vec<&ModeEvent> {
        self.events
            .iter()
            .filter(|e| e.kind == ModeEventKind::FlowDecelerated)
            .collect()
    }
    /// `FlowStopped` events: deactivations.
    pub fn deactivations(&self) -> Vec<&ModeEvent> {
        self.events
            .iter()
            .filter(|e| e.kind == ModeEventKind::FlowStopped)
            .collect()
    }
    /// Largest residual of any step.
    pub fn worst_residual(&self) -> f64 {
        self.steps.iter().fold(0.0, |a, s| a.max(s.residual))
    }
    /// Total pivots of all steps.
    pub fn pivots(&self) -> usize {
        self.steps.iter().map(|s| s.pivots).sum()
    }
    /// `q` at time `t`, interpolated linearly between recorded states (exact at
    /// step ends when every step is recorded: `q` is linear over a step). `None`
    /// outside the recorded range.
    pub fn displacement_at(&self, t: f64) -> Option<Vec<f64>> {
        let (first, last) = (*self.times.first()?, *self.times.last()?);
        let slack = 1e-9 * self.h;
        if t < first - slack || t > last + slack {
            return None;
        }
        let k = self
            .times
            .partition_point(|&s| s < t)
            .min(self.times.len() - 1);
        if k == 0 || (self.times[k] - t).abs() <= slack {
            return Some(self.displacement[k].clone());
        }
        let (ta, tb) = (self.times[k - 1], self.times[k]);
        let s = (t - ta) / (tb - ta);
        Some(
            self.displacement[k - 1]
                .iter()
                .zip(&self.displacement[k])
                .map(|(a, b)| a + s * (b - a))
                .collect(),
        )
    }
}

/// `(1/h)` times the integral of `lambda` over `[a, b]`, exact for the built-in histories.
pub fn mean_load(history: &History, a: f64, b: f64) -> f64 {
    let h = b - a;
    if h <= 0.0 {
        return history.lambda(a);
    }
    match history {
        History::Saturating { peak, tau } => {
            // integral of 1 - e^(-t/tau) = h + tau e^(-a/tau) expm1(-h/tau)
            peak * (h + tau * (-a / tau).exp() * (-h / tau).exp_m1()) / h
        }
        _ => {
            // piecewise linear: trapezoids between the knots inside
            let mut cuts = vec![a];
            cuts.extend(history.knots(b).into_iter().filter(|&t| t > a));
            cuts.push(b);
            let sum: f64 = cuts
                .windows(2)
                .map(|w| 0.5 * (w[1] - w[0]) * (history.lambda(w[0]) + history.lambda(w[1])))
                .sum();
            sum / h
        }
    }
}

/// The integrator for one system, one history and one step size.
#[derive(Clone, Debug)]
pub struct TimeStepping {
    system: System,
    history: History,
    options: StepOptions,
    h: f64,
    steps: usize,
    /// The step matrix: system (9)'s (impulse form).
    m: Mat<f64>,
}

impl TimeStepping {
    /// Prepares the step matrix. Errors for options out of range.
    pub fn new(
        system: &System,
        history: &History,
        options: &StepOptions,
    ) -> Result<Self, FramesError> {
        options.validate()?;
        Ok(Self::with_span(system, history, options, options.t_end))
    }

    fn with_span(system: &System, history: &History, options: &StepOptions, span: f64) -> Self {
        let steps = ((span / options.h).round() as usize).max(1);
        let h = span / steps as f64;
        let (m, _, _) = system.blocks();
        Self {
            system: system.clone(),
            history: history.clone(),
            options: options.clone(),
            h,
            steps,
            m,
        }
    }

    /// The step size actually used.
    pub fn h(&self) -> f64 {
        self.h
    }

    /// The right-hand side of the step from `v` over `[t, t + h]`, in impulse
    /// form: `(M_q v_n + h lambda_n a_o, 0, h X*)`.
    fn rhs(&self, v: &[f64], t: f64) -> Col<f64> {
        let s = &self.system;
        let (nb, ns) = (s.coordinates.len(), s.forces.len());
        let lambda = mean_load(&self.history, t, t + self.h);
        Col::from_fn(self.m.nrows(), |i| {
            if i < nb {
                s.mass[i] * v[i] + self.h * lambda * s.load[i]
            } else if i < nb + ns {
                0.0
            } else {
                self.h * s.capacities[i - nb - ns]
            }
        })
    }

    fn solve(
        &self,
        q: &Col<f64>,
        d: &Col<f64>,
        lambda_max: f64,
        warm: Option<Vec<Var>>,
    ) -> Result<plcp::Path<f64>, FramesError> {
        let free = self.system.sizes().free();
        let problem = Plcp::mixed(self.m.as_ref(), q.as_ref(), d.as_ref(), free)?
            .with_range(0.0, Some(lambda_max))?;
        let settings = Settings {
            warm_basis: warm,
            ..Settings::with_method(Method::Wolfe)
        };
        Ok(plcp::solve(&problem, &settings)?)
    }

    /// Integrates from `start` (its `t`) to the end time of the options.
    pub fn run(&self, start: &StepState) -> Result<StepResponse, FramesError> {
        let timer = std::time::Instant::now();
        let s = &self.system;
        let (nb, np) = (s.coordinates.len(), s.modes.len());
        if start.q.len() != nb || start.v.len() != nb || start.rate.len() != np {
            return Err(FramesError::invalid(
                "start state",
                format!(
                    "sizes ({}, {}, {}) do not fit the system ({nb} coordinates, {np} modes)",
                    start.q.len(),
                    start.v.len(),
                    start.rate.len()
                ),
            ));
        }
        let mut state = start.clone();
        if state.plastic.len() != np {
            state.plastic = vec![0.0; np];
        }
        let span = self.options.t_end - start.t;
        let runner;
        let me = if span > 0.0 && (span - self.h * self.steps as f64).abs() > 1e-12 * span {
            // started later than t = 0: re-fit the step to the remaining span
            runner = Self::with_span(s, &self.history, &self.options, span);
            &runner
        } else {
            self
        };
        let (h, steps) = (me.h, if span > 0.0 { me.steps } else { 0 });
        let mmax = s.mass.iter().fold(0.0f64, |a, &m| a.max(m));
        let amax = s.load.iter().fold(0.0f64, |a, &l| a.max(l.abs()));
        let mut flowing: Vec<bool> = {
            let scale = state
                .v
                .iter()
                .chain(&state.rate)
                .fold(0.0f64, |a, x| a.max(x.abs()));
            state
                .rate
                .iter()
                .map(|&r| r > self.options.rate_tol * scale)
                .collect()
        };
        let mut peak = state.rate.clone();
        let mut decelerated = vec![false; np];
        let mut rate_drop = vec![0.0; np];
        let mut out = StepResponse {
            h,
            start: start.clone(),
            end: state.clone(),
            times: vec![state.t],
            displacement: vec![state.q.clone()],
            velocity: vec![state.v.clone()],
            steps: Vec::with_capacity(steps),
            events: Vec::new(),
            rate_drop: Vec::new(),
            cold_restarts: 0,
            outcome: StepOutcome::Completed,
            seconds: 0.0,
        };
        let mut prev: Option<(Col<f64>, Vec<Var>)> = None;
        for n in 0..steps {
            let t0 = start.t + n as f64 * h;
            let t1 = if n + 1 == steps {
                self.options.t_end
            } else {
                start.t + (n + 1) as f64 * h
            };
            let rhs = me.rhs(&state.v, t0);
            // the step LCP is homogeneous in its right-hand side: solved for
            // rhs / |rhs| (values of order one whatever h), answer scaled back
            let norm = (0..rhs.nrows()).fold(f64::MIN_POSITIVE, |a, i| a.max(rhs[i].abs()));
            let mut warm_used = false;
            let mut pivots = 0;
            let mut path = None;
            if let (true, Some((q_old, basis))) = (self.options.warm, &prev) {
                let q0 = Col::from_fn(rhs.nrows(), |i| q_old[i] / norm);
                let d = Col::from_fn(rhs.nrows(), |i| (rhs[i] - q_old[i]) / norm);
                let p = me.solve(&q0, &d, 1.0, Some(basis.clone()))?;
                pivots += p.info.pivots;
                if p.status == Status::Reached && p.info.warm_start {
                    warm_used = true;
                    path = Some(p);
                } else {
                    out.cold_restarts += 1;
                }
            }
            let path = match path {
                Some(p) => p,
                None => {
                    let zero = Col::<f64>::zeros(rhs.nrows());
                    let q0 = Col::from_fn(rhs.nrows(), |i| rhs[i] / norm);
                    let p = me.solve(&q0, &zero, 0.0, None)?;
                    pivots += p.info.pivots;
                    p
                }
            };
            let residual = path.info.residual.worst();
            out.steps.push(StepRecord {
                t: t1,
                status: path.status,
                pivots,
                residual,
                warm: warm_used,
            });
            if !path.status.is_success() {
                out.outcome = StepOutcome::Stopped {
                    t: t0,
                    status: path.status,
                    message: path.message.clone(),
                };
                break;
            }
            let back = |c: &Col<f64>| -> Vec<f64> { c.iter().map(|x| x * norm).collect() };
            // u = (v, h X), z = xdot, w = h y
            let (u, z, w) = (back(&path.end.u), back(&path.end.z), back(&path.end.w));
            let lambda = mean_load(&self.history, t0, t1);
            let scale = (0..nb)
                .map(|j| u[j].abs())
                .chain((0..np).map(|k| z[k].abs()))
                .fold(
                    h * lambda.abs() * amax / mmax.max(f64::MIN_POSITIVE),
                    f64::max,
                );
            let tol = self.options.rate_tol * scale;
            state.v.copy_from_slice(&u[..nb]);
            for (q, v) in state.q.iter_mut().zip(&state.v) {
                *q += h * v;
            }
            for k in 0..np {
                let r = z[k].max(0.0);
                state.rate[k] = r;
                state.plastic[k] += h * r;
                let now = r > tol;
                let mode = s.modes[k];
                let mut event = |kind| {
                    out.events.push(ModeEvent {
                        t: t1,
                        lambda: self.history.lambda(t1),
                        kind,
                        mode: k,
                        section: mode.section,
                        sign: mode.sign,
                        y_relative: w[k] / (h * s.capacities[k]),
                    })
                };
                if now != flowing[k] {
                    if now {
                        event(ModeEventKind::FlowStarted);
                        peak[k] = 0.0;
                        decelerated[k] = false;
                    } else {
                        event(ModeEventKind::FlowStopped);
                    }
                    flowing[k] = now;
                }
                if now {
                    peak[k] = peak[k].max(r);
                    if !decelerated[k] && r < peak[k] * (1.0 - self.options.decel_tol) {
                        event(ModeEventKind::FlowDecelerated);
                        decelerated[k] = true;
                    }
                }
                if peak[k] > 0.0 && (now || peak[k] > tol) {
                    rate_drop[k] = f64::max(rate_drop[k], (peak[k] - r) / peak[k]);
                }
            }
            state.t = t1;
            let record = self.options.record_every;
            if n + 1 == steps || (record > 0 && (n + 1) % record == 0) {
                out.times.push(state.t);
                out.displacement.push(state.q.clone());
                out.velocity.push(state.v.clone());
            }
            prev = path.final_basis.clone().map(|b| (rhs, b));
        }
        if out.times.last() != Some(&state.t) {
            out.times.push(state.t);
            out.displacement.push(state.q.clone());
            out.velocity.push(state.v.clone());
        }
        out.end = state;
        out.rate_drop = rate_drop;
        out.seconds = timer.elapsed().as_secs_f64();
        Ok(out)
    }
}

/// The exact state of the PLCP response at time `t` (velocities, displacements,
/// plastic rates and multipliers integrated from rest in closed form,
/// [`crate::integrate`]). Valid only up to the first deactivation of the path.
pub fn path_state(analysis: &Analysis, t: f64) -> StepState {
    let s = &analysis.system;
    let (nb, np) = (s.coordinates.len(), s.modes.len());
    // piece by piece: an interval's accelerations are one affine function,
    // but the split of plastic rates between tied sections may change where
    // the path pivots inside it
    let pieces: Vec<AffinePiece> = analysis
        .reading
        .intervals
        .iter()
        .flat_map(|iv| iv.pieces.iter().map(move |sp| (iv.rigid, sp)))
        .map(|(rigid, sp)| {
            let p = &analysis.solution.pieces[sp.piece];
            let (mut base, mut slope) = (vec![0.0; nb + np], vec![0.0; nb + np]);
            if !rigid {
                let (u0, z0) = (p.u(0.0), p.z(0.0));
                base[..nb].copy_from_slice(&u0[..nb]);
                slope[..nb].copy_from_slice(&p.du[..nb]);
                base[nb..].copy_from_slice(&z0);
                slope[nb..].copy_from_slice(&p.dz);
            }
            AffinePiece {
                lambda_from: sp.lambda_from,
                lambda_to: sp.lambda_to,
                base,
                slope,
            }
        })
        .collect();
    if pieces.is_empty() || t <= 0.0 {
        return StepState {
            t: t.max(0.0),
            ..StepState::rest(s)
        };
    }
    let m = integrate(&pieces, &analysis.scene.history, &[t]);
    let (q, v) = (&m.displacement[0], &m.velocity[0]);
    StepState {
        t,
        q: q[..nb].to_vec(),
        v: v[..nb].to_vec(),
        rate: v[nb..].to_vec(),
        plastic: q[nb..].to_vec(),
    }
}

/// The first deactivation of the PLCP path, `(Lambda, t)`: the PLCP response is
/// not valid beyond it. `None` when the path has none.
pub fn plcp_valid_until(analysis: &Analysis) -> Option<(f64, f64)> {
    let (lambda, _) = analysis.reading.deactivations().into_iter().next()?;
    let t = analysis.scene.history.time_at(lambda)?;
    Some((lambda, t))
}

/// Largest translation of any node, `max |q_j|` over translational coordinates
/// (x and y of a planar frame, z of a grillage; never a rotation).
pub fn largest_translation(system: &System, q: &[f64]) -> f64 {
    system
        .coordinates
        .iter()
        .zip(q)
        .filter(|(c, _)| !c.component.is_rotation())
        .fold(0.0, |a, (_, x)| a.max(x.abs()))
}

/// A time-stepping run against the PLCP response.
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// Time of the comparison (the end time, or the PLCP path's first
    /// deactivation if earlier).
    pub t: f64,
    /// Largest difference of a nodal translation at `t`.
    pub displacement_error: f64,
    /// Largest nodal translation of the PLCP response at `t`.
    pub displacement_scale: f64,
    /// Largest difference of a hinge's start-of-flow time, over the PLCP
    /// hinges that form before `t` (`inf` if one of them never flows in the run).
    pub activation_error: f64,
    /// PLCP hinges (groups) compared.
    pub hinges_compared: usize,
    /// Groups that flow in the run before `t` but not in the PLCP path.
    pub extra_activations: usize,
}

/// Start-of-flow time of every hinge group in a run.
fn group_starts(analysis: &Analysis, run: &StepResponse) -> Vec<Option<f64>> {
    let mut first = vec![None; analysis.reading.groups.len()];
    for e in run.activations() {
        if let Some(Some(g)) = analysis.reading.group_of.get(e.section) {
            let f: &mut Option<f64> = &mut first[*g];
            if f.is_none() {
                *f = Some(e.t);
            }
        }
    }
    first
}

/// Compares a run from rest with the PLCP response at `min(run end, first
/// deactivation of the path)`.
pub fn compare(analysis: &Analysis, run: &StepResponse) -> Comparison {
    let history = &analysis.scene.history;
    let mut t = run.end.t;
    if let Some((_, td)) = plcp_valid_until(analysis) {
        t = t.min(td);
    }
    let exact = path_state(analysis, t);
    let ts = run
        .displacement_at(t)
        .unwrap_or_else(|| vec![f64::NAN; exact.q.len()]);
    let diff: Vec<f64> = exact.q.iter().zip(&ts).map(|(a, b)| a - b).collect();
    let displacement_error = largest_translation(&analysis.system, &diff);
    let starts = group_starts(analysis, run);
    let mut activation_error: f64 = 0.0;
    let mut compared = 0;
    let mut plcp_groups = vec![false; starts.len()];
    for hinge in &analysis.reading.hinges {
        let Some(tp) = history.time_at(hinge.lambda) else {
            continue;
        };
        if tp >= t {
            continue;
        }
        plcp_groups[hinge.group] = true;
        compared += 1;
        let e = starts[hinge.group].map_or(f64::INFINITY, |ts| (ts - tp).abs());
        activation_error = activation_error.max(e);
    }
    let extra = starts
        .iter()
        .zip(&plcp_groups)
        .filter(|(s, p)| !**p && s.is_some_and(|ts| ts < t))
        .count();
    Comparison {
        t,
        displacement_error,
        displacement_scale: largest_translation(&analysis.system, &exact.q),
        activation_error,
        hinges_compared: compared,
        extra_activations: extra,
    }
}

/// The response beyond the PLCP path's first deactivation, by time stepping
/// from the exact PLCP state there.
#[derive(Clone, Debug)]
pub struct Continuation {
    /// `Lambda` of the first deactivation of the path: the PLCP response is not
    /// valid beyond it.
    pub lambda: f64,
    /// The time it is reached.
    pub t: f64,
    /// The run from there to the end time.
    pub run: StepResponse,
}

impl Continuation {
    /// Time-steps from the PLCP state at the path's first deactivation to
    /// `options.t_end`. `None` if the path has no deactivation, or it comes at
    /// or after `t_end`.
    pub fn after_deactivation(
        analysis: &Analysis,
        options: &StepOptions,
    ) -> Result<Option<Continuation>, FramesError> {
        options.validate()?;
        let Some((lambda, t)) = plcp_valid_until(analysis) else {
            return Ok(None);
        };
        if t >= options.t_end {
            return Ok(None);
        }
        let start = path_state(analysis, t);
        let ts = TimeStepping::new(&analysis.system, &analysis.scene.history, options)?;
        let run = ts.run(&start)?;
        Ok(Some(Continuation { lambda, t, run }))
    }

    fn section_label(analysis: &Analysis, section: usize) -> String {
        let n = crate::hinge::section_name(&analysis.scene.frame, &analysis.system, section);
        format!("{} ({} {})", n.node, n.member, n.end.as_str())
    }

    /// Displacements per node at the end of the run, in the slots of
    /// [`crate::model::Component::index`]: `[x, y, rz]` (planar) or `[z, rx, ry]` (grillage).
    pub fn end_displacements(&self, analysis: &Analysis) -> Vec<[f64; 6]> {
        let mut out = vec![[0.0; 6]; analysis.scene.frame.nodes.len()];
        for (j, c) in analysis.system.coordinates.iter().enumerate() {
            out[c.node][c.component.index()] = self.run.end.q[j];
        }
        out
    }

    /// The text section of the report.
    pub fn to_text(&self, analysis: &Analysis) -> String {
        use std::fmt::Write as _;
        let mut s = String::new();
        let r = &self.run;
        let _ = writeln!(
            s,
            "\ntime stepping from Lambda = {} (t = {}) to t = {}: h = {:.3e}, {} steps, {} pivots, {} cold restarts, worst residual {:.1e}, {:.3} s",
            format_number(self.lambda), format_number(self.t), format_number(r.end.t), r.h, r.steps.len(), r.pivots(), r.cold_restarts, r.worst_residual(), r.seconds
        );
        if let StepOutcome::Stopped { t, status, message } = &r.outcome {
            let _ = writeln!(
                s,
                "  WARNING: stopped at t = {t}: step LCP {}: {message}",
                status.as_str()
            );
        }
        for e in &r.events {
            let _ = writeln!(
                s,
                "  t = {:.6}  Lambda = {:.6}  {} {} ({}), y/X* = {:.3e}",
                e.t,
                e.lambda,
                Self::section_label(analysis, e.section),
                e.kind.as_str(),
                e.sign.as_str(),
                e.y_relative
            );
        }
        let fr = &analysis.scene.frame;
        let d = self.end_displacements(analysis);
        let model = analysis.system.model;
        // the translation of a node: (x, y) in plane, z out of plane
        let size = |x: &[f64; 6]| model.translation_size(x);
        if let Some((i, _)) = d
            .iter()
            .enumerate()
            .max_by(|a, b| size(a.1).total_cmp(&size(b.1)))
        {
            let what = model
                .translations()
                .iter()
                .map(|c| format!("{} = {:.6}", c.as_str(), d[i][c.index()]))
                .collect::<Vec<_>>()
                .join(", ");
            let _ = writeln!(
                s,
                "  at t = {}: largest displacement at {}: {what}",
                r.end.t, fr.nodes[i].id
            );
        }
        s
    }

    /// The JSON object of the continuation.
    pub fn to_json(&self, analysis: &Analysis) -> Value {
        let r = &self.run;
        let fr = &analysis.scene.frame;
        let events: Vec<Value> = r
            .events
            .iter()
            .map(|e| {
                let n = crate::hinge::section_name(fr, &analysis.system, e.section);
                json!({
                    "t": e.t, "lambda": e.lambda, "kind": e.kind.as_str(),
                    "node": n.node, "member": n.member, "end": n.end.as_str(),
                    "sign": e.sign.as_str(), "y_relative": e.y_relative,
                })
            })
            .collect();
        let d = self.end_displacements(analysis);
        let comps = analysis.system.model.components();
        let nodes: Vec<Value> = fr
            .nodes
            .iter()
            .zip(&d)
            .map(|(n, x)| {
                let mut o = serde_json::Map::new();
                o.insert("node".into(), json!(n.id));
                for c in comps {
                    o.insert(c.as_str().into(), json!(x[c.index()]));
                }
                Value::Object(o)
            })
            .collect();
        let (status, message) = match &r.outcome {
            StepOutcome::Completed => ("completed", String::new()),
            StepOutcome::Stopped {
                status, message, ..
            } => (status.as_str(), message.clone()),
        };
        json!({
            "plcp_valid_up_to_lambda": self.lambda,
            "plcp_valid_up_to_t": self.t,
            "method": "backward Euler at velocity level (Moreau-Jean), one mixed LCP per step solved by plcp (Wolfe), warm-started",
            "h": r.h,
            "t_end": r.end.t,
            "steps": r.steps.len(),
            "pivots": r.pivots(),
            "cold_restarts": r.cold_restarts,
            "worst_residual": r.worst_residual(),
            "status": status,
            "message": message,
            "seconds": r.seconds,
            "events": events,
            "end_displacements": nodes,
        })
    }
}
