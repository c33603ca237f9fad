//! The direct certificate of a `secondary_ray` claim: the exact pivots at
//! `L*` and the exact ray, each basis solved by p-adic lifting (any order).
//!
//! # What is proven
//!
//! With `L` as a variable (its column `-d` in `A x - L d = q`, the rows scaled
//! to integers as everywhere in the certificate), the engines' `secondary_ray`
//! (`pivoting/trace.rs`, and the exact tracer, `exact/trace.rs`) is: an
//! almost-complementary basis `B` with `L` basic, feasible (every basic `z`,
//! `w` nonnegative) at `L*`, and a driver `e` (the complement of the variable
//! that left last, so that its pair has no basic member) whose column
//! `y = B^-1 A_e` blocks nothing, `x_B(t) = x_B - t y` for `t >= 0`: no basic
//! `z`, `w` has `y_r > 0`, and the rate of `L` along it, `-y_L`, is not
//! positive (zero: `L` stays at `L*`; negative: `L` falls without bound).
//! Every point of the ray is complementary (the driver's pair has only the
//! driver nonzero, every other pair one basic member) and feasible; Lemke's
//! method pivots again only where something blocks the driver, so it
//! follows the ray for ever, and `L` never rises along it: the path reaches
//! no `L` beyond `L*`.
//!
//! The certificate builds that basis from the last segment's complementary
//! basis `S` (certified by the segment checks, ending exactly at `L*`):
//!
//! 1. exactly one basic `z`, `w` of `S` reaches zero at `L*` in the segment's
//!    direction (`X0`; two at once are a tie whose order decides the path);
//! 2. `B = S - X0 + L`, driver the complement of `X0`; then, while the
//!    driver's column blocks: the least ratio must be attained by one row
//!    only (a forced pivot, the same under every tie rule, the exact
//!    tracer's lexicographic one included), and the step must leave `L` at
//!    `L*` (a zero step, or a rate of `L` exactly zero); that row leaves, the
//!    driver enters, the complement of the leaving variable drives next;
//! 3. at every basis the exact solution of `B x = q` has `L = L*` and every
//!    basic `z`, `w` nonnegative (checked, not assumed);
//! 4. the last driver's column blocks nothing and the rate of `L` is `<= 0`.
//!
//! Each basis costs one p-adic solve with two right-hand sides (`q` and the
//! driver's column), verified exactly (`B num = den b`): no tableau. A
//! driver whose column does not block while `L` rises is the path going on
//! as an unbounded ray, and a block reached while `L` moves is the path going
//! on to another breakpoint: the claim is wrong ([`Verdict::Wrong`]). A tie,
//! a basis the lifting does not solve (singular modulo the primes tried), a
//! last segment whose basis does not hold every free variable (Wolfe's long
//! form with free variables held at zero), or too many pivots at `L*` leave
//! the claim unproven ([`Verdict::Undecided`]): the caller may ask the exact
//! tracer where it applies, else the claim is not certified.
//!
//! Mixed problems: Lemke on the Schur reduction keeps every free variable
//! basic (its segments list `z` and `w` only; the certificate adds every
//! `u`), so its bases are square in `u`, `z`, `w`, `L`, and free variables,
//! unbounded in sign, never block. Wolfe's long form may hold free
//! variables at zero with the artificial of an equality row basic (any move
//! of such a row blocks, and an artificial that leaves starts Wolfe's
//! unlocking moves, which are not recorded in the path); a `secondary_ray`
//! of that kind, and the stall Wolfe reports with the same status (an
//! equality row blocks every move of `L`, `Path::ray` is `None`), is
//! undecided here unless the last segment's basis holds every free
//! variable.

use super::super::modular;
use super::super::short;
use super::super::solution::Solution;
use super::bases::Bases;
use crate::path::{Path, Var};
use crate::scalar::Scalar;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};
use std::cmp::Ordering;
use std::collections::HashSet;

/// Why the direct certificate does not certify a `secondary_ray`.
pub(super) enum Verdict {
    /// The exact path provably goes on: the claim is wrong.
    Wrong(String),
    /// Not proven either way by the direct certificate.
    Undecided(String),
}

/// What the direct certificate proved.
pub(super) struct Proven {
    /// Pivots at `L*` after the last segment (the first is its leaving
    /// variable's).
    pub pivots: usize,
    /// The driver of the ray.
    pub driver: Var,
    /// The exact rate of `L` along the ray, per unit of the driver (`<= 0`).
    pub rate: BigRational,
}

/// The direct certificate (see the module documentation) of the path's
/// `secondary_ray` at `end = L*`, from `last`, the exact solution of the last
/// segment's basis. At most `max_pivots` pivots at `L*`.
pub(super) fn direct<T: Scalar>(
    path: &Path<T>,
    bases: &Bases<'_, T>,
    last: &Solution,
    end: &BigRational,
    max_pivots: usize,
) -> Result<Proven, Verdict> {
    let (p, n) = (last.p, last.n);
    let dim = p + n;
    let lam = p + 2 * n + 1;
    let seg = path.segments.last().expect("a last segment");
    if last.basis.len() != dim || last.basis.iter().any(|&c| c >= lam) {
        return Err(Verdict::Undecided(format!(
            "the last segment's basis does not hold every free variable ({} of {p} basic, the others held at zero by equality rows)",
            last.basis.iter().filter(|&&c| c < p).count()
        )));
    }
    // 1. the variable that reaches zero at L*, in the segment's direction
    let up = seg.lambda_to >= seg.lambda_from;
    let falling = if up { -1 } else { 1 };
    let zero: Vec<usize> = (0..dim)
        .filter(|&i| last.signed(last.basis[i]))
        .filter(|&i| last.sign_at(i, end) == 0 && last.slope_sign(i) == falling)
        .collect();
    let name = |c: usize| {
        last.var_of(c)
            .map_or_else(|| format!("column {c}"), |v| v.to_string())
    };
    let x0 = match zero[..] {
        [i] => last.basis[i],
        [] => {
            return Err(Verdict::Undecided(format!(
                "no basic variable of the last segment reaches zero at L* = {}",
                short(end)
            )))
        }
        _ => {
            return Err(Verdict::Undecided(format!(
                "{} reach zero together at L* = {} (a tie: which leaves decides the path)",
                zero.iter()
                    .map(|&i| name(last.basis[i]))
                    .collect::<Vec<_>>()
                    .join(", "),
                short(end)
            )))
        }
    };
    // 2. the pivots at L*
    let complement = |c: usize| {
        last.var_of(c)
            .and_then(Var::complement)
            .and_then(|v| last.col_of(v))
    };
    let mut basis: Vec<usize> = last.basis.clone();
    let r0 = basis.iter().position(|&c| c == x0).expect("basic");
    basis[r0] = lam;
    let mut driver = complement(x0).expect("a z or w");
    let mut seen: HashSet<(Vec<usize>, usize)> = HashSet::new();
    let scaled = &bases.scaled;
    for pivots in 1.. {
        if pivots > max_pivots {
            return Err(Verdict::Undecided(format!(
                "more than {max_pivots} pivots at L* = {}",
                short(end)
            )));
        }
        let mut key = basis.clone();
        key.sort_unstable();
        if !seen.insert((key, driver)) {
            return Err(Verdict::Undecided(format!(
                "the pivots at L* = {} come back to a basis (a cycle)",
                short(end)
            )));
        }
        check_structure(&basis, driver, p, n, lam)?;
        let cols: Vec<Vec<(usize, BigInt)>> = basis
            .iter()
            .map(|&c| scaled.column(c, lam).expect("a stored column or L"))
            .collect();
        let mut a_e = vec![BigInt::zero(); dim];
        for (i, v) in scaled.column(driver, lam).expect("z or w") {
            a_e[i] = v;
        }
        let Some(mut sol) = modular::solve(&cols, &[scaled.q().to_vec(), a_e]) else {
            return Err(Verdict::Undecided(format!(
                "a basis at L* = {} is singular modulo the primes tried (or the lifting failed)",
                short(end)
            )));
        };
        let (y, dy) = sol.pop().expect("two");
        let (x, dx) = sol.pop().expect("two");
        // 3. the basic solution is the point at L*, feasible
        let rl = basis.iter().position(|&c| c == lam).expect("L basic");
        let at = BigRational::new(x[rl].clone(), dx.clone());
        if &at != end {
            return Err(Verdict::Undecided(format!(
                "the basis after {pivots} pivots puts L at {}, not at L* = {}",
                short(&at),
                short(end)
            )));
        }
        let signed = |c: usize| c >= p && c < p + 2 * n;
        if let Some(r) = (0..dim).find(|&r| signed(basis[r]) && x[r].is_negative()) {
            return Err(Verdict::Undecided(format!(
                "{} < 0 at L* = {} in the basis after {pivots} pivots",
                name(basis[r]),
                short(end)
            )));
        }
        // the rate of L along the driver: -y_L (dy > 0)
        let rate = BigRational::new(-y[rl].clone(), dy.clone());
        // the blocking rows and the least ratio x_r / y_r (common positive
        // denominators: compared by numerators)
        let block: Vec<usize> = (0..dim)
            .filter(|&r| signed(basis[r]) && y[r].is_positive())
            .collect();
        let least = |a: usize, b: usize| (&x[a] * &y[b]).cmp(&(&x[b] * &y[a]));
        let Some(best) = block.iter().copied().min_by(|&a, &b| least(a, b)) else {
            // 4. the ray (its rate per unit of the driver itself)
            let rate = last.per_unit(driver, rate);
            if rate.is_positive() {
                return Err(Verdict::Wrong(format!(
                    "ends unbounded_ray as L rises to infinity: after {pivots} exact pivots at L*, the column of {} blocks nothing and L rises along it at rate {}",
                    name(driver),
                    short(&rate)
                )));
            }
            return Ok(Proven {
                pivots,
                driver: last.var_of(driver).expect("z or w"),
                rate,
            });
        };
        let ties: Vec<usize> = block
            .iter()
            .copied()
            .filter(|&r| least(r, best) == Ordering::Equal)
            .collect();
        let theta_zero = x[best].is_zero();
        if !theta_zero && !rate.is_zero() {
            // the driver moves by x/y (in its own units: dx, dy apart)
            let theta = BigRational::new(x[best].clone() * &dy, y[best].clone() * &dx);
            let to = end + &rate * theta;
            let rate = last.per_unit(driver, rate);
            return Err(Verdict::Wrong(format!(
                "goes on: after {pivots} exact pivots at L*, {} blocks the column of {} only at L = {} (rate of L {})",
                name(basis[best]),
                name(driver),
                short(&to),
                short(&rate)
            )));
        }
        if ties.len() > 1 {
            return Err(Verdict::Undecided(format!(
                "after {pivots} pivots at L* = {}, {} block the column of {} together (a tie: which leaves decides the path)",
                short(end),
                ties.iter()
                    .map(|&r| name(basis[r]))
                    .collect::<Vec<_>>()
                    .join(", "),
                name(driver)
            )));
        }
        let leaving = basis[best];
        basis[best] = driver;
        driver = complement(leaving).expect("a z or w leaves");
    }
    unreachable!("the loop returns")
}

/// The basis holds `L`, every free variable, one member of every pair but
/// the driver's, and nothing of the driver's pair.
fn check_structure(
    basis: &[usize],
    driver: usize,
    p: usize,
    n: usize,
    lam: usize,
) -> Result<(), Verdict> {
    let mut pair = vec![0u8; n];
    let mut free = 0;
    let mut l = 0;
    for &c in basis {
        if c < p {
            free += 1;
        } else if c < p + 2 * n {
            pair[(c - p) % n] += 1;
        } else if c == lam {
            l += 1;
        }
    }
    let dp = (driver - p) % n;
    let ok = free == p
        && l == 1
        && pair
            .iter()
            .enumerate()
            .all(|(i, &k)| k == u8::from(i != dp));
    if ok {
        Ok(())
    } else {
        Err(Verdict::Undecided(
            "internal: a basis at L* is not almost complementary".into(),
        ))
    }
}
