//! The scene: a planar frame or a grillage (nodes, members, arcs, supports,
//! masses, loads, yield polygons) and the
//! load history `lambda(t)`, read from TOML with errors that name file, line and key.
//!
//! The keys of a scene file (the contract; every other key is an error that
//! names the key, its line and column, and the keys its table accepts). Every
//! table also accepts `comment = ...` (any TOML value), read and ignored, for
//! annotations that should travel with the data (`#` comments are fine too).
//! The file must be UTF-8 throughout ([`Scene::from_bytes`]).
//!
//! ```toml
//! title = "optional text"
//! model = "planar"        # the default; or "grillage" (see Models below)
//!
//! [[node]]
//! id = "A"
//! x = 0.0
//! y = 0.0
//!
//! [[member]]
//! id = "AB"
//! from = "A"
//! to = "B"
//! plastic_moment = 1.0
//! elements = 4            # optional: n equal elements, new nodes "AB.1" .. "AB.3"
//! mass_per_length = 1.0   # optional: lumped, mu*h/2 to each element end
//! # plastic_torque = 0.9  # grillage: required, Tp
//! # plastic_axial = 4.0   # planar, optional: Np, the bending-axial interaction
//! # facets = 16           # with either: facets of the yield polygon
//!
//! [[support]]
//! node = "A"
//! fix = ["x", "y", "rz"]  # grillage: any of "z", "rx", "ry"
//!
//! [[mass]]
//! node = "B"
//! m = 0.25                # translational mass (x and y)
//! j = 0.0                 # optional rotary inertia
//!
//! [[load]]
//! node = "B"
//! fy = 1.0                # the pattern a_o: fx, fy, mz (each optional); grillage: fz, mx, my
//!
//! [[arc]]                 # a curved member, subdivided into straight elements
//! id = "Q"
//! centre = [0.0, 0.0]
//! radius = 1.0
//! start_angle = 0.0       # degrees, counter-clockwise from +x
//! end_angle = 90.0        # the sweep is end - start (0 < |sweep| < 360)
//! elements = 8            # nodes "Q.1" .. "Q.7" on the arc (chords between them)
//! from = "A"              # optional: a [[node]] at the start point, else "Q.0" is generated
//! to = "C"                # optional: a [[node]] at the end point, else "Q.8"
//! plastic_moment = 1.0    # and plastic_torque / plastic_axial / facets / mass_per_length as a member
//!
//! [[target]]              # optional, any number: report when a gap first closes
//! node = "B"
//! direction = [0.0, -1.0, 0.0]  # [dx, dy, dz], normalised; planar: dz = 0, grillage: dx = dy = 0
//! gap = 0.1               # positive: the displacement along direction to reach
//!
//! [history]               # lambda(t); default: ramp with rate 1
//! kind = "ramp"
//! rate = 1.0
//! # kind = "table",      points = [[0.0, 0.0], [1.0, 2.0], [3.0, 2.5]]  (t, lambda), held after the last
//! # kind = "saturating", peak = 5.0, tau = 0.5                         lambda = peak (1 - exp(-t/tau))
//! ```
//!
//! **Space scenes.** `model = "space"`: nodes take `z` too, supports fix any of
//! `"x", "y", "z", "rx", "ry", "rz"`, loads are `fx, fy, fz, mx, my, mz`, every
//! member needs `plastic_torque`; the scene is solved as planar or grillage in
//! the plane of its nodes, as its loads need, else as the general space model
//! (six components per node, the yield polyhedron; [`crate::space`]). An
//! `[[arc]]` of a space scene takes `centre = [x, y, z]`, optional `normal =
//! [nx, ny, nz]` (its plane, default z; angles counter-clockwise about it)
//! and `reference = [rx, ry, rz]` (the direction of angle 0, its part in the
//! plane; default the plane's direction nearest x, or y). A member may give `orientation = [vx, vy, vz]`: its elements' local
//! `e3` is the part of that vector across the member (default `z`, `x` for a
//! vertical member; [`crate::space::element_axes`]); a key of space scenes only.
//!
//! **Models.** `model = "planar"` (the default: every file without the key is
//! planar, as before) or `model = "grillage"`. In a grillage the frame lies in
//! the x-y plane; nodes move in z and rotate about x and y (right-handed):
//! supports fix any of `"z"`, `"rx"`, `"ry"`, loads are `fz`, `mx`, `my`, `m`
//! of `[[mass]]` acts in z and `j` about both x and y, and JSON accelerations
//! use the component names `"z"`, `"rx"`, `"ry"`. Keys of the other model are
//! errors.
//!
//! **Yield polygons.** Every grillage member needs `plastic_torque = Tp`; its
//! sections yield on `(M/Mp)^2 + (T/Tp)^2 <= 1`. A planar member may give
//! `plastic_axial = Np`: its sections then yield on the thin-walled pipe's
//! `|M/Mp| <= cos(pi N / 2 Np)`, and its axial force is a yield force instead
//! of a reaction. Either curve is replaced by an INSCRIBED polygon (vertices
//! on the curve, the axis points among them; see [`crate::yield_surface`]) of
//! `facets = k` facets, k a multiple of 4 up to 256, set on the member (or arc) or for
//! the whole scene in a top-level table:
//!
//! ```toml
//! [yield]
//! facets = 16             # the default when neither says
//! ```
//!
//! ```
//! let src = r#"
//! [[node]]
//! id = "A"
//! x = 0.0
//! y = 0.0
//! [[node]]
//! id = "B"
//! x = 1.0
//! y = 0.0
//! [[member]]
//! id = "AB"
//! from = "A"
//! to = "B"
//! plastic_moment = 1.0
//! elements = 2
//! mass_per_length = 1.0
//! [[support]]
//! node = "A"
//! fix = ["x", "y", "rz"]
//! [[load]]
//! node = "B"
//! fy = -1.0
//! "#;
//! let scene = frames::Scene::from_toml(src, "demo.toml").unwrap();
//! assert_eq!(scene.frame.nodes.len(), 3); // A, B and the generated AB.1
//! assert_eq!(scene.frame.elements.len(), 2);
//!
//! let bad = src.replace("to = \"B\"", "to = \"Q\"");
//! let err = frames::Scene::from_toml(&bad, "demo.toml").unwrap_err();
//! assert_eq!(err.to_string(), "demo.toml:13: member \"AB\" to: unknown node \"Q\"");
//! ```

use crate::error::FramesError;
use crate::target::Target;
use crate::yield_surface::{Curve, Polygon};
use serde::de::IgnoredAny;
use serde::Deserialize;
use std::collections::HashMap;
use toml::Spanned;

pub use crate::kind::{Component, Model};

mod ctx;
mod history;
mod raw;
mod read;
#[cfg(test)]
mod tests;

use ctx::*;
use history::*;
use raw::*;
use read::*;

/// A node of the frame (given in the scene, or generated by splitting a member).
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    /// The id (`"AB.2"` for the second inner node of member `AB`).
    pub id: String,
    /// x coordinate.
    pub x: f64,
    /// y coordinate.
    pub y: f64,
    /// z coordinate (zero but in a general space scene).
    pub z: f64,
    /// Supported components, by [`Component::index`] (`x, y, rz, z, rx, ry`;
    /// only the model's components are read).
    pub fixed: [bool; 6],
    /// Lumped translational mass (from `[[mass]]` and `mass_per_length`).
    pub mass: f64,
    /// Rotary inertia (about z; in a grillage, about x and about y each).
    pub inertia: f64,
    /// Load pattern `a_o` at the node, by [`Component::index`]:
    /// `[fx, fy, mz, fz, mx, my]` (only the model's components are nonzero).
    pub load: [f64; 6],
    /// True for nodes generated by `elements = n`.
    pub generated: bool,
}

/// A member of the scene, possibly split into equal elements.
#[derive(Clone, Debug, PartialEq)]
pub struct Member {
    /// The id.
    pub id: String,
    /// Index of the start node.
    pub from: usize,
    /// Index of the end node.
    pub to: usize,
    /// Plastic moment `Mp` (the same at every section of the member).
    pub plastic_moment: f64,
    /// The interaction of bending with the torque (grillage) or the axial force
    /// (planar, where asked for); `None`: bending only.
    pub interaction: Option<Interaction>,
    /// Mass per unit length.
    pub mass_per_length: f64,
    /// The node chain from `from` to `to` (length `elements + 1`).
    pub nodes: Vec<usize>,
    /// The member's elements, as a range of indices into [`Frame::elements`].
    pub elements: core::ops::Range<usize>,
}

/// How a member's sections couple the bending moment with a second force.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interaction {
    /// The curve (bending-torsion or bending-axial).
    pub curve: Curve,
    /// The plastic capacity of the second force alone (`Tp` or `Np`).
    pub capacity: f64,
    /// The number of facets of the inscribed polygon (a multiple of 4); for
    /// the space polyhedron (polytope) its number of longitudes.
    pub facets: usize,
    /// General space model only: the plastic axial force `Np` of a member
    /// with `plastic_axial`, whose sections then yield on the
    /// bending-torsion-axial polytope ([`crate::yield_surface::Polytope`]);
    /// `None` elsewhere (the axial force of a planar member is the `capacity`).
    pub axial: Option<f64>,
}

/// A straight rigid-plastic beam element between two nodes, with a critical
/// section at each end (axially rigid unless it has a bending-axial interaction).
#[derive(Clone, Debug, PartialEq)]
pub struct Element {
    /// The member it belongs to.
    pub member: usize,
    /// Start node.
    pub from: usize,
    /// End node.
    pub to: usize,
    /// Length.
    pub length: f64,
    /// Direction cosine `(x_to - x_from) / length`.
    pub cos: f64,
    /// Direction sine `(y_to - y_from) / length`.
    pub sin: f64,
    /// Plastic moment at both end sections.
    pub plastic_moment: f64,
    /// The member's interaction (see [`Member::interaction`]).
    pub interaction: Option<Interaction>,
    /// The element's axes `e1` (along it), `e2`, `e3` (rows, global
    /// coordinates); planar and grillage: `(c, s, 0)`, `(-s, c, 0)`, `z`; a
    /// general space element: from its member's `orientation`
    /// ([`crate::space::element_axes`]).
    pub axes: [[f64; 3]; 3],
}

/// A planar frame ready for assembly: nodes with their supports, masses and
/// loads, members and their elements.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Frame {
    /// Scene title (may be empty).
    pub title: String,
    /// Planar or grillage.
    pub model: Model,
    /// Nodes: those of the scene first, then the generated ones.
    pub nodes: Vec<Node>,
    /// Members in scene order.
    pub members: Vec<Member>,
    /// Elements, member by member.
    pub elements: Vec<Element>,
    /// For a `model = "space"` scene: the model it is solved as and the axes
    /// of its plane ([`crate::space`]); `None` for planar and grillage scenes.
    pub reduction: Option<crate::space::Reduction>,
}

impl Frame {
    /// Index of the node with this id.
    pub fn node_index(&self, id: &str) -> Option<usize> {
        self.nodes.iter().position(|n| n.id == id)
    }
}

/// The load history `lambda(t)`: monotone nondecreasing from `lambda(0) = 0`.
#[derive(Clone, Debug, PartialEq)]
pub enum History {
    /// `lambda = rate * t`.
    Ramp {
        /// Positive rate.
        rate: f64,
    },
    /// Piecewise linear through `(t, lambda)` points, starting at `(0, 0)`, held
    /// constant after the last point.
    Table {
        /// The points, `t` increasing, `lambda` nondecreasing.
        points: Vec<(f64, f64)>,
    },
    /// `lambda = peak (1 - exp(-t / tau))`: a saturating rise (a blowdown force).
    Saturating {
        /// The asymptotic value.
        peak: f64,
        /// The time constant.
        tau: f64,
    },
}

impl Default for History {
    fn default() -> Self {
        History::Ramp { rate: 1.0 }
    }
}

/// A scene: the frame and the load history, with where each item sits in the file.
///
/// Read from a TOML file ([`Scene::from_file`]) or text ([`Scene::from_toml`]);
/// the format is described in the README and the module documentation.
///
/// ```
/// // a cantilever of length 1 as one element, a tip mass, a tip load
/// let scene = frames::Scene::from_toml(r#"
///     title = "one-element cantilever"
///     [[node]]
///     id = "A"
///     x = 0.0
///     y = 0.0
///     [[node]]
///     id = "B"
///     x = 1.0
///     y = 0.0
///     [[member]]
///     id = "AB"
///     from = "A"
///     to = "B"
///     plastic_moment = 1.0
///     [[support]]
///     node = "A"
///     fix = ["x", "y", "rz"]
///     [[mass]]
///     node = "B"
///     m = 1.0
///     [[load]]
///     node = "B"
///     fy = -1.0
/// "#, "inline.toml").unwrap();
/// assert_eq!(scene.frame.nodes.len(), 2);
/// assert_eq!(scene.frame.node_index("B"), Some(1));
/// // a mistake names the file, line, column and key
/// let err = frames::Scene::from_toml("[[node]]\nid = \"A\"\nx = 0.0\nz = 1\n", "bad.toml");
/// assert!(err.unwrap_err().to_string().starts_with("bad.toml:"));
/// ```
#[derive(Clone, Debug)]
pub struct Scene {
    /// The file name as given (used in error messages).
    pub file: String,
    /// The frame.
    pub frame: Frame,
    /// The load history.
    pub history: History,
    /// Line of the first `[[load]]` key at each (node, component) (for error messages).
    pub(crate) load_lines: HashMap<(usize, usize), usize>,
    /// Line of each `[[node]]` entry.
    pub(crate) node_lines: HashMap<usize, usize>,
    /// The `[[target]]`s: gaps whose first closing is reported ([`crate::target`]).
    pub targets: Vec<Target>,
}

/// Options of reading a scene ([`Scene::from_toml_with`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ReadOptions {
    /// Solve a `model = "space"` scene whose nodes and loads are planar as the
    /// planar or grillage model ([`crate::space`]); `true` by default. With
    /// `false` every space scene is assembled as the general space model (six
    /// components per node, the yield polyhedron): the same answer, larger.
    pub reduce_space: bool,
}

impl Default for ReadOptions {
    fn default() -> Self {
        ReadOptions { reduce_space: true }
    }
}

/// Facets of the yield polygons when neither the member nor `[yield]` says.
pub const DEFAULT_FACETS: usize = 16;

impl Scene {
    /// Reads a scene file.
    pub fn from_file(path: impl AsRef<std::path::Path>) -> Result<Scene, FramesError> {
        let path = path.as_ref();
        let file = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|e| FramesError::Io {
            file: file.clone(),
            message: e.to_string(),
        })?;
        Scene::from_bytes(&bytes, &file)
    }

    /// Parses a scene given as the bytes of a file: [`Scene::from_toml`] after
    /// checking that they are UTF-8 throughout, comments included (an error
    /// names the byte offset, line and column of the first bad byte).
    pub fn from_bytes(bytes: &[u8], file: &str) -> Result<Scene, FramesError> {
        let src = plcp::io::utf8(bytes).map_err(|e| FramesError::Syntax {
            file: file.to_string(),
            line: e.line,
            column: e.column,
            key: "(encoding)".to_string(),
            message: e.brief(),
        })?;
        Scene::from_toml(src, file)
    }

    /// Parses and checks a scene given as TOML text; `file` names it in errors.
    pub fn from_toml(src: &str, file: &str) -> Result<Scene, FramesError> {
        Scene::from_toml_with(src, file, ReadOptions::default())
    }

    /// [`Scene::from_toml`] with options (e.g. a space scene assembled as the
    /// general space model even where it is planar, a check of the reduction).
    pub fn from_toml_with(
        src: &str,
        file: &str,
        options: ReadOptions,
    ) -> Result<Scene, FramesError> {
        let mut r = Reader::new(src, file, options)?;
        r.nodes()?;
        r.reduce()?;
        r.members()?;
        r.arcs()?;
        r.supports_and_masses()?;
        r.loads()?;
        r.finish()
    }

    /// Semantic checks that need the kinematics: no load, no matter how small,
    /// may act on a mechanism that carries no mass (its acceleration would be infinite).
    fn check_mechanics(&self) -> Result<(), FramesError> {
        if self.frame.nodes.iter().all(|n| n.load == [0.0; 6]) {
            return Err(FramesError::Scene {
                file: self.file.clone(),
                line: 0,
                key: "load".into(),
                message: "the scene has no nonzero [[load]]: nothing would move".into(),
            });
        }
        if self
            .frame
            .nodes
            .iter()
            .all(|n| (0..6).all(|c| n.load[c] == 0.0 || n.fixed[c]))
        {
            let line = self.load_lines.values().min().copied().unwrap_or(0);
            return Err(FramesError::Scene {
                file: self.file.clone(),
                line,
                key: "load".into(),
                message: "every load acts on a supported component: the supports take it and nothing would move".into(),
            });
        }
        if let Some((node, comp)) = crate::assemble::massless_mechanism(&self.frame) {
            let n = &self.frame.nodes[node];
            let line = self
                .load_lines
                .get(&(node, comp.index()))
                .or_else(|| self.node_lines.get(&node))
                .copied()
                .unwrap_or(0);
            return Err(FramesError::Scene {
                file: self.file.clone(),
                line,
                key: format!("load \"{}\" {}", n.id, self.frame.model.load_key(comp)),
                message: format!(
                    "the load acts on a mechanism with no mass on it (node \"{}\", component {}): add a [[mass]] or mass_per_length, or a support",
                    n.id,
                    comp.as_str()
                ),
            });
        }
        Ok(())
    }
}

/// A `[[target]]`: the node, its direction made a unit vector (in the
/// model's translations: `dz = 0` in a planar scene, `dx = dy = 0` in a
/// grillage, where the other translations are not unknowns), a positive gap.
fn parse_target(
    cx: &Ctx<'_>,
    model: Model,
    reduction: Option<&crate::space::Reduction>,
    nid: &str,
    node: usize,
    t: &RawTarget,
) -> Result<Target, FramesError> {
    let key = |k: &str| format!("target \"{nid}\" {k}");
    let d = t.direction.get_ref();
    if d.len() != 3 || d.iter().any(|v| !v.is_finite() || v.abs() > 1e100) {
        return cx.err(
            t.direction.span(),
            key("direction"),
            format!("must be three finite numbers [dx, dy, dz], got {d:?}"),
        );
    }
    // a space scene: the direction in the plane's axes, rounding snapped to zero
    let local;
    let d = match reduction {
        None => d,
        Some(r) => {
            let mut l = r.to_local([d[0], d[1], d[2]]);
            let scale = l.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            for v in &mut l {
                if v.abs() <= crate::space::PLANE_TOLERANCE * scale {
                    *v = 0.0;
                }
            }
            local = l.to_vec();
            &local
        }
    };
    let (zero, which) = model.target_zero();
    if zero.iter().any(|&k| d[k] != 0.0) {
        return cx.err(
            t.direction.span(),
            key("direction"),
            format!("{which}, got {d:?}"),
        );
    }
    let norm = d.iter().map(|v| v * v).sum::<f64>().sqrt();
    if !(norm > 0.0 && norm.is_finite()) {
        return cx.err(
            t.direction.span(),
            key("direction"),
            format!("must not be zero, got {d:?}"),
        );
    }
    let gap = cx.positive(&t.gap, key("gap"))?;
    Ok(Target {
        node,
        direction: [d[0] / norm, d[1] / norm, d[2] / norm],
        gap,
    })
}
