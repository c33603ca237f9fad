//! The glue between the PLCP path and time stepping: the exact state of the
//! PLCP response at a time ([`path_state`]), where the path stops being the
//! response ([`plcp_valid_until`], its first deactivation), and the response
//! beyond it by time stepping from that state ([`Continuation`], which
//! [`Analysis::continue_by_time_stepping`] calls).

use super::*;

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

    /// [`Continuation::after_deactivation`] up to the end of the analysis's
    /// time response, with steps of `h_relative` times that end time (the
    /// run keeps its end state only). `None` when there is no response time
    /// or no deactivation before its end; an error for `h_relative` outside
    /// `(0, 1)`.
    pub fn for_analysis(
        analysis: &Analysis,
        h_relative: f64,
    ) -> Result<Option<Continuation>, FramesError> {
        if !(h_relative > 0.0 && h_relative < 1.0) {
            return Err(FramesError::invalid(
                "time-stepping step",
                format!("must be a fraction of the response time in (0, 1), got {h_relative}"),
            ));
        }
        let t_end = analysis.response.time.times.last().copied().unwrap_or(0.0);
        if t_end <= 0.0 {
            return Ok(None);
        }
        let options = StepOptions {
            h: h_relative * t_end,
            t_end,
            record_every: 0,
            ..StepOptions::default()
        };
        Continuation::after_deactivation(analysis, &options)
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
    #[cfg(feature = "json")]
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
