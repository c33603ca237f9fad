//! Plots of what the paper's figures show, as SVG (plotters), with the numbers
//! beside them as CSV:
//!
//! | file | what | paper |
//! |---|---|---|
//! | `activation.svg/.csv` | hinges against `Lambda`: accelerating, rotating at constant rate, at yield | Fig. 1(c) |
//! | `profiles.svg/.csv` | the shape of the acceleration (velocity-increment) field in each interval | Fig. 1(b) |
//! | `moments.svg/.csv` | bending moment along the members at every critical `Lambda` | Fig. 2(a) |
//! | `displacements.svg/.csv` | nodal displacements (and velocities in the CSV) against time | Fig. 2(b) |
//! | `geometry.svg/.csv` | the frame in plan with the hinges numbered in their order of formation, with `Lambda` | |
//!
//! A grillage's acceleration field (out of the plane) is drawn in an oblique
//! view: plan coordinates `(x, y)` at `(x + 0.5 y, 0.5 y)` and `z` upward.
//!
//! **Space scenes** (the general model) are drawn in a projection ([`View`]):
//! chosen (`frames run --view xy|xz|yz|iso`) or automatic (the plane of the
//! nodes when they lie in a coordinate plane, else the isometric view from
//! `(1, 1, 1)`); the geometry and the profiles say which in their captions.
//! Their moment plot shows what a pipe engineer reads at each section: the
//! bending magnitude `sqrt(M2^2 + M3^2)` against `Mp` and the torque `T`
//! against `+-Tp` (the CSV adds `m2`, `bending` and `torque`).
//!
//! **Large scenes stay readable**: the moment plot draws at most
//! [`MAX_CURVES`] critical `Lambda` values (evenly sampled, the first and the
//! last among them; its CSV holds the same ones), the activation diagram at
//! most [`MAX_ROWS`] hinges (evenly sampled), the geometry's legend and
//! numbers the first [`MAX_LEGEND`] hinges, the profiles show 12 intervals;
//! each plot says so in its caption. Members are drawn as one polyline each,
//! the activation bars one per run of intervals in the same state. The CSVs
//! follow the plots where those sample: `moments.csv` and `profiles.csv` hold
//! the shown `Lambda` values and intervals, `displacements.csv` every node up
//! to [`MAX_CSV_NODES`], else the plotted ones.

mod activation;
mod displacements;
mod geometry;
mod moments;
mod profiles;

use activation::activation;
use displacements::displacements;
use geometry::geometry;
use moments::moments;
use profiles::profiles;

use crate::analysis::Analysis;
use crate::error::FramesError;
use crate::hinge::section_name;
use crate::model::{Component, Model};
use crate::report::format_number as g;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// Most moment diagrams (critical `Lambda` values) in `moments.svg`.
pub const MAX_CURVES: usize = 12;
/// Most hinges (rows) in `activation.svg`.
pub const MAX_ROWS: usize = 60;
/// Most hinges in the legend (and numbered) in `geometry.svg`.
pub const MAX_LEGEND: usize = 20;
/// Most nodes in `displacements.csv` (beyond: the plotted ones only).
pub const MAX_CSV_NODES: usize = 200;

/// `count` indices of `0..n` evenly spread, the first and the last among
/// them (all of them when `n <= count`).
fn sample(n: usize, count: usize) -> Vec<usize> {
    if n <= count {
        return (0..n).collect();
    }
    let mut v: Vec<usize> = (0..count).map(|k| k * (n - 1) / (count - 1)).collect();
    v.dedup();
    v
}

/// How a space scene is projected on the page.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum View {
    /// The plane of the nodes when they lie in a coordinate plane (`x-y`,
    /// `x-z` or `y-z`), else [`View::Isometric`].
    #[default]
    Auto,
    /// Plan: `x` to the right, `y` up.
    Xy,
    /// Elevation: `x` to the right, `z` up.
    Xz,
    /// Elevation: `y` to the right, `z` up.
    Yz,
    /// Isometric from `(1, 1, 1)`: `z` up, `x` to the lower left, `y` to the lower right.
    Isometric,
}

impl View {
    /// Reads `auto`, `xy`, `xz`, `yz` or `iso`.
    pub fn parse(s: &str) -> Result<View, String> {
        match s {
            "auto" => Ok(View::Auto),
            "xy" => Ok(View::Xy),
            "xz" => Ok(View::Xz),
            "yz" => Ok(View::Yz),
            "iso" | "isometric" => Ok(View::Isometric),
            _ => Err(format!("unknown view \"{s}\" (auto, xy, xz, yz or iso)")),
        }
    }
}

/// A projection of space onto the page: `(right . p, up . p)`.
#[derive(Clone, Debug)]
struct Projection {
    right: [f64; 3],
    up: [f64; 3],
    name: &'static str,
}

impl Projection {
    fn of(view: View, fr: &crate::model::Frame) -> Projection {
        let view = match view {
            View::Auto => {
                let span = |f: fn(&crate::model::Node) -> f64| {
                    let (lo, hi) = fr.nodes.iter().fold((f64::MAX, f64::MIN), |(lo, hi), n| {
                        (lo.min(f(n)), hi.max(f(n)))
                    });
                    (hi - lo).max(0.0)
                };
                let (sx, sy, sz) = (span(|n| n.x), span(|n| n.y), span(|n| n.z));
                let tiny = 1e-12 * sx.max(sy).max(sz);
                if sz <= tiny {
                    View::Xy
                } else if sy <= tiny {
                    View::Xz
                } else if sx <= tiny {
                    View::Yz
                } else {
                    View::Isometric
                }
            }
            v => v,
        };
        let r = std::f64::consts::FRAC_1_SQRT_2;
        let u = 1.0 / 6f64.sqrt();
        match view {
            View::Xz => Projection {
                right: [1.0, 0.0, 0.0],
                up: [0.0, 0.0, 1.0],
                name: "elevation x-z (x right, z up)",
            },
            View::Yz => Projection {
                right: [0.0, 1.0, 0.0],
                up: [0.0, 0.0, 1.0],
                name: "elevation y-z (y right, z up)",
            },
            View::Isometric => Projection {
                right: [-r, r, 0.0],
                up: [-u, -u, 2.0 * u],
                name: "isometric view from (1, 1, 1) (z up, x lower left, y lower right)",
            },
            _ => Projection {
                right: [1.0, 0.0, 0.0],
                up: [0.0, 1.0, 0.0],
                name: "plan x-y (x right, y up)",
            },
        }
    }
    fn at(&self, p: [f64; 3]) -> (f64, f64) {
        let d = |v: [f64; 3]| v[0] * p[0] + v[1] * p[1] + v[2] * p[2];
        (d(self.right), d(self.up))
    }
    fn node(&self, n: &crate::model::Node) -> (f64, f64) {
        self.at([n.x, n.y, n.z])
    }
}

fn io(file: &Path, e: impl std::fmt::Display) -> FramesError {
    FramesError::Io {
        file: file.display().to_string(),
        message: format!("cannot write: {e}"),
    }
}

fn write(file: &Path, text: &str) -> Result<PathBuf, FramesError> {
    std::fs::write(file, text).map_err(|e| io(file, e))?;
    Ok(file.to_path_buf())
}

/// Writes every plot and its CSV into `dir` (created if needed); returns the files.
pub fn write_all(a: &Analysis, dir: &Path) -> Result<Vec<PathBuf>, FramesError> {
    write_all_with(a, dir, View::Auto)
}

/// [`write_all`] with a chosen projection of a space scene (planar and
/// grillage scenes are drawn as always).
pub fn write_all_with(a: &Analysis, dir: &Path, view: View) -> Result<Vec<PathBuf>, FramesError> {
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let mut files = Vec::new();
    files.extend(activation(a, dir)?);
    files.extend(profiles(a, dir, view)?);
    files.extend(moments(a, dir)?);
    files.extend(displacements(a, dir)?);
    files.extend(geometry(a, dir, view)?);
    Ok(files)
}

fn lambda_end(a: &Analysis) -> f64 {
    let last = a
        .reading
        .breakpoints
        .last()
        .map(|b| b.lambda)
        .unwrap_or(1.0);
    let reached = a.solution.lambda_reached;
    let mut end = 1.25 * last.max(f64::MIN_POSITIVE);
    if a.solution.status != plcp::Status::UnboundedRay && reached.is_finite() && reached > 0.0 {
        end = end.min(reached);
    }
    end.max(last)
}

fn group_label(a: &Analysis, g: usize) -> String {
    let grp = &a.reading.groups[g];
    if grp.sections.len() > 1 {
        a.scene.frame.nodes[grp.node].id.clone()
    } else {
        let n = section_name(&a.scene.frame, &a.system, grp.sections[0]);
        format!("{} ({} {})", n.node, n.member, n.end.as_str())
    }
}
