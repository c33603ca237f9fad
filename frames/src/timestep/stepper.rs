//! The time stepper: one mixed LCP per step ([`TimeStepping`]).

use super::*;

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
            ..crate::solve::plcp_settings(Method::Wolfe)
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
        let mut flow = Flow::new(&state, self.options.rate_tol);
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
            let warm = prev.as_ref().filter(|_| self.options.warm);
            let (path, pivots, warm_used) = me.solve_step(&rhs, norm, warm)?;
            if warm.is_some() && !warm_used {
                out.cold_restarts += 1;
            }
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
                let mode = s.modes[k];
                flow.update(k, r, tol, self.options.decel_tol, |kind| {
                    out.events.push(ModeEvent {
                        t: t1,
                        lambda: self.history.lambda(t1),
                        kind,
                        mode: k,
                        section: mode.section,
                        sign: mode.sign,
                        y_relative: w[k] / (h * s.capacities[k]),
                    })
                });
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
        out.rate_drop = flow.rate_drop;
        out.seconds = timer.elapsed().as_secs_f64();
        Ok(out)
    }

    /// One step's LCP for the scaled right-hand side `rhs / norm`: from the
    /// last step's basis along the segment from its right-hand side `q_old`
    /// to this one's when `warm` is given, else (or when that path does not
    /// reach its end from a warm start) solved cold. Returns the path, the
    /// pivots of both attempts and whether the warm start was used.
    fn solve_step(
        &self,
        rhs: &Col<f64>,
        norm: f64,
        warm: Option<&(Col<f64>, Vec<Var>)>,
    ) -> Result<(plcp::Path<f64>, usize, bool), FramesError> {
        let mut pivots = 0;
        if let Some((q_old, basis)) = warm {
            let q0 = Col::from_fn(rhs.nrows(), |i| q_old[i] / norm);
            let d = Col::from_fn(rhs.nrows(), |i| (rhs[i] - q_old[i]) / norm);
            let p = self.solve(&q0, &d, 1.0, Some(basis.clone()))?;
            pivots += p.info.pivots;
            if p.status == Status::Reached && p.info.warm_start {
                return Ok((p, pivots, true));
            }
        }
        let zero = Col::<f64>::zeros(rhs.nrows());
        let q0 = Col::from_fn(rhs.nrows(), |i| rhs[i] / norm);
        let p = self.solve(&q0, &zero, 0.0, None)?;
        pivots += p.info.pivots;
        Ok((p, pivots, false))
    }
}

/// The flow state of each yield mode across the steps: flowing or not, the
/// peak rate since its flow started, whether it has decelerated, and the
/// largest relative drop of its rate from the peak.
struct Flow {
    flowing: Vec<bool>,
    peak: Vec<f64>,
    decelerated: Vec<bool>,
    rate_drop: Vec<f64>,
}

impl Flow {
    /// The modes flowing at the start: a rate above `rate_tol` times the
    /// largest velocity or rate.
    fn new(state: &StepState, rate_tol: f64) -> Flow {
        let np = state.rate.len();
        let scale = state
            .v
            .iter()
            .chain(&state.rate)
            .fold(0.0f64, |a, x| a.max(x.abs()));
        Flow {
            flowing: state.rate.iter().map(|&r| r > rate_tol * scale).collect(),
            peak: state.rate.clone(),
            decelerated: vec![false; np],
            rate_drop: vec![0.0; np],
        }
    }

    /// Mode `k` now rates `r` (flowing when above `tol`): calls `event` for
    /// a start, a stop or a first deceleration by `decel_tol` below the peak.
    fn update(
        &mut self,
        k: usize,
        r: f64,
        tol: f64,
        decel_tol: f64,
        mut event: impl FnMut(ModeEventKind),
    ) {
        let now = r > tol;
        if now != self.flowing[k] {
            if now {
                event(ModeEventKind::FlowStarted);
                self.peak[k] = 0.0;
                self.decelerated[k] = false;
            } else {
                event(ModeEventKind::FlowStopped);
            }
            self.flowing[k] = now;
        }
        if now {
            self.peak[k] = self.peak[k].max(r);
            if !self.decelerated[k] && r < self.peak[k] * (1.0 - decel_tol) {
                event(ModeEventKind::FlowDecelerated);
                self.decelerated[k] = true;
            }
        }
        let peak = self.peak[k];
        if peak > 0.0 && (now || peak > tol) {
            self.rate_drop[k] = f64::max(self.rate_drop[k], (peak - r) / peak);
        }
    }
}
