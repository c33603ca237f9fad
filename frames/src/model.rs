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

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    title: Option<String>,
    model: Option<Spanned<String>>,
    #[serde(rename = "yield")]
    yield_table: Option<Spanned<RawYield>>,
    #[serde(default)]
    arc: Vec<Spanned<RawArc>>,
    #[serde(default)]
    node: Vec<Spanned<RawNode>>,
    #[serde(default)]
    member: Vec<Spanned<RawMember>>,
    #[serde(default)]
    support: Vec<Spanned<RawSupport>>,
    #[serde(default)]
    mass: Vec<Spanned<RawMass>>,
    #[serde(default)]
    load: Vec<Spanned<RawLoad>>,
    history: Option<Spanned<RawHistory>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    _comment: Option<IgnoredAny>,
    #[serde(default)]
    target: Vec<Spanned<RawTarget>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTarget {
    node: Spanned<String>,
    direction: Spanned<Vec<f64>>,
    gap: Spanned<f64>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    _comment: Option<IgnoredAny>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawNode {
    id: Spanned<String>,
    x: Spanned<f64>,
    y: Spanned<f64>,
    z: Option<Spanned<f64>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    _comment: Option<IgnoredAny>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMember {
    id: Spanned<String>,
    from: Spanned<String>,
    to: Spanned<String>,
    plastic_moment: Spanned<f64>,
    plastic_torque: Option<Spanned<f64>>,
    plastic_axial: Option<Spanned<f64>>,
    facets: Option<Spanned<i64>>,
    elements: Option<Spanned<i64>>,
    mass_per_length: Option<Spanned<f64>>,
    orientation: Option<Spanned<Vec<f64>>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    _comment: Option<IgnoredAny>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawYield {
    facets: Option<Spanned<i64>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    _comment: Option<IgnoredAny>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawArc {
    id: Spanned<String>,
    centre: Spanned<Vec<f64>>,
    radius: Spanned<f64>,
    start_angle: Spanned<f64>,
    end_angle: Spanned<f64>,
    elements: Spanned<i64>,
    from: Option<Spanned<String>>,
    to: Option<Spanned<String>>,
    plastic_moment: Spanned<f64>,
    plastic_torque: Option<Spanned<f64>>,
    plastic_axial: Option<Spanned<f64>>,
    facets: Option<Spanned<i64>>,
    mass_per_length: Option<Spanned<f64>>,
    normal: Option<Spanned<Vec<f64>>>,
    reference: Option<Spanned<Vec<f64>>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    _comment: Option<IgnoredAny>,
}

impl RawArc {
    /// A space arc's centre, unit normal, in-plane axes and points, if its
    /// keys are valid (else the arc's own checks report them).
    fn space_points(&self) -> Option<Vec<[f64; 3]>> {
        let c = self.centre.get_ref();
        if c.len() != 3 || c.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let n = match &self.normal {
            Some(n) => crate::space::unit_of(n.get_ref())?,
            None => [0.0, 0.0, 1.0],
        };
        let (r, a0, a1) = (
            *self.radius.get_ref(),
            *self.start_angle.get_ref(),
            *self.end_angle.get_ref(),
        );
        let k = usize::try_from(*self.elements.get_ref()).ok()?;
        if !(r > 0.0 && r.is_finite() && a0.is_finite() && a1.is_finite()) || k == 0 || k > 100_000
        {
            return None;
        }
        let reference = match &self.reference {
            Some(g) => Some(crate::space::unit_of(g.get_ref())?),
            None => None,
        };
        let axes = crate::space::arc_axes(n, reference)?;
        Some(
            (0..=k)
                .map(|i| {
                    crate::space::arc_point(
                        [c[0], c[1], c[2]],
                        r,
                        axes,
                        a0 + (a1 - a0) * i as f64 / k as f64,
                    )
                })
                .collect(),
        )
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSupport {
    node: Spanned<String>,
    fix: Spanned<Vec<Spanned<String>>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    _comment: Option<IgnoredAny>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMass {
    node: Spanned<String>,
    m: Option<Spanned<f64>>,
    j: Option<Spanned<f64>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    _comment: Option<IgnoredAny>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLoad {
    node: Spanned<String>,
    fx: Option<Spanned<f64>>,
    fy: Option<Spanned<f64>>,
    mz: Option<Spanned<f64>>,
    fz: Option<Spanned<f64>>,
    mx: Option<Spanned<f64>>,
    my: Option<Spanned<f64>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    _comment: Option<IgnoredAny>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawHistory {
    kind: Option<Spanned<String>>,
    rate: Option<Spanned<f64>>,
    points: Option<Spanned<Vec<Spanned<Vec<f64>>>>>,
    peak: Option<Spanned<f64>>,
    tau: Option<Spanned<f64>>,
    /// An annotation (any TOML value), read and ignored.
    #[serde(default, rename = "comment")]
    _comment: Option<IgnoredAny>,
}

impl RawLoad {
    /// The value given under a load key (`fx`, `fy`, `fz`, `mx`, `my`, `mz`).
    fn key(&self, name: &str) -> Option<&Spanned<f64>> {
        match name {
            "fx" => self.fx.as_ref(),
            "fy" => self.fy.as_ref(),
            "fz" => self.fz.as_ref(),
            "mx" => self.mx.as_ref(),
            "my" => self.my.as_ref(),
            "mz" => self.mz.as_ref(),
            _ => None,
        }
    }
}

/// 1-based line of a byte offset.
fn line_of(src: &str, offset: usize) -> usize {
    let end = offset.min(src.len());
    src.as_bytes()[..end]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

struct Ctx<'a> {
    src: &'a str,
    file: &'a str,
}

impl Ctx<'_> {
    fn err<T>(
        &self,
        span: core::ops::Range<usize>,
        key: impl Into<String>,
        message: impl Into<String>,
    ) -> Result<T, FramesError> {
        Err(FramesError::Scene {
            file: self.file.to_string(),
            line: line_of(self.src, span.start),
            key: key.into(),
            message: message.into(),
        })
    }
    fn finite(&self, v: &Spanned<f64>, key: impl Into<String>) -> Result<f64, FramesError> {
        let x = *v.get_ref();
        if !x.is_finite() {
            self.err(v.span(), key, format!("must be a finite number, got {x}"))
        } else if x.abs() > 1e100 {
            // products of such numbers overflow in the solver
            self.err(
                v.span(),
                key,
                format!("{x:e} is out of range (at most 1e100 in magnitude)"),
            )
        } else {
            Ok(x)
        }
    }
    fn positive(&self, v: &Spanned<f64>, key: impl Into<String>) -> Result<f64, FramesError> {
        let key = key.into();
        let x = self.finite(v, key.clone())?;
        if x > 0.0 {
            Ok(x)
        } else {
            self.err(v.span(), key, format!("must be positive, got {x}"))
        }
    }
    fn nonnegative(&self, v: &Spanned<f64>, key: impl Into<String>) -> Result<f64, FramesError> {
        let key = key.into();
        let x = self.finite(v, key.clone())?;
        if x >= 0.0 {
            Ok(x)
        } else {
            self.err(v.span(), key, format!("must not be negative, got {x}"))
        }
    }
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

/// The strength keys of a member or an arc.
struct Keys<'a> {
    plastic_moment: &'a Spanned<f64>,
    plastic_torque: Option<&'a Spanned<f64>>,
    plastic_axial: Option<&'a Spanned<f64>>,
    facets: Option<&'a Spanned<i64>>,
    mass_per_length: Option<&'a Spanned<f64>>,
}

impl Keys<'_> {
    /// The capacity given under `key` (`plastic_axial` or `plastic_torque`).
    fn capacity(&self, key: &str) -> Option<&Spanned<f64>> {
        match key {
            "plastic_axial" => self.plastic_axial,
            "plastic_torque" => self.plastic_torque,
            _ => None,
        }
    }
}

impl Ctx<'_> {
    fn facets(&self, v: &Spanned<i64>, key: &str) -> Result<usize, FramesError> {
        let k = *v.get_ref();
        let ku = usize::try_from(k).unwrap_or(0);
        match Polygon::new(Curve::BendingTorsion, ku) {
            Ok(_) => Ok(ku),
            Err(_) => self.err(
                v.span(),
                key,
                format!("must be a multiple of 4 from 4 to 256 (4, 8, 16, 32, ...), got {k}"),
            ),
        }
    }

    /// The strength keys of a space scene's member or arc (`what`: "a
    /// member", "an arc") for the model it is solved as: `plastic_torque`
    /// required (a pipe); a reduced model's other capacity is not an unknown
    /// (planar: no torque, and without `plastic_axial` the polyhedron's
    /// cross-section at `T = N = 0` is `+-Mp`, no facets; grillage: no axial force).
    fn space_keys<'k>(
        &self,
        model: Model,
        table: &str,
        what: &str,
        id: &Spanned<String>,
        mut keys: Keys<'k>,
    ) -> Result<Keys<'k>, FramesError> {
        let Some(tp) = keys.plastic_torque else {
            return self.err(
                id.span(),
                format!("{table} plastic_torque"),
                format!("{what} of a space scene needs plastic_torque (the plastic torque Tp of the pipe)"),
            );
        };
        self.positive(tp, format!("{table} plastic_torque"))?;
        match model {
            Model::Planar => {
                keys.plastic_torque = None;
                if keys.plastic_axial.is_none() {
                    keys.facets = None;
                }
            }
            Model::Grillage => keys.plastic_axial = None,
            Model::Space => {}
        }
        Ok(keys)
    }

    fn element_count(&self, v: &Spanned<i64>, key: &str) -> Result<usize, FramesError> {
        let n = *v.get_ref();
        if !(1..=100_000).contains(&n) {
            return self.err(
                v.span(),
                key,
                format!("must be an integer from 1 to 100000, got {n}"),
            );
        }
        Ok(n as usize)
    }

    /// `(Mp, interaction, mass per length)` of a member or arc, checked against the model.
    fn strength(
        &self,
        model: Model,
        table: &str,
        id: &Spanned<String>,
        k: Keys<'_>,
        default_facets: usize,
    ) -> Result<(f64, Option<Interaction>, f64), FramesError> {
        let mp = self.positive(k.plastic_moment, format!("{table} plastic_moment"))?;
        let mu = match k.mass_per_length {
            Some(v) => self.nonnegative(v, format!("{table} mass_per_length"))?,
            None => 0.0,
        };
        let facets = match k.facets {
            Some(f) => Some(self.facets(f, &format!("{table} facets"))?),
            None => None,
        };
        let rule = model.second_force_rule();
        let (own, foreign) = (k.capacity(rule.key), k.capacity(rule.foreign_key));
        if let Some(v) = foreign {
            return self.err(
                v.span(),
                format!("{table} {}", rule.foreign_key),
                rule.foreign_message,
            );
        }
        let interaction = match own {
            Some(v) => Some(Interaction {
                curve: rule.curve,
                capacity: self.positive(v, format!("{table} {}", rule.key))?,
                facets: facets.unwrap_or(default_facets),
                axial: match rule.third_key.and_then(|key| k.capacity(key)) {
                    Some(np) => Some(self.positive(np, format!("{table} plastic_axial"))?),
                    None => None,
                },
            }),
            None if rule.required => {
                return self.err(
                    id.span(),
                    format!("{table} {}", rule.key),
                    rule.required_message,
                );
            }
            None => {
                if let Some(f) = k.facets {
                    return self.err(f.span(), format!("{table} facets"), rule.facets_message);
                }
                None
            }
        };
        if let Some(it) = interaction.filter(|it| it.axial.is_some() && it.facets > 64) {
            return self.err(
                k.facets.map_or(id.span(), |f| f.span()),
                format!("{table} facets"),
                format!(
                    "with plastic_axial the general space model's polytope takes at most 64 longitudes (about k^3 / 2 facets per section), got {}",
                    it.facets
                ),
            );
        }
        Ok((mp, interaction, mu))
    }

    /// Adds a generated node, refusing an id that is taken.
    #[allow(clippy::too_many_arguments)]
    fn generate_node(
        &self,
        frame: &mut Frame,
        ids: &mut HashMap<String, usize>,
        gid: String,
        (x, y, z): (f64, f64, f64),
        generated: bool,
        span: core::ops::Range<usize>,
        key: &str,
    ) -> Result<usize, FramesError> {
        if ids.contains_key(&gid) {
            return self.err(
                span,
                key,
                format!("generated node id \"{gid}\" is already taken"),
            );
        }
        let i = frame.nodes.len();
        ids.insert(gid.clone(), i);
        frame.nodes.push(Node {
            id: gid,
            x,
            y,
            z,
            fixed: [false; 6],
            mass: 0.0,
            inertia: 0.0,
            load: [0.0; 6],
            generated,
        });
        Ok(i)
    }
}

/// Adds a member over a chain of nodes, one element per link with its
/// `(length, cos, sin)` (and its axes: none given for the planar axes of
/// `(cos, sin)`), lumping `mu h / 2` to each element end.
#[allow(clippy::too_many_arguments)]
fn push_member(
    frame: &mut Frame,
    id: String,
    chain: Vec<usize>,
    dirs: &[(f64, f64, f64)],
    axes: &[[[f64; 3]; 3]],
    mp: f64,
    interaction: Option<Interaction>,
    mu: f64,
) {
    let mi = frame.members.len();
    let first = frame.elements.len();
    for (k, (w, &(h, c, s))) in chain.windows(2).zip(dirs).enumerate() {
        frame.elements.push(Element {
            member: mi,
            from: w[0],
            to: w[1],
            length: h,
            cos: c,
            sin: s,
            plastic_moment: mp,
            interaction,
            axes: axes
                .get(k)
                .copied()
                .unwrap_or([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]),
        });
        let lump = 0.5 * mu * h;
        frame.nodes[w[0]].mass += lump;
        frame.nodes[w[1]].mass += lump;
    }
    frame.members.push(Member {
        id,
        from: chain[0],
        to: chain[chain.len() - 1],
        plastic_moment: mp,
        interaction,
        mass_per_length: mu,
        nodes: chain,
        elements: first..frame.elements.len(),
    });
}

/// 1-based column, in characters, of a byte offset on its line.
fn column_of(src: &str, offset: usize) -> usize {
    let mut end = offset.min(src.len());
    while !src.is_char_boundary(end) {
        end -= 1;
    }
    let start = src[..end].rfind('\n').map_or(0, |i| i + 1);
    src[start..end].chars().count() + 1
}

/// Turns a toml syntax or type error into one line with file, line, column
/// and key; an unknown key's message lists the keys its table accepts.
fn toml_error(src: &str, file: &str, e: toml::de::Error) -> FramesError {
    let first = e.message().lines().next().unwrap_or("invalid TOML").trim();
    if let (Some(span), Some(rest)) = (e.span(), first.strip_prefix("unknown field `")) {
        let key = rest.split('`').next().unwrap_or("").to_string();
        // serde lists them as "expected one of `a`, `b`" or "expected `a` or `b`"
        let accepted = rest
            .split_once(", expected one of ")
            .or_else(|| rest.split_once(", expected "))
            .map_or("none", |(_, list)| list);
        return FramesError::Syntax {
            file: file.to_string(),
            line: line_of(src, span.start),
            column: column_of(src, span.start),
            message: format!(
                "unknown key \"{key}\": the accepted keys are {accepted} (a typo would change the scene silently; annotate with # or a comment key)"
            ),
            key,
        };
    }
    let Some(span) = e.span() else {
        return FramesError::Scene {
            file: file.to_string(),
            line: 0,
            key: "(syntax)".to_string(),
            message: first.to_string(),
        };
    };
    let text = src.get(span.clone()).unwrap_or("").trim();
    let key = if !text.is_empty()
        && text.len() <= 40
        && text
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '.')
    {
        text.to_string()
    } else {
        // the key is the word before '=' on that line, if any
        let l = line_of(src, span.start);
        src.lines()
            .nth(l - 1)
            .and_then(|s| s.split_once('='))
            .map(|(k, _)| k.trim().to_string())
            .filter(|k| !k.is_empty())
            .unwrap_or_else(|| "(syntax)".to_string())
    };
    FramesError::Syntax {
        file: file.to_string(),
        line: line_of(src, span.start),
        column: column_of(src, span.start),
        key,
        message: first.to_string(),
    }
}

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

fn parse_history(cx: &Ctx<'_>, h: &Spanned<RawHistory>) -> Result<History, FramesError> {
    let r = h.get_ref();
    let kind = r
        .kind
        .as_ref()
        .map(|k| k.get_ref().as_str())
        .unwrap_or("ramp");
    let unexpected =
        |present: bool, key: &str, span: core::ops::Range<usize>| -> Result<(), FramesError> {
            if present {
                cx.err(
                    span,
                    format!("history {key}"),
                    format!("not a key of kind = \"{kind}\""),
                )
            } else {
                Ok(())
            }
        };
    let span_of = |v: &Option<Spanned<f64>>| v.as_ref().map(|s| s.span()).unwrap_or(0..0);
    match kind {
        "ramp" => {
            unexpected(
                r.points.is_some(),
                "points",
                r.points.as_ref().map(|s| s.span()).unwrap_or(0..0),
            )?;
            unexpected(r.peak.is_some(), "peak", span_of(&r.peak))?;
            unexpected(r.tau.is_some(), "tau", span_of(&r.tau))?;
            let rate = match &r.rate {
                Some(v) => cx.positive(v, "history rate")?,
                None => 1.0,
            };
            Ok(History::Ramp { rate })
        }
        "table" => {
            unexpected(r.rate.is_some(), "rate", span_of(&r.rate))?;
            unexpected(r.peak.is_some(), "peak", span_of(&r.peak))?;
            unexpected(r.tau.is_some(), "tau", span_of(&r.tau))?;
            let Some(pts) = &r.points else {
                return cx.err(
                    h.span(),
                    "history points",
                    "kind = \"table\" needs points = [[t, lambda], ...]",
                );
            };
            let mut points: Vec<(f64, f64)> = Vec::new();
            for p in pts.get_ref() {
                let v = p.get_ref();
                if v.len() != 2 {
                    return cx.err(
                        p.span(),
                        "history points",
                        format!("each point is [t, lambda], got {} numbers", v.len()),
                    );
                }
                let (t, l) = (v[0], v[1]);
                if !t.is_finite() || !l.is_finite() {
                    return cx.err(
                        p.span(),
                        "history points",
                        format!("non-finite number in [{t}, {l}]"),
                    );
                }
                if let Some(&(t0, l0)) = points.last() {
                    if t <= t0 {
                        return cx.err(
                            p.span(),
                            "history points",
                            format!("times must increase: {t} after {t0}"),
                        );
                    }
                    if l < l0 {
                        return cx.err(p.span(), "history points", format!("decreasing history: lambda = {l} at t = {t} after {l0} at t = {t0} (the loading class is monotone nondecreasing)"));
                    }
                } else if t != 0.0 || l != 0.0 {
                    return cx.err(p.span(), "history points", format!("the history starts from rest: the first point must be [0.0, 0.0], got [{t}, {l}]"));
                }
                points.push((t, l));
            }
            if points.len() < 2 {
                return cx.err(
                    pts.span(),
                    "history points",
                    "at least two points are needed",
                );
            }
            Ok(History::Table { points })
        }
        "saturating" => {
            unexpected(r.rate.is_some(), "rate", span_of(&r.rate))?;
            unexpected(
                r.points.is_some(),
                "points",
                r.points.as_ref().map(|s| s.span()).unwrap_or(0..0),
            )?;
            let (Some(peak), Some(tau)) = (&r.peak, &r.tau) else {
                return cx.err(
                    h.span(),
                    "history",
                    "kind = \"saturating\" needs peak and tau (lambda = peak (1 - exp(-t/tau)))",
                );
            };
            Ok(History::Saturating {
                peak: cx.positive(peak, "history peak")?,
                tau: cx.positive(tau, "history tau")?,
            })
        }
        other => {
            let span = r.kind.as_ref().map(|k| k.span()).unwrap_or(0..0);
            cx.err(
                span,
                "history kind",
                format!("unknown kind \"{other}\": expected \"ramp\", \"table\" or \"saturating\""),
            )
        }
    }
}

impl History {
    /// `lambda(t)` for `t >= 0`.
    pub fn lambda(&self, t: f64) -> f64 {
        match self {
            History::Ramp { rate } => rate * t,
            History::Table { points } => {
                let last = points[points.len() - 1];
                if t >= last.0 {
                    return last.1;
                }
                let k = points.partition_point(|p| p.0 <= t).max(1);
                let (a, b) = (points[k - 1], points[k]);
                a.1 + (b.1 - a.1) * (t - a.0) / (b.0 - a.0)
            }
            History::Saturating { peak, tau } => -peak * (-t / tau).exp_m1(),
        }
    }

    /// The first time at which `lambda(t) >= lambda`, if it is ever reached.
    pub fn time_at(&self, lambda: f64) -> Option<f64> {
        if lambda <= 0.0 {
            return Some(0.0);
        }
        match self {
            History::Ramp { rate } => Some(lambda / rate),
            History::Table { points } => {
                let k = points.iter().position(|p| p.1 >= lambda)?;
                let (a, b) = (points[k - 1], points[k]);
                Some(a.0 + (b.0 - a.0) * (lambda - a.1) / (b.1 - a.1))
            }
            History::Saturating { peak, tau } => {
                if lambda >= *peak {
                    None
                } else {
                    Some(-tau * (-lambda / peak).ln_1p())
                }
            }
        }
    }

    /// The largest value the history ever reaches (`inf` for a ramp).
    pub fn sup(&self) -> f64 {
        match self {
            History::Ramp { .. } => f64::INFINITY,
            History::Table { points } => points[points.len() - 1].1,
            History::Saturating { peak, .. } => *peak,
        }
    }

    /// Times in `(0, t_end)` where the history's formula changes (table knots).
    pub fn knots(&self, t_end: f64) -> Vec<f64> {
        match self {
            History::Table { points } => points
                .iter()
                .map(|p| p.0)
                .filter(|&t| t > 0.0 && t < t_end)
                .collect(),
            _ => Vec::new(),
        }
    }

    /// A one-line description, e.g. `ramp lambda = 1 t`.
    pub fn describe(&self) -> String {
        match self {
            History::Ramp { rate } => format!("ramp: lambda(t) = {rate} t"),
            History::Table { points } => format!(
                "table: piecewise linear through {} points, held at {} after t = {}",
                points.len(),
                points[points.len() - 1].1,
                points[points.len() - 1].0
            ),
            History::Saturating { peak, tau } => {
                format!("saturating: lambda(t) = {peak} (1 - exp(-t / {tau}))")
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const BASE: &str = r#"
[[node]]
id = "A"
x = 0
y = 0
[[node]]
id = "B"
x = 2.0
y = 0.0
[[member]]
id = "AB"
from = "A"
to = "B"
plastic_moment = 1.0
elements = 4
mass_per_length = 2.0
[[support]]
node = "A"
fix = ["x", "y", "rz"]
[[load]]
node = "B"
fy = -1.0
"#;

    fn err(src: &str) -> String {
        Scene::from_toml(src, "s.toml").unwrap_err().to_string()
    }

    #[test]
    fn parses_and_lumps() {
        let s = Scene::from_toml(BASE, "s.toml").unwrap();
        let f = &s.frame;
        assert_eq!(f.nodes.len(), 5);
        assert_eq!(f.nodes[2].id, "AB.1");
        assert_eq!(f.nodes[4].x, 1.5);
        // mu h / 2 to each end: h = 0.5, mu = 2 -> 0.5 per end
        assert_eq!(f.nodes[1].mass, 0.5); // tip: half
        assert_eq!(f.nodes[2].mass, 1.0);
        assert_eq!(f.elements[3].to, 1);
        assert_eq!(s.history, History::Ramp { rate: 1.0 });
    }

    #[test]
    fn errors_name_file_line_key() {
        assert_eq!(
            err(&BASE.replace("to = \"B\"", "to = \"Q\"")),
            "s.toml:13: member \"AB\" to: unknown node \"Q\""
        );
        assert_eq!(
            err(&BASE.replace("id = \"B\"", "id = \"A\"")),
            "s.toml:7: node \"A\" id: duplicate node id \"A\""
        );
        assert_eq!(
            err(&BASE.replace("x = 2.0", "x = 0.0")),
            "s.toml:13: member \"AB\" to: member of zero length (nodes \"A\" and \"B\" coincide)"
        );
        assert_eq!(err(&BASE.replace("mass_per_length = 2.0", "mass_per_length = 0.0")), "s.toml:22: load \"B\" fy: the load acts on a mechanism with no mass on it (node \"B\", component y): add a [[mass]] or mass_per_length, or a support");
        assert_eq!(
            err(&BASE.replace("y = 0.0", "y = nan")),
            "s.toml:9: node \"B\" y: must be a finite number, got NaN"
        );
        let e = err(&BASE.replace("plastic_moment", "plastic_momnet"));
        assert!(
            e.starts_with("s.toml:14:1: plastic_momnet: unknown key \"plastic_momnet\": the accepted keys are `id`, `from`, `to`, `plastic_moment`,"),
            "{e}"
        );
        let e = err(&format!(
            "{BASE}[history]\nkind = \"table\"\npoints = [[0.0, 0.0], [1.0, 2.0], [2.0, 1.0]]\n"
        ));
        assert!(
            e.starts_with("s.toml:25: history points: decreasing history"),
            "{e}"
        );
        assert_eq!(err(&BASE.replace("\"rz\"]", "\"rot\"]")), "s.toml:19: support \"A\" fix: unknown component \"rot\": expected \"x\", \"y\" or \"rz\"");
        assert_eq!(
            err(&BASE.replace("fy = -1.0", "fy = 0.0")),
            "s.toml:0: load: the scene has no nonzero [[load]]: nothing would move"
        );
        let e = err(&BASE.replace("y = 0\n", "y = \n"));
        assert!(e.starts_with("s.toml:5:5: "), "{e}");
        // never more than one line
        assert!(!e.contains('\n'));
    }

    /// Every table of the contract, each header followed by its keys.
    const EVERY_TABLE: [(&str, &str); 11] = [
        ("", "title = \"every table\"\nmodel = \"planar\"\n"),
        ("[yield]", "facets = 8\n"),
        ("[[node]]", "id = \"A\"\nx = 1.0\ny = 0.0\n"),
        ("[[node]]", "id = \"C\"\nx = 0.0\ny = 1.0\n"),
        (
            "[[arc]]",
            "id = \"Q\"\ncentre = [0.0, 0.0]\nradius = 1.0\nstart_angle = 0.0\nend_angle = 90.0\nelements = 4\nfrom = \"A\"\nto = \"C\"\nplastic_moment = 1.0\nplastic_axial = 4.0\nmass_per_length = 1.0\n",
        ),
        (
            "[[member]]",
            "id = \"AB\"\nfrom = \"A\"\nto = \"B\"\nplastic_moment = 1.0\nelements = 2\nmass_per_length = 1.0\n",
        ),
        ("[[support]]", "node = \"A\"\nfix = [\"x\", \"y\", \"rz\"]\n"),
        ("[[mass]]", "node = \"C\"\nm = 1.0\nj = 0.5\n"),
        ("[[load]]", "node = \"C\"\nfy = 1.0\n"),
        ("[history]", "kind = \"ramp\"\nrate = 2.0\n"),
        ("[[target]]", "node = \"C\"\ndirection = [1.0, 0.0, 0.0]\ngap = 0.5\n"),
    ];

    /// The scene with `extra` (a line) right after the header of table `at`.
    fn every_table(at: usize, extra: &str) -> String {
        let mut src = String::new();
        for (i, (header, body)) in EVERY_TABLE.iter().enumerate() {
            if !header.is_empty() {
                src.push_str(header);
                src.push('\n');
            }
            if i == at {
                src.push_str(extra);
                src.push('\n');
            }
            src.push_str(body);
            if i == 3 {
                src.push_str("[[node]]\nid = \"B\"\nx = 2.0\ny = 0.0\n");
            }
        }
        src
    }

    /// Unknown keys were already refused by `deny_unknown_fields`; now the error
    /// gives the column, and a `comment` key of any value is accepted in every
    /// table (it was an unknown key everywhere).
    #[test]
    fn every_table_refuses_unknown_keys_and_accepts_comment() {
        let plain = Scene::from_toml(&every_table(usize::MAX, ""), "s.toml").unwrap();
        for (at, (_, body)) in EVERY_TABLE.iter().enumerate() {
            for value in [
                "\"a note\"",
                "3",
                "[1, \"two\"]",
                "{ by = \"me\", rate = 5.0 }",
            ] {
                let src = every_table(at, &format!("comment = {value}"));
                let s = Scene::from_toml(&src, "s.toml")
                    .unwrap_or_else(|e| panic!("comment = {value} in table {at}: {e}"));
                assert_eq!(s.frame.nodes.len(), plain.frame.nodes.len());
                assert_eq!(s.history, plain.history);
            }
            let src = every_table(at, "  colour = \"red\"");
            let line = src.lines().position(|l| l.contains("colour")).unwrap() + 1;
            let e = Scene::from_toml(&src, "s.toml").unwrap_err();
            assert!(matches!(e, FramesError::Syntax { .. }), "{e:?}");
            let e = e.to_string();
            let want =
                format!("s.toml:{line}:3: colour: unknown key \"colour\": the accepted keys are ");
            assert!(e.starts_with(&want), "table {at}: {e}");
            assert!(e.contains("`comment`"), "table {at}: {e}");
            // each table lists its own keys
            let own = body.split(" =").next().unwrap();
            assert!(e.contains(&format!("`{own}`")), "table {at}: {e}");
            assert!(!e.contains('\n'));
        }
        // nested and inline tables, and a sub-table of an array-of-tables entry
        let inline = "history = { kind = \"ramp\", rate = 2.0, rat = 3.0 }";
        let src = format!(
            "{inline}\n{}",
            every_table(usize::MAX, "").replace("[history]\nkind = \"ramp\"\nrate = 2.0\n", "")
        );
        assert!(Scene::from_toml(&src.replace(", rat = 3.0", ""), "s.toml").is_ok());
        let e = err(&src);
        let column = inline.find("rat =").unwrap() + 1;
        assert!(
            e.starts_with(&format!("s.toml:1:{column}: rat: unknown key \"rat\""))
                && e.contains("`rate`"),
            "{e}"
        );
        let e = err(&format!(
            "{}[load.extra]\nfz = 1.0\n",
            every_table(usize::MAX, "")
        ));
        assert!(e.contains("extra: unknown key \"extra\""), "{e}");
        let e = err(&format!(
            "{}[units]\nlength = \"m\"\n",
            every_table(usize::MAX, "")
        ));
        assert!(
            e.contains("units: unknown key \"units\"") && e.contains("`node`"),
            "{e}"
        );
    }

    /// A stray Latin-1 byte (here in a `#` comment) was an I/O error without a
    /// position from `read_to_string`; it names offset, line and column.
    #[test]
    fn invalid_utf8_names_the_position() {
        let src = format!("# r\u{e9}sum\u{e9}\n{BASE}");
        assert!(Scene::from_bytes(src.as_bytes(), "s.toml").is_ok());
        let mut bytes = b"# r\xe9sum\xe9\n".to_vec();
        bytes.extend_from_slice(BASE.as_bytes());
        let e = Scene::from_bytes(&bytes, "s.toml").unwrap_err().to_string();
        assert!(
            e.starts_with("s.toml:1:4: (encoding): invalid UTF-8 at byte offset 3: byte 0xE9"),
            "{e}"
        );
        let mut bytes = BASE.as_bytes().to_vec();
        bytes.extend_from_slice(b"[[mass]]\nnode = \"B\"\nm = 1.0\xff\n");
        let e = Scene::from_bytes(&bytes, "s.toml").unwrap_err().to_string();
        let line = BASE.lines().count() + 3;
        let want = format!(
            "s.toml:{line}:8: (encoding): invalid UTF-8 at byte offset {}",
            BASE.len() + 27
        );
        assert!(e.starts_with(&want), "{e} (want {want})");
    }

    #[test]
    fn histories() {
        let t = History::Table {
            points: vec![(0.0, 0.0), (1.0, 2.0), (3.0, 2.0), (4.0, 3.0)],
        };
        assert_eq!(t.lambda(0.5), 1.0);
        assert_eq!(t.lambda(2.0), 2.0);
        assert_eq!(t.lambda(9.0), 3.0);
        assert_eq!(t.time_at(2.0), Some(1.0));
        assert_eq!(t.time_at(2.5), Some(3.5));
        assert_eq!(t.time_at(3.5), None);
        let s = History::Saturating {
            peak: 2.0,
            tau: 0.5,
        };
        let ts = s.time_at(1.0).unwrap();
        assert!((s.lambda(ts) - 1.0).abs() < 1e-14);
        assert_eq!(s.time_at(2.0), None);
    }
}

/// The stages of reading a scene ([`Scene::from_toml_with`]), in order:
/// nodes, the reduction of a space scene, members, arcs, supports and
/// masses, loads, then the history and the targets.
struct Reader<'a> {
    src: &'a str,
    file: &'a str,
    options: ReadOptions,
    raw: RawScene,
    cx: Ctx<'a>,
    frame: Frame,
    ids: HashMap<String, usize>,
    node_lines: HashMap<usize, usize>,
    load_lines: HashMap<(usize, usize), usize>,
    space: bool,
    model: Model,
    zs: Vec<f64>,
    default_facets: usize,
    member_ids: HashMap<String, ()>,
}

/// The node named by `s` in a `table`, or an error naming it.
fn node_ref(
    cx: &Ctx<'_>,
    ids: &HashMap<String, usize>,
    s: &Spanned<String>,
    table: &str,
) -> Result<usize, FramesError> {
    match ids.get(s.get_ref().trim()) {
        Some(&i) => Ok(i),
        None => cx.err(
            s.span(),
            format!("{table} node"),
            format!("unknown node \"{}\"", s.get_ref()),
        ),
    }
}

impl<'a> Reader<'a> {
    /// Parses the TOML and reads the model kind.
    fn new(src: &'a str, file: &'a str, options: ReadOptions) -> Result<Reader<'a>, FramesError> {
        let raw: RawScene = toml::from_str(src).map_err(|e| toml_error(src, file, e))?;
        let cx = Ctx { src, file };
        let frame = Frame {
            title: raw.title.clone().unwrap_or_default(),
            ..Frame::default()
        };
        let ids: HashMap<String, usize> = HashMap::new();
        let node_lines = HashMap::new();
        let space = raw
            .model
            .as_ref()
            .is_some_and(|m| m.get_ref().trim() == "space");
        let model = match &raw.model {
            None => Model::Planar,
            Some(_) if space => Model::Planar,
            Some(m) => match Model::from_name(m.get_ref().trim()) {
                Some(kind) => kind,
                None => {
                    let other = m.get_ref().trim();
                    return cx.err(
                        m.span(),
                        "model",
                        format!("unknown model \"{other}\": expected \"planar\", \"grillage\" or \"space\""),
                    );
                }
            },
        };
        Ok(Reader {
            src,
            file,
            options,
            raw,
            cx,
            frame,
            ids,
            node_lines,
            load_lines: HashMap::new(),
            space,
            model,
            zs: Vec::new(),
            default_facets: DEFAULT_FACETS,
            member_ids: HashMap::new(),
        })
    }

    /// The `[[node]]`s.
    fn nodes(&mut self) -> Result<(), FramesError> {
        let (src, space) = (self.src, self.space);
        let Reader {
            raw,
            cx,
            frame,
            ids,
            node_lines,
            zs,
            ..
        } = self;
        zs.reserve(raw.node.len());
        for n in &raw.node {
            let n = n.get_ref();
            let id = n.id.get_ref().trim().to_string();
            if id.is_empty() {
                return cx.err(n.id.span(), "node id", "must not be empty");
            }
            if ids.contains_key(&id) {
                return cx.err(
                    n.id.span(),
                    format!("node \"{id}\" id"),
                    format!("duplicate node id \"{id}\""),
                );
            }
            let x = cx.finite(&n.x, format!("node \"{id}\" x"))?;
            let y = cx.finite(&n.y, format!("node \"{id}\" y"))?;
            match (&n.z, space) {
                (Some(z), true) => zs.push(cx.finite(z, format!("node \"{id}\" z"))?),
                (None, true) => {
                    return cx.err(
                        n.id.span(),
                        format!("node \"{id}\" z"),
                        "a node of a space scene needs z",
                    )
                }
                (Some(z), false) => {
                    return cx.err(
                        z.span(),
                        format!("node \"{id}\" z"),
                        "a key of space scenes only (model = \"space\")",
                    )
                }
                (None, false) => {}
            }
            ids.insert(id.clone(), frame.nodes.len());
            node_lines.insert(frame.nodes.len(), line_of(src, n.id.span().start));
            frame.nodes.push(Node {
                id,
                x,
                y,
                z: 0.0,
                fixed: [false; 6],
                mass: 0.0,
                inertia: 0.0,
                load: [0.0; 6],
                generated: false,
            });
        }
        Ok(())
    }

    /// A space scene: the plane sought and the model it is solved as; the
    /// default number of facets.
    fn reduce(&mut self) -> Result<(), FramesError> {
        let options = self.options;
        let space = self.space;
        let Reader {
            raw,
            cx,
            frame,
            model,
            zs,
            ..
        } = self;
        if space {
            let loads = raw
                .load
                .iter()
                .map(|l| {
                    let l = l.get_ref();
                    let v = |k: &str| l.key(k).map_or(0.0, |v| *v.get_ref());
                    ([v("fx"), v("fy"), v("fz")], [v("mx"), v("my"), v("mz")])
                })
                .filter(|l| l.0.iter().chain(&l.1).all(|v| v.is_finite()))
                .collect::<Vec<_>>();
            let mut points: Vec<[f64; 3]> = frame
                .nodes
                .iter()
                .zip(zs.iter())
                .map(|(n, &z)| [n.x, n.y, z])
                .collect();
            // the arcs' points are part of the geometry whose plane is sought
            for a in &raw.arc {
                points.extend(a.get_ref().space_points().unwrap_or_default());
            }
            let span = raw.model.as_ref().map_or(0..0, |m| m.span());
            if points.is_empty() {
                return cx.err(span, "node", "the scene has no [[node]]");
            }
            let reduced = if options.reduce_space {
                crate::space::reduce(&points, &loads)
            } else {
                crate::space::general(
                    &points,
                    "the reduction is switched off (ReadOptions::reduce_space = false)",
                )
            };
            let r = match reduced {
                Ok(r) => r,
                Err(why) => return cx.err(span, "model", why),
            };
            if !r.global_axes {
                for (n, p) in frame.nodes.iter_mut().zip(&points) {
                    let l = r.to_local(*p);
                    (n.x, n.y) = (l[0], l[1]);
                }
            }
            if r.kind == Model::Space {
                for (n, p) in frame.nodes.iter_mut().zip(&points) {
                    n.z = p[2];
                }
            }
            *model = r.kind;
            frame.reduction = Some(r);
        }
        frame.model = *model;
        self.default_facets = match raw
            .yield_table
            .as_ref()
            .and_then(|y| y.get_ref().facets.as_ref())
        {
            Some(f) => cx.facets(f, "yield facets")?,
            None => DEFAULT_FACETS,
        };
        Ok(())
    }

    /// The `[[member]]`s.
    fn members(&mut self) -> Result<(), FramesError> {
        let (space, default_facets) = (self.space, self.default_facets);
        let Reader {
            raw,
            cx,
            frame,
            ids,
            model,
            member_ids,
            ..
        } = self;
        let model = *model;
        for m in &raw.member {
            let m = m.get_ref();
            let id = m.id.get_ref().trim().to_string();
            if id.is_empty() {
                return cx.err(m.id.span(), "member id", "must not be empty");
            }
            if member_ids.insert(id.clone(), ()).is_some() {
                return cx.err(
                    m.id.span(),
                    format!("member \"{id}\" id"),
                    format!("duplicate member id \"{id}\""),
                );
            }
            let lookup = |s: &Spanned<String>, key: &str| -> Result<usize, FramesError> {
                match ids.get(s.get_ref().trim()) {
                    Some(&i) if !frame.nodes[i].generated => Ok(i),
                    _ => cx.err(
                        s.span(),
                        format!("member \"{id}\" {key}"),
                        format!("unknown node \"{}\"", s.get_ref()),
                    ),
                }
            };
            let from = lookup(&m.from, "from")?;
            let to = lookup(&m.to, "to")?;
            let mut keys = Keys {
                plastic_moment: &m.plastic_moment,
                plastic_torque: m.plastic_torque.as_ref(),
                plastic_axial: m.plastic_axial.as_ref(),
                facets: m.facets.as_ref(),
                mass_per_length: m.mass_per_length.as_ref(),
            };
            if space {
                keys =
                    cx.space_keys(model, &format!("member \"{id}\""), "a member", &m.id, keys)?;
            }
            let orientation = match (&m.orientation, space) {
                (None, _) => None,
                (Some(o), false) => {
                    return cx.err(
                        o.span(),
                        format!("member \"{id}\" orientation"),
                        "a key of space scenes only (model = \"space\")",
                    )
                }
                (Some(o), true) => {
                    let v = o.get_ref();
                    if v.len() != 3 || v.iter().any(|x| !x.is_finite() || x.abs() > 1e100) {
                        return cx.err(
                            o.span(),
                            format!("member \"{id}\" orientation"),
                            format!("must be three finite numbers [vx, vy, vz], got {v:?}"),
                        );
                    }
                    let g = [v[0], v[1], v[2]];
                    // a reduced scene's axes are those of its plane
                    Some((
                        frame.reduction.as_ref().map_or(g, |r| r.to_local(g)),
                        o.span(),
                    ))
                }
            };
            let (mp, interaction, mu) = cx.strength(
                model,
                &format!("member \"{id}\""),
                &m.id,
                keys,
                default_facets,
            )?;
            let n = match &m.elements {
                Some(v) => cx.element_count(v, &format!("member \"{id}\" elements"))?,
                None => 1,
            };
            let (a, b) = (&frame.nodes[from], &frame.nodes[to]);
            let (dx, dy, dz) = (b.x - a.x, b.y - a.y, b.z - a.z);
            let length = if model == Model::Space {
                (dx * dx + dy * dy + dz * dz).sqrt()
            } else {
                dx.hypot(dy)
            };
            if length.is_nan() || length <= 0.0 || !length.is_finite() {
                return cx.err(
                    m.to.span(),
                    format!("member \"{id}\" to"),
                    format!(
                        "member of zero length (nodes \"{}\" and \"{}\" coincide)",
                        a.id, b.id
                    ),
                );
            }
            let (ax, ay, az) = (a.x, a.y, a.z);
            // the chain of nodes, generating the inner ones
            let mut chain = vec![from];
            for k in 1..n {
                let gid = format!("{id}.{k}");
                let t = k as f64 / n as f64;
                // exact at the ends of axis-parallel members: dx or dy is exactly zero
                let i = cx.generate_node(
                    frame,
                    ids,
                    gid,
                    (ax + t * dx, ay + t * dy, az + t * dz),
                    true,
                    m.elements.as_ref().map(|e| e.span()).unwrap_or(m.id.span()),
                    &format!("member \"{id}\" elements"),
                )?;
                chain.push(i);
            }
            chain.push(to);
            // equal elements share the member's direction: exact zeros for
            // axis-parallel members keep decoupled parts decoupled
            let dirs = vec![(length / n as f64, dx / length, dy / length); n];
            let axes = if model == Model::Space {
                let e1 = [dx / length, dy / length, dz / length];
                let (v, span) = match orientation {
                    Some((v, span)) => (Some(v), span),
                    None => (None, m.id.span()),
                };
                match crate::space::element_axes(e1, v) {
                    Ok(axes) => Some(axes),
                    Err(why) => return cx.err(span, format!("member \"{id}\" orientation"), why),
                }
            } else {
                None
            };
            let axes: Vec<[[f64; 3]; 3]> = axes.map_or_else(Vec::new, |a| vec![a; n]);
            push_member(frame, id, chain, &dirs, &axes, mp, interaction, mu);
        }
        Ok(())
    }

    /// The `[[arc]]`s.
    fn arcs(&mut self) -> Result<(), FramesError> {
        let (space, default_facets) = (self.space, self.default_facets);
        let Reader {
            raw,
            cx,
            frame,
            ids,
            model,
            member_ids,
            ..
        } = self;
        let model = *model;
        for arc in &raw.arc {
            let r = arc.get_ref();
            let id = r.id.get_ref().trim().to_string();
            if id.is_empty() {
                return cx.err(r.id.span(), "arc id", "must not be empty");
            }
            if member_ids.insert(id.clone(), ()).is_some() {
                return cx.err(
                    r.id.span(),
                    format!("arc \"{id}\" id"),
                    format!("duplicate member id \"{id}\" (arcs and members share ids)"),
                );
            }
            let table = format!("arc \"{id}\"");
            let mut keys = Keys {
                plastic_moment: &r.plastic_moment,
                plastic_torque: r.plastic_torque.as_ref(),
                plastic_axial: r.plastic_axial.as_ref(),
                facets: r.facets.as_ref(),
                mass_per_length: r.mass_per_length.as_ref(),
            };
            if space {
                keys = cx.space_keys(model, &table, "an arc", &r.id, keys)?;
            }
            let (mp, interaction, mu) = cx.strength(model, &table, &r.id, keys, default_facets)?;
            let centre = r.centre.get_ref();
            let dims = if space { 3 } else { 2 };
            if centre.len() != dims || centre.iter().any(|v| !v.is_finite() || v.abs() > 1e100) {
                let what = if space {
                    "three finite numbers [x, y, z] (model = \"space\")"
                } else {
                    "two finite numbers [x, y]"
                };
                return cx.err(
                    r.centre.span(),
                    format!("{table} centre"),
                    format!("must be {what}, got {centre:?}"),
                );
            }
            // a space arc: its plane's normal (global), in-plane axes
            let normal = match (&r.normal, space) {
                (Some(n), false) => {
                    return cx.err(
                        n.span(),
                        format!("{table} normal"),
                        "a key of space scenes only (model = \"space\")",
                    )
                }
                (Some(n), true) => match crate::space::unit_of(n.get_ref()) {
                    Some(u) => u,
                    None => {
                        return cx.err(
                            n.span(),
                            format!("{table} normal"),
                            format!(
                                "must be three finite numbers [nx, ny, nz], not all zero, got {:?}",
                                n.get_ref()
                            ),
                        )
                    }
                },
                (None, _) => [0.0, 0.0, 1.0],
            };
            let reference = match (&r.reference, space) {
                (Some(g), false) => {
                    return cx.err(
                        g.span(),
                        format!("{table} reference"),
                        "a key of space scenes only (model = \"space\")",
                    )
                }
                (Some(g), true) => match crate::space::unit_of(g.get_ref()) {
                    Some(u) => Some((u, g.span())),
                    None => {
                        return cx.err(
                            g.span(),
                            format!("{table} reference"),
                            format!(
                                "must be three finite numbers, not all zero, got {:?}",
                                g.get_ref()
                            ),
                        )
                    }
                },
                (None, _) => None,
            };
            let Some(arc_axes) = crate::space::arc_axes(normal, reference.as_ref().map(|g| g.0))
            else {
                let span = reference.map_or(r.id.span(), |g| g.1);
                return cx.err(
                    span,
                    format!("{table} reference"),
                    "the reference direction is along the normal: give one in the arc's plane",
                );
            };
            let radius = cx.positive(&r.radius, format!("{table} radius"))?;
            let a0 = cx.finite(&r.start_angle, format!("{table} start_angle"))?;
            let a1 = cx.finite(&r.end_angle, format!("{table} end_angle"))?;
            let sweep = a1 - a0;
            if sweep == 0.0 || sweep.abs() >= 360.0 {
                return cx.err(
                    r.end_angle.span(),
                    format!("{table} end_angle"),
                    format!("the arc must sweep more than 0 and less than 360 degrees, got {sweep} (from {a0} to {a1})"),
                );
            }
            let n = cx.element_count(&r.elements, &format!("{table} elements"))?;
            let general = model == Model::Space;
            let reduction = frame.reduction.clone();
            let point = |k: usize| {
                if space {
                    let angle = a0 + sweep * k as f64 / n as f64;
                    let c = [centre[0], centre[1], centre[2]];
                    let p = crate::space::arc_point(c, radius, arc_axes, angle);
                    if general {
                        return (p[0], p[1], p[2]);
                    }
                    let l = reduction.as_ref().map_or(p, |r| r.to_local(p));
                    return (l[0], l[1], 0.0);
                }
                let t = (a0 + sweep * k as f64 / n as f64).to_radians();
                let (s, c) = t.sin_cos();
                (centre[0] + radius * c, centre[1] + radius * s, 0.0)
            };
            let mut chain = Vec::with_capacity(n + 1);
            for k in 0..=n {
                let end = if k == 0 {
                    Some((&r.from, "from"))
                } else if k == n {
                    Some((&r.to, "to"))
                } else {
                    None
                };
                let p = point(k);
                if let Some((Some(node), key)) = end {
                    let i = match ids.get(node.get_ref().trim()) {
                        Some(&i) if !frame.nodes[i].generated => i,
                        _ => {
                            return cx.err(
                                node.span(),
                                format!("{table} {key}"),
                                format!("unknown node \"{}\"", node.get_ref()),
                            )
                        }
                    };
                    let nd = &frame.nodes[i];
                    let off = if general {
                        (nd.x - p.0).hypot(nd.y - p.1).hypot(nd.z - p.2)
                    } else {
                        (nd.x - p.0).hypot(nd.y - p.1)
                    };
                    if off > 1e-9 * radius.max(p.0.abs()).max(p.1.abs()).max(p.2.abs()) {
                        return cx.err(
                            node.span(),
                            format!("{table} {key}"),
                            format!(
                                "node \"{}\" at ({}, {}) is not the arc's {} point ({}, {})",
                                nd.id,
                                nd.x,
                                nd.y,
                                if k == 0 { "start" } else { "end" },
                                p.0,
                                p.1
                            ),
                        );
                    }
                    chain.push(i);
                } else {
                    let i = cx.generate_node(
                        frame,
                        ids,
                        format!("{id}.{k}"),
                        p,
                        end.is_none(),
                        r.elements.span(),
                        &format!("{table} elements"),
                    )?;
                    chain.push(i);
                }
            }
            let mut dirs = Vec::with_capacity(n);
            let mut axes = Vec::new();
            for w in chain.windows(2) {
                let (a, b) = (&frame.nodes[w[0]], &frame.nodes[w[1]]);
                let (dx, dy, dz) = (b.x - a.x, b.y - a.y, b.z - a.z);
                let h = if general {
                    dx.hypot(dy).hypot(dz)
                } else {
                    dx.hypot(dy)
                };
                if general && h > 0.0 && h.is_finite() {
                    // e3 the arc's normal: bending in its plane is about e3
                    match crate::space::element_axes([dx / h, dy / h, dz / h], Some(normal)) {
                        Ok(e) => axes.push(e),
                        Err(why) => {
                            return cx.err(r.elements.span(), format!("{table} elements"), why)
                        }
                    }
                }
                if !(h > 0.0 && h.is_finite()) {
                    return cx.err(
                        r.elements.span(),
                        format!("{table} elements"),
                        format!("an element of zero length between \"{}\" and \"{}\" (too many elements for the radius)", a.id, b.id),
                    );
                }
                dirs.push((h, dx / h, dy / h));
            }
            push_member(frame, id, chain, &dirs, &axes, mp, interaction, mu);
        }
        Ok(())
    }

    /// The `[[support]]`s and `[[mass]]`es.
    fn supports_and_masses(&mut self) -> Result<(), FramesError> {
        let Reader {
            raw,
            cx,
            frame,
            ids,
            model,
            ..
        } = self;
        let model = *model;
        let node_ref = |s: &Spanned<String>, table: &str| node_ref(cx, ids, s, table);
        let mut supported: HashMap<usize, ()> = HashMap::new();
        for s in &raw.support {
            let s = s.get_ref();
            let i = node_ref(&s.node, "support")?;
            let nid = frame.nodes[i].id.clone();
            if supported.insert(i, ()).is_some() {
                return cx.err(s.node.span(), format!("support \"{nid}\" node"), format!("a second [[support]] for node \"{nid}\" (list every fixed component in one)"));
            }
            if let Some(r) = &frame.reduction {
                const SIX: [&str; 6] = ["x", "y", "z", "rx", "ry", "rz"];
                let mut fixed = [false; 6];
                for c in s.fix.get_ref() {
                    let Some(k) = SIX.iter().position(|k| *k == c.get_ref().as_str()) else {
                        return cx.err(
                            c.span(),
                            format!("support \"{nid}\" fix"),
                            format!("unknown component \"{}\": expected \"x\", \"y\", \"z\", \"rx\", \"ry\" or \"rz\" (model = \"space\")", c.get_ref()),
                        );
                    };
                    fixed[k] = true;
                }
                match crate::space::local_fixed(r, fixed) {
                    Ok(f) => frame.nodes[i].fixed = f,
                    Err(why) => return cx.err(s.fix.span(), format!("support \"{nid}\" fix"), why),
                }
                continue;
            }
            let comps = model.components();
            for c in s.fix.get_ref() {
                let Some(k) = comps.iter().find(|k| k.as_str() == c.get_ref().as_str()) else {
                    let other = c.get_ref();
                    let names: Vec<&str> = comps.iter().map(|k| k.as_str()).collect();
                    let (a, b, d) = (names[0], names[1], names[2]);
                    let hint = model.support_hint();
                    return cx.err(
                        c.span(),
                        format!("support \"{nid}\" fix"),
                        format!("unknown component \"{other}\": expected \"{a}\", \"{b}\" or \"{d}\"{hint}"),
                    );
                };
                frame.nodes[i].fixed[k.index()] = true;
            }
        }
        for m in &raw.mass {
            let m = m.get_ref();
            let i = node_ref(&m.node, "mass")?;
            let nid = frame.nodes[i].id.clone();
            if let Some(v) = &m.m {
                frame.nodes[i].mass += cx.nonnegative(v, format!("mass \"{nid}\" m"))?;
            }
            if let Some(v) = &m.j {
                frame.nodes[i].inertia += cx.nonnegative(v, format!("mass \"{nid}\" j"))?;
            }
        }
        Ok(())
    }

    /// The `[[load]]`s.
    fn loads(&mut self) -> Result<(), FramesError> {
        let src = self.src;
        let Reader {
            raw,
            cx,
            frame,
            ids,
            load_lines,
            model,
            ..
        } = self;
        let model = *model;
        let node_ref = |s: &Spanned<String>, table: &str| node_ref(cx, ids, s, table);
        for l in &raw.load {
            let l = l.get_ref();
            let i = node_ref(&l.node, "load")?;
            let nid = frame.nodes[i].id.clone();
            if let Some(r) = &frame.reduction {
                let mut v = [0.0; 6];
                for (k, name) in ["fx", "fy", "fz", "mx", "my", "mz"].into_iter().enumerate() {
                    if let Some(x) = l.key(name) {
                        v[k] = cx.finite(x, format!("load \"{nid}\" {name}"))?;
                        let line = line_of(src, x.span().start);
                        for c in 0..6 {
                            load_lines.entry((i, c)).or_insert(line);
                        }
                    }
                }
                let local = crate::space::local_load(r, ([v[0], v[1], v[2]], [v[3], v[4], v[5]]));
                for (k, x) in local.into_iter().enumerate() {
                    frame.nodes[i].load[k] += x;
                }
                continue;
            }
            for name in model.foreign_load_keys() {
                if let Some(v) = l.key(name) {
                    let keys = model.load_keys();
                    let (a, b, c) = (keys[0], keys[1], keys[2]);
                    return cx.err(
                        v.span(),
                        format!("load \"{nid}\" {name}"),
                        format!(
                            "not a load of a {} scene (model = \"{}\": {a}, {b}, {c})",
                            model.as_str(),
                            model.as_str()
                        ),
                    );
                }
            }
            for (&name, comp) in model.load_keys().iter().zip(model.components()) {
                let k = comp.index();
                if let Some(v) = l.key(name) {
                    load_lines
                        .entry((i, k))
                        .or_insert_with(|| line_of(src, v.span().start));
                    frame.nodes[i].load[k] += cx.finite(v, format!("load \"{nid}\" {name}"))?;
                }
            }
        }
        Ok(())
    }

    /// The history and the `[[target]]`s; the scene, checked.
    fn finish(self) -> Result<Scene, FramesError> {
        let Reader {
            file,
            raw,
            cx,
            frame,
            ids,
            node_lines,
            load_lines,
            model,
            ..
        } = self;
        let node_ref = |s: &Spanned<String>, table: &str| node_ref(&cx, &ids, s, table);
        let history = match &raw.history {
            None => History::default(),
            Some(h) => parse_history(&cx, h)?,
        };
        let mut targets = Vec::with_capacity(raw.target.len());
        for t in &raw.target {
            let t = t.get_ref();
            let node = node_ref(&t.node, "target")?;
            targets.push(parse_target(
                &cx,
                model,
                frame.reduction.as_ref(),
                &frame.nodes[node].id,
                node,
                t,
            )?);
        }
        if frame.members.is_empty() {
            return cx.err(0..0, "member", "the scene has no [[member]]");
        }
        let scene = Scene {
            file: file.to_string(),
            frame,
            history,
            load_lines,
            node_lines,
            targets,
        };
        scene.check_mechanics()?;
        Ok(scene)
    }
}
