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
#[cfg(feature = "json")]
use serde_json::{json, Value};

mod compare;
mod continuation;
mod stepper;

pub use compare::*;
pub use continuation::*;
pub use stepper::*;

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
