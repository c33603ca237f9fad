//! What the hinge reading reports: the events at each breakpoint, the
//! intervals between them with their hinge sets, and the reading as a whole.

use crate::assemble::Sign;

/// What happened to a physical hinge at a breakpoint.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum EventKind {
    /// Reached yield (`y* = 0`).
    Yielded,
    /// Started to accelerate (`x*_dd` became positive).
    FlowStarted,
    /// Stopped accelerating while staying at yield: rotates on at a constant rate.
    FlowStopped,
    /// Left yield after having flowed: a deactivation.
    Unloaded,
}

impl EventKind {
    /// The JSON key: `yielded`, `flow_started`, `flow_stopped`, `unloaded`.
    pub fn as_str(self) -> &'static str {
        match self {
            EventKind::Yielded => "yielded",
            EventKind::FlowStarted => "flow_started",
            EventKind::FlowStopped => "flow_stopped",
            EventKind::Unloaded => "unloaded",
        }
    }
}

/// One event of one physical hinge.
#[derive(Clone, Debug, PartialEq)]
pub struct HingeEvent {
    /// What happened.
    pub kind: EventKind,
    /// The group (physical hinge), index into [`Reading::groups`].
    pub group: usize,
    /// The section of the group the event was read from.
    pub section: usize,
    /// The sign of the yield mode involved.
    pub sign: Sign,
    /// The yield mode involved (index into [`System::modes`](crate::assemble::System::modes)): for a section
    /// with a yield polygon, the facet it yields or flows on.
    pub mode: usize,
}

/// A set of critical sections that act as one physical hinge at a node.
#[derive(Clone, Debug, PartialEq)]
pub struct HingeGroup {
    /// The node.
    pub node: usize,
    /// The sections (one, or two tied ones).
    pub sections: Vec<usize>,
}

/// All events at one `Lambda`.
#[derive(Clone, Debug, PartialEq)]
pub struct EventPoint {
    /// The critical value of the load parameter.
    pub lambda: f64,
    /// The events, in group order within each kind.
    pub events: Vec<HingeEvent>,
    /// Whether the member forces are unique just after this point.
    pub stress_unique: bool,
}

impl EventPoint {
    /// The events of one kind.
    pub fn of(&self, kind: EventKind) -> impl Iterator<Item = &HingeEvent> {
        self.events.iter().filter(move |e| e.kind == kind)
    }
}

/// A piece of the path inside an interval, with the range of `Lambda` it
/// covers there (a piece shorter than the reading's tolerance is absorbed by
/// the next one, whose range then starts where the previous one ended).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Span {
    /// Index into the path's pieces.
    pub piece: usize,
    /// Start.
    pub lambda_from: f64,
    /// End (`f64::INFINITY` if unbounded).
    pub lambda_to: f64,
}

/// An interval of `Lambda` with one mechanism.
///
/// The path may pivot inside an interval: in the rigid phase of an
/// indeterminate frame, as redundant moments reach yield, and in a plastic
/// interval where the stress is not unique. The accelerations are one affine
/// function on the whole interval (zero in the rigid phase); the member
/// forces (and the split of plastic rates between tied sections) are affine
/// on each piece only: read them from [`Interval::piece_at`].
#[derive(Clone, Debug, PartialEq)]
pub struct Interval {
    /// Start.
    pub lambda_from: f64,
    /// End (`f64::INFINITY` if unbounded).
    pub lambda_to: f64,
    /// The first piece of the path on this interval: its accelerations hold
    /// on the whole interval, its member forces only on its own span
    /// (`pieces[0]`).
    pub piece: usize,
    /// The pieces of the path that make up this interval, in order, covering
    /// `[lambda_from, lambda_to]` end to end (at least one).
    pub pieces: Vec<Span>,
    /// True before the first plastic flow (the frame does not deform).
    pub rigid: bool,
    /// Groups that accelerate (`x*_dd > 0`).
    pub accelerating: Vec<usize>,
    /// Groups that flowed before and rotate at a constant rate (at yield, `x*_dd = 0`).
    pub constant_rate: Vec<usize>,
    /// Groups at yield (reported only where the stress is unique or forced).
    pub at_yield: Vec<usize>,
}

impl Interval {
    /// The span of the piece of the path that holds `lambda`: the last one
    /// starting at or before it (at a breakpoint between two pieces the later
    /// one; the path is continuous there, so both give the same values up to
    /// round-off), the first one for `lambda` before the interval.
    pub fn span_at(&self, lambda: f64) -> Span {
        self.pieces
            .iter()
            .rev()
            .find(|s| s.lambda_from <= lambda)
            .or(self.pieces.first())
            .copied()
            .unwrap_or(Span {
                piece: self.piece,
                lambda_from: self.lambda_from,
                lambda_to: self.lambda_to,
            })
    }

    /// The index of the piece of the path that holds `lambda` (see [`Interval::span_at`]).
    pub fn piece_at(&self, lambda: f64) -> usize {
        self.span_at(lambda).piece
    }
}

/// A physical hinge in order of formation.
#[derive(Clone, Debug, PartialEq)]
pub struct Hinge {
    /// The group.
    pub group: usize,
    /// The node.
    pub node: usize,
    /// `Lambda` at which the hinge started to flow.
    pub lambda: f64,
    /// Sagging or hogging.
    pub sign: Sign,
    /// The section that flowed first.
    pub section: usize,
    /// The yield mode it flowed on first (index into [`System::modes`](crate::assemble::System::modes)).
    pub mode: usize,
}

/// The path read as hinge events.
#[derive(Clone, Debug, PartialEq)]
pub struct Reading {
    /// Physical hinges (groups of tied sections), by node.
    pub groups: Vec<HingeGroup>,
    /// The group of each section (`None` for sections left out of the system).
    pub group_of: Vec<Option<usize>>,
    /// Critical values of `Lambda` with their events; the first is the limit load.
    pub breakpoints: Vec<EventPoint>,
    /// Intervals between them, starting with the rigid phase `[0, first]`.
    pub intervals: Vec<Interval>,
    /// Hinges in order of formation.
    pub hinges: Vec<Hinge>,
}

impl Reading {
    /// `Lambda` of the first plastic flow: the static collapse load (fact 3).
    pub fn collapse_load(&self) -> Option<f64> {
        self.breakpoints.first().map(|b| b.lambda)
    }
    /// All `unloaded` events (should be none for this loading class).
    pub fn deactivations(&self) -> Vec<(f64, &HingeEvent)> {
        self.breakpoints
            .iter()
            .flat_map(|b| b.of(EventKind::Unloaded).map(move |e| (b.lambda, e)))
            .collect()
    }
}
