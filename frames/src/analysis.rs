//! One analysis, end to end: scene, system (9), path, hinge reading, response.

use crate::assemble::System;
use crate::error::FramesError;
use crate::hinge::{self, Reading};
use crate::model::Scene;
use crate::response::{self, Response};
use crate::solve::{self, Solution, SolveOptions};
use crate::target::{self, Arrival};
use crate::timestep::Continuation;

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
    /// Continue in double-double (`fx128`) when the `f64` path ends
    /// `ill_conditioned` (from where it failed: [`plcp::Settings::escalate`]),
    /// and re-solve in `fx128` when it ends early otherwise or does not satisfy
    /// system (9) to 1e-6 (default `true`; only for `f64`).
    pub escalate: bool,
    /// Certify the path in exact rational arithmetic
    /// ([`solve::solve_certified`]; default `false`).
    pub certify: bool,
    /// Solve in exact rational arithmetic instead of `solve.precision`
    /// ([`solve::solve_exact`]; no escalation; default `false`).
    pub exact: bool,
}

impl AnalysisOptions {
    /// `Err` naming the option that no analysis can take (`t_end` not
    /// positive and finite).
    pub fn check(&self) -> Result<(), FramesError> {
        if let Some(t) = self.t_end {
            if t.is_nan() || t <= 0.0 || !t.is_finite() {
                return Err(FramesError::invalid(
                    "t_end",
                    format!("must be positive and finite, got {t}"),
                ));
            }
        }
        Ok(())
    }
}

impl Default for AnalysisOptions {
    fn default() -> Self {
        Self {
            solve: SolveOptions::default(),
            t_end: None,
            samples: 201,
            escalate: true,
            certify: false,
            exact: false,
        }
    }
}

/// The complete analysis of a scene.
///
/// ```
/// let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cantilever.toml");
/// let scene = frames::Scene::from_file(file).unwrap();
/// let a = frames::Analysis::run(scene, &frames::AnalysisOptions::default()).unwrap();
/// // the path of system (9), read as hinge events: the static collapse load first
/// assert!(a.solution.status.is_success());
/// let first = &a.reading.hinges[0];
/// assert_eq!(a.scene.frame.nodes[first.node].id, "A");
/// assert!((first.lambda - 1.0).abs() < 1e-12);
/// // the reports: text (what `frames run` prints) and JSON (`--json`)
/// assert!(a.to_text().contains("critical Lambda"));
/// assert_eq!(a.to_json()["hinges"].as_array().map(|h| h.len()), Some(4));
/// ```
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
    /// The first arrival at each of the scene's `[[target]]`s, in scene order.
    pub targets: Vec<Arrival>,
    /// Set when the path was re-solved in a higher precision, and why.
    pub note: Option<String>,
    /// The response by time stepping beyond the path's first deactivation,
    /// where the PLCP response stops being valid (see
    /// [`Analysis::continue_by_time_stepping`]; `None` until asked for).
    pub time_stepping: Option<Continuation>,
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
        Self::run_watched(scene, options, None)
    }

    /// [`Analysis::run`], with `watch` called after every segment of the trace
    /// (`Lambda`, pivots and breakpoints so far: what `frames run` shows in its
    /// progress line). Not called for exact precision or certification,
    /// which trace the path whole.
    ///
    /// ```
    /// use std::{cell::RefCell, rc::Rc};
    /// let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cantilever.toml");
    /// let scene = frames::Scene::from_file(file).unwrap();
    /// let seen = Rc::new(RefCell::new(Vec::new()));
    /// let log = seen.clone();
    /// let watch: frames::solve::Watch =
    ///     Rc::new(RefCell::new(move |t: &frames::solve::Tick| log.borrow_mut().push(t.lambda)));
    /// let a = frames::Analysis::run_watched(scene, &Default::default(), Some(watch)).unwrap();
    /// // one tick per segment of the path, in order of Lambda
    /// assert_eq!(seen.borrow().len(), a.solution.pieces.len());
    /// assert!(seen.borrow().windows(2).all(|w| w[0] <= w[1]));
    /// ```
    pub fn run_watched(
        scene: Scene,
        options: &AnalysisOptions,
        watch: Option<solve::Watch>,
    ) -> Result<Analysis, FramesError> {
        options.check()?;
        let system = System::assemble(&scene.frame);
        let escalate =
            options.escalate && !options.exact && options.solve.precision == plcp::Precision::F64;
        // an ill_conditioned f64 path is continued in fx128 from where it failed
        let solve_with = |o: &SolveOptions, escalate: bool| {
            if options.exact {
                solve::solve_exact(&system, o)
            } else if options.certify {
                solve::solve_certified(&system, o, escalate)
            } else if let Some(w) = &watch {
                solve::solve_watched(&system, o, escalate, w.clone())
            } else {
                solve::solve_escalating(&system, o, escalate)
            }
        };
        let mut solution = solve_with(&options.solve, escalate)?;
        let mut note = solution.info.escalation.as_ref().map(|e| {
            let how = if e.warm {
                format!(
                    "continued in f128 from Lambda = {:e}, warm-started from the f64 basis there",
                    e.lambda
                )
            } else {
                format!("re-solved in f128 from Lambda = {:e} ({})", e.lambda, e.note)
            };
            format!(
                "the f64 path was {how} ({} f64 pivots in {:.2} s, {} f128 pivots in {:.2} s), because: {}",
                e.pivots_before, e.seconds_before, e.pivots_fx128, e.seconds_fx128, e.reason
            )
        });
        // any other poor outcome: the whole path re-solved in fx128
        let poor = |s: &Solution| !s.status.is_success() || s.info.residual.worst() > 1e-6;
        if escalate && poor(&solution) {
            let wide = SolveOptions {
                precision: plcp::Precision::F128,
                ..options.solve
            };
            if let Ok(better) = solve_with(&wide, false) {
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
        let reached = if solution.status == plcp::Status::UnboundedRay {
            f64::INFINITY
        } else {
            solution.lambda_reached
        };
        let times = response::response_times(
            &scene.history,
            &reading,
            options.t_end,
            options.solve.lambda_max,
            reached,
            options.samples,
        );
        let response = response::build(
            &scene.frame,
            &system,
            &solution.pieces,
            &reading,
            &scene.history,
            &times,
        );
        let first_deactivation = reading.deactivations().first().map(|d| d.0);
        let targets = target::arrivals(
            &system,
            &response,
            &scene.history,
            first_deactivation,
            &scene.targets,
        );
        Ok(Analysis {
            targets,
            scene,
            system,
            options: options.clone(),
            solution,
            reading,
            response,
            note,
            time_stepping: None,
        })
    }

    /// Where the path shows a deactivation, the PLCP response is not valid
    /// beyond its `Lambda`: continues from the exact PLCP state there by time
    /// stepping ([`crate::timestep`]) up to the end of the time response, with
    /// steps of `h_relative` times that end time, and keeps it in
    /// [`Analysis::time_stepping`]. `Ok(false)` (nothing done) when the path has
    /// no deactivation before the end time.
    ///
    /// ```
    /// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/two-storey-sway.toml");
    /// let scene = frames::Scene::from_file(path).unwrap();
    /// let mut a = frames::Analysis::run(scene, &frames::AnalysisOptions::default()).unwrap();
    /// assert!(a.continue_by_time_stepping(1e-3).unwrap());
    /// let c = a.time_stepping.as_ref().unwrap();
    /// assert!((c.lambda - 6.0).abs() < 1e-9);
    /// // the column-top hinges the path reads as unloading stop flowing
    /// assert_eq!(c.run.deactivations().len(), 2);
    /// ```
    pub fn continue_by_time_stepping(&mut self, h_relative: f64) -> Result<bool, FramesError> {
        self.time_stepping = Continuation::for_analysis(self, h_relative)?;
        Ok(self.time_stepping.is_some())
    }
}
