//! A large scene's analysis in memory linear in the structure: two passes
//! over the path of system (9), neither of which stores it.
//!
//! [`Analysis::run`] keeps every piece of the path in full (`pieces x
//! unknowns` numbers), and per interval every node's accelerations, per time
//! every node's state: quadratic in the number of elements (30 GB estimated
//! for a 10^4-element cantilever). [`run`] traces the path twice instead
//! (plcp's trace is deterministic: the second gives the same pieces, bit for
//! bit, and stops after the last piece it needs):
//!
//! 1. each piece is read as it comes by the hinge reading
//!    ([`crate::hinge::Reader`]) and its residual measured, then dropped;
//! 2. with the breakpoints known (so the end time, the times of the time
//!    response, and the sampled `Lambda` values of the [`OutputSelection`]),
//!    each interval's accelerations are integrated as they come with the
//!    steps of [`crate::integrate::integrate`] (the same operations on the
//!    same numbers) and kept for the selected nodes only; the moment pieces
//!    and diagrams are computed for the selected intervals and breakpoints
//!    only, and the pieces those need kept.
//!
//! What it keeps equals [`Analysis::run`]'s bit for bit
//! (`frames/tests/output_bounds.rs` compares the JSON and text reports).
//! What it does not keep: [`crate::response::Response::nodes`] names the
//! kept nodes; other intervals' moment pieces and other breakpoints'
//! diagrams have no moments; the pieces of [`crate::solve::Solution`] other
//! than the kept ones are hollow (their range only, empty vectors).
//! Plots, targets and the time-stepping continuation need the whole
//! response: [`run`] runs [`Analysis::run_watched`] where the scene has
//! targets or yield polygons, the options ask for exact arithmetic, a
//! certificate or a precision other than `f64`, the system is small (dense
//! route), or the first pass ends anything but a clean success (a path
//! escalated to `fx128`, re-solved, or stopped early).
//!
//! Memory: the reading (per breakpoint its events, per interval its hinge
//! sets and the ranges of its pieces), per piece its range and residual,
//! the state of the integration (two vectors of the coordinates), the
//! selected series and moments, and plcp's engine (the sparse system and
//! its basis factors).

use crate::analysis::{Analysis, AnalysisOptions};
use crate::assemble::System;
use crate::error::FramesError;
use crate::hinge::{self, moment_positions, Reading};
use crate::integrate::{schedule, step, METHOD};
use crate::model::{History, Scene};
use crate::report::{MomentPick, NodePick, OutputSelection};
use crate::response::{
    self, affine_accelerations, residual_at, to_nodes, IntervalResponse, MomentDiagram,
    MomentPiece, Response, TimeResponse,
};
use crate::solve::{self, Piece};
use plcp::{Control, Residual};
use std::collections::HashMap;

/// Whether [`run`] analyses `scene` in two passes (else it runs
/// [`Analysis::run_watched`]), before the first pass.
pub fn applies(scene: &Scene, system: &System, options: &AnalysisOptions) -> bool {
    !options.exact
        && !options.certify
        && options.solve.precision == plcp::Precision::F64
        && scene.targets.is_empty()
        && system.modes.iter().all(|m| m.facet.is_none())
        && solve::uses_sparse(system, &options.solve)
}

/// A hollow piece: its range only.
fn hollow(lambda_from: f64, lambda_to: f64) -> Piece {
    Piece {
        lambda_from,
        lambda_to,
        u_from: Vec::new(),
        du: Vec::new(),
        z_from: Vec::new(),
        dz: Vec::new(),
        w_from: Vec::new(),
        dw: Vec::new(),
    }
}

/// The analysis of `scene` in two passes over its path, keeping what the
/// JSON and text reports ask for with `moments` and `nodes` (`None`: the
/// default of [`OutputSelection::default_for`]); see the module
/// documentation. `Err` as [`Analysis::run`], and for a node id `nodes` names
/// that the scene has not.
pub fn run(
    scene: Scene,
    options: &AnalysisOptions,
    moments: Option<MomentPick>,
    nodes: Option<NodePick>,
    watch: Option<solve::Watch>,
) -> Result<Analysis, FramesError> {
    run_in_passes(scene, options, moments, nodes, watch.clone(), watch)
}

/// [`run`], told per segment of the first pass (and of an analysis run
/// whole instead) to `watch` and per segment of the second pass to
/// `second`, so that a display can say which pass it is in (`frames run`'s
/// progress line).
pub fn run_in_passes(
    scene: Scene,
    options: &AnalysisOptions,
    moments: Option<MomentPick>,
    nodes: Option<NodePick>,
    watch: Option<solve::Watch>,
    second: Option<solve::Watch>,
) -> Result<Analysis, FramesError> {
    options.check()?;
    let system = System::assemble(&scene.frame);
    if !applies(&scene, &system, options) {
        return Analysis::run_watched(scene, options, watch);
    }
    let tolerance = (f64::EPSILON.sqrt() * 10.0).max(1e-13);
    // pass 1: the reading, and each piece's range and residuals
    let first = first_pass(&scene, &system, options, tolerance, watch.clone())?;
    let poor = !first.solution.status.is_success() || first.solution.info.residual.worst() > 1e-6;
    if first.solution.info.escalation.is_some() || poor || first.solution.tolerance != tolerance {
        return Analysis::run_watched(scene, options, watch);
    }
    let FirstPass {
        mut solution,
        reading,
        ranges,
        residuals,
    } = first;
    // the times, as Analysis::run_watched takes them
    let reached = if solution.status == plcp::Status::UnboundedRay {
        f64::INFINITY
    } else {
        solution.lambda_reached
    };
    let times = response::response_times(
        &scene.history,
        &reading,
        options.t_end,
        options.solve.lambda_max,
        reached,
        options.samples,
    );
    // what the reports will ask for
    let mut sel =
        OutputSelection::default_for_counts(scene.frame.nodes.len(), reading.breakpoints.len());
    if let Some(m) = moments {
        sel.moments = m;
    }
    if let Some(n) = nodes {
        sel.nodes = n;
    }
    let kept = kept_nodes(&scene, &sel)?;
    // the integration's windows, each with its interval; folded as the
    // intervals come, so they must come in order (a history whose lambda(t)
    // returns to an earlier interval is analysed whole)
    let iv_ranges: Vec<(f64, f64)> = reading
        .intervals
        .iter()
        .map(|iv| (iv.lambda_from, iv.lambda_to))
        .collect();
    let (knots, windows) = schedule(&iv_ranges, &scene.history, &times);
    let order: Vec<usize> = windows.iter().flatten().copied().collect();
    if order.windows(2).any(|w| w[1] < w[0]) {
        return Analysis::run_watched(scene, options, watch);
    }
    let plan = Plan::new(&system, &reading, &sel, kept, ranges.len());
    let intervals = skeleton(&reading, &ranges, &residuals);
    drop(residuals);
    // pass 2
    let mut fold = Fold::new(
        Context {
            system: &system,
            reading: &reading,
            history: &scene.history,
            plan: &plan,
            ranges: &ranges,
            knots: &knots,
            windows: &windows,
        },
        &times,
        intervals,
    );
    solve::trace_pieces(&system, &options.solve, options.escalate, second, |k, p| {
        fold.piece(k, p)
    })?;
    if !fold.complete() {
        // the second trace did not retrace the first: analysed whole
        return Analysis::run_watched(scene, options, watch);
    }
    let Fold {
        intervals,
        diagrams,
        displacement,
        velocity,
        end_q,
        mut retained,
        ..
    } = fold;
    let nb = system.coordinates.len();
    let end_displacement = to_nodes(
        &scene.frame,
        &system,
        &end_q.unwrap_or_else(|| vec![0.0; nb]),
    );
    let zero = || vec![[0.0; 6]; plan.kept.len()];
    let history = &scene.history;
    let time = TimeResponse {
        history: history.clone(),
        method: METHOD,
        lambda: times.iter().map(|&t| history.lambda(t)).collect(),
        times,
        displacement: displacement
            .into_iter()
            .map(|d| d.unwrap_or_else(zero))
            .collect(),
        velocity: velocity
            .into_iter()
            .map(|d| d.unwrap_or_else(zero))
            .collect(),
        end_displacement,
    };
    solution.pieces = ranges
        .iter()
        .enumerate()
        .map(|(k, &(from, to))| retained.remove(&k).unwrap_or_else(|| hollow(from, to)))
        .collect();
    let response = Response {
        intervals,
        moments_at_breakpoints: diagrams,
        time,
        nodes: Some(plan.kept),
    };
    Ok(Analysis {
        targets: Vec::new(),
        scene,
        system,
        options: options.clone(),
        solution,
        reading,
        response,
        note: None,
        time_stepping: None,
    })
}

/// What the first pass leaves: the solution (its pieces not kept), the
/// hinge reading, and per piece its range and its residuals at its start
/// and its representative point.
struct FirstPass {
    solution: solve::Solution,
    reading: Reading,
    ranges: Vec<(f64, f64)>,
    residuals: Vec<Option<(Residual, Residual)>>,
}

/// Pass 1: the path traced once, each piece read by the hinge reading and
/// its residual measured, then dropped.
fn first_pass(
    scene: &Scene,
    system: &System,
    options: &AnalysisOptions,
    tolerance: f64,
    watch: Option<solve::Watch>,
) -> Result<FirstPass, FramesError> {
    let problem = system.plcp_sparse::<f64>(None).ok();
    let mut reader = hinge::Reader::new(&scene.frame, system, tolerance);
    let mut ranges: Vec<(f64, f64)> = Vec::new();
    let mut residuals: Vec<Option<(Residual, Residual)>> = Vec::new();
    let solution = solve::trace_pieces(system, &options.solve, options.escalate, watch, |k, p| {
        reader.push(k, &p);
        ranges.push((p.lambda_from, p.lambda_to));
        residuals.push(problem.as_ref().map(|problem| {
            (
                residual_at(problem, &p, p.lambda_from),
                residual_at(problem, &p, p.representative()),
            )
        }));
        Control::Continue
    })?;
    Ok(FirstPass {
        solution,
        reading: reader.finish(),
        ranges,
        residuals,
    })
}

/// The nodes whose series are kept: those `sel` names, and the nodes with
/// mass when there are at most 8 (the text report lists their accelerations).
fn kept_nodes(scene: &Scene, sel: &OutputSelection) -> Result<Vec<usize>, FramesError> {
    let frame = &scene.frame;
    let ids: Vec<&str> = frame.nodes.iter().map(|n| n.id.as_str()).collect();
    let mut kept = sel
        .node_indices(&ids)
        .map_err(|message| FramesError::Scene {
            file: scene.file.clone(),
            line: 0,
            key: "--nodes".into(),
            message,
        })?;
    let massive: Vec<usize> = (0..frame.nodes.len())
        .filter(|&i| frame.nodes[i].mass > 0.0 || frame.nodes[i].inertia > 0.0)
        .collect();
    if massive.len() <= 8 {
        kept.extend(massive);
    }
    kept.sort_unstable();
    kept.dedup();
    Ok(kept)
}

/// What pass 2 needs of each piece, known after pass 1.
struct Plan {
    /// The kept nodes, ascending.
    kept: Vec<usize>,
    /// Per coordinate of the system, its kept node's slot.
    slot_of: Vec<Option<usize>>,
    /// Per piece, the interval it starts (whose accelerations it gives).
    first_of: Vec<Option<usize>>,
    /// Per piece, the selected intervals' moment pieces it gives.
    span_of: HashMap<usize, Vec<(usize, usize)>>,
    /// Per piece, the selected breakpoints' diagrams it gives.
    diagram_of: HashMap<usize, Vec<usize>>,
    /// The breakpoints' `Lambda` values that have a diagram.
    diagram_lambdas: Vec<f64>,
    /// The last piece pass 2 needs.
    last_needed: usize,
    /// Per section, the row of its moment in `u`.
    positions: Vec<Option<usize>>,
}

impl Plan {
    fn new(
        system: &System,
        reading: &Reading,
        sel: &OutputSelection,
        kept: Vec<usize>,
        npieces: usize,
    ) -> Plan {
        let interval_lambdas: Vec<f64> =
            reading.intervals.iter().map(|iv| iv.lambda_from).collect();
        let interval_sel = sel.moment_indices(&interval_lambdas);
        let plastic: Vec<usize> = (0..reading.intervals.len())
            .filter(|&i| !reading.intervals[i].rigid)
            .collect();
        // per breakpoint, the piece that starts there (as response::build)
        let diagram_pieces: Vec<usize> = reading
            .breakpoints
            .iter()
            .zip(&plastic)
            .map(|(b, &i)| reading.intervals[i].piece_at(b.lambda))
            .collect();
        let diagram_lambdas: Vec<f64> = reading
            .breakpoints
            .iter()
            .take(diagram_pieces.len())
            .map(|b| b.lambda)
            .collect();
        let diagram_sel = sel.moment_indices(&diagram_lambdas);
        let mut first_of: Vec<Option<usize>> = vec![None; npieces];
        for (i, iv) in reading.intervals.iter().enumerate() {
            first_of[iv.piece] = Some(i);
        }
        let mut span_of: HashMap<usize, Vec<(usize, usize)>> = HashMap::new();
        for &i in &interval_sel {
            for (j, sp) in reading.intervals[i].pieces.iter().enumerate() {
                span_of.entry(sp.piece).or_default().push((i, j));
            }
        }
        let mut diagram_of: HashMap<usize, Vec<usize>> = HashMap::new();
        for &d in &diagram_sel {
            diagram_of.entry(diagram_pieces[d]).or_default().push(d);
        }
        // every interval's accelerations are reported
        let last_needed = reading
            .intervals
            .iter()
            .map(|iv| iv.piece)
            .chain(span_of.keys().copied())
            .chain(diagram_of.keys().copied())
            .max()
            .unwrap_or(0);
        let slot_of: Vec<Option<usize>> = system
            .coordinates
            .iter()
            .map(|c| kept.binary_search(&c.node).ok())
            .collect();
        Plan {
            kept,
            slot_of,
            first_of,
            span_of,
            diagram_of,
            diagram_lambdas,
            last_needed,
            positions: moment_positions(system),
        }
    }
}

/// The response's skeleton: per interval its range, its moment pieces'
/// ranges and its residual, the worst of its pieces' (as response::build).
fn skeleton(
    reading: &Reading,
    ranges: &[(f64, f64)],
    residuals: &[Option<(Residual, Residual)>],
) -> Vec<IntervalResponse> {
    // a traced path's pieces start at rising Lambda: each interval's pieces
    // are then found by bisection, not by a scan of all (else scanned)
    let sorted = ranges.windows(2).all(|w| w[0].0 <= w[1].0);
    reading
        .intervals
        .iter()
        .map(|iv| {
            let upper = iv.lambda_to.max(iv.lambda_from + f64::MIN_POSITIVE);
            let inside = |r: &(f64, f64)| r.0 >= iv.lambda_from && r.0 < upper;
            let (lo, hi) = if sorted {
                (
                    ranges.partition_point(|r| r.0 < iv.lambda_from),
                    ranges.partition_point(|r| r.0 < upper),
                )
            } else {
                (0, ranges.len())
            };
            let mut res = Residual::default();
            for k in lo..hi.max(lo) {
                if inside(&ranges[k]) {
                    if let Some((a, b)) = residuals[k] {
                        res = res.max(a);
                        res = res.max(b);
                    }
                }
            }
            IntervalResponse {
                lambda_from: iv.lambda_from,
                lambda_to: iv.lambda_to,
                accelerations: Vec::new(),
                pieces: iv
                    .pieces
                    .iter()
                    .map(|sp| MomentPiece {
                        lambda_from: sp.lambda_from,
                        lambda_to: sp.lambda_to,
                        piece: sp.piece,
                        moments: Vec::new(),
                    })
                    .collect(),
                residual: res,
            }
        })
        .collect()
}

/// What pass 2 reads and does not change.
struct Context<'a> {
    system: &'a System,
    reading: &'a Reading,
    history: &'a History,
    plan: &'a Plan,
    ranges: &'a [(f64, f64)],
    knots: &'a [f64],
    windows: &'a [Option<usize>],
}

/// Pass 2 as a fold over the pieces: the integration of the accelerations
/// (the steps of [`crate::integrate::integrate`]), the kept series, moment
/// pieces and diagrams, and the pieces they came from.
struct Fold<'a> {
    cx: Context<'a>,
    /// Per time (its bits), its indices in the response's times.
    slots: HashMap<u64, Vec<usize>>,
    t_last: Option<f64>,
    intervals: Vec<IntervalResponse>,
    diagrams: Vec<MomentDiagram>,
    displacement: Vec<Option<Vec<[f64; 6]>>>,
    velocity: Vec<Option<Vec<[f64; 6]>>>,
    end_q: Option<Vec<f64>>,
    q: Vec<f64>,
    v: Vec<f64>,
    next_window: usize,
    retained: HashMap<usize, Piece>,
    /// Whether every piece so far has the range it had in pass 1.
    same: bool,
}

impl<'a> Fold<'a> {
    fn new(cx: Context<'a>, times: &[f64], intervals: Vec<IntervalResponse>) -> Fold<'a> {
        let mut slots: HashMap<u64, Vec<usize>> = HashMap::new();
        for (k, t) in times.iter().enumerate() {
            slots.entry(t.to_bits()).or_default().push(k);
        }
        let nb = cx.system.coordinates.len();
        let diagrams = cx
            .plan
            .diagram_lambdas
            .iter()
            .map(|&lambda| MomentDiagram {
                lambda,
                moments: Vec::new(),
            })
            .collect();
        let mut fold = Fold {
            cx,
            slots,
            t_last: times.last().copied(),
            intervals,
            diagrams,
            displacement: vec![None; times.len()],
            velocity: vec![None; times.len()],
            end_q: None,
            q: vec![0.0; nb],
            v: vec![0.0; nb],
            next_window: 0,
            retained: HashMap::new(),
            same: true,
        };
        fold.record(0.0);
        fold
    }

    /// The kept nodes' rows of a coordinate vector.
    fn rows(&self, q: &[f64]) -> Vec<[f64; 6]> {
        let mut out = vec![[0.0; 6]; self.cx.plan.kept.len()];
        for (j, c) in self.cx.system.coordinates.iter().enumerate() {
            if let Some(s) = self.cx.plan.slot_of[j] {
                out[s][c.component.index()] = q.get(j).copied().unwrap_or(0.0);
            }
        }
        out
    }

    /// Keeps the state at time `t` where the response asks for it.
    fn record(&mut self, t: f64) {
        if let Some(ks) = self.slots.get(&t.to_bits()) {
            for &k in ks {
                self.displacement[k] = Some(self.rows(&self.q));
                self.velocity[k] = Some(self.rows(&self.v));
            }
        }
        if Some(t) == self.t_last {
            self.end_q = Some(self.q.clone());
        }
    }

    /// Piece `k` of the path, in order.
    fn piece(&mut self, k: usize, p: Piece) -> Control {
        let cx = &self.cx;
        self.same &= cx.ranges.get(k).is_some_and(|r| {
            r.0.to_bits() == p.lambda_from.to_bits() && r.1.to_bits() == p.lambda_to.to_bits()
        });
        if let Some(i) = cx.plan.first_of[k] {
            self.interval(i, &p);
        }
        let mut keep = false;
        let ns = self.cx.system.sections.len();
        let positions = &self.cx.plan.positions;
        let moment = |u: &[f64], s: usize| positions[s].map_or(0.0, |r| u[r]);
        if let Some(spans) = self.cx.plan.span_of.get(&k) {
            let u0 = p.u(0.0);
            for &(i, j) in spans {
                self.intervals[i].pieces[j].moments = (0..ns)
                    .map(|s| [moment(&u0, s), moment(&p.du, s)])
                    .collect();
            }
            keep = true;
        }
        if let Some(ds) = self.cx.plan.diagram_of.get(&k) {
            for &d in ds {
                let u = p.u(self.diagrams[d].lambda);
                self.diagrams[d].moments = (0..ns).map(|s| moment(&u, s)).collect();
            }
            keep = true;
        }
        if keep {
            self.retained.insert(k, p);
        }
        if k >= self.cx.plan.last_needed {
            Control::Stop
        } else {
            Control::Continue
        }
    }

    /// Interval `i`, which piece `p` starts: its accelerations kept, and
    /// the integration stepped through its windows.
    fn interval(&mut self, i: usize, p: &Piece) {
        let cx = &self.cx;
        let iv = &cx.reading.intervals[i];
        let (base, slope) = affine_accelerations(cx.system, iv, p);
        let mut acc = vec![[[0.0; 2]; 6]; cx.plan.kept.len()];
        for (j, c) in cx.system.coordinates.iter().enumerate() {
            if let Some(s) = cx.plan.slot_of[j] {
                acc[s][c.component.index()] = [base[j], slope[j]];
            }
        }
        self.intervals[i].accelerations = acc;
        // the windows of this interval, in order
        while self.next_window < self.cx.windows.len() {
            match self.cx.windows[self.next_window] {
                None => {}
                Some(w) if w == i => {
                    let (ta, tb) = (
                        self.cx.knots[self.next_window],
                        self.cx.knots[self.next_window + 1],
                    );
                    step(
                        self.cx.history,
                        (ta, tb),
                        (&base, &slope),
                        &mut self.q,
                        &mut self.v,
                    );
                    self.record(tb);
                }
                Some(_) => break,
            }
            self.next_window += 1;
        }
    }

    /// Whether pass 2 retraced pass 1 and stepped through every window.
    fn complete(&self) -> bool {
        let windows = self.cx.windows;
        self.same
            && !windows[self.next_window.min(windows.len())..]
                .iter()
                .any(Option::is_some)
    }
}
