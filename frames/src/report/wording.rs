//! The names and summaries both reports use: a section's or a group's label,
//! a yield mode's tag, the yield surfaces, what system (9) leaves out and the
//! exact critical loads.

use super::fmt_g;
use crate::analysis::Analysis;
use crate::assemble::MemberForce;
use crate::hinge::section_name;
use crate::model::Component;

impl Analysis {
    /// `+`/`-` for a bending-only mode, `@angle` (the facet normal's angle in
    /// degrees in the plane (m, F)) for a facet of a yield polygon.
    pub(super) fn mode_tag(&self, mode: usize, sign: crate::assemble::Sign) -> String {
        match self.system.modes.get(mode).and_then(|m| m.facet) {
            Some(f) => format!(
                "@{:.0}",
                crate::yield_surface::Facet {
                    normal: f.normal,
                    offset: 0.0
                }
                .angle_degrees()
            ),
            None => if sign == crate::assemble::Sign::Positive {
                "+"
            } else {
                "-"
            }
            .into(),
        }
    }

    /// The yield surfaces of the scene, one line per distinct polygon.
    pub fn yield_summary(&self) -> Vec<String> {
        let mut seen: Vec<(crate::yield_surface::Curve, usize, bool)> = Vec::new();
        for el in &self.scene.frame.elements {
            if let Some(it) = el.interaction {
                if !seen.contains(&(it.curve, it.facets, it.axial.is_some())) {
                    seen.push((it.curve, it.facets, it.axial.is_some()));
                }
            }
        }
        let space = self.scene.frame.model == crate::model::Model::Space;
        seen.iter()
            .map(|&(c, k, axial)| {
                if axial {
                    return format!(
                        "(M2^2 + M3^2)/Mp^2 <= g(T/Tp, N/Np)^2, g(t, n) = s cos(pi n / 2 s), s = sqrt(1 - t^2): inscribed polytope of {} facets ({k} longitudes times the triangles of a (t, n) grid; vertices on the surface), one yield mode per facet",
                        crate::yield_surface::Polytope::new(k).map_or(0, |p| p.facets().len())
                    );
                }
                if space {
                    return format!(
                        "(M2^2 + M3^2)/Mp^2 + (T/Tp)^2 <= 1: inscribed polyhedron of {} facets ({k} longitudes, the polygon's latitudes; vertices on the surface), one yield mode per facet",
                        k * k / 2
                    );
                }
                format!(
                    "{}: inscribed polygon of {k} facets (vertices on the curve, the axis points among them), one yield mode per facet",
                    c.describe()
                )
            })
            .collect()
    }

    pub(super) fn coord_name(&self, node: usize, c: Component) -> String {
        format!("{}.{}", self.scene.frame.nodes[node].id, c.as_str())
    }

    #[cfg(feature = "json")]
    pub(super) fn force_name(&self, f: &MemberForce) -> String {
        let fr = &self.scene.frame;
        match *f {
            MemberForce::Moment(k) => {
                let n = section_name(fr, &self.system, k);
                format!("moment {} {} ({})", n.member, n.end.as_str(), n.node)
            }
            MemberForce::Moment2(k) => {
                let n = section_name(fr, &self.system, k);
                format!(
                    "moment about e2 {} {} ({})",
                    n.member,
                    n.end.as_str(),
                    n.node
                )
            }
            MemberForce::Axial(e) | MemberForce::Torque(e) => {
                let el = &fr.elements[e];
                let what = if matches!(f, MemberForce::Axial(_)) {
                    "axial force"
                } else {
                    "torque"
                };
                format!(
                    "{what} {} ({}-{})",
                    fr.members[el.member].id, fr.nodes[el.from].id, fr.nodes[el.to].id
                )
            }
        }
    }

    /// One line per thing left out of system (9).
    pub fn left_out_summary(&self) -> Vec<String> {
        let lo = &self.system.left_out;
        let fr = &self.scene.frame;
        let mut out = Vec::new();
        let nn = fr.nodes.len();
        let other = match fr.model {
            crate::model::Model::Planar => {
                "out-of-plane coordinates (z, rx, ry) and forces (torques, out-of-plane moments)"
            }
            crate::model::Model::Grillage => {
                "in-plane coordinates (x, y, rz) and forces (axial forces, in-plane moments)"
            }
            crate::model::Model::Space => "",
        };
        if !other.is_empty() {
            out.push(format!(
            "by construction ({} model): the {} of a space frame, {} coordinates and {} member forces",
            fr.model.as_str(),
            other,
            3 * nn,
            3 * fr.elements.len()
        ));
        }
        if let Some(r) = &fr.reduction {
            out.push(r.summary());
        }
        if lo.full_assembly {
            out.push("nothing else (full assembly: no ties, no decoupled parts left out)".into());
        }
        if !lo.supported.is_empty() {
            let names: Vec<String> = lo
                .supported
                .iter()
                .map(|&(n, c)| self.coord_name(n, c))
                .collect();
            out.push(format!(
                "{} supported coordinates ({})",
                names.len(),
                names.join(", ")
            ));
        }
        if !lo.loads_on_supports.is_empty() {
            let names: Vec<String> = lo
                .loads_on_supports
                .iter()
                .map(|&(n, c)| self.coord_name(n, c))
                .collect();
            out.push(format!(
                "loads on supported coordinates, taken by the supports ({})",
                names.join(", ")
            ));
        }
        if !lo.tied_sections.is_empty() {
            out.push(format!(
                "yield modes of {} tied sections (at a node joining two sections, the hinge is carried by the weaker one)",
                lo.tied_sections.len()
            ));
        }
        if !lo.decoupled_coordinates.is_empty() || !lo.decoupled_forces.is_empty() {
            let mut by_comp = std::collections::BTreeMap::new();
            for &(n, c) in &lo.decoupled_coordinates {
                by_comp
                    .entry(c)
                    .or_insert_with(Vec::new)
                    .push(fr.nodes[n].id.clone());
            }
            let coords: Vec<String> = by_comp
                .iter()
                .map(|(c, ns)| format!("{} at {} nodes", c.as_str(), ns.len()))
                .collect();
            let axial = lo
                .decoupled_forces
                .iter()
                .filter(|f| matches!(f, MemberForce::Axial(_)))
                .count();
            let torques = lo
                .decoupled_forces
                .iter()
                .filter(|f| matches!(f, MemberForce::Torque(_)))
                .count();
            let moments = lo.decoupled_forces.len() - axial - torques;
            let mut forces = Vec::new();
            if axial > 0 {
                forces.push(format!("axial forces of {axial} elements"));
            }
            if torques > 0 {
                forces.push(format!("torques of {torques} elements"));
            }
            if moments > 0 {
                forces.push(format!(
                    "{moments} end moments and {} yield modes",
                    lo.decoupled_modes
                ));
            }
            out.push(format!(
                "an unloaded part decoupled from the loaded one (its solution is zero): {}{}{}",
                coords.join(", "),
                if coords.is_empty() || forces.is_empty() {
                    ""
                } else {
                    "; "
                },
                forces.join(", ")
            ));
        }
        out
    }

    /// The critical loads (the reading's breakpoints) as their exact values
    /// from the certificate, as short fractions where short (`1`, `13/3`),
    /// else decimals; a load the certificate does not hold (to 1e-9
    /// relative) is given as its float value followed by `?`.
    pub fn exact_critical_loads(&self) -> Vec<String> {
        let Some(c) = &self.solution.info.certificate else {
            return Vec::new();
        };
        self.reading
            .breakpoints
            .iter()
            .map(|b| {
                c.breakpoints
                    .iter()
                    .find(|e| {
                        let ef = plcp::exact::rational_to_f64(e);
                        (ef - b.lambda).abs() <= 1e-9 * ef.abs().max(1e-300)
                    })
                    .map_or_else(|| format!("{}?", fmt_g(b.lambda)), plcp::exact::short)
            })
            .collect()
    }

    pub(super) fn group_label(&self, g: usize) -> String {
        let fr = &self.scene.frame;
        let grp = &self.reading.groups[g];
        if grp.sections.len() > 1 {
            fr.nodes[grp.node].id.clone()
        } else {
            let n = section_name(fr, &self.system, grp.sections[0]);
            format!("{} ({} {})", n.node, n.member, n.end.as_str())
        }
    }
}
