//! Mixed PLCPs (free variables): Wolfe's long form against Lemke on the Schur
//! reduction, and against an independent QP solver (Clarabel).
//!
//! Random convex parametric QPs with equality constraints,
//!
//! ```text
//! minimise 1/2 x'Hx + (c + L e)'x   subject to  A x = b + L b_d,  x_J >= 0,
//! ```
//!
//! `x = (x_f, z)` (free primal variables, then the bounded ones), `H = B B'`
//! positive semidefinite and singular, give the mixed PLCP with free variables
//! `u = (x_f, y)` (`y` the equality multipliers) and complementary pairs `(z, w)`:
//!
//! ```text
//! M = [[ H_ff, A_f', H_fz],      q = (c_f, b, c_z),   d = (e_f, b_d, e_z),
//!      [-A_f,  0,   -A_z],
//!      [ H_zf, A_z', H_zz]]
//! ```
//!
//! (the equality rows negated so that `M` is monotone: its symmetric part is
//! `diag(H)`-shaped and PSD). The free block is `[[H_ff, A_f'], [-A_f, 0]]`;
//! it is singular when `A` has a dependent row (multipliers not unique), when `A`
//! has more rows than there are free primal variables (as in system (9) of an
//! indeterminate frame), or when a free primal variable appears nowhere (its value
//! is not unique). Variants with `H_zz = H_fz = 0` (the bounded variables enter
//! linearly, as the plastic multipliers of system (9)) are included.
//!
//! Checks (all data dyadic, so every precision solves the same problem):
//!
//! * nonsingular free block: Wolfe and Lemke-on-the-reduction return the same
//!   status, and where the solution is unique (reduced matrix positive definite)
//!   the same breakpoints and the same `u, z, w` at every segment end and interior
//!   point; otherwise the same `w` (unique: the reduced matrix is symmetric PSD).
//!   Tolerance in f64: 1e-10 relative (to `max(1, |.|_inf)`).
//! * singular free block: Lemke returns `Err(SingularFreeBlock { p, rank })` with
//!   the rank computed here; Wolfe reports that rank, `p - rank` nonbasic free
//!   variables and `p - rank` dependent rows.
//! * every Wolfe path: residuals (equation, feasibility, complementarity) below
//!   the stated tolerance at every checked point, and the primal solution at those
//!   points agrees with Clarabel (gap and feasibility tolerances 1e-11): the
//!   objective to 1e-6 relative, `H x` to 1e-4 (both unique for a convex QP), `x`
//!   itself to 1e-4 where `H` is positive definite on the null space of `A` with
//!   curvature >= 1e-2 (unique and well determined `x`). A path that stops must be
//!   right to: Clarabel finds the QP unbounded just beyond the stop.
//! * proptest on random monotone mixed PLCPs `B B' + S + I/8` (not of KKT form):
//!   Lemke's path against enumeration of the complementary bases with the free
//!   variables solved for; Wolfe, which claims monotone problems, must succeed
//!   and agree.
//! * f32 (agreement 2e-3, residual 1e-3, Clarabel 2e-3) and fx128 (agreement
//!   1e-22, residual 2e-27 (the same multiple of eps as f64's 1e-11), Clarabel as f64).
//!
//! The residual, forward and agreement tolerances above hold for free blocks with
//! condition number up to 100 and grow in proportion beyond (see `for_conditioning`).

use crate::common;

use clarabel::algebra::CscMatrix;
use clarabel::solver::{DefaultSettings, DefaultSolver, IPSolver, SolverStatus, SupportedConeT};
use common::*;
use faer::{Col, Mat};
use plcp::{Method, Path, Plcp, PlcpError, Point, Scalar, Settings, Status, Var};
use proptest::prelude::*;
use proptest::test_runner::{FileFailurePersistence, TestCaseError};

// ---------------------------------------------------------------- tolerances

#[derive(Clone, Copy, Debug)]
struct MixedTol {
    path: Tol,
    /// Wolfe against Lemke, relative.
    agree: f64,
    /// Against Clarabel: objective (relative), `H x` and `x` (relative).
    qp_obj: f64,
    qp_x: f64,
}

const F64: MixedTol = MixedTol {
    path: Tol {
        residual: 1e-11,
        forward: 1e-9,
        enum_feas: 1e-9,
        lambda: 1e-10,
    },
    agree: 1e-10,
    qp_obj: 1e-6,
    qp_x: 1e-4,
};
const F32: MixedTol = MixedTol {
    path: Tol {
        // ten times the default tie tolerance 1e3 * eps (see prop_path.rs)
        residual: 1e-3,
        forward: 2e-3,
        enum_feas: 1e-9,
        lambda: 1e-4,
    },
    agree: 2e-3,
    qp_obj: 2e-3,
    qp_x: 2e-3,
};
const F128: MixedTol = MixedTol {
    path: Tol {
        // about 4e4 eps, the same multiple of eps as f64's 1e-11
        residual: 2e-27,
        forward: 1e-22,
        enum_feas: 1e-24,
        lambda: 1e-24,
    },
    agree: 1e-22,
    qp_obj: 1e-6,
    qp_x: 1e-4,
};

// ---------------------------------------------------------------- the QP family

/// A random convex parametric QP and its mixed PLCP.
#[derive(Clone, Debug)]
struct Kkt {
    nf: usize,
    nb: usize,
    h: Mat<f64>,
    a: Mat<f64>,
    b: Vec<f64>,
    bd: Vec<f64>,
    c: Vec<f64>,
    e: Vec<f64>,
    lambda_max: Option<f64>,
    variant: &'static str,
}

impl Kkt {
    fn nx(&self) -> usize {
        self.nf + self.nb
    }
    fn m(&self) -> usize {
        self.a.nrows()
    }
    /// The mixed PLCP (see the module docs for the layout).
    fn instance(&self) -> Instance {
        let (nf, nb, m) = (self.nf, self.nb, self.m());
        let p = nf + m;
        let dim = p + nb;
        // index of x_j (j < nx) and y_k in the PLCP's unknowns
        let xi = |j: usize| if j < nf { j } else { p + (j - nf) };
        let yi = |k: usize| nf + k;
        let mut mm = Mat::<f64>::zeros(dim, dim);
        let mut q = vec![0.0; dim];
        let mut d = vec![0.0; dim];
        for i in 0..self.nx() {
            for j in 0..self.nx() {
                mm[(xi(i), xi(j))] = self.h[(i, j)];
            }
            for k in 0..m {
                mm[(xi(i), yi(k))] = self.a[(k, i)];
                mm[(yi(k), xi(i))] = -self.a[(k, i)];
            }
            q[xi(i)] = self.c[i];
            d[xi(i)] = self.e[i];
        }
        for k in 0..m {
            q[yi(k)] = self.b[k];
            d[yi(k)] = self.bd[k];
        }
        Instance {
            m: mm,
            q,
            d,
            free: p,
            lambda0: 0.0,
            lambda_max: self.lambda_max,
            kind: Kind::Other,
        }
    }
    /// `x = (x_f, z)` from a point of the PLCP.
    fn x_of<T: Scalar>(&self, pt: &Point<T>) -> Vec<f64> {
        (0..self.nf)
            .map(|j| pt.u[j].to_f64())
            .chain((0..self.nb).map(|i| pt.z[i].to_f64()))
            .collect()
    }
    fn hx(&self, x: &[f64]) -> Vec<f64> {
        (0..self.nx())
            .map(|i| (0..self.nx()).map(|j| self.h[(i, j)] * x[j]).sum())
            .collect()
    }
    /// Largest violation of `A x = b + L bd` (relative to `max(1, |b + L bd|)`)
    /// and of `z >= 0` (relative to `max(1, |x|)`).
    fn infeasibility(&self, x: &[f64], l: f64) -> f64 {
        let xs = x.iter().fold(1.0f64, |a, v| a.max(v.abs()));
        let mut worst = (0..self.nb).fold(0.0f64, |a, i| a.max(-x[self.nf + i] / xs));
        for k in 0..self.m() {
            let rhs = self.b[k] + l * self.bd[k];
            let ax: f64 = (0..self.nx()).map(|j| self.a[(k, j)] * x[j]).sum();
            let scale = (0..self.nx())
                .map(|j| (self.a[(k, j)] * x[j]).abs())
                .fold(rhs.abs().max(1.0), f64::max);
            worst = worst.max((ax - rhs).abs() / scale);
        }
        worst
    }
    /// Largest violation of `A x = b + L bd` relative to `max(1, |b + L bd|)`
    /// only (not to the terms: a point far out, |x| ~ 1e19, is judged by
    /// what it misses absolutely).
    fn infeasibility_abs(&self, x: &[f64], l: f64) -> f64 {
        let mut worst = (0..self.nb).fold(0.0f64, |a, i| a.max(-x[self.nf + i]));
        for k in 0..self.m() {
            let rhs = self.b[k] + l * self.bd[k];
            let ax: f64 = (0..self.nx()).map(|j| self.a[(k, j)] * x[j]).sum();
            worst = worst.max((ax - rhs).abs() / rhs.abs().max(1.0));
        }
        worst
    }
    fn objective(&self, x: &[f64], l: f64) -> f64 {
        let hx = self.hx(x);
        (0..self.nx())
            .map(|i| 0.5 * x[i] * hx[i] + (self.c[i] + l * self.e[i]) * x[i])
            .sum()
    }
    /// `H` positive definite on the null space of `A` with curvature at least 1e-2:
    /// the primal solution is unique and Clarabel's is accurate enough to compare.
    fn unique_x(&self) -> bool {
        // well determined: an interior-point answer is then accurate to about
        // sqrt(gap / curvature), inside the stated tolerance
        self.curvature() > 1e-2
    }
    /// Smallest eigenvalue of `H` on the null space of `A` (infinite when the
    /// null space is empty): a feasible point whose objective is `g` above the
    /// optimum lies within `sqrt(2 g / curvature)` of it.
    fn curvature(&self) -> f64 {
        let nx = self.nx();
        // null space of A from its SVD
        let basis: Vec<Vec<f64>> = if self.m() == 0 {
            (0..nx)
                .map(|j| (0..nx).map(|i| if i == j { 1.0 } else { 0.0 }).collect())
                .collect()
        } else {
            let svd = self.a.svd().expect("svd");
            let s = svd.S();
            let v = svd.V();
            let smax = (0..s.dim()).fold(0.0f64, |a, i| a.max(s[i].abs()));
            let rank = (0..s.dim())
                .filter(|&i| s[i].abs() > 1e-10 * smax.max(1.0))
                .count();
            (rank..nx)
                .map(|j| (0..nx).map(|i| v[(i, j)]).collect())
                .collect()
        };
        let k = basis.len();
        if k == 0 {
            return f64::INFINITY;
        }
        let r = Mat::from_fn(k, k, |a, b| {
            let hb = self.hx(&basis[b]);
            (0..nx).map(|i| basis[a][i] * hb[i]).sum::<f64>()
        });
        let ev = r
            .self_adjoint_eigenvalues(faer::Side::Lower)
            .expect("eigenvalues");
        ev.iter().cloned().fold(f64::INFINITY, f64::min)
    }
    /// The QP at `l` by Clarabel: `Ok(x)` or the solver's status. Tolerances
    /// 1e-11; on a numerical failure (no progress, iteration limit) once more at 1e-9.
    fn clarabel(&self, l: f64) -> Result<Vec<f64>, SolverStatus> {
        match self.clarabel_at(l, 1e-11) {
            Err(
                SolverStatus::InsufficientProgress
                | SolverStatus::MaxIterations
                | SolverStatus::NumericalError,
            ) => self.clarabel_at(l, 1e-9),
            r => r,
        }
    }
    fn clarabel_at(&self, l: f64, tol: f64) -> Result<Vec<f64>, SolverStatus> {
        let nx = self.nx();
        let m = self.m();
        let p_rows: Vec<Vec<f64>> = (0..nx)
            .map(|i| (0..nx).map(|j| self.h[(i, j)]).collect())
            .collect();
        let mut a_rows: Vec<Vec<f64>> = (0..m)
            .map(|k| (0..nx).map(|j| self.a[(k, j)]).collect())
            .collect();
        let mut rhs: Vec<f64> = (0..m).map(|k| self.b[k] + l * self.bd[k]).collect();
        for i in 0..self.nb {
            // -z_i + s = 0, s >= 0
            a_rows.push(
                (0..nx)
                    .map(|j| if j == self.nf + i { -1.0 } else { 0.0 })
                    .collect(),
            );
            rhs.push(0.0);
        }
        let lin: Vec<f64> = (0..nx).map(|i| self.c[i] + l * self.e[i]).collect();
        let pm = CscMatrix::from(&p_rows);
        let am = CscMatrix::from(&a_rows);
        let mut cones = Vec::new();
        if m > 0 {
            cones.push(SupportedConeT::ZeroConeT(m));
        }
        cones.push(SupportedConeT::NonnegativeConeT(self.nb));
        let settings = DefaultSettings::<f64> {
            verbose: false,
            max_iter: 500,
            tol_gap_abs: tol,
            tol_gap_rel: tol,
            tol_feas: tol,
            ..DefaultSettings::default()
        };
        let mut solver =
            DefaultSolver::new(&pm, &lin, &am, &rhs, &cones, settings).expect("clarabel setup");
        solver.solve();
        match solver.solution.status {
            SolverStatus::Solved | SolverStatus::AlmostSolved => {
                // an answer counts only with its own certificate: stationarity
                // P x + lin + A' z = 0 (Clarabel's sign convention) to 1e-6 of
                // the data, with multipliers z of sane size. On an unbounded LP
                // with a dependent equality row Clarabel 0.11 was seen to report
                // Solved with a feasible, non-optimal x, its z at 3e8 and a
                // stationarity residual of 3e-2: no verdict then (as for an x
                // running off, below)
                let (x, z) = (&solver.solution.x, &solver.solution.z);
                let scale = lin.iter().fold(1.0f64, |a, v| a.max(v.abs()));
                let mut worst = 0.0f64;
                for i in 0..nx {
                    let mut r = lin[i];
                    for (j, xj) in x.iter().enumerate() {
                        r += p_rows[i][j] * xj;
                    }
                    for (k, row) in a_rows.iter().enumerate() {
                        r += row[i] * z[k];
                    }
                    worst = worst.max(r.abs());
                }
                let zmax = z.iter().fold(0.0f64, |a, v| a.max(v.abs()));
                if worst > 1e-6 * scale || zmax > 1e6 {
                    return Err(SolverStatus::NumericalError);
                }
                Ok(x.clone())
            }
            s => Err(s),
        }
    }
}

fn dy(k: i32, denom: f64) -> f64 {
    k as f64 / denom
}

/// How the free block is made singular (or not).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[allow(clippy::enum_variant_names)] // MoreRowsThanFree reads as meant
enum Free {
    /// `A_f` of full row rank, `H_ff` generic: nonsingular.
    Nonsingular,
    /// The last row of `A` is the sum of the first two: dependent equality rows.
    DependentRow,
    /// More equality rows than free primal variables (system (9) of an indeterminate frame).
    MoreRowsThanFree,
    /// The first free primal variable appears nowhere: its value is not unique.
    IdleVariable,
}

fn kkt(free: Free) -> impl Strategy<Value = Kkt> {
    let sizes = match free {
        Free::Nonsingular => (1usize..=3, 1usize..=4, 0usize..=3).boxed(),
        Free::DependentRow => (1usize..=3, 1usize..=4, 2usize..=3).boxed(),
        Free::MoreRowsThanFree => (1usize..=2, 2usize..=4, 2usize..=3).boxed(),
        Free::IdleVariable => (2usize..=3, 1usize..=4, 0usize..=2).boxed(),
    };
    sizes
        .prop_filter("m <= nf for a nonsingular free block", move |(nf, _, m)| {
            free != Free::Nonsingular || m <= nf
        })
        .prop_filter("more rows than free variables", move |(nf, _, m)| {
            free != Free::MoreRowsThanFree || m > nf
        })
        .prop_flat_map(move |(nf, nb, m)| {
            let nx = nf + nb;
            (
                Just((nf, nb, m)),
                0..nx, // rank of H: singular
                prop::collection::vec(-8i32..=8, nx * nx),
                prop::collection::vec(-8i32..=8, m * nx),
                prop::collection::vec(-8i32..=8, nx),
                prop::collection::vec(0i32..=8, nx),
                prop::collection::vec(-16i32..=16, nx),
                prop::collection::vec(-16i32..=16, nx),
                any::<bool>(), // the bounded variables enter linearly (H_zz = H_fz = 0)
                any::<bool>(), // a parametric right-hand side b_d
                prop_oneof![Just(None), (1i32..=64).prop_map(Some)],
            )
        })
        .prop_map(
            move |((nf, nb, m), r, bv, av, x0, xd, c, e, linear_z, with_bd, lm)| {
                let nx = nf + nb;
                let r = r.max(if free == Free::Nonsingular { nf } else { 0 });
                let mut bmat: Vec<f64> = (0..nx * r).map(|k| dy(bv[k], 8.0)).collect();
                if linear_z {
                    for i in nf..nx {
                        for k in 0..r {
                            bmat[i * r + k] = 0.0;
                        }
                    }
                }
                let mut a = Mat::from_fn(m, nx, |k, j| dy(av[k * nx + j], 8.0));
                let mut c: Vec<f64> = c.into_iter().map(|k| dy(k, 16.0)).collect();
                let mut e: Vec<f64> = e.into_iter().map(|k| dy(k, 16.0)).collect();
                match free {
                    Free::DependentRow => {
                        // the last row: the sum of the first two (m = 3) or twice the first (m = 2)
                        for j in 0..nx {
                            a[(m - 1, j)] = if m >= 3 {
                                a[(0, j)] + a[(1, j)]
                            } else {
                                2.0 * a[(0, j)]
                            };
                        }
                    }
                    Free::IdleVariable => {
                        // row 0 of B: x_f0 has no curvature
                        bmat[..r].fill(0.0);
                        for kk in 0..m {
                            a[(kk, 0)] = 0.0;
                        }
                        c[0] = 0.0;
                        e[0] = 0.0;
                    }
                    _ => {}
                }
                let h = gram(&bmat, nx, r);
                // a feasible point for every L >= 0: x0 + L xd with xd_z >= 0
                let x0: Vec<f64> = (0..nx)
                    .map(|j| {
                        if j < nf {
                            dy(x0[j], 8.0)
                        } else {
                            dy(x0[j].abs(), 8.0)
                        }
                    })
                    .collect();
                let xd: Vec<f64> = (0..nx)
                    .map(|j| if with_bd { dy(xd[j], 16.0) } else { 0.0 })
                    .collect();
                let ax = |v: &[f64]| -> Vec<f64> {
                    (0..m)
                        .map(|k| (0..nx).map(|j| a[(k, j)] * v[j]).sum())
                        .collect()
                };
                let b = ax(&x0);
                let bd = ax(&xd);
                Kkt {
                    nf,
                    nb,
                    h,
                    a,
                    b,
                    bd,
                    c,
                    e,
                    lambda_max: lm.map(|k| dy(k, 8.0)),
                    variant: match (free, linear_z) {
                        (Free::Nonsingular, false) => "nonsingular",
                        (Free::Nonsingular, true) => "nonsingular, linear in z",
                        (Free::DependentRow, _) => "dependent row",
                        (Free::MoreRowsThanFree, _) => "more rows than free variables",
                        (Free::IdleVariable, _) => "idle free variable",
                    },
                }
            },
        )
}

// ---------------------------------------------------------------- facts about an instance

/// Numerical rank (f64 SVD) of the free block.
fn free_block_rank(inst: &Instance) -> usize {
    let p = inst.free;
    if p == 0 {
        return 0;
    }
    let f = Mat::from_fn(p, p, |i, j| inst.m[(i, j)]);
    let s = f.singular_values().expect("svd");
    let smax = s.iter().cloned().fold(0.0f64, f64::max);
    s.iter().filter(|&&v| v > 1e-10 * smax.max(1e-300)).count()
}

/// Condition number of the free block on its range: `s_1 / s_r` (singular values,
/// `r` the numerical rank); 1 without free variables.
fn free_block_condition(inst: &Instance) -> f64 {
    let p = inst.free;
    if p == 0 {
        return 1.0;
    }
    let f = Mat::from_fn(p, p, |i, j| inst.m[(i, j)]);
    let s = f.singular_values().expect("svd");
    let smax = s.iter().cloned().fold(0.0f64, f64::max);
    let smin = s
        .iter()
        .cloned()
        .filter(|&v| v > 1e-10 * smax.max(1e-300))
        .fold(f64::INFINITY, f64::min);
    if smin.is_finite() {
        smax / smin
    } else {
        1.0
    }
}

/// The stated tolerances (path, agreement, Clarabel) hold for a free block with
/// condition number up to 100 and a reduced matrix with smallest relative
/// eigenvalue at least 0.01; beyond, they grow in proportion (errors of `cond * eps` are the precision's, not the
/// method's).
fn for_conditioning(tol: MixedTol, inst: &Instance) -> MixedTol {
    let f = (free_block_condition(inst) / 100.0).max(1.0);
    // solutions (not residuals) are as sensitive as the reduced problem is
    // ill-conditioned: forward and agreement tolerances grow with 1 / its
    // smallest relative eigenvalue too, where that is above 100
    let e = reduced_min_eig_rel(inst);
    let r = if e > 0.0 { (0.01 / e).max(1.0) } else { 1.0 };
    MixedTol {
        path: Tol {
            residual: tol.path.residual * f,
            forward: tol.path.forward * f * r,
            ..tol.path
        },
        agree: tol.agree * f * r,
        qp_obj: tol.qp_obj * f,
        qp_x: tol.qp_x * f * r,
    }
}

/// Smallest eigenvalue of the symmetric part of the Schur complement
/// `M_zz - M_zu F^-1 M_uz`, relative to its largest entry (1 without
/// complementary pairs). Above 1e-8: unique `u, z, w`; its inverse is the
/// condition of the reduced problem.
fn reduced_min_eig_rel(inst: &Instance) -> f64 {
    use faer::linalg::solvers::Solve;
    let p = inst.free;
    let n = inst.n();
    if n == 0 {
        return 1.0;
    }
    let f = Mat::from_fn(p, p, |i, j| inst.m[(i, j)]);
    let muz = Mat::from_fn(p, n, |i, j| inst.m[(i, p + j)]);
    let g = if p > 0 {
        f.partial_piv_lu().solve(muz.as_ref())
    } else {
        Mat::zeros(0, n)
    };
    let s = Mat::from_fn(n, n, |i, j| {
        let mut v = inst.m[(p + i, p + j)];
        for k in 0..p {
            v -= inst.m[(p + i, k)] * g[(k, j)];
        }
        v
    });
    let sym = Mat::from_fn(n, n, |i, j| 0.5 * (s[(i, j)] + s[(j, i)]));
    let scale = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .fold(1.0f64, |a, (i, j)| a.max(sym[(i, j)].abs()));
    let ev = sym
        .self_adjoint_eigenvalues(faer::Side::Lower)
        .expect("eigenvalues");
    ev.iter().cloned().fold(f64::INFINITY, f64::min) / scale
}

fn reduced_positive_definite(inst: &Instance) -> bool {
    reduced_min_eig_rel(inst) > 1e-8
}

// ---------------------------------------------------------------- comparisons

fn solve_with<T: Scalar>(problem: &Plcp<T>, method: Method) -> Result<Path<T>, PlcpError> {
    plcp::solve(problem, &Settings::with_method(method))
}

/// Where the solution path kinks: the starts of segments whose slopes (`dz`,
/// `dw`, `du`) differ from the previous segment's by more than `tol` (relative).
/// For a unique solution these are properties of the problem; pivots that
/// change no slope (degenerate steps, e.g. at a tie at the start) are the
/// method's own and are not compared.
fn kinks<T: Scalar>(path: &Path<T>, tol: f64) -> Vec<f64> {
    let mut out = Vec::new();
    for k in 1..path.segments.len() {
        let (a, b) = (&path.segments[k - 1], &path.segments[k]);
        let ds = rel_dist(a.dz.as_ref(), b.dz.as_ref())
            .max(rel_dist(a.dw.as_ref(), b.dw.as_ref()))
            .max(rel_dist(a.du.as_ref(), b.du.as_ref()));
        if ds > tol {
            out.push(b.lambda_from.to_f64());
        }
    }
    out
}

/// Compares two paths of the same problem: status, end, breakpoints where the
/// solution kinks (when `unique`; slopes compared to `sqrt(tol)`, kink positions
/// to `tol`) and the solution at every checked point of either.
fn compare_paths<T: Scalar>(
    a: &Path<T>,
    b: &Path<T>,
    unique: bool,
    tol: f64,
    frac: f64,
) -> Result<(), String> {
    if a.status != b.status {
        return Err(format!(
            "statuses differ: {:?} ({}) vs {:?} ({})",
            a.status, a.message, b.status, b.message
        ));
    }
    let lr = |p: &Path<T>| p.lambda_reached.to_f64();
    if a.status != Status::UnboundedRay && (lr(a) - lr(b)).abs() > tol * lr(a).abs().max(1.0) {
        return Err(format!("lambda_reached differ: {} vs {}", lr(a), lr(b)));
    }
    if unique {
        let (la, lb) = (kinks(a, tol.sqrt()), kinks(b, tol.sqrt()));
        let same = la.len() == lb.len()
            && la
                .iter()
                .zip(lb.iter())
                .all(|(x, y)| (x - y).abs() <= tol * x.abs().max(1.0));
        if !same {
            return Err(format!("breakpoints differ:\n  {la:?}\n  {lb:?}"));
        }
    }
    let mut ls = sample_lambdas(a, frac);
    ls.extend(sample_lambdas(b, frac));
    // the two ends agree to `tol` (checked above); sample within both ranges
    let end = if a.status == Status::UnboundedRay {
        None
    } else {
        Some(a.lambda_reached.min(b.lambda_reached))
    };
    let (ea, eb) = (own_error(a), own_error(b));
    for l in ls {
        let l = match end {
            Some(e) if l > e => e,
            _ => l,
        };
        let (Some(pa), Some(pb)) = (a.at(l), b.at(l)) else {
            return Err(format!("L = {}: one path has no point", l.to_f64()));
        };
        // one scale for the whole solution: u, z and w solve one linear
        // system, and a component near zero (a variable about to leave)
        // carries the rounding of the largest (as in the exact certificate)
        let scale = [&pa, &pb]
            .iter()
            .flat_map(|p| p.u.iter().chain(p.z.iter()).chain(p.w.iter()))
            .fold(1.0f64, |m, v| m.max(v.to_f64().abs()));
        let diff = |x: &Col<T>, y: &Col<T>| {
            x.iter()
                .zip(y.iter())
                .fold(0.0f64, |m, (p, q)| m.max((*p - *q).abs().to_f64()))
        };
        let dw = diff(&pa.w, &pb.w);
        let dzu = diff(&pa.z, &pb.z).max(diff(&pa.u, &pb.u));
        // the values agree to the comparison's tolerance plus what each path
        // says about its own accuracy, and near a breakpoint also to the
        // breakpoint's resolution times the kink there
        let allowed = (tol + ea + eb) * scale
            + near_kink(a, l, tol + ea, scale)
            + near_kink(b, l, tol + eb, scale);
        if dw > allowed || (unique && dzu > allowed) {
            return Err(format!(
                "L = {}: solutions differ (w by {dw:e}, z/u by {dzu:e}; allowed {allowed:e}: tol {tol:e}, own errors {ea:e} (cond {:e}, residual {:e}) and {eb:e} (cond {:e}, residual {:e}), scale {scale:e})\n  u {:?} / {:?}\n  z {:?} / {:?}\n  w {:?} / {:?}",
                l.to_f64(),
                a.info.max_condition,
                a.info.residual.equation,
                b.info.max_condition,
                b.info.residual.equation,
                col_f64(pa.u.as_ref()),
                col_f64(pb.u.as_ref()),
                col_f64(pa.z.as_ref()),
                col_f64(pb.z.as_ref()),
                col_f64(pa.w.as_ref()),
                col_f64(pb.w.as_ref()),
            ));
        }
    }
    Ok(())
}

/// A path's own bound on the relative error of its values, from what it
/// reports: forward error <= condition x backward error, with the largest
/// basis condition estimate of `Info` and the larger of its reported
/// equation residual and `eps` (the rounding of the data).
fn own_error<T: Scalar>(path: &Path<T>) -> f64 {
    let eps = T::eps().to_f64();
    path.info.max_condition.max(1.0) * path.info.residual.equation.max(eps)
}

/// The residual tolerance for a path: the stated one, or what the path's own
/// bases allow, `10 eps` times its `Info::max_condition`, up to the library's
/// trust level `sqrt(eps)` (a success claimed above it is turned
/// `ill_conditioned`). The tracer's bases hold the parameter's column (and
/// Wolfe's the long form's), which the complementary bases that
/// `check_path` measures do not: seed 257's Wolfe path (condition estimate
/// 1.2e7) reports residual 7.2e-11 against the stated 4.7e-11, seed 304's
/// (1.1e6) has 2.5e-11 at its breakpoint against 1e-11; both certified
/// exactly, breakpoints right to 3e-14 and 7e-12.
fn own_residual<T: Scalar>(tol: Tol, path: &Path<T>) -> Tol {
    let eps = T::eps().to_f64();
    Tol {
        residual: tol
            .residual
            .max((10.0 * eps * path.info.max_condition).min(eps.sqrt())),
        ..tol
    }
}

/// What a breakpoint's position error does to the values near it: a
/// breakpoint is where the leaving variable's line reaches zero, so a value
/// error `err * scale` of that line moves it by `delta = err * scale / |rate|`
/// (`rate` its slope before the breakpoint); within `delta` of the float
/// breakpoint the other path may already (or still) be on the other side,
/// and the values differ by up to the jump of the slopes there times
/// `delta`. Zero away from every breakpoint.
fn near_kink<T: Scalar>(path: &Path<T>, l: T, err: f64, scale: f64) -> f64 {
    let mut allow = 0.0f64;
    for bp in &path.breakpoints {
        let (Some(k), Some(next)) = (bp.segment.checked_sub(1), path.segments.get(bp.segment))
        else {
            continue;
        };
        let prev = &path.segments[k];
        let rate = match bp.leaving {
            Var::Z(i) => prev.dz[i].to_f64(),
            Var::W(i) => prev.dw[i].to_f64(),
            Var::U(j) => prev.du[j].to_f64(),
            _ => continue,
        }
        .abs();
        if rate == 0.0 {
            continue;
        }
        let delta = err * scale / rate;
        if (l - bp.lambda).abs().to_f64() > delta {
            continue;
        }
        let jump = [
            (&prev.dz, &next.dz),
            (&prev.dw, &next.dw),
            (&prev.du, &next.du),
        ]
        .iter()
        .flat_map(|(x, y)| x.iter().zip(y.iter()))
        .fold(0.0f64, |m, (p, q)| m.max((*p - *q).abs().to_f64()));
        allow += jump * delta;
    }
    allow
}

/// The path's primal solution against Clarabel at every checked point, and its
/// stop (if any) against Clarabel's unboundedness just beyond.
fn compare_with_clarabel<T: Scalar>(
    kkt: &Kkt,
    problem: &Plcp<T>,
    path: &Path<T>,
    points: &[Point<T>],
    tol: MixedTol,
) -> Result<(), String> {
    let unique_x = kkt.unique_x();
    let mut undecided = 0;
    // the path's exact certificate, read only where Clarabel disagrees
    let mut certified: Option<bool> = None;
    for pt in points {
        // where the path stops on a secondary ray, the QP is unbounded just beyond
        // L*, and the working precision's L* may lie a rounding error beyond the
        // true one: compare a tolerance inside it instead
        let l_stop = path.lambda_reached.to_f64();
        let near_stop = path.status == Status::SecondaryRay
            && (pt.lambda.to_f64() - l_stop).abs() <= tol.path.lambda * l_stop.abs().max(1.0);
        let inside;
        let pt = if near_stop && T::NAME == "f32" {
            let l_in = T::from_f64(l_stop - 10.0 * tol.path.lambda * l_stop.abs().max(1.0));
            match path.at(l_in) {
                Some(p) => {
                    inside = p;
                    &inside
                }
                None => continue,
            }
        } else {
            pt
        };
        let l = pt.lambda.to_f64();
        let x = kkt.x_of(pt);
        let xc = match kkt.clarabel(l) {
            Ok(xc) => xc,
            // the oracle fails numerically (near-degenerate QP): no verdict here
            Err(
                SolverStatus::InsufficientProgress
                | SolverStatus::MaxIterations
                | SolverStatus::NumericalError,
            ) => {
                undecided += 1;
                continue;
            }
            // a KKT point of a convex QP is optimal: where the exact
            // certificate proves the path's point a solution, a verdict of
            // unboundedness is the oracle's error (unseeded seeds 1 and 91:
            // "linear in z" QPs, DualInfeasible at a point of a certified path)
            // nor where an ill_conditioned path stopped: it claims no
            // solution there (seed 91: Lemke on the reduction stopped at
            // L = 1.8017035, 7.5e-7 past the exact secondary ray 2117/1175
            // that Wolfe reports, certified)
            Err(SolverStatus::DualInfeasible | SolverStatus::AlmostDualInfeasible)
                if path.status == Status::IllConditioned
                    && pt.lambda.to_f64() >= path.lambda_reached.to_f64() =>
            {
                undecided += 1;
                continue;
            }
            Err(SolverStatus::DualInfeasible | SolverStatus::AlmostDualInfeasible)
                if *certified.get_or_insert_with(|| plcp::certify(problem, path).certified()) =>
            {
                undecided += 1;
                continue;
            }
            Err(s) => {
                return Err(format!(
                    "L = {l}: the path has a solution, Clarabel says {s:?}"
                ))
            }
        };
        let (f, fc) = (kkt.objective(&x, l), kkt.objective(&xc, l));
        // the path's point is feasible (checked here, in f64: its rounding to f64
        // bounds the check) and lower than Clarabel's:
        // in a convex QP it is the better answer, and the interior-point oracle
        // stopped short (seen at large L, where |x| ~ 1e4 and AlmostSolved)
        if fc - f > tol.qp_obj * fc.abs().max(1.0)
            && kkt.infeasibility(&x, l) <= tol.path.forward.max(1e-9)
        {
            undecided += 1;
            continue;
        }
        // Clarabel's point is lower but not feasible (AlmostSolved far out, |x|
        // ~ 1e19): no verdict from it
        if f - fc > tol.qp_obj * fc.abs().max(1.0) && kkt.infeasibility_abs(&xc, l) > 1e-6 {
            undecided += 1;
            continue;
        }
        if (f - fc).abs() > tol.qp_obj * fc.abs().max(1.0) {
            return Err(format!(
                "L = {l}: objective {f} vs Clarabel {fc} (x = {x:?}, Clarabel {xc:?})"
            ));
        }
        let (hx, hxc) = (kkt.hx(&x), kkt.hx(&xc));
        let scale = hxc.iter().fold(1.0f64, |a, v| a.max(v.abs()));
        let dh = hx
            .iter()
            .zip(hxc.iter())
            .fold(0.0f64, |a, (u, v)| a.max((u - v).abs()));
        // Clarabel's own accuracy: where the path's point is feasible and no
        // worse than Clarabel's, both are optimal to the objective's
        // tolerance, and H x may then differ by what a gap of that size
        // allows, sqrt(2 gap |H|) (an unseeded case: at the breakpoint
        // L = 1570 of a degenerate QP, whose path certifies exactly,
        // Clarabel's x_0 was 11.9988 for 12, H x off by 1.7e-4 of 1.69,
        // objectives -1624 within 1e-6)
        let path_as_good = f <= fc && kkt.infeasibility(&x, l) <= tol.path.forward.max(1e-9);
        let hnorm = (0..kkt.nx())
            .map(|i| (0..kkt.nx()).map(|j| kkt.h[(i, j)].abs()).sum::<f64>())
            .fold(0.0f64, f64::max);
        let allowed = (2.0 * tol.qp_obj * fc.abs().max(1.0) * hnorm).sqrt();
        if dh > tol.qp_x * scale && path_as_good && dh <= allowed {
            undecided += 1;
            continue;
        }
        if dh > tol.qp_x * scale {
            return Err(format!(
                "L = {l}: H x differs from Clarabel's by {dh:e} (x = {x:?}, Clarabel {xc:?}; objective {f} vs {fc})"
            ));
        }
        if unique_x {
            let scale = xc.iter().fold(1.0f64, |a, v| a.max(v.abs()));
            let dx = x
                .iter()
                .zip(xc.iter())
                .fold(0.0f64, |a, (u, v)| a.max((u - v).abs()));
            // Clarabel's own accuracy in x: where the path's point is feasible
            // and no worse, both points are within `sqrt(2 g / curvature)` of
            // the optimum, `g` the objective's tolerance (strong convexity on
            // the null space of A; the first-order term is >= 0 at an optimum).
            // Seed 198: at L = 12129 (|x| ~ 9e3, objective ~ -1e8) Clarabel's
            // x_3 was 1.07 where the path's certified x_3 is 0
            let allowed_x = 2.0 * (2.0 * tol.qp_obj * fc.abs().max(1.0) / kkt.curvature()).sqrt();
            if dx > tol.qp_x * scale && path_as_good && dx <= allowed_x {
                undecided += 1;
                continue;
            }
            if dx > tol.qp_x * scale {
                return Err(format!(
                    "L = {l}: x = {x:?} differs from Clarabel's {xc:?} by {dx:e} (x unique)"
                ));
            }
        }
    }
    if !points.is_empty() && undecided == points.len() {
        return Err(format!(
            "Clarabel could decide none of the {} points",
            points.len()
        ));
    }
    let stop = match path.status {
        Status::SecondaryRay => Some(path.lambda_reached.to_f64()),
        Status::Infeasible => Some(path.lambda0.to_f64()),
        _ => None,
    };
    if let Some(l) = stop {
        let beyond = if path.status == Status::Infeasible {
            l
        } else {
            l + 1e-2 * (1.0 + l.abs())
        };
        match kkt.clarabel(beyond) {
            Err(SolverStatus::DualInfeasible | SolverStatus::AlmostDualInfeasible) => {}
            // the oracle cannot decide (it fails numerically on some unbounded
            // QPs with singular H): no verdict either way
            Err(
                SolverStatus::InsufficientProgress
                | SolverStatus::MaxIterations
                | SolverStatus::NumericalError,
            ) => {}
            // a "solution" of norm 1e6 on O(1) data is the iterates running off
            // along a direction of unboundedness
            Ok(x) if x.iter().fold(0.0f64, |a, v| a.max(v.abs())) > 1e6 => {}
            other => {
                return Err(format!(
                    "the path stops ({:?}) at L = {l}, but at L = {beyond} Clarabel says {:?}",
                    path.status,
                    other.map(|x| format!("solved, x = {x:?}"))
                ))
            }
        }
    }
    Ok(())
}

// ---------------------------------------------------------------- the properties

/// Nonsingular free block: Wolfe and Lemke on the reduction agree; both against Clarabel.
fn check_nonsingular<T: Scalar>(kkt: &Kkt, tol: MixedTol, frac: f64) -> Result<(), String> {
    let inst = kkt.instance();
    let tol = for_conditioning(tol, &inst);
    let p = inst.free;
    if free_block_rank(&inst) < p {
        return Ok(()); // rare degenerate draw: covered by the singular tests
    }
    let problem = inst.plcp::<T>();
    let lemke = solve_with(&problem, Method::Lemke).map_err(|e| format!("Lemke: {e}"))?;
    let wolfe = solve_with(&problem, Method::Wolfe).map_err(|e| format!("Wolfe: {e}"))?;
    if wolfe.info.free_block.rank != p
        || !wolfe.info.free_block.nonbasic_free.is_empty()
        || !wolfe.info.free_block.dependent_rows.is_empty()
    {
        return Err(format!(
            "Wolfe reports the nonsingular free block as {:?}",
            wolfe.info.free_block
        ));
    }
    let unique = reduced_positive_definite(&inst);
    let continuity = if unique {
        Continuity::All
    } else {
        Continuity::W
    };
    // Lemke runs on the Schur reduction: its breakpoints carry the reduction's
    // error (about eps cond(F) cond(reduced)), documented in the README's known
    // limits; the segment values are polished on the unreduced system, the
    // breakpoint positions are not. Wolfe is held to the plain tolerance.
    // where the reduced problem is nearly singular (z not unique: its smallest
    // relative eigenvalue e), a segment's active set cannot be polished and its
    // values keep the reduction's error, amplified by 1 / e
    // (singular reduced problem: e at the rounding level, either sign; then 1e8)
    let e = reduced_min_eig_rel(&inst);
    let amplify = (0.01 / e.max(1e-10)).max(1.0);
    let pts_l = check_path(
        &problem,
        &lemke,
        own_residual(tol.path.scaled(100.0 * amplify), &lemke),
        frac,
        continuity,
        true,
    )
    .map_err(|e| format!("Lemke path: {e}"))?;
    let pts_w = check_path(
        &problem,
        &wolfe,
        own_residual(tol.path, &wolfe),
        frac,
        continuity,
        true,
    )
    .map_err(|e| format!("Wolfe path: {e}"))?;
    if unique && !lemke.status.is_success() && lemke.status != Status::IllConditioned {
        return Err(format!(
            "unique solution for every L, but Lemke ends with {:?}: {}",
            lemke.status, lemke.message
        ));
    }
    // a method that declares the basis too ill-conditioned for the precision
    // gives no answer to compare (an honest status, not a wrong answer); what it
    // traced before stopping is still checked above and against Clarabel below
    let ill = lemke.status == Status::IllConditioned || wolfe.status == Status::IllConditioned;
    if !ill {
        compare_paths(&lemke, &wolfe, unique, tol.agree, frac)
            .map_err(|e| format!("Lemke vs Wolfe: {e}"))?;
    }
    compare_with_clarabel(kkt, &problem, &lemke, &pts_l, tol)
        .map_err(|e| format!("Lemke vs Clarabel: {e}"))?;
    compare_with_clarabel(kkt, &problem, &wolfe, &pts_w, tol)
        .map_err(|e| format!("Wolfe vs Clarabel: {e}"))?;
    Ok(())
}

/// Singular free block: Lemke refuses with the right rank; Wolfe reports the
/// block and agrees with Clarabel.
fn check_singular<T: Scalar>(kkt: &Kkt, tol: MixedTol, frac: f64) -> Result<(), String> {
    let inst = kkt.instance();
    let tol = for_conditioning(tol, &inst);
    let p = inst.free;
    let rank = free_block_rank(&inst);
    if rank == p {
        return Ok(()); // the construction did not make it singular (e.g. a zero row)
    }
    let problem = inst.plcp::<T>();
    match solve_with(&problem, Method::Lemke) {
        Err(PlcpError::SingularFreeBlock { p: pp, rank: r }) if pp == p && r == rank => {}
        other => {
            return Err(format!(
                "Lemke on a singular free block (p = {p}, rank {rank}): expected Err(SingularFreeBlock), got {:?}",
                other.map(|path| path.status)
            ))
        }
    }
    let wolfe = solve_with(&problem, Method::Wolfe).map_err(|e| format!("Wolfe: {e}"))?;
    let fb = &wolfe.info.free_block;
    if fb.rank != rank || fb.nonbasic_free.len() != p - rank || fb.dependent_rows.len() != p - rank
    {
        return Err(format!(
            "Wolfe's free block info {fb:?}, expected rank {rank} of {p}"
        ));
    }
    let points = check_path(
        &problem,
        &wolfe,
        own_residual(tol.path, &wolfe),
        frac,
        Continuity::None,
        true,
    )
    .map_err(|e| format!("Wolfe path: {e}"))?;
    compare_with_clarabel(kkt, &problem, &wolfe, &points, tol)
        .map_err(|e| format!("Wolfe vs Clarabel: {e}"))?;
    Ok(())
}

fn fail(kkt: &Kkt, prec: &str, e: String) -> TestCaseError {
    TestCaseError::fail(format!(
        "[{prec}] {} ({}): {e}\ninstance: {}",
        kkt.variant,
        if kkt.instance().free > 0 {
            "mixed"
        } else {
            "standard"
        },
        kkt.instance().to_json()
    ))
}

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        max_shrink_iters: 4096,
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "proptest-regressions/mixed.txt",
        ))),
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config(150))]

    #[test]
    fn f64_nonsingular_wolfe_and_lemke_agree(k in kkt(Free::Nonsingular), frac in 0.0..1.0f64) {
        check_nonsingular::<f64>(&k, F64, frac).map_err(|e| fail(&k, "f64", e))?;
    }

    #[test]
    fn f64_dependent_rows_wolfe_matches_clarabel(k in kkt(Free::DependentRow), frac in 0.0..1.0f64) {
        check_singular::<f64>(&k, F64, frac).map_err(|e| fail(&k, "f64", e))?;
    }

    #[test]
    fn f64_more_rows_than_free_wolfe_matches_clarabel(k in kkt(Free::MoreRowsThanFree), frac in 0.0..1.0f64) {
        check_singular::<f64>(&k, F64, frac).map_err(|e| fail(&k, "f64", e))?;
    }

    #[test]
    fn f64_idle_free_variable_wolfe_matches_clarabel(k in kkt(Free::IdleVariable), frac in 0.0..1.0f64) {
        check_singular::<f64>(&k, F64, frac).map_err(|e| fail(&k, "f64", e))?;
    }
}

proptest! {
    #![proptest_config(config(48))]

    #[test]
    #[ignore = "known gap: in f32 a free block with cond(F) eps above ~1e-2 is numerically singular, and Wolfe's rank decision there can differ from the reduction's (README, known limits)"]
    fn f32_nonsingular_wolfe_and_lemke_agree(k in kkt(Free::Nonsingular), frac in 0.0..1.0f64) {
        check_nonsingular::<f32>(&k, F32, frac).map_err(|e| fail(&k, "f32", e))?;
    }

    #[test]
    #[ignore = "known gap: in f32 a free block with cond(F) eps above ~1e-2 is numerically singular, and Wolfe's rank decision there can differ from the reduction's (README, known limits)"]
    fn f32_singular_wolfe_matches_clarabel(k in kkt(Free::MoreRowsThanFree), frac in 0.0..1.0f64) {
        check_singular::<f32>(&k, F32, frac).map_err(|e| fail(&k, "f32", e))?;
    }

    #[test]
    fn f128_nonsingular_wolfe_and_lemke_agree(k in kkt(Free::Nonsingular), frac in 0.0..1.0f64) {
        check_nonsingular::<faer::fx128>(&k, F128, frac).map_err(|e| fail(&k, "f128", e))?;
    }

    #[test]
    fn f128_singular_wolfe_matches_clarabel(k in kkt(Free::DependentRow), frac in 0.0..1.0f64) {
        check_singular::<faer::fx128>(&k, F128, frac).map_err(|e| fail(&k, "f128", e))?;
    }
}

// ---------------------------------------------------------------- random monotone mixed PLCPs

/// `M = B B' + S + I/8` of order `p + n` (positive definite: nonsingular free
/// block, unique solution), random `q, d`.
fn monotone_mixed() -> impl Strategy<Value = Instance> {
    (1usize..=3, 1usize..=5)
        .prop_flat_map(|(p, n)| {
            let dim = p + n;
            (
                Just((p, n)),
                prop::collection::vec(-8i32..=8, dim * dim),
                prop::collection::vec(-8i32..=8, dim * dim),
                prop::collection::vec(-64i32..=64, dim),
                prop::collection::vec(-64i32..=64, dim),
                prop_oneof![Just(None), (1i32..=64).prop_map(Some)],
            )
        })
        .prop_map(|((p, n), b, s, q, d, lm)| {
            let dim = p + n;
            let b: Vec<f64> = b.into_iter().map(|k| dy(k, 8.0)).collect();
            let s: Vec<f64> = s.into_iter().map(|k| dy(k, 8.0)).collect();
            Instance {
                m: monotone(&b, dim, dim, &s, 0.125),
                q: q.into_iter().map(|k| dy(k, 64.0)).collect(),
                d: d.into_iter().map(|k| dy(k, 64.0)).collect(),
                free: p,
                lambda0: 0.0,
                lambda_max: lm.map(|k| dy(k, 8.0)),
                kind: Kind::PositiveDefinite,
            }
        })
}

fn check_monotone_mixed<T: Scalar>(
    inst: &Instance,
    tol: MixedTol,
    frac: f64,
    oracle_points: usize,
) -> Result<(), String> {
    let tol = for_conditioning(tol, inst);
    let problem = inst.plcp::<T>();
    let lemke = solve_with(&problem, Method::Lemke).map_err(|e| format!("Lemke: {e}"))?;
    if !lemke.status.is_success() {
        return Err(format!(
            "Lemke ends with {:?} on a positive definite problem: {}",
            lemke.status, lemke.message
        ));
    }
    let points = check_path(
        &problem,
        &lemke,
        own_residual(tol.path, &lemke),
        frac,
        Continuity::All,
        true,
    )
    .map_err(|e| format!("Lemke path: {e}"))?;
    let step = (points.len() / oracle_points.max(1)).max(1);
    for pt in points.iter().step_by(step) {
        // the oracle in the working precision, except for f32: there in f64 on
        // the same (exactly representable) data
        let r = if T::NAME == "f32" {
            let pt64 = Point {
                lambda: pt.lambda.to_f64(),
                z: col_t::<f64>(&col_f64(pt.z.as_ref())),
                w: col_t::<f64>(&col_f64(pt.w.as_ref())),
                u: col_t::<f64>(&col_f64(pt.u.as_ref())),
            };
            compare_with_enumeration(
                &inst.plcp::<f64>(),
                &pt64,
                Kind::PositiveDefinite,
                tol.path.forward,
                tol.path.enum_feas,
            )
        } else {
            compare_with_enumeration(
                &problem,
                pt,
                Kind::PositiveDefinite,
                tol.path.forward,
                tol.path.enum_feas,
            )
        };
        r.map_err(|e| format!("Lemke vs enumeration: {e}"))?;
    }
    let wolfe = solve_with(&problem, Method::Wolfe).map_err(|e| format!("Wolfe: {e}"))?;
    check_path(
        &problem,
        &wolfe,
        own_residual(tol.path, &wolfe),
        frac,
        Continuity::All,
        true,
    )
    .map_err(|e| format!("Wolfe path: {e}"))?;
    compare_paths(&lemke, &wolfe, true, tol.agree, frac)
        .map_err(|e| format!("Lemke vs Wolfe: {e}"))?;
    Ok(())
}

fn fail_inst(inst: &Instance, prec: &str, e: String) -> TestCaseError {
    TestCaseError::fail(format!("[{prec}] {e}\ninstance: {}", inst.to_json()))
}

proptest! {
    #![proptest_config(config(150))]

    #[test]
    fn f64_monotone_mixed(inst in monotone_mixed(), frac in 0.0..1.0f64) {
        check_monotone_mixed::<f64>(&inst, F64, frac, usize::MAX).map_err(|e| fail_inst(&inst, "f64", e))?;
    }
}

proptest! {
    #![proptest_config(config(32))]

    #[test]
    #[ignore = "known gap: in f32 a free block with cond(F) eps above ~1e-2 is numerically singular, and Wolfe's rank decision there can differ from the reduction's (README, known limits)"]
    fn f32_monotone_mixed(inst in monotone_mixed(), frac in 0.0..1.0f64) {
        check_monotone_mixed::<f32>(&inst, F32, frac, usize::MAX).map_err(|e| fail_inst(&inst, "f32", e))?;
    }

    #[test]
    fn f128_monotone_mixed(inst in monotone_mixed(), frac in 0.0..1.0f64) {
        check_monotone_mixed::<faer::fx128>(&inst, F128, frac, 6).map_err(|e| fail_inst(&inst, "f128", e))?;
    }
}

// ---------------------------------------------------------------- small fixed cases

/// System (9) in miniature: one free "acceleration" `a` with unit mass, two
/// compatibility rows (more equality rows than free primal variables, so the
/// multipliers, the "member forces", are not unique), two plastic multipliers:
///
/// minimise 1/2 a^2 - L a + z1 + z2  s.t.  a - z1 = 0,  a - z2 = 0,  z >= 0.
///
/// The free block `[[1, 1, 1], [-1, 0, 0], [-1, 0, 0]]` has rank 2. For
/// `L <= 2` the optimum is `a = z1 = z2 = 0` (rigid); beyond, `a = z1 = z2 =
/// L - 2`. Wolfe must find the breakpoint at `L = 2`; Lemke must refuse.
fn tiny_indeterminate<T: Scalar>() {
    let kkt = Kkt {
        nf: 1,
        nb: 2,
        h: mat_from_rows(&[
            vec![1.0, 0.0, 0.0],
            vec![0.0, 0.0, 0.0],
            vec![0.0, 0.0, 0.0],
        ]),
        a: mat_from_rows(&[vec![1.0, -1.0, 0.0], vec![1.0, 0.0, -1.0]]),
        b: vec![0.0, 0.0],
        bd: vec![0.0, 0.0],
        c: vec![0.0, 1.0, 1.0],
        e: vec![-1.0, 0.0, 0.0],
        lambda_max: Some(5.0),
        variant: "tiny indeterminate",
    };
    let inst = kkt.instance();
    assert_eq!(free_block_rank(&inst), 2);
    let problem = inst.plcp::<T>();
    match solve_with(&problem, Method::Lemke) {
        Err(PlcpError::SingularFreeBlock { p: 3, rank: 2 }) => {}
        other => panic!("[{}] Lemke: {:?}", T::NAME, other.map(|p| p.status)),
    }
    let path = solve_with(&problem, Method::Wolfe).unwrap();
    assert_eq!(
        path.status,
        Status::Reached,
        "[{}] {}",
        T::NAME,
        path.message
    );
    let tol = match T::NAME {
        "f32" => 1e-5,
        "f64" => 1e-12,
        _ => 1e-28,
    };
    for (l, want) in [(1.0, 0.0), (2.0, 0.0), (3.0, 1.0), (5.0, 3.0)] {
        let pt = path.at(T::from_f64(l)).unwrap();
        let x = kkt.x_of(&pt);
        for v in x {
            assert!(
                (v - want).abs() <= tol * 10.0,
                "[{}] L = {l}: x = {:?}, expected all {want}",
                T::NAME,
                kkt.x_of(&pt)
            );
        }
    }
    // x kinks at L = 2: a breakpoint there (others before it may come from the
    // arbitrary split of the non-unique multipliers y)
    assert!(
        path.breakpoints
            .iter()
            .any(|bp| (bp.lambda.to_f64() - 2.0).abs() <= tol),
        "[{}] no breakpoint at L = 2: {:?}",
        T::NAME,
        path.breakpoints
    );
    let points = check_path(
        &problem,
        &path,
        path_tol_of::<T>(),
        0.5,
        Continuity::None,
        true,
    )
    .unwrap_or_else(|e| panic!("[{}] {e}", T::NAME));
    compare_with_clarabel(
        &kkt,
        &problem,
        &path,
        &points,
        match T::NAME {
            "f32" => F32,
            "f64" => F64,
            _ => F128,
        },
    )
    .unwrap_or_else(|e| panic!("[{}] {e}", T::NAME));
}

fn path_tol_of<T: Scalar>() -> Tol {
    match T::NAME {
        "f32" => F32.path,
        "f64" => F64.path,
        _ => F128.path,
    }
}

#[test]
fn tiny_indeterminate_f32() {
    tiny_indeterminate::<f32>();
}

#[test]
fn tiny_indeterminate_f64() {
    tiny_indeterminate::<f64>();
}

#[test]
fn tiny_indeterminate_f128() {
    tiny_indeterminate::<faer::fx128>();
}

/// A standard-form problem (`free = 0`) through both methods: the same path.
#[test]
fn standard_form_wolfe_equals_lemke() {
    let m = mat_from_rows(&[vec![2.0, 1.0], vec![1.0, 2.0]]);
    let inst = Instance {
        m,
        q: vec![1.0, 1.0],
        d: vec![-1.0, -0.5],
        free: 0,
        lambda0: 0.0,
        lambda_max: None,
        kind: Kind::PositiveDefinite,
    };
    let p = inst.plcp::<f64>();
    let a = solve_with(&p, Method::Lemke).unwrap();
    let b = solve_with(&p, Method::Wolfe).unwrap();
    compare_paths(&a, &b, true, 1e-12, 0.5).unwrap();
    assert_eq!(b.status, Status::UnboundedRay);
}

/// The start phase's artificial reaches zero at the same step as a slack
/// blocks (a tie with the end of the homotopy): the tie goes to the end, and the
/// start point is the LCP's solution. Before the fix Wolfe reported
/// `infeasible` here while holding the solution. Worked by hand: `u = (0.75,
/// -1.5)` from the first equality row and `w_2 = w_3 = 0`; the second equality
/// row then needs `z_2 + z_3 = 0.125` with `z_1 = 0`.
#[test]
fn wolfe_start_phase_tie_with_its_end() {
    let rows: [[f64; 6]; 6] = [
        [0.25, 0.375, 0.0, 0.0, 0.0, 0.0],
        [-0.375, 0.0, 0.0, 0.625, -0.25, -0.25],
        [0.0; 6],
        [0.0, -0.625, 0.0, 0.0, 0.0, 0.0],
        [0.0, 0.25, 0.0, 0.0, 0.0, 0.0],
        [0.0, 0.25, 0.0, 0.0, 0.0, 0.0],
    ];
    let m = Mat::from_fn(6, 6, |i, j| rows[i][j]);
    let q = faer::Col::from_fn(6, |i| [0.375, 0.3125, 0.0, -0.9375, 0.375, 0.375][i]);
    let d = faer::Col::<f64>::zeros(6);
    let problem = Plcp::mixed(m.as_ref(), q.as_ref(), d.as_ref(), 2).unwrap();
    for method in [Method::Wolfe, Method::Lemke] {
        let path = plcp::solve(&problem, &Settings::with_method(method)).unwrap();
        assert_eq!(
            path.status,
            Status::UnboundedRay,
            "{method:?}: {}",
            path.message
        );
        let e = &path.end;
        assert!(
            (e.u[0] - 0.75).abs() < 1e-14 && (e.u[1] + 1.5).abs() < 1e-14,
            "{method:?} u = {:?}",
            e.u
        );
        assert!(
            e.z[0].abs() < 1e-14 && e.z[1].abs() < 1e-14,
            "{method:?} z = {:?}",
            e.z
        );
        assert!(
            (e.z[2] + e.z[3] - 0.125).abs() < 1e-14,
            "{method:?} z = {:?}",
            e.z
        );
        assert!(path.info.residual.worst() < 1e-14);
    }
}

/// The instance on which `f64_idle_free_variable_wolfe_matches_clarabel`
/// failed once (2026-11-26, an unseeded run): Wolfe's path reported residual
/// `2.3e-15` (the trace's own, of the basic values on the scaled system) where
/// its segments, evaluated at their ends on the problem, have `2.5e-12` (a
/// feasibility residual). The reported residual bounds what the delivered
/// segments give at their ends: `residual::measure_ends` measures both ends
/// of every segment (and a streamed trace those it hands over,
/// `observe.rs`).
#[test]
fn f64_reported_residual_bounds_the_segment_ends() {
    let m = faer::mat![
        [0.0, 0.0, 0.0, -0.0, 0.0, 0.0, -0.0],
        [0.0, 1.609375, 0.203125, -0.6875, 0.0, -0.3125, -0.25],
        [0.0, 0.203125, 1.328125, -0.28125, 0.0, -1.40625, -0.28125],
        [-0.0, -0.6875, -0.28125, 1.828125, -0.0, -0.484375, 1.5],
        [0.0, 0.0, 0.0, -0.0, 0.0, 0.0, -0.0],
        [0.0, -0.3125, -1.40625, -0.484375, 0.0, 3.109375, -1.78125],
        [-0.0, -0.25, -0.28125, 1.5, -0.0, -1.78125, 2.875]
    ];
    let q = faer::col![0.0, 0.125, 0.375, -0.6875, 0.0, 0.125, -0.3125];
    let d = faer::col![0.0, -0.25, -0.0625, 0.0, 0.0, -0.375, 0.0625];
    let problem = Plcp::mixed(m.as_ref(), q.as_ref(), d.as_ref(), 3).unwrap();
    let path = solve_with(&problem, Method::Wolfe).unwrap();
    let mut at_ends = plcp::residual::residual(&problem, &path.end).worst();
    for s in &path.segments {
        at_ends = at_ends.max(plcp::residual::residual(&problem, &s.eval(s.lambda_from)).worst());
        if !s.unbounded {
            at_ends = at_ends.max(plcp::residual::residual(&problem, &s.eval(s.lambda_to)).worst());
        }
    }
    println!(
        "reported {:?}, at the segment ends {at_ends:e}",
        path.info.residual
    );
    assert!(
        path.info.residual.worst() >= at_ends,
        "reported {:?}, at the segment ends {at_ends:e}",
        path.info.residual
    );
}

/// The comparison of Wolfe with Lemke still sees a wrong answer: on a
/// small positive definite instance the two paths agree, and Wolfe's path with one segment's values off by `1e-8` of
/// the solution's scale, or with one breakpoint moved by `1e-8` relative
/// (the next segment re-based along its own line, so the path stays
/// continuous and only the kink moves), is rejected. Both errors are below
/// the exact certificate's limit (`sqrt(eps) = 1.5e-8`) and far above
/// f64's resolution on this instance.
#[test]
fn the_comparison_rejects_a_perturbed_path() {
    let rows = |r: &[&[f64]]| mat_from_rows(&r.iter().map(|v| v.to_vec()).collect::<Vec<_>>());
    // H positive definite: a unique solution for every L, whose z_1 leaves
    // and z_2 enters as L rises
    let kkt = Kkt {
        nf: 1,
        nb: 2,
        h: rows(&[&[1.0, 0.25, 0.0], &[0.25, 1.0, 0.125], &[0.0, 0.125, 1.0]]),
        a: Mat::zeros(0, 3),
        b: vec![],
        bd: vec![],
        c: vec![0.0, -0.5, 0.25],
        e: vec![0.5, 1.0, -1.0],
        lambda_max: None,
        variant: "nonsingular",
    };
    let inst = kkt.instance();
    let tol = for_conditioning(F64, &inst).agree;
    let unique = reduced_positive_definite(&inst);
    assert!(unique && tol <= 1e-9, "unique {unique}, tol {tol:e}");
    let problem = inst.plcp::<f64>();
    let lemke = solve_with(&problem, Method::Lemke).unwrap();
    let wolfe = solve_with(&problem, Method::Wolfe).unwrap();
    compare_paths(&lemke, &wolfe, unique, tol, 0.5).unwrap();
    // a breakpoint between two segments of positive length
    let k = (1..wolfe.segments.len())
        .find(|&k| {
            let (a, b) = (&wolfe.segments[k - 1], &wolfe.segments[k]);
            a.lambda_to > a.lambda_from && (b.unbounded || b.lambda_to > b.lambda_from)
        })
        .expect("a breakpoint between two segments");
    let scale = wolfe.segments[k]
        .z_from
        .iter()
        .chain(wolfe.segments[k].u_from.iter())
        .fold(1.0f64, |m, v| m.max(v.abs()));
    // values off by 1e-8 of the scale on one segment
    let mut off = wolfe.clone();
    let i = (0..off.segments[k].z_from.nrows())
        .max_by(|&a, &b| {
            off.segments[k].z_from[a]
                .abs()
                .total_cmp(&off.segments[k].z_from[b].abs())
        })
        .unwrap();
    off.segments[k].z_from[i] += 1e-8 * scale;
    // w is unique even where z is not (a symmetric PSD reduced problem)
    let iw = (0..off.segments[k].w_from.nrows())
        .max_by(|&a, &b| {
            off.segments[k].w_from[a]
                .abs()
                .total_cmp(&off.segments[k].w_from[b].abs())
        })
        .unwrap();
    off.segments[k].w_from[iw] += 1e-8 * scale;
    let e = compare_paths(&lemke, &off, unique, tol, 0.5).expect_err("a value error of 1e-8");
    assert!(e.contains("solutions differ"), "{e}");
    // the breakpoint moved by 1e-8 relative
    let mut moved = wolfe.clone();
    let l = moved.segments[k].lambda_from;
    let shift = 1e-8 * l.abs().max(1.0);
    let seg = &mut moved.segments[k];
    for (x, dx) in [
        (&mut seg.z_from, &seg.dz),
        (&mut seg.w_from, &seg.dw),
        (&mut seg.u_from, &seg.du),
    ] {
        for j in 0..x.nrows() {
            x[j] += dx[j] * shift;
        }
    }
    seg.lambda_from = l + shift;
    moved.segments[k - 1].lambda_to = l + shift;
    for b in &mut moved.breakpoints {
        if b.segment == k {
            b.lambda = l + shift;
        }
    }
    let e =
        compare_paths(&lemke, &moved, unique, tol, 0.5).expect_err("a breakpoint moved by 1e-8");
    assert!(e.contains("differ"), "{e}");
}

// ---------------------------------------------------------------- extra seeds (2026-11-27)

// Four seeds of about 320 beyond CI's failed (`PROPTEST_RNG_SEED=198, 257,
// 294, 304`; docs/testing.md): in 198, 257 and 304 (dependent row) the
// paths are certified exactly and the test's comparison was too tight; in
// 294 and 304 Lemke's secondary ray was off (fixed in lemke.rs). Their `cc` lines are in
// `proptest-regressions/mixed.txt`; the instances are also fixed here.

fn fixed_instance(
    rows: &[&[f64]],
    q: &[f64],
    d: &[f64],
    free: usize,
    lambda_max: Option<f64>,
) -> Instance {
    Instance {
        m: mat_from_rows(&rows.iter().map(|r| r.to_vec()).collect::<Vec<_>>()),
        q: q.to_vec(),
        d: d.to_vec(),
        free,
        lambda0: 0.0,
        lambda_max,
        kind: Kind::Other,
    }
}

/// Seed 257 (nonsingular, linear in z): Wolfe reports residual 7.2e-11.
fn seed_257() -> Instance {
    fixed_instance(
        &[
            &[0.671875, -0.3125, -1.0, 1.0, -0.875, 0.0, 0.0, 0.0, 0.0],
            &[-0.3125, 0.96875, 0.03125, 0.125, 0.75, 0.0, 0.0, 0.0, 0.0],
            &[-1.0, 0.03125, 1.71875, 0.625, 0.125, 0.0, 0.0, 0.0, 0.0],
            &[-1.0, -0.125, -0.625, 0.0, 0.0, -0.25, -1.0, 0.5, 0.875],
            &[0.875, -0.75, -0.125, 0.0, 0.0, -0.875, -0.75, -0.75, -0.25],
            &[0.0, 0.0, 0.0, 0.25, 0.875, 0.0, 0.0, 0.0, 0.0],
            &[0.0, 0.0, 0.0, 1.0, 0.75, 0.0, 0.0, 0.0, 0.0],
            &[0.0, 0.0, 0.0, -0.5, 0.75, 0.0, 0.0, 0.0, 0.0],
            &[0.0, 0.0, 0.0, -0.875, 0.25, 0.0, 0.0, 0.0, 0.0],
        ],
        &[
            -0.4375, 0.125, -0.8125, 1.015625, 1.171875, 0.4375, -0.5, -0.625, 0.25,
        ],
        &[
            -0.75, -1.0, -0.8125, 0.0, 0.0, -0.1875, 0.375, -0.9375, -0.9375,
        ],
        5,
        None,
    )
}

/// Seed 294 (nonsingular): Lemke puts the secondary ray L* = 16/11 at 8e-8 relative.
fn seed_294() -> Instance {
    fixed_instance(
        &[
            &[1.0625, -0.90625, 0.75, -0.875, -0.0, -0.0, -0.0, -0.0],
            &[-0.90625, 0.78125, 0.625, -0.875, 0.0, 0.0, 0.0, 0.0],
            &[-0.75, -0.625, 0.0, 0.0, 0.75, -0.375, 0.5, 0.875],
            &[0.875, 0.875, 0.0, 0.0, 0.125, -0.25, 0.125, 0.75],
            &[-0.0, 0.0, -0.75, -0.125, 0.0, 0.0, 0.0, 0.0],
            &[-0.0, 0.0, 0.375, 0.25, 0.0, 0.0, 0.0, 0.0],
            &[-0.0, 0.0, -0.5, -0.125, 0.0, 0.0, 0.0, 0.0],
            &[-0.0, 0.0, -0.875, -0.75, 0.0, 0.0, 0.0, 0.0],
        ],
        &[0.6875, -1.0, 0.015625, -2.0625, -1.0, 0.0, 0.4375, 1.0],
        &[-0.4375, 0.375, 0.0, 0.0, -0.8125, 0.1875, -0.875, -0.625],
        4,
        Some(3.25),
    )
}

/// Seed 304 (dependent row): Wolfe has residual 2.5e-11 at its breakpoint.
fn seed_304_dependent() -> Instance {
    fixed_instance(
        &[
            &[0.78125, 0.09375, 1.0, 2.0, 0.140625, -0.09375, 0.15625],
            &[0.09375, 1.34375, -0.875, -1.75, -0.859375, 0.25, 0.5625],
            &[-1.0, 0.875, 0.0, 0.0, -0.5, 0.375, -0.25],
            &[-2.0, 1.75, 0.0, 0.0, -1.0, 0.75, -0.5],
            &[0.140625, -0.859375, 0.5, 1.0, 1.46875, -0.609375, -1.203125],
            &[
                -0.09375, 0.25, -0.375, -0.75, -0.609375, 2.390625, -0.703125,
            ],
            &[0.15625, 0.5625, 0.25, 0.5, -1.203125, -0.703125, 1.828125],
        ],
        &[0.25, 0.0, 0.265625, 0.53125, -0.8125, 0.25, -0.0625],
        &[-0.3125, 0.8125, 0.2890625, 0.578125, 0.75, -0.125, 0.125],
        4,
        None,
    )
}

/// Seed 304 (nonsingular): Lemke puts the secondary ray L* = 2/25 at 1e-8 relative.
fn seed_304() -> Instance {
    fixed_instance(
        &[
            &[
                1.953125, 0.328125, -0.046875, -0.5, 0.125, 0.0, 0.0, 0.0, 0.0,
            ],
            &[0.328125, 1.46875, 0.671875, -1.0, 0.375, 0.0, 0.0, 0.0, 0.0],
            &[-0.046875, 0.671875, 0.328125, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0],
            &[0.5, 1.0, -0.5, 0.0, 0.0, -0.125, 0.625, 0.125, -0.125],
            &[-0.125, -0.375, -0.0, 0.0, 0.0, 0.5, 0.875, -0.25, -1.0],
            &[0.0, 0.0, 0.0, 0.125, -0.5, 0.0, 0.0, 0.0, 0.0],
            &[0.0, 0.0, 0.0, -0.625, -0.875, 0.0, 0.0, 0.0, 0.0],
            &[0.0, 0.0, 0.0, -0.125, 0.25, 0.0, 0.0, 0.0, 0.0],
            &[0.0, 0.0, 0.0, 0.125, 1.0, 0.0, 0.0, 0.0, 0.0],
        ],
        &[
            0.3125, 0.0625, -0.375, -0.15625, 0.21875, -0.25, 0.3125, 0.25, 0.25,
        ],
        &[
            1.0, 0.9375, -0.6875, 0.0, 0.0, -0.6875, 0.25, 0.9375, -0.3125,
        ],
        5,
        None,
    )
}

/// Found while seed 257 shrank: the exact path ends on a secondary ray at
/// L* = 25/82 (Wolfe, certified); Lemke on the reduction reads the rate of L
/// there as 2.7e-10 and claims an unbounded ray from L*, rejected exactly.
fn secondary_ray_read_as_unbounded() -> Instance {
    fixed_instance(
        &[
            &[
                1.671875, -0.71875, 0.046875, -0.5, 0.125, 0.0, 0.0, 0.0, 0.0,
            ],
            &[-0.71875, 2.25, 0.671875, 0.875, -0.25, 0.0, 0.0, 0.0, 0.0],
            &[
                0.046875, 0.671875, 2.65625, -0.625, 0.125, 0.0, 0.0, 0.0, 0.0,
            ],
            &[0.5, -0.875, 0.625, 0.0, 0.0, -0.125, -0.0, -0.75, 0.75],
            &[-0.125, 0.25, -0.125, 0.0, 0.0, -0.75, 0.625, -0.625, -0.75],
            &[0.0, 0.0, 0.0, 0.125, 0.75, 0.0, 0.0, 0.0, 0.0],
            &[0.0, 0.0, 0.0, 0.0, -0.625, 0.0, 0.0, 0.0, 0.0],
            &[0.0, 0.0, 0.0, 0.75, 0.625, 0.0, 0.0, 0.0, 0.0],
            &[0.0, 0.0, 0.0, -0.75, 0.75, 0.0, 0.0, 0.0, 0.0],
        ],
        &[
            -0.0625, 0.75, -0.875, -1.375, 0.546875, -0.0625, 0.0, 0.75, 1.0,
        ],
        &[
            1.0, 0.3125, -0.3125, -0.0703125, 0.3046875, -0.4375, 0.1875, 0.875, -1.0,
        ],
        5,
        None,
    )
}

/// Seed 198 (nonsingular, linear in z): at L = 12129 (|x| ~ 9e3) Clarabel's
/// x_3 is 1.07 where both certified paths have 0.
fn seed_198() -> Kkt {
    Kkt {
        nf: 3,
        nb: 2,
        h: mat_from_rows(&[
            vec![1.15625, 0.796875, 1.28125, 0.0, 0.0],
            vec![0.796875, 1.46875, 0.921875, 0.0, 0.0],
            vec![1.28125, 0.921875, 1.59375, 0.0, 0.0],
            vec![0.0; 5],
            vec![0.0; 5],
        ]),
        a: mat_from_rows(&[
            vec![0.75, 0.875, -0.625, 0.5, -1.0],
            vec![0.0, -0.5, 0.5, -0.875, -0.625],
        ]),
        b: vec![0.359375, -1.140625],
        bd: vec![0.0, 0.0],
        c: vec![0.6875, 0.875, -1.0, 0.4375, 0.3125],
        e: vec![-1.0, -0.8125, -0.0625, -0.6875, 0.25],
        lambda_max: None,
        variant: "nonsingular, linear in z",
    }
}

#[test]
fn seed_198_clarabel_is_held_to_its_own_accuracy() {
    let kkt = seed_198();
    let inst = kkt.instance();
    let tol = for_conditioning(F64, &inst);
    let problem = inst.plcp::<f64>();
    assert!(kkt.unique_x(), "curvature {:e}", kkt.curvature());
    for method in [Method::Lemke, Method::Wolfe] {
        let path = solve_with(&problem, method).unwrap();
        assert_eq!(path.status, Status::UnboundedRay, "{method:?}");
        assert!(plcp::certify(&problem, &path).certified(), "{method:?}");
        let own = own_residual(tol.path, &path);
        let pts = check_path(&problem, &path, own, 0.5, Continuity::All, true).unwrap();
        compare_with_clarabel(&kkt, &problem, &path, &pts, tol).unwrap();
        // the ray's start, where Clarabel was off: the path's point moved by
        // 1e-4 of its scale in x_0 is rejected
        let mut pt = path.end.clone();
        let scale = kkt.x_of(&pt).iter().fold(1.0f64, |m, v| m.max(v.abs()));
        pt.u[0] += 1e-4 * scale;
        let e = compare_with_clarabel(&kkt, &problem, &path, &[pt], tol)
            .expect_err("x_0 off by 1e-4 of the scale");
        println!("{method:?} at L = {}: {e}", path.end.lambda);
    }
}

/// Lemke's secondary ray on the reduction: `L*` is taken from the polished
/// segment (`lemke.rs`, `reintersect_secondary_ray`); it was 8e-8 (seed 294)
/// and 1e-8 (seed 304) relative off the exact `16/11` and `2/25`.
#[test]
fn seeds_294_304_lemke_secondary_ray_at_the_exact_l() {
    for (inst, exact) in [(seed_294(), 16.0 / 11.0), (seed_304(), 2.0 / 25.0)] {
        let tol = for_conditioning(F64, &inst);
        let problem = inst.plcp::<f64>();
        let lemke = solve_with(&problem, Method::Lemke).unwrap();
        let wolfe = solve_with(&problem, Method::Wolfe).unwrap();
        for p in [&lemke, &wolfe] {
            assert_eq!(p.status, Status::SecondaryRay, "{}", p.message);
            assert!(plcp::certify(&problem, p).certified(), "{}", p.message);
            let l = p.lambda_reached;
            assert!(
                (l - exact).abs() <= 1e-14 * exact,
                "{}: L* = {l} for {exact}",
                p.info.method
            );
            assert_eq!(p.end.lambda, l);
            assert!(p.info.residual.worst() < 1e-12, "{:?}", p.info.residual);
        }
        let unique = reduced_positive_definite(&inst);
        compare_paths(&lemke, &wolfe, unique, tol.agree, 0.5).unwrap();
        // still able to fail: Wolfe's L* (its last breakpoint and the end)
        // moved by 1e-8 relative, the size of Lemke's error before
        let lw = wolfe.lambda_reached;
        let shift = 1e-8 * lw.abs().max(1.0);
        let mut moved = wolfe.clone();
        moved.lambda_reached += shift;
        moved.end.lambda += shift;
        for b in moved.breakpoints.iter_mut().filter(|b| b.lambda == lw) {
            b.lambda += shift;
        }
        if let Some(s) = moved.segments.last_mut() {
            s.lambda_to += shift;
        }
        let e =
            compare_paths(&lemke, &moved, unique, tol.agree, 0.5).expect_err("L* moved by 1e-8");
        assert!(e.contains("lambda_reached differ"), "{e}");
    }
}

#[test]
fn seeds_257_304_wolfe_residual_within_its_own_bases() {
    for inst in [seed_257(), seed_304_dependent()] {
        let tol = for_conditioning(F64, &inst);
        let problem = inst.plcp::<f64>();
        let wolfe = solve_with(&problem, Method::Wolfe).unwrap();
        assert_eq!(wolfe.status, Status::UnboundedRay, "{}", wolfe.message);
        assert!(plcp::certify(&problem, &wolfe).certified());
        let own = own_residual(tol.path, &wolfe);
        println!(
            "residual {:?}, max_condition {:e}: tolerance {:e} (stated {:e})",
            wolfe.info.residual, wolfe.info.max_condition, own.residual, tol.path.residual
        );
        check_path(&problem, &wolfe, own, 0.5, Continuity::None, true).unwrap();
        // still able to fail: one segment's values off by 1e-6 of its scale
        let mut off = wolfe.clone();
        let s = off.segments.last_mut().unwrap();
        let scale = s
            .z_from
            .iter()
            .chain(s.u_from.iter())
            .fold(1.0f64, |m, v| m.max(v.abs()));
        let i = (0..s.z_from.nrows())
            .max_by(|&a, &b| s.z_from[a].abs().total_cmp(&s.z_from[b].abs()))
            .unwrap();
        s.z_from[i] += 1e-6 * scale;
        let e = check_path(&problem, &off, own, 0.5, Continuity::None, true)
            .expect_err("values off by 1e-6");
        assert!(e.contains("residual"), "{e}");
    }
}

/// A wrong success, fixed: Lemke on the Schur reduction claimed
/// `unbounded_ray` where the exact path ends on a secondary ray (a zero rate
/// of `L` read as `2.7e-10` against a direction of order one); the ray is
/// now doubted against the reduced basis's noise (`lemke.rs`
/// `doubt_ray_on_reduction`) and the path stops `ill_conditioned`.
#[test]
fn lemke_on_the_reduction_claims_no_ray_the_certificate_rejects() {
    let problem = secondary_ray_read_as_unbounded().plcp::<f64>();
    let wolfe = solve_with(&problem, Method::Wolfe).unwrap();
    assert_eq!(wolfe.status, Status::SecondaryRay);
    assert!(plcp::certify(&problem, &wolfe).certified());
    let lemke = solve_with(&problem, Method::Lemke).unwrap();
    assert!(
        !lemke.status.is_success() || plcp::certify(&problem, &lemke).certified(),
        "Lemke: {:?} ({}), rejected exactly",
        lemke.status,
        lemke.message
    );
}
