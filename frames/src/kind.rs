//! One place that knows a model kind: what differs between a planar frame and
//! a grillage (and what a space scene is reduced to, see [`crate::space`]).
//!
//! A kind fixes
//!
//! - the three nodal components (`x, y, rz` or `z, rx, ry`) and their load keys;
//! - the second member force of an element (axial force or torque) and the
//!   strength key that couples it with bending in the yield polygon
//!   (`plastic_axial`, optional, or `plastic_torque`, required);
//! - the element's deformation rows of `A`: the two end sections' hinge
//!   rotations and the elongation or twist, in the element's axes
//!   (the formulas are in [`crate::assemble`]);
//! - which pairs of sections at a node are tied (one physical hinge);
//! - which translations a `[[target]]` direction may have.
//!
//! Every other module asks the kind instead of matching on it, so a new kind
//! is added here (and in the report's wording).

use crate::assemble::MemberForce;
use crate::model::{Element, Node};
use crate::yield_surface::Curve;

/// The structural model of a scene: which three components a node has.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Model {
    /// In-plane frame: nodes move in x and y and rotate about z; members carry
    /// end moments (and an axial force).
    #[default]
    Planar,
    /// Grillage: the frame lies in the x-y plane, nodes move in z and rotate
    /// about x and y; members carry end bending moments and a torque.
    Grillage,
}

/// A nodal component: translations in x, y (planar) or z (grillage), rotations
/// about z (planar) or about x and y (grillage).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Component {
    /// Translation along the global x axis (planar).
    X,
    /// Translation along the global y axis (planar).
    Y,
    /// Rotation about z, counter-clockwise positive (planar).
    Rz,
    /// Translation along the global z axis, out of the frame's plane (grillage).
    Z,
    /// Rotation about the global x axis, right-handed (grillage).
    Rx,
    /// Rotation about the global y axis, right-handed (grillage).
    Ry,
}

impl Component {
    /// The three components of the planar model in order.
    pub const ALL: [Component; 3] = [Component::X, Component::Y, Component::Rz];
    /// `"x"`, `"y"`, `"rz"`, `"z"`, `"rx"` or `"ry"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Component::X => "x",
            Component::Y => "y",
            Component::Rz => "rz",
            Component::Z => "z",
            Component::Rx => "rx",
            Component::Ry => "ry",
        }
    }
    /// The slot in [`Node::fixed`], [`Node::load`] and the per-node arrays of
    /// the response: 0, 1, 2 for `x, y, rz` (planar) and for `z, rx, ry` (grillage).
    pub fn index(self) -> usize {
        match self {
            Component::X | Component::Z => 0,
            Component::Y | Component::Rx => 1,
            Component::Rz | Component::Ry => 2,
        }
    }
    /// True for the rotations.
    pub fn is_rotation(self) -> bool {
        matches!(self, Component::Rz | Component::Rx | Component::Ry)
    }
}

/// A row of `A` an element contributes to (see [`Model::element_rows`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum ElementRow {
    /// The hinge rotation of the section at the start node.
    From,
    /// The hinge rotation of the section at the end node.
    To,
    /// The elongation (planar) or twist (grillage), dual to the second force.
    Second,
}

/// How a kind reads the strength of a member's second force.
pub(crate) struct SecondForceRule {
    /// The key giving its plastic capacity (`plastic_axial` or `plastic_torque`).
    pub key: &'static str,
    /// The interaction curve with bending.
    pub curve: Curve,
    /// Whether every member must give it.
    pub required: bool,
    /// The message when it is missing but required.
    pub required_message: &'static str,
    /// The capacity key of the other kind, an error here.
    pub foreign_key: &'static str,
    /// The message for the other kind's key.
    pub foreign_message: &'static str,
    /// The message for `facets` without the capacity (when not required).
    pub facets_message: &'static str,
}

impl Model {
    /// `"planar"` or `"grillage"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Model::Planar => "planar",
            Model::Grillage => "grillage",
        }
    }
    /// The kind named by a scene's `model` key, if it is one of these.
    pub fn from_name(name: &str) -> Option<Model> {
        match name {
            "planar" => Some(Model::Planar),
            "grillage" => Some(Model::Grillage),
            _ => None,
        }
    }
    /// The three nodal components, in the order of [`Node::fixed`] and [`Node::load`].
    pub fn components(self) -> [Component; 3] {
        match self {
            Model::Planar => [Component::X, Component::Y, Component::Rz],
            Model::Grillage => [Component::Z, Component::Rx, Component::Ry],
        }
    }
    /// The load keys of the three components: `fx, fy, mz` or `fz, mx, my`.
    pub fn load_keys(self) -> [&'static str; 3] {
        match self {
            Model::Planar => ["fx", "fy", "mz"],
            Model::Grillage => ["fz", "mx", "my"],
        }
    }
    /// The load keys of the other kind (errors in a scene of this kind).
    pub(crate) fn foreign_load_keys(self) -> [&'static str; 3] {
        match self {
            Model::Planar => ["fz", "mx", "my"],
            Model::Grillage => ["fx", "fy", "mz"],
        }
    }
    /// Appended to an unknown support component's message.
    pub(crate) fn support_hint(self) -> &'static str {
        match self {
            Model::Planar => "",
            Model::Grillage => " (model = \"grillage\")",
        }
    }
    /// The second member force of element `e`: its axial force or its torque.
    pub fn second_force(self, e: usize) -> MemberForce {
        match self {
            Model::Planar => MemberForce::Axial(e),
            Model::Grillage => MemberForce::Torque(e),
        }
    }
    /// How the second force's strength is given.
    pub(crate) fn second_force_rule(self) -> SecondForceRule {
        match self {
            Model::Grillage => SecondForceRule {
                key: "plastic_torque",
                curve: Curve::BendingTorsion,
                required: true,
                required_message: "a grillage member needs plastic_torque (the plastic torque Tp)",
                foreign_key: "plastic_axial",
                foreign_message: "not a key of a grillage member (out of plane a member carries bending and torsion: plastic_torque)",
                facets_message: "",
            },
            Model::Planar => SecondForceRule {
                key: "plastic_axial",
                curve: Curve::BendingAxial,
                required: false,
                required_message: "",
                foreign_key: "plastic_torque",
                foreign_message: "a key of grillage members only (model = \"grillage\")",
                facets_message: "facets sets the bending-axial polygon of a planar member: give plastic_axial too",
            },
        }
    }
    /// True if an element's second force has no yield mode and its dual
    /// deformation is held at zero (inextensible planar members).
    pub(crate) fn second_force_is_rigid(self, el: &Element) -> bool {
        self == Model::Planar && el.interaction.is_none()
    }
    /// The entries of element `el`'s rows of `A`, given the coordinate
    /// indices `ia`, `ib` of its end nodes (in the order of
    /// [`Model::components`]; `None` where supported). Calls `add(row,
    /// coordinate, value)` for each term, in a fixed order (the sums are
    /// bit-identical from run to run).
    pub(crate) fn element_rows(
        self,
        el: &Element,
        ia: [Option<usize>; 3],
        ib: [Option<usize>; 3],
        add: &mut dyn FnMut(ElementRow, Option<usize>, f64),
    ) {
        let (c, s, h) = (el.cos, el.sin, el.length);
        let (rf, rt, rn) = (ElementRow::From, ElementRow::To, ElementRow::Second);
        match self {
            Model::Planar => {
                // psi = (-s (uxb - uxa) + c (uyb - uya)) / h
                let psi = [
                    (ia[0], s / h),
                    (ia[1], -c / h),
                    (ib[0], -s / h),
                    (ib[1], c / h),
                ];
                // from section: -(theta_a - psi)
                add(rf, ia[2], -1.0);
                for &(j, v) in &psi {
                    add(rf, j, v);
                }
                // to section: theta_b - psi
                add(rt, ib[2], 1.0);
                for &(j, v) in &psi {
                    add(rt, j, -v);
                }
                // elongation
                add(rn, ia[0], -c);
                add(rn, ia[1], -s);
                add(rn, ib[0], c);
                add(rn, ib[1], s);
            }
            Model::Grillage => {
                // psi = -(w_b - w_a) / h; theta = -s r_x + c r_y; phi = c r_x + s r_y
                let psi = [(ia[0], 1.0 / h), (ib[0], -1.0 / h)];
                // from section: -(theta_a - psi)
                add(rf, ia[1], s);
                add(rf, ia[2], -c);
                for &(j, v) in &psi {
                    add(rf, j, v);
                }
                // to section: theta_b - psi
                add(rt, ib[1], -s);
                add(rt, ib[2], c);
                for &(j, v) in &psi {
                    add(rt, j, -v);
                }
                // twist phi_b - phi_a
                add(rn, ia[1], -c);
                add(rn, ia[2], -s);
                add(rn, ib[1], c);
                add(rn, ib[2], s);
            }
        }
    }
    /// Whether the two sections of elements `ea`, `eb` meeting at node `n`
    /// (without rotary inertia, the node's only two sections) are tied:
    /// planar, sections without interaction at a free, unloaded rotation;
    /// grillage, collinear elements of equal strength at a node whose two
    /// rotations are free and unloaded.
    pub(crate) fn tied(self, n: &Node, ea: &Element, eb: &Element) -> bool {
        match self {
            Model::Planar => {
                !n.fixed[2]
                    && n.load[2] == 0.0
                    && ea.interaction.is_none()
                    && eb.interaction.is_none()
            }
            Model::Grillage => {
                let collinear = (ea.cos == eb.cos && ea.sin == eb.sin)
                    || (ea.cos == -eb.cos && ea.sin == -eb.sin);
                !n.fixed[1]
                    && !n.fixed[2]
                    && n.load[1] == 0.0
                    && n.load[2] == 0.0
                    && collinear
                    && ea.plastic_moment == eb.plastic_moment
                    && ea.interaction == eb.interaction
            }
        }
    }
    /// The translations (0 = x, 1 = y, 2 = z) a target direction must not
    /// have in this kind, and why.
    pub(crate) fn target_zero(self) -> (&'static [usize], &'static str) {
        match self {
            Model::Planar => (
                &[2usize][..],
                "dz must be 0 in a planar scene (nodes move in x and y)",
            ),
            Model::Grillage => (
                &[0usize, 1][..],
                "dx and dy must be 0 in a grillage (nodes move in z only)",
            ),
        }
    }
}
