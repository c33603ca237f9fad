//! `Settings::threads = Some(1)` keeps the whole solve on the calling thread:
//! no thread pool is started, also where the default would use one (the
//! inversions of large blocks at refactorisation read faer's global
//! parallelism before, whatever the setting said).
//!
//! One test in this file: the process's thread count is read before and after
//! (`/proc/self/task`, Linux), so no other test may run beside it.

use faer::{Col, Mat};
use plcp::{Plcp, Settings, Status};

/// A positive definite `M = D + (R - R') / 2` (`D` diagonal in `[1, 2]`, `R`
/// uniform in `[-1, 1]`: the skew part leaves `x'Mx = x'Dx`), `q` in
/// `[0.1, 1]`, `d` in `[-1.5, 0.5]`: from a seeded linear congruential
/// generator (no matrix product, which could itself start a pool).
fn instance(n: usize) -> (Mat<f64>, Col<f64>, Col<f64>) {
    let mut s: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = move || {
        s = s
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let r = Mat::<f64>::from_fn(n, n, |_, _| 2.0 * next() - 1.0);
    let diag: Vec<f64> = (0..n).map(|_| 1.0 + next()).collect();
    let m = Mat::<f64>::from_fn(n, n, |i, j| {
        (r[(i, j)] - r[(j, i)]) / 2.0 + if i == j { diag[i] } else { 0.0 }
    });
    let q = Col::<f64>::from_fn(n, |_| 0.1 + 0.9 * next());
    let d = Col::<f64>::from_fn(n, |_| next() * 2.0 - 1.5);
    (m, q, d)
}

#[cfg(target_os = "linux")]
fn threads_now() -> usize {
    std::fs::read_dir("/proc/self/task")
        .map(|d| d.count())
        .unwrap_or(0)
}

/// A path at n = 700 whose basis block grows past order 322 (where the
/// inversion at refactorisation went parallel by faer's global setting)
/// with `threads: Some(1)`: the thread count of the process does not grow.
#[cfg(target_os = "linux")]
#[test]
fn one_thread_setting_starts_no_pool() {
    let n = 700;
    let (m, q, d) = instance(n);
    let problem = Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
        .unwrap()
        .with_range(0.0, Some(50.0))
        .unwrap();
    let settings = Settings::<f64> {
        threads: Some(1),
        ..Settings::default()
    };
    let before = threads_now();
    let path = plcp::solve(&problem, &settings).unwrap();
    let after = threads_now();
    assert!(
        path.status.is_success(),
        "{:?}: {}",
        path.status,
        path.message
    );
    let k = path.end.z.iter().filter(|&&z| z > 0.0).count();
    assert!(
        k > 400 && path.info.refactorisations > 0,
        "the block must grow past order 322 with refactorisations: {k} basic z, {} refactorisations",
        path.info.refactorisations
    );
    assert_ne!(path.status, Status::IllConditioned);
    assert_eq!(before, after, "threads before and after the solve");
}
