//! The full blocks of system (9): every free coordinate, member force,
//! critical section and yield mode, before anything is left out; and the
//! tied sections that [`super::System::assemble`] leaves without modes.

use super::modes::yield_modes;
use super::{Coordinate, CriticalSection, End, MemberForce, YieldMode};
use crate::model::{Component, Frame};

/// One yield mode of the full system with its column of `T N` and its capacity.
pub(super) struct ModeSpec {
    pub(super) mode: YieldMode,
    pub(super) column: Vec<(usize, f64)>,
    pub(super) capacity: f64,
}

/// The full (nothing left out but supports) blocks of a frame.
pub(super) struct Full {
    pub(super) coords: Vec<Coordinate>,
    pub(super) forces: Vec<MemberForce>,
    pub(super) sections: Vec<CriticalSection>,
    pub(super) modes: Vec<ModeSpec>,
    /// `A` by rows (forces), each row its few nonzero `(coordinate, value)`
    /// entries: the reader and the assembly stay linear in the element count.
    pub(super) a: Vec<Vec<(usize, f64)>>,
    pub(super) mass: Vec<f64>,
    pub(super) load: Vec<f64>,
    pub(super) supported: Vec<(usize, Component)>,
    pub(super) loads_on_supports: Vec<(usize, Component)>,
}

pub(super) fn full_blocks(frame: &Frame) -> Full {
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
    let modes = yield_modes(frame, &sections);
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
pub(super) fn rigid_sections(frame: &Frame, sections: &[CriticalSection]) -> Vec<[usize; 2]> {
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
