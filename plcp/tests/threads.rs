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

fn solve_with(n: usize, threads: Option<usize>) -> plcp::Path<f64> {
    let (m, q, d) = instance(n);
    let problem = Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
        .unwrap()
        .with_range(0.0, Some(50.0))
        .unwrap();
    // the general engine's block basis (the fast path, which takes dense
    // problems up to `PRINCIPAL_MAX_N` = 800, runs on the calling thread)
    let settings = Settings::<f64> {
        threads,
        principal: false,
        ..Settings::default()
    };
    plcp::solve(&problem, &settings).unwrap()
}

/// A path at n = 700 whose basis block grows past order 322 (where the
/// inversion at refactorisation went parallel by faer's global setting):
/// with the default (by size: every product of this path is under the
/// parallel thresholds) and with `threads: Some(1)` the thread count of the
/// process does not grow; with `Some(2)` it does (the setting overrides the
/// size rule's `Par::Seq` for the inversions and the passes over `S^{-1}`
/// that are large enough to be split at all). The three paths are the same.
/// (One test: the rayon pool, once started, stays.)
#[cfg(target_os = "linux")]
#[test]
fn thread_setting_is_honoured() {
    let n = 700;
    let before = threads_now();
    let default = solve_with(n, None);
    let after_default = threads_now();
    let one = solve_with(n, Some(1));
    let after_one = threads_now();
    assert!(one.status.is_success(), "{:?}: {}", one.status, one.message);
    let k = one.end.z.iter().filter(|&&z| z > 0.0).count();
    assert!(
        k > 400 && one.info.refactorisations > 0,
        "the block must grow past order 322 with refactorisations: {k} basic z, {} refactorisations",
        one.info.refactorisations
    );
    assert_ne!(one.status, Status::IllConditioned);
    assert_eq!(
        before, after_default,
        "threads before and after the default solve"
    );
    assert_eq!(
        before, after_one,
        "threads before and after the one-thread solve"
    );
    let two = solve_with(n, Some(2));
    let after_two = threads_now();
    assert!(
        after_two > before,
        "threads: Some(2) must use the pool ({before} threads before, {after_two} after)"
    );
    for (name, other) in [("default", &default), ("two threads", &two)] {
        assert_eq!(other.status, one.status, "{name}");
        assert_eq!(other.info.pivots, one.info.pivots, "{name}: pivots");
        let dz = other
            .end
            .z
            .iter()
            .zip(one.end.z.iter())
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f64, f64::max);
        assert!(dz <= 1e-12, "{name}: end z differ by {dz:e}");
    }
}
