//! Lemke-style complementary pivoting with `L` as the driving variable.
//!
//! Standard form: from a complementary basis feasible at `L0` (all `w` when
//! `q + L0 d >= 0`, else the end basis of Lemke's method with an artificial
//! variable and a covering vector), `L` rises until a basic variable reaches zero.
//! It leaves, `L` enters the basis in its place, and the leaving variable's
//! complement drives the next step; along it `L` is basic and affine in the
//! driver. When `L` would have to fall, it falls (a turning point, reported).
//! Ties go to the lexicographic rule; see [`crate::tolerance`].
//!
//! A mixed problem is reduced by a Schur complement first ([`crate::reduce`]).

use crate::path::{Info, Path, Point, Status, Var};
use crate::pivoting::{run_path, start_phase, Engine};
use crate::reduce::Reduction;
use crate::residual::residual;
use crate::{error::PlcpError, problem::*, scalar::Scalar, settings::Settings};
use faer::Col;

/// The answer to a plain LCP.
#[derive(Clone, Debug)]
pub struct LcpSolution<T: Scalar> {
    /// `Reached` when solved; `SecondaryRay` when Lemke's method with the
    /// covering vector ended on a secondary ray; `PivotLimit`, `IllConditioned`.
    pub status: Status,
    /// The solution (the last point reached otherwise).
    pub z: Col<T>,
    /// `w = q + M z`.
    pub w: Col<T>,
    /// Diagnostics.
    pub message: String,
    /// Counts, residuals, timing.
    pub info: Info,
}

impl<T: Scalar> LcpSolution<T> {
    /// The answer as the [`Path`] of the PLCP `w = q + L 0 + M z` over the range
    /// `[0, 0]`: the LCP is solved by the start phase alone (Lemke's method with
    /// an artificial variable), which is not a path in `L`, so the path is the
    /// single point `L = 0`: no breakpoints, no segments, `end` the solution
    /// (`u` empty), `lambda_reached = 0`, and the status, message and info of
    /// the solution. This is what [`crate::solve`] returns for that PLCP, and what
    /// `plcp lcp` reports in the keys it shares with `plcp solve`. No `ray` is
    /// recorded (a secondary ray's direction is not kept by the start phase).
    ///
    /// ```
    /// use faer::{mat, col};
    /// let lcp = plcp::Lcp::new(mat![[2.0, 1.0], [1.0, 2.0]].as_ref(), col![-5.0, -6.0].as_ref()).unwrap();
    /// let path = plcp::solve_lcp(&lcp, &plcp::Settings::default()).unwrap().as_path();
    /// assert_eq!(path.status, plcp::Status::Reached);
    /// assert!(path.breakpoints.is_empty() && path.segments.is_empty());
    /// assert_eq!((path.lambda0, path.lambda_max, path.lambda_reached), (0.0, Some(0.0), 0.0));
    /// let z1: f64 = path.at(0.0).unwrap().z[1];
    /// assert!((z1 - 7.0 / 3.0).abs() < 1e-12);
    /// ```
    pub fn as_path(&self) -> Path<T> {
        Path {
            status: self.status,
            lambda0: T::zero(),
            lambda_max: Some(T::zero()),
            lambda_reached: T::zero(),
            breakpoints: Vec::new(),
            segments: Vec::new(),
            end: Point {
                lambda: T::zero(),
                z: self.z.clone(),
                w: self.w.clone(),
                u: Col::zeros(0),
            },
            ray: None,
            message: self.message.clone(),
            info: self.info.clone(),
            final_basis: None,
        }
    }
}

pub(crate) fn solve<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
) -> Result<Path<T>, PlcpError> {
    if problem.free() > 0 {
        let timer = std::time::Instant::now();
        let red = Reduction::new(problem)?;
        // the reduced data are known to about eps cond(F): steps of L within that
        // are ties (a turning point or a zero-length step there is an artefact of
        // the reduction, not a property of the problem)
        let mut reduced_settings = settings.clone();
        reduced_settings.tie_tol_eps *=
            crate::tolerance::reduction_tie_factor::<T>(red.cond, settings.tie_tol_eps);
        let mut path = solve_standard(&red.reduced, &reduced_settings, "lemke (Schur reduction)");
        // recover u on every segment and at the end, and measure the residual on
        // the original (unreduced) problem
        let mut res = crate::path::Residual::default();
        for seg in &mut path.segments {
            seg.u_from = red.recover_u(&seg.z_from, seg.lambda_from);
            seg.du = red.recover_du(&seg.dz);
            polish_segment(problem, seg);
        }
        reintersect_breakpoints(&mut path);
        let ray_moved = reintersect_secondary_ray(&mut path, red.cond);
        doubt_ray_on_reduction(&mut path, settings, red.cond);
        for b in &mut path.breakpoints {
            let seg = match b.segment {
                0 => path.segments.first(),
                k => path.segments.get(k - 1),
            };
            if let Some(seg) = seg {
                b.residual = residual(problem, &seg.eval(b.lambda));
            }
        }
        for seg in &path.segments {
            res = res.max(residual(problem, &seg.eval(seg.lambda_from)));
            if !seg.unbounded {
                res = res.max(residual(problem, &seg.eval(seg.lambda_to)));
            }
        }
        path.end.u = red.recover_u(&path.end.z, path.end.lambda);
        // the end point lies on the last (polished) segment
        if let Some(seg) = path.segments.last() {
            let l = path.end.lambda;
            if l.is_finite() && (seg.contains(l) || l == seg.lambda_to) {
                path.end = seg.eval(l);
            }
        }
        if path.end.lambda.is_finite() {
            res = res.max(residual(problem, &path.end));
        }
        if let Some(ray) = &mut path.ray {
            ray.start.u = red.recover_u(&ray.start.z, ray.start.lambda);
            let p = problem.free();
            let n = problem.n();
            // du per unit of the driver: -(G_z dz + G_d dL)
            let du_dl = red.recover_du(&Col::zeros(n));
            let dz_part = red.recover_du(&ray.dz);
            ray.du = Col::from_fn(p, |i| (dz_part[i] - du_dl[i]) + du_dl[i] * ray.dlambda);
            if ray_moved {
                // the ray starts where the path ends, on the polished segment
                ray.start = path.end.clone();
            }
        }
        path.info.residual = res;
        path.info.solve_seconds = timer.elapsed().as_secs_f64();
        return Ok(path);
    }
    Ok(solve_standard(problem, settings, "lemke"))
}

/// Moves each breakpoint between two polished segments to where the variable
/// that leaves the basis there reaches zero on the polished segment before it.
///
/// The reduced path finds its breakpoints on the Schur complement, whose values
/// carry an error of about `eps cond(F)`; the polished segments are accurate, so
/// the breakpoint taken from them is too, and both segments meet there (they
/// solve the same equations with the leaving variable at zero). Only simple
/// breakpoints are moved (one pair swapped, `L` rising through them) and only
/// by less than `sqrt(eps)` relative: a larger move would mean the two
/// computations disagree on more than rounding, and the reduced path is kept.
fn reintersect_breakpoints<T: Scalar>(path: &mut Path<T>) {
    let tol = T::eps().sqrt();
    for k in 1..path.segments.len() {
        let (prev, next) = (&path.segments[k - 1], &path.segments[k]);
        let lb = prev.lambda_to;
        if next.lambda_from != lb || prev.lambda_from >= lb {
            continue;
        }
        if !next.unbounded && next.lambda_to <= lb {
            continue;
        }
        // the variables basic before and nonbasic after reach zero here (several
        // at once after a degenerate run of pivots at one L): the first of them
        let mut l_new: Option<T> = None;
        let mut ok = true;
        for i in 0..prev.basis.len() {
            if prev.basis[i] == next.basis[i] {
                continue;
            }
            let (v, dv) = match prev.basis[i] {
                Var::Z(_) => (prev.z_from[i], prev.dz[i]),
                Var::W(_) => (prev.w_from[i], prev.dw[i]),
                _ => (T::zero(), T::zero()),
            };
            let root = prev.lambda_from - v / dv;
            if dv == T::zero() || !root.is_finite() {
                ok = false;
                break;
            }
            l_new = Some(l_new.map_or(root, |l| l.min(root)));
        }
        let Some(l_new) = l_new.filter(|_| ok) else {
            continue;
        };
        if (l_new - lb).abs() > tol * lb.abs().max(T::one())
            || l_new <= prev.lambda_from
            || (!next.unbounded && l_new >= next.lambda_to)
        {
            continue;
        }
        let shift = l_new - lb;
        let next = &mut path.segments[k];
        for (from, slope) in [
            (&mut next.z_from, &next.dz),
            (&mut next.w_from, &next.dw),
            (&mut next.u_from, &next.du),
        ] {
            for j in 0..from.nrows() {
                from[j] += slope[j] * shift;
            }
        }
        next.lambda_from = l_new;
        path.segments[k - 1].lambda_to = l_new;
        for b in &mut path.breakpoints {
            if b.segment == k && b.lambda == lb {
                b.lambda = l_new;
            }
        }
    }
}

/// Moves the breakpoint of a secondary ray (the path's last, with no segment
/// after it) to where its leaving variable reaches zero on the polished last
/// segment; `lambda_reached` and the end follow. Returns whether it moved.
///
/// The reduced path's `L*` carries the reduction's error, which the reduced
/// basis amplifies: seed 294 of `tests/mixed.rs` (`cond(F)` about 700, basis
/// condition 1.5e7) put `L* = 16/11` at 8e-8 relative, where the polished
/// segment's `w_3` was `-4.5e-8` (its line reaches zero at `16/11` to 1e-15).
/// The move is taken up to `max(sqrt(eps), eps cond(F) max_condition)`
/// relative (that error's size), only forward of the segment's start, and only
/// where the rest of the segment's basic variables stay nonnegative there;
/// else the reduced `L*` is kept.
fn reintersect_secondary_ray<T: Scalar>(path: &mut Path<T>, cond_f: f64) -> bool {
    if path.status != Status::SecondaryRay {
        return false;
    }
    let lb = path.lambda_reached;
    let Some(last) = path.segments.last() else {
        return false;
    };
    if last.unbounded || last.lambda_to != lb || last.lambda_from >= lb {
        return false;
    }
    let leaving: Vec<Var> = path
        .breakpoints
        .iter()
        .filter(|b| b.lambda == lb)
        .map(|b| b.leaving)
        .collect();
    let [leaving] = leaving[..] else {
        return false;
    };
    let Some(i) = last.basis.iter().position(|&v| v == leaving) else {
        return false;
    };
    let (v, dv) = match leaving {
        Var::Z(_) => (last.z_from[i], last.dz[i]),
        Var::W(_) => (last.w_from[i], last.dw[i]),
        _ => return false,
    };
    if dv == T::zero() {
        return false;
    }
    let l_new = last.lambda_from - v / dv;
    let eps = T::eps().to_f64();
    let cap = eps.sqrt().max(eps * cond_f * path.info.max_condition);
    if !l_new.is_finite()
        || l_new <= last.lambda_from
        || (l_new - lb).abs().to_f64() > cap * lb.abs().to_f64().max(1.0)
    {
        return false;
    }
    // the other basic variables stay feasible at the new end (to rounding of
    // the segment's scale)
    let at = last.eval(l_new);
    let scale =
        at.z.iter()
            .chain(at.w.iter())
            .fold(T::one(), |m, x| if x.abs() > m { x.abs() } else { m });
    let floor = -(T::from_f64(cap) * scale);
    if at.z.iter().chain(at.w.iter()).any(|&x| x < floor) {
        return false;
    }
    path.segments.last_mut().expect("checked").lambda_to = l_new;
    for b in &mut path.breakpoints {
        if b.lambda == lb {
            b.lambda = l_new;
        }
    }
    path.lambda_reached = l_new;
    path.end.lambda = l_new;
    true
}

/// Recomputes a segment of the reduced path on the unreduced system: with the
/// segment's active set `J` (basic `z`), solve the square system of the equality
/// rows and the rows `J` for `(u, z_J)` at `lambda_from` and for the slope, then
/// `w` from its rows. This removes the loss of accuracy of the Schur complement
/// (about `eps cond(F)`); if the square system is singular the segment is kept.
fn polish_segment<T: Scalar>(problem: &Plcp<T>, seg: &mut crate::path::Segment<T>) {
    let p = problem.free();
    let n = problem.n();
    let m = problem.m();
    let active: Vec<usize> = (0..n)
        .filter(|&i| seg.basis.get(i) == Some(&Var::Z(i)))
        .collect();
    let rows: Vec<usize> = (0..p).chain(active.iter().map(|&i| p + i)).collect();
    let k = rows.len();
    let a = faer::Mat::from_fn(k, k, |r, c| m[(rows[r], rows[c])]);
    let l0 = seg.lambda_from;
    let rhs = faer::Mat::from_fn(k, 2, |r, c| {
        let i = rows[r];
        if c == 0 {
            -(problem.q()[i] + l0 * problem.d()[i])
        } else {
            -problem.d()[i]
        }
    });
    let Some((inv, umax, umin)) = crate::linalg::inverse(a.as_ref()) else {
        return;
    };
    if umin <= umax * T::eps().to_f64() * (k.max(1) as f64) * 1e3 {
        return;
    }
    let mut sol = crate::linalg::matmul(inv.as_ref(), rhs.as_ref());
    // one step of iterative refinement
    let ax = crate::linalg::matmul(a.as_ref(), sol.as_ref());
    let r = faer::Mat::from_fn(k, 2, |i, j| rhs[(i, j)] - ax[(i, j)]);
    let corr = crate::linalg::matmul(inv.as_ref(), r.as_ref());
    for i in 0..k {
        for j in 0..2 {
            sol[(i, j)] += corr[(i, j)];
        }
    }
    let mut x0 = Col::<T>::zeros(p + n);
    let mut dx = Col::<T>::zeros(p + n);
    for (r, &i) in rows.iter().enumerate() {
        x0[i] = sol[(r, 0)];
        dx[i] = sol[(r, 1)];
    }
    for j in 0..p {
        seg.u_from[j] = x0[j];
        seg.du[j] = dx[j];
    }
    for i in 0..n {
        seg.z_from[i] = x0[p + i];
        seg.dz[i] = dx[p + i];
    }
    for i in 0..n {
        let row = p + i;
        if active.contains(&i) {
            seg.w_from[i] = T::zero();
            seg.dw[i] = T::zero();
            continue;
        }
        let mut w0 = problem.q()[row] + l0 * problem.d()[row];
        let mut dw = problem.d()[row];
        for c in 0..p + n {
            w0 += m[(row, c)] * x0[c];
            dw += m[(row, c)] * dx[c];
        }
        seg.w_from[i] = w0;
        seg.dw[i] = dw;
    }
}

fn solve_standard<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
    label: &'static str,
) -> Path<T> {
    let n = problem.n();
    let start: Vec<Var> = (0..n).map(Var::W).collect();
    run_path(
        problem.matrix(),
        0,
        &problem.q().to_owned(),
        &problem.d().to_owned(),
        problem.lambda0(),
        problem.lambda_max(),
        start,
        settings,
        crate::settings::Method::Lemke,
        label,
        Default::default(),
    )
}

/// Solves the LCP `w = q + M z`, `w, z >= 0`, `w'z = 0` by Lemke's method with a
/// covering vector (`settings.covering`, default all ones) and the lexicographic rule.
///
/// ```
/// use faer::{mat, col};
/// let lcp = plcp::Lcp::new(mat![[2.0, 1.0], [1.0, 2.0]].as_ref(), col![-5.0, -6.0].as_ref()).unwrap();
/// let sol = plcp::solve_lcp(&lcp, &plcp::Settings::default()).unwrap();
/// assert_eq!(sol.status, plcp::Status::Reached);
/// let (z0, z1): (f64, f64) = (sol.z[0], sol.z[1]);
/// assert!((z0 - 4.0 / 3.0).abs() < 1e-12 && (z1 - 7.0 / 3.0).abs() < 1e-12);
/// ```
pub fn solve_lcp<T: Scalar>(
    lcp: &Lcp<T>,
    settings: &Settings<T>,
) -> Result<LcpSolution<T>, PlcpError> {
    T::entry_solve_lcp(lcp, settings)
}

/// [`solve_lcp`]'s body, instantiated in this crate (`entry.rs`).
pub(crate) fn solve_lcp_here<T: Scalar>(
    lcp: &Lcp<T>,
    settings: &Settings<T>,
) -> Result<LcpSolution<T>, PlcpError> {
    settings.validate(lcp.n())?;
    let timer = std::time::Instant::now();
    let n = lcp.n();
    let d = Col::<T>::zeros(n);
    let q = lcp.q.clone();
    let start: Vec<Var> = (0..n).map(Var::W).collect();
    let mut info = Info {
        method: "lemke",
        precision: T::NAME,
        ..Info::default()
    };
    let problem = Plcp::new(lcp.m(), lcp.q(), d.as_ref())?;
    // equilibrated like every path (`crate::trace`): the engine's tolerances
    // (floors of one in the scale of the basic values and of the parameter)
    // are relative to the data only on the equilibrated problem, whose
    // right-hand side is brought near one. Unscaled, `q` of 2e-4 in f32 met
    // tie windows of `1e3 eps * 1` in `x` (issue 14, defect 7: Siconos
    // `enum_fails` in f32 passed its blocking row and ended `reached` with
    // Siconos error 1.04). The covering vector scales with the rows, so the
    // start phase is Lemke's method with the given vector on the original data.
    let eq = if settings.scaling {
        crate::scaling::Equilibration::ruiz(&problem, 8)
    } else {
        crate::scaling::Equilibration {
            rows: vec![1.0; n],
            cols: vec![1.0; n],
        }
    };
    let scaled = if eq.is_identity() {
        None
    } else {
        eq.scale(&problem)
    };
    let eq = if scaled.is_some() {
        eq
    } else {
        crate::scaling::Equilibration {
            rows: vec![1.0; n],
            cols: vec![1.0; n],
        }
    };
    let (sm, sq) = match &scaled {
        Some(s) => (s.m(), s.q().to_owned()),
        None => (lcp.m(), q.clone()),
    };
    let covering = Col::<T>::from_fn(n, |i| {
        let c = settings.covering.as_ref().map_or(T::one(), |c| c[i]);
        c * T::from_f64(eq.rows[i])
    });
    let q = sq;
    let unscale = |mut pt: Point<T>| {
        for i in 0..n {
            pt.z[i] *= T::from_f64(eq.cols[i]);
            pt.w[i] /= T::from_f64(eq.rows[i]);
        }
        pt
    };
    let (status, message, point) = match Engine::new(
        sm.into(),
        0,
        q.clone(),
        d.clone(),
        start,
        T::zero(),
        settings,
    ) {
        Err(msg) => (
            Status::IllConditioned,
            msg,
            Point {
                lambda: T::zero(),
                z: Col::zeros(n),
                w: lcp.q.clone(),
                u: Col::zeros(0),
            },
        ),
        Ok(mut eng) => {
            let r = start_phase(&mut eng, &q, &d, T::zero(), Some(&covering));
            eng.estimate_end_condition();
            info.pivots = eng.pivots;
            info.start_pivots = eng.pivots;
            info.degenerate_pivots = eng.degenerate_pivots;
            info.refactorisations = eng.refactorisations;
            (info.near_ties_resolved, info.near_ties_unresolved) = eng.near_ties.get();
            info.max_condition = eng.max_cond;
            match r {
                Ok(()) => (Status::Reached, String::new(), unscale(eng.point(None))),
                Err(f) => {
                    // Lemke's secondary ray is the LCP's outcome here, not "infeasible"
                    let status = if f.status == Status::Infeasible {
                        Status::SecondaryRay
                    } else {
                        f.status
                    };
                    let mut pt = unscale(eng.point(None));
                    pt.lambda = T::zero();
                    (status, f.message, pt)
                }
            }
        }
    };
    // w recomputed from z, so that the residual measures the equation honestly
    let mut w = lcp.q.clone();
    for j in 0..n {
        for i in 0..n {
            w[i] += lcp.m[(i, j)] * point.z[j];
        }
    }
    // measured with the solver's w and with w recomputed from z; a success
    // beyond the residual guard is `ill_conditioned` (issue 14: Siconos
    // enum_fails in f32, Siconos error 1.04, had been reported `reached`)
    let honest = Point {
        w: w.clone(),
        ..point.clone()
    };
    info.residual = residual(&problem, &point).max(residual(&problem, &honest));
    let (mut status, mut message) = (status, message);
    let worst = info.residual.worst();
    let limit = T::eps().to_f64().sqrt();
    if status.is_success() && (worst.is_nan() || worst > limit) {
        message = format!(
            "the solution's residual {worst:.3e} (equation {:.1e}, feasibility {:.1e}, complementarity {:.1e}) exceeds sqrt(eps) = {limit:.1e} in {}: the answer cannot be trusted; try a higher precision. {message}",
            info.residual.equation,
            info.residual.feasibility,
            info.residual.complementarity,
            T::NAME,
        );
        status = Status::IllConditioned;
    }
    info.solve_seconds = timer.elapsed().as_secs_f64();
    Ok(LcpSolution {
        status,
        z: point.z,
        w,
        message,
        info,
    })
}

/// An `unbounded_ray` of the reduced path whose rate of `L` is within the
/// noise of the reduced basis (`pivot_tol` times its condition estimate,
/// clamped as the trace's noise) widened by the reduction's error
/// ([`crate::tolerance::reduction_tie_factor`]), relative to the ray's
/// largest component, is no evidence that `L` rises: a zero rate (the exact
/// path ends on a secondary ray, 25/82) was read as `2.7e-10` against a
/// direction of order one, and the ray's basis is infeasible exactly. The
/// path stops `ill_conditioned` where the ray would start.
fn doubt_ray_on_reduction<T: Scalar>(path: &mut Path<T>, settings: &Settings<T>, cond_f: f64) {
    if path.status != Status::UnboundedRay {
        return;
    }
    let Some(ray) = &path.ray else {
        return;
    };
    let dirmax = ray
        .dz
        .iter()
        .chain(ray.dw.iter())
        .fold(ray.dlambda.abs(), |m, v| m.max(v.abs()))
        .to_f64();
    let factor = crate::tolerance::reduction_tie_factor::<T>(cond_f, settings.tie_tol_eps);
    let noise = settings.pivot_tol_eps
        * T::eps().to_f64()
        * path.info.max_condition.clamp(1.0, 1e6)
        * factor;
    let rate = ray.dlambda.to_f64();
    if rate.abs() > noise * dirmax {
        return;
    }
    let start = ray.start.clone();
    path.segments.retain(|s| !s.unbounded);
    path.status = Status::IllConditioned;
    path.message = format!(
        "the ray from L = {:e} has a rate of L of {rate:e} against its largest component {dirmax:e}: within the noise {noise:e} of the reduced basis (condition {:e}, reduction factor {factor:e}), so L may not rise along it (a secondary ray); Wolfe's long form or a higher precision decides",
        start.lambda.to_f64(),
        path.info.max_condition
    );
    path.lambda_reached = start.lambda;
    path.end = start;
    path.ray = None;
    path.final_basis = None;
}
