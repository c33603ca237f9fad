//! The exact solutions of segment bases: p-adic lifting, or the
//! fraction-free tableau where a basis needs it.

use super::super::solution::{Scaled, Solution};
use super::super::tableau::Tableau;
use super::{Certificate, Engine};
use crate::problem::Plcp;
use crate::scalar::Scalar;
use num_traits::Zero;

/// The exact solution of the basis `target` (columns of the tableau): a
/// square basis by p-adic lifting; else (an artificial left in a dependent
/// row, three primes dividing `det B`) on the fraction-free tableau, which
/// handles every case.
fn solve_basis<T: Scalar>(
    problem: &Plcp<T>,
    scaled: &Scaled,
    fresh: &Tableau,
    tableau: &mut Option<Tableau>,
    engine: Engine,
    target: &[usize],
    cert: &mut Certificate,
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
            let t = tableau.get_or_insert_with(|| fraction_free(problem, cert).0);
            pivot_to(t, target, &mut cert.pivots);
            Solution::from_tableau(t)
        }
    }
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

/// The exact solver of segment bases: the p-adic lifting, and the
/// fraction-free tableau brought to life only when a basis needs it.
pub(super) struct Bases<'a, T: Scalar> {
    pub(super) problem: &'a Plcp<T>,
    engine: Engine,
    fresh: Tableau,
    pub(super) scaled: Scaled,
    pub(super) tableau: Option<Tableau>,
}

/// The fraction-free tableau of `problem` with the free variables pivoted
/// in, and how many could not enter.
fn fraction_free<T: Scalar>(problem: &Plcp<T>, cert: &mut Certificate) -> (Tableau, usize) {
    let mut t = Tableau::new(problem);
    let left = t.pivot_in_free();
    cert.pivots += problem.free() - left;
    (t, left)
}

impl<'a, T: Scalar> Bases<'a, T> {
    /// The solver for `problem`'s bases, with no fraction-free tableau yet.
    pub(super) fn new(problem: &'a Plcp<T>, engine: Engine) -> Self {
        let fresh = Tableau::new(problem);
        let scaled = Scaled::new(&fresh);
        Bases {
            problem,
            engine,
            fresh,
            scaled,
            tableau: None,
        }
    }

    /// The fraction-free tableau with the free variables pivoted in, and how
    /// many could not enter.
    pub(super) fn bareiss(&self, cert: &mut Certificate) -> (Tableau, usize) {
        fraction_free(self.problem, cert)
    }

    /// The exact solution of the basis `target` ([`solve_basis`]).
    pub(super) fn solve(&mut self, target: &[usize], cert: &mut Certificate) -> Solution {
        solve_basis(
            self.problem,
            &self.scaled,
            &self.fresh,
            &mut self.tableau,
            self.engine,
            target,
            cert,
        )
    }

    /// The fraction-free tableau, made on first use, pivoted to `target`.
    pub(super) fn tableau_at(&mut self, target: &[usize], cert: &mut Certificate) -> Solution {
        if self.tableau.is_none() {
            self.tableau = Some(self.bareiss(cert).0);
        }
        let t = self.tableau.as_mut().expect("made");
        pivot_to(t, target, &mut cert.pivots);
        Solution::from_tableau(t)
    }
}
