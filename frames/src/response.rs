//! The response: accelerations and member forces affine in `Lambda` on each
//! interval, the bending moments at every critical `Lambda`, the residual of
//! system (9) on every interval, and velocities and displacements over time
//! for the scene's history.
//!
//! **Member forces piece by piece.** The accelerations are one affine function
//! of `Lambda` on each interval, but the member forces are affine only on each
//! piece of the path: the path pivots inside the rigid phase of an
//! indeterminate frame (a redundant moment reaching yield) and inside a
//! plastic interval where the stress is not unique. An interval's moments are
//! therefore given per piece ([`IntervalResponse::pieces`]), and the moments
//! at any `Lambda` are read from the piece that holds it
//! ([`Response::moments_at`]). They are the path's own stress state: within
//! every section's capacity (the path keeps `y* >= 0`, to its residual) and
//! continuous in `Lambda` (consecutive pieces and intervals join at their
//! common breakpoint), though in the rigid phase and wherever the stress is
//! not unique, one statically admissible state among many (see
//! [`crate::hinge`]).

use crate::assemble::System;
use crate::hinge::{moment_positions, Interval, Reading, Span};
use crate::integrate::{integrate, AffinePiece, Motion, METHOD};
use crate::model::{Frame, History};
use crate::solve::{Piece, Solution};
use faer::Col;
use plcp::{Point, Residual};

/// `[base, slope]`: the value is `base + slope * Lambda`.
pub type Affine = [f64; 2];

/// One interval of the response.
#[derive(Clone, Debug, PartialEq)]
pub struct IntervalResponse {
    /// Start.
    pub lambda_from: f64,
    /// End (`f64::INFINITY` when unbounded).
    pub lambda_to: f64,
    /// Accelerations per node, per component (by [`crate::model::Component::index`]:
    /// `[x, y, rz, z, rx, ry]`), affine in `Lambda` (zero for supported and
    /// left-out components and those not of the model).
    pub accelerations: Vec<[Affine; 6]>,
    /// The bending moments on each piece of the path the interval holds, in
    /// order, covering it end to end (one piece where the path does not pivot
    /// inside the interval).
    pub pieces: Vec<MomentPiece>,
    /// Worst residual of the mixed PLCP of system (9) at the ends of the interval
    /// (at its start and at one more point when unbounded): equation (dynamic
    /// equilibrium, kinematics, yield), feasibility, complementarity.
    pub residual: Residual,
}

/// The bending moments on one piece of the path inside an interval.
#[derive(Clone, Debug, PartialEq)]
pub struct MomentPiece {
    /// Start.
    pub lambda_from: f64,
    /// End (`f64::INFINITY` when unbounded).
    pub lambda_to: f64,
    /// The piece of the path (index into [`crate::solve::Solution::pieces`]).
    pub piece: usize,
    /// Bending moment per critical section, affine in `Lambda` on
    /// `[lambda_from, lambda_to]` (not unique where the stress is not; see
    /// [`crate::hinge`]).
    pub moments: Vec<Affine>,
}

impl IntervalResponse {
    /// The piece that holds `lambda`: the last one starting at or before it
    /// (the later one at a breakpoint between two), the first one before the
    /// interval.
    pub fn piece_at(&self, lambda: f64) -> &MomentPiece {
        self.pieces
            .iter()
            .rev()
            .find(|p| p.lambda_from <= lambda)
            .unwrap_or(&self.pieces[0])
    }

    /// The bending moment of every critical section at `lambda`, from the
    /// piece that holds it.
    pub fn moments_at(&self, lambda: f64) -> Vec<f64> {
        self.piece_at(lambda)
            .moments
            .iter()
            .map(|m| m[0] + m[1] * lambda)
            .collect()
    }
}

/// The bending moments at one critical `Lambda`.
#[derive(Clone, Debug, PartialEq)]
pub struct MomentDiagram {
    /// The load parameter.
    pub lambda: f64,
    /// Bending moment (sagging positive) at every critical section.
    pub moments: Vec<f64>,
}

/// Displacements and velocities of the nodes over time.
#[derive(Clone, Debug, PartialEq)]
pub struct TimeResponse {
    /// The history.
    pub history: History,
    /// How velocities and displacements were integrated.
    pub method: &'static str,
    /// Times.
    pub times: Vec<f64>,
    /// `lambda(t)`.
    pub lambda: Vec<f64>,
    /// Per time, per node, by [`crate::model::Component::index`] (`[x, y, rz, z, rx, ry]`).
    pub displacement: Vec<Vec<[f64; 6]>>,
    /// Per time, per node, by [`crate::model::Component::index`].
    pub velocity: Vec<Vec<[f64; 6]>>,
    /// Every node's displacement at the last time (the last row of
    /// `displacement`, kept whole where the rows hold a selection of the
    /// nodes: [`Response::nodes`]).
    pub end_displacement: Vec<[f64; 6]>,
}

/// Everything the response holds.
#[derive(Clone, Debug, PartialEq)]
pub struct Response {
    /// One per interval of the reading.
    pub intervals: Vec<IntervalResponse>,
    /// One per breakpoint of the reading.
    pub moments_at_breakpoints: Vec<MomentDiagram>,
    /// Over time.
    pub time: TimeResponse,
    /// `None`: the node-indexed vectors (`IntervalResponse::accelerations`,
    /// the rows of `TimeResponse::displacement` and `velocity`) hold every
    /// node. `Some(nodes)` (a large scene's analysis, [`crate::stream`]):
    /// they hold these nodes only, in this (rising) order; and only the
    /// selected intervals' moment pieces and breakpoints' diagrams hold
    /// moments (the others are empty). [`Response::slot`] finds a node.
    pub nodes: Option<Vec<usize>>,
}

impl Response {
    /// Where `node`'s entries sit in the node-indexed vectors (see
    /// [`Response::nodes`]); `None` if they were not kept.
    pub fn slot(&self, node: usize) -> Option<usize> {
        match &self.nodes {
            None => Some(node),
            Some(kept) => kept.binary_search(&node).ok(),
        }
    }

    /// The bending moment of every critical section at `lambda`, from the
    /// piece of the path that holds it (at a breakpoint, the piece that starts
    /// there); `None` outside the reported intervals.
    pub fn moments_at(&self, lambda: f64) -> Option<Vec<f64>> {
        let iv = self
            .intervals
            .iter()
            .rev()
            .find(|iv| iv.lambda_from <= lambda)?;
        (lambda <= iv.lambda_to).then(|| iv.moments_at(lambda))
    }
}

/// The tolerance of the reported member forces, relative to the scene's
/// scale: a reported moment `M_k` lies within its section's capacity as
/// `|M_k| <= Mp_k + tol * max(Mp_k, S)`, and two fields meet at a common
/// breakpoint as `|M_k - M'_k| <= tol * max(Mp_k, S)`, with `S` the largest
/// `|M|` of the field there and
///
/// ```text
/// tol = max(Solution::tolerance, 64 kappa eps)
/// ```
///
/// (`eps` of the working precision, `kappa` the largest basis condition
/// estimate on the path, [`plcp::Info::max_condition`]): a value solved from a
/// basis of condition `kappa` carries a forward error of about `kappa eps`
/// relative to the largest value solved with it. `Solution::tolerance`
/// (`10 sqrt(eps)`) is the one the hinge reading decides yield with.
pub fn force_tolerance(solution: &Solution) -> f64 {
    let eps = match solution.info.precision {
        "f32" => f64::from(f32::EPSILON),
        "f128" => f64::EPSILON * f64::EPSILON,
        _ => f64::EPSILON,
    };
    let kappa = if solution.info.max_condition.is_finite() {
        solution.info.max_condition
    } else {
        0.0
    };
    solution.tolerance.max(64.0 * kappa * eps)
}

pub(crate) fn to_nodes(frame: &Frame, system: &System, q: &[f64]) -> Vec<[f64; 6]> {
    let mut out = vec![[0.0; 6]; frame.nodes.len()];
    for (j, c) in system.coordinates.iter().enumerate() {
        // a path that stopped early may carry fewer values than coordinates
        out[c.node][c.component.index()] = q.get(j).copied().unwrap_or(0.0);
    }
    out
}

/// The residual of the mixed PLCP (`system.plcp::<f64>(None)`) at `lambda` on a piece.
pub fn residual_at(problem: &plcp::Plcp<f64>, piece: &Piece, lambda: f64) -> Residual {
    plcp::residual::residual(problem, &point_at(piece, lambda))
}

/// [`residual_at`] at the piece's start and at its representative point
/// ([`Piece::representative`]), in one sweep over `M`
/// ([`plcp::residual::residuals`]: the same bits as two calls).
pub fn residuals_of_piece(problem: &plcp::Plcp<f64>, piece: &Piece) -> (Residual, Residual) {
    let from = point_at(piece, piece.lambda_from);
    let mid = point_at(piece, piece.representative());
    let [a, b] = plcp::residual::residuals(problem, [&from, &mid]);
    (a, b)
}

/// The piece's point at `lambda`, the values as [`Piece::z`] (`from + slope
/// (lambda - lambda_from)`) written straight into the columns.
fn point_at(piece: &Piece, lambda: f64) -> Point<f64> {
    let dl = lambda - piece.lambda_from;
    let col = |from: &[f64], slope: &[f64]| {
        Col::from_fn(from.len().min(slope.len()), |i| from[i] + slope[i] * dl)
    };
    Point {
        lambda,
        z: col(&piece.z_from, &piece.dz),
        w: col(&piece.w_from, &piece.dw),
        u: col(&piece.u_from, &piece.du),
    }
}

/// The affine accelerations of an interval (zero in the rigid phase).
pub(crate) fn affine_accelerations(
    system: &System,
    iv: &Interval,
    piece: &Piece,
) -> (Vec<f64>, Vec<f64>) {
    let nb = system.coordinates.len();
    if iv.rigid {
        return (vec![0.0; nb], vec![0.0; nb]);
    }
    // `piece.u(0.0)` (`from + slope (0 - lambda_from)`) for the first `nb`
    // entries only
    let dl = 0.0 - piece.lambda_from;
    let base = piece.u_from[..nb]
        .iter()
        .zip(&piece.du[..nb])
        .map(|(a, b)| a + b * dl)
        .collect();
    (base, piece.du[..nb].to_vec())
}

/// A default end time: `Lambda` reaches 1.5 times the last critical value (or
/// `lambda_max`, or the history's plateau), whichever the history allows.
pub fn default_t_end(history: &History, reading: &Reading, lambda_max: Option<f64>) -> f64 {
    let last = reading.breakpoints.last().map(|b| b.lambda).unwrap_or(1.0);
    let mut target = 1.5 * last;
    if let Some(lm) = lambda_max {
        target = target.min(lm);
    }
    t_end_at(history, target)
}

/// The time at which `Lambda` reaches `target` (where the history never
/// does: its plateau's end, as [`default_t_end`]).
pub(crate) fn t_end_at(history: &History, target: f64) -> f64 {
    match history.time_at(target) {
        Some(t) if t > 0.0 => t,
        _ => match history {
            History::Saturating { tau, .. } => 5.0 * tau,
            History::Table { points } => 1.5 * points[points.len() - 1].0,
            History::Ramp { rate } => target.max(1.0) / rate,
        },
    }
}

/// The times of the time response: `t_end` (`t_end`, or
/// [`default_t_end`], cut to where the path was traced: `reached`, infinite
/// for an unbounded ray) in `samples` even steps, with the time of every
/// breakpoint inside it added, sorted, without repeats.
pub fn response_times(
    history: &History,
    reading: &Reading,
    t_end: Option<f64>,
    lambda_max: Option<f64>,
    reached: f64,
    samples: usize,
) -> Vec<f64> {
    let mut t_end = t_end.unwrap_or_else(|| default_t_end(history, reading, lambda_max));
    // the path is known only up to where it was traced
    if history.lambda(t_end) > reached {
        t_end = history.time_at(reached).unwrap_or(t_end);
    }
    let n = samples.max(2);
    let mut times: Vec<f64> = (0..n).map(|i| t_end * i as f64 / (n - 1) as f64).collect();
    for b in &reading.breakpoints {
        if let Some(t) = history.time_at(b.lambda) {
            if t > 0.0 && t < t_end {
                times.push(t);
            }
        }
    }
    times.sort_by(f64::total_cmp);
    times.dedup();
    times
}

/// Builds the response.
pub fn build(
    frame: &Frame,
    system: &System,
    pieces: &[Piece],
    reading: &Reading,
    history: &History,
    times: &[f64],
) -> Response {
    // each section's moment read from u by its position, found once (a search
    // of the member forces per section and piece was quadratic: 3 s of a
    // 1000-element cantilever's analysis)
    let positions = moment_positions(system);
    let moment = |u: &[f64], k: usize| positions[k].map_or(0.0, |r| u[r]);
    let ns = system.sections.len();
    // sparse: O(nnz) per residual, the same numbers as the dense form
    let problem = system.plcp_sparse::<f64>(None).ok();
    let mut intervals = Vec::new();
    let mut affine_pieces = Vec::new();
    for iv in &reading.intervals {
        let piece = &pieces[iv.piece];
        let (base, slope) = affine_accelerations(system, iv, piece);
        let mut acc = vec![[[0.0; 2]; 6]; frame.nodes.len()];
        for (j, c) in system.coordinates.iter().enumerate() {
            acc[c.node][c.component.index()] = [base[j], slope[j]];
        }
        // the member forces of every piece the interval holds
        let moment_pieces = iv
            .pieces
            .iter()
            .map(
                |&Span {
                     piece: pk,
                     lambda_from,
                     lambda_to,
                 }| {
                    let p = &pieces[pk];
                    let u0 = p.u(0.0);
                    MomentPiece {
                        lambda_from,
                        lambda_to,
                        piece: pk,
                        moments: (0..ns)
                            .map(|k| [moment(&u0, k), moment(&p.du, k)])
                            .collect(),
                    }
                },
            )
            .collect();
        // residuals on every piece the interval spans
        let mut res = Residual::default();
        for p in pieces.iter().filter(|p| {
            p.lambda_from >= iv.lambda_from
                && p.lambda_from < iv.lambda_to.max(iv.lambda_from + f64::MIN_POSITIVE)
        }) {
            if let Some(problem) = &problem {
                let (from, mid) = residuals_of_piece(problem, p);
                res = res.max(from).max(mid);
            }
        }
        intervals.push(IntervalResponse {
            lambda_from: iv.lambda_from,
            lambda_to: iv.lambda_to,
            accelerations: acc,
            pieces: moment_pieces,
            residual: res,
        });
        affine_pieces.push(AffinePiece {
            lambda_from: iv.lambda_from,
            lambda_to: iv.lambda_to,
            base,
            slope,
        });
    }
    let moments_at_breakpoints = reading
        .breakpoints
        .iter()
        .zip(reading.intervals.iter().filter(|i| !i.rigid))
        .map(|(b, iv)| {
            // the piece that starts at the breakpoint
            let u = pieces[iv.piece_at(b.lambda)].u(b.lambda);
            MomentDiagram {
                lambda: b.lambda,
                moments: (0..ns).map(|k| moment(&u, k)).collect(),
            }
        })
        .collect();
    // each coordinate series is freed as it is spread over the nodes
    let Motion {
        times: motion_times,
        lambda,
        displacement,
        velocity,
    } = integrate(&affine_pieces, history, times);
    drop(affine_pieces);
    let end_displacement = displacement
        .last()
        .map(|q| to_nodes(frame, system, q))
        .unwrap_or_default();
    let time = TimeResponse {
        history: history.clone(),
        method: METHOD,
        times: motion_times,
        lambda,
        displacement: displacement
            .into_iter()
            .map(|q| to_nodes(frame, system, &q))
            .collect(),
        velocity: velocity
            .into_iter()
            .map(|q| to_nodes(frame, system, &q))
            .collect(),
        end_displacement,
    };
    Response {
        intervals,
        moments_at_breakpoints,
        time,
        nodes: None,
    }
}
