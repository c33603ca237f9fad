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
//! One trace is enough where what pass 2 needs is known before the trace:
//! the sampled `Lambda` values (the default of a large scene with
//! `lambda_max`, [`crate::report::OutputSelection::default_for`], or
//! `--moments L1,L2,...`), the kept nodes, and the end time (`t_end`, or the
//! time `Lambda` reaches `lambda_max`). Then pass 1 also integrates the
//! accelerations window by window as the knots behind the reading's frontier
//! become final, and keeps the pieces of the intervals nearest the sampled
//! values so far; at the end every guess is checked against what pass 2
//! would use (end time, knots, windows and their intervals, selection), and
//! pass 2 runs only where one failed (an end time cut by a path that stops
//! early, a last breakpoint below `lambda_max / 1.5`, a count of samples,
//! `--moments all`).
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
use crate::hinge::{self, moment_positions, EventPoint, Interval, Reading};
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
    // one pass where what pass 2 needs is decided before the trace
    let kept_up_front = match &nodes {
        Some(n) => kept_nodes(
            &scene,
            &OutputSelection {
                nodes: n.clone(),
                ..OutputSelection::all()
            },
        )?,
        None => kept_nodes(
            &scene,
            &OutputSelection::default_for_counts(scene.frame.nodes.len(), usize::MAX),
        )?,
    };
    let mut single = Single::new(&scene, &system, options, &moments, kept_up_front);
    // pass 1: the reading, and each piece's range and residuals
    let first = first_pass(
        &scene,
        &system,
        options,
        tolerance,
        watch.clone(),
        single.as_mut(),
    )?;
    let poor = !first.solution.status.is_success() || first.solution.info.residual.worst() > 1e-6;
    if first.solution.info.escalation.is_some() || poor || first.solution.tolerance != tolerance {
        return Analysis::run_watched(scene, options, watch);
    }
    let first = match single {
        Some(single) => match single.finish(first, &scene, options, &moments, &nodes) {
            Ok(done) => {
                let (solution, reading, response) = *done;
                return Ok(Analysis {
                    targets: Vec::new(),
                    scene,
                    system,
                    options: options.clone(),
                    solution,
                    reading,
                    response,
                    note: None,
                    time_stepping: None,
                });
            }
            Err(first) => *first,
        },
        None => first,
    };
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
    let mut sel = OutputSelection::default_for_path(
        scene.frame.nodes.len(),
        reading.breakpoints.len(),
        reading.breakpoints.first().map(|b| b.lambda),
        options.solve.lambda_max,
    );
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
    mut single: Option<&mut Single<'_>>,
) -> Result<FirstPass, FramesError> {
    let problem = system.plcp_sparse::<f64>(None).ok();
    let mut reader = hinge::Reader::new(&scene.frame, system, tolerance);
    let mut ranges: Vec<(f64, f64)> = Vec::new();
    let mut residuals: Vec<Option<(Residual, Residual)>> = Vec::new();
    let solution = solve::trace_pieces(system, &options.solve, options.escalate, watch, |k, p| {
        reader.push(k, &p);
        if let Some(single) = single.as_deref_mut() {
            single.piece(k, &p, &reader);
        }
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
        let ns = self.cx.system.sections.len();
        let keep = moments_of(
            self.cx.plan,
            ns,
            k,
            &p,
            &mut self.intervals,
            &mut self.diagrams,
        );
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

/// The moment pieces of the selected intervals and the diagrams at the
/// selected breakpoints that piece `k` gives ([`Plan::span_of`],
/// [`Plan::diagram_of`]); whether it gave any (it is then kept).
fn moments_of(
    plan: &Plan,
    ns: usize,
    k: usize,
    p: &Piece,
    intervals: &mut [IntervalResponse],
    diagrams: &mut [MomentDiagram],
) -> bool {
    let positions = &plan.positions;
    let moment = |u: &[f64], s: usize| positions[s].map_or(0.0, |r| u[r]);
    let mut keep = false;
    if let Some(spans) = plan.span_of.get(&k) {
        let u0 = p.u(0.0);
        for &(i, j) in spans {
            intervals[i].pieces[j].moments = (0..ns)
                .map(|s| [moment(&u0, s), moment(&p.du, s)])
                .collect();
        }
        keep = true;
    }
    if let Some(ds) = plan.diagram_of.get(&k) {
        for &d in ds {
            let u = p.u(diagrams[d].lambda);
            diagrams[d].moments = (0..ns).map(|s| moment(&u, s)).collect();
        }
        keep = true;
    }
    keep
}

/// The kept nodes' displacements and velocities at one time.
type NodeState = (Vec<[f64; 6]>, Vec<[f64; 6]>);

/// The sampled `Lambda` values of a one-pass analysis: given, or spread
/// from the first breakpoint (known once it is read) to `lambda_max`.
enum Targets {
    Fixed(Vec<f64>),
    FromFirst { to: f64, count: usize },
}

/// One pass instead of two ([`run_in_passes`]), where what the second pass
/// needs is decided before the trace: the sampled `Lambda` values
/// ([`MomentPick::At`], the default of a large scene with `lambda_max`:
/// [`OutputSelection::default_for`]), the kept nodes, and the end time (the
/// time `Lambda` reaches `lambda_max`, or `t_end`). Alongside the hinge
/// reading it integrates the accelerations window by window as the knots
/// behind the reading's frontier become final, keeps the kept nodes' states
/// at every knot, and keeps the pieces of the intervals nearest the sampled
/// values so far (a later one replaces them). At the end every guess is
/// checked against what the two passes would use (the end time, the knots
/// and windows of [`schedule`] with the interval of each, the selected
/// intervals and diagrams): the same operations on the same numbers, else
/// the second pass runs as before.
struct Single<'a> {
    system: &'a System,
    history: &'a History,
    kept: Vec<usize>,
    slot_of: Vec<Option<usize>>,
    targets: Targets,
    /// The resolved sampled values (once the first breakpoint is read).
    values: Option<Vec<f64>>,
    t_end: f64,
    /// Knots above `t_cur` not yet stepped to (bits of nonnegative times).
    knots: std::collections::BTreeSet<u64>,
    t_cur: f64,
    q: Vec<f64>,
    v: Vec<f64>,
    /// The windows stepped: start, end (bits) and interval.
    steps: Vec<(u64, u64, usize)>,
    /// The kept nodes' displacements and velocities at every knot reached.
    rows: HashMap<u64, NodeState>,
    end_q: Option<Vec<f64>>,
    /// Per interval not yet passed by the integration, its accelerations.
    accel: std::collections::BTreeMap<usize, (Vec<f64>, Vec<f64>)>,
    /// Per interval, the kept nodes' accelerations.
    acc_rows: Vec<Vec<[[f64; 2]; 6]>>,
    /// Per interval read so far, its start; per breakpoint, its interval.
    iv_from: Vec<f64>,
    /// The plastic intervals read so far.
    plastic: Vec<usize>,
    bp_interval: Vec<(f64, usize)>,
    /// The last interval of a window.
    cursor: usize,
    /// Per sampled value, the nearest interval start and breakpoint so far
    /// (index, distance).
    best_iv: Vec<Option<(usize, f64)>>,
    best_bp: Vec<Option<(usize, f64)>>,
    /// The pieces of the candidate intervals.
    retained: HashMap<usize, Piece>,
    /// The intervals nearest a sampled value so far.
    wanted: std::collections::HashSet<usize>,
    /// Whether `wanted` changed since the pieces kept were last pruned.
    gc: bool,
    /// Something the guesses cannot follow happened: two passes.
    failed: bool,
}

impl<'a> Single<'a> {
    /// `None` where the selection or the end time needs the whole path.
    fn new(
        scene: &'a Scene,
        system: &'a System,
        options: &AnalysisOptions,
        moments: &Option<MomentPick>,
        kept: Vec<usize>,
    ) -> Option<Single<'a>> {
        let lambda_max = options.solve.lambda_max.filter(|l| l.is_finite());
        let targets = match moments {
            Some(MomentPick::At(v)) => Targets::Fixed(v.clone()),
            None if scene.frame.nodes.len() > crate::report::SMALL_SCENE => Targets::FromFirst {
                to: lambda_max?,
                count: crate::report::DEFAULT_SAMPLES,
            },
            _ => return None,
        };
        let history = &scene.history;
        let t_end = match options.t_end {
            Some(t) => t,
            None => response::t_end_at(history, lambda_max?),
        };
        if !(t_end.is_finite() && t_end > 0.0) {
            return None;
        }
        // the knots known before the trace (integrate::schedule's, with the
        // times of response::response_times but its breakpoints')
        let n = options.samples.max(2);
        let mut knots = std::collections::BTreeSet::new();
        let add = |t: f64, set: &mut std::collections::BTreeSet<u64>| {
            if t > 0.0 {
                set.insert(t.to_bits());
            }
        };
        add(t_end, &mut knots);
        for i in 0..n {
            add(t_end * i as f64 / (n - 1) as f64, &mut knots);
        }
        for t in history.knots(t_end) {
            add(t, &mut knots);
        }
        let slot_of = system
            .coordinates
            .iter()
            .map(|c| kept.binary_search(&c.node).ok())
            .collect();
        let values = match &targets {
            Targets::Fixed(v) => Some(v.clone()),
            Targets::FromFirst { .. } => None,
        };
        let nb = system.coordinates.len();
        let mut single = Single {
            system,
            history,
            kept,
            slot_of,
            targets,
            values,
            t_end,
            knots,
            t_cur: 0.0,
            q: vec![0.0; nb],
            v: vec![0.0; nb],
            steps: Vec::new(),
            rows: HashMap::new(),
            end_q: None,
            accel: std::collections::BTreeMap::new(),
            acc_rows: Vec::new(),
            iv_from: Vec::new(),
            plastic: Vec::new(),
            bp_interval: Vec::new(),
            cursor: 0,
            best_iv: Vec::new(),
            best_bp: Vec::new(),
            retained: HashMap::new(),
            wanted: std::collections::HashSet::new(),
            gc: false,
            failed: false,
        };
        single.best_iv = vec![None; single.values.as_ref().map_or(0, Vec::len)];
        single.best_bp = single.best_iv.clone();
        single.record(0.0);
        Some(single)
    }

    /// The kept nodes' rows of a coordinate vector.
    fn node_rows(&self, q: &[f64]) -> Vec<[f64; 6]> {
        let mut out = vec![[0.0; 6]; self.kept.len()];
        for (j, c) in self.system.coordinates.iter().enumerate() {
            if let Some(s) = self.slot_of[j] {
                out[s][c.component.index()] = q[j];
            }
        }
        out
    }

    fn record(&mut self, t: f64) {
        let rows = (self.node_rows(&self.q), self.node_rows(&self.v));
        self.rows.insert(t.to_bits(), rows);
        if t.to_bits() == self.t_end.to_bits() {
            self.end_q = Some(self.q.clone());
        }
    }

    /// A knot at the time `Lambda` reaches `lambda` (inside `(0, t_end)`).
    fn knot_at(&mut self, lambda: f64) {
        if let Some(t) = self.history.time_at(lambda) {
            if t > 0.0 && t < self.t_end {
                if t <= self.t_cur {
                    // a knot behind the integration: the guesses fail
                    self.failed = true;
                }
                self.knots.insert(t.to_bits());
            }
        }
    }

    /// The intervals and breakpoints the reading added: their accelerations,
    /// knots, and whether they are nearest a sampled value.
    fn read_new(&mut self, k: Option<(usize, &Piece)>, intervals: &[Interval], bps: &[EventPoint]) {
        let nb = self.system.coordinates.len();
        let first_new = self.iv_from.len();
        for (i, iv) in intervals.iter().enumerate().skip(first_new) {
            let acc = if iv.rigid {
                (vec![0.0; nb], vec![0.0; nb])
            } else {
                match k {
                    Some((k, p)) if iv.piece == k => affine_accelerations(self.system, iv, p),
                    _ => {
                        self.failed = true;
                        (vec![0.0; nb], vec![0.0; nb])
                    }
                }
            };
            let mut rows = vec![[[0.0; 2]; 6]; self.kept.len()];
            for (j, c) in self.system.coordinates.iter().enumerate() {
                if let Some(s) = self.slot_of[j] {
                    rows[s][c.component.index()] = [acc.0[j], acc.1[j]];
                }
            }
            self.acc_rows.push(rows);
            self.accel.insert(i, acc);
            self.iv_from.push(iv.lambda_from);
            self.knot_at(iv.lambda_from);
        }
        for (i, iv) in intervals.iter().enumerate().skip(first_new) {
            if !iv.rigid {
                self.plastic.push(i);
            }
        }
        // per breakpoint, its plastic interval (as response::build zips them)
        let first_bp = self.bp_interval.len();
        for (d, b) in bps.iter().enumerate().skip(first_bp) {
            match self.plastic.get(d).copied() {
                Some(i) => self.bp_interval.push((b.lambda, i)),
                None => self.failed = true,
            }
            self.knot_at(b.lambda);
        }
        if self.values.is_none() {
            if let (Targets::FromFirst { to, count }, Some(&(first, _))) =
                (&self.targets, self.bp_interval.first())
            {
                let v = crate::report::spread(first, *to, *count);
                self.best_iv = vec![None; v.len()];
                self.best_bp = vec![None; v.len()];
                self.values = Some(v);
                // score everything read so far
                self.score(0, 0);
                return;
            }
        }
        if self.values.is_some() {
            self.score(first_new, first_bp);
        }
    }

    /// The intervals from `iv0` and breakpoints from `bp0` against the
    /// nearest so far (the first of equals wins, as `moment_indices`).
    fn score(&mut self, iv0: usize, bp0: usize) {
        let values = self.values.as_ref().expect("resolved values");
        let mut changed = false;
        for (t, &v) in values.iter().enumerate() {
            for (i, &from) in self.iv_from.iter().enumerate().skip(iv0) {
                let dist = (from - v).abs();
                if self.best_iv[t].is_none_or(|(_, b)| dist.total_cmp(&b).is_lt()) {
                    self.best_iv[t] = Some((i, dist));
                    changed = true;
                }
            }
            for (d, &(lambda, _)) in self.bp_interval.iter().enumerate().skip(bp0) {
                let dist = (lambda - v).abs();
                if self.best_bp[t].is_none_or(|(_, b)| dist.total_cmp(&b).is_lt()) {
                    self.best_bp[t] = Some((d, dist));
                    changed = true;
                }
            }
        }
        if changed {
            self.wanted = self.best_iv.iter().flatten().map(|&(i, _)| i).collect();
            for &(d, _) in self.best_bp.iter().flatten() {
                self.wanted.insert(self.bp_interval[d].1);
            }
            self.gc = true;
        }
    }

    /// Piece `k`, just read by `reader`.
    fn piece(&mut self, k: usize, p: &Piece, reader: &hinge::Reader<'_>) {
        if self.failed {
            return;
        }
        let intervals = reader.intervals();
        self.read_new(Some((k, p)), intervals, reader.breakpoints());
        if self.gc {
            let keep: std::collections::HashSet<usize> = self
                .wanted
                .iter()
                .flat_map(|&i| intervals[i].pieces.iter().map(|sp| sp.piece))
                .collect();
            self.retained.retain(|k, _| keep.contains(k));
            self.gc = false;
        }
        if let Some(last) = intervals.len().checked_sub(1) {
            if self.wanted.contains(&last)
                && intervals[last]
                    .pieces
                    .last()
                    .is_some_and(|sp| sp.piece == k)
            {
                self.retained.insert(k, p.clone());
            }
        }
        // every later knot is at or above the frontier's time
        if let (Some(front), false) = (reader.frontier(), intervals.is_empty()) {
            let limit = self.history.time_at(front).unwrap_or(f64::INFINITY);
            self.advance(intervals, limit, false);
        }
    }

    /// Steps the integration through the windows ending below `limit`
    /// (every window left, if `last`).
    fn advance(&mut self, intervals: &[Interval], limit: f64, last: bool) {
        use std::ops::Bound::{Excluded, Unbounded};
        while let Some(&next) = self
            .knots
            .range((Excluded(self.t_cur.to_bits()), Unbounded))
            .next()
        {
            let (ta, tb) = (self.t_cur, f64::from_bits(next));
            if !(last || tb < limit) {
                break;
            }
            // the first interval holding the window's middle, as schedule's piece_at
            let l = self.history.lambda(0.5 * (ta + tb));
            let holds = |i: usize| l >= intervals[i].lambda_from && l <= intervals[i].lambda_to;
            let i = (self.cursor..intervals.len())
                .find(|&i| holds(i))
                .or_else(|| (0..intervals.len()).find(|&i| holds(i)))
                .unwrap_or(intervals.len() - 1);
            self.cursor = i;
            let Some((base, slope)) = self.accel.get(&i) else {
                self.failed = true;
                return;
            };
            step(
                self.history,
                (ta, tb),
                (base, slope),
                &mut self.q,
                &mut self.v,
            );
            self.steps.push((ta.to_bits(), tb.to_bits(), i));
            self.t_cur = tb;
            self.record(tb);
            // the intervals behind the window are passed
            let ahead = self.accel.split_off(&i);
            self.accel = ahead;
        }
    }

    /// The analysis from the pass (`first`), if every guess held; else
    /// `first` back, for the second pass.
    fn finish(
        mut self,
        first: FirstPass,
        scene: &Scene,
        options: &AnalysisOptions,
        moments: &Option<MomentPick>,
        nodes: &Option<NodePick>,
    ) -> Result<Box<(solve::Solution, Reading, Response)>, Box<FirstPass>> {
        if self.failed || first.reading.intervals.is_empty() {
            return Err(Box::new(first));
        }
        // what the reading's end added (rigid intervals only: no piece is left)
        self.read_new(None, &first.reading.intervals, &first.reading.breakpoints);
        let gone = self
            .wanted
            .iter()
            .any(|&i| first.reading.intervals[i].rigid);
        if self.failed || gone || self.values.is_none() {
            return Err(Box::new(first));
        }
        self.advance(&first.reading.intervals, f64::INFINITY, true);
        let solution = &first.solution;
        let reading = &first.reading;
        let reached = if solution.status == plcp::Status::UnboundedRay {
            f64::INFINITY
        } else {
            solution.lambda_reached
        };
        let times = response::response_times(
            self.history,
            reading,
            options.t_end,
            options.solve.lambda_max,
            reached,
            options.samples,
        );
        // the second pass's knots, windows and their intervals
        let iv_ranges: Vec<(f64, f64)> = reading
            .intervals
            .iter()
            .map(|iv| (iv.lambda_from, iv.lambda_to))
            .collect();
        let (knots, windows) = schedule(&iv_ranges, self.history, &times);
        let expected = windows
            .iter()
            .enumerate()
            .filter_map(|(w, i)| i.map(|i| (knots[w].to_bits(), knots[w + 1].to_bits(), i)));
        let same_steps = expected.eq(self.steps.iter().copied());
        let same_end = times.last().map(|t| t.to_bits()) == Some(self.t_end.to_bits());
        // the second pass's selection
        let mut sel = OutputSelection::default_for_path(
            scene.frame.nodes.len(),
            reading.breakpoints.len(),
            reading.breakpoints.first().map(|b| b.lambda),
            options.solve.lambda_max,
        );
        if let Some(m) = moments {
            sel.moments = m.clone();
        }
        if let Some(n) = nodes {
            sel.nodes = n.clone();
        }
        let same_sel = Some(&sel.moments) == self.values.clone().map(MomentPick::At).as_ref()
            && kept_nodes(scene, &sel).ok().as_ref() == Some(&self.kept)
            && self.acc_rows.len() == reading.intervals.len();
        if !(same_steps && same_end && same_sel) {
            return Err(Box::new(first));
        }
        let plan = Plan::new(
            self.system,
            reading,
            &sel,
            self.kept.clone(),
            first.ranges.len(),
        );
        let needed: Vec<usize> = {
            let mut v: Vec<usize> = plan
                .span_of
                .keys()
                .chain(plan.diagram_of.keys())
                .copied()
                .collect();
            v.sort_unstable();
            v.dedup();
            v
        };
        if needed.iter().any(|k| !self.retained.contains_key(k)) {
            return Err(Box::new(first));
        }
        let FirstPass {
            mut solution,
            reading,
            ranges,
            residuals,
        } = first;
        let mut intervals = skeleton(&reading, &ranges, &residuals);
        for (iv, acc) in intervals.iter_mut().zip(std::mem::take(&mut self.acc_rows)) {
            iv.accelerations = acc;
        }
        let mut diagrams: Vec<MomentDiagram> = plan
            .diagram_lambdas
            .iter()
            .map(|&lambda| MomentDiagram {
                lambda,
                moments: Vec::new(),
            })
            .collect();
        let ns = self.system.sections.len();
        let mut kept_pieces: HashMap<usize, Piece> = HashMap::new();
        for k in needed {
            let p = self.retained.remove(&k).expect("a retained piece");
            moments_of(&plan, ns, k, &p, &mut intervals, &mut diagrams);
            kept_pieces.insert(k, p);
        }
        let nb = self.system.coordinates.len();
        let end_displacement = to_nodes(
            &scene.frame,
            self.system,
            &self.end_q.take().unwrap_or_else(|| vec![0.0; nb]),
        );
        let zero = || vec![[0.0; 6]; self.kept.len()];
        let (mut displacement, mut velocity) = (Vec::new(), Vec::new());
        for t in &times {
            match self.rows.get(&t.to_bits()) {
                Some((d, v)) => {
                    displacement.push(d.clone());
                    velocity.push(v.clone());
                }
                None => {
                    displacement.push(zero());
                    velocity.push(zero());
                }
            }
        }
        let history = self.history;
        let time = TimeResponse {
            history: history.clone(),
            method: METHOD,
            lambda: times.iter().map(|&t| history.lambda(t)).collect(),
            times,
            displacement,
            velocity,
            end_displacement,
        };
        solution.pieces = ranges
            .iter()
            .enumerate()
            .map(|(k, &(from, to))| kept_pieces.remove(&k).unwrap_or_else(|| hollow(from, to)))
            .collect();
        let response = Response {
            intervals,
            moments_at_breakpoints: diagrams,
            time,
            nodes: Some(plan.kept),
        };
        Ok(Box::new((solution, reading, response)))
    }
}
