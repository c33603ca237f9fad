//! Statically admissible stress states, for the pieces of the path where the
//! member forces are not unique.
//!
//! There the solver holds one stress state among many, and a hinge that has
//! flowed may appear to leave yield only because of that choice (system (9)
//! asks `y*' x*_dd = 0`, not `y* = 0` where the plastic rate is positive). Before a
//! deactivation is reported, a linear feasibility problem asks whether some
//! stress state keeps every flowed section at yield:
//!
//! ```text
//! find X:   A^T X = a_o Lambda - M_q q_dd(Lambda)       (dynamic equilibrium)
//!           y*_k = X*_k - (T N)_k' X = 0   for the mode each flowed section flowed on
//!           y*_k >= 0                      for every yield mode
//! ```
//!
//! asked at the ends of the piece; the feasible set moves affinely with
//! `Lambda`, so feasibility at both ends holds in between.
//!
//! **Solved by plcp** (an LP is an LCP), as its smallest violation: every row
//! `a_i' X = b_i` or `a_i' X <= b_i` scaled to `max_r |a_ir| = 1`, and the
//! unknowns and right-hand sides divided by `S = max_i |b_i|` (at least the
//! largest capacity), the LP
//!
//! ```text
//! min t   s.t.   |a_i' X - b_i| <= t  (equalities),   a_i' X - b_i <= t  (inequalities),
//!                X = X+ - X-,   X+, X-, t >= 0
//! ```
//!
//! is always feasible and bounded below by zero, so its KKT system, the LCP
//! `w = [c; -b] + [[0, -C'], [C, 0]] [x; y]` (`min c'x, C x >= b, x >= 0`,
//! `M` skew-symmetric hence copositive-plus), has a solution that Lemke's method
//! with a covering vector finds ([`plcp::solve_lcp`], plcp's default block
//! basis: a dense one is 20 % cheaper at order 113 but about 6 times slower
//! over the tests' larger LPs). The answer is `true`
//! when the `X` it returns violates no row by more than [`FEASIBLE_TOL`]
//! (measured here on the rows, not taken from the solver: `X` is the
//! witness), `false` when the smallest violation `t*` is at least
//! [`INFEASIBLE_TOL`], and `None` otherwise (a status other than `reached`,
//! or a violation between the two). The caller reads `None` as `false`: a
//! deactivation is reported unless a stress state is found.
//!
//! A phase-1 LP rather than `min 0` (whose secondary ray would prove
//! infeasibility) because the equilibrium rows and the pinned modes together
//! are often dependent, with a right-hand side consistent only to rounding:
//! `min 0` would read that rounding as infeasibility, exactly or not, where
//! `t* = 1e-16` says "feasible" with a margin to read.

use crate::assemble::System;
use faer::{Col, Mat};
use plcp::{Lcp, Settings, Status};

/// Largest violation of a scaled row (see the module documentation) by the
/// witness stress state for which the LP reads as feasible: `1e7 eps`, far
/// above the rounding of a consistent system (`1e-16` times the condition of
/// the rows, `1e4` on `scenes/stiff/lengths-portal.toml`).
pub const FEASIBLE_TOL: f64 = 1e-9;

/// Smallest violation `t*` of a scaled row that reads as infeasible: the
/// order of the feasibility tolerance (`1e-8`) of Clarabel, which decided
/// this LP before plcp did, so the decisions stay where they were. A
/// violation between [`FEASIBLE_TOL`] and this is undecided (`None`).
pub const INFEASIBLE_TOL: f64 = 1e-8;

/// The LP's rows, each scaled to `max_r |a_ir| = 1`, right-hand sides
/// divided by `S`: equalities first (`eq` of them), then the yield modes.
struct Rows {
    a: Vec<Vec<f64>>,
    b: Vec<f64>,
    eq: usize,
}

impl Rows {
    fn new(system: &System, rhs: &[f64], pinned: &[usize]) -> Rows {
        let (ns, np) = (system.forces.len(), system.modes.len());
        let mut rows = Rows {
            a: Vec::new(),
            b: Vec::new(),
            eq: 0,
        };
        // X = C X~: each member force in units of the capacity it yields at
        let mut c = vec![0.0f64; ns];
        for k in 0..np {
            for (r, c) in c.iter_mut().enumerate() {
                let t = system.tn[(r, k)].abs();
                if t > 0.0 {
                    *c = c.max(system.capacities[k].abs() / t);
                }
            }
        }
        c.iter_mut()
            .filter(|c| !(**c > 0.0 && c.is_finite()))
            .for_each(|c| *c = 1.0);
        // equilibrium rows: A^T C X~ = rhs
        for (j, &rj) in rhs.iter().enumerate().take(system.coordinates.len()) {
            rows.push((0..ns).map(|r| system.a[(r, j)] * c[r]).collect(), rj);
        }
        let mode = |k: usize| {
            (0..ns)
                .map(|r| system.tn[(r, k)] * c[r])
                .collect::<Vec<f64>>()
        };
        for &k in pinned.iter().filter(|&&k| k < np) {
            rows.push(mode(k), system.capacities[k]);
        }
        rows.eq = rows.a.len();
        for k in 0..np {
            rows.push(mode(k), system.capacities[k]);
        }
        rows
    }

    fn push(&mut self, mut a: Vec<f64>, mut b: f64) {
        let norm = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if norm > 0.0 {
            a.iter_mut().for_each(|v| *v /= norm);
            b /= norm;
        }
        self.a.push(a);
        self.b.push(b);
    }

    /// The largest violation of any row by `x`.
    fn violation(&self, x: &[f64]) -> f64 {
        let mut v = 0.0f64;
        for (i, (a, b)) in self.a.iter().zip(&self.b).enumerate() {
            let r = a.iter().zip(x).map(|(a, x)| a * x).sum::<f64>() - b;
            v = v.max(if i < self.eq { r.abs() } else { r });
        }
        v
    }

    /// The LCP of the smallest-violation LP: `z = [X+, X-, t, y]`.
    fn lcp(&self) -> (Mat<f64>, Col<f64>) {
        let ns = self.a.first().map_or(0, Vec::len);
        let nx = 2 * ns + 1;
        // C x >= b: two rows per equality (b - a'X + t >= 0, a'X - b + t >= 0),
        // one per inequality (b - a'X + t >= 0)
        let mut c_rows: Vec<(f64, usize)> = Vec::new();
        for i in 0..self.a.len() {
            c_rows.push((-1.0, i));
            if i < self.eq {
                c_rows.push((1.0, i));
            }
        }
        let n = nx + c_rows.len();
        let mut m = Mat::<f64>::zeros(n, n);
        let mut q = Col::<f64>::zeros(n);
        q[2 * ns] = 1.0;
        for (k, &(sign, i)) in c_rows.iter().enumerate() {
            let row = nx + k;
            for (r, &v) in self.a[i].iter().enumerate() {
                if v != 0.0 {
                    m[(row, r)] = sign * v;
                    m[(row, ns + r)] = -sign * v;
                    m[(r, row)] = -sign * v;
                    m[(ns + r, row)] = sign * v;
                }
            }
            m[(row, 2 * ns)] = 1.0;
            m[(2 * ns, row)] = -1.0;
            q[row] = -sign * self.b[i];
        }
        (m, q)
    }
}

/// Whether a stress state exists in equilibrium with `rhs` (`a_o Lambda - M_q
/// q_dd`), within yield everywhere and at yield on every `pinned` mode
/// (indices into [`System::modes`]). `None` if plcp could not decide (see the
/// module documentation).
pub fn admissible_with(system: &System, rhs: &[f64], pinned: &[usize]) -> Option<bool> {
    #[cfg(test)]
    tests::ASKED.with(|a| a.borrow_mut().push((rhs.to_vec(), pinned.to_vec())));
    let rows = Rows::new(system, rhs, pinned);
    let ns = system.forces.len();
    let (m, q) = rows.lcp();
    let lcp = Lcp::new(m.as_ref(), q.as_ref()).ok()?;
    let sol = plcp::solve_lcp(&lcp, &Settings::default()).ok()?;
    if sol.status != Status::Reached {
        return None;
    }
    let x: Vec<f64> = (0..ns).map(|r| sol.z[r] - sol.z[ns + r]).collect();
    if rows.violation(&x) <= FEASIBLE_TOL {
        Some(true)
    } else if sol.z[2 * ns] >= INFEASIBLE_TOL {
        Some(false)
    } else {
        None
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use std::cell::RefCell;

    thread_local! {
        /// The questions asked of [`admissible_with`] on this thread.
        pub(crate) static ASKED: RefCell<Vec<(Vec<f64>, Vec<usize>)>> =
            const { RefCell::new(Vec::new()) };
    }

    /// The same LP by Clarabel (interior point), the solver this module used
    /// before: the independent reference.
    fn clarabel_admissible(system: &System, rhs: &[f64], pinned: &[usize]) -> Option<bool> {
        use clarabel::algebra::CscMatrix;
        use clarabel::solver::{
            DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
            SupportedConeT, ZeroConeT,
        };
        let (nb, ns, np) = (
            system.coordinates.len(),
            system.forces.len(),
            system.modes.len(),
        );
        let (mut ii, mut jj, mut vv) = (Vec::new(), Vec::new(), Vec::new());
        let mut b = Vec::new();
        for (j, &rj) in rhs.iter().enumerate().take(nb) {
            for r in 0..ns {
                let v = system.a[(r, j)];
                if v != 0.0 {
                    ii.push(j);
                    jj.push(r);
                    vv.push(v);
                }
            }
            b.push(rj);
        }
        let mut row = nb;
        let mode_row =
            |row: usize, k: usize, ii: &mut Vec<usize>, jj: &mut Vec<usize>, vv: &mut Vec<f64>| {
                for r in 0..ns {
                    let v = system.tn[(r, k)];
                    if v != 0.0 {
                        ii.push(row);
                        jj.push(r);
                        vv.push(v);
                    }
                }
            };
        for &k in pinned.iter().filter(|&&k| k < np) {
            mode_row(row, k, &mut ii, &mut jj, &mut vv);
            b.push(system.capacities[k]);
            row += 1;
        }
        let zero_rows = row;
        for k in 0..np {
            mode_row(row, k, &mut ii, &mut jj, &mut vv);
            b.push(system.capacities[k]);
            row += 1;
        }
        let a = CscMatrix::new_from_triplets(row, ns, ii, jj, vv);
        let p = CscMatrix::<f64>::zeros((ns, ns));
        let q = vec![0.0; ns];
        let cones: Vec<SupportedConeT<f64>> =
            vec![ZeroConeT(zero_rows), NonnegativeConeT(row - zero_rows)];
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .max_iter(200)
            .build()
            .ok()?;
        let mut solver = DefaultSolver::new(&p, &q, &a, &b, &cones, settings).ok()?;
        solver.solve();
        match solver.solution.status {
            SolverStatus::Solved | SolverStatus::AlmostSolved => Some(true),
            SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => Some(false),
            _ => None,
        }
    }

    fn scene_files() -> Vec<std::path::PathBuf> {
        fn walk(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
            for e in std::fs::read_dir(dir).unwrap() {
                let p = e.unwrap().path();
                if p.is_dir() {
                    walk(&p, out);
                } else if p.extension().is_some_and(|x| x == "toml") {
                    out.push(p);
                }
            }
        }
        let mut out = Vec::new();
        walk(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes"),
            &mut out,
        );
        out.sort();
        out
    }

    fn analyse(path: &std::path::Path) -> crate::Analysis {
        let scene = crate::Scene::from_file(path).unwrap();
        crate::Analysis::run(scene, &crate::AnalysisOptions::default()).unwrap()
    }

    /// Every LP the hinge reading asks on every scene in `scenes/`, and on
    /// every scene the static ones (`rhs = a_o Lambda`, none or one of the
    /// first 12 modes pinned) at four `Lambda` from 0 to twice the first
    /// critical load: plcp decides each as Clarabel does, or (only on the
    /// determinate, ill-conditioned `stiff/stiffest-cantilever.toml`, where
    /// Clarabel's absolute tolerances read a violation of `1e-6` against
    /// capacities of `1e6` as none) leaves it undecided. It never
    /// contradicts Clarabel.
    #[test]
    fn plcp_decides_as_clarabel_on_every_scene() {
        let (mut asked, mut total, mut feasible, mut undecided) = (0, 0, 0, 0);
        let files = scene_files();
        assert!(files.len() >= 23, "{} scenes", files.len());
        for path in &files {
            ASKED.with(|a| a.borrow_mut().clear());
            let a = analyse(path);
            let mut lps = ASKED.with(|a| std::mem::take(&mut *a.borrow_mut()));
            let n_asked = lps.len();
            asked += n_asked;
            let sys = &a.system;
            let first = a.reading.hinges.first().map_or(1.0, |h| h.lambda);
            for l in [0.0, 0.5 * first, first, 2.0 * first] {
                let rhs: Vec<f64> = sys.load.iter().map(|a| a * l).collect();
                lps.push((rhs.clone(), vec![]));
                for k in 0..sys.modes.len().min(12) {
                    lps.push((rhs.clone(), vec![k]));
                }
            }
            for (i, (rhs, pinned)) in lps.iter().enumerate() {
                let ours = admissible_with(sys, rhs, pinned);
                let theirs = clarabel_admissible(sys, rhs, pinned);
                let what = format!("{} LP {i} pinned {pinned:?}", path.display());
                assert!(theirs.is_some(), "{what}: Clarabel undecided");
                if ours.is_none() {
                    assert!(i >= n_asked, "{what}: asked by the reading, undecided");
                    assert!(path.ends_with("stiff/stiffest-cantilever.toml"), "{what}");
                    undecided += 1;
                } else {
                    assert_eq!(ours, theirs, "{what}");
                }
                total += 1;
                feasible += usize::from(ours == Some(true));
            }
        }
        // the hinge reading asks on the indeterminate scenes, and both answers occur
        assert!(asked > 0 && feasible > 0 && feasible + undecided < total);
        assert!(undecided <= 12, "{undecided} undecided");
        eprintln!(
            "{total} LPs ({asked} asked by the hinge reading), {feasible} feasible, {undecided} undecided"
        );
    }

    /// A determinate frame at `Lambda = 0`: the only stress state is zero, so
    /// no mode can be pinned at yield. Clarabel reads `1e-6` against `1e6` as
    /// zero and answers `true` on `stiffest-cantilever`; plcp must not.
    #[test]
    fn determinate_frame_at_rest_has_no_mode_at_yield() {
        for name in [
            "stiff/stiffest-cantilever.toml",
            "cantilever.toml",
            "fixed-beam.toml",
        ] {
            let a = analyse(
                &std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                    .join("../scenes")
                    .join(name),
            );
            let sys = &a.system;
            let rhs = vec![0.0; sys.coordinates.len()];
            assert_eq!(admissible_with(sys, &rhs, &[]), Some(true), "{name}");
            for k in 0..sys.modes.len() {
                let ours = admissible_with(sys, &rhs, &[k]);
                if sys.is_determinate() {
                    assert_ne!(ours, Some(true), "{name} mode {k}");
                } else {
                    assert_eq!(
                        ours,
                        clarabel_admissible(sys, &rhs, &[k]),
                        "{name} mode {k}"
                    );
                }
            }
        }
    }

    /// A one-bar frame: the rows of a known small LP, by hand.
    fn rows(a: Vec<Vec<f64>>, b: Vec<f64>, eq: usize) -> Rows {
        let mut r = Rows {
            a: Vec::new(),
            b: Vec::new(),
            eq,
        };
        for (a, b) in a.into_iter().zip(b) {
            r.push(a, b);
        }
        r
    }

    fn decide(r: &Rows) -> (Status, f64, f64) {
        let ns = r.a[0].len();
        let (m, q) = r.lcp();
        let sol = plcp::solve_lcp(
            &Lcp::new(m.as_ref(), q.as_ref()).unwrap(),
            &Settings::default(),
        )
        .unwrap();
        let x: Vec<f64> = (0..ns).map(|i| sol.z[i] - sol.z[ns + i]).collect();
        (sol.status, r.violation(&x), sol.z[2 * ns])
    }

    #[test]
    fn known_feasible_and_infeasible_lps() {
        // x1 + x2 = 2, |x1| <= 1, |x2| <= 1: feasible only at (1, 1)
        let a = vec![
            vec![1.0, 1.0],
            vec![1.0, 0.0],
            vec![-1.0, 0.0],
            vec![0.0, 1.0],
            vec![0.0, -1.0],
        ];
        let (s, v, _) = decide(&rows(a.clone(), vec![2.0, 1.0, 1.0, 1.0, 1.0], 1));
        assert_eq!(s, Status::Reached);
        assert!(v <= FEASIBLE_TOL, "{v}");
        // x1 + x2 = 3: the smallest violation is 1/3 (at x = (4/3, 4/3))
        let (s, v, t) = decide(&rows(a.clone(), vec![3.0, 1.0, 1.0, 1.0, 1.0], 1));
        assert_eq!(s, Status::Reached);
        assert!(
            (t - 1.0 / 3.0).abs() < 1e-12 && (v - t).abs() < 1e-12,
            "{t} {v}"
        );
        // dependent equalities consistent to rounding: x1 + x2 = 0.3, 3 x1 + 3 x2 = 0.9
        let a2 = vec![
            vec![1.0, 1.0],
            vec![3.0, 3.0],
            vec![1.0, 0.0],
            vec![0.0, 1.0],
        ];
        let (s, v, _) = decide(&rows(a2, vec![0.1 + 0.2, 0.9, 1.0, 1.0], 2));
        assert_eq!(s, Status::Reached);
        assert!(v <= FEASIBLE_TOL, "{v}");
    }
}
