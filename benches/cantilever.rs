//! The frames cantilever (system (9), Wolfe's long form, f64): a uniform
//! cantilever of length 1 (Mp = 1, mass per length 1, tip force from rest)
//! cut into 10, 100, ... elements, the path traced to its unbounded ray (the
//! hinge front sweeps from the root to the tip).
//!
//! ```sh
//! cargo bench --bench cantilever                               # 10, 100, 200, 500, 1000 elements
//! PLCP_BENCH_CANTILEVER="10,100" cargo bench --bench cantilever
//! ```
//!
//! Timed: `frames::solve::solve` on the assembled system (assembly outside the
//! timing; it is measured as `assemble/n`). From 100 unknowns on (17
//! elements), frames hands plcp the sparse form with the sparse LU basis
//! (`frames::solve::SPARSE_FROM`); `path-dense/n` times the dense form with
//! the block basis for comparison, up to 100 elements (at 200 it takes over 10 s).
//! Measured (single runs, 2 cores shared): see the README's Performance
//! section. The basis condition grows like n^4 (about 4e9 at 1000 elements on
//! this path); from a condition of `refine_cond_eps / eps` on, the basic values
//! and entering columns are refined with residuals in extra precision
//! (`plcp::Scalar::Wide`), which keeps every size a success in f64 (before,
//! from about 700 elements a degenerate multiplier's forward error pushed the
//! feasibility residual past the sqrt(eps) guard). A size whose f64 path is
//! not a success is reported on stderr and still timed; the number of
//! refinement steps is printed with the other counts.
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
        .unwrap_or_else(|| vec![10, 100, 200, 500, 1000])
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
            "cantilever {n}: sparse {}, {} pivots, {} refactorisations, {} refinements, status {}, residual {:.1e}, condition {:.1e}",
            frames::solve::uses_sparse(&system, &options),
            sol.info.pivots,
            sol.info.refactorisations,
            sol.info.refinements,
            sol.status.as_str(),
            sol.info.residual.worst(),
            sol.info.max_condition
        );
        if !sol.status.is_success() {
            eprintln!("cantilever {n}: not a success in f64: {}", sol.message);
        }
        group.bench_with_input(BenchmarkId::new("path", n), &system, |b, s| {
            b.iter(|| frames::solve::solve(s, &options).expect("solvable"))
        });
        if n <= 100 {
            // the dense form with the block basis, as before the sparse route
            let problem = system.plcp::<f64>(None).expect("valid");
            let settings = frames::solve::plcp_settings::<f64>(plcp::Method::Wolfe);
            group.bench_with_input(BenchmarkId::new("path-dense", n), &problem, |b, p| {
                b.iter(|| plcp::solve(p, &settings).expect("valid settings"))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, cantilever);
criterion_main!(benches);
