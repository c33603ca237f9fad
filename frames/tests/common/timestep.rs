//! The shared set-up of the time-stepping tests (`timestep`,
//! `grillage_timestep`): a scene's analysis and a checked run from rest.

#![allow(dead_code)] // each including test uses what it needs

use frames::timestep::{StepOptions, StepResponse, StepState, TimeStepping};
use frames::{Analysis, AnalysisOptions, Scene};

/// The default analysis of `scenes/<name>.toml` (`name` may hold a folder,
/// `pipe-whip/straight`).
pub fn analysis(name: &str) -> Analysis {
    let path = format!("{}/../scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    Analysis::run(Scene::from_file(path).unwrap(), &AnalysisOptions::default()).unwrap()
}

/// Time-steps the analysis's system from rest with steps `h` to `t_end`;
/// the run completed.
pub fn run_from_rest(a: &Analysis, h: f64, t_end: f64) -> StepResponse {
    let options = StepOptions {
        h,
        t_end,
        ..StepOptions::default()
    };
    let r = TimeStepping::new(&a.system, &a.scene.history, &options)
        .unwrap()
        .run(&StepState::rest(&a.system))
        .unwrap();
    assert!(r.outcome.is_completed(), "{:?}", r.outcome);
    r
}

/// [`run_from_rest`], and every step's LCP reached its end with a residual
/// at rounding level.
pub fn run(a: &Analysis, h: f64, t_end: f64) -> StepResponse {
    let r = run_from_rest(a, h, t_end);
    assert!(
        r.steps.iter().all(|s| s.status == plcp::Status::Reached),
        "every step LCP solved"
    );
    assert!(r.worst_residual() < 1e-10, "{}", r.worst_residual());
    r
}
