//! Reading the path as hinge events: which critical sections reach yield,
//! start to flow, stop accelerating or unload, at which `Lambda`, merged into
//! the physical hinges at the nodes.
//!
//! Definitions (system9-notes, fact 5). A section is *at yield* when one of
//! its plastic potentials `y*` is zero; it *accelerates* when a plastic
//! multiplier acceleration `x*_dd` is positive; it *flows* once it has
//! accelerated (its plastic rate, the time integral of `x*_dd`, is positive).
//! A flowing section whose `x*_dd` returns to zero while it stays at yield
//! keeps rotating at a constant rate: that is `flow_stopped`, not a
//! deactivation. A flowing section that leaves yield is `unloaded`: a real
//! deactivation, against the paper's claim for this loading class; it is
//! reported, never hidden.
//!
//! States are read on each piece at an interior point, with a relative
//! tolerance suited to the working precision (for `x*_dd`, relative to the
//! largest `x*_dd` on the piece; a piece's length relative to its own
//! `Lambda`), so a path whose breakpoints span decades shows every one.
//!
//! **Yield polygons.** A section with an interaction (bending-torsion,
//! bending-axial) has one yield mode per facet of its polygon. It is at yield
//! when any facet is, and accelerates when any facet's `x*_dd` is positive;
//! events name the facet (the nearest to yield, the fastest). The flow moving
//! from one facet to the next is not an event of the hinge (it shows as a
//! breakpoint without events); leaving every facet after having flowed is
//! `unloaded`.
//!
//! **Tied sections.** Where exactly two sections meet at a node whose rotation
//! is free, without rotary inertia or applied moment, node equilibrium makes
//! their moments equal: they yield together and the split of plastic rotation
//! between them is not unique (fact 4). They form one group, the physical
//! hinge at the node, and events are reported per group.
//!
//! **Stress that is not unique.** While a statically indeterminate frame (or
//! its rigid part) does not move, the member forces are not unique (fact 6),
//! so which section reaches yield first is not a property of the problem.
//! Before the first flow nothing is reported; after it, a section reaching
//! yield is reported only where the stress is unique on the piece (`A^T` with
//! the moments of the accelerating sections pinned has full column rank) or
//! where the section itself accelerates (its yield is then forced).

use crate::assemble::{End, MemberForce, System};
use crate::kernel::null_space;
use crate::model::Frame;
use crate::solve::Piece;
use faer::Mat;

mod events;

pub use events::{
    EventKind, EventPoint, GroupSet, Hinge, HingeEvent, HingeGroup, Interval, Reading, Span,
};

/// Per-piece states of every section.
#[derive(Clone, Debug)]
struct State {
    /// `Some(mode)` if the section is at yield (on that mode; the most loaded one).
    yield_mode: Vec<Option<usize>>,
    /// `Some(mode)` if the section accelerates (on that mode; the fastest one).
    acc_mode: Vec<Option<usize>>,
    unique: bool,
    /// The modes that accelerate, in order (for a yield polygon, its facets).
    accelerating: Vec<usize>,
}

/// The most pinned modes [`Reader`]'s cache of [`stress_unique`] holds
/// (8 MB of keys).
const CACHE_ENTRIES: usize = 1 << 20;

/// What [`Reader::group_events`] reads of a piece, per hinge group.
struct GroupSets {
    events: Vec<HingeEvent>,
    accelerating: GroupSet,
    constant_rate: GroupSet,
    at_yield: GroupSet,
    now_yield: Vec<SectionMode>,
    now_acc: Vec<SectionMode>,
}

fn groups(frame: &Frame, system: &System) -> (Vec<HingeGroup>, Vec<Option<usize>>) {
    let kept: Vec<bool> = system
        .moment_indices()
        .iter()
        .map(Option::is_some)
        .collect();
    let mut partner = vec![None; system.sections.len()];
    for t in &system.ties {
        partner[t[0]] = Some(t[1]);
        partner[t[1]] = Some(t[0]);
    }
    let mut at_node: Vec<Vec<usize>> = vec![Vec::new(); frame.nodes.len()];
    for (k, s) in system.sections.iter().enumerate() {
        if kept[k] {
            at_node[s.node].push(k);
        }
    }
    let mut gs = Vec::new();
    let mut group_of: Vec<Option<usize>> = vec![None; system.sections.len()];
    for (i, secs) in at_node.iter().enumerate() {
        for &k in secs {
            if group_of[k].is_some() {
                continue;
            }
            let mut p = vec![k];
            if let Some(o) = partner[k] {
                if kept[o] {
                    p.push(o);
                    p.sort_unstable();
                }
            }
            for &j in &p {
                group_of[j] = Some(gs.len());
            }
            gs.push(HingeGroup {
                node: i,
                sections: p,
            });
        }
    }
    (gs, group_of)
}

/// Whether the member forces are unique once the yield conditions of the
/// `pinned` modes hold as equalities (their columns of `T N` fix combinations
/// of the member forces).
fn stress_unique(system: &System, pinned: &[usize]) -> bool {
    if system.is_determinate() {
        return true;
    }
    let (nb, ns) = (system.coordinates.len(), system.forces.len());
    let m = Mat::from_fn(nb + pinned.len(), ns, |i, j| {
        if i < nb {
            system.a[(j, i)]
        } else {
            system.tn[(j, pinned[i - nb])]
        }
    });
    null_space(&m).0 == ns
}

/// Where the stress is not unique and a section that has flowed appears off
/// yield, asks whether some admissible stress state keeps every flowed section
/// at yield ([`crate::stress`]); if so, the section is read as at yield (a
/// choice of the solver, not a deactivation). One entry of the reading's view
/// at a time: `flowed` holds, per section, the mode it last accelerated on
/// over the entries so far (updated here with this one's).
fn restore_yield(
    system: &System,
    piece: &Piece,
    (from, to): (f64, f64),
    flowed: &mut [Option<usize>],
    state: &mut State,
) {
    let ns = system.sections.len();
    let nb = system.coordinates.len();
    for (f, a) in flowed.iter_mut().zip(&state.acc_mode) {
        if a.is_some() {
            *f = *a;
        }
    }
    if state.unique {
        return;
    }
    let lost: Vec<usize> = (0..ns)
        .filter(|&s| flowed[s].is_some() && state.yield_mode[s].is_none())
        .collect();
    if lost.is_empty() {
        return;
    }
    let pinned: Vec<usize> = flowed.iter().flatten().copied().collect();
    let rep = piece.representative();
    let lambdas: Vec<f64> = if to.is_finite() {
        vec![from, to]
    } else {
        vec![from, rep, 2.0 * rep]
    };
    let ok = lambdas.iter().all(|&l| {
        let u = piece.u(l);
        let rhs: Vec<f64> = (0..nb)
            .map(|j| system.load[j] * l - system.mass[j] * u[j])
            .collect();
        crate::stress::admissible_with(system, &rhs, &pinned) == Some(true)
    });
    if ok {
        for s in lost {
            state.yield_mode[s] = flowed[s];
        }
    }
}

/// Whether a piece moves: the inertia forces are more than round-off of its
/// equations of motion.
///
/// The scale of x*_dd that tells "accelerating" from round-off, per piece,
/// relative to the piece's own scale. A piece on which the inertia forces
/// are round-off of its equations of motion (`max_j m_j |q_dd_j| <= tol^2
/// max_j (|L a_j| + sum_r |A_rj X_r|)`) is rigid: its x*_dd are round-off
/// too (an indeterminate frame's rigid phase pivots with basic x*_dd of
/// 1e-16). On a moving piece the scale is the largest |x*_dd| on the piece
/// itself (at its ends, where an affine function peaks, and inside). A
/// scale taken from the whole path (or a neighbour, read far away inside a
/// long piece) hid real flow on a path whose breakpoints span decades
/// (issue 14: x*_dd of 5e-14 at L = 1e-3 against 1e7 at L = 1e16).
fn moving(system: &System, p: &Piece, tolerance: f64) -> bool {
    let nb = system.coordinates.len();
    // at the piece's far end, where the inertia forces (zero at a
    // breakpoint where a mechanism forms) are largest
    let l = if p.lambda_to.is_finite() {
        p.lambda_to
    } else {
        p.representative()
    };
    let u = p.u(l);
    let (mut inertia, mut forces) = (0.0f64, 0.0f64);
    for j in 0..nb {
        inertia = inertia.max((system.mass[j] * u[j]).abs());
        // column j of A, its stored entries in row order (the zeros
        // added nothing): O(nnz(A)) per piece, not O(s beta)
        let (rows, vals) = system.a.col(j);
        let f = rows
            .iter()
            .zip(vals)
            .map(|(&r, &a)| (a * u[nb + r]).abs())
            .sum::<f64>();
        forces = forces.max((system.load[j] * l).abs() + f);
    }
    // round-off of the equations of motion: `tolerance^2`, 100 eps
    inertia > tolerance * tolerance * forces
}

/// The scale of `x*_dd` on a piece (see [`moving`]): infinite on a rigid piece.
fn zscale(system: &System, p: &Piece, tolerance: f64) -> f64 {
    if !moving(system, p, tolerance) {
        return f64::INFINITY;
    }
    let mut at = vec![p.lambda_from, p.representative()];
    if p.lambda_to.is_finite() {
        at.push(p.lambda_to);
    }
    at.iter()
        .flat_map(|&x| p.z(x))
        .fold(f64::MIN_POSITIVE, |a, v| a.max(v.abs()))
}

/// `(section, mode)` of a group at yield / accelerating.
type SectionMode = Option<(usize, usize)>;

/// The hinge reading as a fold over the pieces of a path, in order of rising
/// `Lambda` ([`Reader::push`] each, then [`Reader::finish`]): what [`read`]
/// does, with the same numbers, holding only the state of the last piece,
/// the first piece of the current interval and the reading itself, so that
/// a path read as it is traced ([`crate::solve`]) need not be stored.
///
/// A piece is read on its own (which sections are at yield and accelerate
/// there), against its predecessor's states (the events) and against the
/// first piece of the current interval (whether its accelerations are the
/// same affine function). Pieces shorter than the tolerance relative to
/// their own `Lambda` (f32 round-off, degenerate steps) are skipped: their
/// neighbours meet at one breakpoint. (Not relative to `max(1, |L|)`: that
/// absorbed the piece `[0, 9.08e-9]` of a frame whose first hinge forms at
/// 9.08e-9.) If every piece is short, every piece is read.
pub struct Reader<'a> {
    system: &'a System,
    tolerance: f64,
    groups: Vec<HingeGroup>,
    group_of: Vec<Option<usize>>,
    /// `lambda_from` of the path's first piece.
    start: Option<f64>,
    /// The end of the last piece read (`None` before the first long piece).
    last_to: Option<f64>,
    /// The pieces before the first long one (read if none is long).
    short: Vec<(usize, Piece)>,
    /// [`stress_unique`] per set of pinned modes, and the modes it holds.
    cache: std::collections::HashMap<Vec<usize>, bool>,
    cache_entries: usize,
    /// Per section, the mode it last accelerated on.
    flowed_modes: Vec<Option<usize>>,
    /// The pieces read before the first flow `(piece, from, to)`.
    rigid: Vec<(usize, f64, f64)>,
    flowing: bool,
    /// The accelerating modes of the last piece read (`None` before the first).
    prev_accelerating: Option<Vec<usize>>,
    reported_yield: Vec<bool>,
    flowed: Vec<bool>,
    started: Vec<bool>,
    prev_acc: Vec<SectionMode>,
    prev_yield: Vec<SectionMode>,
    /// The first piece of the current (plastic) interval: what
    /// [`same_acceleration`] reads of it ([`accelerations_of`]).
    interval_piece: Option<Piece>,
    breakpoints: Vec<EventPoint>,
    intervals: Vec<Interval>,
    hinges: Vec<Hinge>,
}

impl<'a> Reader<'a> {
    /// A reading of a path of `system` (assembled from `frame`), signs read
    /// with the relative `tolerance` ([`crate::solve::Solution::tolerance`]).
    pub fn new(frame: &Frame, system: &'a System, tolerance: f64) -> Self {
        let (groups, group_of) = groups(frame, system);
        let ng = groups.len();
        Reader {
            system,
            tolerance,
            groups,
            group_of,
            start: None,
            last_to: None,
            short: Vec::new(),
            cache: std::collections::HashMap::new(),
            cache_entries: 0,
            flowed_modes: vec![None; system.sections.len()],
            rigid: Vec::new(),
            flowing: false,
            prev_accelerating: None,
            reported_yield: vec![false; ng],
            flowed: vec![false; ng],
            started: vec![false; ng],
            prev_acc: vec![None; ng],
            prev_yield: vec![None; ng],
            interval_piece: None,
            breakpoints: Vec::new(),
            intervals: Vec::new(),
            hinges: Vec::new(),
        }
    }

    /// Reads the next piece of the path (`index` into its pieces).
    pub fn push(&mut self, index: usize, p: &Piece) {
        let tolerance = self.tolerance;
        let start = *self.start.get_or_insert(p.lambda_from);
        let long = !p.lambda_to.is_finite()
            || p.lambda_to - p.lambda_from > tolerance * p.lambda_from.abs().max(p.lambda_to.abs());
        if !long {
            if self.last_to.is_none() {
                self.short.push((index, p.clone()));
            }
            return;
        }
        self.short = Vec::new();
        // the first interval starts where the path does, even when its
        // first pieces are too short to read
        let from = self.last_to.unwrap_or(start);
        self.last_to = Some(p.lambda_to);
        self.entry(index, from, p.lambda_to, p);
    }

    /// The intervals read so far (the last one may still be extended).
    pub(crate) fn intervals(&self) -> &[Interval] {
        &self.intervals
    }

    /// The breakpoints read so far.
    pub(crate) fn breakpoints(&self) -> &[EventPoint] {
        &self.breakpoints
    }

    /// The end of the last piece read (`None` before the first long one):
    /// every later breakpoint and interval starts at or above it.
    pub(crate) fn frontier(&self) -> Option<f64> {
        self.last_to
    }

    /// The reading of the pieces pushed.
    pub fn finish(mut self) -> Reading {
        if self.last_to.is_none() {
            for (i, p) in std::mem::take(&mut self.short) {
                self.entry(i, p.lambda_from, p.lambda_to, &p);
            }
        }
        if !self.flowing {
            // rigid (or moving without hinges) over the whole traced range
            if let Some(last) = self.rigid.last() {
                let iv = rigid_interval(&self.rigid, last.2);
                self.intervals.push(iv);
            }
        }
        Reading {
            groups: self.groups,
            group_of: self.group_of,
            breakpoints: self.breakpoints,
            intervals: self.intervals,
            hinges: self.hinges,
        }
    }

    /// The states of every section on a piece, read at an interior point.
    fn state(&mut self, p: &Piece) -> State {
        let system = self.system;
        let tolerance = self.tolerance;
        let ns = system.sections.len();
        let l = p.representative();
        let (z, w) = (p.z(l), p.w(l));
        let zscale = zscale(system, p, tolerance);
        let mut yield_mode: Vec<Option<usize>> = vec![None; ns];
        let mut acc_mode: Vec<Option<usize>> = vec![None; ns];
        for (k, mode) in system.modes.iter().enumerate() {
            let s = mode.section;
            // at a vertex of a polygon two facets are at yield: keep the
            // one nearer yield, and the faster-accelerating one
            let nearer = match yield_mode[s] {
                None => true,
                Some(j) => w[k] / system.capacities[k] < w[j] / system.capacities[j],
            };
            if w[k] <= tolerance * system.capacities[k] && nearer {
                yield_mode[s] = Some(k);
            }
            let faster = match acc_mode[s] {
                None => true,
                Some(j) => z[k] > z[j],
            };
            if z[k] > tolerance * zscale && faster {
                acc_mode[s] = Some(k);
            }
        }
        let pinned: Vec<usize> = (0..system.modes.len())
            .filter(|&k| z[k] > tolerance * zscale)
            .collect();
        // the cache is keyed by the pinned modes, which for a travelling
        // hinge grow with the hinges behind the front: none is kept where
        // the answer needs no work, and the cache starts over beyond
        // CACHE_ENTRIES modes held (the answers are the same, computed anew)
        let unique = if system.is_determinate() {
            true
        } else {
            if self.cache_entries + pinned.len() > CACHE_ENTRIES {
                self.cache.clear();
                self.cache_entries = 0;
            }
            let entries = &mut self.cache_entries;
            *self.cache.entry(pinned.clone()).or_insert_with(|| {
                *entries += pinned.len();
                stress_unique(system, &pinned)
            })
        };
        State {
            yield_mode,
            acc_mode,
            unique,
            accelerating: pinned,
        }
    }

    /// Reads one entry of the view: piece `pk` on `[lambda, lambda_to]`.
    fn entry(&mut self, pk: usize, lambda: f64, lambda_to: f64, p: &Piece) {
        let mut st = self.state(p);
        restore_yield(
            self.system,
            p,
            (lambda, lambda_to),
            &mut self.flowed_modes,
            &mut st,
        );
        if !self.flowing {
            if !st.acc_mode.iter().any(Option::is_some) {
                self.rigid.push((pk, lambda, lambda_to));
                self.prev_accelerating = Some(st.accelerating);
                return;
            }
            self.flowing = true;
            if !self.rigid.is_empty() {
                // the path pivots inside the rigid phase of an indeterminate
                // frame (redundant moments reaching yield): every piece up to
                // the first flow
                self.intervals.push(rigid_interval(&self.rigid, lambda));
                self.rigid = Vec::new();
            }
        }
        self.plastic(pk, lambda, lambda_to, p, st);
    }

    /// The events of a piece after the first flow, against its predecessor.
    fn plastic(&mut self, pk: usize, lambda: f64, lambda_to: f64, p: &Piece, st: State) {
        let sets = self.group_events(lambda, &st);
        self.close_or_extend(pk, (lambda, lambda_to), p, st, sets);
    }

    /// Per hinge group, its state on a piece (at yield, accelerating)
    /// against its predecessor's: the events at the piece's start `lambda`
    /// (sorted: yielded, flow started, flow stopped, unloaded), the sets of
    /// the piece, and the hinges that form (pushed to the reading).
    fn group_events(&mut self, lambda: f64, st: &State) -> GroupSets {
        let system = self.system;
        let groups = &self.groups;
        let group_state = |st: &State, g: usize| -> (SectionMode, SectionMode) {
            let y = groups[g]
                .sections
                .iter()
                .find_map(|&k| st.yield_mode[k].map(|m| (k, m)));
            let a = groups[g]
                .sections
                .iter()
                .find_map(|&k| st.acc_mode[k].map(|m| (k, m)));
            (y, a)
        };
        let sign = |m: usize| system.modes[m].sign;
        let ng = groups.len();
        let (reported_yield, flowed, started) = (
            &mut self.reported_yield,
            &mut self.flowed,
            &mut self.started,
        );
        let (prev_acc, prev_yield) = (&self.prev_acc, &self.prev_yield);
        let mut events = Vec::new();
        let mut accelerating = GroupSet::new();
        let mut constant_rate = GroupSet::new();
        let mut at_yield = GroupSet::new();
        let mut now_yield = vec![None; ng];
        let mut now_acc = vec![None; ng];
        for g in 0..ng {
            let (y, a) = group_state(st, g);
            now_yield[g] = y;
            now_acc[g] = a;
            if let Some((sec, mode)) = y {
                if !reported_yield[g] && (st.unique || a.is_some()) {
                    events.push(HingeEvent {
                        kind: EventKind::Yielded,
                        group: g,
                        section: sec,
                        sign: sign(mode),
                        mode,
                    });
                    reported_yield[g] = true;
                }
            } else {
                if flowed[g] {
                    if let Some((sec, mode)) = prev_yield[g].or(prev_acc[g]) {
                        events.push(HingeEvent {
                            kind: EventKind::Unloaded,
                            group: g,
                            section: sec,
                            sign: sign(mode),
                            mode,
                        });
                    }
                }
                reported_yield[g] = false;
            }
            match (prev_acc[g], a) {
                (None, Some((sec, mode))) => {
                    events.push(HingeEvent {
                        kind: EventKind::FlowStarted,
                        group: g,
                        section: sec,
                        sign: sign(mode),
                        mode,
                    });
                    if !started[g] {
                        started[g] = true;
                        self.hinges.push(Hinge {
                            group: g,
                            node: groups[g].node,
                            lambda,
                            sign: sign(mode),
                            mode,
                            section: sec,
                        });
                    }
                }
                (Some((sec, mode)), None) if y.is_some() => {
                    events.push(HingeEvent {
                        kind: EventKind::FlowStopped,
                        group: g,
                        section: sec,
                        sign: sign(mode),
                        mode,
                    });
                }
                _ => {}
            }
            if a.is_some() {
                flowed[g] = true;
                accelerating.push(g);
            } else if flowed[g] && y.is_some() {
                constant_rate.push(g);
            }
            if reported_yield[g] {
                at_yield.push(g);
            }
        }
        events.sort_by_key(|e| match e.kind {
            EventKind::Yielded => 0,
            EventKind::FlowStarted => 1,
            EventKind::FlowStopped => 2,
            EventKind::Unloaded => 3,
        });
        GroupSets {
            events,
            accelerating,
            constant_rate,
            at_yield,
            now_yield,
            now_acc,
        }
    }

    /// A piece `pk` on `range` with the sets `sets` of [`Self::group_events`]:
    /// a new breakpoint and interval where something observable changed,
    /// else the current interval extended over it.
    fn close_or_extend(
        &mut self,
        pk: usize,
        range: (f64, f64),
        p: &Piece,
        st: State,
        sets: GroupSets,
    ) {
        let system = self.system;
        let (lambda, lambda_to) = range;
        let GroupSets {
            events,
            mut accelerating,
            mut constant_rate,
            mut at_yield,
            now_yield,
            now_acc,
        } = sets;
        let same_mechanism = self
            .intervals
            .last()
            .map(|iv: &Interval| {
                !iv.rigid
                    && iv.accelerating == accelerating
                    && iv.constant_rate == constant_rate
                    && iv.at_yield == at_yield
            })
            .unwrap_or(false);
        // the flow moving across a yield polygon (a facet starting or
        // stopping while its section flows on) is a breakpoint without events
        let same_facets = self
            .prev_accelerating
            .as_ref()
            .is_none_or(|a| *a == st.accelerating);
        if events.is_empty()
            && same_mechanism
            && same_facets
            && same_acceleration(
                system,
                self.interval_piece.as_ref().unwrap_or(p),
                p,
                self.tolerance,
            )
        {
            // nothing observable changed (a pivot on non-unique forces): extend
            if let Some(iv) = self.intervals.last_mut() {
                iv.lambda_to = lambda_to;
                iv.pieces.push(Span {
                    piece: pk,
                    lambda_from: lambda,
                    lambda_to,
                });
            }
        } else {
            // kept for every interval: no spare capacity (for a travelling
            // hinge the sets hold every hinge behind the front: a run or two)
            accelerating.shrink_to_fit();
            constant_rate.shrink_to_fit();
            at_yield.shrink_to_fit();
            self.breakpoints.push(EventPoint {
                lambda,
                events,
                stress_unique: st.unique,
            });
            self.intervals.push(Interval {
                lambda_from: lambda,
                lambda_to,
                piece: pk,
                pieces: vec![Span {
                    piece: pk,
                    lambda_from: lambda,
                    lambda_to,
                }],
                rigid: false,
                accelerating,
                constant_rate,
                at_yield,
            });
            self.interval_piece = Some(accelerations_of(system, p));
        }
        self.prev_acc = now_acc;
        self.prev_yield = now_yield;
        self.prev_accelerating = Some(st.accelerating);
    }
}

/// Reads the pieces of a path as hinge events ([`Reader`] over every piece).
pub fn read(frame: &Frame, system: &System, pieces: &[Piece], tolerance: f64) -> Reading {
    let mut reader = Reader::new(frame, system, tolerance);
    for (i, p) in pieces.iter().enumerate() {
        reader.push(i, p);
    }
    reader.finish()
}

/// The rigid interval over the pieces `rigid` (the reading's view `(piece,
/// from, to)`, not empty) up to `lambda_to`: the whole rigid phase at the
/// end of the reading, or up to the first flow.
fn rigid_interval(rigid: &[(usize, f64, f64)], lambda_to: f64) -> Interval {
    let first = rigid[0];
    Interval {
        lambda_from: first.1,
        lambda_to,
        piece: first.0,
        pieces: spans(rigid),
        rigid: true,
        accelerating: GroupSet::new(),
        constant_rate: GroupSet::new(),
        at_yield: GroupSet::new(),
    }
}

/// The spans of a run of the reading's view `(piece, from, to)`.
fn spans(view: &[(usize, f64, f64)]) -> Vec<Span> {
    view.iter()
        .map(|&(piece, lambda_from, lambda_to)| Span {
            piece,
            lambda_from,
            lambda_to,
        })
        .collect()
}

/// What [`same_acceleration`] reads of a piece: its range, and its
/// accelerations `q_dd` (the first `nb` entries of `u` and of their slopes;
/// the multipliers and potentials empty). Kept per interval instead of a
/// copy of the whole piece (two of its six vectors, cut to the coordinates:
/// a quarter of the copy on the 1000-element cantilever).
fn accelerations_of(system: &System, p: &Piece) -> Piece {
    let nb = system.coordinates.len();
    Piece {
        lambda_from: p.lambda_from,
        lambda_to: p.lambda_to,
        u_from: p.u_from[..nb.min(p.u_from.len())].to_vec(),
        du: p.du[..nb.min(p.du.len())].to_vec(),
        z_from: Vec::new(),
        dz: Vec::new(),
        w_from: Vec::new(),
        dw: Vec::new(),
    }
}

/// The accelerations of two pieces are the same affine function of `Lambda`.
fn same_acceleration(system: &System, a: &Piece, b: &Piece, tolerance: f64) -> bool {
    let nb = system.coordinates.len();
    let l = b.representative();
    let (ua, ub) = (a.u(l), b.u(l));
    let (sa, sb) = (&a.du, &b.du);
    let scale = ua[..nb]
        .iter()
        .chain(&ub[..nb])
        .fold(1e-300f64, |s, v| s.max(v.abs()));
    let sscale = sa[..nb]
        .iter()
        .chain(&sb[..nb])
        .fold(1e-300f64, |s, v| s.max(v.abs()));
    (0..nb).all(|j| {
        (ua[j] - ub[j]).abs() <= 1e3 * tolerance * scale
            && (sa[j] - sb[j]).abs() <= 1e3 * tolerance * sscale
    })
}

/// A section as the JSON and the tables name it.
#[derive(Clone, Debug, PartialEq)]
pub struct SectionName {
    /// Member id.
    pub member: String,
    /// `"from"` or `"to"`: the end of its element.
    pub end: End,
    /// Node id.
    pub node: String,
}

/// Names a section.
pub fn section_name(frame: &Frame, system: &System, section: usize) -> SectionName {
    let s = &system.sections[section];
    SectionName {
        member: frame.members[s.member].id.clone(),
        end: s.end,
        node: frame.nodes[s.node].id.clone(),
    }
}

/// The position in `u = (q_dd, X)` of every section's moment (`None`: left
/// out), found once: [`moment`] searches the member forces on every call.
pub fn moment_positions(system: &System) -> Vec<Option<usize>> {
    let nb = system.coordinates.len();
    let mut pos = vec![None; system.sections.len()];
    // the first force of each section, as `moment` finds it
    for (r, f) in system.forces.iter().enumerate().rev() {
        if let MemberForce::Moment(s) = *f {
            if s < pos.len() {
                pos[s] = Some(nb + r);
            }
        }
    }
    pos
}

/// The moment of `section` from the free variables `u = (q_dd, X)`, 0 if left out.
pub fn moment(system: &System, u: &[f64], section: usize) -> f64 {
    let nb = system.coordinates.len();
    system
        .forces
        .iter()
        .position(|f| *f == MemberForce::Moment(section))
        .map(|r| u[nb + r])
        .unwrap_or(0.0)
}
