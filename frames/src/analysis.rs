//! One analysis, end to end: scene, system (9), path, hinge reading, response.

use crate::assemble::System;
use crate::error::FramesError;
use crate::hinge::{self, Reading};
use crate::model::Scene;
use crate::response::{self, Response};
use crate::solve::{self, Solution, SolveOptions};

/// Options of an analysis.
#[derive(Clone, Debug, PartialEq)]
pub struct AnalysisOptions {
    /// Method, precision, `lambda_max`.
    pub solve: SolveOptions,
    /// End time of the time response (default: `Lambda` reaches 1.5 times the
    /// last critical value; see [`response::default_t_end`]).
    pub t_end: Option<f64>,
    /// Number of evenly spaced times (the breakpoint crossings are added).
    pub samples: usize,
    /// Re-solve in double-double (`fx128`) when the `f64` path ends early or
    /// does not satisfy system (9) to 1e-6 (default `true`; only for `f64`).
    pub escalate: bool,
}

impl Default for AnalysisOptions {
    fn default() -> Self {
        Self {
            solve: SolveOptions::default(),
            t_end: None,
            samples: 201,
            escalate: true,
        }
    }
}

/// The complete analysis of a scene.
#[derive(Clone, Debug)]
pub struct Analysis {
    /// The scene.
    pub scene: Scene,
    /// System (9).
    pub system: System,
    /// The options used.
    pub options: AnalysisOptions,
    /// The path from plcp, in `f64`.
    pub solution: Solution,
    /// The path read as hinge events.
    pub reading: Reading,
    /// Accelerations, moments, time response.
    pub response: Response,
    /// Set when the path was re-solved in a higher precision, and why.
    pub note: Option<String>,
}

impl Analysis {
    /// Assembles, solves and reads the scene.
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cantilever.toml");
    /// let scene = frames::Scene::from_file(path).unwrap();
    /// let a = frames::Analysis::run(scene, &frames::AnalysisOptions::default()).unwrap();
    /// assert!(a.solution.status.is_success());
    /// // the first critical value is the static collapse load Mp / L = 1
    /// assert!((a.reading.collapse_load().unwrap() - 1.0).abs() < 1e-12);
    /// assert_eq!(a.scene.frame.nodes[a.reading.hinges[0].node].id, "A");
    /// ```
    pub fn run(scene: Scene, options: &AnalysisOptions) -> Result<Analysis, FramesError> {
        if let Some(t) = options.t_end {
            if t.is_nan() || t <= 0.0 || !t.is_finite() {
                return Err(FramesError::invalid(
                    "t_end",
                    format!("must be positive and finite, got {t}"),
                ));
            }
        }
        let system = System::assemble(&scene.frame);
        let mut solution = solve::solve(&system, &options.solve)?;
        let mut note = None;
        let poor = |s: &Solution| !s.status.is_success() || s.info.residual.worst() > 1e-6;
        if options.escalate && options.solve.precision == plcp::Precision::F64 && poor(&solution) {
            let wide = SolveOptions {
                precision: plcp::Precision::F128,
                ..options.solve
            };
            if let Ok(better) = solve::solve(&system, &wide) {
                if !poor(&better) {
                    note = Some(format!(
                        "the f64 path was not good enough (status {}, residual {:.1e}): re-solved in f128",
                        solution.status.as_str(),
                        solution.info.residual.worst()
                    ));
                    solution = better;
                }
            }
        }
        let reading = hinge::read(&scene.frame, &system, &solution.pieces, solution.tolerance);
        let mut t_end = options.t_end.unwrap_or_else(|| {
            response::default_t_end(&scene.history, &reading, options.solve.lambda_max)
        });
        // the path is known only up to where it was traced
        let reached = if solution.status == plcp::Status::UnboundedRay {
            f64::INFINITY
        } else {
            solution.lambda_reached
        };
        if scene.history.lambda(t_end) > reached {
            t_end = scene.history.time_at(reached).unwrap_or(t_end);
        }
        let n = options.samples.max(2);
        let mut times: Vec<f64> = (0..n).map(|i| t_end * i as f64 / (n - 1) as f64).collect();
        for b in &reading.breakpoints {
            if let Some(t) = scene.history.time_at(b.lambda) {
                if t > 0.0 && t < t_end {
                    times.push(t);
                }
            }
        }
        times.sort_by(f64::total_cmp);
        times.dedup();
        let response = response::build(
            &scene.frame,
            &system,
            &solution.pieces,
            &reading,
            &scene.history,
            &times,
        );
        Ok(Analysis {
            scene,
            system,
            options: options.clone(),
            solution,
            reading,
            response,
            note,
        })
    }
}
