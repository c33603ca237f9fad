//! The frames cantilever (system (9), Wolfe's long form, f64): a uniform
//! cantilever of length 1 (Mp = 1, mass per length 1, tip force from rest)
//! cut into 10, 100, ... elements, the path traced to its unbounded ray (the
//! hinge front sweeps from the root to the tip).
//!
//! ```sh
//! cargo bench --bench cantilever                               # 10 and 100 elements
//! PLCP_BENCH_CANTILEVER="10,100,200,1000" cargo bench --bench cantilever
//! ```
//!
//! Timed: `frames::solve::solve` on the assembled system (assembly outside the
//! timing; it is measured as `assemble/n`). The default sizes stop at 100
//! elements: measured at the time of writing (single runs, 2 cores), 10
//! elements take 0.06 s, 100 take 0.9 s, 200 take 14 s (residual 2e-4) and
//! 400 take 180 s (residual 3e-5): about n^3.7, so 1000 elements (3000
//! unknowns) would take over an hour and are left out of the default run.
//! Every size runs at least 12 times (one check, one warm-up, ten samples).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode};
use frames::{Scene, SolveOptions, System};
use std::time::Duration;

fn scene(n: usize) -> Scene {
    let src = format!(
        "[[node]]\nid = \"A\"\nx = 0.0\ny = 0.0\n[[node]]\nid = \"B\"\nx = 1.0\ny = 0.0\n\
         [[member]]\nid = \"AB\"\nfrom = \"A\"\nto = \"B\"\nplastic_moment = 1.0\nmass_per_length = 1.0\nelements = {n}\n\
         [[support]]\nnode = \"A\"\nfix = [\"x\", \"y\", \"rz\"]\n[[load]]\nnode = \"B\"\nfy = -1.0\n"
    );
    Scene::from_toml(&src, &format!("cantilever-{n}.toml")).expect("valid scene")
}

fn sizes() -> Vec<usize> {
    std::env::var("PLCP_BENCH_CANTILEVER")
        .ok()
        .map(|s| s.split(',').filter_map(|t| t.trim().parse().ok()).collect())
        .unwrap_or_else(|| vec![10, 100])
}

fn cantilever(c: &mut Criterion) {
    let mut group = c.benchmark_group("cantilever");
    group.sample_size(10);
    group.sampling_mode(SamplingMode::Flat);
    group.warm_up_time(Duration::from_millis(300));
    group.measurement_time(Duration::from_secs(3));
    for n in sizes() {
        let sc = scene(n);
        group.bench_with_input(BenchmarkId::new("assemble", n), &sc, |b, sc| {
            b.iter(|| System::assemble(&sc.frame))
        });
        let system = System::assemble(&sc.frame);
        let options = SolveOptions::default();
        let sol = frames::solve::solve(&system, &options).expect("solvable");
        eprintln!(
            "cantilever {n}: {} pivots, status {}, residual {:.1e}",
            sol.info.pivots,
            sol.status.as_str(),
            sol.info.residual.worst()
        );
        assert!(sol.status.is_success(), "{n} elements: {:?}", sol.status);
        group.bench_with_input(BenchmarkId::new("path", n), &system, |b, s| {
            b.iter(|| frames::solve::solve(s, &options).expect("solvable"))
        });
    }
    group.finish();
}

criterion_group!(benches, cantilever);
criterion_main!(benches);
