//! One pass instead of two ([`Single`]): pass 2's work done during pass 1
//! where what it needs is decided before the trace, every guess checked at
//! the end.

use super::fold::{moments_of, skeleton, Plan};
use super::{assemble, kept_nodes, selection, times_of, windows_of, FirstPass, Kept};
use crate::analysis::AnalysisOptions;
use crate::assemble::System;
use crate::hinge::{self, EventPoint, Interval, Reading};
use crate::integrate::step;
use crate::model::{History, Scene};
use crate::report::{MomentPick, NodePick};
use crate::response::{self, affine_accelerations, Response};
use crate::solve::{self, Piece};
use std::collections::HashMap;

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
pub(super) struct Single<'a> {
    system: &'a System,
    history: &'a History,
    kept: Vec<usize>,
    /// The coordinates of the kept nodes: (coordinate, the node's slot,
    /// the component's index), in the coordinates' order.
    kept_coords: Vec<(usize, usize, usize)>,
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
    pub(super) fn new(
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
        let kept_coords = super::fold::kept_coordinates(system, &kept);
        let values = match &targets {
            Targets::Fixed(v) => Some(v.clone()),
            Targets::FromFirst { .. } => None,
        };
        let nb = system.coordinates.len();
        let mut single = Single {
            system,
            history,
            kept,
            kept_coords,
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
        for &(j, s, c) in &self.kept_coords {
            out[s][c] = q[j];
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
            for &(j, s, c) in &self.kept_coords {
                rows[s][c] = [acc.0[j], acc.1[j]];
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
    pub(super) fn piece(&mut self, k: usize, p: Piece, reader: &hinge::Reader<'_>) {
        if self.failed {
            return;
        }
        let intervals = reader.intervals();
        self.read_new(Some((k, &p)), intervals, reader.breakpoints());
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
                self.retained.insert(k, p);
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
    pub(super) fn finish(
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
        let reading = &first.reading;
        let times = times_of(self.history, reading, options, &first.solution);
        // the second pass's knots, windows and their intervals
        let (knots, windows) = windows_of(reading, self.history, &times);
        let expected = windows
            .iter()
            .enumerate()
            .filter_map(|(w, i)| i.map(|i| (knots[w].to_bits(), knots[w + 1].to_bits(), i)));
        let same_steps = expected.eq(self.steps.iter().copied());
        let same_end = times.last().map(|t| t.to_bits()) == Some(self.t_end.to_bits());
        // the second pass's selection
        let sel = selection(scene, reading, options, moments.as_ref(), nodes.as_ref());
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
        let mut diagrams = plan.empty_diagrams();
        let ns = self.system.sections.len();
        let mut kept_pieces: HashMap<usize, Piece> = HashMap::new();
        for k in needed {
            let p = self.retained.remove(&k).expect("a retained piece");
            moments_of(&plan, ns, k, &p, &mut intervals, &mut diagrams);
            kept_pieces.insert(k, p);
        }
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
        let kept = Kept {
            displacement,
            velocity,
            end_q: self.end_q.take(),
            pieces: kept_pieces,
            intervals,
            diagrams,
            nodes: plan.kept,
        };
        let (pieces, response) = assemble(scene, self.system, times, &ranges, kept);
        solution.pieces = pieces;
        Ok(Box::new((solution, reading, response)))
    }
}
