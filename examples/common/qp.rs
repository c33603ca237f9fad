//! An independent convex QP solve by Clarabel's interior-point method, for
//! checking the everyday paths (examples and `tests/everyday_paths.rs`):
//!
//! `min 1/2 x'P x + c'x  subject to  A_eq x = b_eq,  A_in x <= b_in`.

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus,
    SupportedConeT, ZeroConeT,
};
use faer::MatRef;

/// The minimiser, or `None` if Clarabel does not report `Solved`.
pub fn clarabel_qp(
    p: MatRef<'_, f64>,
    c: &[f64],
    a_eq: MatRef<'_, f64>,
    b_eq: &[f64],
    a_in: MatRef<'_, f64>,
    b_in: &[f64],
) -> Option<Vec<f64>> {
    let n = p.ncols();
    // Clarabel takes the upper triangle of P
    let p_rows: Vec<Vec<f64>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| if j >= i { p[(i, j)] } else { 0.0 })
                .collect()
        })
        .collect();
    let mut a_rows: Vec<Vec<f64>> = Vec::new();
    for a in [a_eq, a_in] {
        for i in 0..a.nrows() {
            a_rows.push((0..n).map(|j| a[(i, j)]).collect());
        }
    }
    let rhs: Vec<f64> = b_eq.iter().chain(b_in).copied().collect();
    let mut cones: Vec<SupportedConeT<f64>> = Vec::new();
    if !b_eq.is_empty() {
        cones.push(ZeroConeT(b_eq.len()));
    }
    cones.push(NonnegativeConeT(b_in.len()));
    let settings = DefaultSettingsBuilder::default()
        .verbose(false)
        .tol_gap_abs(1e-12)
        .tol_gap_rel(1e-12)
        .tol_feas(1e-12)
        .build()
        .ok()?;
    let (pm, am) = (CscMatrix::from(&p_rows), CscMatrix::from(&a_rows));
    let mut solver = DefaultSolver::new(&pm, c, &am, &rhs, &cones, settings).ok()?;
    solver.solve();
    matches!(
        solver.solution.status,
        SolverStatus::Solved | SolverStatus::AlmostSolved
    )
    .then(|| solver.solution.x.clone())
}

/// `1/2 x'P x + c'x`.
pub fn objective(p: MatRef<'_, f64>, c: &[f64], x: &[f64]) -> f64 {
    let n = x.len();
    let mut f = 0.0;
    for i in 0..n {
        f += c[i] * x[i];
        for j in 0..n {
            f += 0.5 * x[i] * p[(i, j)] * x[j];
        }
    }
    f
}
