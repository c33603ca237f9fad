//! The full path on random dense monotone PLCPs: Lemke against Wolfe, f32 /
//! f64 / fx128, block against dense basis inverse, and Clarabel (interior
//! point) in the same run as the peer.
//!
//! ```sh
//! cargo bench --bench path                       # n = 50 ... 1000
//! PLCP_BENCH_MAX_N=2000 cargo bench --bench path # n = 2000 too (long)
//! PLCP_BENCH_FULL=1 cargo bench --bench path    # every variant at every n
//! ```
//!
//! Instances: `plcp_workspace::random::path_instance(n, seed = 1)` (the same
//! problem and `lambda_max` as `bench_instance`) for n = 50, 200, 500, 1000,
//! 2000: `M = B B'/n + 0.1 I` (`B` standard Gaussian), `q` uniform in
//! `[0.1, 1]`, `d` Gaussian minus 0.5, `lambda_max` midway between the `n/2`-th
//! and `(n/2 + 1)`-th breakpoints (found by a first solve outside the timing),
//! so each timed solve does about `n/2` pivots and ends with `Reached`.
//!
//! Groups (criterion ids `group/variant/n`):
//!
//! * `path/{lemke,wolfe}-{f32,f64,f128}-{block,dense}`: `plcp::solve` with the
//!   default settings but for the method and basis. fx128 runs for n <= 200
//!   only; for n >= 1000 only f64 runs (and the dense basis only with
//!   `PLCP_BENCH_FULL=1`), because one solve takes seconds there.
//! * `clarabel/{lmax,k10,k100}`: Clarabel 0.11 on the QP
//!   `min 1/2 z'Mz + (q + L d)'z, z >= 0` at `L_max` alone, and at K = 10 and
//!   100 evenly spaced values of `L` (the path approximated by re-solving;
//!   one solver object, `update_q` between solves). K = 100 for n <= 200 and
//!   K = 10 for n <= 500 unless `PLCP_BENCH_FULL=1`.
//!
//! Sample sizes are criterion's minimum (10), flat sampling (each sample one
//! iteration when a run is long), short warm-up and measurement times: every
//! variant runs at least 11 times, so n = 1000 takes about a minute and
//! n = 2000 (opt-in, `PLCP_BENCH_MAX_N=2000`) about ten; `speed_report`
//! measures n = 2000 more cheaply (best of few runs). f32 paths that stop
//! early (`IllConditioned`, which happens from n = 200 on) are reported on
//! stderr and not timed.

use criterion::{
    criterion_group, criterion_main, BenchmarkGroup, BenchmarkId, Criterion, SamplingMode,
};
use plcp::{BasisKind, Method, Plcp, Scalar, Settings};
use plcp_workspace::random::path_instance;
use std::time::Duration;

#[path = "../examples/common/speed/peer.rs"]
mod peer;

fn sizes() -> Vec<usize> {
    let max_n = std::env::var("PLCP_BENCH_MAX_N")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1000usize);
    [50usize, 200, 500, 1000, 2000]
        .into_iter()
        .filter(|&n| n <= max_n)
        .collect()
}

fn full() -> bool {
    std::env::var_os("PLCP_BENCH_FULL").is_some()
}

/// For n at or above this size only f64 runs by default (see the module doc).
const LARGE_N: usize = 1000;

/// Times `f` with criterion (flat sampling: at least one warm-up run and ten
/// timed runs).
fn bench<M: criterion::measurement::Measurement<Value = Duration>>(
    group: &mut BenchmarkGroup<'_, M>,
    id: BenchmarkId,
    mut f: impl FnMut(),
) {
    group.bench_function(id, |b| b.iter(&mut f));
}

fn variant<T: Scalar>(
    group: &mut BenchmarkGroup<'_, criterion::measurement::WallTime>,
    problem: &Plcp<f64>,
    n: usize,
    method: Method,
    basis: BasisKind,
) {
    let problem: Plcp<T> = problem.cast();
    let mut settings = Settings::<T>::with_method(method);
    settings.basis = basis;
    // outside the timing: the instance does what the docs say (f64, fx128);
    // f32 may stop early (IllConditioned), and a stopped path is not timed
    let path = plcp::solve(&problem, &settings).expect("valid settings");
    if T::NAME == "f32" && !path.status.is_success() {
        eprintln!(
            "path/{method:?}-f32-{basis:?}/{n}: not timed, the path stopped ({}) at L = {} of {}",
            path.status.as_str(),
            path.lambda_reached.to_f64(),
            problem.lambda_max().map_or(f64::INFINITY, |l| l.to_f64())
        );
        return;
    }
    assert!(
        path.status.is_success(),
        "{method:?} {} {basis:?}, n = {n}: {:?} ({})",
        T::NAME,
        path.status,
        path.message
    );
    let name = format!(
        "{}-{}-{}",
        match method {
            Method::Lemke => "lemke",
            Method::Wolfe => "wolfe",
        },
        T::NAME,
        match basis {
            BasisKind::Block => "block",
            BasisKind::Dense => "dense",
            BasisKind::Sparse => "sparse",
        }
    );
    bench(group, BenchmarkId::new(name, n), || {
        std::hint::black_box(plcp::solve(&problem, &settings).expect("valid settings"));
    });
}

fn full_path(c: &mut Criterion) {
    let mut group = c.benchmark_group("path");
    group.sample_size(10);
    group.sampling_mode(SamplingMode::Flat);
    group.warm_up_time(Duration::from_millis(300));
    group.measurement_time(Duration::from_secs(2));
    for n in sizes() {
        let inst = path_instance(n, 1);
        for method in [Method::Lemke, Method::Wolfe] {
            for basis in [BasisKind::Block, BasisKind::Dense] {
                if n >= LARGE_N && basis == BasisKind::Dense && !full() {
                    continue;
                }
                variant::<f64>(&mut group, &inst.problem, n, method, basis);
                if n < LARGE_N || full() {
                    variant::<f32>(&mut group, &inst.problem, n, method, basis);
                }
                if n <= 200 {
                    variant::<faer::fx128>(&mut group, &inst.problem, n, method, basis);
                }
            }
        }
    }
    group.finish();
}

fn clarabel(c: &mut Criterion) {
    let mut group = c.benchmark_group("clarabel");
    group.sample_size(10);
    group.sampling_mode(SamplingMode::Flat);
    group.warm_up_time(Duration::from_millis(300));
    group.measurement_time(Duration::from_secs(2));
    for n in sizes() {
        let inst = path_instance(n, 1);
        let lmax = inst
            .problem
            .lambda_max()
            .expect("the instance has a finite lambda_max");
        for (name, k) in [("lmax", 1usize), ("k10", 10), ("k100", 100)] {
            let affordable = match k {
                1 => true,
                10 => n <= 500,
                _ => n <= 200,
            };
            if !affordable && !full() {
                continue;
            }
            let problem = &inst.problem;
            bench(&mut group, BenchmarkId::new(name, n), || {
                std::hint::black_box(peer::clarabel_samples(
                    problem,
                    lmax,
                    k,
                    peer::Tolerance::Default,
                ));
            });
        }
    }
    group.finish();
}

criterion_group!(benches, full_path, clarabel);
criterion_main!(benches);
