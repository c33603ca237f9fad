//! Reports of an analysis: a readable text and the JSON document.
//!
//! ```
//! let file = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/portal-sway.toml");
//! let a = frames::Analysis::run(
//!     frames::Scene::from_file(file).unwrap(),
//!     &frames::AnalysisOptions::default(),
//! )
//! .unwrap();
//! let text = a.to_text(); // what `frames run SCENE` prints
//! assert!(text.starts_with(&a.scene.frame.title));
//! let json = a.to_json(); // what `frames run SCENE --json` prints
//! assert_eq!(json["status"], "unbounded_ray");
//! assert_eq!(frames::report::format_number(0.5), "0.5");
//! ```

use crate::analysis::Analysis;
use crate::assemble::MemberForce;
use crate::hinge::{section_name, EventKind, HingeEvent};
use crate::model::Component;
use serde_json::{json, Map, Value};
use std::fmt::Write;

fn num(x: f64) -> Value {
    if x.is_finite() {
        json!(x)
    } else {
        Value::Null
    }
}

fn fmt_g(x: f64) -> String {
    if !x.is_finite() {
        return "inf".into();
    }
    if x == 0.0 {
        return "0".into();
    }
    let a = x.abs();
    if (1e-4..1e6).contains(&a) {
        let s = format!("{x:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    } else {
        format!("{x:.6e}")
    }
}

/// Which Lambda values get moment distributions (and which intervals their
/// pieces) in the JSON report.
#[derive(Clone, Debug, PartialEq)]
pub enum MomentPick {
    /// Every breakpoint and interval.
    All,
    /// At most this many, sampled evenly over the breakpoints (first and last kept).
    Count(usize),
    /// The breakpoints nearest these Lambda values, and the intervals holding them.
    At(Vec<f64>),
}

/// Which nodes get accelerations and the time response in the JSON report.
#[derive(Clone, Debug, PartialEq)]
pub enum NodePick {
    /// Every node.
    All,
    /// At most this many, sampled evenly over the node list (first and last kept).
    Count(usize),
    /// These node ids.
    Ids(Vec<String>),
}

/// What the JSON report writes beyond what it always writes (every
/// breakpoint's events, every interval's hinge sets): moment distributions
/// and node series grow with `breakpoints x sections` and `nodes x times`, so
/// large scenes get a bounded default ([`OutputSelection::default_for`]).
#[derive(Clone, Debug, PartialEq)]
pub struct OutputSelection {
    /// Moment distributions.
    pub moments: MomentPick,
    /// Node accelerations and displacement/velocity series.
    pub nodes: NodePick,
}

/// Scenes up to this many nodes and breakpoints report everything by default.
pub const SMALL_SCENE: usize = 200;
/// The default number of Lambda values with moment distributions, and of
/// nodes with series, for larger scenes.
pub const DEFAULT_SAMPLES: usize = 20;

/// `count` indices of `0..len`, evenly spaced, the first and the last kept.
pub fn sample_indices(len: usize, count: usize) -> Vec<usize> {
    if count == 0 || len == 0 {
        return Vec::new();
    }
    if len <= count {
        return (0..len).collect();
    }
    if count == 1 {
        return vec![len - 1];
    }
    let mut v: Vec<usize> = (0..count)
        .map(|k| ((k as f64) * ((len - 1) as f64) / ((count - 1) as f64)).round() as usize)
        .collect();
    v.dedup();
    v
}

impl OutputSelection {
    /// Everything.
    pub fn all() -> Self {
        Self {
            moments: MomentPick::All,
            nodes: NodePick::All,
        }
    }
    /// Everything for a small scene (at most [`SMALL_SCENE`] nodes and
    /// breakpoints); otherwise [`DEFAULT_SAMPLES`] Lambda values and nodes.
    pub fn default_for(a: &Analysis) -> Self {
        Self::default_for_counts(a.scene.frame.nodes.len(), a.reading.breakpoints.len())
    }
    /// [`OutputSelection::default_for`] a scene of `nodes` nodes whose path
    /// has `bps` breakpoints.
    pub fn default_for_counts(nodes: usize, bps: usize) -> Self {
        Self {
            moments: if bps <= SMALL_SCENE && nodes <= SMALL_SCENE {
                MomentPick::All
            } else {
                MomentPick::Count(DEFAULT_SAMPLES)
            },
            nodes: if nodes <= SMALL_SCENE {
                NodePick::All
            } else {
                NodePick::Count(DEFAULT_SAMPLES)
            },
        }
    }
    /// The node indices selected out of `ids`; `Err` names an unknown id.
    pub fn node_indices(&self, ids: &[&str]) -> Result<Vec<usize>, String> {
        match &self.nodes {
            NodePick::All => Ok((0..ids.len()).collect()),
            NodePick::Count(c) => Ok(sample_indices(ids.len(), *c)),
            NodePick::Ids(want) => want
                .iter()
                .map(|w| {
                    ids.iter()
                        .position(|i| i == w)
                        .ok_or_else(|| format!("--nodes: no node \"{w}\" in the scene"))
                })
                .collect(),
        }
    }
    /// Which of `lambdas` (in order) get moment distributions.
    pub fn moment_indices(&self, lambdas: &[f64]) -> Vec<usize> {
        match &self.moments {
            MomentPick::All => (0..lambdas.len()).collect(),
            MomentPick::Count(c) => sample_indices(lambdas.len(), *c),
            MomentPick::At(ls) => {
                let mut v: Vec<usize> = ls
                    .iter()
                    .filter_map(|l| {
                        (0..lambdas.len()).min_by(|&a, &b| {
                            (lambdas[a] - l).abs().total_cmp(&(lambdas[b] - l).abs())
                        })
                    })
                    .collect();
                v.sort_unstable();
                v.dedup();
                v
            }
        }
    }
    /// One line for the report: what was selected out of how many.
    fn describe(&self, what: &str, kept: usize, of: usize, flag: &str) -> String {
        if kept == of {
            format!("{what}: all {of}")
        } else {
            format!("{what}: {kept} of {of} (sampled; {flag} all, a count, or a list)")
        }
    }
}

impl Analysis {
    fn section_json(&self, section: usize, sign: &str, tied: &[usize]) -> Value {
        let n = section_name(&self.scene.frame, &self.system, section);
        let mut o =
            json!({"member": n.member, "end": n.end.as_str(), "node": n.node, "sign": sign});
        let others: Vec<Value> = tied
            .iter()
            .filter(|&&k| k != section)
            .map(|&k| {
                let m = section_name(&self.scene.frame, &self.system, k);
                json!({"member": m.member, "end": m.end.as_str(), "node": m.node})
            })
            .collect();
        if !others.is_empty() {
            o["tied"] = Value::Array(others);
        }
        o
    }

    fn event_json(&self, e: &HingeEvent) -> Value {
        let mut o = self.section_json(
            e.section,
            e.sign.as_str(),
            &self.reading.groups[e.group].sections,
        );
        self.add_facet(&mut o, e.mode);
        o
    }

    /// Adds `"facet": {"index", "of", "normal"}` for a mode of a yield polygon.
    fn add_facet(&self, o: &mut Value, mode: usize) {
        if let Some(f) = self.system.modes.get(mode).and_then(|m| m.facet) {
            o["facet"] = json!({"index": f.index, "of": f.count, "normal": f.normal});
            if let Some(n3) = f.normal3 {
                o["facet"]["normal3"] = json!(n3);
            }
            if let Some(nn) = f.axial {
                o["facet"]["normal_axial"] = json!(nn);
            }
        }
    }

    /// `+`/`-` for a bending-only mode, `@angle` (the facet normal's angle in
    /// degrees in the plane (m, F)) for a facet of a yield polygon.
    fn mode_tag(&self, mode: usize, sign: crate::assemble::Sign) -> String {
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

    fn coord_name(&self, node: usize, c: Component) -> String {
        format!("{}.{}", self.scene.frame.nodes[node].id, c.as_str())
    }

    fn force_name(&self, f: &MemberForce) -> String {
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

    /// The JSON document (`--json`).
    pub fn to_json(&self) -> Value {
        self.to_json_selected(&OutputSelection::default_for(self))
            .expect("the default selection names no node")
    }

    /// The JSON document with moment distributions and node series where
    /// `sel` asks for them (see [`OutputSelection`]); `Err` names an unknown
    /// node id.
    pub fn to_json_selected(&self, sel: &OutputSelection) -> Result<Value, String> {
        serde_json::to_value(self.json_report(sel)?).map_err(|e| e.to_string())
    }

    /// The JSON document of [`Analysis::to_json_selected`] as a value that
    /// serialises itself part by part: the per-breakpoint, per-interval and
    /// per-diagram entries are built one at a time as they are written, so
    /// that writing it (`serde_json::to_writer(w, &report)`, what `frames run
    /// --json` does) holds one entry in memory, not the document. The bytes
    /// written are those of serialising [`Analysis::to_json_selected`]'s value
    /// (keys in the same sorted order; a test checks it). [`JsonReport::insert`]
    /// adds a key.
    pub fn json_report(&self, sel: &OutputSelection) -> Result<JsonReport<'_>, String> {
        let fr = &self.scene.frame;
        let node_ids: Vec<&str> = fr.nodes.iter().map(|n| n.id.as_str()).collect();
        let node_sel = sel.node_indices(&node_ids)?;
        let interval_lambdas: Vec<f64> = self
            .reading
            .intervals
            .iter()
            .map(|iv| iv.lambda_from)
            .collect();
        let interval_sel = sel.moment_indices(&interval_lambdas);
        let diagram_lambdas: Vec<f64> = self
            .response
            .moments_at_breakpoints
            .iter()
            .map(|d| d.lambda)
            .collect();
        let diagram_sel = sel.moment_indices(&diagram_lambdas);
        self.check_kept(&node_sel, &interval_sel, &diagram_sel)?;
        let sys = &self.system;
        let sz = sys.sizes();
        let lo = &sys.left_out;
        let system = json!({
            "free": sz.free(),
            "complementary": sz.modes,
            "coordinates": sz.coordinates,
            "member_forces": sz.forces,
            "yield_modes": sz.modes,
            "full": {
                "free": sys.full.free(),
                "complementary": sys.full.modes,
                "coordinates": sys.full.coordinates,
                "member_forces": sys.full.forces,
                "yield_modes": sys.full.modes,
            },
            "left_out": {
                "summary": self.left_out_summary(),
                "supported": lo.supported.iter().map(|&(n, c)| self.coord_name(n, c)).collect::<Vec<_>>(),
                "loads_on_supports": lo.loads_on_supports.iter().map(|&(n, c)| self.coord_name(n, c)).collect::<Vec<_>>(),
                "decoupled_coordinates": lo.decoupled_coordinates.iter().map(|&(n, c)| self.coord_name(n, c)).collect::<Vec<_>>(),
                "decoupled_forces": lo.decoupled_forces.iter().map(|f| self.force_name(f)).collect::<Vec<_>>(),
                "decoupled_yield_modes": lo.decoupled_modes,
            },
            "statically_determinate": sys.is_determinate(),
            "indeterminacy": sys.indeterminacy(),
            "model": fr.model.as_str(),
            "yield_surfaces": self.yield_summary(),
            "axial": match fr.model {
                crate::model::Model::Planar => "members without plastic_axial inextensible: the axial force of each such element is a member force whose elongation rate is held at zero (no yield mode); with plastic_axial it enters the yield polygon of both end sections",
                crate::model::Model::Grillage => "grillage: no axial forces; the torque of each element is a member force in the yield polygon of both end sections",
                crate::model::Model::Space if fr.elements.iter().any(|e| e.interaction.is_some_and(|i| i.axial.is_some())) => "space: members without plastic_axial inextensible (their axial force is a member force whose elongation rate is held at zero); the torque and the two bending moments of each section enter its yield polyhedron, with plastic_axial the axial force too (the polytope)",
                crate::model::Model::Space => "space: members inextensible (the axial force of each element is a member force whose elongation rate is held at zero); the torque and the two bending moments of each section enter its yield polyhedron",
            },
        });
        let info = &self.solution.info;
        let solver = json!({
            "method": info.method,
            "precision": info.precision,
            "pivots": info.pivots,
            "degenerate_pivots": info.degenerate_pivots,
            "residual": {"equation": info.residual.equation, "feasibility": info.residual.feasibility, "complementarity": info.residual.complementarity},
            "lambda_reached": num(self.solution.lambda_reached),
            "message": self.solution.message,
            "note": self.note,
            "free_block": {"rank": info.free_block.rank, "nonbasic_free": info.free_block.nonbasic_free.len(), "dependent_rows": info.free_block.dependent_rows.len()},
            "certificate": info.certificate.as_ref().map(|c| c.to_json()),
            "exact_critical_loads": info.certificate.as_ref().map(|_| self.exact_critical_loads()),
        });
        let breakpoints = Part::seq(move || {
            self.reading.breakpoints.iter().map(|b| {
                let mut o = Map::new();
                o.insert("lambda".into(), num(b.lambda));
                for k in [
                    EventKind::Yielded,
                    EventKind::FlowStarted,
                    EventKind::FlowStopped,
                    EventKind::Unloaded,
                ] {
                    o.insert(
                        k.as_str().into(),
                        Value::Array(b.of(k).map(|e| self.event_json(e)).collect()),
                    );
                }
                o.insert("stress_unique".into(), json!(b.stress_unique));
                Value::Object(o)
            })
        });
        let hinges: Vec<Value> = self
            .reading
            .hinges
            .iter()
            .map(|h| {
                let mut v = self.section_json(
                    h.section,
                    h.sign.as_str(),
                    &self.reading.groups[h.group].sections,
                );
                v["lambda"] = num(h.lambda);
                self.add_facet(&mut v, h.mode);
                v
            })
            .collect();
        let group_nodes = |gs: &[usize]| -> Vec<Value> {
            gs.iter()
                .map(|&g| {
                    let k = self.reading.groups[g].sections[0];
                    let n = section_name(fr, sys, k);
                    if self.reading.groups[g].sections.len() > 1 {
                        json!({"node": n.node})
                    } else {
                        json!({"node": n.node, "member": n.member, "end": n.end.as_str()})
                    }
                })
                .collect()
        };
        // the lazy parts own their selections (shared, as each pass of the
        // serialiser makes a new iterator)
        let (n_interval_sel, n_diagram_sel) = (interval_sel.len(), diagram_sel.len());
        let node_sel_iv = std::rc::Rc::new(node_sel.clone());
        let interval_sel = std::rc::Rc::new(interval_sel);
        let diagram_sel = std::rc::Rc::new(diagram_sel);
        let intervals = Part::seq(move || {
            let node_sel = node_sel_iv.clone();
            let interval_sel = interval_sel.clone();
            self.reading
            .intervals
            .iter()
            .zip(&self.response.intervals)
            .enumerate()
            .map(move |(k, (iv, r))| {
                let mut acc = Map::new();
                for &i in node_sel.iter() {
                    let n = &fr.nodes[i];
                    let slot = self.response.slot(i).unwrap_or(i);
                    let mut o = Map::new();
                    for c in fr.model.components() {
                        o.insert(c.as_str().into(), json!(r.accelerations[slot][c.index()]));
                    }
                    acc.insert(n.id.clone(), Value::Object(o));
                }
                // the member forces piece by piece; at the interval's level
                // only where one piece holds the whole interval (null where
                // the path pivots inside it: no one affine field is right)
                let with_moments = interval_sel.binary_search(&k).is_ok();
                let pieces: Vec<Value> = r
                    .pieces
                    .iter()
                    .filter(|_| with_moments)
                    .map(|p| {
                        let mut o = json!({
                            "lambda_from": num(p.lambda_from),
                            "lambda_to": num(p.lambda_to),
                            "moments": self.member_moments(|k| p.moments[k]),
                            "second_forces": self.member_second_forces(&self.solution.pieces[p.piece], None),
                        });
                        self.add_space_forces(&mut o, &self.solution.pieces[p.piece], None);
                        o
                    })
                    .collect();
                let (moments, second_forces) = match pieces.as_slice() {
                    [one] => (one["moments"].clone(), one["second_forces"].clone()),
                    _ => (Value::Null, Value::Null),
                };
                json!({
                    "lambda_from": num(iv.lambda_from),
                    "lambda_to": num(iv.lambda_to),
                    "rigid": iv.rigid,
                    "accelerating": group_nodes(&iv.accelerating),
                    "constant_rate": group_nodes(&iv.constant_rate),
                    "accelerations": acc,
                    "moments": moments,
                    "second_forces": second_forces,
                    "pieces": pieces,
                    "residual": {"equation": r.residual.equation, "feasibility": r.residual.feasibility, "complementarity": r.residual.complementarity},
                })
            })
        });
        let moments = Part::seq(move || {
            let diagram_sel = diagram_sel.clone();
            self.response
            .moments_at_breakpoints
            .iter()
            .zip(self.reading.intervals.iter().filter(|i| !i.rigid))
            .enumerate()
            .filter(move |(k, _)| diagram_sel.binary_search(k).is_ok())
            .map(|(_, x)| x)
            .map(|(d, iv)| {
                let piece = &self.solution.pieces[iv.piece_at(d.lambda)];
                let mut o = json!({"lambda": num(d.lambda), "members": self.member_moments(|k| d.moments[k]), "second_forces": self.member_second_forces(piece, Some(d.lambda))});
                self.add_space_forces(&mut o, piece, Some((d.lambda, &d.moments)));
                o
            })
        });
        let t = &self.response.time;
        let mut nodes = Map::new();
        for &i in &node_sel {
            let n = &fr.nodes[i];
            let slot = self.response.slot(i).unwrap_or(i);
            let series = |v: &Vec<Vec<[f64; 6]>>| {
                let mut o = Map::new();
                for c in fr.model.components() {
                    o.insert(
                        c.as_str().into(),
                        json!(v.iter().map(|row| row[slot][c.index()]).collect::<Vec<_>>()),
                    );
                }
                Value::Object(o)
            };
            nodes.insert(
                n.id.clone(),
                json!({"displacement": series(&t.displacement), "velocity": series(&t.velocity)}),
            );
        }
        let output = json!({
            "moments": sel.describe("Lambda values with moment distributions", n_diagram_sel, diagram_lambdas.len(), "--moments"),
            "interval_moments": sel.describe("intervals with moment pieces", n_interval_sel, interval_lambdas.len(), "--moments"),
            "nodes": sel.describe("nodes with accelerations and series", node_sel.len(), node_ids.len(), "--nodes"),
        });
        let mut report = JsonReport { parts: Vec::new() };
        for (key, part) in [
            ("scene", Part::Value(json!(self.scene.file))),
            ("title", Part::Value(json!(fr.title))),
            ("output", Part::Value(json!(output))),
            ("system", Part::Value(json!(system))),
            ("solver", Part::Value(json!(solver))),
            ("status", Part::Value(json!(self.solution.status.as_str()))),
            ("collapse_load", Part::Value(json!(self.reading.collapse_load().map(num).unwrap_or(Value::Null)))),
            ("model", Part::Value(json!(fr.model.as_str()))),
            ("conventions", Part::Value(json!(match fr.model {
                crate::model::Model::Planar => "bending moments sagging-positive in each element's axes (local y = member direction turned 90 degrees counter-clockwise); sign of a section = sign of its moment at yield (for a facet of a yield polygon: the sign of the normal's bending component; the facet and its unit normal in (M/Mp, N/Np) are given); end = end of the element the section sits at; affine values are [base, slope] with value = base + slope * lambda",
                crate::model::Model::Grillage => "grillage in the x-y plane: z translation, right-handed rotations rx, ry; element axes x' along the member, y' turned 90 degrees counter-clockwise; bending moment about y' dual to the hinge rotation (from end: -(theta_a - psi), to end: theta_b - psi, psi = -(w_b - w_a)/h), torque right-handed about x'; each yield mode is a facet of the inscribed polygon in (M/Mp, T/Tp), given with its unit normal; sign = sign of the normal's bending component; affine values are [base, slope] with value = base + slope * lambda",
                crate::model::Model::Space => "space frame in global axes: translations x, y, z, right-handed rotations rx, ry, rz; element axes e1 along the member, e3 from its orientation (default z), e2 = e3 x e1; the moment about e3 (as the planar one: from end -(e3.th_a - e2.du/h), to end e3.th_b - e2.du/h) and about e2 (as the grillage's: from end -(e2.th_a + e3.du/h), to end e2.th_b + e3.du/h), the torque about e1; each yield mode is a facet of the inscribed polyhedron in (M2/Mp, M3/Mp, T/Tp), given with its unit normal (normal3); moment distributions give M3 (members), M2 (m2), the bending magnitude sqrt(M2^2 + M3^2) (bending: what meets the yield surface; at breakpoints only), the torques (second_forces) and the axial forces (axial_forces, tension positive) per element; affine values are [base, slope] with value = base + slope * lambda",
            }))),
            ("breakpoints", breakpoints),
            ("hinges", Part::Value(json!(hinges))),
            ("intervals", intervals),
            ("moments_at_breakpoints", moments),
            ("targets", Part::Value(json!(self.targets_json()))),
            ("response", Part::Value(json!({
                "history": t.history.describe(),
                "method": t.method,
                "times": t.times,
                "lambda": t.lambda,
                "nodes": nodes,
            }))),
        ] {
            report.insert_part(key, part);
        }
        Ok(report)
    }

    /// `Err` if the selection asks for what a large scene's analysis did not
    /// keep ([`crate::response::Response::nodes`]: it keeps what its own selection asked for).
    fn check_kept(
        &self,
        nodes: &[usize],
        intervals: &[usize],
        diagrams: &[usize],
    ) -> Result<(), String> {
        let r = &self.response;
        if r.nodes.is_none() {
            return Ok(());
        }
        let ns = self.system.sections.len();
        let lost = nodes.iter().any(|&i| r.slot(i).is_none())
            || intervals.iter().any(|&k| {
                r.intervals[k]
                    .pieces
                    .iter()
                    .any(|p| p.moments.len() != ns || self.solution.pieces[p.piece].du.is_empty())
            })
            || diagrams
                .iter()
                .any(|&k| r.moments_at_breakpoints[k].moments.len() != ns);
        if lost {
            return Err("the selection asks for nodes or moments the analysis did not keep (a large scene's analysis keeps what its own selection asked for: pass the same --moments and --nodes)".into());
        }
        Ok(())
    }

    /// Per member: `from`, `to` and `along` (`[s, value]` at every element end).
    fn member_moments<V: serde::Serialize + Copy>(&self, value: impl Fn(usize) -> V) -> Value {
        let fr = &self.scene.frame;
        let mut out = Map::new();
        for (mi, m) in fr.members.iter().enumerate() {
            let mut along = Vec::new();
            let mut s = 0.0;
            for e in m.elements.clone() {
                along.push(json!([s, value(2 * e)]));
                s += fr.elements[e].length;
                along.push(json!([s, value(2 * e + 1)]));
            }
            let _ = mi;
            out.insert(
                m.id.clone(),
                json!({"from": value(2 * m.elements.start), "to": value(2 * m.elements.end - 1), "along": along}),
            );
        }
        Value::Object(out)
    }

    /// A general space scene's other section forces, added to a moment
    /// distribution `o` (keys `m2`, `bending`, `axial_forces`; see
    /// [`crate::section_forces`]): at a breakpoint (`at = (lambda, M3 of
    /// every section)`) their values, on a piece (`at = None`) `M2` and the
    /// axial forces as affine `[base, slope]` (the magnitude is not affine).
    /// Planar and grillage scenes get nothing.
    fn add_space_forces(
        &self,
        o: &mut Value,
        piece: &crate::solve::Piece,
        at: Option<(f64, &[f64])>,
    ) {
        let Some(sf) =
            crate::section_forces::SpaceForces::new(&self.system, self.scene.frame.elements.len())
        else {
            return;
        };
        let fr = &self.scene.frame;
        let per_element = |value: &dyn Fn(usize) -> Value| -> Value {
            let mut out = Map::new();
            for m in &fr.members {
                out.insert(
                    m.id.clone(),
                    Value::Array(m.elements.clone().map(value).collect()),
                );
            }
            Value::Object(out)
        };
        match at {
            Some((lambda, m3)) => {
                let u = piece.u(lambda);
                o["m2"] = self.member_moments(|k| sf.m2(&u, k));
                o["bending"] = self.member_moments(|k| sf.bending(&u, k, m3[k]));
                o["axial_forces"] = per_element(&|e| json!(sf.axial(&u, e)));
            }
            None => {
                let (u0, du) = (piece.u(0.0), &piece.du);
                o["m2"] = self.member_moments(|k| [sf.m2(&u0, k), sf.m2(du, k)]);
                o["axial_forces"] = per_element(&|e| json!([sf.axial(&u0, e), sf.axial(du, e)]));
            }
        }
    }

    /// Per member: the axial force or torque of each element (affine `[base,
    /// slope]` on the piece, or its value at `lambda`), where it is kept.
    fn member_second_forces(&self, piece: &crate::solve::Piece, lambda: Option<f64>) -> Value {
        let fr = &self.scene.frame;
        let nb = self.system.coordinates.len();
        let u0 = piece.u(0.0);
        let mut out = Map::new();
        for m in &fr.members {
            let vals: Vec<Value> = m
                .elements
                .clone()
                .map(|e| match self.system.second_force_index(2 * e) {
                    Some(r) => {
                        let (b, s) = (u0[nb + r], piece.du[nb + r]);
                        match lambda {
                            Some(l) => json!(b + s * l),
                            None => json!([b, s]),
                        }
                    }
                    None => Value::Null,
                })
                .collect();
            if vals.iter().any(|v| !v.is_null()) {
                out.insert(m.id.clone(), Value::Array(vals));
            }
        }
        Value::Object(out)
    }

    /// At a breakpoint, the facets of yield polygons of flowing sections that
    /// start or stop accelerating while their section keeps flowing (the flow
    /// moving across the polygon; no event of the hinge itself), e.g.
    /// `A (AB from) @124 stops, @101 starts`. A facet that stops keeps its rate
    /// in system (9), whose path cannot let a rate decrease.
    fn facet_changes(&self, lambda: f64) -> Vec<String> {
        if self.system.modes.iter().all(|m| m.facet.is_none()) {
            return Vec::new(); // no yield polygon
        }
        let pieces = &self.solution.pieces;
        let ivs = &self.reading.intervals;
        let Some(k) = ivs.iter().position(|i| i.lambda_from == lambda && !i.rigid) else {
            return Vec::new();
        };
        if k == 0 || ivs[k - 1].rigid {
            return Vec::new();
        }
        // the pieces of the path just before and just after the breakpoint,
        // read inside their spans (an interval may hold several pieces)
        let acc = |span: Option<&crate::hinge::Span>| -> Vec<bool> {
            let Some(span) = span else {
                return Vec::new();
            };
            let p = &pieces[span.piece];
            let l = if span.lambda_to.is_finite() {
                0.5 * (span.lambda_from + span.lambda_to)
            } else {
                span.lambda_from + span.lambda_from.abs().max(1.0)
            };
            let z = p.z(l);
            let scale = z.iter().fold(f64::MIN_POSITIVE, |m, v| m.max(v.abs()));
            z.iter()
                .map(|&v| v > self.solution.tolerance * scale)
                .collect()
        };
        let (before, after) = (acc(ivs[k - 1].pieces.last()), acc(ivs[k].pieces.first()));
        if before.is_empty() || after.is_empty() {
            return Vec::new();
        }
        let modes = &self.system.modes;
        // the facet modes of each section, in mode order (one pass over the
        // modes: a scan of all modes per section was quadratic, 4 s of a
        // 1000-element cantilever's report)
        let mut by_section: Vec<Vec<usize>> = vec![Vec::new(); self.system.sections.len()];
        for (m, mode) in modes.iter().enumerate() {
            if mode.facet.is_some() {
                by_section[mode.section].push(m);
            }
        }
        let mut out = Vec::new();
        for (sec, ks) in by_section.iter().enumerate() {
            let was = ks.iter().any(|&m| before[m]);
            let is = ks.iter().any(|&m| after[m]);
            if !(was && is) {
                continue;
            }
            let stops: Vec<String> = ks
                .iter()
                .filter(|&&m| before[m] && !after[m])
                .map(|&m| self.mode_tag(m, modes[m].sign))
                .collect();
            let starts: Vec<String> = ks
                .iter()
                .filter(|&&m| !before[m] && after[m])
                .map(|&m| self.mode_tag(m, modes[m].sign))
                .collect();
            if stops.is_empty() && starts.is_empty() {
                continue;
            }
            let Some(g) = self.reading.group_of[sec] else {
                continue;
            };
            let mut what = Vec::new();
            if !stops.is_empty() {
                what.push(format!("{} stops", stops.join(" ")));
            }
            if !starts.is_empty() {
                what.push(format!("{} starts", starts.join(" ")));
            }
            out.push(format!("{} {}", self.group_label(g), what.join(", ")));
        }
        out
    }

    fn group_label(&self, g: usize) -> String {
        let fr = &self.scene.frame;
        let grp = &self.reading.groups[g];
        if grp.sections.len() > 1 {
            fr.nodes[grp.node].id.clone()
        } else {
            let n = section_name(fr, &self.system, grp.sections[0]);
            format!("{} ({} {})", n.node, n.member, n.end.as_str())
        }
    }

    /// The readable report: the system, the table of critical `Lambda` with the
    /// hinges that form, then the intervals.
    pub fn to_text(&self) -> String {
        let fr = &self.scene.frame;
        let sys = &self.system;
        let sz = sys.sizes();
        let mut s = String::new();
        let title = if fr.title.is_empty() {
            "frame"
        } else {
            &fr.title
        };
        let _ = writeln!(s, "{title} ({})", self.scene.file);
        let _ = writeln!(
            s,
            "system (9): {} coordinates, {} member forces, {} yield modes: mixed PLCP with {} free and {} complementary variables",
            sz.coordinates,
            sz.forces,
            sz.modes,
            sz.free(),
            sz.modes
        );
        let _ = writeln!(
            s,
            "  before leaving out: {} coordinates, {} member forces, {} yield modes",
            sys.full.coordinates, sys.full.forces, sys.full.modes
        );
        for l in self.left_out_summary() {
            let _ = writeln!(s, "  left out: {l}");
        }
        let members_note = match fr.model {
            crate::model::Model::Planar => {
                if fr.elements.iter().any(|e| e.interaction.is_some()) {
                    "planar; members without plastic_axial inextensible (axial forces kept as reactions)"
                } else {
                    "planar; members inextensible (axial forces kept as reactions)"
                }
            }
            crate::model::Model::Grillage => {
                "grillage: z, rx, ry per node; end moments and a torque per element"
            }
            crate::model::Model::Space => {
                "space: x, y, z, rx, ry, rz per node; two bending moments per section, a torque and an axial force (a reaction) per element"
            }
        };
        let _ = writeln!(
            s,
            "  {} (degree of indeterminacy {}); {members_note}",
            if sys.is_determinate() {
                "statically determinate"
            } else {
                "statically indeterminate"
            },
            sys.indeterminacy()
        );
        for y in self.yield_summary() {
            let _ = writeln!(s, "  yield: {y}");
        }
        let info = &self.solution.info;
        let _ = writeln!(
            s,
            "solved: {} in {}, {} pivots, status {}, worst residual {:.1e}",
            info.method,
            info.precision,
            info.pivots,
            self.solution.status.as_str(),
            info.residual.worst()
        );
        if let Some(n) = &self.note {
            let _ = writeln!(s, "  note: {n}");
        }
        if let Some(c) = &info.certificate {
            if c.certified() {
                let _ = writeln!(
                    s,
                    "  certified in exact rational arithmetic: {} segments in {:.3} s, float breakpoints within {:.1e} (relative) of the exact ones",
                    c.segments, c.seconds, c.max_rel_diff
                );
                let _ = writeln!(
                    s,
                    "  exact critical loads: {}",
                    self.exact_critical_loads().join(", ")
                );
            } else if let Some(f) = &c.failure {
                let _ = writeln!(
                    s,
                    "  WARNING: exact certification REJECTED the path at segment {}: {}",
                    f.segment, f.reason
                );
            }
        }
        if info.residual.worst() > 1e-6 {
            let _ = writeln!(
                s,
                "  WARNING: the solver's path does not satisfy system (9) (residual {:.1e}): do not trust the numbers below (try --precision f128)",
                info.residual.worst()
            );
        }
        if !self.solution.status.is_success() {
            let _ = writeln!(
                s,
                "  WARNING: the path ended early at Lambda = {}: {}",
                fmt_g(self.solution.lambda_reached),
                self.solution.message
            );
        }
        let _ = writeln!(
            s,
            "  sign: + sagging, - hogging (element axes){}; load history: {}",
            if self.system.modes.iter().any(|m| m.facet.is_some()) {
                "; @a: on the facet of the yield polygon whose normal points at a degrees in (M/Mp, F/Fp)"
            } else {
                ""
            },
            self.scene.history.describe()
        );
        let _ = writeln!(s);
        let _ = writeln!(s, "critical Lambda   hinges and events");
        if self.reading.breakpoints.is_empty() {
            let _ = writeln!(s, "  (none: the frame stays rigid over the traced range)");
        }
        for (i, b) in self.reading.breakpoints.iter().enumerate() {
            let mut parts = Vec::new();
            let label = |e: &HingeEvent| {
                format!(
                    "{}{}",
                    self.group_label(e.group),
                    self.mode_tag(e.mode, e.sign)
                )
            };
            let forms: Vec<String> = self
                .reading
                .hinges
                .iter()
                .filter(|h| h.lambda == b.lambda)
                .map(|h| self.group_label(h.group))
                .collect();
            if !forms.is_empty() {
                parts.push(format!("hinge forms at {}", forms.join(", ")));
            }
            for (k, what) in [
                (EventKind::Yielded, "yielded"),
                (EventKind::FlowStarted, "started to flow"),
                (
                    EventKind::FlowStopped,
                    "stopped accelerating (rotates on at constant rate)",
                ),
                (EventKind::Unloaded, "UNLOADED (deactivation)"),
            ] {
                let v: Vec<String> = b.of(k).map(label).collect();
                if !v.is_empty() {
                    parts.push(format!("{what}: {}", v.join(", ")));
                }
            }
            let facets = self.facet_changes(b.lambda);
            if !facets.is_empty() {
                parts.push(format!("facets: {}", facets.join(", ")));
            }
            if parts.is_empty() {
                parts.push("no hinge event: the accelerations change slope (a pivot among the flowing hinges)".into());
            }
            let note = if i == 0 {
                "  [static collapse load]"
            } else {
                ""
            };
            let _ = writeln!(s, "{:>15}   {}{}", fmt_g(b.lambda), parts.join("; "), note);
        }
        let facet_stops = self.reading.breakpoints.iter().any(|b| {
            self.facet_changes(b.lambda)
                .iter()
                .any(|f| f.contains(" stops"))
        });
        if facet_stops {
            let _ = writeln!(s, "NOTE: a facet that stops accelerating while its hinge flows on keeps its rate on the path of (9), which cannot let a rate decrease; the true flow may turn by decelerating it (a deactivation of that facet: check by time stepping, see examples/pipe_whip.rs)");
        }
        let dea = self.reading.deactivations();
        if !dea.is_empty() {
            let _ = writeln!(s, "WARNING: {} deactivation(s): a flowing hinge left yield, against the paper's claim for this loading class", dea.len());
        }
        let _ = writeln!(s);
        let _ = writeln!(
            s,
            "intervals (accelerations of the nodes with mass, base + slope * Lambda)"
        );
        let massive: Vec<usize> = (0..fr.nodes.len())
            .filter(|&i| fr.nodes[i].mass > 0.0 || fr.nodes[i].inertia > 0.0)
            .collect();
        for (iv, r) in self.reading.intervals.iter().zip(&self.response.intervals) {
            let range = if iv.lambda_to.is_finite() {
                format!("[{}, {}]", fmt_g(iv.lambda_from), fmt_g(iv.lambda_to))
            } else {
                format!("[{}, inf)", fmt_g(iv.lambda_from))
            };
            if iv.rigid {
                let _ = writeln!(s, "  {range:<24} rigid (no plastic flow)");
                continue;
            }
            let acc: Vec<String> = iv
                .accelerating
                .iter()
                .map(|&g| self.group_label(g))
                .collect();
            let cr: Vec<String> = iv
                .constant_rate
                .iter()
                .map(|&g| self.group_label(g))
                .collect();
            let _ = writeln!(
                s,
                "  {range:<24} accelerating: {}{}   residual {:.1e}",
                acc.join(", "),
                if cr.is_empty() {
                    String::new()
                } else {
                    format!("; constant rate: {}", cr.join(", "))
                },
                r.residual.worst()
            );
            if massive.len() <= 8 {
                // round-off below 1e-12 of the largest coefficient prints as 0
                let slot = |i: usize| self.response.slot(i).unwrap_or(i);
                let scale = massive
                    .iter()
                    .flat_map(|&i| r.accelerations[slot(i)].iter().flatten().map(|v| v.abs()))
                    .fold(0.0f64, f64::max);
                let snap = |v: f64| if v.abs() <= 1e-12 * scale { 0.0 } else { v };
                for &i in &massive {
                    let a = r.accelerations[slot(i)];
                    let comps: Vec<String> = fr
                        .model
                        .components()
                        .iter()
                        .map(|c| (c, snap(a[c.index()][0]), snap(a[c.index()][1])))
                        .filter(|(_, b, sl)| *b != 0.0 || *sl != 0.0)
                        .map(|(c, b, sl)| {
                            let sign = if sl < 0.0 { "-" } else { "+" };
                            format!("{} = {} {sign} {} L", c.as_str(), fmt_g(b), fmt_g(sl.abs()))
                        })
                        .collect();
                    if !comps.is_empty() {
                        let _ =
                            writeln!(s, "  {:<24}   {}: {}", "", fr.nodes[i].id, comps.join(", "));
                    }
                }
            }
        }
        let t = &self.response.time;
        if let Some(&t_end) = t.times.last() {
            let _ = writeln!(s);
            let k = t.times.len() - 1;
            let mut far = (0usize, 0.0f64);
            for (i, d) in t.end_displacement.iter().enumerate() {
                let m = fr.model.translation_size(d);
                if m > far.1 {
                    far = (i, m);
                }
            }
            let d = t.end_displacement[far.0];
            let what = fr
                .model
                .translations()
                .iter()
                .map(|c| format!("{} = {}", c.as_str(), fmt_g(d[c.index()])))
                .collect::<Vec<_>>()
                .join(", ");
            let _ = writeln!(
                s,
                "at t = {} (lambda = {}): largest displacement at {}: {what}  [integration exact on each piece]",
                fmt_g(t_end),
                fmt_g(t.lambda[k]),
                fr.nodes[far.0].id,
            );
        }
        if !self.targets.is_empty() {
            let _ = writeln!(s);
            let _ = writeln!(s, "targets (first time the gap closes; velocity along the direction; kinetic energy of the whole structure)");
            for a in &self.targets {
                let tg = &a.target;
                let head = format!(
                    "  {} along [{}, {}, {}], gap {}:",
                    fr.nodes[tg.node].id,
                    fmt_g(tg.direction[0]),
                    fmt_g(tg.direction[1]),
                    fmt_g(tg.direction[2]),
                    fmt_g(tg.gap)
                );
                match (a.time, a.lambda, a.velocity, a.kinetic_energy) {
                    (Some(t), Some(l), Some(v), Some(e)) => {
                        let _ = writeln!(
                            s,
                            "{head} reached at t = {} (lambda = {}), velocity {}, kinetic energy {}{}",
                            fmt_g(t),
                            fmt_g(l),
                            fmt_g(v),
                            fmt_g(e),
                            if a.after_deactivation {
                                "  [after a deactivation: the path's response is not valid there]"
                            } else {
                                ""
                            }
                        );
                    }
                    _ => {
                        let _ = writeln!(
                            s,
                            "{head} not reached by t = {} (the analysed range)",
                            fmt_g(a.t_end)
                        );
                    }
                }
            }
        }
        s
    }

    /// The `targets` of the JSON report: one object per `[[target]]`.
    fn targets_json(&self) -> Value {
        let fr = &self.scene.frame;
        Value::Array(
            self.targets
                .iter()
                .map(|a| {
                    let opt = |x: Option<f64>| x.map(num).unwrap_or(Value::Null);
                    json!({
                        "node": fr.nodes[a.target.node].id,
                        "direction": a.target.direction,
                        "gap": num(a.target.gap),
                        "reached": a.reached,
                        "time": opt(a.time),
                        "lambda": opt(a.lambda),
                        "velocity": opt(a.velocity),
                        "kinetic_energy": opt(a.kinetic_energy),
                        "t_end": num(a.t_end),
                        "after_deactivation": a.after_deactivation,
                    })
                })
                .collect(),
        )
    }
}

/// Formats a number compactly (six significant digits).
pub fn format_number(x: f64) -> String {
    fmt_g(x)
}

/// One top-level entry of a [`JsonReport`]: a value, or a sequence whose
/// elements are built one at a time as they are written.
enum Part<'a> {
    Value(Value),
    Seq(Box<dyn Fn() -> Box<dyn Iterator<Item = Value> + 'a> + 'a>),
}

impl<'a> Part<'a> {
    fn seq<I: Iterator<Item = Value> + 'a>(f: impl Fn() -> I + 'a) -> Self {
        Part::Seq(Box::new(move || Box::new(f())))
    }
}

impl serde::Serialize for Part<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Part::Value(v) => v.serialize(s),
            Part::Seq(f) => s.collect_seq(f()),
        }
    }
}

/// The JSON report of an analysis, written part by part
/// ([`Analysis::json_report`]): `serde_json::to_writer` on it writes the
/// document of [`Analysis::to_json_selected`] holding one breakpoint, interval
/// or moment diagram at a time.
pub struct JsonReport<'a> {
    /// Sorted by key, as `serde_json::Map` (a `BTreeMap`) writes them.
    parts: Vec<(String, Part<'a>)>,
}

impl<'a> JsonReport<'a> {
    /// Adds (or replaces) a top-level key.
    pub fn insert(&mut self, key: &str, value: Value) {
        self.insert_part(key, Part::Value(value));
    }

    fn insert_part(&mut self, key: &str, part: Part<'a>) {
        match self.parts.binary_search_by(|(k, _)| k.as_str().cmp(key)) {
            Ok(i) => self.parts[i].1 = part,
            Err(i) => self.parts.insert(i, (key.to_string(), part)),
        }
    }
}

impl serde::Serialize for JsonReport<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = s.serialize_map(Some(self.parts.len()))?;
        for (k, v) in &self.parts {
            map.serialize_entry(k, v)?;
        }
        map.end()
    }
}
