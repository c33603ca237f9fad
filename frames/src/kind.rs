//! One place that knows a model kind: what differs between a planar frame, a
//! grillage and a general space frame (and what a space scene is reduced to,
//! see [`crate::space`]).
//!
//! A kind fixes
//!
//! - the nodal components (`x, y, rz`, `z, rx, ry` or all six) and their load keys;
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

/// The structural model of a scene: which components a node has.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Model {
    /// In-plane frame: nodes move in x and y and rotate about z; members carry
    /// end moments (and an axial force).
    #[default]
    Planar,
    /// Grillage: the frame lies in the x-y plane, nodes move in z and rotate
    /// about x and y; members carry end bending moments and a torque.
    Grillage,
    /// General space frame (a `model = "space"` scene that is not planar):
    /// nodes move in x, y, z and rotate about all three axes; members carry an
    /// axial force (a reaction: inextensible), a torque and two bending
    /// moments at each end, in the element's axes ([`crate::space`]).
    Space,
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
    /// the response (six slots, one per component): 0, 1, 2 for `x, y, rz`
    /// (the planar components), 3, 4, 5 for `z, rx, ry` (the grillage's).
    pub fn index(self) -> usize {
        match self {
            Component::X => 0,
            Component::Y => 1,
            Component::Rz => 2,
            Component::Z => 3,
            Component::Rx => 4,
            Component::Ry => 5,
        }
    }
    /// The global axis (0 = x, 1 = y, 2 = z) of the translation or rotation.
    pub fn axis(self) -> usize {
        match self {
            Component::X | Component::Rx => 0,
            Component::Y | Component::Ry => 1,
            Component::Z | Component::Rz => 2,
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
    /// The hinge rotation of the section at the start node (space: about `e3`).
    From,
    /// The hinge rotation of the section at the end node (space: about `e3`).
    To,
    /// The elongation (planar) or twist (grillage, space), dual to the second force.
    Second,
    /// Space: the hinge rotation about `e2` of the section at the start node.
    From2,
    /// Space: the hinge rotation about `e2` of the section at the end node.
    To2,
    /// Space: the elongation, dual to the axial force (held at zero).
    Third,
}

impl ElementRow {
    /// The row of `A` (the member force) of element `e` of `ne`: the moments
    /// of all sections `[0, 2 ne)`, the second forces `[2 ne, 3 ne)`, then
    /// (space) the moments about `e2` `[3 ne, 5 ne)` and the axial forces.
    pub(crate) fn row(self, e: usize, ne: usize) -> usize {
        match self {
            ElementRow::From => 2 * e,
            ElementRow::To => 2 * e + 1,
            ElementRow::Second => 2 * ne + e,
            ElementRow::From2 => 3 * ne + 2 * e,
            ElementRow::To2 => 3 * ne + 2 * e + 1,
            ElementRow::Third => 5 * ne + e,
        }
    }
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
    /// A third force's capacity key that enlarges the yield surface (space:
    /// `plastic_axial`, the bending-torsion-axial polytope).
    pub third_key: Option<&'static str>,
}

impl Model {
    /// `"planar"`, `"grillage"` or `"space"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Model::Planar => "planar",
            Model::Grillage => "grillage",
            Model::Space => "space",
        }
    }
    /// The kind named by a scene's `model` key, if it is planar or grillage
    /// (`"space"` is read by the scene: it may reduce to either).
    pub fn from_name(name: &str) -> Option<Model> {
        match name {
            "planar" => Some(Model::Planar),
            "grillage" => Some(Model::Grillage),
            _ => None,
        }
    }
    /// The nodal components, in the order of the generalised coordinates.
    pub fn components(self) -> &'static [Component] {
        match self {
            Model::Planar => &[Component::X, Component::Y, Component::Rz],
            Model::Grillage => &[Component::Z, Component::Rx, Component::Ry],
            Model::Space => &[
                Component::X,
                Component::Y,
                Component::Z,
                Component::Rx,
                Component::Ry,
                Component::Rz,
            ],
        }
    }
    /// The load keys of the components: `fx, fy, mz`, `fz, mx, my` or all six.
    pub fn load_keys(self) -> &'static [&'static str] {
        match self {
            Model::Planar => &["fx", "fy", "mz"],
            Model::Grillage => &["fz", "mx", "my"],
            Model::Space => &["fx", "fy", "fz", "mx", "my", "mz"],
        }
    }
    /// The load key of component `c` of this kind (`fx`, ..., `mz`).
    pub fn load_key(self, c: Component) -> &'static str {
        let k = self.components().iter().position(|&x| x == c);
        k.map_or("", |k| self.load_keys()[k])
    }
    /// The load keys of the other kind (errors in a scene of this kind).
    pub(crate) fn foreign_load_keys(self) -> &'static [&'static str] {
        match self {
            Model::Planar => &["fz", "mx", "my"],
            Model::Grillage => &["fx", "fy", "mz"],
            Model::Space => &[],
        }
    }
    /// Appended to an unknown support component's message.
    pub(crate) fn support_hint(self) -> &'static str {
        match self {
            Model::Planar => "",
            Model::Grillage => " (model = \"grillage\")",
            Model::Space => " (model = \"space\")",
        }
    }
    /// The translations of a node in this kind: `x, y`; `z`; `x, y, z`.
    pub fn translations(self) -> &'static [Component] {
        match self {
            Model::Planar => &[Component::X, Component::Y],
            Model::Grillage => &[Component::Z],
            Model::Space => &[Component::X, Component::Y, Component::Z],
        }
    }
    /// The length of a node's translation, from its per-node array (by
    /// [`Component::index`]).
    pub fn translation_size(self, v: &[f64; 6]) -> f64 {
        match self {
            Model::Planar => v[0].hypot(v[1]),
            Model::Grillage => v[3].abs(),
            Model::Space => (v[0] * v[0] + v[1] * v[1] + v[3] * v[3]).sqrt(),
        }
    }
    /// Member forces per element: 3 (two end moments and the second force),
    /// 6 in space (two moments about `e3`, the torque, two about `e2`, the
    /// axial force), in the row order of [`ElementRow::row`].
    pub(crate) fn forces_per_element(self) -> usize {
        match self {
            Model::Planar | Model::Grillage => 3,
            Model::Space => 6,
        }
    }
    /// The member force of row `r` of `A` (see [`ElementRow::row`]), for `ne` elements.
    pub(crate) fn force_of_row(self, r: usize, ne: usize) -> MemberForce {
        if r < 2 * ne {
            MemberForce::Moment(r)
        } else if r < 3 * ne {
            self.second_force(r - 2 * ne)
        } else if r < 5 * ne {
            MemberForce::Moment2(r - 3 * ne)
        } else {
            MemberForce::Axial(r - 5 * ne)
        }
    }
    /// The second member force of element `e`: its axial force or its torque
    /// (space: the torque; the axial force is the third).
    pub fn second_force(self, e: usize) -> MemberForce {
        match self {
            Model::Planar => MemberForce::Axial(e),
            Model::Grillage | Model::Space => MemberForce::Torque(e),
        }
    }
    /// How the second force's strength is given.
    pub(crate) fn second_force_rule(self) -> SecondForceRule {
        match self {
            Model::Space => SecondForceRule {
                key: "plastic_torque",
                curve: Curve::BendingTorsion,
                required: true,
                required_message: "a member of a space scene needs plastic_torque (the plastic torque Tp of the pipe)",
                foreign_key: "",
                foreign_message: "",
                facets_message: "",
                third_key: Some("plastic_axial"),
            },
            Model::Grillage => SecondForceRule {
                key: "plastic_torque",
                curve: Curve::BendingTorsion,
                required: true,
                required_message: "a grillage member needs plastic_torque (the plastic torque Tp)",
                foreign_key: "plastic_axial",
                foreign_message: "not a key of a grillage member (out of plane a member carries bending and torsion: plastic_torque)",
                facets_message: "",
                third_key: None,
            },
            Model::Planar => SecondForceRule {
                key: "plastic_axial",
                curve: Curve::BendingAxial,
                required: false,
                required_message: "",
                foreign_key: "plastic_torque",
                foreign_message: "a key of grillage members only (model = \"grillage\")",
                facets_message: "facets sets the bending-axial polygon of a planar member: give plastic_axial too",
                third_key: None,
            },
        }
    }
    /// True if an element's second force has no yield mode and its dual
    /// deformation is held at zero (inextensible planar members).
    pub(crate) fn second_force_is_rigid(self, el: &Element) -> bool {
        self == Model::Planar && el.interaction.is_none()
    }
    /// The rows of `A` of element `e` (of `ne`) whose deformation is held at
    /// zero (no yield mode): the elongation of an inextensible member.
    pub(crate) fn rigid_rows(self, el: &Element, e: usize, ne: usize) -> Option<usize> {
        match self {
            // inextensible unless the axial force enters the polytope
            Model::Space => el
                .interaction
                .is_none_or(|it| it.axial.is_none())
                .then(|| ElementRow::Third.row(e, ne)),
            _ => self
                .second_force_is_rigid(el)
                .then(|| ElementRow::Second.row(e, ne)),
        }
    }
    /// The entries of element `el`'s rows of `A`, given the coordinate
    /// indices `ia`, `ib` of its end nodes (by [`Component::index`]; `None`
    /// where supported or not a component of the kind). Calls `add(row,
    /// coordinate, value)` for each term, in a fixed order (the sums are
    /// bit-identical from run to run).
    pub(crate) fn element_rows(
        self,
        el: &Element,
        ia: [Option<usize>; 6],
        ib: [Option<usize>; 6],
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
                let psi = [(ia[3], 1.0 / h), (ib[3], -1.0 / h)];
                // from section: -(theta_a - psi)
                add(rf, ia[4], s);
                add(rf, ia[5], -c);
                for &(j, v) in &psi {
                    add(rf, j, v);
                }
                // to section: theta_b - psi
                add(rt, ib[4], -s);
                add(rt, ib[5], c);
                for &(j, v) in &psi {
                    add(rt, j, -v);
                }
                // twist phi_b - phi_a
                add(rn, ia[4], -c);
                add(rn, ia[5], -s);
                add(rn, ib[4], c);
                add(rn, ib[5], s);
            }
            Model::Space => {
                // global slots of the translations and rotations
                const T: [usize; 3] = [0, 1, 3];
                const R: [usize; 3] = [4, 5, 2];
                let [e1, e2, e3] = el.axes;
                let (f2, t2, th) = (ElementRow::From2, ElementRow::To2, ElementRow::Third);
                // about e3 (the planar rows when e3 = z):
                // from: -(e3 . th_a - e2 . du / h), to: e3 . th_b - e2 . du / h
                for g in 0..3 {
                    add(rf, ia[R[g]], -e3[g]);
                }
                for g in 0..3 {
                    add(rf, ia[T[g]], -e2[g] / h);
                    add(rf, ib[T[g]], e2[g] / h);
                }
                for g in 0..3 {
                    add(rt, ib[R[g]], e3[g]);
                }
                for g in 0..3 {
                    add(rt, ia[T[g]], e2[g] / h);
                    add(rt, ib[T[g]], -e2[g] / h);
                }
                // twist e1 . (th_b - th_a)
                for g in 0..3 {
                    add(rn, ia[R[g]], -e1[g]);
                    add(rn, ib[R[g]], e1[g]);
                }
                // about e2 (the grillage rows when e3 = z):
                // from: -(e2 . th_a + e3 . du / h), to: e2 . th_b + e3 . du / h
                for g in 0..3 {
                    add(f2, ia[R[g]], -e2[g]);
                }
                for g in 0..3 {
                    add(f2, ia[T[g]], e3[g] / h);
                    add(f2, ib[T[g]], -e3[g] / h);
                }
                for g in 0..3 {
                    add(t2, ib[R[g]], e2[g]);
                }
                for g in 0..3 {
                    add(t2, ia[T[g]], -e3[g] / h);
                    add(t2, ib[T[g]], e3[g] / h);
                }
                // elongation e1 . (u_b - u_a)
                for g in 0..3 {
                    add(th, ia[T[g]], -e1[g]);
                    add(th, ib[T[g]], e1[g]);
                }
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
                !n.fixed[4]
                    && !n.fixed[5]
                    && n.load[4] == 0.0
                    && n.load[5] == 0.0
                    && collinear
                    && ea.plastic_moment == eb.plastic_moment
                    && ea.interaction == eb.interaction
            }
            // Space: collinear elements of the same strength and the same
            // axes (then all three moments carry over in the same axes) at a
            // node whose three rotations are free and unloaded.
            Model::Space => {
                // an axial yield force is never tied (as planar: the two
                // elements' axial forces differ by the node's inertia)
                let same = ea.axes == eb.axes && ea.interaction.is_none_or(|it| it.axial.is_none());
                [2, 4, 5].iter().all(|&k| !n.fixed[k] && n.load[k] == 0.0)
                    && same
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
            Model::Space => (&[][..], ""),
        }
    }
}
