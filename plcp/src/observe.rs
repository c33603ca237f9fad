//! Watching a trace as it runs, stopping it, and keeping only what the caller needs.
//!
//! The path of a PLCP is a sequence of segments `k = 0, 1, ...` on which
//! `x(L) = x_k + (L - L_k) dx_k` (`x = (z, w, u)`). Stored whole
//! ([`crate::solve`]) it costs `segments x (p + n)` numbers: 7500 segments of
//! 30000 unknowns are 10 GB. [`solve_observed`] hands each segment to an
//! [`Observer`] as soon as the engine has finished it (on the original,
//! unscaled problem: the same numbers, bit for bit, that [`crate::solve`]
//! stores), and the observer answers [`Control::Continue`] or
//! [`Control::Stop`]. A stopped trace ends at the breakpoint after the segment
//! last seen, with status [`crate::Status::StoppedByObserver`].
//!
//! # Memory model
//!
//! What is kept is chosen by [`Keep`]:
//!
//! * [`Keep::All`]: every segment in [`crate::Path::segments`], as
//!   [`crate::solve`] (`O(segments x (p + n))`).
//! * [`Keep::Compact`]: a [`CompactPath`]: per segment its range of `L` and its
//!   change of basis against the previous segment (a few `(row, variable)`
//!   pairs: one per pivot), the first segment's basis, and in full only the
//!   first and the last segment and every `checkpoint_every`-th one. That is
//!   `O(p + n + pivots + (segments / checkpoint_every) (p + n))` memory.
//!   [`CompactPath::at`] evaluates a checkpoint exactly and recomputes any other
//!   segment from its basis (one factorisation, a warm start of the engine).
//! * [`Keep::Nothing`]: the breakpoints (events, `O(pivots)`) and the end only;
//!   the observer keeps what it wants.
//!
//! The engine itself holds `O(nnz(M) + (p + n))` plus its basis factors. The
//! bytes held by the stored path are reported in [`crate::Info::path_bytes`].
//!
//! # Limits
//!
//! Streaming happens inside the engine for the standard form and for Wolfe's
//! long form. For [`crate::Method::Lemke`] on a mixed problem (a Schur
//! reduction whose segments are re-solved on the unreduced system afterwards)
//! the path is traced whole and then shown to the observer segment by segment,
//! so a stop saves no work there. A path continued in `fx128`
//! ([`crate::Settings::escalate`]) keeps the continuation's segments in full in
//! [`crate::Path::segments`] whatever [`Keep`] says; the observer has seen the
//! working precision's segments up to the point of escalation only.
//!
//! ```
//! use faer::{col, mat};
//! use plcp::{solve_observed, Control, Keep, Progress};
//! use plcp::{Plcp, Segment, Settings, Status};
//!
//! let m = mat![[2.0, 1.0], [1.0, 2.0]];
//! let problem = Plcp::new(m.as_ref(), col![1.0, 1.0].as_ref(), col![-1.0, -0.5].as_ref())
//!     .unwrap()
//!     .with_range(0.0, Some(10.0))
//!     .unwrap();
//! // stop after the first segment that passes L = 0.5
//! let watch = |s: &Segment<f64>, _: &Progress<'_, f64>| {
//!     if s.lambda_to > 0.5 { Control::Stop } else { Control::Continue }
//! };
//! let run = solve_observed(&problem, &Settings::default(), watch, Keep::Nothing).unwrap();
//! assert_eq!(run.path.status, Status::StoppedByObserver);
//! assert!(run.path.segments.is_empty());
//! assert_eq!(run.path.lambda_reached, 1.0); // w0 = 1 - L reaches zero at L = 1
//! assert_eq!(run.path.breakpoints.len(), 1);
//! ```

use crate::path::{Breakpoint, Path, Point, Segment, Status, Var};
use crate::problem::Plcp;
use crate::scalar::Scalar;
use crate::settings::{Method, Settings};
use crate::PlcpError;
use std::any::Any;
use std::cell::{Cell, RefCell};
use std::rc::Rc;

/// What an observer tells the trace after each segment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Control {
    /// Go on tracing.
    Continue,
    /// End the trace at the end of this segment
    /// ([`crate::Status::StoppedByObserver`]).
    Stop,
}

/// Where the trace stands when a segment is handed over.
#[derive(Clone, Copy, Debug)]
pub struct Progress<'a, T: Scalar> {
    /// Index of the segment in path order.
    pub index: usize,
    /// Pivots so far (all phases; when the path is shown after the trace,
    /// see the module's limits: the breakpoints so far).
    pub pivots: usize,
    /// The event at the segment's start (`None` for the first segment), with
    /// the residual the trace measured there (L, entering, leaving, residual).
    pub breakpoint: Option<&'a Breakpoint<T>>,
    /// Breakpoints so far.
    pub breakpoints: usize,
}

/// Watches a trace segment by segment (the observer pattern of argmin: it
/// is moved into the solve and handed back in [`Observed`]).
pub trait Observer<T: Scalar> {
    /// Called once per segment, in path order, as soon as it is known.
    fn on_segment(&mut self, segment: &Segment<T>, progress: &Progress<'_, T>) -> Control;
}

impl<T: Scalar, F: FnMut(&Segment<T>, &Progress<'_, T>) -> Control> Observer<T> for F {
    fn on_segment(&mut self, segment: &Segment<T>, progress: &Progress<'_, T>) -> Control {
        self(segment, progress)
    }
}

/// What [`solve_observed`] keeps of the path (see the module's memory model).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Keep {
    /// Every segment in full, as [`crate::solve`].
    All,
    /// A [`CompactPath`] with a full segment every `checkpoint_every` segments
    /// (0: only the first and the last).
    Compact {
        /// Distance between full segments.
        checkpoint_every: usize,
    },
    /// Breakpoints and the end point only.
    Nothing,
}

/// The result of [`solve_observed`].
#[derive(Debug)]
pub struct Observed<T: Scalar, O> {
    /// The path; its `segments` are empty unless [`Keep::All`] (or an
    /// escalation, see the module's limits).
    pub path: Path<T>,
    /// The compact path, for [`Keep::Compact`].
    pub compact: Option<CompactPath<T>>,
    /// The observer, handed back with whatever it kept.
    pub observer: O,
}

/// A path in memory linear in `(p + n) + pivots`: segment ranges, sparse basis
/// changes, and a few full segments from which the others are recomputed.
#[derive(Clone, Debug)]
pub struct CompactPath<T: Scalar> {
    /// `(lambda_from, lambda_to, unbounded)` per segment.
    pub ranges: Vec<(T, T, bool)>,
    /// Per segment, the end of its changes in `changes` (segment `k`'s are
    /// `changes[change_end[k - 1]..change_end[k]]`).
    change_end: Vec<usize>,
    /// `(position in Segment::basis, variable)`; a position equal to the basis
    /// length appends, and a length change is recorded as a full checkpoint.
    changes: Vec<(u32, Var)>,
    /// Full segments: the first, the last, every `checkpoint_every`-th.
    checkpoints: Vec<(usize, Segment<T>)>,
    method: Method,
    dependent_rows: Vec<usize>,
}

impl<T: Scalar> CompactPath<T> {
    fn new(method: Method) -> Self {
        Self {
            ranges: Vec::new(),
            change_end: Vec::new(),
            changes: Vec::new(),
            checkpoints: Vec::new(),
            method,
            dependent_rows: Vec::new(),
        }
    }

    /// Number of segments.
    pub fn len(&self) -> usize {
        self.ranges.len()
    }

    /// True when the path has no segment.
    pub fn is_empty(&self) -> bool {
        self.ranges.is_empty()
    }

    /// Bytes held (vectors' lengths, not their spare capacity).
    pub fn bytes(&self) -> usize {
        let t = std::mem::size_of::<T>();
        let seg = |s: &Segment<T>| {
            std::mem::size_of::<Segment<T>>()
                + s.basis.len() * std::mem::size_of::<Var>()
                + (s.z_from.nrows() + s.dz.nrows() + s.w_from.nrows() + s.dw.nrows()) * t
                + (s.u_from.nrows() + s.du.nrows()) * t
        };
        std::mem::size_of::<Self>()
            + self.ranges.len() * std::mem::size_of::<(T, T, bool)>()
            + self.change_end.len() * std::mem::size_of::<usize>()
            + self.changes.len() * std::mem::size_of::<(u32, Var)>()
            + self.dependent_rows.len() * std::mem::size_of::<usize>()
            + self
                .checkpoints
                .iter()
                .map(|(_, s)| std::mem::size_of::<usize>() + seg(s))
                .sum::<usize>()
    }

    /// The index of the first segment (in path order) whose range holds `lambda`.
    pub fn segment_at(&self, lambda: T) -> Option<usize> {
        self.ranges.iter().position(|&(a, b, unbounded)| {
            let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
            lambda >= lo && (unbounded || lambda <= hi)
        })
    }

    /// The stored full segment `k`, if it is a checkpoint.
    pub fn checkpoint(&self, k: usize) -> Option<&Segment<T>> {
        self.checkpoints
            .binary_search_by_key(&k, |(i, _)| *i)
            .ok()
            .map(|j| &self.checkpoints[j].1)
    }

    /// The complementary basis of segment `k` (as [`Segment::basis`]), from the
    /// nearest checkpoint before it and the changes since.
    pub fn basis(&self, k: usize) -> Option<Vec<Var>> {
        if k >= self.len() {
            return None;
        }
        let j = match self.checkpoints.binary_search_by_key(&k, |(i, _)| *i) {
            Ok(j) => j,
            Err(0) => return None,
            Err(j) => j - 1,
        };
        let (c, seg) = &self.checkpoints[j];
        let mut b = seg.basis.clone();
        for s in c + 1..=k {
            let from = if s == 0 { 0 } else { self.change_end[s - 1] };
            for &(pos, v) in &self.changes[from..self.change_end[s]] {
                let pos = pos as usize;
                if pos == b.len() {
                    b.push(v);
                } else {
                    b[pos] = v;
                }
            }
        }
        Some(b)
    }

    /// The solution at `lambda` (first segment in path order that holds it).
    ///
    /// On a checkpoint this is [`Segment::eval`], the same numbers as the full
    /// path. Elsewhere the segment's basis is refactorised at `lambda` (a warm
    /// start of [`crate::solve`] on `problem` with `settings`, zero pivots):
    /// the same point to the rounding of one solve, not bit for bit. `None`
    /// outside the traced range; `Err` if the warm start was refused (then the
    /// message says why).
    pub fn at(
        &self,
        problem: &Plcp<T>,
        settings: &Settings<T>,
        lambda: T,
    ) -> Result<Option<Point<T>>, PlcpError> {
        let Some(k) = self.segment_at(lambda) else {
            return Ok(None);
        };
        if let Some(seg) = self.checkpoint(k) {
            return Ok(Some(seg.eval(lambda)));
        }
        let (p, n) = (problem.free(), problem.n());
        let mut b = self.basis(k).expect("segment inside the path");
        let missing_u: Vec<Var> = (0..p).map(Var::U).filter(|v| !b.contains(v)).collect();
        match self.method {
            Method::Lemke => b.extend(missing_u),
            Method::Wolfe => {
                if (p + n).saturating_sub(b.len()) == self.dependent_rows.len() {
                    b.extend(self.dependent_rows.iter().map(|&k| Var::Artificial(k)));
                }
            }
        }
        let pr = problem.clone().with_range(lambda, Some(lambda))?;
        let mut s = settings.clone();
        s.warm_basis = Some(b);
        s.escalate = false;
        s.max_pivots = Some(1);
        let path = crate::solve(&pr, &s)?;
        if !path.info.warm_start {
            return Err(PlcpError::Invalid {
                what: "compact path".into(),
                why: format!(
                    "segment {k}'s basis could not be refactorised at L = {:e}: {}",
                    lambda.to_f64(),
                    path.info.warm_start_note
                ),
            });
        }
        Ok(Some(path.end))
    }
}

/// Traces `problem` as [`crate::solve`] does, handing each segment to
/// `observer` as soon as it is known and keeping what `keep` says.
///
/// The numbers are those of [`crate::solve`] with the same settings, bit for
/// bit (segments, breakpoints, end), unless the observer stops the trace.
/// The observer is `'static` (moved in, handed back in [`Observed`]), as in
/// argmin; share state with it through `Rc<RefCell<_>>` if needed.
pub fn solve_observed<T, O>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
    observer: O,
    keep: Keep,
) -> Result<Observed<T, O>, PlcpError>
where
    T: Scalar + 'static,
    O: Observer<T> + 'static,
{
    let shared = Rc::new(RefCell::new(observer));
    // the principal-pivoting fast path's answer, if it gives one, is handed
    // to the observer after the fact (the path `crate::solve` returns, the
    // same bits), as a path on a Schur reduction is
    let (mut fast, fast_path) = match crate::trace::principal_measured(problem, settings) {
        Ok(path) => (Some(path), ""),
        Err(why) => (None, why),
    };
    let in_engine = fast.is_none() && !(settings.method == Method::Lemke && problem.free() > 0);
    let (p, n) = (problem.free(), problem.n());
    let unscale = if settings.scaling && in_engine {
        let eq = crate::scaling::Equilibration::ruiz(problem, 8);
        (!eq.is_identity()).then(|| Unscale {
            cu: (0..p).map(|j| T::from_f64(eq.cols[j])).collect(),
            cz: (0..n).map(|i| T::from_f64(eq.cols[p + i])).collect(),
            rw: (0..n).map(|i| T::from_f64(eq.rows[p + i])).collect(),
        })
    } else {
        None
    };
    STOP.with(|s| s.set(false));
    let outer = if in_engine {
        let dyn_obs: Rc<RefCell<dyn Observer<T>>> = shared.clone();
        let active = Active::<T> {
            observer: dyn_obs,
            keep,
            unscale,
            compact: CompactPath::new(settings.method),
            last_basis: Vec::new(),
            emitted: 0,
            breakpoints_at: Vec::new(),
            units: (keep != Keep::All).then(|| crate::residual::SignUnits::new(problem)),
            ends: None,
        };
        ACTIVE.with(|a| a.replace(Some(Box::new(active))))
    } else {
        None
    };
    let result = match fast.take() {
        Some(mut path) => {
            path.info.path_bytes = path_bytes(&path);
            Ok(path)
        }
        None => crate::solve(problem, settings),
    };
    let active = if in_engine {
        ACTIVE
            .with(|a| a.replace(outer))
            .and_then(|b| b.downcast::<Active<T>>().ok())
    } else {
        None
    };
    let stopped = STOP.with(|s| s.replace(false));
    let mut path = result?;
    if !fast_path.is_empty() {
        // the engine's own call of the fast path saw the observer and
        // declined; the reason that counts is the one before it
        path.info.fast_path = fast_path;
    }
    let mut compact = None;
    match active {
        Some(active) => {
            let Active {
                compact: mut c,
                breakpoints_at,
                emitted,
                observer,
                ..
            } = *active;
            drop(observer);
            let escalated = path.info.escalation.is_some();
            if keep != Keep::All && !escalated {
                // breakpoint `j` lies after the segments emitted before it
                let mut s = 0;
                for (j, b) in path.breakpoints.iter_mut().enumerate() {
                    while s < emitted && breakpoints_at[s] <= j {
                        s += 1;
                    }
                    b.segment = s;
                }
            }
            if stopped && path.status == Status::PivotLimit {
                stop_status(&mut path);
            }
            if let Keep::Compact { .. } = keep {
                c.dependent_rows = path.info.free_block.dependent_rows.clone();
                if !escalated {
                    // the last segment as the path holds it (unscaled, and cut
                    // back by the residual guard if that failed the path)
                    c.close(path.segments.last().cloned());
                }
                compact = Some(c);
            }
            if keep != Keep::All && !escalated {
                path.segments = Vec::new();
            }
        }
        None => {
            // after the fact: Lemke on a Schur reduction, or the fast path
            let mut obs = shared.borrow_mut();
            let mut stop_at = None;
            for (k, seg) in path.segments.iter().enumerate() {
                let bps: Vec<&Breakpoint<T>> =
                    path.breakpoints.iter().filter(|b| b.segment <= k).collect();
                let progress = Progress {
                    index: k,
                    pivots: bps.len(),
                    breakpoint: bps.last().copied(),
                    breakpoints: bps.len(),
                };
                if obs.on_segment(seg, &progress) == Control::Stop {
                    stop_at = Some(k + 1);
                    break;
                }
            }
            drop(obs);
            if let Some(k) = stop_at.filter(|&k| k < path.segments.len()) {
                let end = path.segments[k - 1].eval(path.segments[k - 1].lambda_to);
                path.segments.truncate(k);
                path.breakpoints.retain(|b| b.segment <= k);
                path.lambda_reached = end.lambda;
                path.end = end;
                stop_status(&mut path);
            }
            if let Keep::Compact { checkpoint_every } = keep {
                let mut c = CompactPath::new(settings.method);
                c.dependent_rows = path.info.free_block.dependent_rows.clone();
                let mut last = Vec::new();
                let total = path.segments.len();
                for (k, seg) in path.segments.iter().enumerate() {
                    c.push(seg, &mut last, checkpoint_every, k + 1 == total);
                }
                compact = Some(c);
            }
            if keep != Keep::All {
                path.segments = Vec::new();
            }
        }
    }
    path.info.path_bytes = path_bytes(&path) + compact.as_ref().map_or(0, |c| c.bytes());
    let observer = Rc::try_unwrap(shared)
        .ok()
        .expect("the observer is held only here after the solve")
        .into_inner();
    Ok(Observed {
        path,
        compact,
        observer,
    })
}

fn stop_status<T: Scalar>(path: &mut Path<T>) {
    path.status = Status::StoppedByObserver;
    path.message = format!(
        "stopped by the observer at L = {:e}",
        path.lambda_reached.to_f64()
    );
    path.ray = None;
    path.final_basis = None;
}

/// Bytes held by a path's vectors (segments, breakpoints, end, ray).
pub fn path_bytes<T: Scalar>(path: &Path<T>) -> usize {
    let t = std::mem::size_of::<T>();
    let pt = |p: &Point<T>| (p.z.nrows() + p.w.nrows() + p.u.nrows()) * t;
    let seg = |s: &Segment<T>| {
        std::mem::size_of::<Segment<T>>()
            + s.basis.len() * std::mem::size_of::<Var>()
            + (2 * s.z_from.nrows() + 2 * s.w_from.nrows() + 2 * s.u_from.nrows()) * t
    };
    std::mem::size_of::<Path<T>>()
        + path.segments.iter().map(seg).sum::<usize>()
        + path.breakpoints.len() * std::mem::size_of::<Breakpoint<T>>()
        + pt(&path.end)
        + path.ray.as_ref().map_or(0, |r| {
            pt(&r.start) + (r.dz.nrows() + r.dw.nrows() + r.du.nrows()) * t
        })
        + path
            .final_basis
            .as_ref()
            .map_or(0, |b| b.len() * std::mem::size_of::<Var>())
}

impl<T: Scalar> CompactPath<T> {
    /// Appends a segment: its range, its change of basis against `last`, and
    /// the segment itself if it is a checkpoint.
    fn push(&mut self, seg: &Segment<T>, last: &mut Vec<Var>, every: usize, is_last: bool) {
        let k = self.ranges.len();
        self.ranges
            .push((seg.lambda_from, seg.lambda_to, seg.unbounded));
        let full =
            k == 0 || is_last || (every > 0 && k % every == 0) || seg.basis.len() != last.len();
        if !full {
            for (i, (a, b)) in last.iter().zip(&seg.basis).enumerate() {
                if a != b {
                    self.changes.push((i as u32, *b));
                }
            }
        }
        self.change_end.push(self.changes.len());
        if full {
            self.checkpoints.push((k, seg.clone()));
        }
        last.clear();
        last.extend_from_slice(&seg.basis);
    }

    /// Makes the path's last segment (as the finished path holds it) a
    /// checkpoint.
    fn close(&mut self, latest: Option<Segment<T>>) {
        let k = self.ranges.len();
        let (Some(seg), true) = (latest, k > 0) else {
            return;
        };
        self.ranges[k - 1] = (seg.lambda_from, seg.lambda_to, seg.unbounded);
        match self.checkpoints.last_mut() {
            Some((i, s)) if *i == k - 1 => *s = seg,
            _ => self.checkpoints.push((k - 1, seg)),
        }
    }
}

struct Unscale<T> {
    cu: Vec<T>,
    cz: Vec<T>,
    rw: Vec<T>,
}

/// The sink the engine writes into while [`solve_observed`] runs.
struct Active<T: Scalar> {
    observer: Rc<RefCell<dyn Observer<T>>>,
    keep: Keep,
    unscale: Option<Unscale<T>>,
    compact: CompactPath<T>,
    last_basis: Vec<Var>,
    emitted: usize,
    /// Breakpoints recorded when each segment was emitted.
    breakpoints_at: Vec<usize>,
    /// The problem's units, to measure the ends of the segments that are
    /// handed over and not kept; `None` with [`Keep::All`] (the stored path
    /// is measured whole, [`crate::residual::measure_ends`]).
    units: Option<crate::residual::SignUnits>,
    /// The largest residual of those segments' ends so far.
    ends: Option<crate::path::Residual>,
}

/// The largest residual at the ends of the segments an observed trace of
/// this scalar type handed over and did not keep (see [`Active::ends`]):
/// [`crate::residual::measure_ends`] counts them as if they were stored.
pub(crate) fn emitted_ends<T: Scalar>() -> Option<crate::path::Residual> {
    ACTIVE.with(|a| {
        a.borrow()
            .as_ref()
            .and_then(|b| b.downcast_ref::<Active<T>>())
            .and_then(|active| active.ends)
    })
}

/// True while [`solve_observed`] runs on this thread (any scalar type): the
/// principal-pivoting fast path (`plcp/src/principal.rs`) then leaves the trace
/// to the engine, whose recording site hands segments to the observer.
pub(crate) fn observing() -> bool {
    ACTIVE.with(|a| a.borrow().is_some())
}

thread_local! {
    static ACTIVE: RefCell<Option<Box<dyn Any>>> = const { RefCell::new(None) };
    static STOP: Cell<bool> = const { Cell::new(false) };
}

/// Set when an observer asked to stop: the engine ends its trace at the next
/// step (as a pivot limit, relabelled by [`solve_observed`]).
pub(crate) fn stop_requested() -> bool {
    STOP.with(|s| s.get())
}

/// The engine's one recording site: a finished segment, on the system the
/// engine traces (scaled). Without an active observer of this scalar type it
/// is stored as before.
pub(crate) fn record<T: Scalar>(
    segments: &mut Vec<Segment<T>>,
    breakpoints: &[Breakpoint<T>],
    pivots: usize,
    segment: Segment<T>,
) {
    let taken = ACTIVE.with(|a| {
        let mut slot = a.borrow_mut();
        let is_ours = slot.as_ref().is_some_and(|b| b.is::<Active<T>>());
        if is_ours {
            slot.take()
        } else {
            None
        }
    });
    let Some(mut boxed) = taken else {
        segments.push(segment);
        return;
    };
    let active = boxed.downcast_mut::<Active<T>>().expect("checked");
    let mut segment = segment;
    // the engine's path is unscaled as a whole after the trace: it keeps the
    // scaled original, the observer sees the unscaled copy (same operations)
    let mut original = None;
    if let Some(u) = &active.unscale {
        original = Some(segment.clone());
        let fix = |z: &mut faer::Col<T>, w: &mut faer::Col<T>, uu: &mut faer::Col<T>| {
            for i in 0..z.nrows() {
                z[i] *= u.cz[i];
            }
            for i in 0..w.nrows() {
                w[i] /= u.rw[i];
            }
            for j in 0..uu.nrows() {
                uu[j] *= u.cu[j];
            }
        };
        fix(
            &mut segment.z_from,
            &mut segment.w_from,
            &mut segment.u_from,
        );
        fix(&mut segment.dz, &mut segment.dw, &mut segment.du);
    }
    let progress = Progress {
        index: active.emitted,
        pivots,
        breakpoint: breakpoints.last(),
        breakpoints: breakpoints.len(),
    };
    let control = active.observer.borrow_mut().on_segment(&segment, &progress);
    if let Some(units) = &active.units {
        // measured as the stored path's segments are (the same unscaled bits)
        let r = crate::residual::segment_ends(units, &segment);
        active.ends = Some(active.ends.map_or(r, |a| a.max(r)));
    }
    active.breakpoints_at.push(breakpoints.len());
    active.emitted += 1;
    if let Keep::Compact { checkpoint_every } = active.keep {
        let mut last = std::mem::take(&mut active.last_basis);
        active
            .compact
            .push(&segment, &mut last, checkpoint_every, false);
        active.last_basis = last;
    }
    // the engine's own vector: everything for Keep::All, else the first and
    // the latest segment (the residual measured at the path's ends reads them)
    let stored = original.unwrap_or(segment);
    if active.keep == Keep::All || segments.len() < 2 {
        segments.push(stored);
    } else {
        segments[1] = stored;
    }
    if control == Control::Stop {
        STOP.with(|s| s.set(true));
    }
    ACTIVE.with(|a| *a.borrow_mut() = Some(boxed));
}
