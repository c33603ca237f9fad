//! The phases around the trace: the start phase (Lemke's method with an
//! artificial variable and a covering vector, or a warm basis), then the trace,
//! and the assembly of the [`crate::path::Path`] from how it ended.

use super::*;
use crate::settings::Method;

/// Why the start phase failed.
pub(crate) struct StartFailure {
    pub status: crate::path::Status,
    pub message: String,
}

/// The start phase: after the basis `eng` holds (all `w` basic, free variables as
/// far as the rank allows), find a complementary basis feasible at `lambda0` by
/// Lemke's method with an artificial variable and covering vector `c`.
///
/// Lemke's method is itself a parametric path: with `a = max_i (-x_i / c_i)` the
/// system `q + lambda0 d + (a - s) c` is trivially solved at `s = 0`, and `s = a`
/// gives back the problem at `lambda0`. The artificial variable is `z0 = a - s`;
/// "`z0` leaves the basis" is "`s` reaches `a`", which wins every tie.
pub(crate) fn start_phase<T: Scalar>(
    eng: &mut Engine<'_, T>,
    q: &Col<T>,
    d: &Col<T>,
    lambda0: T,
    covering: Option<&Col<T>>,
) -> Result<(), StartFailure> {
    use crate::path::Status;
    let (p, n) = (eng.p, eng.n);
    let dim = p + n;
    // equality rows left to artificial variables must hold already
    // relative to the data alone (no floor at one: q may be tiny)
    let mut scale = T::zero();
    for r in 0..dim {
        scale = scale.max(q[r].abs()).max((lambda0 * d[r]).abs());
    }
    if scale == T::zero() {
        scale = T::one();
    }
    // the covering vector in the units of the right-hand side: only its
    // direction matters (a factor rescales the artificial variable), so it is
    // brought by a power of two (exactly) to within a factor of two of
    // max |q + L0 d|. The artificial variable's start value `a` (and the
    // parameter of the start phase's trace) is then dimensionless, of the
    // order of one for any scale of the data, and the trace's tolerances
    // (floors of one) act on it as on `L`; a uniform scaling of the data by
    // `2^k` leaves the start phase's arithmetic unchanged but for the factor
    let cmax = (0..n).fold(T::zero(), |m, i| {
        m.max(covering.map_or(T::one(), |c| c[i]).abs())
    });
    let cunit = T::from_f64(crate::scaling::exp2i(
        crate::scaling::exponent(scale.to_f64()) - crate::scaling::exponent(cmax.to_f64()),
    ));
    // (`solve_lcp` traces the equilibrated problem: unscaled, this power of
    // two let Siconos enum_fails in f32 trace to `reached` with error 1.04)
    let cunit = if SCALE_COVERING { cunit } else { T::one() };
    let c = |i: usize| covering.map_or(T::one(), |c| c[i]) * cunit;
    let tol = eng.tie_tol_value() * scale * T::from_f64(dim.max(1) as f64);
    // equality rows left to artificial variables (fixed at zero) that do not hold
    // at the start: their residual h is removed from the right-hand side at s = 0
    // and brought back as s rises, so the path must find variables that satisfy them
    let mut h = Col::<T>::zeros(dim);
    let mut repair = false;
    for r in 0..dim {
        if let Var::Artificial(k) = eng.basis[r] {
            if eng.x[r].abs() > tol {
                h[k] = -eng.x[r];
                repair = true;
            }
        }
    }
    let mut a = T::zero();
    for r in 0..dim {
        if let Var::W(i) = eng.basis[r] {
            let need = -eng.x[r] / c(i);
            if eng.x[r] < -tol && need > a {
                a = need;
            }
        }
    }
    if a == T::zero() && !repair {
        return Ok(());
    }
    if a == T::zero() {
        a = T::one();
    }
    let mut qa = Col::zeros(dim);
    let mut da = Col::zeros(dim);
    for r in 0..dim {
        qa[r] = q[r] + lambda0 * d[r] + h[r];
        da[r] = -h[r] / a;
    }
    // the covering vector acts on the rows whose slack is basic: B^{-1} (c on
    // those rows) = c on those slacks exactly, even where free variables have
    // taken other complementary rows
    for i in 0..n {
        if eng.row_of(Var::W(i)).is_some() {
            qa[p + i] += a * c(i);
            da[p + i] -= c(i);
        }
    }
    let ill = |m: String| StartFailure {
        status: Status::IllConditioned,
        message: m,
    };
    eng.reset_system(qa, da, T::zero()).map_err(ill)?;
    match eng.trace(Some(a), None) {
        TraceEnd::Reached { driver, theta } => {
            eng.settle(driver, theta).map_err(ill)?;
            if eng.trace_pivots {
                eprintln!(
                    "start phase end: basis {:?} x {:?}",
                    eng.basis,
                    (0..dim).map(|r| eng.x[r].to_f64()).collect::<Vec<_>>()
                );
            }
            eng.reset_system(q.clone(), d.clone(), lambda0)
                .map_err(ill)?;
            if eng.trace_pivots {
                eprintln!(
                    "after reset: x {:?}",
                    (0..dim).map(|r| eng.x[r].to_f64()).collect::<Vec<_>>()
                );
            }
            Ok(())
        }
        TraceEnd::SecondaryRay { driver, col, .. } | TraceEnd::UnboundedRay { driver, col, .. } => {
            Err(ray_evidence(eng, q, d, lambda0, driver, &col))
        }
        TraceEnd::Stalled(m) => Err(StartFailure {
            status: Status::Infeasible,
            message: m,
        }),
        TraceEnd::PivotLimit => Err(StartFailure {
            status: Status::PivotLimit,
            message: format!(
                "pivot limit ({}) reached in the start phase at L = {:e}",
                eng.max_pivots,
                lambda0.to_f64()
            ),
        }),
        TraceEnd::IllConditioned(m) => Err(ill(m)),
    }
}

/// What the start phase's ray at `lambda0` proves ([`crate::evidence`]):
/// `infeasible` with the certificate when its direction is a Farkas
/// certificate; `ill_conditioned` when `M`'s symmetric part is positive
/// definite (a P-matrix: a solution exists, the ray is rounding's doing);
/// otherwise `infeasible` saying that no solution was found and that this is
/// not a proof that none exists.
fn ray_evidence<T: Scalar>(
    eng: &Engine<'_, T>,
    q: &Col<T>,
    d: &Col<T>,
    lambda0: T,
    driver: Var,
    col: &Col<T>,
) -> StartFailure {
    use crate::path::Status;
    let (p, n) = (eng.p, eng.n);
    let at = lambda0.to_f64();
    let head = format!(
        "Lemke's method with the covering vector ended on a secondary ray at L = {at:e}: no solution was found at the start value"
    );
    if p > 0 {
        return StartFailure {
            status: Status::Infeasible,
            message: format!(
                "{head}; with free variables no certificate is checked, so this does not prove that none exists"
            ),
        };
    }
    // the ray's z part: the driver rises by one, basic variables by -col
    let mut v = Col::<T>::zeros(n);
    for (r, b) in eng.basis.iter().enumerate() {
        if let Var::Z(i) = *b {
            v[i] = -col[r];
        }
    }
    if let Var::Z(i) = driver {
        v[i] = T::one();
    }
    let r = Col::from_fn(n, |i| q[i] + lambda0 * d[i]);
    if let Some(why) = crate::evidence::farkas(eng.m, &r, &v) {
        return StartFailure {
            status: Status::Infeasible,
            message: format!("{head}; {why}"),
        };
    }
    if crate::evidence::symmetric_part_positive_definite(eng.m) {
        return StartFailure {
            status: Status::IllConditioned,
            message: format!(
                "{head}, which cannot happen for this M in exact arithmetic: its symmetric part is positive definite, so M is a P-matrix and a solution exists; the ray is an artefact of rounding in {}: use a higher precision",
                T::NAME
            ),
        };
    }
    StartFailure {
        status: Status::Infeasible,
        message: format!(
            "{head}; this does not prove that none exists: the ray's direction is no certificate of infeasibility (v >= 0, M'v <= 0, (q + L0 d)'v < 0 fails), and M's class is not known (a copositive-plus M would give one)"
        ),
    }
}

/// Traces the whole path: start phase at `lambda0`, then `L` rising to `lambda_max`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn run_path<T: Scalar>(
    m: MatrixRef<'_, T>,
    p: usize,
    q: &Col<T>,
    d: &Col<T>,
    lambda0: T,
    lambda_max: Option<T>,
    start: Vec<Var>,
    settings: &Settings<T>,
    method: Method,
    label: &'static str,
    free_block: crate::path::FreeBlockInfo,
) -> crate::path::Path<T> {
    use crate::path::{Info, Path, Status};
    let timer = std::time::Instant::now();
    let dim = m.nrows();
    let n = dim - p;
    let mut info = Info {
        method: label,
        precision: T::NAME,
        free_block,
        ..Info::default()
    };
    let empty = |status: Status, message: String, info: Info| Path {
        status,
        lambda0,
        lambda_max,
        lambda_reached: lambda0,
        breakpoints: Vec::new(),
        segments: Vec::new(),
        end: Point {
            lambda: lambda0,
            z: Col::zeros(n),
            w: Col::zeros(n),
            u: Col::zeros(p),
        },
        ray: None,
        message,
        info,
        final_basis: None,
    };
    // a warm start: the given basis, if nonsingular and feasible at lambda0
    let mut warm_note = String::new();
    let mut warm: Option<Engine<'_, T>> = None;
    if let Some(wb) = &settings.warm_basis {
        let mut wb = wb.clone();
        if wb.len() != dim {
            // a mixed problem's basis for its Schur reduction: z and w only
            wb.retain(|v| matches!(v, Var::W(_) | Var::Z(_)));
        }
        let fits = wb.len() == dim
            && wb.iter().all(|v| match *v {
                Var::W(i) | Var::Z(i) => i < n,
                Var::U(j) | Var::Artificial(j) => j < p,
                Var::Lambda => false,
            });
        if !fits {
            warm_note = "the warm basis does not fit this problem's rows".into();
        } else {
            match Engine::new(m, p, q.clone(), d.clone(), wb, lambda0, settings) {
                Err(msg) => warm_note = format!("warm basis not used: {msg}"),
                Ok(e) => match e.infeasibility() {
                    Some(why) => warm_note = format!("warm basis not used: {why}"),
                    None => warm = Some(e),
                },
            }
        }
    }
    info.warm_start = warm.is_some();
    info.warm_start_note = warm_note;
    if let Some(mut eng) = warm {
        let rec = Recorder::new();
        return finish_path(&mut eng, rec, lambda0, lambda_max, info, timer, true);
    }
    let mut eng = match Engine::new(m, p, q.clone(), d.clone(), start, lambda0, settings) {
        Ok(e) => e,
        Err(msg) => {
            info.solve_seconds = timer.elapsed().as_secs_f64();
            return empty(Status::IllConditioned, msg, info);
        }
    };
    let fill = |info: &mut Info, eng: &Engine<'_, T>| {
        info.pivots = eng.pivots;
        info.degenerate_pivots = eng.degenerate_pivots;
        info.refactorisations = eng.refactorisations;
        info.refinements = eng.refinements;
        (info.near_ties_resolved, info.near_ties_unresolved) = eng.near_ties.get();
        info.max_condition = eng.max_cond;
    };
    let started = if method == Method::Wolfe {
        eng.place_free_in_degenerate_rows()
            .map(|_| ())
            .map_err(|message| StartFailure {
                status: Status::IllConditioned,
                message,
            })
    } else {
        Ok(())
    };
    if let Err(f) =
        started.and_then(|_| start_phase(&mut eng, q, d, lambda0, settings.covering.as_ref()))
    {
        eng.estimate_end_condition();
        fill(&mut info, &eng);
        info.start_pivots = eng.pivots;
        info.solve_seconds = timer.elapsed().as_secs_f64();
        let mut path = empty(f.status, f.message, info);
        path.end = eng.point(None);
        path.end.lambda = lambda0;
        return path;
    }
    info.start_pivots = eng.pivots;
    // residuals are measured once the path is complete, on the original problem
    // (crate::residual::measure_path)
    let rec = Recorder::new();
    finish_path(&mut eng, rec, lambda0, lambda_max, info, timer, false)
}

/// Traces from the engine's basis (after the start phase, or a warm start) to
/// `lambda_max` and assembles the path.
pub(crate) fn finish_path<T: Scalar>(
    eng: &mut Engine<'_, T>,
    mut rec: Recorder<T>,
    lambda0: T,
    lambda_max: Option<T>,
    mut info: crate::path::Info,
    timer: std::time::Instant,
    warm: bool,
) -> crate::path::Path<T> {
    use crate::path::{Path, Ray, Status};
    let (n, p) = (eng.n, eng.p);
    let fill = |info: &mut crate::path::Info, eng: &Engine<'_, T>| {
        info.pivots = eng.pivots;
        info.degenerate_pivots = eng.degenerate_pivots;
        info.refactorisations = eng.refactorisations;
        info.refinements = eng.refinements;
        (info.near_ties_resolved, info.near_ties_unresolved) = eng.near_ties.get();
        info.max_condition = eng.max_cond;
    };
    if warm {
        info.start_pivots = 0;
    }
    let end = eng.trace(lambda_max, Some(&mut rec));
    let ray_of = |eng: &Engine<'_, T>, driver: Var, col: &Col<T>, rate: T| {
        let mut dz = Col::zeros(n);
        let mut dw = Col::zeros(n);
        let mut du = Col::zeros(p);
        let mut set = |v: Var, val: T| match v {
            Var::W(i) => dw[i] = val,
            Var::Z(i) => dz[i] = val,
            Var::U(j) => du[j] = val,
            _ => {}
        };
        for (r, v) in eng.basis.iter().enumerate() {
            set(*v, -col[r]);
        }
        set(driver, T::one());
        Ray {
            start: eng.point(None),
            dz,
            dw,
            du,
            dlambda: rate,
        }
    };
    let mut final_basis = None;
    let (status, end_point, lambda_reached, ray, message) = match end {
        TraceEnd::Reached { driver, theta } => {
            let pt = eng.point(Some((driver, theta)));
            // the end as a vertex at L fixed: the driver takes L's position
            let mut fb = eng.basis.clone();
            if let Some(l) = eng.row_of(Var::Lambda) {
                fb[l] = driver;
            }
            final_basis = Some(fb);
            let l = pt.lambda;
            (Status::Reached, pt, l, None, String::new())
        }
        TraceEnd::UnboundedRay { driver, col, rate } => {
            let r = ray_of(eng, driver, &col, rate);
            (
                Status::UnboundedRay,
                eng.point(None),
                crate::scalar::infinity(),
                Some(r),
                format!(
                    "the last segment, from L = {:e}, holds for every larger L",
                    eng.lambda.to_f64()
                ),
            )
        }
        TraceEnd::SecondaryRay { driver, col, rate } => {
            let r = ray_of(eng, driver, &col, rate);
            let l = eng.lambda;
            (
                Status::SecondaryRay,
                eng.point(None),
                l,
                Some(r),
                format!(
                    "secondary ray at L* = {:e}: the path has no continuation beyond it",
                    l.to_f64()
                ),
            )
        }
        TraceEnd::Stalled(msg) => {
            let l = eng.lambda;
            (Status::SecondaryRay, eng.point(None), l, None, msg)
        }
        TraceEnd::PivotLimit => {
            let l = eng.lambda;
            (
                Status::PivotLimit,
                eng.point(None),
                l,
                None,
                format!(
                    "pivot limit ({}) reached at L = {:e}",
                    eng.max_pivots,
                    l.to_f64()
                ),
            )
        }
        TraceEnd::IllConditioned(msg) => {
            let l = eng.lambda;
            (Status::IllConditioned, eng.point(None), l, None, msg)
        }
    };
    eng.estimate_end_condition();
    fill(&mut info, eng);
    info.turning_points = rec.turning_points;
    info.solve_seconds = timer.elapsed().as_secs_f64();
    Path {
        status,
        lambda0,
        lambda_max,
        lambda_reached,
        breakpoints: rec.breakpoints,
        segments: rec.segments,
        end: end_point,
        ray,
        message,
        info,
        final_basis,
    }
}

/// How a lean trace ended ([`finish_lean`]).
pub(crate) struct LeanEnd<T: Scalar> {
    pub status: crate::path::Status,
    pub message: String,
    /// The driver and its value where `lambda_max` was reached.
    pub reached: Option<(Var, T)>,
}

/// [`finish_path`] without the path: traces from the engine's basis to
/// `lambda_max` with a recorder of breakpoints alone (the breakpoints'
/// residuals measured and refined as in a full path, so the numbers are the
/// same) and writes the end point into `end` (no allocation for it). The
/// statuses and messages are those of [`finish_path`].
pub(crate) fn finish_lean<T: Scalar>(
    eng: &mut Engine<'_, T>,
    rec: &mut Recorder<T>,
    lambda_max: Option<T>,
    end: &mut Point<T>,
) -> LeanEnd<T> {
    use crate::path::Status;
    rec.clear();
    let traced = eng.trace(lambda_max, Some(rec));
    let (status, message, reached) = match traced {
        TraceEnd::Reached { driver, theta } => {
            eng.point_into(Some((driver, theta)), end);
            (Status::Reached, String::new(), Some((driver, theta)))
        }
        TraceEnd::UnboundedRay { .. } => {
            eng.point_into(None, end);
            let m = format!(
                "the last segment, from L = {:e}, holds for every larger L",
                eng.lambda.to_f64()
            );
            (Status::UnboundedRay, m, None)
        }
        TraceEnd::SecondaryRay { .. } => {
            eng.point_into(None, end);
            let m = format!(
                "secondary ray at L* = {:e}: the path has no continuation beyond it",
                eng.lambda.to_f64()
            );
            (Status::SecondaryRay, m, None)
        }
        TraceEnd::Stalled(m) => {
            eng.point_into(None, end);
            (Status::SecondaryRay, m, None)
        }
        TraceEnd::PivotLimit => {
            eng.point_into(None, end);
            let m = format!(
                "pivot limit ({}) reached at L = {:e}",
                eng.max_pivots,
                eng.lambda.to_f64()
            );
            (Status::PivotLimit, m, None)
        }
        TraceEnd::IllConditioned(m) => {
            eng.point_into(None, end);
            (Status::IllConditioned, m, None)
        }
    };
    LeanEnd {
        status,
        message,
        reached,
    }
}
