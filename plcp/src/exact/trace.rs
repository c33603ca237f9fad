//! The exact tracer: Lemke's method with `L` as the driving variable on the
//! integer tableau (`--precision exact`).
//!
//! With `L0 = num / den`, the second phase works in `x~ = den x` and
//! `L~ = den (L - L0)`, so that the right-hand side `den q + num d` stays
//! integer: `A x~ - L~ d = den q + num d`, `L~` a nonbasic column at first.
//! If `q + L0 d` is not nonnegative, the LCP at `L0` is first solved by
//! Lemke's method with an artificial `z0` and the covering vector of ones in
//! the (power-of-two scaled) rows. Ratio ties are broken by the lexicographic
//! rule on the rows of `B^-1` (its `w` columns: the whole of `B^-1` when there
//! are no free variables, since the `w` block of the tableau starts as the
//! identity), exactly, so that degenerate steps never cycle (with free
//! variables, whose columns of `B^-1` are not stored, then the least basic
//! variable); ties go to `z0` leaving and to `L_max`. Every state (basis,
//! entering column) is remembered: one seen again would repeat forever and is
//! reported, a closed loop of the path through `L0` (random case "huge #9" of
//! `tests/stiff.rs`: `M` monotone and singular, 12 breakpoints round) as
//! `secondary_ray`, a degenerate cycle as `pivot_limit`. Every basis is
//! complementary with at most one pair's driver outside, as in the float
//! engine, and the path it returns has the same shape.
//!
//! Limits: the order `p + n` at most [`EXACT_MAX_DIM`] (each pivot costs
//! `O((p + n)^2)` operations on integers of up to `(p + n) * 60` bits), and
//! a free block of full rank (the free variables must all be basic).

use super::tableau::Tableau;
use super::{rational_to_f64, to_rational};
use crate::error::PlcpError;
use crate::path::{Breakpoint, Info, Path, Point, Ray, Residual, Segment, Status, Var};
use crate::problem::Plcp;
use crate::scalar::Scalar;
use crate::settings::Settings;
use faer::Col;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use std::cmp::Ordering;
use std::time::Instant;

/// The largest order `p + n` the exact tracer accepts: beyond it
/// `--precision exact` is an `Err` (a dense `n = 200` path already takes
/// minutes; see `docs/certification.md`).
pub const EXACT_MAX_DIM: usize = 400;

/// A path traced in exact arithmetic: rounded to `f64` for the usual
/// readers, with the exact breakpoints beside it.
#[derive(Clone, Debug)]
pub struct ExactPath {
    /// The path, every value the nearest `f64` to the exact one;
    /// `info.precision` is `"exact"`.
    pub path: Path<f64>,
    /// The exact parameter value of every breakpoint, as in `path.breakpoints`.
    pub breakpoints: Vec<BigRational>,
    /// The exact parameter value where the path ended.
    pub lambda_reached: BigRational,
    /// The exact values of every segment, as in `path.segments`: the
    /// escalation rounds them to its working precision (`fx128` values from
    /// `f64` ones would carry `f64`'s rounding into an `fx128` path).
    pub(crate) exact_segments: Vec<ExactSegment>,
}

/// One segment of an [`ExactPath`] in exact arithmetic: where it starts and
/// ends, and `(value at the start, slope)` of every variable, by column
/// (`u`, then `z`, then `w`, unscaled).
#[derive(Clone, Debug)]
pub(crate) struct ExactSegment {
    pub from: BigRational,
    pub to: Option<BigRational>,
    pub vals: Vec<(BigRational, BigRational)>,
}

impl ExactSegment {
    /// The values `(u, z, w)` at `lambda`, each rounded once to `T`.
    pub fn at<T: Scalar>(&self, lambda: &BigRational, p: usize, n: usize) -> [Col<T>; 3] {
        let dl = lambda - &self.from;
        let x = |c: usize| -> T {
            let (v, d) = &self.vals[c];
            super::rational_to(&(v + d * &dl))
        };
        [
            Col::from_fn(p, &x),
            Col::from_fn(n, |i| x(p + i)),
            Col::from_fn(n, |i| x(p + n + i)),
        ]
    }

    /// The slopes `(du, dz, dw)`, each rounded once to `T`.
    pub fn slopes<T: Scalar>(&self, p: usize, n: usize) -> [Col<T>; 3] {
        let d = |c: usize| -> T { super::rational_to(&self.vals[c].1) };
        [
            Col::from_fn(p, &d),
            Col::from_fn(n, |i| d(p + i)),
            Col::from_fn(n, |i| d(p + n + i)),
        ]
    }
}

/// Traces `problem` from `lambda0` exactly (see the module documentation).
///
/// `Err` when the problem is larger than [`EXACT_MAX_DIM`] or its free block
/// is singular; every outcome of the method is a [`Status`] as usual.
/// `settings.max_pivots` is honoured; tolerances have no role.
pub fn trace<T: Scalar>(problem: &Plcp<T>, settings: &Settings<T>) -> Result<ExactPath, PlcpError> {
    T::entry_exact_trace(problem, settings)
}

/// [`trace`]'s body, instantiated in this crate (`entry.rs`).
pub(crate) fn trace_here<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
) -> Result<ExactPath, PlcpError> {
    let timer = Instant::now();
    let mut t = setup(problem)?;
    let l0 = to_rational(problem.lambda0());
    let mut run = Run::new(problem, settings, l0.clone());
    if let Some(why) = run.start_phase(&mut t) {
        return Ok(run.finish(problem, &t, why.0, why.1, timer));
    }
    let (status, message) = run.parametric(&mut t);
    Ok(run.finish(problem, &t, status, message, timer))
}

/// Continues `problem` exactly from `basis` at `lambda` (for the escalation
/// f64 -> fx128 -> exact: a segment's `basis` and its `lambda_from`). The
/// basis lists one of `z_i`, `w_i` per pair and may list free variables
/// (all of them are made basic in any case). The returned path starts at
/// `lambda` (its `lambda0`), with no start phase.
///
/// `Err` when the basis is not complementary, singular, or infeasible at
/// `lambda`, and for the limits of [`trace`].
pub fn trace_from<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
    basis: &[Var],
    lambda: T,
) -> Result<ExactPath, PlcpError> {
    T::entry_exact_trace_from(problem, settings, basis, lambda)
}

/// [`trace_from`]'s body, instantiated in this crate (`entry.rs`).
pub(crate) fn trace_from_here<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
    basis: &[Var],
    lambda: T,
) -> Result<ExactPath, PlcpError> {
    let timer = Instant::now();
    let mut t = setup(problem)?;
    let invalid = |why: String| PlcpError::Invalid {
        what: "exact continuation basis".into(),
        why,
    };
    let n = problem.n();
    let mut seen = vec![0u8; n];
    let mut target = Vec::new();
    for v in basis {
        match *v {
            Var::Z(i) | Var::W(i) if i < n => {
                seen[i] += 1;
                target.push(t.col_of(*v).expect("a pair"));
            }
            Var::U(j) if j < problem.free() => {}
            other => {
                return Err(invalid(format!(
                    "{other} cannot be in a complementary basis"
                )))
            }
        }
    }
    if let Some(i) = seen.iter().position(|&s| s != 1) {
        return Err(invalid(format!("pair {i} appears {} times", seen[i])));
    }
    for &c in &target {
        let row = (0..t.basis.len())
            .filter(|&r| {
                !target.contains(&t.basis[r]) && t.basis[r] >= t.p && !t.rows[r][c].is_zero()
            })
            .min_by_key(|&r| t.rows[r][c].bits());
        if !t.basic[c] {
            match row {
                Some(r) => t.pivot(r, c),
                None => {
                    return Err(invalid(format!(
                        "singular: {} cannot enter",
                        t.var_of(c).expect("z or w")
                    )))
                }
            }
        }
    }
    let l = to_rational(lambda);
    for i in 0..t.basis.len() {
        if t.signed(t.basis[i]) {
            let (a, b) = t.affine(i);
            if (a + b * &l).is_negative() {
                let v = t.var_of(t.basis[i]).expect("z or w");
                return Err(invalid(format!("{v} < 0 at L = {}", super::short(&l))));
            }
        }
    }
    let mut run = Run::new(problem, settings, l);
    run.lambda0_t = lambda.to_f64();
    let (status, message) = run.parametric(&mut t);
    Ok(run.finish(problem, &t, status, message, timer))
}

fn setup<T: Scalar>(problem: &Plcp<T>) -> Result<Tableau, PlcpError> {
    let dim = problem.dim();
    if dim > EXACT_MAX_DIM {
        return Err(PlcpError::Invalid {
            what: "precision exact".into(),
            why: format!(
                "the problem has order p + n = {dim}, above the exact tracer's limit {EXACT_MAX_DIM} (each exact pivot costs O((p+n)^2) big-integer operations): use a float precision and --certify"
            ),
        });
    }
    let mut t = Tableau::new(problem);
    let left = t.pivot_in_free();
    if left > 0 {
        return Err(PlcpError::Invalid {
            what: "precision exact".into(),
            why: format!(
                "the free block is singular ({left} of {} free variables cannot be basic): the exact tracer needs a free block of full rank; use a float precision with Wolfe's method and --certify",
                problem.free()
            ),
        });
    }
    Ok(t)
}

/// The state of one exact trace and what it records.
struct Run {
    p: usize,
    n: usize,
    /// The start value and its numerator and denominator.
    l0: BigRational,
    lambda0_t: f64,
    lambda_max: Option<BigRational>,
    max_pivots: usize,
    pivots: usize,
    start_pivots: usize,
    degenerate: usize,
    turning: usize,
    /// `L` now (exact).
    lambda: BigRational,
    rising: bool,
    breakpoints: Vec<Breakpoint<f64>>,
    exact_bps: Vec<BigRational>,
    segments: Vec<Segment<f64>>,
    exact_segments: Vec<ExactSegment>,
    ray: Option<Ray<f64>>,
    /// The entering column of the last step (for the segment basis).
    driver: Option<usize>,
}

/// The bases already left, with the entering column: the exact method is
/// deterministic, so one seen again repeats forever (issue 14: random case
/// "huge #9", whose path is a closed loop through `L0`).
#[derive(Default)]
struct Visits {
    /// (sorted basis, entering column) -> number of breakpoints then.
    seen: std::collections::HashMap<(Vec<usize>, usize), usize>,
}

impl Visits {
    /// Records the state; `Some(k)`: it was seen when there were `k` breakpoints.
    fn visit(&mut self, t: &Tableau, entering: usize, breakpoints: usize) -> Option<usize> {
        let mut b = t.basis.clone();
        b.sort_unstable();
        match self.seen.entry((b, entering)) {
            std::collections::hash_map::Entry::Occupied(e) => Some(*e.get()),
            std::collections::hash_map::Entry::Vacant(e) => {
                e.insert(breakpoints);
                None
            }
        }
    }
}

/// `a/b` compared with `c/d` for `b, d > 0`.
fn cmp_frac(a: &BigInt, b: &BigInt, c: &BigInt, d: &BigInt) -> Ordering {
    (a * d).cmp(&(c * b))
}

impl Run {
    fn new<T: Scalar>(problem: &Plcp<T>, settings: &Settings<T>, l0: BigRational) -> Self {
        let (p, n) = (problem.free(), problem.n());
        Run {
            p,
            n,
            lambda: l0.clone(),
            l0,
            lambda0_t: problem.lambda0().to_f64(),
            lambda_max: problem.lambda_max().map(to_rational),
            max_pivots: settings.max_pivots_for(n + p),
            pivots: 0,
            start_pivots: 0,
            degenerate: 0,
            turning: 0,
            rising: true,
            breakpoints: Vec::new(),
            exact_bps: Vec::new(),
            segments: Vec::new(),
            exact_segments: Vec::new(),
            ray: None,
            driver: None,
        }
    }

    /// Numerators of the basic values at `L0` (times `sign(det) den`).
    fn values_at_l0(&self, t: &Tableau) -> Vec<BigInt> {
        let (num, den) = (self.l0.numer(), self.l0.denom());
        let s = BigInt::from(t.sign());
        t.rows
            .iter()
            .map(|r| (&r[t.qc()] * den + &r[t.dc()] * num) * &s)
            .collect()
    }

    /// The lexicographic key of row `i` (its row of `B^-1` on the `w`
    /// columns, sign-normalised).
    fn lex(&self, t: &Tableau, i: usize, k: usize) -> BigInt {
        let c = t.p + t.n + k;
        let v = if t.basic[c] {
            if t.basis[i] == c {
                t.det.clone()
            } else {
                BigInt::zero()
            }
        } else {
            t.rows[i][c].clone()
        };
        v * BigInt::from(t.sign())
    }

    /// Compares the ratios of rows `i` and `j` (values `v`, column `col`, both
    /// positive in `col`), lexicographically.
    fn cmp_rows(&self, t: &Tableau, v: &[BigInt], col: &[BigInt], i: usize, j: usize) -> Ordering {
        let o = cmp_frac(&v[i], &col[i], &v[j], &col[j]);
        if o != Ordering::Equal {
            return o;
        }
        for k in 0..self.n {
            let o = cmp_frac(&self.lex(t, i, k), &col[i], &self.lex(t, j, k), &col[j]);
            if o != Ordering::Equal {
                return o;
            }
        }
        // (only with free rows, whose columns of B^-1 are not stored) the
        // least basic variable: a fixed order; a cycle is caught by `Visits`
        t.basis[i].cmp(&t.basis[j])
    }

    fn col(t: &Tableau, c: usize) -> Vec<BigInt> {
        let s = BigInt::from(t.sign());
        t.rows.iter().map(|r| &r[c] * &s).collect()
    }

    fn complement_col(t: &Tableau, c: usize) -> Option<usize> {
        t.var_of(c)?.complement().and_then(|v| t.col_of(v))
    }

    /// Lemke's start phase at `L0` if `q + L0 d` is not nonnegative. Returns
    /// the status and message when it does not end with `z0` leaving.
    fn start_phase(&mut self, t: &mut Tableau) -> Option<(Status, String)> {
        let v = self.values_at_l0(t);
        let signed: Vec<usize> = (0..t.basis.len())
            .filter(|&i| t.signed(t.basis[i]))
            .collect();
        if signed.iter().all(|&i| !v[i].is_negative()) {
            let z0 = t.z0();
            t.active[z0] = false;
            return None;
        }
        let z0 = t.z0();
        let col = Self::col(t, z0);
        // z0 enters at the most negative ratio; its column is -1 on the w rows
        let neg: Vec<BigInt> = col.iter().map(|c| -c).collect();
        let vneg: Vec<BigInt> = v.iter().map(|x| -x).collect();
        let r = signed
            .iter()
            .copied()
            .filter(|&i| v[i].is_negative() && neg[i].is_positive())
            .max_by(|&i, &j| self.cmp_rows(t, &vneg, &neg, i, j))
            .expect("a negative row");
        let mut leaving = t.basis[r];
        t.pivot(r, z0);
        self.pivots += 1;
        self.start_pivots += 1;
        let mut visits = Visits::default();
        loop {
            if self.pivots >= self.max_pivots {
                return Some((
                    Status::PivotLimit,
                    format!("pivot limit {} in the start phase", self.max_pivots),
                ));
            }
            let c = Self::complement_col(t, leaving).expect("a z or w left");
            if visits.visit(t, c, 0).is_some() {
                return Some((
                    Status::PivotLimit,
                    format!(
                        "the start phase at L0 = {} returned to a basis it had left (a cycle of degenerate pivots, which the lexicographic rule on the stored columns of B^-1 did not break): stopped after {} pivots",
                        super::short(&self.l0),
                        self.start_pivots
                    ),
                ));
            }
            let v = self.values_at_l0(t);
            let col = Self::col(t, c);
            let cand: Vec<usize> = (0..t.basis.len())
                .filter(|&i| t.signed(t.basis[i]) && col[i].is_positive())
                .collect();
            let Some(best) = cand
                .iter()
                .copied()
                .min_by(|&i, &j| self.cmp_rows(t, &v, &col, i, j))
            else {
                return Some((
                    Status::Infeasible,
                    format!(
                        "no solution found at L0 = {}: Lemke's start phase (covering vector of ones in the scaled rows) ended on a secondary ray in exact arithmetic (for copositive-plus M this proves that no solution exists)",
                        super::short(&self.l0)
                    ),
                ));
            };
            // ties go to z0 leaving
            let zrow = t.row_of(z0).expect("z0 basic");
            let r = if cand.contains(&zrow)
                && cmp_frac(&v[zrow], &col[zrow], &v[best], &col[best]) == Ordering::Equal
            {
                zrow
            } else {
                best
            };
            leaving = t.basis[r];
            t.pivot(r, c);
            self.pivots += 1;
            self.start_pivots += 1;
            if leaving == z0 {
                t.active[z0] = false;
                return None;
            }
        }
    }

    /// The second phase: `L` rises from `L0` (see the module documentation).
    fn parametric(&mut self, t: &mut Tableau) -> (Status, String) {
        let (num, den) = (self.l0.numer().clone(), self.l0.denom().clone());
        let (qc, dc, lam) = (t.qc(), t.dc(), t.lam());
        for row in t.rows.iter_mut() {
            let r = &row[qc] * &den + &row[dc] * &num;
            row[lam] = -&row[dc];
            row[qc] = r;
        }
        t.active[dc] = false;
        t.active[lam] = true;
        let den_r = BigRational::from_integer(den.clone());
        let mut entering = lam;
        let mut visits = Visits::default();
        loop {
            if self.pivots >= self.max_pivots {
                return (
                    Status::PivotLimit,
                    format!("pivot limit {} reached", self.max_pivots),
                );
            }
            if let Some(k) = visits.visit(t, entering, self.breakpoints.len()) {
                return self.closed(k);
            }
            let s = BigInt::from(t.sign());
            let absdet = t.det.abs();
            let v: Vec<BigInt> = t.rows.iter().map(|r| &r[qc] * &s).collect();
            let col = Self::col(t, entering);
            // dL~/dtheta, times |det|
            let dl = match t.row_of(lam) {
                None => absdet.clone(),
                Some(rl) => -&col[rl],
            };
            let cand: Vec<usize> = (0..t.basis.len())
                .filter(|&i| t.signed(t.basis[i]) && col[i].is_positive())
                .collect();
            let best = cand
                .iter()
                .copied()
                .min_by(|&i, &j| self.cmp_rows(t, &v, &col, i, j));
            // theta (as a fraction num/den with den > 0) of the blocking row
            let theta_row = best.map(|i| BigRational::new(v[i].clone(), col[i].clone()));
            // theta at which L reaches L_max
            let lmax_theta = match (&self.lambda_max, dl.is_positive()) {
                (Some(lm), true) => {
                    let target = (lm - &self.l0) * &den_r; // L~ at L_max
                    let cur = (&self.lambda - &self.l0) * &den_r;
                    Some(
                        (target - cur) * BigRational::from_integer(absdet.clone())
                            / BigRational::from_integer(dl.clone()),
                    )
                }
                _ => None,
            };
            let ends_at_max = match (&lmax_theta, &theta_row) {
                (Some(a), Some(b)) => a <= b,
                (Some(_), None) => true,
                _ => false,
            };
            let theta = if ends_at_max {
                lmax_theta.clone()
            } else {
                theta_row.clone()
            };
            // the new L
            let dlam_dtheta = BigRational::new(dl.clone(), absdet.clone() * &den);
            let next_lambda = theta.as_ref().map(|th| &self.lambda + th * &dlam_dtheta);
            if !dl.is_zero() && theta.as_ref().is_none_or(|th| !th.is_zero()) {
                self.record_segment(t, entering, &v, &col, &dl, next_lambda.as_ref());
            }
            let Some(theta) = theta else {
                // no block: a ray
                self.ray = Some(self.make_ray(t, entering, &col, &dl));
                return if dl.is_positive() {
                    if let Some(seg) = self.segments.last_mut() {
                        seg.unbounded = true;
                    }
                    (Status::UnboundedRay, String::new())
                } else {
                    (
                        Status::SecondaryRay,
                        format!(
                            "the path ends on a secondary ray at L = {} (exact): no solution beyond it on this path",
                            super::short(&self.lambda)
                        ),
                    )
                };
            };
            let next_lambda = next_lambda.expect("theta");
            if ends_at_max {
                self.lambda = next_lambda;
                return (Status::Reached, String::new());
            }
            let r = best.expect("a blocking row");
            let degenerate = theta.is_zero();
            if dl.is_negative() && self.rising && !degenerate {
                self.turning += 1;
            }
            let turning = dl.is_negative() && self.rising && !degenerate;
            if !degenerate && !dl.is_zero() {
                self.rising = dl.is_positive();
            }
            self.lambda = next_lambda;
            let leaving = t.basis[r];
            t.pivot(r, entering);
            self.pivots += 1;
            if degenerate {
                self.degenerate += 1;
            }
            // the float paths' convention: the variable that enters is the
            // leaving one's complement, which drives the next segment (the
            // column pivoted in here, `L` at the first breakpoint, is the
            // one that was moving)
            let next = Self::complement_col(t, leaving).unwrap_or(entering);
            self.breakpoints.push(Breakpoint {
                lambda: rational_to_f64(&self.lambda),
                entering: t.var_of(next).expect("a variable"),
                leaving: t.var_of(leaving).expect("a variable"),
                degenerate,
                turning,
                segment: self.segments.len(),
                residual: Residual::default(),
            });
            self.exact_bps.push(self.lambda.clone());
            entering = match Self::complement_col(t, leaving) {
                Some(c) => c,
                None => {
                    return (
                        Status::SecondaryRay,
                        format!(
                            "{} left the basis: no complementary driver",
                            t.var_of(leaving).expect("var")
                        ),
                    )
                }
            };
        }
    }

    /// The path came back to the state it had after `k` breakpoints: exact
    /// pivoting is deterministic, so it would repeat forever. A loop along
    /// which `L` moves is a closed curve of the path (possible when `M` is
    /// not a P-matrix: the solution set at one `L` is not a point): it passes
    /// through `L0` and never leaves `[min, max]` of its breakpoints, so the
    /// method cannot reach beyond (`secondary_ray`, no direction). A loop at
    /// constant `L` is a degenerate cycle (`pivot_limit`, said so).
    fn closed(&self, k: usize) -> (Status, String) {
        let lams = &self.exact_bps[k.min(self.exact_bps.len())..];
        let moved = lams.windows(2).any(|w| w[0] != w[1]);
        if !moved {
            return (
                Status::PivotLimit,
                format!(
                    "a cycle of degenerate pivots at L = {} (exact): the lexicographic rule on the stored columns of B^-1 did not break it",
                    super::short(&self.lambda)
                ),
            );
        }
        let hi = lams.iter().max().expect("two");
        let lo = lams.iter().min().expect("two");
        (
            Status::SecondaryRay,
            format!(
                "the path is a closed loop (exact): after {} breakpoints it returns to the basis it had after {k}, so Lemke's method from L0 = {} never leaves [{}, {}] (L = {:e} at most); no solution beyond that is reachable on this path",
                self.breakpoints.len(),
                super::short(&self.l0),
                super::short(lo),
                super::short(hi),
                rational_to_f64(hi)
            ),
        )
    }

    /// The values of `z`, `w`, `u` at the current vertex plus `theta` of
    /// column `entering`: as functions of `L`, value at the current `L` and
    /// slope (per unit of `L`; `dl = dL~/dtheta |det|`).
    #[allow(clippy::type_complexity)]
    fn values(
        &self,
        t: &Tableau,
        entering: usize,
        v: &[BigInt],
        col: &[BigInt],
        dl: &BigInt,
    ) -> (Vec<(BigRational, BigRational)>, Vec<BigRational>) {
        // variables of the tableau (u, z, w scaled) as (value, d/dtheta)
        let absdet = t.det.abs();
        let den = BigRational::from_integer(self.l0.denom().clone());
        let nv = t.p + 2 * t.n;
        let mut val = vec![(BigRational::zero(), BigRational::zero()); nv];
        for i in 0..t.basis.len() {
            let c = t.basis[i];
            if c < nv {
                val[c] = (
                    BigRational::new(v[i].clone(), absdet.clone()) / &den,
                    BigRational::new(-&col[i], absdet.clone()) / &den,
                );
            }
        }
        if entering < nv {
            val[entering].1 = BigRational::one() / &den;
        }
        // per unit of L: d/dtheta divided by dL/dtheta
        let dldt = BigRational::new(dl.clone(), absdet * self.l0.denom());
        let unscale = |c: usize| -> BigRational {
            if c >= t.p + t.n {
                let e = t.row_exp[c - t.n];
                if e >= 0 {
                    BigRational::from_integer(BigInt::one() << e as usize)
                } else {
                    BigRational::new(BigInt::one(), BigInt::one() << (-e) as usize)
                }
            } else {
                BigRational::one()
            }
        };
        let out: Vec<(BigRational, BigRational)> = val
            .into_iter()
            .enumerate()
            .map(|(c, (x, dx))| {
                let f = unscale(c);
                let slope = if dldt.is_zero() { dx } else { dx / &dldt };
                (x * &f, slope * &f)
            })
            .collect();
        (out, Vec::new())
    }

    fn record_segment(
        &mut self,
        t: &Tableau,
        entering: usize,
        v: &[BigInt],
        col: &[BigInt],
        dl: &BigInt,
        to: Option<&BigRational>,
    ) {
        let (vals, _) = self.values(t, entering, v, col, dl);
        let (p, n) = (self.p, self.n);
        let f = |k: usize, slope: bool| {
            let (x, d) = &vals[k];
            rational_to_f64(if slope { d } else { x })
        };
        let basis: Vec<Var> = (0..n)
            .map(|i| {
                let wc = p + n + i;
                if t.basic[wc] && t.row_of(wc).is_some() || entering == wc {
                    Var::W(i)
                } else {
                    Var::Z(i)
                }
            })
            .chain((0..p).map(Var::U))
            .collect();
        self.driver = Some(entering);
        self.segments.push(Segment {
            lambda_from: rational_to_f64(&self.lambda),
            lambda_to: to.map_or(f64::INFINITY, rational_to_f64),
            unbounded: false,
            basis,
            z_from: Col::from_fn(n, |i| f(p + i, false)),
            dz: Col::from_fn(n, |i| f(p + i, true)),
            w_from: Col::from_fn(n, |i| f(p + n + i, false)),
            dw: Col::from_fn(n, |i| f(p + n + i, true)),
            u_from: Col::from_fn(p, |j| f(j, false)),
            du: Col::from_fn(p, |j| f(j, true)),
        });
        self.exact_segments.push(ExactSegment {
            from: self.lambda.clone(),
            to: to.cloned(),
            vals,
        });
    }

    fn point(&self, t: &Tableau) -> Point<f64> {
        let qc = t.qc();
        let s = BigInt::from(t.sign());
        let v: Vec<BigInt> = t.rows.iter().map(|r| &r[qc] * &s).collect();
        let zero = vec![BigInt::zero(); t.basis.len()];
        let (vals, _) = self.values(t, t.lam(), &v, &zero, &BigInt::zero());
        let (p, n) = (self.p, self.n);
        Point {
            lambda: rational_to_f64(&self.lambda),
            z: Col::from_fn(n, |i| rational_to_f64(&vals[p + i].0)),
            w: Col::from_fn(n, |i| rational_to_f64(&vals[p + n + i].0)),
            u: Col::from_fn(p, |j| rational_to_f64(&vals[j].0)),
        }
    }

    fn make_ray(&self, t: &Tableau, entering: usize, col: &[BigInt], dl: &BigInt) -> Ray<f64> {
        let zero = vec![BigInt::zero(); t.basis.len()];
        let (vals, _) = self.values(t, entering, &zero, col, &BigInt::zero());
        let (p, n) = (self.p, self.n);
        Ray {
            start: self.point(t),
            dz: Col::from_fn(n, |i| rational_to_f64(&vals[p + i].1)),
            dw: Col::from_fn(n, |i| rational_to_f64(&vals[p + n + i].1)),
            du: Col::from_fn(p, |j| rational_to_f64(&vals[j].1)),
            dlambda: rational_to_f64(&BigRational::new(dl.clone(), t.det.abs() * self.l0.denom())),
        }
    }

    fn finish<T: Scalar>(
        self,
        problem: &Plcp<T>,
        t: &Tableau,
        status: Status,
        message: String,
        timer: Instant,
    ) -> ExactPath {
        // reached inside a segment: its driver is part-way, which the
        // tableau's basic values do not hold (a warm continuation's end at
        // L_max had residual 0.5): the end is the last segment there
        let end = match self.segments.last() {
            Some(s) if status == Status::Reached && s.contains(rational_to_f64(&self.lambda)) => {
                s.eval(rational_to_f64(&self.lambda))
            }
            _ => self.point(t),
        };
        let final_basis = (status == Status::Reached).then(|| {
            self.segments
                .last()
                .map(|s| s.basis.clone())
                .unwrap_or_else(|| {
                    (0..self.n)
                        .map(Var::W)
                        .chain((0..self.p).map(Var::U))
                        .collect()
                })
        });
        let lambda_reached = if status == Status::UnboundedRay {
            f64::INFINITY
        } else {
            rational_to_f64(&self.lambda)
        };
        let mut path = Path {
            status,
            lambda0: self.lambda0_t,
            lambda_max: problem.lambda_max().map(|l| l.to_f64()),
            lambda_reached,
            breakpoints: self.breakpoints,
            segments: self.segments,
            end,
            ray: self
                .ray
                .filter(|_| matches!(status, Status::UnboundedRay | Status::SecondaryRay)),
            message,
            info: Info {
                method: "lemke",
                precision: "exact",
                pivots: self.pivots,
                start_pivots: self.start_pivots,
                degenerate_pivots: self.degenerate,
                turning_points: self.turning,
                ..Info::default()
            },
            final_basis,
        };
        let f64_problem: Plcp<f64> = problem.cast();
        crate::residual::measure_path(&f64_problem, &mut path, true);
        path.info.solve_seconds = timer.elapsed().as_secs_f64();
        ExactPath {
            path,
            breakpoints: self.exact_bps,
            lambda_reached: self.lambda,
            exact_segments: self.exact_segments,
        }
    }
}
