//! One trace of a problem in its own precision: validate the settings, scale
//! (Ruiz equilibration), run the method, unscale, measure the residuals on the
//! original problem, and turn a success whose residual is too large into
//! `IllConditioned`. [`crate::solve`] adds the escalation to `fx128` on top;
//! the escalation itself calls this (never the crate root), so the two do not
//! call each other.

use crate::error::PlcpError;
use crate::path::{Path, Status, Var};
use crate::problem::Plcp;
use crate::residual::RowScales;
use crate::scalar::Scalar;
use crate::settings::{Method, Settings};
use crate::{lemke, residual, scaling, wolfe};

/// Traces `problem` once in `T` (no escalation), residual guarded.
pub(crate) fn trace<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
) -> Result<Path<T>, PlcpError> {
    let mut path = trace_unguarded(problem, settings)?;
    guard_residual(&mut path);
    Ok(path)
}

/// A path that claims success must satisfy the problem: if its largest residual
/// (measured on the original problem) exceeds `sqrt(eps)`, the status becomes
/// `IllConditioned` with the evidence, never a confident wrong answer.
pub(crate) fn guard_residual<T: Scalar>(path: &mut Path<T>) {
    let limit = T::eps().to_f64().sqrt();
    let worst = path.info.residual.worst();
    if path.status.is_success() && (worst.is_nan() || worst > limit) {
        path.message = format!(
            "the path's largest residual {worst:.3e} (equation {:.1e}, feasibility {:.1e}, complementarity {:.1e}) exceeds sqrt(eps) = {limit:.1e} in {}: the answer cannot be trusted; try a higher precision. {}",
            path.info.residual.equation,
            path.info.residual.feasibility,
            path.info.residual.complementarity,
            T::NAME,
            path.message
        );
        path.status = Status::IllConditioned;
        // nothing beyond the last finite point is claimed any more
        if let Some(seg) = path.segments.last_mut() {
            if seg.unbounded {
                seg.unbounded = false;
                seg.lambda_to = seg.lambda_from;
            }
        }
        if !path.lambda_reached.is_finite() {
            path.lambda_reached = path.end.lambda;
        }
        path.ray = None;
    }
}

pub(crate) fn measure<T: Scalar>(problem: &Plcp<T>, path: &mut Path<T>, whole: bool) {
    measure_scaled(problem, path, whole, RowScales::Unknown);
}

/// [`measure`] of a path traced with row scales `rows`, which bound how far
/// the trace's own breakpoint residuals may be below the documented measure
/// ([`residual::measure_for_guard`]).
fn measure_scaled<T: Scalar>(
    problem: &Plcp<T>,
    path: &mut Path<T>,
    whole: bool,
    rows: RowScales<'_>,
) {
    if whole {
        residual::measure_path(problem, path, true);
    } else {
        residual::measure_for_guard(problem, path, rows);
    }
}

fn trace_unguarded<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
) -> Result<Path<T>, PlcpError> {
    settings.validate(problem.n())?;
    if let Some(b) = &settings.warm_basis {
        let (p, dim) = (problem.free(), problem.dim());
        let why = if b.len() != dim {
            Some(format!("{} variables for {dim} rows (p + n)", b.len()))
        } else {
            b.iter().find_map(|v| match *v {
                Var::U(j) | Var::Artificial(j) if j >= p => {
                    Some(format!("{v} with only {p} free variables / equality rows"))
                }
                _ => None,
            })
        };
        if let Some(why) = why {
            return Err(PlcpError::Invalid {
                what: "warm_basis".into(),
                why,
            });
        }
    }
    let timer = std::time::Instant::now();
    // the principal-pivoting fast path, on the data as given (its tolerances
    // are relative to each pivot's and row's own terms; a badly scaled
    // problem shows in its condition bound and goes to the engine, which
    // equilibrates)
    let fast_path = match principal_measured(problem, settings) {
        Ok(path) => return Ok(path),
        Err(why) => why,
    };
    // no scales (none asked for, all one, or the scaled data overflow): the
    // trace runs on `problem` itself
    let eq = settings
        .scaling
        .then(|| scaling::Equilibration::ruiz(problem, 8));
    let scaled = eq
        .as_ref()
        .filter(|eq| !eq.is_identity())
        .and_then(|eq| Some((eq, eq.scale(problem)?)));
    // segments of Lemke on the Schur reduction are re-solved one by one on the
    // unreduced system: measure both ends of each
    let both_ends = settings.method == Method::Lemke && problem.free() > 0;
    let Some((eq, scaled)) = scaled else {
        let mut path = match settings.method {
            Method::Lemke => lemke::solve(problem, settings)?,
            Method::Wolfe => wolfe::solve(problem, settings)?,
        };
        measure_scaled(problem, &mut path, both_ends, RowScales::Ones);
        path.info.solve_seconds = timer.elapsed().as_secs_f64();
        path.info.fast_path = fast_path;
        return Ok(path);
    };
    // the covering vector acts on the rows of w: scale it with them, so the start
    // phase follows the same path as on the unscaled problem
    let (p, n) = (problem.free(), problem.n());
    let mut scaled_settings = settings.clone();
    scaled_settings.covering = Some(faer::Col::from_fn(n, |i| {
        let c = settings.covering.as_ref().map_or(T::one(), |c| c[i]);
        c * T::from_f64(eq.rows[p + i])
    }));
    let mut path = match settings.method {
        Method::Lemke => lemke::solve(&scaled, &scaled_settings)?,
        Method::Wolfe => wolfe::solve(&scaled, &scaled_settings)?,
    };
    eq.unscale(problem, &mut path);
    measure_scaled(problem, &mut path, both_ends, RowScales::Scaled(&eq.rows));
    path.info.solve_seconds = timer.elapsed().as_secs_f64();
    path.info.fast_path = fast_path;
    Ok(path)
}

/// The fast path's answer ([`principal`]) measured on the problem as every
/// path is, if its residual passes the guard (`sqrt(eps)`); else why not
/// ([`crate::Info::fast_path`]: the kernel was not tried, declined, or the
/// guard would fail it; the engine then traces).
/// [`crate::observe::solve_observed`] calls this before it starts its
/// observer, and hands the path to the observer after the fact.
pub(crate) fn principal_measured<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
) -> Result<Path<T>, &'static str> {
    T::entry_principal_measured(problem, settings)
}

/// [`principal_measured`]'s body, instantiated in this crate (`entry.rs`).
pub(crate) fn principal_measured_here<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
) -> Result<Path<T>, &'static str> {
    if settings.validate(problem.n()).is_err() {
        return Err("not tried: invalid settings");
    }
    let timer = std::time::Instant::now();
    let mut path = principal(problem, settings)?;
    measure_scaled(problem, &mut path, false, RowScales::Ones);
    let worst = path.info.residual.worst();
    if worst.is_nan() || worst > T::eps().to_f64().sqrt() {
        return Err("declined: the measured residual above sqrt(eps)");
    }
    path.info.solve_seconds = timer.elapsed().as_secs_f64();
    Ok(path)
}

/// The path by `plcp/src/principal.rs` where the settings allow it and the
/// kernel answers: Lemke's method asked for, standard form, dense `M`, `f64`,
/// the default block basis, no warm basis.
fn principal<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
) -> Result<Path<T>, &'static str> {
    let not = if !settings.principal {
        "not tried: Settings::principal is off"
    } else if settings.method != Method::Lemke {
        "not tried: Wolfe's method asked for"
    } else if problem.free() > 0 {
        "not tried: free variables (mixed form)"
    } else if settings.warm_basis.is_some() {
        "not tried: a warm basis given"
    } else if settings.basis != crate::settings::BasisKind::Block {
        "not tried: a basis other than the default block basis asked for"
    } else if T::NAME != "f64" {
        "not tried: a precision other than f64"
    } else if !problem.lambda_max().is_some_and(|l| l.is_finite()) {
        "not tried: no finite L_max"
    } else if problem.n() > crate::tolerance::PRINCIPAL_MAX_N {
        // (a `&'static str`: the number is written out, and the build fails
        // where it and the constant part)
        const _: () = assert!(crate::tolerance::PRINCIPAL_MAX_N == 800);
        "not tried: order above PRINCIPAL_MAX_N = 800"
    } else {
        ""
    };
    if !not.is_empty() {
        return Err(not);
    }
    let crate::matrix::MatrixRef::Dense(m) = problem.matrix() else {
        return Err("not tried: sparse M");
    };
    let max_pivots = settings.max_pivots_for(problem.dim());
    crate::principal::trace(
        m,
        problem.q(),
        problem.d(),
        problem.lambda0(),
        problem.lambda_max(),
        max_pivots,
        "lemke (principal)",
    )
    .map_err(crate::principal::Decline::reason)
}
