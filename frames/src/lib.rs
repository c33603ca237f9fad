//! # frames: the dynamic response of rigid-plastic planar frames, by system (9)
//!
//! A planar frame of rigid, perfectly plastic, inextensible members, with
//! lumped masses, is loaded from rest by a proportional load `a_o lambda(t)`,
//! `lambda` monotone nondecreasing from 0. Plastic hinges form at critical
//! sections at both ends of every element, with yield modes `m <= Mp` and
//! `-m <= Mp`. With the load parameter `Lambda` in place of `lambda(t)`, the
//! accelerations `q_dd`, member forces `X`, plastic multiplier accelerations
//! `x*_dd` and plastic potentials `y*` solve the parametric LCP (the paper's
//! system (9)):
//!
//! ```text
//! (a)  0 = -M_q q_dd - A^T X + a_o Lambda            dynamic equilibrium
//! (b)  0 = -A q_dd + T N x*_dd                        rigid members: deformation only at hinges
//! (c)  y* = X* - N^T T^T X                            distance to yield
//!      y* >= 0,  x*_dd >= 0,  y*' x*_dd = 0,          Lambda from 0 upward
//! ```
//!
//! `M_q` is the (singular) lumped mass matrix, `A` the compatibility matrix
//! (end rotations relative to the chord, and the elongation, which must vanish),
//! `T N` maps yield modes to member deformations (`T = I`, `N = [1, -1]` per
//! section), `X*` the plastic moments. It is the KKT system of the convex QP
//! `min 1/2 q_dd' M_q q_dd - Lambda a_o' q_dd + X*' x*_dd` s.t. `A q_dd = T N x*_dd`,
//! `x*_dd >= 0`. plcp traces its solution as `Lambda` rises (Wolfe's long form
//! on the unreduced system by default; Lemke on the Schur reduction for
//! statically determinate frames).
//!
//! **Grillages and yield polygons.** A scene with `model = "grillage"` is a
//! frame in the x-y plane loaded out of it (pipe whip normal to the plane of a
//! bent or curved pipe): nodes move in z and rotate about x and y, an element
//! carries two end bending moments and a torque, and each critical section
//! yields on an inscribed polygon of `(M/Mp)^2 + (T/Tp)^2 <= 1`, one yield mode
//! per facet ([`yield_surface`]). Planar members may ask for the bending-axial
//! interaction the same way. Both are "just another system (9)": the same
//! solver, hinge reading, response and reports.
//!
//! The crate reads a scene ([`model`]), assembles system (9) leaving out what
//! does not move ([`assemble`]), solves it ([`solve`]), reads the path as
//! hinge events ([`hinge`], with [`stress`] to tell a real deactivation from
//! a choice among non-unique stress states), builds the response ([`response`],
//! [`integrate`]) and reports it as text, JSON ([`report`]) and plots
//! ([`plot`]). [`timestep`] integrates the same frame independently, one
//! velocity-level LCP per step, where hinges may unload: it checks the path
//! and continues the response where the path stops being valid.
//!
//! ```
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cantilever.toml");
//! let scene = frames::Scene::from_file(path).unwrap();
//! let a = frames::Analysis::run(scene, &frames::AnalysisOptions::default()).unwrap();
//! // the paper's cantilever, four equal masses: hinges at the root, then outward
//! let order: Vec<(&str, f64)> = a.reading.hinges.iter()
//!     .map(|h| (a.scene.frame.nodes[h.node].id.as_str(), h.lambda)).collect();
//! let expected = [("A", 1.0), ("AB.1", 4.0), ("AB.2", 6.0), ("AB.3", 12.0)];
//! for ((n, l), (en, el)) in order.iter().zip(expected) {
//!     assert_eq!(*n, en);
//!     assert!((l - el).abs() < 1e-9);
//! }
//! assert!(a.reading.deactivations().is_empty());
//! ```
//!
//! **Features.** `json` (the JSON report, serde_json) and `plot` (SVG plots,
//! plotters) are on by default, with `cli` (the `frames` binary, clap), which
//! implies both. Without default features the crate depends on plcp, faer,
//! serde, toml and thiserror: the analysis and the text report.
#![deny(missing_docs)]

pub mod analysis;
pub mod assemble;
pub mod error;
pub mod hinge;
pub mod integrate;
mod kernel;
pub mod kind;
pub mod model;
#[cfg(feature = "plot")]
pub mod plot;
pub mod report;
pub mod response;
pub mod section_forces;
pub mod solve;
pub mod space;
pub mod stream;
pub mod stress;
pub mod target;
pub mod timestep;
pub mod yield_surface;

pub use analysis::{Analysis, AnalysisOptions};
pub use assemble::{SparseBlock, System};
pub use error::FramesError;
pub use model::{Frame, History, Model, ReadOptions, Scene};
pub use solve::SolveOptions;
pub use timestep::{StepOptions, StepResponse, TimeStepping};
