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
//!
//! Where the float path steps over events closer than its rounding (two
//! variables reaching zero `1e-16` apart, taken as one degenerate breakpoint
//! with two pivots), `E_{k-1}` lies just outside `I_k`. The certificate then
//! follows the exact path from `S_{k-1}` at `E_{k-1}` by complementary pivots
//! (the variable reaching zero leaves, its complement enters) until it
//! reaches `S_k` inside `I_k`: a *bridge* of exact bases, each feasible on
//! its exact interval. A bridge is accepted only if it is unique at every
//! step (one variable reaching zero), at most [`MAX_BRIDGE`] bases, and
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

use super::solution::{Scaled, Solution};
use super::tableau::{col_of, Tableau};
use super::{rational_to_f64, rel_diff, short, to_rational};
use crate::path::{Path, Status, Var};
use crate::problem::Plcp;
use crate::scalar::Scalar;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};
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
                "certified: {} segments{}, exact breakpoints [{}], largest relative difference of the float breakpoints {:.1e}, {:.3} s",
                self.segments,
                self.bridge_note(),
                self.breakpoints.iter().map(short).collect::<Vec<_>>().join(", "),
                self.max_rel_diff,
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
            "breakpoints_f64": self.breakpoints.iter().map(rational_to_f64).collect::<Vec<_>>(),
            "max_rel_diff": self.max_rel_diff,
            "segments": self.segments,
            "pivots": self.pivots,
            "modular": self.modular,
            "bridges": self.bridges,
            "bridge_span": self.bridge_span,
            "reordered": self.reordered,
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

/// The exact interval `[lo, hi]` (`None`: unbounded that way) on which every
/// basic `z`, `w` is nonnegative, or the variable that is negative everywhere.
type Interval = (Option<BigRational>, Option<BigRational>);

fn interval(s: &Solution) -> Result<Interval, String> {
    // the roots -a_i / b_i compared by their numerators (the denominators are
    // common and positive), reduced once at the end
    let mut lo: Option<(&BigInt, &BigInt)> = None;
    let mut hi: Option<(&BigInt, &BigInt)> = None;
    // -a1/b1 > -a2/b2 for the numerators of two roots
    let greater = |x: (&BigInt, &BigInt), y: (&BigInt, &BigInt)| {
        let (l, r) = (-(x.0 * y.1), -(y.0 * x.1));
        // divide by b1 b2: keep the order when b1 b2 > 0
        if x.1.is_positive() == y.1.is_positive() {
            l > r
        } else {
            l < r
        }
    };
    for i in 0..s.basis.len() {
        let c = s.basis[i];
        let (a, b) = s.numerators(i);
        if c >= s.ncol() {
            // an artificial of a dependent equality row: the row must be 0 = 0
            if !a.is_zero() || !b.is_zero() {
                let (a, b) = s.affine(i);
                return Err(format!(
                    "equality row {} cannot hold with this basis (it reads 0 = {} + L {})",
                    c - s.ncol(),
                    short(&a.reduced()),
                    short(&b.reduced())
                ));
            }
            continue;
        }
        if !s.signed(c) {
            continue;
        }
        let var = s.var_of(c).expect("a z or w column");
        if b.is_zero() {
            if a.is_negative() {
                // the variable's own value, not its row's: the row is scaled
                // by a power of two (the rotated 3D run's w430 read -2.9e-4
                // for its value -1.6e-20)
                return Err(format!(
                    "{var} = {} < 0 for every L",
                    short(&s.value(c, &BigRational::zero()).reduced())
                ));
            }
        } else if b.is_positive() {
            if lo.is_none_or(|l| greater((a, b), l)) {
                lo = Some((a, b));
            }
        } else if hi.is_none_or(|h| greater(h, (a, b))) {
            hi = Some((a, b));
        }
    }
    let lo = lo.map(|(a, b)| s.root(a, b));
    let hi = hi.map(|(a, b)| s.root(a, b));
    if let (Some(l), Some(h)) = (&lo, &hi) {
        if l > h {
            return Err(format!(
                "no L makes the basis feasible (its variables need L >= {} and L <= {})",
                short(l),
                short(h)
            ));
        }
    }
    Ok((lo, hi))
}

/// Pivots the variables of `target` into the basis (each replacing a basic
/// variable outside `target`); those that cannot enter stay at zero.
fn pivot_to(t: &mut Tableau, target: &[usize], pivots: &mut usize) {
    let mut want = vec![false; t.ncol() + t.basis.len()];
    for &c in target {
        want[c] = true;
    }
    for &c in target {
        if t.basic[c] {
            continue;
        }
        let row = (0..t.basis.len())
            .filter(|&r| !want[t.basis[r]] && !t.rows[r][c].is_zero())
            .min_by_key(|&r| t.rows[r][c].bits());
        if let Some(r) = row {
            t.pivot(r, c);
            *pivots += 1;
        }
    }
}

/// `err <= limit`, false for NaN (an unmeasurable difference fails).
fn within(err: f64, limit: f64) -> bool {
    err <= limit
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

/// The value of the basic or nonbasic variable `v` at `lambda`.
fn value_at(t: &Solution, v: Var, lambda: &BigRational) -> BigRational {
    match t.col_of(v) {
        Some(c) => t.value(c, lambda),
        None => BigRational::zero(),
    }
}

/// The most exact bases a bridge may insert between two segments.
pub const MAX_BRIDGE: usize = 8;

/// The exact solution of the basis `target` (columns of the tableau): a
/// square basis by p-adic lifting; else (an artificial left in a dependent
/// row, three primes dividing `det B`) on the fraction-free tableau, which
/// handles every case.
fn solve_basis(
    scaled: &Scaled,
    fresh: &Tableau,
    tableau: &mut Option<Tableau>,
    engine: Engine,
    target: &[usize],
    cert: &mut Certificate,
    bareiss: &dyn Fn(&mut Certificate) -> (Tableau, usize),
) -> Solution {
    let modular = match engine {
        Engine::Modular => Solution::modular(scaled, fresh, target),
        Engine::Bareiss => None,
    };
    match modular {
        Some(s) => {
            cert.modular += 1;
            s
        }
        None => {
            let t = tableau.get_or_insert_with(|| bareiss(cert).0);
            pivot_to(t, target, &mut cert.pivots);
            Solution::from_tableau(t)
        }
    }
}

/// The exact path from basis `from` at `start` (where `from`'s interval
/// ends as `L` rises) to basis `to`, by complementary pivots: at each step
/// the one basic `z` or `w` that reaches zero there leaves and its
/// complement enters, and the new basis must be feasible where the step
/// starts. Returns the number of bases inserted and where `to` takes over,
/// or `None` (no bridge: the caller reports the gap) when a step is not
/// unique, a basis is singular or infeasible there, the span exceeds
/// `limit` relative to `max(1, |start|)`, or [`MAX_BRIDGE`] bases do not
/// reach `to`.
fn bridge(
    from: &[usize],
    to: &[usize],
    start: &BigRational,
    limit: f64,
    solve: &mut dyn FnMut(&[usize], &mut Certificate) -> Solution,
    cert: &mut Certificate,
) -> Option<(usize, BigRational)> {
    let same = |a: &[usize], b: &[usize]| {
        let (mut a, mut b) = (a.to_vec(), b.to_vec());
        a.sort_unstable();
        b.sort_unstable();
        a == b
    };
    let scale = rational_to_f64(start).abs().max(1.0);
    let (mut cur, mut at) = (from.to_vec(), start.clone());
    let mut s = solve(&cur, cert);
    for step in 0..=MAX_BRIDGE {
        // the basic z or w that reaches zero at `at` as L rises
        let mut leaving = (0..s.basis.len()).filter(|&i| {
            let c = s.basis[i];
            c < s.ncol() && s.signed(c) && {
                let (a, b) = s.affine(i);
                b.is_negative() && (a + b * &at).is_zero()
            }
        });
        let (Some(i), None) = (leaving.next(), leaving.next()) else {
            return None;
        };
        let out = s.basis[i];
        let into = s.var_of(out)?.complement().and_then(|v| s.col_of(v))?;
        let pos = cur.iter().position(|&c| c == out)?;
        cur[pos] = into;
        s = solve(&cur, cert);
        if !s.is_basic(into) {
            return None; // singular: the complement cannot enter
        }
        let (lo, hi) = interval(&s).ok()?;
        if lo.as_ref().is_some_and(|l| l > &at) || hi.as_ref().is_some_and(|h| h < &at) {
            return None;
        }
        if same(&cur, to) {
            return Some((step, at));
        }
        at = hi?;
        if !within(rational_to_f64(&(&at - start)).abs() / scale, limit) {
            return None;
        }
    }
    None
}

/// The exact solver of segment bases: the p-adic lifting, and the
/// fraction-free tableau brought to life only when a basis needs it.
struct Bases<'a, T: Scalar> {
    problem: &'a Plcp<T>,
    engine: Engine,
    fresh: Tableau,
    scaled: Scaled,
    tableau: Option<Tableau>,
}

impl<T: Scalar> Bases<'_, T> {
    /// The fraction-free tableau with the free variables pivoted in, and how
    /// many could not enter.
    fn bareiss(&self, cert: &mut Certificate) -> (Tableau, usize) {
        let mut t = Tableau::new(self.problem);
        let left = t.pivot_in_free();
        cert.pivots += self.problem.free() - left;
        (t, left)
    }

    /// The exact solution of the basis `target` ([`solve_basis`]).
    fn solve(&mut self, target: &[usize], cert: &mut Certificate) -> Solution {
        let Bases {
            problem,
            engine,
            fresh,
            scaled,
            tableau,
        } = self;
        let problem: &Plcp<T> = problem;
        let bareiss = |cert: &mut Certificate| -> (Tableau, usize) {
            let mut t = Tableau::new(problem);
            let left = t.pivot_in_free();
            cert.pivots += problem.free() - left;
            (t, left)
        };
        solve_basis(scaled, fresh, tableau, *engine, target, cert, &bareiss)
    }

    /// The fraction-free tableau, made on first use, pivoted to `target`.
    fn tableau_at(&mut self, target: &[usize], cert: &mut Certificate) -> Solution {
        if self.tableau.is_none() {
            self.tableau = Some(self.bareiss(cert).0);
        }
        let t = self.tableau.as_mut().expect("made");
        pivot_to(t, target, &mut cert.pivots);
        Solution::from_tableau(t)
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
}

fn run<T: Scalar>(
    problem: &Plcp<T>,
    path: &Path<T>,
    engine: Engine,
    cert: &mut Certificate,
) -> Result<(), Failure> {
    let p = problem.free();
    let fresh = Tableau::new(problem);
    let scaled = Scaled::new(&fresh);
    let mut bases = Bases {
        problem,
        engine,
        fresh,
        scaled,
        tableau: None,
    };
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
    };
    if path.segments.is_empty() {
        return end_point(path, &mut bases, &chain.start, cert);
    }
    for k in 0..path.segments.len() {
        segment(path, k, &mut bases, &mut chain, u_unique, cert)?;
    }
    path_end(path, &chain.start)
}

/// A path without segments claims a solution at `L0` only: certify the
/// basis of its end point (`z_i` basic where `z_i > w_i`).
fn end_point<T: Scalar>(
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
fn segment<T: Scalar>(
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
    Ok(())
}

/// Where the segment's interval misses the chain's start (as `L` rises),
/// follows the exact path from the previous segment's basis across the gap
/// ([`bridge`]) and moves the start to where this basis takes over.
fn bridge_to<T: Scalar>(
    bases: &mut Bases<'_, T>,
    chain: &mut Chain,
    target: &[usize],
    (lo, hi): (&Option<BigRational>, &Option<BigRational>),
    up: bool,
    cert: &mut Certificate,
) {
    let outside = |start: &BigRational| {
        lo.as_ref().is_some_and(|l| l > start) || hi.as_ref().is_some_and(|h| h < start)
    };
    if !outside(&chain.start) || !up {
        return;
    }
    let Some(prev) = &chain.prev_target else {
        return;
    };
    let limit = T::eps().to_f64().sqrt();
    let start = &chain.start;
    if let Some((n, at)) = bridge(
        prev,
        target,
        start,
        limit,
        &mut |b, c| bases.solve(b, c),
        cert,
    ) {
        if !outside(&at) {
            let span =
                rational_to_f64(&(&at - start)).abs() / rational_to_f64(start).abs().max(1.0);
            cert.bridges += n;
            cert.bridge_span = cert.bridge_span.max(span);
            chain.start = at;
        }
    }
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
    // precision's trust level (sqrt(eps), as the residual guard)
    let diff = rel_diff(end_float, e, &chain.start);
    if !within(diff, limit) && (!last || path.status.is_success()) {
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
fn path_end<T: Scalar>(path: &Path<T>, start: &BigRational) -> Result<(), Failure> {
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
