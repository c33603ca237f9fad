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

/// A list of hinge groups (indices into [`Reading::groups`], in the order
/// of the groups), stored as runs of consecutive indices.
///
/// Why runs: every interval keeps its sets, and for a travelling hinge the
/// hinges behind the front (neighbours along a member, consecutive groups)
/// are in every later interval's `constant_rate`; as lists they grew as
/// `intervals x hinges` (about half of the 10^4-element cantilever's peak
/// resident memory), as runs they take one or a few pairs per interval.
/// The memory of a set is linear in its number of runs, at most its length.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct GroupSet {
    /// Maximal runs `start..end` (half-open), in the list's order.
    runs: Vec<(usize, usize)>,
}

impl GroupSet {
    /// The empty set.
    pub fn new() -> Self {
        Self::default()
    }

    /// The groups, in the list's order.
    pub fn iter(&self) -> impl Iterator<Item = usize> + '_ {
        self.runs.iter().flat_map(|&(a, b)| a..b)
    }

    /// Whether group `g` is in the set (a pass over the runs).
    pub fn contains(&self, g: &usize) -> bool {
        self.runs.iter().any(|&(a, b)| (a..b).contains(g))
    }

    /// The number of groups.
    pub fn len(&self) -> usize {
        self.runs.iter().map(|&(a, b)| b - a).sum()
    }

    /// Whether the set is empty.
    pub fn is_empty(&self) -> bool {
        self.runs.is_empty()
    }

    /// The groups as a list, in order.
    pub fn to_vec(&self) -> Vec<usize> {
        self.iter().collect()
    }

    /// Appends `g` (extends the last run when `g` follows it).
    pub fn push(&mut self, g: usize) {
        match self.runs.last_mut() {
            Some((_, b)) if *b == g => *b = g + 1,
            _ => self.runs.push((g, g + 1)),
        }
    }

    /// Frees spare capacity (a set kept with every interval).
    pub fn shrink_to_fit(&mut self) {
        self.runs.shrink_to_fit();
    }
}

impl FromIterator<usize> for GroupSet {
    fn from_iter<I: IntoIterator<Item = usize>>(iter: I) -> Self {
        let mut s = Self::new();
        iter.into_iter().for_each(|g| s.push(g));
        s
    }
}

impl From<Vec<usize>> for GroupSet {
    fn from(v: Vec<usize>) -> Self {
        v.into_iter().collect()
    }
}

impl From<&[usize]> for GroupSet {
    fn from(v: &[usize]) -> Self {
        v.iter().copied().collect()
    }
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
    pub accelerating: GroupSet,
    /// Groups that flowed before and rotate at a constant rate (at yield, `x*_dd = 0`).
    pub constant_rate: GroupSet,
    /// Groups at yield (reported only where the stress is unique or forced).
    pub at_yield: GroupSet,
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

#[cfg(test)]
mod tests {
    use super::GroupSet;

    /// A set as runs gives back its list, in order, with its length and
    /// membership, and two sets are equal exactly when their lists are.
    #[test]
    fn group_set_keeps_the_list() {
        let lists: [&[usize]; 6] = [
            &[],
            &[3],
            &[0, 1, 2, 3],
            &[0, 2, 4, 5, 6, 9],
            &[7, 8, 1, 2, 3],
            &[5, 5, 6],
        ];
        for list in lists {
            let s = GroupSet::from(list);
            assert_eq!(s.to_vec(), list);
            assert_eq!(s.len(), list.len());
            assert_eq!(s.is_empty(), list.is_empty());
            for g in 0..12 {
                assert_eq!(s.contains(&g), list.contains(&g), "{list:?} {g}");
            }
            for other in lists {
                assert_eq!(s == GroupSet::from(other), list == other);
            }
        }
        // a contiguous list is one run
        let run: GroupSet = (0..1000).collect();
        assert_eq!(run.runs.len(), 1);
    }
}
