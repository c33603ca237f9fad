//! The JSON document (`frames run SCENE --json`): [`Analysis::to_json`],
//! and [`JsonReport`], the same document written part by part.

use super::num;
use super::{HingeSets, OutputSelection};
use crate::analysis::Analysis;
use crate::hinge::{section_name, EventKind, HingeEvent};
use crate::response::TimeResponse;
use serde_json::{json, Map, Value};

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
        let (n_interval_sel, n_diagram_sel) = (interval_sel.len(), diagram_sel.len());
        let output = json!({
            "moments": sel.describe("Lambda values with moment distributions", n_diagram_sel, diagram_lambdas.len(), "--moments"),
            "interval_moments": sel.describe("intervals with moment pieces", n_interval_sel, interval_lambdas.len(), "--moments"),
            "nodes": sel.describe("nodes with accelerations and series", node_sel.len(), node_ids.len(), "--nodes"),
        });
        let mut output = output;
        if sel.hinge_sets == HingeSets::Changes {
            output["hinge_sets"] = json!(
                "changes per interval (hinge_changes: added/removed against the interval before; --hinge-sets full for the lists)"
            );
        }
        let mut report = JsonReport { parts: Vec::new() };
        for (key, part) in [
            ("scene", Part::Value(json!(self.scene.file))),
            ("title", Part::Value(json!(fr.title))),
            ("output", Part::Value(json!(output))),
            ("system", Part::Value(json!(self.system_json()))),
            ("solver", Part::Value(json!(self.solver_json()))),
            ("status", Part::Value(json!(self.solution.status.as_str()))),
            (
                "collapse_load",
                Part::Value(json!(self
                    .reading
                    .collapse_load()
                    .map(num)
                    .unwrap_or(Value::Null))),
            ),
            ("model", Part::Value(json!(fr.model.as_str()))),
            ("conventions", Part::Value(json!(conventions(fr.model)))),
            (
                "breakpoints",
                Part::seq(move || {
                    self.reading
                        .breakpoints
                        .iter()
                        .map(|b| self.breakpoint_json(b))
                }),
            ),
            ("hinges", Part::Value(json!(self.hinges_json()))),
            (
                "intervals",
                self.intervals_part(node_sel.clone(), interval_sel, sel.hinge_sets),
            ),
            ("moments_at_breakpoints", self.diagrams_part(diagram_sel)),
            ("targets", Part::Value(json!(self.targets_json()))),
            (
                "response",
                Part::Response(ResponsePart {
                    analysis: self,
                    nodes: node_sel.clone(),
                }),
            ),
        ] {
            report.insert_part(key, part);
        }
        Ok(report)
    }

    /// The `system` of the JSON report: sizes, what is left out, the model.
    fn system_json(&self) -> Value {
        let fr = &self.scene.frame;
        let sys = &self.system;
        let sz = sys.sizes();
        let lo = &sys.left_out;
        json!({
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
        })
    }

    /// The `solver` of the JSON report: method, pivots, residuals, certificate.
    fn solver_json(&self) -> Value {
        let info = &self.solution.info;
        json!({
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
        })
    }

    /// One entry of `breakpoints`: its `lambda` and events.
    fn breakpoint_json(&self, b: &crate::hinge::EventPoint) -> Value {
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
    }

    /// The `hinges`: each section's first yield.
    fn hinges_json(&self) -> Vec<Value> {
        self.reading
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
            .collect()
    }

    /// The nodes (and, for a single section, member and end) of groups `gs`.
    fn group_nodes(&self, gs: &[usize]) -> Vec<Value> {
        let (fr, sys) = (&self.scene.frame, &self.system);
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
    }

    /// The keys of the per-node series (the response's, the intervals'
    /// accelerations) in the order a `Map` writes them: the nodes `sel` by
    /// id, a node selected twice once, each with its slot in the response's
    /// node-indexed vectors; and the model's components by name, each with
    /// its slot in a node's six (a model's components are distinct).
    fn series_keys(&self, sel: &[usize]) -> SeriesKeys<'_> {
        let fr = &self.scene.frame;
        let mut nodes: Vec<(&str, usize)> = sel
            .iter()
            .map(|&i| (fr.nodes[i].id.as_str(), self.response.slot(i).unwrap_or(i)))
            .collect();
        nodes.sort_by(|a, b| a.0.cmp(b.0));
        nodes.dedup_by(|a, b| a.0 == b.0);
        let mut comps: Vec<(&'static str, usize)> = fr
            .model
            .components()
            .iter()
            .map(|c| (c.as_str(), c.index()))
            .collect();
        comps.sort();
        (nodes, comps)
    }

    /// The `intervals`, written one at a time (the part owns its
    /// selections, shared, as each pass of the serialiser makes a new
    /// iterator). Each entry is serialised straight from the reading and
    /// the response ([`IntervalEntry`]); only the hinge sets and the member
    /// forces of the selected intervals are built as values.
    fn intervals_part(
        &self,
        node_sel: Vec<usize>,
        interval_sel: Vec<usize>,
        hinge_sets: HingeSets,
    ) -> Part<'_> {
        // the accelerations' keys in the order a `Map` writes them
        let (nodes, comps) = self.series_keys(&node_sel);
        let shared = std::rc::Rc::new((node_sel, interval_sel, nodes, comps));
        Part::Intervals(Box::new(move || {
            let shared = shared.clone();
            let intervals = &self.reading.intervals;
            Box::new(
                intervals
                    .iter()
                    .zip(&self.response.intervals)
                    .enumerate()
                    .map(move |(k, (iv, r))| {
                        let (_, interval_sel, _, _) = &*shared;
                        let with_moments = interval_sel.binary_search(&k).is_ok();
                        let sets = self.interval_sets(k, hinge_sets);
                        IntervalEntry {
                            analysis: self,
                            iv,
                            r,
                            keys: shared.clone(),
                            with_moments,
                            sets,
                        }
                    }),
            )
        }))
    }

    /// The hinge sets of interval `k` (keys and values): the lists, or
    /// their changes against the interval before.
    fn interval_sets(&self, k: usize, hinge_sets: HingeSets) -> Vec<(&'static str, Value)> {
        let intervals = &self.reading.intervals;
        let iv = &intervals[k];
        match hinge_sets {
            HingeSets::Full => vec![
                (
                    "accelerating",
                    json!(self.group_nodes(&iv.accelerating.to_vec())),
                ),
                (
                    "constant_rate",
                    json!(self.group_nodes(&iv.constant_rate.to_vec())),
                ),
            ],
            HingeSets::Changes => {
                let before = k.checked_sub(1).map(|j| &intervals[j]);
                let change = |now: &[usize], was: Option<&[usize]>| {
                    let (added, removed) = set_changes(was.unwrap_or(&[]), now);
                    json!({
                        "added": self.group_nodes(&added),
                        "removed": self.group_nodes(&removed),
                    })
                };
                let acc = before.map(|b| b.accelerating.to_vec());
                let cr = before.map(|b| b.constant_rate.to_vec());
                vec![(
                    "hinge_changes",
                    json!({
                        "accelerating": change(&iv.accelerating.to_vec(), acc.as_deref()),
                        "constant_rate": change(&iv.constant_rate.to_vec(), cr.as_deref()),
                    }),
                )]
            }
        }
    }

    /// The member forces of one piece of an interval but its bending
    /// moments (`lambda_from`, `lambda_to`, `second_forces` and a space
    /// scene's other forces): the `moments` are written straight from the
    /// response beside them ([`WithEntry`], [`MemberMoments`]), not built.
    fn piece_forces(&self, p: &crate::response::MomentPiece) -> Map<String, Value> {
        let piece = &self.solution.pieces[p.piece];
        let mut o = json!({
            "lambda_from": num(p.lambda_from),
            "lambda_to": num(p.lambda_to),
            "second_forces": self.member_second_forces(piece, None),
        });
        self.add_space_forces(&mut o, piece, None);
        match o {
            Value::Object(m) => m,
            _ => Map::new(),
        }
    }

    /// The `moments_at_breakpoints` selected by `diagram_sel`, built one at a
    /// time as they are written.
    fn diagrams_part(&self, diagram_sel: Vec<usize>) -> Part<'_> {
        let diagram_sel = std::rc::Rc::new(diagram_sel);
        Part::Diagrams(Box::new(move || {
            let diagram_sel = diagram_sel.clone();
            Box::new(
                self.response
                    .moments_at_breakpoints
                    .iter()
                    .zip(self.reading.intervals.iter().filter(|i| !i.rigid))
                    .enumerate()
                    .filter(move |(k, _)| diagram_sel.binary_search(k).is_ok())
                    .map(|(_, x)| x)
                    .map(|(d, iv)| {
                        let piece = &self.solution.pieces[iv.piece_at(d.lambda)];
                        let mut o = json!({"lambda": num(d.lambda), "second_forces": self.member_second_forces(piece, Some(d.lambda))});
                        self.add_space_forces(&mut o, piece, Some((d.lambda, &d.moments)));
                        let values = match o {
                            Value::Object(m) => m,
                            _ => Map::new(),
                        };
                        // `members` written straight from the diagram
                        WithEntry {
                            values,
                            key: "members",
                            extra: MemberMoments {
                                frame: &self.scene.frame,
                                value: Box::new(move |k: usize| d.moments[k])
                                    as Box<dyn Fn(usize) -> f64 + '_>,
                            },
                        }
                    }),
            )
        }))
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
    /// (As a value: what [`MemberMoments`] writes.)
    fn member_moments<V: serde::Serialize + Copy>(&self, value: impl Fn(usize) -> V) -> Value {
        serde_json::to_value(MemberMoments {
            frame: &self.scene.frame,
            value,
        })
        .unwrap_or(Value::Null)
    }

    /// The per-member moments of `values` (one per section), written
    /// directly ([`MemberMoments`]).
    fn moments_by_member<'s, V: serde::Serialize + Copy>(
        &'s self,
        values: &'s [V],
    ) -> MemberMoments<'s, impl Fn(usize) -> V + 's> {
        MemberMoments {
            frame: &self.scene.frame,
            value: move |k: usize| values[k],
        }
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
        let second = self.system.second_force_indices();
        let mut out = Map::new();
        for m in &fr.members {
            let vals: Vec<Value> = m
                .elements
                .clone()
                .map(|e| match second[2 * e] {
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

/// The sign conventions of a model (`conventions` of the JSON report).
/// What `now` adds to `was` and what it removes from it; both sorted
/// (a reading pushes the groups of a set in increasing order), and so are
/// the two lists returned.
fn set_changes(was: &[usize], now: &[usize]) -> (Vec<usize>, Vec<usize>) {
    let (mut added, mut removed) = (Vec::new(), Vec::new());
    let (mut i, mut j) = (0, 0);
    loop {
        match (was.get(i), now.get(j)) {
            (None, None) => break,
            (Some(a), Some(b)) if a == b => {
                i += 1;
                j += 1;
            }
            (Some(a), Some(b)) if a > b => {
                added.push(*b);
                j += 1;
            }
            (Some(a), _) => {
                removed.push(*a);
                i += 1;
            }
            (None, Some(b)) => {
                added.push(*b);
                j += 1;
            }
        }
    }
    (added, removed)
}

fn conventions(model: crate::model::Model) -> &'static str {
    match model {
        crate::model::Model::Planar => "bending moments sagging-positive in each element's axes (local y = member direction turned 90 degrees counter-clockwise); sign of a section = sign of its moment at yield (for a facet of a yield polygon: the sign of the normal's bending component; the facet and its unit normal in (M/Mp, N/Np) are given); end = end of the element the section sits at; affine values are [base, slope] with value = base + slope * lambda",
        crate::model::Model::Grillage => "grillage in the x-y plane: z translation, right-handed rotations rx, ry; element axes x' along the member, y' turned 90 degrees counter-clockwise; bending moment about y' dual to the hinge rotation (from end: -(theta_a - psi), to end: theta_b - psi, psi = -(w_b - w_a)/h), torque right-handed about x'; each yield mode is a facet of the inscribed polygon in (M/Mp, T/Tp), given with its unit normal; sign = sign of the normal's bending component; affine values are [base, slope] with value = base + slope * lambda",
        crate::model::Model::Space => "space frame in global axes: translations x, y, z, right-handed rotations rx, ry, rz; element axes e1 along the member, e3 from its orientation (default z), e2 = e3 x e1; the moment about e3 (as the planar one: from end -(e3.th_a - e2.du/h), to end e3.th_b - e2.du/h) and about e2 (as the grillage's: from end -(e2.th_a + e3.du/h), to end e2.th_b + e3.du/h), the torque about e1; each yield mode is a facet of the inscribed polyhedron in (M2/Mp, M3/Mp, T/Tp), given with its unit normal (normal3); moment distributions give M3 (members), M2 (m2), the bending magnitude sqrt(M2^2 + M3^2) (bending: what meets the yield surface; at breakpoints only), the torques (second_forces) and the axial forces (axial_forces, tension positive) per element; affine values are [base, slope] with value = base + slope * lambda",
    }
}

/// One top-level entry of a [`JsonReport`]: a value, or a sequence whose
/// elements are built one at a time as they are written.
enum Part<'a> {
    Value(Value),
    Seq(Box<dyn Fn() -> Box<dyn Iterator<Item = Value> + 'a> + 'a>),
    Intervals(Box<IntervalIter<'a>>),
    Diagrams(Box<DiagramIter<'a>>),
    Response(ResponsePart<'a>),
}

/// What makes the iterator of the `moments_at_breakpoints` part.
type DiagramIter<'a> = dyn Fn() -> Box<dyn Iterator<Item = Diagram<'a>> + 'a> + 'a;

/// One entry of `moments_at_breakpoints`: its values but the moments,
/// and the moments written directly.
type Diagram<'a> = WithEntry<Map<String, Value>, MemberMoments<'a, Box<dyn Fn(usize) -> f64 + 'a>>>;

/// An object: the entries of `values` and `key: extra`, written in a
/// `Map`'s order (keys sorted; an entry of `values` under `key` is left
/// out), as the object holding all of them as values would be written,
/// without building `extra` as a value.
struct WithEntry<M, X> {
    values: M,
    key: &'static str,
    extra: X,
}

impl<M: std::borrow::Borrow<Map<String, Value>>, X: serde::Serialize> serde::Serialize
    for WithEntry<M, X>
{
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let values = self.values.borrow();
        let len = values.len() + usize::from(!values.contains_key(self.key));
        let mut m = s.serialize_map(Some(len))?;
        let mut written = false;
        for (k, v) in values {
            if !written && k.as_str() >= self.key {
                m.serialize_entry(self.key, &self.extra)?;
                written = true;
            }
            if k != self.key {
                m.serialize_entry(k, v)?;
            }
        }
        if !written {
            m.serialize_entry(self.key, &self.extra)?;
        }
        m.end()
    }
}

/// Per member (by id, in a `Map`'s order): `from`, `to` and `along`
/// (`[s, value]` at every element end), `value` per section; written as
/// the value [`Analysis::member_moments`] builds, without building it (a
/// 1000-element member is 2000 small arrays).
struct MemberMoments<'f, F> {
    frame: &'f crate::model::Frame,
    value: F,
}

impl<V: serde::Serialize, F: Fn(usize) -> V> serde::Serialize for MemberMoments<'_, F> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::{SerializeMap, SerializeSeq};
        let fr = self.frame;
        let value = &self.value;
        // sorted by id; of equal ids the last member (a map keeps the last
        // insert), the members being in scene order
        let mut order: Vec<usize> = (0..fr.members.len()).collect();
        order.sort_by(|&a, &b| fr.members[a].id.cmp(&fr.members[b].id));
        let order: Vec<usize> = order
            .iter()
            .enumerate()
            .filter(|&(i, &k)| {
                order
                    .get(i + 1)
                    .is_none_or(|&n| fr.members[n].id != fr.members[k].id)
            })
            .map(|(_, &k)| k)
            .collect();
        struct Along<'f, F>(&'f crate::model::Frame, std::ops::Range<usize>, &'f F);
        impl<V: serde::Serialize, F: Fn(usize) -> V> serde::Serialize for Along<'_, F> {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                let (fr, value) = (self.0, self.2);
                let mut seq = s.serialize_seq(Some(2 * self.1.len()))?;
                let mut at = 0.0;
                for e in self.1.clone() {
                    seq.serialize_element(&(at, value(2 * e)))?;
                    at += fr.elements[e].length;
                    seq.serialize_element(&(at, value(2 * e + 1)))?;
                }
                seq.end()
            }
        }
        struct Member<'f, F>(&'f crate::model::Frame, std::ops::Range<usize>, &'f F);
        impl<V: serde::Serialize, F: Fn(usize) -> V> serde::Serialize for Member<'_, F> {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                let (els, value) = (&self.1, self.2);
                let mut m = s.serialize_map(Some(3))?;
                m.serialize_entry("along", &Along(self.0, els.clone(), value))?;
                m.serialize_entry("from", &value(2 * els.start))?;
                m.serialize_entry("to", &value(2 * els.end - 1))?;
                m.end()
            }
        }
        let mut m = s.serialize_map(Some(order.len()))?;
        for k in order {
            let member = &fr.members[k];
            m.serialize_entry(&member.id, &Member(fr, member.elements.clone(), value))?;
        }
        m.end()
    }
}

/// The node keys and the component keys of [`Analysis::series_keys`].
type SeriesKeys<'a> = (Vec<(&'a str, usize)>, Vec<(&'static str, usize)>);

/// The `response` of the JSON report (keys in a `Map`'s order), its
/// series written straight from the time response.
struct ResponsePart<'a> {
    analysis: &'a Analysis,
    nodes: Vec<usize>,
}

impl serde::Serialize for ResponsePart<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let a = self.analysis;
        let t = &a.response.time;
        let (nodes, comps) = a.series_keys(&self.nodes);
        struct Series<'s>(&'s [Vec<[f64; 6]>], usize, &'s [(&'static str, usize)]);
        impl serde::Serialize for Series<'_> {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                struct Column<'c>(&'c [Vec<[f64; 6]>], usize, usize);
                impl serde::Serialize for Column<'_> {
                    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                        s.collect_seq(self.0.iter().map(|row| row[self.1][self.2]))
                    }
                }
                let mut m = s.serialize_map(Some(self.2.len()))?;
                for &(name, c) in self.2 {
                    m.serialize_entry(name, &Column(self.0, self.1, c))?;
                }
                m.end()
            }
        }
        struct Node<'s>(&'s TimeResponse, usize, &'s [(&'static str, usize)]);
        impl serde::Serialize for Node<'_> {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                let mut m = s.serialize_map(Some(2))?;
                m.serialize_entry(
                    "displacement",
                    &Series(&self.0.displacement, self.1, self.2),
                )?;
                m.serialize_entry("velocity", &Series(&self.0.velocity, self.1, self.2))?;
                m.end()
            }
        }
        struct Nodes<'s>(
            &'s TimeResponse,
            &'s [(&'s str, usize)],
            &'s [(&'static str, usize)],
        );
        impl serde::Serialize for Nodes<'_> {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                let mut m = s.serialize_map(Some(self.1.len()))?;
                for &(id, slot) in self.1 {
                    m.serialize_entry(id, &Node(self.0, slot, self.2))?;
                }
                m.end()
            }
        }
        let mut m = s.serialize_map(Some(5))?;
        m.serialize_entry("history", &t.history.describe())?;
        m.serialize_entry("lambda", &t.lambda)?;
        m.serialize_entry("method", t.method)?;
        m.serialize_entry("nodes", &Nodes(t, &nodes, &comps))?;
        m.serialize_entry("times", &t.times)?;
        m.end()
    }
}

/// What makes the iterator of the `intervals` part.
type IntervalIter<'a> = dyn Fn() -> Box<dyn Iterator<Item = IntervalEntry<'a>> + 'a> + 'a;

/// The node ids and accelerations' slots, and the components' names and
/// slots, sorted by name (with the node and interval selections).
type IntervalKeys<'a> = (
    Vec<usize>,
    Vec<usize>,
    Vec<(&'a str, usize)>,
    Vec<(&'static str, usize)>,
);

/// One entry of `intervals`, serialised as the object
/// [`Analysis::to_json_selected`] holds (keys in `Map`'s sorted order, the
/// same numbers) without building it.
struct IntervalEntry<'a> {
    analysis: &'a Analysis,
    iv: &'a crate::hinge::Interval,
    r: &'a crate::response::IntervalResponse,
    keys: std::rc::Rc<IntervalKeys<'a>>,
    with_moments: bool,
    sets: Vec<(&'static str, Value)>,
}

/// A number as `json!` writes it (null if not finite), or an object of
/// named numbers.
struct Num(f64);

impl serde::Serialize for Num {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        if self.0.is_finite() {
            s.serialize_f64(self.0)
        } else {
            s.serialize_unit()
        }
    }
}

/// The accelerations of the selected nodes in one interval.
struct Accelerations<'e, 'a>(&'e IntervalEntry<'a>);

impl serde::Serialize for Accelerations<'_, '_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        struct Node<'n>(&'n [[f64; 2]], &'n [(&'static str, usize)]);
        impl serde::Serialize for Node<'_> {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                let mut m = s.serialize_map(Some(self.1.len()))?;
                for &(name, c) in self.1 {
                    m.serialize_entry(name, &self.0[c])?;
                }
                m.end()
            }
        }
        let e = self.0;
        let (_, _, nodes, comps) = &*e.keys;
        let mut m = s.serialize_map(Some(nodes.len()))?;
        for &(id, slot) in nodes {
            m.serialize_entry(id, &Node(&e.r.accelerations[slot][..], comps))?;
        }
        m.end()
    }
}

impl serde::Serialize for IntervalEntry<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        enum Field<'f, 'a> {
            Value(&'f Value),
            Num(f64),
            Bool(bool),
            Acc(&'f IntervalEntry<'a>),
            Residual(&'f crate::response::IntervalResponse),
            Moments(&'f [crate::response::Affine]),
            Pieces(&'f [Map<String, Value>]),
        }
        // the member forces piece by piece (`pieces`), and at the
        // interval's level (`moments`, `second_forces`) only where one
        // piece holds the whole interval (null where the path pivots
        // inside it: no one affine field is right); the moments written
        // straight from the response
        let pieces: Vec<Map<String, Value>> = if self.with_moments {
            self.r
                .pieces
                .iter()
                .map(|p| self.analysis.piece_forces(p))
                .collect()
        } else {
            Vec::new()
        };
        let null = Value::Null;
        let (moments, second_forces) = match (pieces.as_slice(), self.r.pieces.as_slice()) {
            ([one], [p]) => (
                Field::Moments(&p.moments[..]),
                Field::Value(one.get("second_forces").unwrap_or(&null)),
            ),
            _ => (Field::Value(&null), Field::Value(&null)),
        };
        let mut fields: Vec<(&str, Field<'_, '_>)> = vec![
            ("lambda_from", Field::Num(self.iv.lambda_from)),
            ("lambda_to", Field::Num(self.iv.lambda_to)),
            ("rigid", Field::Bool(self.iv.rigid)),
            ("accelerations", Field::Acc(self)),
            ("moments", moments),
            ("second_forces", second_forces),
            ("pieces", Field::Pieces(&pieces)),
            ("residual", Field::Residual(self.r)),
        ];
        fields.extend(self.sets.iter().map(|(k, v)| (*k, Field::Value(v))));
        fields.sort_by(|a, b| a.0.cmp(b.0));
        let mut m = s.serialize_map(Some(fields.len()))?;
        for (k, f) in &fields {
            match f {
                Field::Value(v) => m.serialize_entry(k, v)?,
                Field::Num(x) => m.serialize_entry(k, &Num(*x))?,
                Field::Bool(b) => m.serialize_entry(k, b)?,
                Field::Acc(e) => m.serialize_entry(k, &Accelerations(e))?,
                Field::Moments(v) => m.serialize_entry(k, &self.analysis.moments_by_member(v))?,
                Field::Pieces(p) => {
                    struct Pieces<'p>(&'p [Map<String, Value>], &'p IntervalEntry<'p>);
                    impl serde::Serialize for Pieces<'_> {
                        fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                            s.collect_seq(self.0.iter().zip(&self.1.r.pieces).map(|(values, p)| {
                                WithEntry {
                                    values,
                                    key: "moments",
                                    extra: self.1.analysis.moments_by_member(&p.moments[..]),
                                }
                            }))
                        }
                    }
                    m.serialize_entry(k, &Pieces(p, self))?
                }
                Field::Residual(r) => {
                    struct Res<'r>(&'r plcp::Residual);
                    impl serde::Serialize for Res<'_> {
                        fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                            let mut m = s.serialize_map(Some(3))?;
                            m.serialize_entry("complementarity", &Num(self.0.complementarity))?;
                            m.serialize_entry("equation", &Num(self.0.equation))?;
                            m.serialize_entry("feasibility", &Num(self.0.feasibility))?;
                            m.end()
                        }
                    }
                    m.serialize_entry(k, &Res(&r.residual))?
                }
            }
        }
        m.end()
    }
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
            Part::Intervals(f) => s.collect_seq(f()),
            Part::Diagrams(f) => s.collect_seq(f()),
            Part::Response(r) => r.serialize(s),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Frame, Scene};

    /// The moment distribution as the report built it before
    /// [`MemberMoments`] (a `Value` per member, per element end).
    fn built<V: serde::Serialize + Copy>(fr: &Frame, value: impl Fn(usize) -> V) -> Value {
        let mut out = Map::new();
        for m in &fr.members {
            let mut along = Vec::new();
            let mut s = 0.0;
            for e in m.elements.clone() {
                along.push(json!([s, value(2 * e)]));
                s += fr.elements[e].length;
                along.push(json!([s, value(2 * e + 1)]));
            }
            out.insert(
                m.id.clone(),
                json!({"from": value(2 * m.elements.start), "to": value(2 * m.elements.end - 1), "along": along}),
            );
        }
        Value::Object(out)
    }

    /// Values per section with the cases a distribution meets: signs, a
    /// negative zero, a NaN and infinities (written as null).
    fn value(k: usize) -> f64 {
        match k % 7 {
            0 => -0.0,
            3 if k % 2 == 1 => f64::NAN,
            5 if k % 3 == 0 => f64::INFINITY,
            5 => f64::NEG_INFINITY,
            _ => (k as f64) * 0.37 - 1.0 / (1.0 + k as f64),
        }
    }

    /// [`MemberMoments`] writes the bytes of the values it replaces, compact
    /// and pretty, for the members of every scene (ids sorted apart from
    /// scene order in the portals and frames), with plain and affine
    /// values; [`WithEntry`] writes the object holding the same entries.
    #[test]
    fn member_moments_write_the_values_they_replace() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
        let mut checked = 0;
        for dir in [root.clone(), root.join("pipe-whip"), root.join("stiff")] {
            for e in std::fs::read_dir(dir).unwrap() {
                let path = e.unwrap().path();
                if path.extension().is_none_or(|x| x != "toml") {
                    continue;
                }
                let fr = Scene::from_file(&path).unwrap().frame;
                let name = path.display().to_string();
                let plain = MemberMoments { frame: &fr, value };
                let affine = MemberMoments {
                    frame: &fr,
                    value: |k: usize| [value(k), value(k + 3)],
                };
                let (bp, ba) = (built(&fr, value), built(&fr, |k| [value(k), value(k + 3)]));
                for (ours, theirs) in [
                    (serde_json::to_string(&plain), serde_json::to_string(&bp)),
                    (serde_json::to_string(&affine), serde_json::to_string(&ba)),
                    (
                        serde_json::to_string_pretty(&plain),
                        serde_json::to_string_pretty(&bp),
                    ),
                    (
                        serde_json::to_string_pretty(&affine),
                        serde_json::to_string_pretty(&ba),
                    ),
                ] {
                    assert_eq!(ours.unwrap(), theirs.unwrap(), "{name}");
                }
                assert_eq!(serde_json::to_value(&plain).unwrap(), bp, "{name}");
                // an object of values and the moments under a key between,
                // before and after theirs
                for key in ["members", "a", "zz", "lambda"] {
                    let mut values = Map::new();
                    values.insert("lambda".into(), json!(1.5));
                    values.insert("second_forces".into(), json!({}));
                    let mut whole = values.clone();
                    whole.insert(key.into(), bp.clone());
                    let ours = WithEntry {
                        values: &values,
                        key,
                        extra: MemberMoments { frame: &fr, value },
                    };
                    assert_eq!(
                        serde_json::to_string_pretty(&ours).unwrap(),
                        serde_json::to_string_pretty(&Value::Object(whole)).unwrap(),
                        "{name} {key}"
                    );
                }
                checked += 1;
            }
        }
        assert!(checked >= 20, "{checked}");
    }
}
