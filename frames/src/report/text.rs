//! The readable text report (`frames run SCENE`): the system, the table of
//! critical `Lambda` with the hinges that form, the intervals, the end of the
//! time response and the targets.

use super::fmt_g;
use crate::analysis::Analysis;
use crate::hinge::{EventKind, HingeEvent};
use std::fmt::Write;

/// A `fmt::Write` onto an `io::Write` that keeps the first I/O error (and
/// writes nothing after it).
struct IoText<'w, W: std::io::Write> {
    w: &'w mut W,
    err: Option<std::io::Error>,
}

impl<W: std::io::Write> Write for IoText<'_, W> {
    fn write_str(&mut self, text: &str) -> std::fmt::Result {
        if self.err.is_some() {
            return Err(std::fmt::Error);
        }
        self.w.write_all(text.as_bytes()).map_err(|e| {
            self.err = Some(e);
            std::fmt::Error
        })
    }
}

impl Analysis {
    /// The readable report: the system, the table of critical `Lambda` with the
    /// hinges that form, then the intervals.
    pub fn to_text(&self) -> String {
        let mut s = String::new();
        self.text_parts(&mut s);
        s
    }

    /// [`Self::to_text`] written to `w` line by line, not built whole (the
    /// report of a large scene lists the hinge sets of every interval).
    pub fn write_text(&self, w: &mut impl std::io::Write) -> std::io::Result<()> {
        let mut a = IoText { w, err: None };
        self.text_parts(&mut a);
        a.err.map_or(Ok(()), Err)
    }

    fn text_parts(&self, s: &mut impl Write) {
        self.text_system(s);
        self.text_solver(s);
        self.text_breakpoints(s);
        self.text_intervals(s);
        self.text_time_end(s);
        self.text_targets(s);
    }

    /// The header: the scene, the size of system (9) and what it leaves
    /// out, the model and the yield surfaces.
    fn text_system(&self, s: &mut impl Write) {
        let fr = &self.scene.frame;
        let sys = &self.system;
        let sz = sys.sizes();
        let title = if fr.title.is_empty() {
            "frame"
        } else {
            &fr.title
        };
        let _ = writeln!(s, "{title} ({})", self.scene.file);
        let _ = writeln!(
            s,
            "system (9): {} coordinates, {} member forces, {} yield modes: mixed PLCP with {} free and {} complementary variables",
            sz.coordinates,
            sz.forces,
            sz.modes,
            sz.free(),
            sz.modes
        );
        let _ = writeln!(
            s,
            "  before leaving out: {} coordinates, {} member forces, {} yield modes",
            sys.full.coordinates, sys.full.forces, sys.full.modes
        );
        for l in self.left_out_summary() {
            let _ = writeln!(s, "  left out: {l}");
        }
        let members_note = match fr.model {
            crate::model::Model::Planar => {
                if fr.elements.iter().any(|e| e.interaction.is_some()) {
                    "planar; members without plastic_axial inextensible (axial forces kept as reactions)"
                } else {
                    "planar; members inextensible (axial forces kept as reactions)"
                }
            }
            crate::model::Model::Grillage => {
                "grillage: z, rx, ry per node; end moments and a torque per element"
            }
            crate::model::Model::Space => {
                "space: x, y, z, rx, ry, rz per node; two bending moments per section, a torque and an axial force (a reaction) per element"
            }
        };
        let _ = writeln!(
            s,
            "  {} (degree of indeterminacy {}); {members_note}",
            if sys.is_determinate() {
                "statically determinate"
            } else {
                "statically indeterminate"
            },
            sys.indeterminacy()
        );
        for y in self.yield_summary() {
            let _ = writeln!(s, "  yield: {y}");
        }
    }

    /// How the path was solved: method, certificate, warnings, the sign
    /// convention and the load history.
    fn text_solver(&self, s: &mut impl Write) {
        let info = &self.solution.info;
        let _ = writeln!(
            s,
            "solved: {} in {}, {} pivots, status {}, worst residual {:.1e}",
            info.method,
            info.precision,
            info.pivots,
            self.solution.status.as_str(),
            info.residual.worst()
        );
        if let Some(n) = &self.note {
            let _ = writeln!(s, "  note: {n}");
        }
        if let Some(c) = &info.certificate {
            if c.certified() {
                let _ = writeln!(
                    s,
                    "  certified in exact rational arithmetic: {} segments in {:.3} s, float breakpoints within {:.1e} (relative) of the exact ones",
                    c.segments, c.seconds, c.max_rel_diff
                );
                let _ = writeln!(
                    s,
                    "  exact critical loads: {}",
                    self.exact_critical_loads().join(", ")
                );
            } else if let Some(f) = &c.failure {
                let _ = writeln!(
                    s,
                    "  WARNING: exact certification REJECTED the path at segment {}: {}",
                    f.segment, f.reason
                );
            }
        }
        if info.residual.worst() > 1e-6 {
            let _ = writeln!(
                s,
                "  WARNING: the solver's path does not satisfy system (9) (residual {:.1e}): do not trust the numbers below (try --precision f128)",
                info.residual.worst()
            );
        }
        if !self.solution.status.is_success() {
            let _ = writeln!(
                s,
                "  WARNING: the path ended early at Lambda = {}: {}",
                fmt_g(self.solution.lambda_reached),
                self.solution.message
            );
        }
        let _ = writeln!(
            s,
            "  sign: + sagging, - hogging (element axes){}; load history: {}",
            if self.system.modes.iter().any(|m| m.facet.is_some()) {
                "; @a: on the facet of the yield polygon whose normal points at a degrees in (M/Mp, F/Fp)"
            } else {
                ""
            },
            self.scene.history.describe()
        );
    }

    /// The table of critical `Lambda` with the hinges that form and the events.
    fn text_breakpoints(&self, s: &mut impl Write) {
        let _ = writeln!(s);
        let _ = writeln!(s, "critical Lambda   hinges and events");
        if self.reading.breakpoints.is_empty() {
            let _ = writeln!(s, "  (none: the frame stays rigid over the traced range)");
        }
        for (i, b) in self.reading.breakpoints.iter().enumerate() {
            let mut parts = Vec::new();
            let label = |e: &HingeEvent| {
                format!(
                    "{}{}",
                    self.group_label(e.group),
                    self.mode_tag(e.mode, e.sign)
                )
            };
            let forms: Vec<String> = self
                .reading
                .hinges
                .iter()
                .filter(|h| h.lambda == b.lambda)
                .map(|h| self.group_label(h.group))
                .collect();
            if !forms.is_empty() {
                parts.push(format!("hinge forms at {}", forms.join(", ")));
            }
            for (k, what) in [
                (EventKind::Yielded, "yielded"),
                (EventKind::FlowStarted, "started to flow"),
                (
                    EventKind::FlowStopped,
                    "stopped accelerating (rotates on at constant rate)",
                ),
                (EventKind::Unloaded, "UNLOADED (deactivation)"),
            ] {
                let v: Vec<String> = b.of(k).map(label).collect();
                if !v.is_empty() {
                    parts.push(format!("{what}: {}", v.join(", ")));
                }
            }
            let facets = self.facet_changes(b.lambda);
            if !facets.is_empty() {
                parts.push(format!("facets: {}", facets.join(", ")));
            }
            if parts.is_empty() {
                parts.push("no hinge event: the accelerations change slope (a pivot among the flowing hinges)".into());
            }
            let note = if i == 0 {
                "  [static collapse load]"
            } else {
                ""
            };
            let _ = writeln!(s, "{:>15}   {}{}", fmt_g(b.lambda), parts.join("; "), note);
        }
        let facet_stops = self.reading.breakpoints.iter().any(|b| {
            self.facet_changes(b.lambda)
                .iter()
                .any(|f| f.contains(" stops"))
        });
        if facet_stops {
            let _ = writeln!(s, "NOTE: a facet that stops accelerating while its hinge flows on keeps its rate on the path of (9), which cannot let a rate decrease; the true flow may turn by decelerating it (a deactivation of that facet: check by time stepping, see examples/pipe_whip.rs)");
        }
        let dea = self.reading.deactivations();
        if !dea.is_empty() {
            let _ = writeln!(s, "WARNING: {} deactivation(s): a flowing hinge left yield, against the paper's claim for this loading class", dea.len());
        }
    }

    /// The intervals: the hinges accelerating, and the accelerations of
    /// the nodes with mass.
    fn text_intervals(&self, s: &mut impl Write) {
        let fr = &self.scene.frame;
        let _ = writeln!(s);
        let _ = writeln!(
            s,
            "intervals (accelerations of the nodes with mass, base + slope * Lambda)"
        );
        let massive: Vec<usize> = (0..fr.nodes.len())
            .filter(|&i| fr.nodes[i].mass > 0.0 || fr.nodes[i].inertia > 0.0)
            .collect();
        for (iv, r) in self.reading.intervals.iter().zip(&self.response.intervals) {
            let range = if iv.lambda_to.is_finite() {
                format!("[{}, {}]", fmt_g(iv.lambda_from), fmt_g(iv.lambda_to))
            } else {
                format!("[{}, inf)", fmt_g(iv.lambda_from))
            };
            if iv.rigid {
                let _ = writeln!(s, "  {range:<24} rigid (no plastic flow)");
                continue;
            }
            let acc: Vec<String> = iv
                .accelerating
                .iter()
                .map(|g| self.group_label(g))
                .collect();
            let cr: Vec<String> = iv
                .constant_rate
                .iter()
                .map(|g| self.group_label(g))
                .collect();
            let _ = writeln!(
                s,
                "  {range:<24} accelerating: {}{}   residual {:.1e}",
                acc.join(", "),
                if cr.is_empty() {
                    String::new()
                } else {
                    format!("; constant rate: {}", cr.join(", "))
                },
                r.residual.worst()
            );
            if massive.len() <= 8 {
                // round-off below 1e-12 of the largest coefficient prints as 0
                let slot = |i: usize| self.response.slot(i).unwrap_or(i);
                let scale = massive
                    .iter()
                    .flat_map(|&i| r.accelerations[slot(i)].iter().flatten().map(|v| v.abs()))
                    .fold(0.0f64, f64::max);
                let snap = |v: f64| if v.abs() <= 1e-12 * scale { 0.0 } else { v };
                for &i in &massive {
                    let a = r.accelerations[slot(i)];
                    let comps: Vec<String> = fr
                        .model
                        .components()
                        .iter()
                        .map(|c| (c, snap(a[c.index()][0]), snap(a[c.index()][1])))
                        .filter(|(_, b, sl)| *b != 0.0 || *sl != 0.0)
                        .map(|(c, b, sl)| {
                            let sign = if sl < 0.0 { "-" } else { "+" };
                            format!("{} = {} {sign} {} L", c.as_str(), fmt_g(b), fmt_g(sl.abs()))
                        })
                        .collect();
                    if !comps.is_empty() {
                        let _ =
                            writeln!(s, "  {:<24}   {}: {}", "", fr.nodes[i].id, comps.join(", "));
                    }
                }
            }
        }
    }

    /// The largest displacement at the end of the time response.
    fn text_time_end(&self, s: &mut impl Write) {
        let fr = &self.scene.frame;
        let t = &self.response.time;
        if let Some(&t_end) = t.times.last() {
            let _ = writeln!(s);
            let k = t.times.len() - 1;
            let mut far = (0usize, 0.0f64);
            for (i, d) in t.end_displacement.iter().enumerate() {
                let m = fr.model.translation_size(d);
                if m > far.1 {
                    far = (i, m);
                }
            }
            let d = t.end_displacement[far.0];
            let what = fr
                .model
                .translations()
                .iter()
                .map(|c| format!("{} = {}", c.as_str(), fmt_g(d[c.index()])))
                .collect::<Vec<_>>()
                .join(", ");
            let _ = writeln!(
                s,
                "at t = {} (lambda = {}): largest displacement at {}: {what}  [integration exact on each piece]",
                fmt_g(t_end),
                fmt_g(t.lambda[k]),
                fr.nodes[far.0].id,
            );
        }
    }

    /// The targets: when each gap closes, with velocity and kinetic energy.
    fn text_targets(&self, s: &mut impl Write) {
        let fr = &self.scene.frame;
        if !self.targets.is_empty() {
            let _ = writeln!(s);
            let _ = writeln!(s, "targets (first time the gap closes; velocity along the direction; kinetic energy of the whole structure)");
            for a in &self.targets {
                let tg = &a.target;
                let head = format!(
                    "  {} along [{}, {}, {}], gap {}:",
                    fr.nodes[tg.node].id,
                    fmt_g(tg.direction[0]),
                    fmt_g(tg.direction[1]),
                    fmt_g(tg.direction[2]),
                    fmt_g(tg.gap)
                );
                match (a.time, a.lambda, a.velocity, a.kinetic_energy) {
                    (Some(t), Some(l), Some(v), Some(e)) => {
                        let _ = writeln!(
                            s,
                            "{head} reached at t = {} (lambda = {}), velocity {}, kinetic energy {}{}",
                            fmt_g(t),
                            fmt_g(l),
                            fmt_g(v),
                            fmt_g(e),
                            if a.after_deactivation {
                                "  [after a deactivation: the path's response is not valid there]"
                            } else {
                                ""
                            }
                        );
                    }
                    _ => {
                        let _ = writeln!(
                            s,
                            "{head} not reached by t = {} (the analysed range)",
                            fmt_g(a.t_end)
                        );
                    }
                }
            }
        }
    }
}
