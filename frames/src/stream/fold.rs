//! Pass 2 of a large scene's analysis ([`super::run_in_passes`]): what it
//! needs of each piece, known after pass 1 ([`Plan`]), the response's
//! skeleton, and the fold over the retraced pieces ([`Fold`]).

use crate::assemble::System;
use crate::hinge::{moment_positions, Reading};
use crate::integrate::step;
use crate::model::History;
use crate::report::OutputSelection;
use crate::response::{affine_accelerations, IntervalResponse, MomentDiagram, MomentPiece};
use crate::solve::Piece;
use plcp::{Control, Residual};
use std::collections::HashMap;

/// What pass 2 needs of each piece, known after pass 1.
pub(super) struct Plan {
    /// The kept nodes, ascending.
    pub(super) kept: Vec<usize>,
    /// The coordinates of the kept nodes ([`kept_coordinates`]).
    pub(super) kept_coords: Vec<(usize, usize, usize)>,
    /// Per piece, the interval it starts (whose accelerations it gives).
    pub(super) first_of: Vec<Option<usize>>,
    /// Per piece, the selected intervals' moment pieces it gives.
    pub(super) span_of: HashMap<usize, Vec<(usize, usize)>>,
    /// Per piece, the selected breakpoints' diagrams it gives.
    pub(super) diagram_of: HashMap<usize, Vec<usize>>,
    /// The breakpoints' `Lambda` values that have a diagram.
    pub(super) diagram_lambdas: Vec<f64>,
    /// The last piece pass 2 needs.
    pub(super) last_needed: usize,
    /// Per section, the row of its moment in `u`.
    pub(super) positions: Vec<Option<usize>>,
}

impl Plan {
    /// The diagrams at the selected breakpoints, their moments not yet read.
    pub(super) fn empty_diagrams(&self) -> Vec<MomentDiagram> {
        self.diagram_lambdas
            .iter()
            .map(|&lambda| MomentDiagram {
                lambda,
                moments: Vec::new(),
            })
            .collect()
    }

    pub(super) fn new(
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
        let kept_coords = kept_coordinates(system, &kept);
        Plan {
            kept,
            kept_coords,
            first_of,
            span_of,
            diagram_of,
            diagram_lambdas,
            last_needed,
            positions: moment_positions(system),
        }
    }
}

/// The coordinates of the nodes `kept` (ascending): per coordinate of
/// `system` whose node is kept, (the coordinate, the node's slot in `kept`,
/// the component's index), in the coordinates' order. What the kept nodes'
/// rows read of a vector of the coordinates, found once (not a pass over
/// every coordinate per row).
pub(super) fn kept_coordinates(system: &System, kept: &[usize]) -> Vec<(usize, usize, usize)> {
    system
        .coordinates
        .iter()
        .enumerate()
        .filter_map(|(j, c)| {
            kept.binary_search(&c.node)
                .ok()
                .map(|s| (j, s, c.component.index()))
        })
        .collect()
}

/// The response's skeleton: per interval its range, its moment pieces'
/// ranges and its residual, the worst of its pieces' (as response::build).
pub(super) fn skeleton(
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
pub(super) struct Context<'a> {
    pub(super) system: &'a System,
    pub(super) reading: &'a Reading,
    pub(super) history: &'a History,
    pub(super) plan: &'a Plan,
    pub(super) ranges: &'a [(f64, f64)],
    pub(super) knots: &'a [f64],
    pub(super) windows: &'a [Option<usize>],
}

/// Pass 2 as a fold over the pieces: the integration of the accelerations
/// (the steps of [`crate::integrate::integrate`]), the kept series, moment
/// pieces and diagrams, and the pieces they came from.
pub(super) struct Fold<'a> {
    pub(super) cx: Context<'a>,
    /// Per time (its bits), its indices in the response's times.
    pub(super) slots: HashMap<u64, Vec<usize>>,
    pub(super) t_last: Option<f64>,
    pub(super) intervals: Vec<IntervalResponse>,
    pub(super) diagrams: Vec<MomentDiagram>,
    pub(super) displacement: Vec<Option<Vec<[f64; 6]>>>,
    pub(super) velocity: Vec<Option<Vec<[f64; 6]>>>,
    pub(super) end_q: Option<Vec<f64>>,
    pub(super) q: Vec<f64>,
    pub(super) v: Vec<f64>,
    pub(super) next_window: usize,
    pub(super) retained: HashMap<usize, Piece>,
    /// Whether every piece so far has the range it had in pass 1.
    pub(super) same: bool,
}

impl<'a> Fold<'a> {
    pub(super) fn new(
        cx: Context<'a>,
        times: &[f64],
        intervals: Vec<IntervalResponse>,
    ) -> Fold<'a> {
        let mut slots: HashMap<u64, Vec<usize>> = HashMap::new();
        for (k, t) in times.iter().enumerate() {
            slots.entry(t.to_bits()).or_default().push(k);
        }
        let nb = cx.system.coordinates.len();
        let diagrams = cx.plan.empty_diagrams();
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
        for &(j, s, c) in &self.cx.plan.kept_coords {
            out[s][c] = q.get(j).copied().unwrap_or(0.0);
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
    pub(super) fn piece(&mut self, k: usize, p: Piece) -> Control {
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
        for &(j, s, c) in &cx.plan.kept_coords {
            acc[s][c] = [base[j], slope[j]];
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
    pub(super) fn complete(&self) -> bool {
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
pub(super) fn moments_of(
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
