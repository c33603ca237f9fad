//! System (9) of a frame: generalised coordinates, member forces, critical
//! sections and yield modes, the blocks `M_q`, `A`, `T N`, `X*`, `a_o`, and the
//! mixed PLCP that plcp solves.
//!
//! Kinematics of an element from node `a` to node `b` (length `h`, direction
//! `(c, s)`), with nodal coordinates `(u_x, u_y, theta)`:
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
//! **Axial rigidity.** Members are inextensible. The axial force `N` of every
//! element is kept as a member force (a free variable of the PLCP) whose dual
//! deformation, the elongation rate, must vanish: its row of `A q = T N x*`
//! has no yield mode. Nothing is eliminated, so the kinematics stay exact for
//! any geometry; the price is `s` larger by one per element, and an
//! indeterminate free block for frames whose axial forces are not statically
//! determined.
//!
//! **Tied sections.** Where two sections meet at a node with a free,
//! massless, unloaded rotation, only the weaker one carries yield modes (see
//! `rigid_sections`): one physical hinge, one pair of yield modes.
//!
//! **What is left out.** Supported coordinates, and every part of the system
//! that carries no load and is decoupled from the loaded part (found as the
//! connected components of the sparsity graph of system (9)): its solution is
//! zero for every `Lambda`. The straight, transversely loaded cantilever loses
//! its axial motion this way and becomes statically determinate.

use crate::kernel::null_space;
use crate::model::{Component, Frame};
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
    /// Sagging or hogging.
    pub sign: Sign,
}

/// A generalised coordinate: one unsupported component of one node.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coordinate {
    /// Node index.
    pub node: usize,
    /// Component.
    pub component: Component,
}

/// A member force: the bending moment at a critical section, or an element's axial force.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum MemberForce {
    /// Bending moment (sagging positive) at a section (index into [`System::sections`]).
    Moment(usize),
    /// Axial force (tension positive) of an element, the reaction of inextensibility.
    Axial(usize),
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
}

/// System (9) of a frame, with what was left out.
#[derive(Clone, Debug)]
pub struct System {
    /// Kept generalised coordinates (`beta`).
    pub coordinates: Vec<Coordinate>,
    /// Kept member forces (`s`).
    pub forces: Vec<MemberForce>,
    /// Kept yield modes (`p`).
    pub modes: Vec<YieldMode>,
    /// All critical sections of the frame (two per element), kept or not.
    pub sections: Vec<CriticalSection>,
    /// Diagonal of the lumped mass matrix `M_q` (`beta`).
    pub mass: Vec<f64>,
    /// Compatibility `A` (`s x beta`): member deformations from coordinates.
    pub a: Mat<f64>,
    /// `T N` (`s x p`): member deformations from the plastic multipliers.
    pub tn: Mat<f64>,
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

/// The full (nothing left out but supports) blocks of a frame.
struct Full {
    coords: Vec<Coordinate>,
    index: Vec<[Option<usize>; 3]>,
    forces: Vec<MemberForce>,
    sections: Vec<CriticalSection>,
    a: Mat<f64>,
    mass: Vec<f64>,
    load: Vec<f64>,
    supported: Vec<(usize, Component)>,
    loads_on_supports: Vec<(usize, Component)>,
}

fn full_blocks(frame: &Frame) -> Full {
    let mut coords = Vec::new();
    let mut index = vec![[None; 3]; frame.nodes.len()];
    let mut supported = Vec::new();
    let mut loads_on_supports = Vec::new();
    for (i, n) in frame.nodes.iter().enumerate() {
        for c in Component::ALL {
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
    // forces: the moments of all sections, then the axial forces
    let mut forces: Vec<MemberForce> = (0..2 * ne).map(MemberForce::Moment).collect();
    forces.extend((0..ne).map(MemberForce::Axial));
    let mut a = Mat::<f64>::zeros(3 * ne, coords.len());
    for (e, el) in frame.elements.iter().enumerate() {
        let (c, s, h) = (el.cos, el.sin, el.length);
        let ia = index[el.from];
        let ib = index[el.to];
        let mut add = |row: usize, idx: Option<usize>, v: f64| {
            if let Some(j) = idx {
                if v != 0.0 {
                    a[(row, j)] += v;
                }
            }
        };
        // psi = (-s (uxb - uxa) + c (uyb - uya)) / h
        let psi = [
            (ia[0], s / h),
            (ia[1], -c / h),
            (ib[0], -s / h),
            (ib[1], c / h),
        ];
        let (rf, rt, rn) = (2 * e, 2 * e + 1, 2 * ne + e);
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
    let mass = coords
        .iter()
        .map(|co| {
            let n = &frame.nodes[co.node];
            match co.component {
                Component::Rz => n.inertia,
                _ => n.mass,
            }
        })
        .collect();
    let load = coords
        .iter()
        .map(|co| frame.nodes[co.node].load[co.component.index()])
        .collect();
    Full {
        coords,
        index,
        forces,
        sections,
        a,
        mass,
        load,
        supported,
        loads_on_supports,
    }
}

/// Tied pairs: where exactly two sections meet at a node whose rotation is
/// free, without rotary inertia or applied moment, node equilibrium makes
/// their moments equal and only the split of the hinge rotation between them
/// would differ (fact 4 of the notes). The stronger section of each pair (the
/// later one on a tie) gets no yield modes: the same mechanisms and the same
/// dissipation, without duplicate yield rows, non-unique node rotations and
/// the degenerate pivots they cause.
fn rigid_sections(frame: &Frame, sections: &[CriticalSection]) -> Vec<bool> {
    let mut at_node: Vec<Vec<usize>> = vec![Vec::new(); frame.nodes.len()];
    for (k, s) in sections.iter().enumerate() {
        at_node[s.node].push(k);
    }
    let mut rigid = vec![false; sections.len()];
    for (i, secs) in at_node.iter().enumerate() {
        let n = &frame.nodes[i];
        if secs.len() == 2 && !n.fixed[2] && n.inertia == 0.0 && n.load[2] == 0.0 {
            let (a, b) = (secs[0], secs[1]);
            let drop = if sections[b].plastic_moment >= sections[a].plastic_moment {
                b
            } else {
                a
            };
            rigid[drop] = true;
        }
    }
    rigid
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
    // A massless motion moves only massless coordinates; bending is free at the
    // hinges of every element end, so only the inextensibility rows restrict it.
    let ne = frame.elements.len();
    let c = Mat::from_fn(ne, massless.len(), |i, k| f.a[(2 * ne + i, massless[k])]);
    let (_, basis) = null_space(&c);
    let scale = massless.iter().fold(0.0f64, |s, &j| s.max(f.load[j].abs()));
    if scale == 0.0 {
        return None;
    }
    for v in &basis {
        let vn = v.iter().fold(0.0f64, |s, x| s.max(x.abs()));
        let work: f64 = v.iter().zip(&massless).map(|(x, &j)| x * f.load[j]).sum();
        if work.abs() > 1e-9 * scale * vn * (massless.len() as f64) {
            // point at a loaded coordinate that moves in this mechanism
            let k = (0..massless.len())
                .filter(|&k| v[k] != 0.0 && f.load[massless[k]] != 0.0)
                .max_by(|&x, &y| {
                    (v[x] * f.load[massless[x]])
                        .abs()
                        .total_cmp(&(v[y] * f.load[massless[y]]).abs())
                })?;
            let co = f.coords[massless[k]];
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
fn full_rank_sparse(a: &Mat<f64>) -> Option<usize> {
    let n = a.nrows();
    if n != a.ncols() || n == 0 {
        return None;
    }
    let csc = plcp::matrix::Csc::from_dense(a.as_ref());
    let cond = csc.lu_condition()?;
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
        let f = full_blocks(frame);
        let (nb, ns) = (f.coords.len(), f.forces.len());
        let ne = frame.elements.len();
        let np = 4 * ne;
        // variables: coordinates [0, nb), forces [nb, nb + ns), modes [nb + ns, ...)
        let mut dsu = Dsu((0..nb + ns + np).collect());
        for r in 0..ns {
            for j in 0..nb {
                if f.a[(r, j)] != 0.0 {
                    dsu.union(nb + r, j);
                }
            }
        }
        for k in 0..2 * ne {
            // section k's moment is force k; its modes are 2k, 2k + 1
            dsu.union(nb + k, nb + ns + 2 * k);
            dsu.union(nb + k, nb + ns + 2 * k + 1);
        }
        let mut loaded = vec![false; nb + ns + np];
        for j in 0..nb {
            if f.load[j] != 0.0 {
                let r = dsu.find(j);
                loaded[r] = true;
            }
        }
        let keep: Vec<bool> = (0..nb + ns + np).map(|v| loaded[dsu.find(v)]).collect();
        let kc: Vec<usize> = (0..nb).filter(|&j| keep[j]).collect();
        let kf: Vec<usize> = (0..ns).filter(|&r| keep[nb + r]).collect();
        let rigid = rigid_sections(frame, &f.sections);
        let km: Vec<usize> = (0..np)
            .filter(|&k| keep[nb + ns + k] && !rigid[k / 2])
            .collect();
        let mut left_out = LeftOut {
            supported: f.supported.clone(),
            loads_on_supports: f.loads_on_supports.clone(),
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
        left_out.tied_sections = (0..f.sections.len())
            .filter(|&k| rigid[k] && keep[nb + k])
            .collect();
        left_out.decoupled_modes = np - km.len() - 2 * left_out.tied_sections.len();
        let a = Mat::from_fn(kf.len(), kc.len(), |i, j| f.a[(kf[i], kc[j])]);
        let mut tn = Mat::<f64>::zeros(kf.len(), km.len());
        let modes: Vec<YieldMode> = km
            .iter()
            .map(|&k| YieldMode {
                section: k / 2,
                sign: if k % 2 == 0 {
                    Sign::Positive
                } else {
                    Sign::Negative
                },
            })
            .collect();
        for (col, &k) in km.iter().enumerate() {
            let sec_force = k / 2; // the moment of section k/2 is force k/2
            if let Some(row) = kf.iter().position(|&r| r == sec_force) {
                tn[(row, col)] = if k % 2 == 0 { 1.0 } else { -1.0 };
            }
        }
        let capacities = modes
            .iter()
            .map(|m| f.sections[m.section].plastic_moment)
            .collect();
        let rank_a = full_rank_sparse(&a).unwrap_or_else(|| null_space(&a).0);
        let _ = &f.index;
        System {
            coordinates: kc.iter().map(|&j| f.coords[j]).collect(),
            forces: kf.iter().map(|&r| f.forces[r]).collect(),
            modes,
            sections: f.sections,
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
        for r in 0..ns {
            for j in 0..nb {
                let v = self.a[(r, j)];
                if v != 0.0 {
                    m[(j, nb + r)] = -v;
                    m[(nb + r, j)] = -v;
                }
            }
            for k in 0..np {
                let v = self.tn[(r, k)];
                if v != 0.0 {
                    m[(nb + r, nb + ns + k)] = v;
                    m[(nb + ns + k, nb + r)] = -v;
                }
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
    /// stored entries of the mass diagonal, `A` and `T N` only; `O(beta s + s p)`
    /// to read the dense blocks, no dense `M`), for plcp's sparse basis.
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
        for r in 0..ns {
            for j in 0..nb {
                let v = self.a[(r, j)];
                if v != 0.0 {
                    triplets.push((j, nb + r, T::from_f64(-v)));
                    triplets.push((nb + r, j, T::from_f64(-v)));
                }
            }
            for k in 0..np {
                let v = self.tn[(r, k)];
                if v != 0.0 {
                    triplets.push((nb + r, nb + ns + k, T::from_f64(v)));
                    triplets.push((nb + ns + k, nb + r, T::from_f64(-v)));
                }
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
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Scene;

    fn scene(src: &str) -> Scene {
        Scene::from_toml(src, "t.toml").unwrap()
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
            n.fixed = [false; 3];
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
