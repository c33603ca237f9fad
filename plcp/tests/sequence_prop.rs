//! The solver object's warm path against cold solves on random monotone
//! problems (property test): `M = B B'/n + S + 0.1 I` with `S` skew, so
//! `M + M'` is positive definite and every PLCP on it has one solution. A
//! loop of lean steps ([`plcp::Solver::step_end`]) with a drifting linear
//! term, and a jump in the middle (data that do not continue the last end:
//! the cold start), must give at every step the end z of an independent
//! cold `plcp::solve` of the same PLCP, start warm wherever the data
//! continue (again after the jump), and report the end residual it
//! measured.

use faer::{Col, Mat};
use plcp::{Plcp, Settings, Solver, Status};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// `M`, the targets `g_0..g_k` (steps of `step` times a uniform vector), and
/// a jump target replacing `g_jump` (its own draw, not a continuation).
fn instance(n: usize, k: usize, step: f64, seed: u64) -> (Mat<f64>, Vec<Col<f64>>, Col<f64>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut unit = move || rng.gen_range(-1.0..1.0f64);
    let b = Mat::<f64>::from_fn(n, n, |_, _| unit());
    let s = Mat::<f64>::from_fn(n, n, |_, _| unit());
    let m = Mat::<f64>::from_fn(n, n, |i, j| {
        let bb: f64 = (0..n).map(|l| b[(i, l)] * b[(j, l)]).sum();
        let skew = 0.5 * (s[(i, j)] - s[(j, i)]);
        bb / n as f64 + skew + if i == j { 0.1 } else { 0.0 }
    });
    let mut g = vec![Col::<f64>::from_fn(n, |_| unit())];
    for _ in 0..k {
        let last = g.last().unwrap().clone();
        g.push(Col::from_fn(n, |i| last[i] + step * unit()));
    }
    let jump = Col::<f64>::from_fn(n, |_| 2.0 * unit());
    (m, g, jump)
}

fn max_diff(a: &Col<f64>, b: &Col<f64>) -> f64 {
    (0..a.nrows())
        .map(|i| (a[i] - b[i]).abs())
        .fold(0.0, f64::max)
}

fn max_abs(a: &Col<f64>) -> f64 {
    (0..a.nrows()).map(|i| a[i].abs()).fold(1.0, f64::max)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn warm_lean_steps_equal_cold_solves(
        n in 1usize..24,
        step in 0.01..1.0f64,
        seed in any::<u64>(),
    ) {
        let k = 12;
        let (m, mut g, jump) = instance(n, k, step, seed);
        let settings = Settings::<f64>::default();
        let mut solver = Solver::new(m.as_ref(), &settings).unwrap();
        let first = solver.lcp_end(g[0].as_ref()).unwrap();
        prop_assert_eq!(first.status, Status::Reached);
        // the step into `k / 2` goes from the last end to an unrelated
        // target (still continuing); the one after it starts from data that
        // do not continue the last end: the cold start
        g[k / 2] = jump;
        for s in 1..=k {
            let q = if s == k / 2 + 1 {
                // not where the last step ended
                Col::<f64>::from_fn(n, |i| g[s - 1][i] + 0.5)
            } else {
                g[s - 1].clone()
            };
            let d = &g[s] - &q;
            let end = solver.step_end(q.as_ref(), d.as_ref()).unwrap().clone();
            prop_assert_eq!(end.status, Status::Reached, "step {}: {}", s, end.message);
            let continues = s != k / 2 + 1;
            if continues {
                prop_assert!(end.warm, "step {}: the data continue the last end", s);
                prop_assert_eq!(end.start_pivots, 0);
            }
            let worst = end.residual.worst();
            prop_assert!(worst.is_finite() && worst < 1e-12, "step {}: residual {:e}", s, worst);
            let problem = Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
                .unwrap()
                .with_range(0.0, Some(1.0))
                .unwrap();
            let cold = plcp::solve(&problem, &settings).unwrap();
            prop_assert_eq!(cold.status, Status::Reached);
            let diff = max_diff(&end.end.z, &cold.end.z) / max_abs(&cold.end.z);
            prop_assert!(diff < 1e-9, "n = {}, step {}: end z differ by {:e}", n, s, diff);
        }
    }
}
