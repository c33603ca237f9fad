//! System (9) of a frame: generalised coordinates, member forces, critical
//! sections and yield modes, the blocks `M_q`, `A`, `T N`, `X*`, `a_o`, and the
//! mixed PLCP that plcp solves.
//!
//! **Planar members.** Kinematics of an element from node `a` to node `b`
//! (length `h`, direction `(c, s)`), with nodal coordinates `(u_x, u_y, theta)`:
//!
//! ```text
//! chord rotation      psi = (-s (u_xb - u_xa) + c (u_yb - u_ya)) / h
//! section at a:       -(theta_a - psi)      dual to the bending moment m_a
//! section at b:         theta_b - psi       dual to the bending moment m_b
//! elongation          c (u_xb - u_xa) + s (u_yb - u_ya)   dual to the axial force N
//! ```
//!
//! Bending moments are sagging-positive in the element's own axes (local y is
//! the member direction turned 90 degrees counter-clockwise), so `T = I` and a
//! section's positive yield mode is a sagging hinge (`m = +Mp`), its negative
//! mode a hogging one (`m = -Mp`): `N = [1, -1]` per section.
//!
//! **Grillage members** (`model = "grillage"`): the frame lies in the x-y
//! plane, nodal coordinates `(w, r_x, r_y)` (translation along z, right-handed
//! rotations about x and y). In the element's axes (`x'` along the member,
//! `y'` the member direction turned 90 degrees counter-clockwise, `z` common)
//! a nodal rotation has the twist `phi = c r_x + s r_y` (about `x'`) and the
//! bending rotation `theta = -s r_x + c r_y` (about `y'`; a positive `theta`
//! tilts the axis down, so the chord's is `psi = -(w_b - w_a) / h`):
//!
//! ```text
//! section at a:       -(theta_a - psi)      dual to the bending moment m_a
//! section at b:         theta_b - psi       dual to the bending moment m_b
//! twist               phi_b - phi_a         dual to the torque T (constant along the element)
//! ```
//!
//! **Yield modes.** A section of a member without interaction has the two
//! modes `+-m <= Mp`. A section of a member with an interaction (every
//! grillage member; a planar member with `plastic_axial`) has one mode per
//! facet of the inscribed polygon of [`crate::yield_surface`] in the plane
//! `(m / Mp, F / Fp)`, `F` the element's torque or axial force. `F` is one
//! member force shared by the element's two end sections, and it enters the
//! yield condition of both: in `T N` its row carries the facet normals' `F`
//! components of the modes of both sections. By the flow rule the element's
//! twist (or elongation) is the sum of the plastic twists of its two end
//! hinges, each following the normal of the facet it flows on; a twist with
//! no hinge at either end is impossible (the element is rigid between its
//! critical sections).
//!
//! **Axial rigidity.** Planar members without `plastic_axial` are
//! inextensible. The axial force `N` of every element is kept as a member
//! force (a free variable of the PLCP) whose dual deformation, the elongation
//! rate, must vanish: its row of `A q = T N x*` has no yield mode. Nothing is
//! eliminated, so the kinematics stay exact for any geometry.
//!
//! **Tied sections.** Where two sections meet at a node with a free,
//! massless, unloaded rotation and their forces are equal by node equilibrium
//! (planar members without interaction; collinear grillage elements of equal
//! strength), only the weaker one carries yield modes (see `rigid_sections`):
//! one physical hinge, one set of yield modes.
//!
//! **What is left out.** By construction, the other model's components: a
//! planar scene has no out-of-plane coordinates and forces, a grillage none in
//! plane. Then supported coordinates, and every part of the system that
//! carries no load and is decoupled from the loaded part (found as the
//! connected components of the sparsity graph of system (9)): its solution is
//! zero for every `Lambda`. The straight, transversely loaded planar
//! cantilever loses its axial motion this way and becomes statically
//! determinate. [`System::assemble_full`] keeps everything but the supported
//! coordinates (for checks).

mod full;
mod mechanism;
mod modes;
mod plcp_form;
mod reduce;
mod sparse_block;
#[cfg(test)]
mod tests;

pub use mechanism::massless_mechanism;
pub use sparse_block::SparseBlock;

use crate::model::{Component, Model};

/// Which end of its element a critical section sits at.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum End {
    /// The element's start node.
    From,
    /// The element's end node.
    To,
}

impl End {
    /// `"from"` or `"to"`.
    pub fn as_str(self) -> &'static str {
        match self {
            End::From => "from",
            End::To => "to",
        }
    }
}

/// The sign of a yield mode: sagging (`m = +Mp`) or hogging (`m = -Mp`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sign {
    /// Sagging, `m = +Mp`.
    Positive,
    /// Hogging, `m = -Mp`.
    Negative,
}

impl Sign {
    /// `"positive"` or `"negative"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Sign::Positive => "positive",
            Sign::Negative => "negative",
        }
    }
}

/// A critical section: one end of one element.
#[derive(Clone, Debug, PartialEq)]
pub struct CriticalSection {
    /// The element.
    pub element: usize,
    /// The member the element belongs to.
    pub member: usize,
    /// The node the section sits at.
    pub node: usize,
    /// Which end of the element.
    pub end: End,
    /// Plastic moment.
    pub plastic_moment: f64,
}

/// A yield mode: one yield plane of one critical section.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct YieldMode {
    /// Index into [`System::sections`].
    pub section: usize,
    /// Sagging or hogging (for a facet of a polygon: the sign of its normal's
    /// bending component, never zero).
    pub sign: Sign,
    /// For a section with an interaction: the facet of its polygon, with the
    /// unit normal in the normalised plane `(m / Mp, F / Fp)`; `None` for the
    /// bending-only modes `+-m <= Mp`.
    pub facet: Option<FacetMode>,
}

/// The facet of a yield polygon (or polyhedron) a mode stands for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FacetMode {
    /// Index of the facet (counter-clockwise from the first quadrant).
    pub index: usize,
    /// Number of facets of the polygon (polyhedron).
    pub count: usize,
    /// Unit normal `(n_m, n_F)`; for a facet of the space polyhedron the
    /// signed bending part `(+-|(n_m2, n_m3)|, n_t)`.
    pub normal: [f64; 2],
    /// A facet of the space polyhedron ([`crate::yield_surface::Polyhedron`]):
    /// its unit normal `(n_m2, n_m3, n_t)` in `(M2/Mp, M3/Mp, T/Tp)`.
    pub normal3: Option<[f64; 3]>,
    /// A facet of the bending-torsion-axial polytope
    /// ([`crate::yield_surface::Polytope`]): the normal's component along
    /// `N/Np` (the other three are `normal3`).
    pub axial: Option<f64>,
}

/// A generalised coordinate: one unsupported component of one node.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coordinate {
    /// Node index.
    pub node: usize,
    /// Component.
    pub component: Component,
}

/// A member force: the bending moment at a critical section, or an element's
/// axial force or torque.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MemberForce {
    /// Bending moment (sagging positive) at a section (index into [`System::sections`]).
    Moment(usize),
    /// Axial force (tension positive) of a planar element: the reaction of
    /// inextensibility, or a yield force where the member asks for the interaction.
    Axial(usize),
    /// Torque of a grillage or space element (right-handed about the element's axis).
    Torque(usize),
    /// The bending moment about the element's `e2` axis at a section of a
    /// space element (index into [`System::sections`]); [`MemberForce::Moment`]
    /// is then the one about `e3`.
    Moment2(usize),
}

/// Sizes of system (9).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Sizes {
    /// Generalised coordinates `beta`.
    pub coordinates: usize,
    /// Member forces `s`.
    pub forces: usize,
    /// Yield modes `p` (the complementary pairs).
    pub modes: usize,
}

impl Sizes {
    /// Free variables of the mixed PLCP: `beta + s`.
    pub fn free(&self) -> usize {
        self.coordinates + self.forces
    }
}

/// What was left out of system (9), and why.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LeftOut {
    /// Supported coordinates (node, component).
    pub supported: Vec<(usize, Component)>,
    /// Loads on supported coordinates (taken by the supports).
    pub loads_on_supports: Vec<(usize, Component)>,
    /// Coordinates of unloaded parts decoupled from the loaded part.
    pub decoupled_coordinates: Vec<(usize, Component)>,
    /// Member forces of those parts.
    pub decoupled_forces: Vec<MemberForce>,
    /// Yield modes of those parts.
    pub decoupled_modes: usize,
    /// Sections made rigid because they are tied to a weaker (or equal) one at
    /// the same node: the pair's hinge is carried by the other section alone.
    pub tied_sections: Vec<usize>,
    /// Nothing but supports was left out ([`System::assemble_full`]).
    pub full_assembly: bool,
}

/// System (9) of a frame, with what was left out.
#[derive(Clone, Debug)]
pub struct System {
    /// Planar or grillage.
    pub model: Model,
    /// Kept generalised coordinates (`beta`).
    pub coordinates: Vec<Coordinate>,
    /// Kept member forces (`s`).
    pub forces: Vec<MemberForce>,
    /// Kept yield modes (`p`).
    pub modes: Vec<YieldMode>,
    /// All critical sections of the frame (two per element), kept or not.
    pub sections: Vec<CriticalSection>,
    /// Tied pairs `[carrier, rigid]`: the rigid section's yield modes were left
    /// out, the carrier's hinge is the pair's (one physical hinge).
    pub ties: Vec<[usize; 2]>,
    /// Diagonal of the lumped mass matrix `M_q` (`beta`).
    pub mass: Vec<f64>,
    /// Compatibility `A` (`s x beta`): member deformations from coordinates
    /// (sparse: a few entries per row, so the system stays linear in the
    /// elements; `a[(r, j)]` reads an entry).
    pub a: SparseBlock,
    /// `T N` (`s x p`): member deformations from the plastic multipliers (sparse).
    pub tn: SparseBlock,
    /// Plastic capacities `X*` (`p`).
    pub capacities: Vec<f64>,
    /// Load pattern `a_o` (`beta`).
    pub load: Vec<f64>,
    /// Sizes before anything was left out.
    pub full: Sizes,
    /// What was left out.
    pub left_out: LeftOut,
    /// Rank of `A`.
    pub rank_a: usize,
}

impl System {
    /// Sizes of the system as solved.
    pub fn sizes(&self) -> Sizes {
        Sizes {
            coordinates: self.coordinates.len(),
            forces: self.forces.len(),
            modes: self.modes.len(),
        }
    }

    /// Statically determinate: `A` square and invertible, so the member forces
    /// follow from equilibrium alone and the free block of the PLCP is nonsingular.
    pub fn is_determinate(&self) -> bool {
        self.a.nrows() == self.a.ncols() && self.rank_a == self.a.ncols()
    }

    /// Degree of static indeterminacy `s - rank(A)` (independent self-stress states).
    pub fn indeterminacy(&self) -> usize {
        self.forces.len() - self.rank_a
    }

    /// Degrees of freedom of rigid (hinge-free) motion `beta - rank(A)`: nonzero
    /// for a frame that is a mechanism before any hinge forms.
    pub fn rigid_body_freedom(&self) -> usize {
        self.coordinates.len() - self.rank_a
    }

    /// Index of the kept coordinate `(node, component)`, if kept.
    pub fn coordinate_index(&self, node: usize, component: Component) -> Option<usize> {
        self.coordinates
            .iter()
            .position(|c| c.node == node && c.component == component)
    }

    /// Index of the kept member force holding the moment of `section`, if kept.
    pub fn moment_index(&self, section: usize) -> Option<usize> {
        self.forces
            .iter()
            .position(|f| *f == MemberForce::Moment(section))
    }

    /// [`Self::moment_index`] of every section, in one pass over the forces
    /// (each section's first moment, as `position` finds it): reading the
    /// hinge groups asked it of every section, `sections x forces`
    /// comparisons (at 10^4 elements 20000 x 20000).
    pub fn moment_indices(&self) -> Vec<Option<usize>> {
        let mut by_section: Vec<Option<usize>> = vec![None; self.sections.len()];
        for (k, f) in self.forces.iter().enumerate() {
            if let MemberForce::Moment(s) = *f {
                if let Some(slot) = by_section.get_mut(s) {
                    slot.get_or_insert(k);
                }
            }
        }
        by_section
    }

    /// Index of the kept member force holding the bending moment about `e2`
    /// of `section` (space frames), if kept.
    pub fn moment2_index(&self, section: usize) -> Option<usize> {
        self.forces
            .iter()
            .position(|f| *f == MemberForce::Moment2(section))
    }

    /// Index of the kept member force holding the axial force or torque of
    /// `section`'s element, if kept (space: the torque).
    pub fn second_force_index(&self, section: usize) -> Option<usize> {
        let e = self.sections[section].element;
        self.forces.iter().position(|f| match self.model {
            Model::Space => *f == MemberForce::Torque(e),
            _ => *f == MemberForce::Axial(e) || *f == MemberForce::Torque(e),
        })
    }

    /// [`Self::second_force_index`] of every section, in one pass over the
    /// forces (each element's first matching force, as `position` finds
    /// it): a report reading every section costs `O(forces + sections)`
    /// rather than their product (at 1000 elements the JSON spent 0.58 G
    /// instructions in the searches).
    pub fn second_force_indices(&self) -> Vec<Option<usize>> {
        let elements = self.sections.iter().map(|s| s.element + 1).max();
        let mut by_element: Vec<Option<usize>> = vec![None; elements.unwrap_or(0)];
        for (k, f) in self.forces.iter().enumerate() {
            let e = match (self.model, f) {
                (Model::Space, MemberForce::Torque(e)) => *e,
                (Model::Space, _) => continue,
                (_, MemberForce::Axial(e) | MemberForce::Torque(e)) => *e,
                _ => continue,
            };
            if let Some(slot) = by_element.get_mut(e) {
                slot.get_or_insert(k);
            }
        }
        self.sections
            .iter()
            .map(|s| by_element[s.element])
            .collect()
    }
}
