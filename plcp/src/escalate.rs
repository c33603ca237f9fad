//! Continuing a path in `fx128` where the working precision gave up
//! ([`crate::Settings::escalate`]).
//!
//! When a path in `f32` or `f64` ends `ill_conditioned` (a basis too
//! ill-conditioned for the precision, a nearly singular free block, or the
//! residual guard), the part traced before the trouble is kept and the rest is
//! traced in double-double:
//!
//! 1. the restart point is the start `L_k` of the last segment whose start is
//!    trustworthy: the segment the trouble arose in, or, if a breakpoint's
//!    residual already exceeded `sqrt(eps)`, the segment ending at the first such
//!    breakpoint; every breakpoint kept lies at or before `L_k` and was measured
//!    within `sqrt(eps)`; if `fx128` rejects that segment's basis (singular, or
//!    infeasible inside the segment: the working precision had left the path
//!    before), earlier segments are tried, `1, 2, 4, 8, ...` segments back;
//! 2. the problem is converted to `fx128` (exactly: `f32` and `f64` values are
//!    `fx128` values; the equilibration is recomputed from the same data, so it
//!    is the same), and traced from the middle of segment `k` (not from `L_k`:
//!    a breakpoint rounded to `T` is off by rounding, and its leaving variable
//!    may be slightly negative there in `fx128`) to `lambda_max`, warm-started
//!    from that segment's basis ([`crate::Settings::warm_basis`]: validated
//!    there as nonsingular and feasible); its first segment, extended back to
//!    `L_k` (the same basis, so the same affine solution), replaces segment `k`;
//! 3. the `fx128` segments and breakpoints are rounded to `T` and spliced after
//!    the kept ones; the residuals of the start and end are measured on the
//!    original problem, the breakpoints keep theirs, and the status is the
//!    `fx128` run's.
//!
//! Where a warm start is not possible (no segment traced yet, a path with
//! turning points, or the basis not accepted in `fx128`), the whole path is
//! re-solved in `fx128` from `lambda0` instead; [`Escalation`] says which.

use crate::path::{Breakpoint, Path, Point, Ray, Segment, Status, Var};
use crate::problem::Plcp;
use crate::scalar::Scalar;
use crate::settings::{Method, Settings};
use faer::{fx128, Col};

pub use crate::path::Escalation;

/// The segments tried for a warm restart, from `k0` back: `k0, k0 - 1,
/// k0 - 2, k0 - 4, ...` (doubling steps, at most about `log2(k0) + 2` tries,
/// each one factorisation in `fx128`), the last one `0`.
fn restart_candidates(k0: usize) -> Vec<usize> {
    let mut v = vec![k0];
    let mut step = 1;
    while let Some(k) = k0.checked_sub(step) {
        v.push(k);
        step *= 2;
    }
    if v.last() != Some(&0) {
        v.push(0);
    }
    v
}

fn col_to<U: Scalar, T: Scalar>(c: &Col<U>) -> Col<T> {
    Col::from_fn(c.nrows(), |i| T::from_f64(c[i].to_f64()))
}

/// A value of precision `U` in `T`, rounded through `f64` (`fx128::to_f64`
/// rounds the double-double to the nearest `f64`; the exact tracer's values are
/// `f64` already).
fn val_to<U: Scalar, T: Scalar>(v: U) -> T {
    T::from_f64(v.to_f64())
}

fn point_to<U: Scalar, T: Scalar>(p: &Point<U>) -> Point<T> {
    Point {
        lambda: val_to(p.lambda),
        z: col_to(&p.z),
        w: col_to(&p.w),
        u: col_to(&p.u),
    }
}

/// The one conversion of a continuation's segment to the path's precision
/// `T`: a warm continuation's first segment starts inside segment `k`, on its
/// basis, so extended back to `back_to` (segment `k`'s start) it is segment
/// `k` (the same affine solution).
fn segment_to<U: Scalar, T: Scalar>(s: &Segment<U>, back_to: Option<f64>) -> Segment<T> {
    let mut s = s.clone();
    if let Some(from) = back_to {
        let from = U::from_f64(from);
        let back = from - s.lambda_from;
        for (v, slope) in [
            (&mut s.z_from, &s.dz),
            (&mut s.w_from, &s.dw),
            (&mut s.u_from, &s.du),
        ] {
            for i in 0..v.nrows() {
                v[i] += slope[i] * back;
            }
        }
        s.lambda_from = from;
    }
    Segment {
        lambda_from: val_to(s.lambda_from),
        lambda_to: val_to(s.lambda_to),
        unbounded: s.unbounded,
        basis: s.basis.clone(),
        z_from: col_to(&s.z_from),
        dz: col_to(&s.dz),
        w_from: col_to(&s.w_from),
        dw: col_to(&s.dw),
        u_from: col_to(&s.u_from),
        du: col_to(&s.du),
    }
}

/// Keeps `path.segments[..k]` (and, for a warm continuation from `warm_from`,
/// the breakpoints up to their end), and appends the continuation `rest`
/// (`fx128` or exact) in `T`: segments, breakpoints, the end, ray and status.
fn append_rest<U: Scalar, T: Scalar>(
    path: &mut Path<T>,
    k: usize,
    warm_from: Option<f64>,
    rest: &Path<U>,
) {
    path.segments.truncate(k);
    path.breakpoints
        .retain(|b| warm_from.is_some() && b.segment <= k);
    for (j, s) in rest.segments.iter().enumerate() {
        path.segments
            .push(segment_to(s, warm_from.filter(|_| j == 0)));
    }
    for b in &rest.breakpoints {
        path.breakpoints.push(Breakpoint {
            lambda: val_to(b.lambda),
            entering: b.entering,
            leaving: b.leaving,
            degenerate: b.degenerate,
            turning: b.turning,
            segment: b.segment + k,
            residual: b.residual,
        });
    }
    path.status = rest.status;
    path.lambda_reached = val_to(rest.lambda_reached);
    path.end = point_to(&rest.end);
    path.ray = rest.ray.as_ref().map(|r| Ray {
        start: point_to(&r.start),
        dz: col_to(&r.dz),
        dw: col_to(&r.dw),
        du: col_to(&r.du),
        dlambda: val_to(r.dlambda),
    });
    path.final_basis = rest.final_basis.clone();
}

fn settings_fx128<T: Scalar>(s: &Settings<T>, warm: Option<Vec<Var>>) -> Settings<fx128> {
    Settings {
        method: s.method,
        covering: s.covering.as_ref().map(col_to),
        max_pivots: s.max_pivots,
        pivot_tol_eps: s.pivot_tol_eps,
        tie_tol_eps: s.tie_tol_eps,
        near_ties: s.near_ties,
        refactor_period: s.refactor_period,
        max_cond_eps: s.max_cond_eps,
        refine_tol_eps: s.refine_tol_eps,
        refine_cond_eps: s.refine_cond_eps,
        scaling: s.scaling,
        basis: s.basis,
        warm_basis: warm,
        escalate: false,
        escalate_exact: false,
        threads: s.threads,
        principal: s.principal,
    }
}

/// The segment to restart from: `Some(k)` (keep `segments[..k]`, restart at
/// `segments[k].lambda_from`), or `None` for a re-solve from `lambda0`, with why.
fn restart_segment<T: Scalar>(path: &Path<T>) -> Result<usize, String> {
    if path.segments.is_empty() {
        return Err("no segment was traced in the working precision".into());
    }
    if path.info.turning_points > 0
        || path
            .segments
            .iter()
            .any(|s| !s.unbounded && s.lambda_to < s.lambda_from)
    {
        return Err("the path has turning points".into());
    }
    let limit = T::eps().to_f64().sqrt();
    let mut k = path.segments.len() - 1;
    if let Some(b) = path
        .breakpoints
        .iter()
        .find(|b| b.residual.worst().is_nan() || b.residual.worst() > limit)
    {
        if b.segment == 0 {
            return Err(format!(
                "the first breakpoint's residual {:.1e} exceeds sqrt(eps)",
                b.residual.worst()
            ));
        }
        k = k.min(b.segment - 1);
    }
    Ok(k)
}

/// The basis of `seg` as a warm basis of `p + n` variables: its `z`/`w` per
/// pair and basic `u`, completed by the free variables it lacks (Lemke: the
/// reduction drops them again) or, for Wolfe, by the artificial variables of the
/// dependent rows. `None` if that does not give `p + n` variables.
fn warm_basis_of<T: Scalar>(
    seg: &Segment<T>,
    path: &Path<T>,
    method: Method,
    p: usize,
    n: usize,
) -> Option<Vec<Var>> {
    let mut b = seg.basis.clone();
    let missing_u: Vec<Var> = (0..p).map(Var::U).filter(|v| !b.contains(v)).collect();
    match method {
        Method::Lemke => b.extend(missing_u),
        Method::Wolfe => {
            let need = (p + n).saturating_sub(b.len());
            let dep = &path.info.free_block.dependent_rows;
            if need == dep.len() {
                b.extend(dep.iter().map(|&k| Var::Artificial(k)));
            }
        }
    }
    (b.len() == p + n).then_some(b)
}

/// Whether `path` (in `f32`/`f64`) is continued in `fx128`: it ended
/// `ill_conditioned`, or it claims an end (`reached`, `unbounded_ray`,
/// `secondary_ray`) on a basis whose condition estimate times `eps` exceeded
/// [`crate::tolerance::ESCALATE_COND_EPS`].
pub(crate) fn needs_fx128<T: Scalar>(path: &Path<T>) -> bool {
    if T::NAME == <fx128 as Scalar>::NAME {
        return false;
    }
    match path.status {
        Status::IllConditioned => true,
        Status::Reached | Status::UnboundedRay | Status::SecondaryRay => {
            path.info.max_condition * T::eps().to_f64() > crate::tolerance::ESCALATE_COND_EPS
        }
        _ => false,
    }
}

/// Continues `path` (of `problem`, solved with `settings`) in `fx128`, if
/// [`needs_fx128`] says so. Called by [`crate::solve`] when
/// [`Settings::escalate`] is set; a no-op in `fx128` itself.
pub(crate) fn continue_in_fx128<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
    path: &mut Path<T>,
) {
    if !needs_fx128(path) {
        return;
    }
    let reason = if path.status == Status::IllConditioned {
        format!("{} in {}: {}", path.status.as_str(), T::NAME, path.message)
    } else {
        format!(
            "{} in {} on a basis of condition estimate {:.1e} (cond * eps = {:.1e} > {:.0e}: breakpoints to about that relative error, and a blocking entry below it is lost, which fakes a ray): not trusted without fx128",
            path.status.as_str(),
            T::NAME,
            path.info.max_condition,
            path.info.max_condition * T::eps().to_f64(),
            crate::tolerance::ESCALATE_COND_EPS
        )
    };
    fx128_from(problem, settings, path, restart_segment(path), reason);
}

/// The continuation in `fx128` from segment `start` (tried `1, 2, 4, ...`
/// segments back, see [`restart_candidates`]), or re-solved from `lambda0`
/// if `start` is an `Err` or no candidate is accepted; `reason` says why.
fn fx128_from<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
    path: &mut Path<T>,
    start: Result<usize, String>,
    reason: String,
) {
    let timer = std::time::Instant::now();
    let (p, n) = (problem.free(), problem.n());
    let wide = problem.cast::<fx128>();
    // a warm continuation from segment k, else a whole re-solve
    let mut escalation = Escalation {
        from: T::NAME,
        reason,
        pivots_before: path.info.pivots,
        seconds_before: path.info.solve_seconds,
        ..Escalation::default()
    };
    let attempt = |k: usize, basis: Vec<Var>| -> Result<Path<fx128>, String> {
        let seg = &path.segments[k];
        // inside the segment, not at its start: a breakpoint rounded to T is
        // off by rounding, and its leaving variable may be negative there in fx128
        if seg.lambda_to <= seg.lambda_from || !seg.lambda_to.is_finite() || seg.unbounded {
            return Err(format!("segment {k} has no interior to restart in"));
        }
        let mid = fx128::from_f64(seg.lambda_from.to_f64())
            + (fx128::from_f64(seg.lambda_to.to_f64()) - fx128::from_f64(seg.lambda_from.to_f64()))
                * fx128::from_f64(0.5);
        let from = mid;
        let pr = wide
            .clone()
            .with_range(
                from,
                problem.lambda_max().map(|l| fx128::from_f64(l.to_f64())),
            )
            .map_err(|e| e.to_string())?;
        // a probe first: one pivot at most, so that a rejected basis (whose
        // solve would fall back to a whole cold trace) costs one factorisation
        let mut probe_settings = settings_fx128(settings, Some(basis.clone()));
        probe_settings.max_pivots = Some(1);
        let probe = crate::trace::trace(&pr, &probe_settings).map_err(|e| e.to_string())?;
        if !probe.info.warm_start {
            return Err(format!(
                "fx128 did not accept the basis at L = {:e}: {}",
                from.to_f64(),
                probe.info.warm_start_note
            ));
        }
        let rest = crate::trace::trace(&pr, &settings_fx128(settings, Some(basis)))
            .map_err(|e| e.to_string())?;
        // the basis is feasible at the restart point; it is the path's basis
        // at L_k only if it stays feasible back to L_k (affine: at L_k), else
        // the true path has events between L_k and the restart point, which
        // the splice would lose (the working precision had already missed one
        // inside segment k)
        feasible_back_to::<T>(&rest, fx128::from_f64(seg.lambda_from.to_f64()))?;
        Ok(rest)
    };
    // the segment the trouble arose in may itself start where the working
    // precision already erred (its start is where its basis was first formed):
    // fx128 checks each basis, and a rejected one sends the restart one segment
    // back, a few times at most
    let warm = start.and_then(|k0| {
        let mut why = String::new();
        for k in restart_candidates(k0) {
            let basis = match warm_basis_of(&path.segments[k], path, settings.method, p, n) {
                Some(b) => b,
                None => {
                    why = "the segment's basis does not give one variable per row".into();
                    continue;
                }
            };
            match attempt(k, basis) {
                Ok(rest) => return Ok((k, rest)),
                Err(e) => why = e,
            }
        }
        Err(why)
    });
    let (k, rest) = match warm {
        Ok((k, rest)) => {
            escalation.warm = true;
            (k, rest)
        }
        Err(why) => {
            escalation.note = why;
            match crate::trace::trace(&wide, &settings_fx128(settings, None)) {
                Ok(rest) => (0, rest),
                Err(e) => {
                    path.message = format!(
                        "{} The continuation in f128 could not run: {e}",
                        path.message
                    );
                    return;
                }
            }
        }
    };
    escalation.lambda = if escalation.warm {
        path.segments[k].lambda_from.to_f64()
    } else {
        problem.lambda0().to_f64()
    };
    escalation.kept_segments = k;
    escalation.pivots_fx128 = rest.info.pivots;
    escalation.segment_precisions = path.segments[..k.min(path.segments.len())]
        .iter()
        .map(|_| T::NAME)
        .chain(rest.segments.iter().map(|_| <fx128 as Scalar>::NAME))
        .collect();
    splice(path, k, rest, &mut escalation);
    escalation.seconds_fx128 = timer.elapsed().as_secs_f64();
    path.info.solve_seconds = escalation.seconds_before + escalation.seconds_fx128;
    path.info.escalation = Some(escalation);
}

/// `Ok` if the first segment of `rest`, extended back to `lambda` (its basis,
/// its affine solution), has `z, w >= 0` there, up to what the working
/// precision's breakpoint `lambda` can be off by: a variable negative at
/// `lambda` must reach zero within `sqrt(eps) * max(1, |lambda|, segment)`
/// of it (`eps` of `T`); else an event lies between `lambda` and the restart
/// point, and why is returned.
fn feasible_back_to<T: Scalar>(rest: &Path<fx128>, lambda: fx128) -> Result<(), String> {
    let Some(s) = rest.segments.first() else {
        return Ok(());
    };
    let back = lambda - s.lambda_from;
    let one = fx128::from_f64(1.0);
    let span = one.max(lambda.abs()).max(back.abs()).max(if s.unbounded {
        one
    } else {
        (s.lambda_to - lambda).abs()
    });
    let gap_tol = fx128::from_f64(T::eps().to_f64().sqrt()) * span;
    for (name, from, slope) in [("z", &s.z_from, &s.dz), ("w", &s.w_from, &s.dw)] {
        for i in 0..from.nrows() {
            let v = from[i] + slope[i] * back;
            if v < fx128::from_f64(0.0) && -v > gap_tol * slope[i].abs() {
                return Err(format!(
                    "the restart basis is not the path's at L = {:e}: {name}{i} = {:e} there, zero only at L = {:e} (an event lies between)",
                    lambda.to_f64(),
                    v.to_f64(),
                    (lambda - v / slope[i]).to_f64()
                ));
            }
        }
    }
    Ok(())
}

/// Keeps `path.segments[..k]` and the breakpoints up to their end, and appends
/// `rest` rounded to `T`.
fn splice<T: Scalar>(path: &mut Path<T>, k: usize, rest: Path<fx128>, esc: &mut Escalation) {
    append_rest(path, k, esc.warm.then_some(esc.lambda), &rest);
    let how = if esc.warm {
        format!(
            "continued in f128 from L = {:e} (warm start from the {} basis there, {} segments of {} kept)",
            esc.lambda, esc.from, k, esc.from
        )
    } else {
        format!("re-solved in f128 from L = {:e} ({})", esc.lambda, esc.note)
    };
    let outcome = if rest.status.is_success() {
        format!("the f128 run ended {}", rest.status.as_str())
    } else {
        format!(
            "the f128 run failed too: {}: {}",
            rest.status.as_str(),
            rest.message
        )
    };
    path.message = format!(
        "{how} after {}; {outcome}. {}",
        esc.reason,
        if rest.status.is_success() {
            rest.message.as_str()
        } else {
            ""
        }
    )
    .trim_end()
    .to_string();
    let info = &mut path.info;
    info.pivots += rest.info.pivots;
    info.degenerate_pivots += rest.info.degenerate_pivots;
    info.refactorisations += rest.info.refactorisations;
    info.refinements += rest.info.refinements;
    info.near_ties_resolved += rest.info.near_ties_resolved;
    info.near_ties_unresolved += rest.info.near_ties_unresolved;
    info.turning_points += rest.info.turning_points;
    info.max_condition = info.max_condition.max(rest.info.max_condition);
    if !esc.warm {
        info.start_pivots = rest.info.start_pivots;
        info.warm_start = rest.info.warm_start;
        info.warm_start_note = rest.info.warm_start_note.clone();
        info.free_block = rest.info.free_block.clone();
    }
}

/// The last step of the escalation ([`Settings::escalate_exact`]): a path
/// still `ill_conditioned` (after `fx128`, or in `fx128` itself) is continued
/// in exact rational arithmetic ([`crate::exact::trace_from`]).
///
/// The restart is chosen as for `fx128` ([`restart_segment`], then
/// `1, 2, 4, ...` segments back): the exact tracer starts inside segment `k`
/// on its basis, which it checks exactly (complementary, nonsingular,
/// feasible there), and its first segment must stay feasible back to the
/// segment's start ([`feasible_back_to`]); else the whole path is traced
/// exactly from `lambda0`. The exact segments and breakpoints (rounded to
/// `T`) replace the path from `k` on, and [`Escalation::segment_precisions`]
/// says which precision produced each segment. Problems of order above
/// [`crate::tolerance::ESCALATE_EXACT_MAX_DIM`] are left as they are, with a
/// note.
pub(crate) fn continue_exactly<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
    path: &mut Path<T>,
) {
    if path.status != Status::IllConditioned {
        return;
    }
    exact_from(problem, settings, path, restart_segment(path));
}

/// The exact continuation from segment `start` (tried `1, 2, 4, ...`
/// segments back), or traced exactly from `lambda0` if `start` is an `Err`
/// or no candidate is accepted.
fn exact_from<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
    path: &mut Path<T>,
    start: Result<usize, String>,
) {
    let timer = std::time::Instant::now();
    let mut esc = exact_escalation_of(path);
    let dim = problem.dim();
    if dim > crate::tolerance::ESCALATE_EXACT_MAX_DIM {
        esc.exact_note = format!(
            "not continued exactly: order {dim} exceeds ESCALATE_EXACT_MAX_DIM = {}",
            crate::tolerance::ESCALATE_EXACT_MAX_DIM
        );
        path.info.escalation = Some(esc);
        return;
    }
    let warm = start.and_then(|k0| {
        let mut why = String::new();
        for k in restart_candidates(k0.min(path.segments.len().saturating_sub(1))) {
            match exact_attempt(problem, settings, path, k) {
                Ok(rest) => return Ok((k, rest)),
                Err(e) => why = e,
            }
        }
        Err(why)
    });
    let (k, rest, from) = match warm {
        Ok((k, rest)) => {
            let from = path.segments[k].lambda_from;
            (k, rest, from)
        }
        Err(why) => match crate::exact::trace(problem, settings) {
            Ok(rest) => {
                esc.exact_note = format!("traced exactly from lambda0 ({why})");
                (0, rest, problem.lambda0())
            }
            Err(e) => {
                esc.exact_note = format!("the exact continuation could not run: {e} ({why})");
                path.info.escalation = Some(esc);
                return;
            }
        },
    };
    let warm = from != problem.lambda0() || k > 0;
    splice_exact(problem, path, esc, (k, warm.then_some(from)), &rest);
    path.info.solve_seconds += timer.elapsed().as_secs_f64();
}

/// The path's escalation record for the exact step: the `fx128` one if
/// there was one, else a new one from `T`; one precision per segment.
fn exact_escalation_of<T: Scalar>(path: &mut Path<T>) -> Escalation {
    let mut esc = path.info.escalation.take().unwrap_or_else(|| Escalation {
        from: T::NAME,
        reason: format!("{} in {}: {}", path.status.as_str(), T::NAME, path.message),
        pivots_before: path.info.pivots,
        seconds_before: path.info.solve_seconds,
        ..Escalation::default()
    });
    if esc.segment_precisions.len() != path.segments.len() {
        esc.segment_precisions = vec![T::NAME; path.segments.len()];
    }
    esc
}

/// The exact tracer started inside segment `k` on its basis
/// ([`crate::exact::trace_from`]), if its first segment stays feasible back
/// to segment `k`'s start.
fn exact_attempt<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
    path: &Path<T>,
    k: usize,
) -> Result<crate::exact::ExactPath, String> {
    let seg = &path.segments[k];
    if seg.unbounded || seg.lambda_to <= seg.lambda_from || !seg.lambda_to.is_finite() {
        return Err(format!("segment {k} has no interior to restart in"));
    }
    let basis: Vec<Var> = seg
        .basis
        .iter()
        .copied()
        .filter(|v| matches!(v, Var::Z(_) | Var::W(_) | Var::U(_)))
        .collect();
    let mid = seg.lambda_from + (seg.lambda_to - seg.lambda_from) * T::from_f64(0.5);
    let rest =
        crate::exact::trace_from(problem, settings, &basis, mid).map_err(|e| e.to_string())?;
    exact_feasible_back(seg, &rest.path, k)?;
    Ok(rest)
}

/// The same check as for fx128 ([`feasible_back_to`]): no event between
/// segment `k`'s start and the exact restart inside it.
fn exact_feasible_back<T: Scalar>(
    seg: &Segment<T>,
    rest: &Path<f64>,
    k: usize,
) -> Result<(), String> {
    let Some(s) = rest.segments.first() else {
        return Ok(());
    };
    let back = seg.lambda_from.to_f64() - s.lambda_from;
    let span = 1f64
        .max(seg.lambda_from.to_f64().abs())
        .max(back.abs())
        .max(if s.unbounded {
            1.0
        } else {
            (s.lambda_to - s.lambda_from).abs()
        });
    let gap = T::eps().to_f64().sqrt() * span;
    for (from, slope) in [(&s.z_from, &s.dz), (&s.w_from, &s.dw)] {
        for i in 0..from.nrows() {
            let v = from[i] + slope[i] * back;
            if v < 0.0 && -v > gap * slope[i].abs() {
                return Err(format!(
                    "the basis of segment {k} is not the path's at L = {:e} (an event lies between)",
                    seg.lambda_from.to_f64()
                ));
            }
        }
    }
    Ok(())
}

/// Keeps `path.segments[..k]` and appends the exact `rest` (from `from`
/// for a warm continuation, `None`: from `lambda0`), rounded once to `T`;
/// the message, counts and escalation record say so.
fn splice_exact<T: Scalar>(
    problem: &Plcp<T>,
    path: &mut Path<T>,
    mut esc: Escalation,
    (k, warm_from): (usize, Option<T>),
    rest: &crate::exact::ExactPath,
) {
    let from = warm_from.unwrap_or(problem.lambda0());
    esc.exact = true;
    esc.lambda_exact = from.to_f64();
    esc.segment_precisions.truncate(k);
    esc.segment_precisions
        .extend(rest.path.segments.iter().map(|_| "exact"));
    append_rest(path, k, warm_from.map(|l| l.to_f64()), &rest.path);
    exact_tail_in::<T>(path, k, warm_from, rest, problem.free());
    let r = &rest.path;
    path.message = format!(
        "continued in exact arithmetic from L = {:e} ({} segments kept) after {}: the exact run ended {}. {}",
        from.to_f64(),
        k,
        path.message.trim_end_matches('.'),
        r.status.as_str(),
        r.message
    )
    .trim_end()
    .to_string();
    path.info.pivots += r.info.pivots;
    path.info.turning_points += r.info.turning_points;
    path.info.escalation = Some(esc);
}

/// Rounds the exact tail appended from segment `k` on (by [`append_rest`],
/// through `f64`) once from its exact values to `T`: segments (the first
/// extended back to `back_to` exactly), breakpoints, and the end of a path
/// that reached `L_max` or ends on a ray. In `f64` this changes nothing; in
/// `fx128` the tail through `f64` carried `f64`'s rounding (residual `5e-11`
/// where the segment was extended back), which fx128's residual guard
/// rejects.
fn exact_tail_in<T: Scalar>(
    path: &mut Path<T>,
    k: usize,
    back_to: Option<T>,
    rest: &crate::exact::ExactPath,
    p: usize,
) {
    let to_t = crate::exact::rational_to::<T>;
    let n = path.end.z.nrows();
    for (j, es) in rest.exact_segments.iter().enumerate() {
        let Some(seg) = path.segments.get_mut(k + j) else {
            break;
        };
        let from = match back_to.filter(|_| j == 0) {
            Some(l) => crate::exact::to_rational(l),
            None => es.from.clone(),
        };
        let [u, z, w] = es.at::<T>(&from, p, n);
        let [du, dz, dw] = es.slopes::<T>(p, n);
        seg.lambda_from = to_t(&from);
        if let Some(to) = &es.to {
            seg.lambda_to = to_t(to);
        }
        (seg.u_from, seg.z_from, seg.w_from) = (u, z, w);
        (seg.du, seg.dz, seg.dw) = (du, dz, dw);
    }
    let nb = rest.breakpoints.len();
    let first = path.breakpoints.len().saturating_sub(nb);
    for (b, e) in path.breakpoints[first..].iter_mut().zip(&rest.breakpoints) {
        b.lambda = to_t(e);
    }
    let ends = matches!(rest.path.status, Status::Reached | Status::UnboundedRay);
    if let (true, Some(last)) = (ends, rest.exact_segments.last()) {
        let l = &rest.lambda_reached;
        let [u, z, w] = last.at::<T>(l, p, n);
        path.end = Point {
            lambda: to_t(l),
            z,
            w,
            u,
        };
        if rest.path.status == Status::Reached {
            path.lambda_reached = to_t(l);
        }
    }
}

/// The precision that produced segment `k` of `path` (its escalation record,
/// else the working precision).
fn segment_precision<T: Scalar>(path: &Path<T>, k: usize) -> &'static str {
    path.info
        .escalation
        .as_ref()
        .and_then(|e| e.segment_precisions.get(k).copied())
        .unwrap_or(T::NAME)
}

/// Certifies `path` ([`crate::exact::certify`]) and, with
/// [`Settings::escalate`], lets the certificate drive the escalation: a
/// segment it rejects that `T` produced is traced again in `fx128`, one that
/// `fx128` produced (with [`Settings::escalate_exact`]) exactly, each warm
/// from the certified segment before it (tried `1, 2, 4, ...` segments back,
/// else from `lambda0`), and the new path is certified again. Returns the last
/// certificate.
///
/// Why: a float path can be wrong while nothing in it looks ill-conditioned.
/// Two events within the tie window (`1e3 eps`) that are not an exact tie are
/// taken in the lexicographic rule's order, which may be the wrong one: the
/// block `[[1, 1], [1, 1 + 2^-46]]` with `q = (1.5, 1.5 + 2.5 2^-46)`, `d =
/// (-1, -(1 + 2^-46))` has `w_1` reach zero `1.4e-14` before `w_2`; f64
/// enters `z_2` first, and its path (`z_1 = 0` for ever, where exactly
/// `z_1 = 1` from `L = 2.5`) has a residual of `1.4e-14` on bases of condition
/// `5e8`: `reached`, and only the certificate sees it
/// (`plcp/tests/escalate.rs`).
pub(crate) fn certify_escalating<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
    path: &mut Path<T>,
) -> crate::exact::Certificate {
    let mut cert = crate::exact::certify(problem, path);
    if !settings.escalate {
        return cert;
    }
    let both_ends = settings.method == Method::Lemke && problem.free() > 0;
    // at most one step per precision above T, and one spare: a step that
    // does not change who produced the failing segment ends the loop
    for _ in 0..3 {
        let Some(fail) = cert.failure.clone() else {
            break;
        };
        let k = fail.segment.min(path.segments.len().saturating_sub(1));
        let produced = segment_precision(path, k);
        let why = format!(
            "exact certification rejected segment {} ({produced}): {}",
            fail.segment, fail.reason
        );
        // the segments before k are certified: restart in the one before it
        // (no warm restart on a path with turning points, nor past a
        // breakpoint whose residual exceeded sqrt(eps): [`restart_segment`])
        let start = restart_segment(path).and_then(|k0| match k {
            0 => Err(format!("{why}; no certified segment before it")),
            _ => Ok((k - 1).min(k0)),
        });
        if produced == T::NAME && T::NAME != <fx128 as Scalar>::NAME {
            let reason = format!("{} in {}: {why}", path.status.as_str(), T::NAME);
            fx128_from(problem, settings, path, start, reason);
            trace_measure(problem, path, both_ends);
            if settings.escalate_exact && path.status == Status::IllConditioned {
                continue_exactly(problem, settings, path);
                trace_measure(problem, path, both_ends);
            }
        } else if produced != "exact" && settings.escalate_exact {
            path.message = format!("{why}. {}", path.message);
            exact_from(problem, settings, path, start);
            trace_measure(problem, path, both_ends);
        } else {
            break;
        }
        cert = crate::exact::certify(problem, path);
    }
    cert
}

/// The spliced path's start and end measured on the original problem and
/// the residual guard, as [`crate::solve`] does after a continuation.
fn trace_measure<T: Scalar>(problem: &Plcp<T>, path: &mut Path<T>, both_ends: bool) {
    crate::trace::measure(problem, path, both_ends);
    crate::trace::guard_residual(path);
}
