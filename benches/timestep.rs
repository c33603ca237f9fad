//! Time stepping against the PLCP path, side by side in one run (issue 6):
//! `frames::Analysis::run` (path of system (9), hinge reading, exact response)
//! and the velocity-level integrator `frames::timestep` from rest to the same
//! end time, with steps of 1e-2 and 1e-3 of it (warm-started), and 1e-2 with
//! every step solved cold.
//!
//! ```sh
//! cargo bench --bench timestep
//! ```
//!
//! The ratio of the time-stepping rows to the `plcp` row is the cost of the
//! baseline a user would otherwise run; `examples/timestep_report.rs` prints
//! it with the errors for h/T down to 1e-5.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode};
use frames::timestep::{StepOptions, StepState, TimeStepping};
use frames::{Analysis, AnalysisOptions, Scene};
use std::time::Duration;

fn timestep(c: &mut Criterion) {
    let mut group = c.benchmark_group("timestep");
    group.sample_size(10);
    group.sampling_mode(SamplingMode::Flat);
    group.warm_up_time(Duration::from_millis(300));
    group.measurement_time(Duration::from_secs(2));
    for name in ["cantilever", "two-storey"] {
        let path = format!("{}/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
        let scene = Scene::from_file(path).expect("scene");
        let options = AnalysisOptions::default();
        group.bench_with_input(BenchmarkId::new("plcp", name), &scene, |b, s| {
            b.iter(|| Analysis::run(s.clone(), &options).expect("analysis"))
        });
        let a = Analysis::run(scene, &options).expect("analysis");
        let t_end = *a.response.time.times.last().expect("times");
        for (label, rel, warm) in [
            ("step_1e-2", 1e-2, true),
            ("step_1e-3", 1e-3, true),
            ("step_1e-2_cold", 1e-2, false),
        ] {
            let o = StepOptions {
                h: rel * t_end,
                t_end,
                warm,
                record_every: 0,
                ..StepOptions::default()
            };
            let ts = TimeStepping::new(&a.system, &a.scene.history, &o).expect("options");
            let rest = StepState::rest(&a.system);
            group.bench_with_input(BenchmarkId::new(label, name), &rest, |b, r| {
                b.iter(|| ts.run(r).expect("run"))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, timestep);
criterion_main!(benches);
