//! The yield modes of the critical sections: `+-Mp` without interaction, one
//! mode per facet of the section's polygon (planar, grillage), polyhedron or
//! polytope (space), each with its column of `T N` and its capacity.

use super::full::ModeSpec;
use super::{CriticalSection, FacetMode, Sign, YieldMode};
use crate::kind::ElementRow;
use crate::model::{Frame, Interaction, Model};
use crate::yield_surface::{Polygon, Polyhedron, Polytope};

/// The yield modes of every section, in section order.
pub(super) fn yield_modes(frame: &Frame, sections: &[CriticalSection]) -> Vec<ModeSpec> {
    let ne = frame.elements.len();
    let mut modes = Vec::new();
    for (k, sec) in sections.iter().enumerate() {
        let el = &frame.elements[sec.element];
        let mp = sec.plastic_moment;
        match el.interaction {
            Some(it) if frame.model == Model::Space => space_modes(k, sec, ne, &it, &mut modes),
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
                    let facet = FacetMode {
                        index: i,
                        count: it.facets,
                        normal: f.normal,
                        normal3: None,
                        axial: None,
                    };
                    modes.push(facet_mode(k, nm, facet, column, f.offset * mp));
                }
            }
        }
    }
    modes
}

/// A space facet: the normal's bending and torsion components `(n2, n3,
/// nt)`, its axial component (the polytope only) and its offset.
type SpaceFacet = ([f64; 3], Option<f64>, f64);

/// The modes of space section `k`: the facets of the bending-torsion
/// polyhedron, or of the bending-torsion-axial polytope when the member has
/// a plastic axial force (one more component, the axial force's row).
fn space_modes(
    k: usize,
    sec: &CriticalSection,
    ne: usize,
    it: &Interaction,
    modes: &mut Vec<ModeSpec>,
) {
    let mp = sec.plastic_moment;
    // (normal (n2, n3, nt), axial component nn, offset), the facet count and Np
    let (facets, count, np): (Vec<SpaceFacet>, usize, f64) = match it.axial {
        Some(np) => {
            let polytope =
                Polytope::new(it.facets).expect("the scene checked the number of facets");
            let facets = polytope.facets();
            let list = facets
                .iter()
                .map(|f| {
                    let [n2, n3, nt, nn] = f.normal;
                    ([n2, n3, nt], Some(nn), f.offset)
                })
                .collect();
            (list, facets.len(), np)
        }
        None => {
            let polyhedron =
                Polyhedron::new(it.facets).expect("the scene checked the number of facets");
            let list = polyhedron
                .facets()
                .iter()
                .map(|f| (f.normal, None, f.offset))
                .collect();
            (list, it.facets * it.facets / 2, f64::NAN)
        }
    };
    // rounding of an exactly zero component is dropped: the planes move by
    // 1e-15 at most, the pattern stays exact
    let round = |v: f64| if v.abs() <= 1e-14 { 0.0 } else { v };
    for (i, (normal, axial, offset)) in facets.into_iter().enumerate() {
        let [n2, n3, nt] = normal.map(round);
        let nn = axial.map(round);
        let mut column = Vec::with_capacity(4);
        let mut rows = vec![
            (k, n3),
            (
                ElementRow::Second.row(sec.element, ne),
                nt * mp / it.capacity,
            ),
            (3 * ne + k, n2),
        ];
        if let Some(nn) = nn {
            rows.push((ElementRow::Third.row(sec.element, ne), nn * mp / np));
        }
        for (row, v) in rows {
            if v != 0.0 {
                column.push((row, v));
            }
        }
        let lead = if n3 != 0.0 { n3 } else { n2 };
        let bending = n2.hypot(n3);
        let facet = FacetMode {
            index: i,
            count,
            normal: [if lead >= 0.0 { bending } else { -bending }, nt],
            normal3: Some([n2, n3, nt]),
            axial: nn,
        };
        modes.push(facet_mode(k, lead, facet, column, offset * mp));
    }
}

/// The mode of section `k` on a facet: positive (sagging) when the facet's
/// leading bending component `lead` is nonnegative.
fn facet_mode(
    k: usize,
    lead: f64,
    facet: FacetMode,
    column: Vec<(usize, f64)>,
    capacity: f64,
) -> ModeSpec {
    ModeSpec {
        mode: YieldMode {
            section: k,
            sign: if lead >= 0.0 {
                Sign::Positive
            } else {
                Sign::Negative
            },
            facet: Some(facet),
        },
        column,
        capacity,
    }
}
