//! The full path on random dense monotone PLCPs, Lemke against Wolfe.
//!
//! Instances: `plcp_workspace::random::bench_instance(n, seed = 1)` for
//! n = 50, 200, 1000: `M = B B'/n + 0.1 I` (`B` standard Gaussian), `q` uniform in
//! `[0.1, 1]`, `d` Gaussian minus 0.5, `lambda_max` midway between the `n/2`-th and
//! `(n/2 + 1)`-th breakpoints of the full path (so each timed solve does about
//! `n/2` pivots and ends with `Reached`). The instance is built (and its full
//! path traced once) outside the timed loop.
//!
//! Sample sizes are criterion's minimum (10) with short measurement times, so
//! that `cargo bench --bench path` finishes in a few minutes; n = 1000 takes
//! most of it.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use plcp::{Method, Settings, Status};
use plcp_workspace::random::bench_instance;
use std::time::Duration;

fn full_path(c: &mut Criterion) {
    let mut group = c.benchmark_group("path");
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(3));
    for n in [50usize, 200, 1000] {
        let inst = bench_instance(n, 1);
        for method in [Method::Lemke, Method::Wolfe] {
            let settings = Settings::<f64>::with_method(method);
            // outside the timing: the instance does what the docs say
            let path = plcp::solve(&inst.problem, &settings).expect("valid settings");
            assert!(
                matches!(path.status, Status::Reached | Status::UnboundedRay),
                "{method:?}, n = {n}: {:?} ({})",
                path.status,
                path.message
            );
            let name = match method {
                Method::Lemke => "lemke",
                Method::Wolfe => "wolfe",
            };
            group.bench_with_input(BenchmarkId::new(name, n), &inst.problem, |b, p| {
                b.iter(|| plcp::solve(p, &settings).expect("valid settings"))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, full_path);
criterion_main!(benches);
