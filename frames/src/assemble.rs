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

use crate::kernel::null_space;
use crate::kind::ElementRow;
use crate::model::{Component, Frame, Model};
use crate::yield_surface::{Polygon, Polyhedron, Polytope};
use faer::{Col, Mat};
use plcp::{Plcp, PlcpError, Scalar};

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

/// A sparse block of system (9) (`A` or `T N`), stored by columns with sorted
/// row indices and no zeros (so `==` compares the matrices). `A` and `T N`
/// hold a few entries per row: stored densely they were quadratic in the
/// elements (64 MB at 1000 elements, 6.4 GB at 10^4). Read an entry with
/// `block[(i, j)]` (zero if not stored), a column with [`SparseBlock::col`].
///
/// ```
/// let src = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cantilever.toml")).unwrap();
/// let scene = frames::Scene::from_toml(&src, "cantilever.toml").unwrap();
/// let sys = frames::System::assemble(&scene.frame);
/// let dense = sys.a.to_dense();
/// assert_eq!((sys.a.nrows(), sys.a.ncols()), (dense.nrows(), dense.ncols()));
/// assert_eq!(sys.a[(0, 0)], dense[(0, 0)]);
/// assert!(sys.a.nnz() < sys.a.nrows() * sys.a.ncols());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct SparseBlock(plcp::matrix::Csc<f64>);

static ZERO: f64 = 0.0;

impl SparseBlock {
    /// From `(row, column, value)` entries (zeros dropped; a position given
    /// twice keeps its last value, as writing them into a dense block would).
    fn from_entries(nrows: usize, ncols: usize, entries: Vec<(usize, usize, f64)>) -> Self {
        let mut last: std::collections::HashMap<(usize, usize), f64> =
            std::collections::HashMap::with_capacity(entries.len());
        for (i, j, v) in entries {
            last.insert((i, j), v);
        }
        let triplets: Vec<(usize, usize, f64)> = last
            .into_iter()
            .filter(|&(_, v)| v != 0.0)
            .map(|((i, j), v)| (i, j, v))
            .collect();
        // assembled from finite geometry and strengths: an entry that is not
        // finite (or out of range) is a bug of the assembly
        Self(
            plcp::matrix::Csc::try_from_triplets(nrows, ncols, &triplets)
                .expect("the assembled blocks of system (9) are finite and in range"),
        )
    }
    /// Number of rows.
    pub fn nrows(&self) -> usize {
        self.0.nrows()
    }
    /// Number of columns.
    pub fn ncols(&self) -> usize {
        self.0.ncols()
    }
    /// Number of stored (nonzero) entries.
    pub fn nnz(&self) -> usize {
        self.0.nnz()
    }
    /// Row indices (ascending) and values of column `j`.
    pub fn col(&self, j: usize) -> (&[usize], &[f64]) {
        self.0.col(j)
    }
    /// The compressed sparse column form.
    pub fn csc(&self) -> &plcp::matrix::Csc<f64> {
        &self.0
    }
    /// The dense matrix (for small systems and checks).
    pub fn to_dense(&self) -> Mat<f64> {
        self.0.to_dense()
    }
}

impl std::ops::Index<(usize, usize)> for SparseBlock {
    type Output = f64;
    fn index(&self, (i, j): (usize, usize)) -> &f64 {
        assert!(
            i < self.nrows() && j < self.ncols(),
            "index ({i}, {j}) out of a {} x {} block",
            self.nrows(),
            self.ncols()
        );
        let (col_ptr, _, vals) = self.0.parts();
        let (col_rows, _) = self.0.col(j);
        match col_rows.binary_search(&i) {
            Ok(k) => &vals[col_ptr[j] + k],
            Err(_) => &ZERO,
        }
    }
}

struct Dsu(Vec<usize>);
impl Dsu {
    fn find(&mut self, i: usize) -> usize {
        let mut r = i;
        while self.0[r] != r {
            r = self.0[r];
        }
        let mut i = i;
        while self.0[i] != r {
            let n = self.0[i];
            self.0[i] = r;
            i = n;
        }
        r
    }
    fn union(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        if a != b {
            self.0[a] = b;
        }
    }
}

/// One yield mode of the full system with its column of `T N` and its capacity.
struct ModeSpec {
    mode: YieldMode,
    column: Vec<(usize, f64)>,
    capacity: f64,
}

/// The full (nothing left out but supports) blocks of a frame.
struct Full {
    coords: Vec<Coordinate>,
    forces: Vec<MemberForce>,
    sections: Vec<CriticalSection>,
    modes: Vec<ModeSpec>,
    /// `A` by rows (forces), each row its few nonzero `(coordinate, value)`
    /// entries: the reader and the assembly stay linear in the element count.
    a: Vec<Vec<(usize, f64)>>,
    mass: Vec<f64>,
    load: Vec<f64>,
    supported: Vec<(usize, Component)>,
    loads_on_supports: Vec<(usize, Component)>,
}

fn full_blocks(frame: &Frame) -> Full {
    let model = frame.model;
    let comps = model.components();
    let mut coords = Vec::new();
    let mut index = vec![[None; 6]; frame.nodes.len()];
    let mut supported = Vec::new();
    let mut loads_on_supports = Vec::new();
    for (i, n) in frame.nodes.iter().enumerate() {
        for &c in comps {
            if n.fixed[c.index()] {
                supported.push((i, c));
                if n.load[c.index()] != 0.0 {
                    loads_on_supports.push((i, c));
                }
            } else {
                index[i][c.index()] = Some(coords.len());
                coords.push(Coordinate {
                    node: i,
                    component: c,
                });
            }
        }
    }
    let ne = frame.elements.len();
    let mut sections = Vec::with_capacity(2 * ne);
    for (e, el) in frame.elements.iter().enumerate() {
        for (end, node) in [(End::From, el.from), (End::To, el.to)] {
            sections.push(CriticalSection {
                element: e,
                member: el.member,
                node,
                end,
                plastic_moment: el.plastic_moment,
            });
        }
    }
    // forces: the moments of all sections, then the axial force or torque of
    // each element (space: then the moments about e2, the axial forces)
    let nr = model.forces_per_element() * ne;
    let forces: Vec<MemberForce> = (0..nr).map(|r| model.force_of_row(r, ne)).collect();
    let mut a: Vec<Vec<(usize, f64)>> = vec![Vec::new(); nr];
    for (e, el) in frame.elements.iter().enumerate() {
        let ia = index[el.from];
        let ib = index[el.to];
        let mut add = |row: usize, idx: Option<usize>, v: f64| {
            if let Some(j) = idx {
                if v != 0.0 {
                    let entries = &mut a[row];
                    match entries.iter_mut().find(|(k, _)| *k == j) {
                        Some((_, x)) => *x += v,
                        None => entries.push((j, v)),
                    }
                }
            }
        };
        model.element_rows(el, ia, ib, &mut |row, j, v| add(row.row(e, ne), j, v));
    }
    // entries that cancelled (an element's two ends on one coordinate) are zeros
    for row in &mut a {
        row.retain(|&(_, v)| v != 0.0);
    }
    let mut modes = Vec::new();
    for (k, sec) in sections.iter().enumerate() {
        let el = &frame.elements[sec.element];
        let mp = sec.plastic_moment;
        match el.interaction {
            Some(it) if model == Model::Space && it.axial.is_some() => {
                let np = it.axial.expect("matched");
                let polytope =
                    Polytope::new(it.facets).expect("the scene checked the number of facets");
                let count = polytope.facets().len();
                for (i, f) in polytope.facets().iter().enumerate() {
                    // rounding of an exactly zero component is dropped
                    let [n2, n3, nt, nn] = f.normal.map(|v| if v.abs() <= 1e-14 { 0.0 } else { v });
                    let mut column = Vec::with_capacity(4);
                    for (row, v) in [
                        (k, n3),
                        (
                            ElementRow::Second.row(sec.element, ne),
                            nt * mp / it.capacity,
                        ),
                        (3 * ne + k, n2),
                        (ElementRow::Third.row(sec.element, ne), nn * mp / np),
                    ] {
                        if v != 0.0 {
                            column.push((row, v));
                        }
                    }
                    let lead = if n3 != 0.0 { n3 } else { n2 };
                    let bending = n2.hypot(n3);
                    modes.push(ModeSpec {
                        mode: YieldMode {
                            section: k,
                            sign: if lead >= 0.0 {
                                Sign::Positive
                            } else {
                                Sign::Negative
                            },
                            facet: Some(FacetMode {
                                index: i,
                                count,
                                normal: [if lead >= 0.0 { bending } else { -bending }, nt],
                                normal3: Some([n2, n3, nt]),
                                axial: Some(nn),
                            }),
                        },
                        column,
                        capacity: f.offset * mp,
                    });
                }
            }
            Some(it) if model == Model::Space => {
                let polyhedron =
                    Polyhedron::new(it.facets).expect("the scene checked the number of facets");
                for (i, f) in polyhedron.facets().iter().enumerate() {
                    // rounding of an exactly zero component is dropped: the
                    // planes move by 1e-15 at most, the pattern stays exact
                    let [n2, n3, nt] = f.normal.map(|v| if v.abs() <= 1e-14 { 0.0 } else { v });
                    let mut column = Vec::with_capacity(3);
                    for (row, v) in [
                        (k, n3),
                        (
                            ElementRow::Second.row(sec.element, ne),
                            nt * mp / it.capacity,
                        ),
                        (3 * ne + k, n2),
                    ] {
                        if v != 0.0 {
                            column.push((row, v));
                        }
                    }
                    let lead = if n3 != 0.0 { n3 } else { n2 };
                    let bending = n2.hypot(n3);
                    modes.push(ModeSpec {
                        mode: YieldMode {
                            section: k,
                            sign: if lead >= 0.0 {
                                Sign::Positive
                            } else {
                                Sign::Negative
                            },
                            facet: Some(FacetMode {
                                index: i,
                                count: it.facets * it.facets / 2,
                                normal: [if lead >= 0.0 { bending } else { -bending }, nt],
                                normal3: Some([n2, n3, nt]),
                                axial: None,
                            }),
                        },
                        column,
                        capacity: f.offset * mp,
                    });
                }
            }
            None => {
                for (sign, v) in [(Sign::Positive, 1.0), (Sign::Negative, -1.0)] {
                    modes.push(ModeSpec {
                        mode: YieldMode {
                            section: k,
                            sign,
                            facet: None,
                        },
                        column: vec![(k, v)],
                        capacity: mp,
                    });
                }
            }
            Some(it) => {
                let polygon = Polygon::new(it.curve, it.facets)
                    .expect("the scene checked the number of facets");
                for (i, f) in polygon.facets().iter().enumerate() {
                    let [nm, nf] = f.normal;
                    let mut column = vec![(k, nm)];
                    if nf != 0.0 {
                        column.push((2 * ne + sec.element, nf * mp / it.capacity));
                    }
                    modes.push(ModeSpec {
                        mode: YieldMode {
                            section: k,
                            sign: if nm >= 0.0 {
                                Sign::Positive
                            } else {
                                Sign::Negative
                            },
                            facet: Some(FacetMode {
                                index: i,
                                count: it.facets,
                                normal: f.normal,
                                normal3: None,
                                axial: None,
                            }),
                        },
                        column,
                        capacity: f.offset * mp,
                    });
                }
            }
        }
    }
    let mass = coords
        .iter()
        .map(|co| {
            let n = &frame.nodes[co.node];
            if co.component.is_rotation() {
                n.inertia
            } else {
                n.mass
            }
        })
        .collect();
    let load = coords
        .iter()
        .map(|co| frame.nodes[co.node].load[co.component.index()])
        .collect();
    Full {
        coords,
        forces,
        sections,
        modes,
        a,
        mass,
        load,
        supported,
        loads_on_supports,
    }
}

/// Tied pairs `[carrier, rigid]`: where exactly two sections meet at a node
/// whose rotation is free, without rotary inertia or applied moment, node
/// equilibrium makes their forces equal and only the split of the hinge
/// rotation between them would differ (fact 4 of the notes). The stronger
/// section of each pair (the later one on a tie) gets no yield modes: the
/// same mechanisms and the same dissipation, without duplicate yield rows,
/// non-unique node rotations and the degenerate pivots they cause.
///
/// Planar: sections without interaction (the moment is a scalar, equal across
/// any angle). An axial interaction is never tied (nodal masses and loads
/// change the axial force from one element to the next). Grillage: collinear
/// elements (then the bending moment and the torque both carry over) with the
/// same strength, at a node whose two rotations are free and unloaded.
fn rigid_sections(frame: &Frame, sections: &[CriticalSection]) -> Vec<[usize; 2]> {
    let mut at_node: Vec<Vec<usize>> = vec![Vec::new(); frame.nodes.len()];
    for (k, s) in sections.iter().enumerate() {
        at_node[s.node].push(k);
    }
    let mut ties = Vec::new();
    for (i, secs) in at_node.iter().enumerate() {
        let n = &frame.nodes[i];
        if secs.len() != 2 || n.inertia != 0.0 {
            continue;
        }
        let (a, b) = (secs[0], secs[1]);
        let (ea, eb) = (
            &frame.elements[sections[a].element],
            &frame.elements[sections[b].element],
        );
        let tied = frame.model.tied(n, ea, eb);
        if tied {
            let drop = if sections[b].plastic_moment >= sections[a].plastic_moment {
                b
            } else {
                a
            };
            let keep = if drop == b { a } else { b };
            ties.push([keep, drop]);
        }
    }
    ties
}

/// A coordinate that the load can accelerate without limit: it moves in a
/// mechanism that carries no mass (rotations of a lumped model carry none
/// unless `j` is given). `None` if there is none.
pub fn massless_mechanism(frame: &Frame) -> Option<(usize, Component)> {
    let f = full_blocks(frame);
    let massless: Vec<usize> = (0..f.coords.len()).filter(|&j| f.mass[j] == 0.0).collect();
    if massless.is_empty() {
        return None;
    }
    let scale = massless.iter().fold(0.0f64, |s, &j| s.max(f.load[j].abs()));
    if scale == 0.0 {
        return None;
    }
    // A massless motion moves only massless coordinates; every deformation with
    // a yield mode is free at the hinges, so only the rows without one (the
    // inextensibility of planar members) restrict it: the null space of `C`,
    // those rows on the massless columns. Columns of `C` that are zero (the
    // rotations of a planar frame: inextensibility involves translations only)
    // are unit null vectors; the rest is the null space of the small block `C'`
    // of the rows and columns that touch, found densely.
    let ne = frame.elements.len();
    let rigid_rows: Vec<usize> = (0..ne)
        .filter_map(|e| frame.model.rigid_rows(&frame.elements[e], e, ne))
        .collect();
    let mut position = vec![None; f.coords.len()];
    for (k, &j) in massless.iter().enumerate() {
        position[j] = Some(k);
    }
    let mut touched_col = vec![None; massless.len()];
    let mut touched: Vec<usize> = Vec::new();
    let mut rows: Vec<usize> = Vec::new();
    for &r in &rigid_rows {
        let mut any = false;
        for &(j, _) in &f.a[r] {
            if let Some(k) = position[j] {
                any = true;
                if touched_col[k].is_none() {
                    touched_col[k] = Some(touched.len());
                    touched.push(k);
                }
            }
        }
        if any {
            rows.push(r);
        }
    }
    let tol = 1e-9 * scale * (massless.len() as f64);
    // a unit null vector: the work is the load on its coordinate
    if let Some(k) =
        (0..massless.len()).find(|&k| touched_col[k].is_none() && f.load[massless[k]].abs() > tol)
    {
        let co = f.coords[massless[k]];
        return Some((co.node, co.component));
    }
    if touched.is_empty() {
        return None;
    }
    let mut c = Mat::<f64>::zeros(rows.len(), touched.len());
    for (i, &r) in rows.iter().enumerate() {
        for &(j, v) in &f.a[r] {
            if let Some(col) = position[j].and_then(|k| touched_col[k]) {
                c[(i, col)] = v;
            }
        }
    }
    let (_, basis) = null_space(&c);
    for v in &basis {
        let vn = v.iter().fold(0.0f64, |s, x| s.max(x.abs()));
        let load = |t: usize| f.load[massless[touched[t]]];
        let work: f64 = v.iter().enumerate().map(|(t, x)| x * load(t)).sum();
        if work.abs() > tol * vn {
            // point at a loaded coordinate that moves in this mechanism
            let t = (0..touched.len())
                .filter(|&t| v[t] != 0.0 && load(t) != 0.0)
                .max_by(|&x, &y| (v[x] * load(x)).abs().total_cmp(&(v[y] * load(y)).abs()))?;
            let co = f.coords[massless[touched[t]]];
            return Some((co.node, co.component));
        }
    }
    None
}

/// The rank of a square `A` that its sparse LU shows nonsingular: full, when
/// the condition estimate says `A` is farther than the kernel's relative
/// tolerance `1e-10` from a singular matrix (`cond_1(A) * 1e-10 < 1`, a
/// backward-stable LU and Hager's estimator standing in for the size factor
/// the dense elimination of [`null_space`] adds for its own rounding); `None`
/// otherwise (then the dense elimination decides). `O(nnz(L + U))` instead of
/// `O(n^3)`: the cantilever's `A` has `cond_1 = 6 n^2` for `n` elements, and
/// at 1000 elements the dense elimination took 30 s.
fn full_rank_sparse(a: &SparseBlock) -> Option<usize> {
    let n = a.nrows();
    if n != a.ncols() || n == 0 {
        return None;
    }
    let cond = a.csc().lu_condition()?;
    (cond * 1e-10 < 1.0).then_some(n)
}

impl System {
    /// Assembles system (9) for a frame, leaving out supported coordinates and
    /// unloaded decoupled parts.
    ///
    /// ```
    /// let src = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cantilever.toml")).unwrap();
    /// let scene = frames::Scene::from_toml(&src, "cantilever.toml").unwrap();
    /// let sys = frames::System::assemble(&scene.frame);
    /// // four elements: y and rz at four free nodes, two end moments each;
    /// // the axial motion (x, N) is unloaded and decoupled, so it is left out
    /// assert_eq!((sys.full.coordinates, sys.full.forces, sys.full.modes), (12, 12, 16));
    /// // the tied sections at the three inner nodes keep one pair of yield modes each
    /// assert_eq!((sys.coordinates.len(), sys.forces.len(), sys.modes.len()), (8, 8, 10));
    /// assert!(sys.is_determinate());
    /// ```
    pub fn assemble(frame: &Frame) -> System {
        Self::assemble_with(frame, true)
    }

    /// System (9) with nothing left out but the supported coordinates: every
    /// coordinate, member force and yield mode of the model, no ties. The same
    /// path as [`System::assemble`] (a check of the leave-outs), larger.
    pub fn assemble_full(frame: &Frame) -> System {
        Self::assemble_with(frame, false)
    }

    fn assemble_with(frame: &Frame, leave_out: bool) -> System {
        let f = full_blocks(frame);
        let (nb, ns, np) = (f.coords.len(), f.forces.len(), f.modes.len());
        // variables: coordinates [0, nb), forces [nb, nb + ns), modes [nb + ns, ...)
        let mut dsu = Dsu((0..nb + ns + np).collect());
        for (r, row) in f.a.iter().enumerate() {
            for &(j, _) in row {
                dsu.union(nb + r, j);
            }
        }
        for (k, m) in f.modes.iter().enumerate() {
            for &(r, _) in &m.column {
                dsu.union(nb + r, nb + ns + k);
            }
        }
        let mut loaded = vec![false; nb + ns + np];
        for j in 0..nb {
            if f.load[j] != 0.0 {
                let r = dsu.find(j);
                loaded[r] = true;
            }
        }
        let keep: Vec<bool> = (0..nb + ns + np)
            .map(|v| !leave_out || loaded[dsu.find(v)])
            .collect();
        let kc: Vec<usize> = (0..nb).filter(|&j| keep[j]).collect();
        let kf: Vec<usize> = (0..ns).filter(|&r| keep[nb + r]).collect();
        let ties: Vec<[usize; 2]> = if leave_out {
            rigid_sections(frame, &f.sections)
                .into_iter()
                .filter(|t| keep[nb + t[0]] && keep[nb + t[1]])
                .collect()
        } else {
            Vec::new()
        };
        let mut rigid = vec![false; f.sections.len()];
        for t in &ties {
            rigid[t[1]] = true;
        }
        let km: Vec<usize> = (0..np)
            .filter(|&k| keep[nb + ns + k] && !rigid[f.modes[k].mode.section])
            .collect();
        let mut left_out = LeftOut {
            supported: f.supported.clone(),
            loads_on_supports: f.loads_on_supports.clone(),
            full_assembly: !leave_out,
            ..LeftOut::default()
        };
        for (co, _) in f.coords.iter().zip(&keep).filter(|(_, k)| !**k) {
            left_out.decoupled_coordinates.push((co.node, co.component));
        }
        for r in 0..ns {
            if !keep[nb + r] {
                left_out.decoupled_forces.push(f.forces[r]);
            }
        }
        left_out.tied_sections = ties.iter().map(|t| t[1]).collect();
        let tied_modes = (0..np)
            .filter(|&k| keep[nb + ns + k] && rigid[f.modes[k].mode.section])
            .count();
        left_out.decoupled_modes = np - km.len() - tied_modes;
        let mut col_of = vec![None; nb];
        for (k, &j) in kc.iter().enumerate() {
            col_of[j] = Some(k);
        }
        let mut entries = Vec::new();
        for (i, &r) in kf.iter().enumerate() {
            for &(j, v) in &f.a[r] {
                if let Some(k) = col_of[j] {
                    entries.push((i, k, v));
                }
            }
        }
        let a = SparseBlock::from_entries(kf.len(), kc.len(), entries);
        let mut row_of = vec![None; ns];
        for (i, &r) in kf.iter().enumerate() {
            row_of[r] = Some(i);
        }
        let mut entries = Vec::new();
        for (col, &k) in km.iter().enumerate() {
            for &(r, v) in &f.modes[k].column {
                if let Some(row) = row_of[r] {
                    entries.push((row, col, v));
                }
            }
        }
        let tn = SparseBlock::from_entries(kf.len(), km.len(), entries);
        let modes: Vec<YieldMode> = km.iter().map(|&k| f.modes[k].mode).collect();
        let capacities = km.iter().map(|&k| f.modes[k].capacity).collect();
        let rank_a = full_rank_sparse(&a).unwrap_or_else(|| null_space(&a.to_dense()).0);
        System {
            model: frame.model,
            coordinates: kc.iter().map(|&j| f.coords[j]).collect(),
            forces: kf.iter().map(|&r| f.forces[r]).collect(),
            modes,
            sections: f.sections,
            ties,
            mass: kc.iter().map(|&j| f.mass[j]).collect(),
            a,
            tn,
            capacities,
            load: kc.iter().map(|&j| f.load[j]).collect(),
            full: Sizes {
                coordinates: nb,
                forces: ns,
                modes: np,
            },
            left_out,
            rank_a,
        }
    }

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

    /// The mixed PLCP of system (9), in plcp's form
    /// `0 = (M x + q + L d)[..free]`, `w = (M x + q + L d)[free..]`, with
    /// `x = (q_dd, X, x*_dd)`, `w = y*` and `L = Lambda`:
    ///
    /// ```text
    /// M = [ -M_q  -A^T     0  ]   q = [ 0  ]   d = [ a_o ]
    ///     [ -A     0      T N ]       [ 0  ]       [ 0   ]
    ///     [  0   -(T N)^T  0  ]       [ X* ]       [ 0   ]
    /// ```
    pub fn blocks(&self) -> (Mat<f64>, Col<f64>, Col<f64>) {
        let (nb, ns, np) = (self.coordinates.len(), self.forces.len(), self.modes.len());
        let dim = nb + ns + np;
        let mut m = Mat::<f64>::zeros(dim, dim);
        for j in 0..nb {
            m[(j, j)] = -self.mass[j];
        }
        for j in 0..nb {
            let (rows, vals) = self.a.col(j);
            for (&r, &v) in rows.iter().zip(vals) {
                m[(j, nb + r)] = -v;
                m[(nb + r, j)] = -v;
            }
        }
        for k in 0..np {
            let (rows, vals) = self.tn.col(k);
            for (&r, &v) in rows.iter().zip(vals) {
                m[(nb + r, nb + ns + k)] = v;
                m[(nb + ns + k, nb + r)] = -v;
            }
        }
        let q = Col::from_fn(dim, |i| {
            if i >= nb + ns {
                self.capacities[i - nb - ns]
            } else {
                0.0
            }
        });
        let d = Col::from_fn(dim, |i| if i < nb { self.load[i] } else { 0.0 });
        (m, q, d)
    }

    /// The mixed PLCP in precision `T`, for `Lambda` from 0 to `lambda_max` (`None`: infinity).
    pub fn plcp<T: Scalar>(&self, lambda_max: Option<f64>) -> Result<Plcp<T>, PlcpError> {
        let (m, q, d) = self.blocks();
        let mt = Mat::from_fn(m.nrows(), m.ncols(), |i, j| T::from_f64(m[(i, j)]));
        let qt = Col::from_fn(q.nrows(), |i| T::from_f64(q[i]));
        let dt = Col::from_fn(d.nrows(), |i| T::from_f64(d[i]));
        Plcp::mixed(mt.as_ref(), qt.as_ref(), dt.as_ref(), self.sizes().free())?
            .with_range(T::zero(), lambda_max.map(T::from_f64))
    }

    /// The mixed PLCP of [`System::blocks`] with `M` in sparse form (the
    /// stored entries of the mass diagonal, `A` and `T N` only; `O(nnz)`,
    /// no dense `M`), for plcp's sparse basis.
    ///
    /// ```
    /// let src = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cantilever.toml")).unwrap();
    /// let scene = frames::Scene::from_toml(&src, "cantilever.toml").unwrap();
    /// let sys = frames::System::assemble(&scene.frame);
    /// let sparse = sys.plcp_sparse::<f64>(None).unwrap();
    /// assert!(sparse.is_sparse());
    /// assert_eq!(sparse.m(), sys.plcp::<f64>(None).unwrap().m());
    /// ```
    pub fn plcp_sparse<T: Scalar>(&self, lambda_max: Option<f64>) -> Result<Plcp<T>, PlcpError> {
        let (nb, ns, np) = (self.coordinates.len(), self.forces.len(), self.modes.len());
        let dim = nb + ns + np;
        let mut triplets: Vec<(usize, usize, T)> = Vec::new();
        for j in 0..nb {
            triplets.push((j, j, T::from_f64(-self.mass[j])));
        }
        // the stored entries only: O(nnz), in any order (the triplets are
        // sorted into columns, each position given once)
        for j in 0..nb {
            let (rows, vals) = self.a.col(j);
            for (&r, &v) in rows.iter().zip(vals) {
                triplets.push((j, nb + r, T::from_f64(-v)));
                triplets.push((nb + r, j, T::from_f64(-v)));
            }
        }
        for k in 0..np {
            let (rows, vals) = self.tn.col(k);
            for (&r, &v) in rows.iter().zip(vals) {
                triplets.push((nb + r, nb + ns + k, T::from_f64(v)));
                triplets.push((nb + ns + k, nb + r, T::from_f64(-v)));
            }
        }
        let m = plcp::matrix::Csc::try_from_triplets(dim, dim, &triplets)?;
        let qt = Col::from_fn(dim, |i| {
            T::from_f64(if i >= nb + ns {
                self.capacities[i - nb - ns]
            } else {
                0.0
            })
        });
        let dt = Col::from_fn(dim, |i| {
            T::from_f64(if i < nb { self.load[i] } else { 0.0 })
        });
        Plcp::mixed_sparse(m, qt.as_ref(), dt.as_ref(), self.sizes().free())?
            .with_range(T::zero(), lambda_max.map(T::from_f64))
    }

    /// The mixed PLCP as plcp's JSON input: `{"M": rows, "q", "d", "lambda_max", "free"}`.
    pub fn plcp_json(&self, lambda_max: Option<f64>) -> serde_json::Value {
        let (m, q, d) = self.blocks();
        let rows: Vec<Vec<f64>> = (0..m.nrows())
            .map(|i| (0..m.ncols()).map(|j| m[(i, j)]).collect())
            .collect();
        serde_json::json!({
            "M": rows,
            "q": (0..q.nrows()).map(|i| q[i]).collect::<Vec<_>>(),
            "d": (0..d.nrows()).map(|i| d[i]).collect::<Vec<_>>(),
            "lambda_max": lambda_max,
            "free": self.sizes().free(),
        })
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Scene;

    /// The sparse `A` and `T N` hold exactly what the dense assembly wrote
    /// (entries written into a zero matrix, a later write of a position
    /// replacing an earlier one) on every scene, and the mixed PLCP built from
    /// them in sparse form equals the dense one.
    #[test]
    fn sparse_blocks_equal_the_dense_assembly_on_every_scene() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
        let mut checked = 0;
        for dir in [root.clone(), root.join("pipe-whip"), root.join("stiff")] {
            for e in std::fs::read_dir(dir).unwrap() {
                let path = e.unwrap().path();
                if path.extension().is_none_or(|x| x != "toml") {
                    continue;
                }
                let scene = Scene::from_file(&path).unwrap();
                for leave_out in [true, false] {
                    let sys = System::assemble_with(&scene.frame, leave_out);
                    let f = full_blocks(&scene.frame);
                    let keep_c: Vec<usize> = sys
                        .coordinates
                        .iter()
                        .map(|c| f.coords.iter().position(|x| x == c).unwrap())
                        .collect();
                    let keep_f: Vec<usize> = sys
                        .forces
                        .iter()
                        .map(|m| f.forces.iter().position(|x| x == m).unwrap())
                        .collect();
                    let mut dense = Mat::<f64>::zeros(keep_f.len(), keep_c.len());
                    for (i, &r) in keep_f.iter().enumerate() {
                        for &(j, v) in &f.a[r] {
                            if let Some(k) = keep_c.iter().position(|&c| c == j) {
                                dense[(i, k)] = v;
                            }
                        }
                    }
                    let what = format!("{} (leave out {leave_out})", path.display());
                    assert_eq!(sys.a.to_dense(), dense, "{what}: A");
                    for i in 0..dense.nrows() {
                        for j in 0..dense.ncols() {
                            assert_eq!(sys.a[(i, j)].to_bits(), dense[(i, j)].to_bits(), "{what}");
                        }
                    }
                    let tn = sys.tn.to_dense();
                    for i in 0..tn.nrows() {
                        for j in 0..tn.ncols() {
                            assert_eq!(sys.tn[(i, j)].to_bits(), tn[(i, j)].to_bits(), "{what}");
                        }
                    }
                    let sparse = sys.plcp_sparse::<f64>(None).unwrap();
                    assert_eq!(sparse.m(), sys.plcp::<f64>(None).unwrap().m(), "{what}");
                    checked += 1;
                }
            }
        }
        assert!(checked >= 40, "{checked}");
    }

    fn scene(src: &str) -> Scene {
        Scene::from_toml(src, "t.toml").unwrap()
    }

    /// A bar A-B-C along x, A clamped, B without mass, C with a lumped mass,
    /// loaded at B by `load`.
    fn massless_middle(load: &str) -> Result<Scene, crate::FramesError> {
        let src = format!(
            "[[node]]\nid = \"A\"\nx = 0.0\ny = 0.0\n[[node]]\nid = \"B\"\nx = 1.0\ny = 0.0\n\
             [[node]]\nid = \"C\"\nx = 2.0\ny = 0.0\n\
             [[member]]\nid = \"AB\"\nfrom = \"A\"\nto = \"B\"\nplastic_moment = 1.0\nmass_per_length = 0.0\n\
             [[member]]\nid = \"BC\"\nfrom = \"B\"\nto = \"C\"\nplastic_moment = 1.0\nmass_per_length = 0.0\n\
             [[mass]]\nnode = \"C\"\nm = 1.0\n\
             [[support]]\nnode = \"A\"\nfix = [\"x\", \"y\", \"rz\"]\n\
             [[load]]\nnode = \"B\"\n{load} = 1.0\n"
        );
        Scene::from_toml(&src, "t.toml")
    }

    #[test]
    fn massless_node_held_by_inextensible_members_is_no_mechanism() {
        // B's axial motion is fixed by AB's inextensibility (a touched column
        // whose block has no null space); its transverse motion and rotation are
        // free and carry no mass (untouched columns, unit null vectors)
        assert!(massless_middle("fx").is_ok());
        let err = massless_middle("fy").unwrap_err().to_string();
        assert!(err.contains("node \"B\", component y"), "{err}");
        let err = massless_middle("mz").unwrap_err().to_string();
        assert!(err.contains("node \"B\", component rz"), "{err}");
    }

    #[test]
    fn massless_inclined_bar_is_a_mechanism_across_its_axis() {
        // one massless bar at 45 degrees: B may move across the bar's axis (the
        // null space of the touched block, (-s, c)), which a horizontal load drives
        let src = "[[node]]\nid = \"A\"\nx = 0.0\ny = 0.0\n[[node]]\nid = \"B\"\nx = 1.0\ny = 1.0\n\
                   [[member]]\nid = \"AB\"\nfrom = \"A\"\nto = \"B\"\nplastic_moment = 1.0\nmass_per_length = 0.0\n\
                   [[support]]\nnode = \"A\"\nfix = [\"x\", \"y\", \"rz\"]\n\
                   [[load]]\nnode = \"B\"\nfx = 1.0\n";
        let err = Scene::from_toml(src, "t.toml").unwrap_err().to_string();
        assert!(err.contains("node \"B\", component x"), "{err}");
        // along the axis the bar holds it: a load along (1, 1) does no work on (-1, 1)
        let along = src.replace("fx = 1.0", "fx = 1.0\nfy = 1.0");
        assert!(Scene::from_toml(&along, "t.toml").is_ok());
    }

    const PORTAL: &str = r#"
[[node]]
id = "A"
x = 0.0
y = 0.0
[[node]]
id = "B"
x = 0.0
y = 1.0
[[node]]
id = "C"
x = 2.0
y = 1.0
[[node]]
id = "D"
x = 2.0
y = 0.0
[[member]]
id = "AB"
from = "A"
to = "B"
plastic_moment = 1.0
mass_per_length = 1.0
[[member]]
id = "BC"
from = "B"
to = "C"
plastic_moment = 1.0
mass_per_length = 1.0
elements = 2
[[member]]
id = "CD"
from = "C"
to = "D"
plastic_moment = 1.0
mass_per_length = 1.0
[[support]]
node = "A"
fix = ["x", "y", "rz"]
[[support]]
node = "D"
fix = ["x", "y", "rz"]
[[load]]
node = "B"
fx = 1.0
"#;

    #[test]
    fn portal_is_indeterminate_of_degree_three() {
        let s = System::assemble(&scene(PORTAL).frame);
        assert_eq!(s.coordinates.len(), 9);
        assert_eq!(s.forces.len(), 12);
        assert_eq!(s.modes.len(), 10);
        assert_eq!(s.indeterminacy(), 3);
        assert_eq!(s.rigid_body_freedom(), 0);
        assert!(!s.is_determinate());
    }

    #[test]
    fn virtual_work_of_a_rigid_rotation_is_zero() {
        // a rigid-body rotation of the whole unsupported frame deforms nothing
        let mut f = scene(PORTAL).frame;
        for n in &mut f.nodes {
            n.fixed = [false; 6];
        }
        let s = System::assemble(&f);
        let q: Vec<f64> = s
            .coordinates
            .iter()
            .map(|c| {
                let n = &f.nodes[c.node];
                match c.component {
                    Component::X => -n.y,
                    Component::Y => n.x,
                    Component::Rz => 1.0,
                    other => panic!("{other:?} in a planar frame"),
                }
            })
            .collect();
        for r in 0..s.forces.len() {
            let v: f64 = (0..q.len()).map(|j| s.a[(r, j)] * q[j]).sum();
            assert!(v.abs() < 1e-12, "row {r}: {v}");
        }
    }

    #[test]
    fn cantilever_statics() {
        // tip load P up on a cantilever of length 2: root moment +2P (sagging)
        let src = PORTAL.replace("fx = 1.0", "fy = 1.0");
        let _ = src;
        let f = scene(
            r#"
[[node]]
id = "A"
x = 0.0
y = 0.0
[[node]]
id = "B"
x = 2.0
y = 0.0
[[member]]
id = "AB"
from = "A"
to = "B"
plastic_moment = 1.0
[[mass]]
node = "B"
m = 1.0
[[support]]
node = "A"
fix = ["x", "y", "rz"]
[[load]]
node = "B"
fy = 1.0
"#,
        )
        .frame;
        let s = System::assemble(&f);
        assert_eq!(s.coordinates.len(), 2);
        assert_eq!(s.left_out.decoupled_coordinates, vec![(1, Component::X)]);
        assert_eq!(s.left_out.decoupled_forces, vec![MemberForce::Axial(0)]);
        assert!(s.is_determinate());
        // solve A^T X = a_o by hand: X = (m_from, m_to)
        let (a, l) = (&s.a, &s.load);
        let det = a[(0, 0)] * a[(1, 1)] - a[(1, 0)] * a[(0, 1)];
        let m_from = (l[0] * a[(1, 1)] - l[1] * a[(1, 0)]) / det;
        assert!((m_from - 2.0).abs() < 1e-12);
    }
}
