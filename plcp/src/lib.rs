//! # plcp: parametric linear complementarity problems
//!
//! Given `M` (order `p + n`), `q`, `d` and a parameter `L` rising from `L0` to
//! `L_max` (finite or infinite), trace the solution of
//!
//! ```text
//! 0 = (M x + q + L d)[0..p]                       equality rows, u = x[0..p] free
//! w = (M x + q + L d)[p..p+n],   z = x[p..p+n],
//! w >= 0,   z >= 0,   w'z = 0
//! ```
//!
//! as a piecewise-affine [`Path`]: breakpoints (which variable entered, which
//! left), segments (basis, and `z, w, u` affine in `L`), evaluation at any `L`,
//! and an [`Info`] record that says how well the answer is known (pivots,
//! refactorisations, residuals of the equation, feasibility and complementarity
//! at every breakpoint, time). With `p = 0` this is the standard form
//! `w = q + L d + M z`.
//!
//! Two algorithms share one pivoting core:
//!
//! * [`Method::Lemke`]: Lemke-style complementary pivoting with `L` as the
//!   driving variable, on the standard form. If `q + L0 d` is not nonnegative
//!   the LCP at `L0` is first solved by Lemke's method with an artificial
//!   variable and a covering vector. A mixed problem is reduced to standard form
//!   by a Schur complement on its free block (which must be nonsingular).
//! * [`Method::Wolfe`]: Wolfe's simplex method for QP in its long form, on the
//!   unreduced tableau of the mixed system: free variables are made basic as far
//!   as the rank of the free block allows, dependent equality rows keep an
//!   artificial variable fixed at zero, and `L` rises by pivots with restricted
//!   basis entry (`z_i`, `w_i` never both basic).
//!
//! Degeneracy is handled by a lexicographic minimum-ratio rule, so no basis
//! repeats. Outcomes are [`Status`] values in the path, never errors; bad input
//! is a [`PlcpError`] at construction.
//!
//! Everything is generic over the [`Scalar`] trait: `f32`, `f64` and
//! `faer::fx128` (double-double).
//!
//! ```
//! use faer::{mat, col};
//! use plcp::{Plcp, Settings, Status};
//!
//! // w = q + L d + M z with M positive definite: a unique solution for every L.
//! let m = mat![[2.0, 1.0], [1.0, 2.0]];
//! let q = col![1.0, 1.0];
//! let d = col![-1.0, -0.5];
//! let problem = Plcp::new(m.as_ref(), q.as_ref(), d.as_ref()).unwrap();
//! let path = plcp::solve(&problem, &Settings::default()).unwrap();
//! assert_eq!(path.status, Status::UnboundedRay); // holds for every larger L
//! assert_eq!(path.breakpoints[0].lambda, 1.0);   // w0 = 1 - L reaches zero at L = 1
//! let at = path.at(3.0).unwrap();
//! assert!(at.w.iter().zip(at.z.iter()).all(|(w, z)| *w >= -1e-12 && *z >= -1e-12));
//! ```
#![deny(missing_docs)]
// Index loops read like the formulas they implement in the numeric kernels.
#![allow(clippy::needless_range_loop)]

// The public surface: the types and functions re-exported below, and the
// modules a user opens by name (exact arithmetic, file formats, sparse
// matrices, residuals, scaling, the tolerances every status depends on, the
// observers and their memory model).
// Everything else is the engine's inside.
mod basis;
mod entry;
mod error;
mod escalate;
mod evidence;
pub mod exact;
pub mod io;
mod lemke;
mod linalg;
pub mod matrix;
pub mod observe;
mod path;
mod pivoting;
mod principal;
mod problem;
#[cfg(feature = "cli")]
pub mod progress;
mod reduce;
pub mod residual;
mod scalar;
pub mod scaling;
mod settings;
mod solver;
mod sparse_lu;
#[cfg(test)]
mod test_rng;
pub mod tolerance;
mod trace;
mod wolfe;

/// Test hook (not part of the API): while on, the lexicographic rule also
/// breaks every tie the way it did before issue 15's change and panics on a
/// different choice (`PLCP_LEX_CHECK=1` turns it on for a whole process);
/// returns the number of ties checked so far on the calling thread.
#[doc(hidden)]
pub use basis::lex::set_check as lex_check;
pub use error::PlcpError;
pub use escalate::Escalation;
pub use exact::{certify, Certificate};
pub use lemke::{solve_lcp, LcpSolution};
pub use observe::{solve_observed, CompactPath, Control, Keep, Observed, Observer, Progress};
pub use path::{Breakpoint, FreeBlockInfo, Info, Path, Point, Ray, Residual, Segment, Status, Var};
pub use problem::{Lcp, Plcp};
pub use scalar::{infinity, Precision, Scalar};
pub use settings::{BasisKind, Method, NearTies, Settings, DEFAULT_REFACTOR_PERIOD};
pub use solver::{warm_up, Solver, StepEnd};

/// Traces the solution path of `problem` with the method chosen in `settings`.
///
/// With [`Settings::escalate`], a path that ends `IllConditioned` in `f32` or
/// `f64`, or claims its end on a basis too ill-conditioned to be sure of it
/// ([`tolerance::ESCALATE_COND_EPS`]), is continued in `fx128` (the
/// splice is described by [`Escalation`]).
///
/// Returns `Err` only for invalid settings, or for [`Method::Lemke`] on a mixed
/// problem whose free block is singular (use [`Method::Wolfe`] there). Every
/// outcome of the algorithm itself is a [`Status`] in the returned path.
pub fn solve<T: Scalar>(problem: &Plcp<T>, settings: &Settings<T>) -> Result<Path<T>, PlcpError> {
    T::entry_solve(problem, settings)
}

/// [`solve`]'s body, instantiated in this crate for the three types
/// (`entry.rs`).
pub(crate) fn solve_here<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
) -> Result<Path<T>, PlcpError> {
    let mut path = trace::trace(problem, settings)?;
    path.info.path_bytes = observe::path_bytes(&path);
    if settings.escalate && escalate::needs_fx128(&path) {
        escalate::continue_in_fx128(problem, settings, &mut path);
        if path.info.escalation.is_some() {
            // the spliced path: start and end measured on the original problem,
            // the breakpoints keep the residuals their precision measured
            let both_ends = settings.method == Method::Lemke && problem.free() > 0;
            trace::measure(problem, &mut path, both_ends);
            trace::guard_residual(&mut path);
        }
    }
    if settings.escalate && settings.escalate_exact && path.status == Status::IllConditioned {
        escalate::continue_exactly(problem, settings, &mut path);
        if path.info.escalation.as_ref().is_some_and(|e| e.exact) {
            let both_ends = settings.method == Method::Lemke && problem.free() > 0;
            trace::measure(problem, &mut path, both_ends);
            trace::guard_residual(&mut path);
        }
    }
    Ok(path)
}

/// [`solve`], then [`certify`] the path in exact rational arithmetic; the
/// certificate is [`Info::certificate`]. A path that claims success
/// (`reached`, `unbounded_ray`) or an end (`secondary_ray`) but is rejected
/// becomes `IllConditioned`
/// (its floats cannot be trusted in this precision: try a higher one, or
/// [`exact::trace`]), `lambda_reached` falls back to the start of the failing
/// segment, and the message gives the certificate's reason. So a success
/// or `secondary_ray` status from this function is a certified one. Costs one exact pivot per
/// basis change (`docs/certification.md`). With [`Settings::escalate`] (and
/// [`Settings::escalate_exact`]) a rejected segment is first traced again in
/// `fx128` (then exactly) from the certified one before it, and the new path
/// certified ([`Escalation::segment_precisions`] says which precision produced
/// which segment).
///
/// ```
/// use faer::{mat, col};
/// let m = mat![[2.0, 1.0], [1.0, 2.0]];
/// let problem = plcp::Plcp::new(m.as_ref(), col![1.0, 1.0].as_ref(), col![-1.0, -0.5].as_ref()).unwrap();
/// let path = plcp::solve_certified(&problem, &plcp::Settings::default()).unwrap();
/// let cert = path.info.certificate.as_ref().unwrap();
/// assert!(cert.certified());
/// assert_eq!(plcp::exact::short(&cert.breakpoints[0]), "1"); // w0 = 1 - L
/// ```
pub fn solve_certified<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
) -> Result<Path<T>, PlcpError> {
    let mut path = solve(problem, settings)?;
    let cert = T::entry_certify_escalating(problem, settings, &mut path);
    reject_uncertified(&mut path, &cert);
    path.info.certificate = Some(cert);
    Ok(path)
}

/// A path that claims success or a secondary ray but whose exact certificate
/// rejects it becomes `IllConditioned` (its floats cannot be trusted in this precision), with the
/// certificate's reason, and claims nothing beyond the start of the failing
/// segment.
fn reject_uncertified<T: Scalar>(path: &mut Path<T>, cert: &Certificate) {
    let Some(fail) = &cert.failure else {
        return;
    };
    // a secondary ray is a claim too (no solution beyond it on this path),
    // which the certificate checks exactly: rejected, it is withdrawn
    if !path.status.is_success() && path.status != Status::SecondaryRay {
        path.message = format!(
            "{} (exact certification of the traced part: rejected at segment {}: {})",
            path.message, fail.segment, fail.reason
        );
        return;
    }
    path.message = format!(
        "exact certification rejected the {} path at segment {}: {}; the answer cannot be trusted in {}: try a higher precision or exact. {}",
        path.status.as_str(),
        fail.segment,
        fail.reason,
        T::NAME,
        path.message
    );
    path.status = Status::IllConditioned;
    if let Some(seg) = path.segments.get(fail.segment) {
        path.lambda_reached = seg.lambda_from;
    } else if !path.lambda_reached.is_finite() {
        path.lambda_reached = path.end.lambda;
    }
    if let Some(seg) = path.segments.last_mut() {
        if seg.unbounded {
            seg.unbounded = false;
            seg.lambda_to = seg.lambda_from;
        }
    }
    path.ray = None;
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::{col, mat};

    /// A `secondary_ray` the certificate rejects is withdrawn like a
    /// success: the unbounded ray of `w0 = 1 - L` (then `z0` rises) cut at
    /// its breakpoint and relabelled `secondary_ray` becomes
    /// `ill_conditioned`; the true path stays as it is.
    #[test]
    fn a_rejected_secondary_ray_is_withdrawn() {
        let m = mat![[2.0, 1.0], [1.0, 2.0]];
        let problem = Plcp::new(
            m.as_ref(),
            col![1.0, 1.0].as_ref(),
            col![-1.0, -0.5].as_ref(),
        )
        .unwrap();
        let path = solve(&problem, &Settings::default()).unwrap();
        assert_eq!(path.status, Status::UnboundedRay);
        let mut right = path.clone();
        reject_uncertified(&mut right, &certify(&problem, &path));
        assert_eq!(right.status, Status::UnboundedRay);
        let mut wrong = path.clone();
        let last = wrong.segments.pop().unwrap();
        wrong.status = Status::SecondaryRay;
        wrong.lambda_reached = last.lambda_from;
        wrong.ray = None;
        let cert = certify(&problem, &wrong);
        assert!(!cert.certified(), "{}", cert.summary());
        reject_uncertified(&mut wrong, &cert);
        assert_eq!(wrong.status, Status::IllConditioned, "{}", wrong.message);
        assert!(
            wrong.message.contains("exact continuation"),
            "{}",
            wrong.message
        );
    }
}
