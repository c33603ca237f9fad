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
use crate::hinge::{self, Reading};
use crate::integrate::{schedule, METHOD};
use crate::model::{History, Scene};
use crate::report::{MomentPick, NodePick, OutputSelection};
use crate::response::{
    self, residuals_of_piece, to_nodes, IntervalResponse, MomentDiagram, Response, TimeResponse,
};
use crate::solve::{self, Piece};
use plcp::{Control, Residual};
use std::collections::HashMap;

mod fold;
mod single;

use fold::{skeleton, Context, Fold, Plan};
use single::Single;

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
                return Ok(analysis(
                    scene, system, options, solution, reading, response,
                ));
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
    let times = times_of(&scene.history, &reading, options, &solution);
    // what the reports will ask for
    let sel = selection(&scene, &reading, options, moments.as_ref(), nodes.as_ref());
    let kept = kept_nodes(&scene, &sel)?;
    // the integration's windows, each with its interval; folded as the
    // intervals come, so they must come in order (a history whose lambda(t)
    // returns to an earlier interval is analysed whole)
    let (knots, windows) = windows_of(&reading, &scene.history, &times);
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
        retained,
        ..
    } = fold;
    let zero = || vec![[0.0; 6]; plan.kept.len()];
    let kept = Kept {
        displacement: displacement
            .into_iter()
            .map(|d| d.unwrap_or_else(zero))
            .collect(),
        velocity: velocity
            .into_iter()
            .map(|d| d.unwrap_or_else(zero))
            .collect(),
        end_q,
        pieces: retained,
        intervals,
        diagrams,
        nodes: plan.kept,
    };
    let (pieces, response) = assemble(&scene, &system, times, &ranges, kept);
    solution.pieces = pieces;
    Ok(analysis(
        scene, system, options, solution, reading, response,
    ))
}

/// How far the path went, as the response's times take it.
fn reached(solution: &solve::Solution) -> f64 {
    if solution.status == plcp::Status::UnboundedRay {
        f64::INFINITY
    } else {
        solution.lambda_reached
    }
}

/// The response's times, as [`Analysis::run_watched`] takes them.
fn times_of(
    history: &History,
    reading: &Reading,
    options: &AnalysisOptions,
    solution: &solve::Solution,
) -> Vec<f64> {
    response::response_times(
        history,
        reading,
        options.t_end,
        options.solve.lambda_max,
        reached(solution),
        options.samples,
    )
}

/// What the reports ask for, once the breakpoints are known: the default
/// of the path, or `moments` and `nodes` where given.
fn selection(
    scene: &Scene,
    reading: &Reading,
    options: &AnalysisOptions,
    moments: Option<&MomentPick>,
    nodes: Option<&NodePick>,
) -> OutputSelection {
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
    sel
}

/// The integration's knots and windows, each window with its interval
/// ([`schedule`]).
fn windows_of(
    reading: &Reading,
    history: &History,
    times: &[f64],
) -> (Vec<f64>, Vec<Option<usize>>) {
    let iv_ranges: Vec<(f64, f64)> = reading
        .intervals
        .iter()
        .map(|iv| (iv.lambda_from, iv.lambda_to))
        .collect();
    schedule(&iv_ranges, history, times)
}

/// What either route keeps for the response: the kept nodes' series at
/// every time, the end state, the pieces kept, the intervals and diagrams.
struct Kept {
    displacement: Vec<Vec<[f64; 6]>>,
    velocity: Vec<Vec<[f64; 6]>>,
    end_q: Option<Vec<f64>>,
    pieces: HashMap<usize, Piece>,
    intervals: Vec<IntervalResponse>,
    diagrams: Vec<MomentDiagram>,
    nodes: Vec<usize>,
}

/// The solution's pieces (kept, or hollow: their range only) and the
/// response, from what a route kept.
fn assemble(
    scene: &Scene,
    system: &System,
    times: Vec<f64>,
    ranges: &[(f64, f64)],
    mut kept: Kept,
) -> (Vec<Piece>, Response) {
    let nb = system.coordinates.len();
    let end_displacement = to_nodes(
        &scene.frame,
        system,
        &kept.end_q.unwrap_or_else(|| vec![0.0; nb]),
    );
    let history = &scene.history;
    let time = TimeResponse {
        history: history.clone(),
        method: METHOD,
        lambda: times.iter().map(|&t| history.lambda(t)).collect(),
        times,
        displacement: kept.displacement,
        velocity: kept.velocity,
        end_displacement,
    };
    let pieces = ranges
        .iter()
        .enumerate()
        .map(|(k, &(from, to))| kept.pieces.remove(&k).unwrap_or_else(|| hollow(from, to)))
        .collect();
    let response = Response {
        intervals: kept.intervals,
        moments_at_breakpoints: kept.diagrams,
        time,
        nodes: Some(kept.nodes),
    };
    (pieces, response)
}

/// The analysis a route ends with.
fn analysis(
    scene: Scene,
    system: System,
    options: &AnalysisOptions,
    solution: solve::Solution,
    reading: Reading,
    response: Response,
) -> Analysis {
    Analysis {
        targets: Vec::new(),
        scene,
        system,
        options: options.clone(),
        solution,
        reading,
        response,
        note: None,
        time_stepping: None,
    }
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
        ranges.push((p.lambda_from, p.lambda_to));
        residuals.push(
            problem
                .as_ref()
                .map(|problem| residuals_of_piece(problem, &p)),
        );
        // last: the one-pass route keeps the piece itself where it needs it
        // (moved, not copied)
        if let Some(single) = single.as_deref_mut() {
            single.piece(k, p, &reader);
        }
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
