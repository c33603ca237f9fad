//! Certifying a float path exactly.
//!
//! For segment `k` with basis `S_k` (one of `z_i`, `w_i` per pair, plus the
//! free variables), the exact basic solution `x(L) = a + L b` is feasible on
//! the exact interval `I_k = {L : a_i + L b_i >= 0 for every basic z, w}`.
//! The certificate holds when, with `E_{-1} = L0`:
//!
//! 1. `S_k` is complementary (for each pair exactly one of `z_i`, `w_i`) and its
//!    equality rows hold (an equality row whose artificial stays basic must
//!    read `0 = 0` in both `q` and `d`);
//! 2. `E_{k-1}` lies in `I_k` (the segment starts, feasibly, where the previous
//!    one ended exactly);
//! 3. `E_k` is the end of `I_k` in the segment's direction (where its leaving
//!    variable reaches zero; the breakpoint's leaving variable must be zero
//!    there), or `L_max` for the last segment of a `reached` path (which needs
//!    `L_max` in `I_k`), or `+inf` for an unbounded ray (which needs `I_k`
//!    unbounded above).
//! 4. A `secondary_ray` (the path claims it cannot go on) is proven
//!    directly at any order (ray.rs): from the last segment's basis, the
//!    exact pivots at `L*` (each forced, `L` held at `L*`) reach a basis
//!    whose driver's column blocks nothing while the rate of `L` is not
//!    positive. Where that is undecided (a tie at `L*`, a Wolfe basis with
//!    free variables held at zero), the path is continued exactly from the
//!    last segment's basis ([`super::trace_from`], order at most
//!    [`super::EXACT_MAX_DIM`]), which must end on a secondary ray at the
//!    same exact `L`.
//!
//! Where the float path steps over events closer than its rounding (two
//! variables reaching zero `1e-16` apart, taken as one degenerate breakpoint
//! with two pivots), `E_{k-1}` lies just outside `I_k`. The certificate then
//! follows the exact path from `S_{k-1}` at `E_{k-1}` by complementary pivots
//! (the variable reaching zero leaves, its complement enters) until it
//! reaches `S_k` inside `I_k`: a *bridge* of exact bases, each feasible on
//! its exact interval. A bridge is accepted only if it is unique at every
//! step (one variable reaching zero), at most [`MAX_BRIDGE`](bridge::MAX_BRIDGE) bases, and
//! spans at most `sqrt(eps)` relative to `max(1, |L|)` (the float path's
//! trust level: a longer span is a segment the float path missed, and the
//! certificate fails). [`Certificate::bridges`] counts the bases inserted.
//! Likewise a breakpoint whose float leaving variable is not yet zero at the
//! exact end (another variable reaches zero first, `1e-19` earlier) is
//! accepted when the next segment is reached from that exact end
//! ([`Certificate::reordered`]); if it is not, that is the failure.
//!
//! Then for every `L` in `[L0, E_last]` some `S_k` gives an exact solution,
//! complementary since the non-basic member of each pair is zero: the path's
//! claim holds exactly, whatever rounding its floats carry. Free variables
//! that cannot be basic (a singular free block) are held at zero, which gives
//! one of the solutions if any exists with this `S_k`.

mod bases;
mod bridge;
mod interval;
mod ray;
mod segment;

use self::bases::Bases;
use self::segment::{end_point, path_end, secondary_ray_end, segment};
use super::{short, to_rational};
use crate::path::Path;
use crate::problem::Plcp;
use crate::scalar::Scalar;
use num_rational::BigRational;
use std::time::Instant;

/// Why a path is not certified: the first segment that fails.
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    /// The segment index (`segments.len()` for a check of the path's end).
    pub segment: usize,
    /// What failed, with the exact values.
    pub reason: String,
}

/// The outcome of [`certify`].
#[derive(Clone, Debug, Default)]
pub struct Certificate {
    /// `None`: the path is certified; else the first failing segment.
    pub failure: Option<Failure>,
    /// The exact end of each certified segment, in path order (the last one is
    /// `L_max`, or absent for an unbounded ray).
    pub breakpoints: Vec<BigRational>,
    /// The largest relative difference between a float breakpoint (segment
    /// end) and its exact value.
    pub max_rel_diff: f64,
    /// Segments checked.
    pub segments: usize,
    /// Pivots of the fraction-free tableau (0 when every basis was solved by
    /// p-adic lifting; see [`Engine`]).
    pub pivots: usize,
    /// Bases solved by p-adic lifting ([`Engine::Modular`]).
    pub modular: usize,
    /// Exact bases inserted between two segments where the float path
    /// stepped over events closer than its rounding (see the module
    /// documentation); 0 when every segment starts where the previous one
    /// ends exactly.
    pub bridges: usize,
    /// The largest span of a bridge, relative to `max(1, |L|)` (0 without
    /// bridges).
    pub bridge_span: f64,
    /// Breakpoints whose float leaving variable is not the one that reaches
    /// zero first exactly (two events closer than rounding, taken in the
    /// other order), where the next segment is still reached from the exact
    /// end, directly or by a bridge.
    pub reordered: usize,
    /// How a `secondary_ray` claim was proven: `direct: ...` (the exact
    /// pivots at `L*` and the exact ray, any order; see the module
    /// documentation, 4.) or `exact continuation: ...` (the exact tracer,
    /// where the direct certificate is undecided and the order is at most
    /// [`crate::exact::EXACT_MAX_DIM`]); `None` for other statuses.
    pub secondary_ray: Option<String>,
    /// Wall-clock seconds.
    pub seconds: f64,
}

impl Certificate {
    /// True if the path is certified.
    pub fn certified(&self) -> bool {
        self.failure.is_none()
    }
    /// One line: `certified (5 segments, ...)` or the failure.
    pub fn summary(&self) -> String {
        match &self.failure {
            None => format!(
                "certified: {} segments{}, exact breakpoints [{}], largest relative difference of the float breakpoints {:.1e}{}, {:.3} s",
                self.segments,
                self.bridge_note(),
                self.breakpoints.iter().map(short).collect::<Vec<_>>().join(", "),
                self.max_rel_diff,
                self.secondary_ray
                    .as_ref()
                    .map_or(String::new(), |r| format!(", secondary ray {r}")),
                self.seconds
            ),
            Some(f) => format!("rejected at segment {}: {}", f.segment, f.reason),
        }
    }
    /// ` (with 2 exact bases bridging events the float path took as one,
    /// spans up to 3.5e-16)`, or empty without bridges.
    pub fn bridge_note(&self) -> String {
        if self.bridges == 0 && self.reordered == 0 {
            return String::new();
        }
        format!(
            " (with {} exact bases bridging events the float path took as one, spans up to {:.1e}; {} breakpoints whose events the float path took in the other order)",
            self.bridges, self.bridge_span, self.reordered
        )
    }
    /// As JSON: `{"certified", "failure": {"segment", "reason"} or null,
    /// "breakpoints": ["4", "13/3", ...], "breakpoints_f64": [...],
    /// "max_rel_diff", "segments", "pivots", "seconds"}`. With the `json`
    /// feature.
    #[cfg(feature = "json")]
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::json!({
            "certified": self.certified(),
            "failure": self.failure.as_ref().map(|f| serde_json::json!({
                "segment": f.segment, "reason": f.reason })),
            "breakpoints": self.breakpoints.iter().map(short).collect::<Vec<_>>(),
            "breakpoints_f64": self.breakpoints.iter().map(super::rational_to_f64).collect::<Vec<_>>(),
            "max_rel_diff": self.max_rel_diff,
            "segments": self.segments,
            "pivots": self.pivots,
            "modular": self.modular,
            "bridges": self.bridges,
            "bridge_span": self.bridge_span,
            "reordered": self.reordered,
            "secondary_ray": self.secondary_ray,
            "seconds": self.seconds,
        })
    }
}

/// How [`certify_with`] finds the exact solution of each segment's basis.
/// Both give the same certificate (the same checks on the same exact
/// solutions); they differ in cost.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Engine {
    /// Dixon's p-adic lifting on each square basis (an LU modulo a word-size
    /// prime, lifting, rational reconstruction, then an exact check
    /// `B x = b`), `O((p + n)^3)` word operations per segment; the
    /// fraction-free tableau takes over where a basis is not square (a
    /// dependent equality row), or the lifting does not apply (a prime
    /// dividing `det B` three times).
    #[default]
    Modular,
    /// The fraction-free tableau `det(B) B^-1 [A | q | d]` (Edmonds'
    /// integer pivoting) for every basis: one exact pivot per basis change,
    /// `O((p + n)^2)` operations on integers of thousands of bits each.
    Bareiss,
}

/// Checks `path` exactly against `problem` (see the module documentation):
/// the answer is [`Certificate::certified`] or names the first segment that
/// fails and why. Works for every precision, form and storage (a sparse `M`
/// is read through its dense copy). Solves each basis by p-adic lifting
/// ([`Engine::Modular`]); see `docs/certification.md` for the cost.
pub fn certify<T: Scalar>(problem: &Plcp<T>, path: &Path<T>) -> Certificate {
    certify_with(problem, path, Engine::Modular)
}

/// [`certify`] with the given [`Engine`] (the certificate is the same; the
/// fraction-free one is kept as a reference and for comparisons).
pub fn certify_with<T: Scalar>(problem: &Plcp<T>, path: &Path<T>, engine: Engine) -> Certificate {
    T::entry_certify_with(problem, path, engine)
}

/// [`certify_with`]'s body, instantiated in this crate (`entry.rs`).
pub(crate) fn certify_here<T: Scalar>(
    problem: &Plcp<T>,
    path: &Path<T>,
    engine: Engine,
) -> Certificate {
    let timer = Instant::now();
    let mut cert = Certificate::default();
    let result = run(problem, path, engine, &mut cert);
    cert.failure = result.err();
    cert.seconds = timer.elapsed().as_secs_f64();
    cert
}

impl<T: Scalar> Path<T> {
    /// [`certify`] this path against the problem it solves.
    pub fn certify(&self, problem: &Plcp<T>) -> Certificate {
        certify(problem, self)
    }
}

fn fail(segment: usize, reason: String) -> Failure {
    Failure { segment, reason }
}

/// What the segment loop carries from one segment to the next.
struct Chain {
    /// Where the next segment must start, exactly.
    start: BigRational,
    /// The basis (columns) of the last certified segment.
    prev_target: Option<Vec<usize>>,
    /// A breakpoint whose leaving variable is not the exact one: resolved if
    /// the next segment is reached from the exact end.
    pending: Option<Failure>,
    /// The exact solution of the last certified segment's basis.
    last: Option<super::solution::Solution>,
}

fn run<T: Scalar>(
    problem: &Plcp<T>,
    path: &Path<T>,
    engine: Engine,
    cert: &mut Certificate,
) -> Result<(), Failure> {
    let p = problem.free();
    let mut bases = Bases::new(problem, engine);
    // with a singular free block `u` is not unique: its values are not
    // compared (a nonsingular block modulo a prime is nonsingular; else the
    // tableau's pivots decide, as they did before the lifting)
    let u_unique = if engine == Engine::Modular && bases.scaled.free_block_nonsingular(p) {
        true
    } else {
        let (t, left) = bases.bareiss(cert);
        bases.tableau = Some(t);
        left == 0
    };
    let mut chain = Chain {
        start: to_rational(path.lambda0),
        prev_target: None,
        pending: None,
        last: None,
    };
    if path.segments.is_empty() {
        end_point(path, &mut bases, &chain.start, cert)?;
        return secondary_ray_end(problem, path, &bases, &chain, cert);
    }
    for k in 0..path.segments.len() {
        segment(path, k, &mut bases, &mut chain, u_unique, cert)?;
    }
    path_end(path, &chain.start)?;
    secondary_ray_end(problem, path, &bases, &chain, cert)
}
