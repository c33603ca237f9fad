//! The solver object of the MPC user's loop ([`plcp::Solver`]) against
//! independent cold solves: each step's end z equals `plcp::solve` of the
//! same PLCP started from scratch (the LCP at g_0 against `solve_lcp`), on
//! random positive definite M with a drifting linear term; and the warm steps
//! start where the last ended (no start phase after the first step).

use faer::{Col, Mat};
use plcp::{Plcp, Settings, Solver, Status};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// `M = B B'/n + 0.1 I` (B standard-ish Gaussian by Box-Muller), `g_0` and
/// steps of size `step` (the family of the qpOASES comparison).
fn instance(n: usize, k: usize, step: f64, seed: u64) -> (Mat<f64>, Vec<Col<f64>>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut gauss = move || {
        let (u, v): (f64, f64) = (rng.gen_range(1e-12..1.0), rng.gen_range(0.0..1.0));
        (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
    };
    let b = Mat::<f64>::from_fn(n, n, |_, _| gauss());
    let m = Mat::<f64>::from_fn(n, n, |i, j| {
        let s: f64 = (0..n).map(|l| b[(i, l)] * b[(j, l)]).sum();
        s / n as f64 + if i == j { 0.1 } else { 0.0 }
    });
    let mut g = vec![Col::<f64>::from_fn(n, |_| gauss())];
    for _ in 0..k {
        let last = g.last().unwrap().clone();
        g.push(Col::from_fn(n, |i| last[i] + step * gauss()));
    }
    (m, g)
}

fn max_diff(a: &Col<f64>, b: &Col<f64>) -> f64 {
    (0..a.nrows())
        .map(|i| (a[i] - b[i]).abs())
        .fold(0.0, f64::max)
}

fn check(n: usize, k: usize, step: f64, seed: u64) {
    let (m, g) = instance(n, k, step, seed);
    let settings = Settings::<f64>::default();
    let mut solver = Solver::new(m.as_ref(), &settings).unwrap();
    let first = solver.lcp(g[0].as_ref()).unwrap();
    assert_eq!(first.status, Status::Reached);
    let cold = plcp::solve_lcp(
        &plcp::Lcp::new(m.as_ref(), g[0].as_ref()).unwrap(),
        &settings,
    )
    .unwrap();
    assert!(max_diff(&first.end.z, &cold.z) < 1e-10, "step 0");
    let mut warm_steps = 0;
    for s in 1..=k {
        let d = &g[s] - &g[s - 1];
        let path = solver.step(g[s - 1].as_ref(), d.as_ref()).unwrap();
        assert_eq!(path.status, Status::Reached, "step {s}: {}", path.message);
        assert!(
            path.info.residual.worst() < 1e-12,
            "step {s}: {:?}",
            path.info.residual
        );
        warm_steps += usize::from(path.info.warm_start && path.info.start_pivots == 0);
        let problem = Plcp::new(m.as_ref(), g[s - 1].as_ref(), d.as_ref())
            .unwrap()
            .with_range(0.0, Some(1.0))
            .unwrap();
        let cold = plcp::solve(&problem, &settings).unwrap();
        assert_eq!(cold.status, Status::Reached);
        let diff = max_diff(&path.end.z, &cold.end.z);
        assert!(diff < 1e-10, "n = {n}, step {s}: end z differ by {diff:e}");
        // the end of step s is the LCP at g_s
        let at = plcp::solve_lcp(
            &plcp::Lcp::new(m.as_ref(), g[s].as_ref()).unwrap(),
            &settings,
        )
        .unwrap();
        assert!(
            max_diff(&path.end.z, &at.z) < 1e-10,
            "step {s} against the LCP at g_s"
        );
    }
    assert_eq!(
        warm_steps, k,
        "every step after the first starts where the last ended"
    );
}

#[test]
fn steps_equal_cold_solves_small() {
    check(5, 40, 0.3, 1);
}

#[test]
fn steps_equal_cold_solves_medium() {
    check(30, 60, 0.1, 2);
    check(50, 30, 0.5, 3);
}

/// A step whose data do not start where the last ended (the basis is not a
/// feasible start) falls back to the cold start and still answers right.
#[test]
fn a_jump_falls_back_to_the_cold_start() {
    let (m, g) = instance(20, 3, 0.1, 4);
    let settings = Settings::<f64>::default();
    let mut solver = Solver::new(m.as_ref(), &settings).unwrap();
    solver.lcp(g[0].as_ref()).unwrap();
    let q = Col::<f64>::from_fn(20, |i| if i % 2 == 0 { -1.0 } else { 1.0 });
    let d = &g[1] - &q;
    let path = solver.step(q.as_ref(), d.as_ref()).unwrap();
    let problem = Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
        .unwrap()
        .with_range(0.0, Some(1.0))
        .unwrap();
    let cold = plcp::solve(&problem, &settings).unwrap();
    assert_eq!(path.status, Status::Reached);
    assert!(!path.info.warm_start);
    assert!(max_diff(&path.end.z, &cold.end.z) < 1e-10);
}

#[test]
fn bad_data_are_errors() {
    let m = Mat::<f64>::identity(3, 3);
    let settings = Settings::<f64>::default();
    let mut solver = Solver::new(m.as_ref(), &settings).unwrap();
    assert!(solver.lcp(Col::<f64>::zeros(2).as_ref()).is_err());
    let bad = Col::<f64>::from_fn(3, |i| if i == 1 { f64::NAN } else { 1.0 });
    assert!(solver.lcp(bad.as_ref()).is_err());
    assert!(Solver::new(Mat::<f64>::zeros(2, 3).as_ref(), &settings).is_err());
}

/// The lean steps (`Solver::step_end`, no `Path`) trace the same pivots as
/// the full steps (`Solver::step`) of a second solver on the same data: the
/// same end z to the last bit, pivots, statuses and residuals; and each end
/// z equals an independent cold solve of the same PLCP.
#[test]
fn lean_steps_equal_full_steps_and_cold_solves() {
    for (n, k, seed) in [(8usize, 40usize, 3u64), (30, 60, 4), (60, 40, 5)] {
        let (m, g) = instance(n, k, 0.1, seed);
        let settings = Settings::<f64>::default();
        let mut full = Solver::new(m.as_ref(), &settings).unwrap();
        let mut lean = Solver::new(m.as_ref(), &settings).unwrap();
        let a = full.lcp(g[0].as_ref()).unwrap();
        let b = lean.lcp_end(g[0].as_ref()).unwrap();
        assert_eq!(a.status, b.status);
        assert_eq!(max_diff(&a.end.z, &b.end.z), 0.0, "n = {n}, step 0");
        for s in 1..=k {
            let d = &g[s] - &g[s - 1];
            let a = full.step(g[s - 1].as_ref(), d.as_ref()).unwrap();
            let b = lean.step_end(g[s - 1].as_ref(), d.as_ref()).unwrap();
            assert_eq!(a.status, b.status, "n = {n}, step {s}");
            assert_eq!(
                b.status,
                Status::Reached,
                "n = {n}, step {s}: {}",
                b.message
            );
            assert_eq!(a.info.pivots, b.pivots, "n = {n}, step {s}");
            assert_eq!(a.info.warm_start, b.warm, "n = {n}, step {s}");
            assert_eq!(a.info.residual, b.residual, "n = {n}, step {s}");
            assert_eq!(max_diff(&a.end.z, &b.end.z), 0.0, "n = {n}, step {s}");
            assert_eq!(max_diff(&a.end.w, &b.end.w), 0.0, "n = {n}, step {s}");
            let problem = Plcp::new(m.as_ref(), g[s - 1].as_ref(), d.as_ref())
                .unwrap()
                .with_range(0.0, Some(1.0))
                .unwrap();
            let cold = plcp::solve(&problem, &settings).unwrap();
            assert!(
                max_diff(&cold.end.z, &b.end.z) < 1e-10,
                "n = {n}, step {s}: {:e}",
                max_diff(&cold.end.z, &b.end.z)
            );
        }
    }
}

/// `plcp::warm_up` solves its small problem and steps its solver (it
/// reports whether both reached their ends: a warm-up that failed would
/// leave the first real solve paying the one-time costs).
#[test]
fn warm_up_solves_its_problem() {
    assert!(plcp::warm_up());
}
