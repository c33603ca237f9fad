//! The checks of one segment (complementary basis, feasible start, exact
//! end, float values) and of the path's end.

use super::super::solution::Solution;
use super::super::tableau::col_of;
use super::super::{rational_to_f64, rel_diff, short, to_rational};
use super::bases::Bases;
use super::bridge::bridge_to;
use super::interval::{interval, value_at, within};
use super::ray::{direct, Verdict};
use super::{fail, Certificate, Chain, Failure};
use crate::path::{Path, Status, Var};
use crate::scalar::Scalar;
use num_rational::BigRational;
use num_traits::{Signed, Zero};

/// A path without segments claims a solution at `L0` only: certify the
/// basis of its end point (`z_i` basic where `z_i > w_i`).
pub(super) fn end_point<T: Scalar>(
    path: &Path<T>,
    bases: &mut Bases<'_, T>,
    start: &BigRational,
    cert: &mut Certificate,
) -> Result<(), Failure> {
    if !path.status.is_success() {
        return Ok(());
    }
    let (p, n) = (bases.problem.free(), bases.problem.n());
    let basis: Vec<usize> = (0..n)
        .map(|i| {
            let v = if path.end.z[i] > path.end.w[i] {
                Var::Z(i)
            } else {
                Var::W(i)
            };
            col_of(p, n, v).expect("a pair")
        })
        .chain(0..p)
        .collect();
    let (lo, hi) = interval(&bases.tableau_at(&basis, cert)).map_err(|r| fail(0, r))?;
    if lo.as_ref().is_some_and(|l| l > start) || hi.as_ref().is_some_and(|h| h < start) {
        return Err(fail(
            0,
            format!(
                "the end point's basis is infeasible at L0 = {}",
                short(start)
            ),
        ));
    }
    Ok(())
}

/// The columns of segment `k`'s basis, checked complementary (1.): Lemke on
/// the Schur reduction lists `z` and `w` only (every `u` basic); Wolfe's long
/// form lists the basic `u` (the others held at zero, their dependent rows
/// kept by artificial variables).
fn segment_target(basis: &[Var], p: usize, n: usize, k: usize) -> Result<Vec<usize>, Failure> {
    let mut seen = vec![0u8; n];
    for v in basis {
        match *v {
            Var::Z(i) | Var::W(i) if i < n => seen[i] += 1,
            Var::U(j) if j < p => {}
            other => return Err(fail(k, format!("{other} cannot be in a segment's basis"))),
        }
    }
    if let Some(i) = seen.iter().position(|&s| s != 1) {
        return Err(fail(
            k,
            format!(
                "the basis is not complementary: pair {i} appears {} times",
                seen[i]
            ),
        ));
    }
    let all_u = !basis.iter().any(|v| matches!(v, Var::U(_)));
    Ok(basis
        .iter()
        .map(|v| col_of(p, n, *v).expect("checked"))
        .chain((0..p).filter(|_| all_u))
        .collect())
}

/// Certifies segment `k` and moves `chain` to its exact end.
pub(super) fn segment<T: Scalar>(
    path: &Path<T>,
    k: usize,
    bases: &mut Bases<'_, T>,
    chain: &mut Chain,
    u_unique: bool,
    cert: &mut Certificate,
) -> Result<(), Failure> {
    let (p, n) = (bases.problem.free(), bases.problem.n());
    let seg = &path.segments[k];
    let target = segment_target(&seg.basis, p, n, k)?;
    let t = bases.solve(&target, cert);
    // 2. feasible where it starts, directly or across a bridge of exact
    // bases from the previous segment's
    let (lo, hi) = interval(&t).map_err(|r| fail(k, r))?;
    let up = seg.lambda_to >= seg.lambda_from;
    bridge_to(bases, chain, &target, (&lo, &hi), up, cert);
    let start_k = chain.start.clone();
    check_start(&t, (&lo, &hi), chain, k, cert)?;
    // 3. where it ends
    let end = segment_end(path, k, (&lo, &hi), &chain.start)?;
    if let Some(e) = &end {
        check_breakpoint(path, k, &t, e, chain, cert)?;
    }
    // the float values at both ends (slopes for an unbounded segment)
    let limit = T::eps().to_f64().sqrt();
    check_values(&t, seg, &start_k, end.as_ref(), u_unique, limit).map_err(|r| fail(k, r))?;
    cert.segments += 1;
    chain.prev_target = Some(target);
    chain.last = Some(t);
    Ok(())
}

/// The basis is feasible where the segment starts (2.); a pending
/// reordered breakpoint is resolved by that, or is the failure.
fn check_start(
    t: &Solution,
    (lo, hi): (&Option<BigRational>, &Option<BigRational>),
    chain: &mut Chain,
    k: usize,
    cert: &mut Certificate,
) -> Result<(), Failure> {
    let start = &chain.start;
    let below = lo.as_ref().is_some_and(|l| l > start);
    let above = hi.as_ref().is_some_and(|h| h < start);
    if let Some(f) = chain.pending.take() {
        if below || above {
            return Err(f);
        }
        cert.reordered += 1;
    }
    if !(below || above) {
        return Ok(());
    }
    let bad = (0..t.basis.len())
        .filter(|&i| t.signed(t.basis[i]))
        .find(|&i| {
            let (a, b) = t.affine(i);
            (a + b * start).is_negative()
        })
        .and_then(|i| t.var_of(t.basis[i]))
        .map_or(String::new(), |v| {
            format!(" ({v} = {} there)", short(&value_at(t, v, start).reduced()))
        });
    Err(fail(
        k,
        format!(
            "the basis is infeasible where the segment starts, L = {}{bad}; it is feasible on [{}, {}]",
            short(start),
            lo.as_ref().map_or("-inf".into(), short),
            hi.as_ref().map_or("inf".into(), short)
        ),
    ))
}

/// The exact end of segment `k` (3.): `None` for an unbounded ray, `L_max`
/// for the last segment of a `reached` path, else where its interval ends
/// in its direction (where a stopped path stopped, if it does not end).
fn segment_end<T: Scalar>(
    path: &Path<T>,
    k: usize,
    (lo, hi): (&Option<BigRational>, &Option<BigRational>),
    start: &BigRational,
) -> Result<Option<BigRational>, Failure> {
    let seg = &path.segments[k];
    let last = k + 1 == path.segments.len();
    let up = seg.lambda_to >= seg.lambda_from;
    let lambda_max = path.lambda_max.map(to_rational);
    if seg.unbounded {
        if let Some(h) = hi {
            return Err(fail(
                k,
                format!("claimed to hold for every larger L, but a basic variable reaches zero at L = {}", short(h)),
            ));
        }
        return Ok(None);
    }
    if let Some(lm) = lambda_max.filter(|_| last && path.status == Status::Reached) {
        if hi.as_ref().is_some_and(|h| h < &lm) {
            return Err(fail(
                k,
                format!(
                    "the path claims L_max = {} reached, but a basic variable reaches zero at L = {} before",
                    short(&lm),
                    short(hi.as_ref().expect("checked"))
                ),
            ));
        }
        return Ok(Some(lm));
    }
    let exact = if up { hi.clone() } else { lo.clone() };
    match exact {
        Some(e) => Ok(Some(e)),
        // the path stopped here for another reason (pivot limit,
        // ill-conditioning): certify up to where it stopped
        None if last && !path.status.is_success() => Ok(Some(to_rational(seg.lambda_to))),
        None => Err(fail(
            k,
            format!(
                "no basic variable reaches zero as L {} from {}: the breakpoint at L = {:e} does not exist exactly",
                if up { "rises" } else { "falls" },
                short(start),
                seg.lambda_to.to_f64()
            ),
        )),
    }
}

/// At the exact end `e` of segment `k`: the breakpoint's leaving variable
/// is zero there (or the failure is pending, to be resolved by the next
/// segment), and the float breakpoint is the exact one to `sqrt(eps)`;
/// records the end and moves the chain's start there.
fn check_breakpoint<T: Scalar>(
    path: &Path<T>,
    k: usize,
    t: &Solution,
    e: &BigRational,
    chain: &mut Chain,
    cert: &mut Certificate,
) -> Result<(), Failure> {
    let seg = &path.segments[k];
    let last = k + 1 == path.segments.len();
    let end_float = seg.lambda_to.to_f64();
    let limit = T::eps().to_f64().sqrt();
    if let Some(bp) = path.breakpoints.iter().find(|b| b.segment == k + 1) {
        let lv = bp.leaving;
        let in_basis = t.col_of(lv).is_some_and(|c| t.is_basic(c));
        if matches!(lv, Var::Z(_) | Var::W(_)) && in_basis {
            let v = value_at(t, lv, e);
            if !v.is_zero() {
                let f = fail(
                    k,
                    format!(
                        "the breakpoint's leaving variable {lv} is {} at the segment's exact end L = {}, not zero (the float breakpoint is L = {:e})",
                        short(&v.reduced()),
                        short(e),
                        bp.lambda.to_f64()
                    ),
                );
                // another variable reaches zero first, exactly: the
                // float path took the two events in the other order.
                // Right to rounding if the next segment is reached
                // from here (directly or by a bridge)
                if last {
                    return Err(f);
                }
                chain.pending = Some(f);
            }
        }
    }
    // the float breakpoint must be the exact one up to the working
    // precision's trust level (sqrt(eps), as the residual guard); so must
    // the `L*` of a `secondary_ray` (the path claims no solution beyond it).
    // A path that stopped for another reason (pivot limit, ill-conditioning,
    // an observer) may stop inside its last segment: it is certified up to
    // where it stopped, and its float end is not a breakpoint
    let diff = rel_diff(end_float, e, &chain.start);
    let claims_end = path.status.is_success() || path.status == Status::SecondaryRay;
    if !within(diff, limit) && (!last || claims_end) {
        return Err(fail(
            k,
            format!(
                "the segment ends exactly at L = {}, but the path puts its breakpoint at L = {end_float:e} (relative difference {diff:.1e} > sqrt(eps) = {limit:.1e} in {})",
                short(e),
                T::NAME
            ),
        ));
    }
    cert.max_rel_diff = cert.max_rel_diff.max(diff);
    cert.breakpoints.push(e.clone());
    chain.start = e.clone();
    Ok(())
}

/// The end the status claims: an unbounded last segment for
/// `unbounded_ray`, `L_max` for `reached`.
pub(super) fn path_end<T: Scalar>(path: &Path<T>, start: &BigRational) -> Result<(), Failure> {
    let nseg = path.segments.len();
    let last = path.segments.last().expect("nseg > 0");
    if path.status == Status::UnboundedRay && !last.unbounded {
        return Err(fail(
            nseg,
            "status unbounded_ray, but the last segment is not unbounded".into(),
        ));
    }
    if path.status == Status::Reached {
        if let Some(lm) = path.lambda_max.map(to_rational) {
            if start != &lm {
                return Err(fail(
                    nseg,
                    format!(
                        "status reached, but the path ends at L = {} before L_max = {}",
                        short(start),
                        short(&lm)
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// A named group of variables: name, first column, count, values, slopes.
type Group<'a, T> = (&'a str, usize, usize, &'a faer::Col<T>, &'a faer::Col<T>);

/// Compares the float values of segment `seg` with the exact ones of the
/// basis in `t`, at the exact start and end (the slopes for an unbounded
/// segment), relative to the largest entry of each vector.
fn check_values<T: Scalar>(
    t: &Solution,
    seg: &crate::path::Segment<T>,
    start: &BigRational,
    end: Option<&BigRational>,
    u_unique: bool,
    limit: f64,
) -> Result<(), String> {
    let (p, n) = (t.p, t.n);
    let from = to_rational(seg.lambda_from);
    let groups: [Group<'_, T>; 3] = [
        ("z", p, n, &seg.z_from, &seg.dz),
        ("w", p + n, n, &seg.w_from, &seg.dw),
        ("u", 0, if u_unique { p } else { 0 }, &seg.u_from, &seg.du),
    ];
    let mut at = vec![start.clone()];
    if let Some(e) = end {
        at.push(e.clone());
    }
    // the exact values of each group at each end, rounded once
    let exact: Vec<Vec<Vec<f64>>> = groups
        .iter()
        .map(|&(_, c0, len, _, _)| {
            at.iter()
                .map(|l| {
                    (0..len)
                        .map(|i| rational_to_f64(&t.value(c0 + i, l)))
                        .collect()
                })
                .collect()
        })
        .collect();
    // one scale for the whole segment: its largest exact value at either end,
    // or slope times max(1, |L|), over z, w and u (a vector that is zero at
    // one end, as at a degenerate start, is measured against the rest)
    let mut scale = 0.0f64;
    for ((_, _, len, _, dx), ex) in groups.iter().zip(&exact) {
        for (l, ex) in at.iter().zip(ex) {
            let lf = rational_to_f64(l).abs().max(1.0);
            for i in 0..*len {
                scale = scale.max(ex[i].abs()).max(dx[i].to_f64().abs() * lf);
            }
        }
    }
    if scale == 0.0 || !scale.is_finite() {
        return Ok(());
    }
    for ((name, c0, len, x_from, dx), ex) in groups.into_iter().zip(&exact) {
        for (l, exact) in at.iter().zip(ex) {
            // the float value at the exact L, from the segment's affine form
            let dl = rational_to_f64(&(l - &from));
            let float: Vec<f64> = (0..len)
                .map(|i| x_from[i].to_f64() + dx[i].to_f64() * dl)
                .collect();
            let (i, err) = (0..len)
                .map(|i| (i, (exact[i] - float[i]).abs() / scale))
                .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
            if !within(err, limit) {
                return Err(format!(
                    "the float {name}{i} = {:e} at L = {} differs from the exact {:e} by {err:.1e} of the solution's scale {scale:.1e} (> sqrt(eps) = {limit:.1e})",
                    float[i],
                    short(l),
                    exact[i]
                ));
            }
        }
        if end.is_none() && seg.unbounded {
            // the slopes (the ray's direction)
            let exact: Vec<f64> = (0..len)
                .map(|i| rational_to_f64(&t.slope(c0 + i)))
                .collect();
            for i in 0..len {
                let err = (exact[i] - dx[i].to_f64()).abs() / scale;
                if !within(err, limit) {
                    return Err(format!(
                        "the float slope d{name}{i}/dL = {:e} of the unbounded segment differs from the exact {:e}",
                        dx[i].to_f64(),
                        exact[i]
                    ));
                }
            }
        }
    }
    Ok(())
}

/// A `secondary_ray` status claims that the path cannot go on beyond where
/// it ended, `L*`. Proven directly ([`super::ray::direct`]: the exact pivots
/// at `L*` from the last segment's basis and the exact ray, each basis
/// solved by p-adic lifting, at any order); where that is undecided (a tie
/// at `L*`, a Wolfe basis with free variables held at zero, a singular
/// basis) or there is no segment, by continuing the path exactly
/// ([`crate::exact::trace_from`]) from inside the last segment (or from `L0`
/// without segments), which must end on a secondary ray at the same exact
/// `L` (order at most [`crate::exact::EXACT_MAX_DIM`], a free block of full
/// rank; else the claim is not proven). A direct certificate that shows the
/// path going on (an unbounded ray, a block while `L` moves) rejects the
/// claim at once. An f32 path whose last rate of `L` was hidden by the
/// basis's noise claimed a secondary ray where the exact path is an
/// unbounded ray, and the segments alone certified it.
pub(super) fn secondary_ray_end<T: Scalar>(
    problem: &crate::problem::Plcp<T>,
    path: &Path<T>,
    bases: &Bases<'_, T>,
    chain: &Chain,
    cert: &mut Certificate,
) -> Result<(), Failure> {
    if path.status != Status::SecondaryRay {
        return Ok(());
    }
    let nseg = path.segments.len();
    let end = &chain.start;
    // enough pivots for the degenerate pivots of the last breakpoint and one
    // more event beyond it: more means the claim is already wrong
    let max_pivots = 2 * problem.dim() + 16;
    let undecided = match (path.segments.last(), chain.last.as_ref()) {
        (Some(_), Some(last)) => match direct(path, bases, last, end, max_pivots) {
            Ok(proven) => {
                cert.secondary_ray = Some(format!(
                    "direct: {} exact pivots at L* = {}, then the column of {} blocks nothing and L {} along it",
                    proven.pivots,
                    short(end),
                    proven.driver,
                    if proven.rate.is_zero() {
                        "stays".to_string()
                    } else {
                        format!("falls at rate {}", short(&proven.rate))
                    }
                ));
                return Ok(());
            }
            // the ray the claim names does not exist at L*; the exact tracer
            // may still end there by another rule (a closed loop through L0
            // is reported as a secondary ray: `tests/stiff.rs` "huge #9"), so
            // where it applies it decides, and the claim stands only if it
            // ends the same way at the same L
            Err(Verdict::Wrong(why)) => {
                let wrong = fail(
                    nseg,
                    format!(
                        "status secondary_ray at L = {}, but the exact continuation from the last segment's basis {why}",
                        short(end)
                    ),
                );
                return match continuation(problem, path, end, max_pivots) {
                    Ok(()) => {
                        cert.secondary_ray = Some(format!(
                            "exact continuation: the exact tracer ends at L = {} as the path says (the direct certificate finds no ray there: {why})",
                            short(end)
                        ));
                        Ok(())
                    }
                    Err(_) => Err(wrong),
                };
            }
            Err(Verdict::Undecided(why)) => Some(why),
        },
        _ => None,
    };
    match continuation(problem, path, end, max_pivots) {
        Ok(()) => {
            cert.secondary_ray = Some(format!(
                "exact continuation: the exact tracer ends on a secondary ray at L = {}{}",
                short(end),
                undecided
                    .as_ref()
                    .map_or(String::new(), |w| format!(" (the direct certificate: {w})"))
            ));
            Ok(())
        }
        Err(f) => Err(match undecided {
            Some(why) => fail(
                nseg,
                format!(
                    "status secondary_ray at L = {}, not proven by the direct certificate ({why}); {}",
                    short(end),
                    f.reason
                ),
            ),
            None => f,
        }),
    }
}

/// The exact tracer continues the path from inside its last segment (from
/// `L0` without segments) and must end on a secondary ray at `end`.
fn continuation<T: Scalar>(
    problem: &crate::problem::Plcp<T>,
    path: &Path<T>,
    end: &BigRational,
    max_pivots: usize,
) -> Result<(), Failure> {
    let nseg = path.segments.len();
    let settings = crate::settings::Settings::<T> {
        max_pivots: Some(max_pivots),
        ..Default::default()
    };
    let exact = match path.segments.last() {
        Some(seg) => {
            if seg.lambda_to < seg.lambda_from {
                return Err(fail(
                    nseg,
                    "status secondary_ray after a falling segment: not checked exactly".into(),
                ));
            }
            let two = T::one() + T::one();
            let mid = seg.lambda_from + (seg.lambda_to - seg.lambda_from) / two;
            crate::exact::trace_from(problem, &settings, &seg.basis, mid)
        }
        None => crate::exact::trace(problem, &settings),
    };
    let exact = exact.map_err(|e| {
        fail(
            nseg,
            format!(
                "status secondary_ray, not checked exactly: the exact continuation fails ({e})"
            ),
        )
    })?;
    if exact.path.status != Status::SecondaryRay || &exact.lambda_reached != end {
        let at = if exact.path.status == Status::UnboundedRay {
            "as L rises to infinity".to_string()
        } else {
            format!("at L = {}", short(&exact.lambda_reached))
        };
        return Err(fail(
            nseg,
            format!(
                "status secondary_ray at L = {}, but the exact continuation from the last segment's basis ends {} {at}, with {} breakpoints from inside the last segment",
                short(end),
                exact.path.status.as_str(),
                exact.breakpoints.len()
            ),
        ));
    }
    Ok(())
}
