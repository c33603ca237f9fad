//! Reading a scene in stages ([`Scene::from_toml_with`]).

use super::*;

/// The stages of reading a scene ([`Scene::from_toml_with`]), in order:
/// nodes, the reduction of a space scene, members, arcs, supports and
/// masses, loads, then the history and the targets.
pub(super) struct Reader<'a> {
    pub(super) src: &'a str,
    pub(super) file: &'a str,
    pub(super) options: ReadOptions,
    pub(super) raw: RawScene,
    pub(super) cx: Ctx<'a>,
    pub(super) frame: Frame,
    pub(super) ids: HashMap<String, usize>,
    pub(super) node_lines: HashMap<usize, usize>,
    pub(super) load_lines: HashMap<(usize, usize), usize>,
    pub(super) space: bool,
    pub(super) model: Model,
    pub(super) zs: Vec<f64>,
    pub(super) default_facets: usize,
    pub(super) member_ids: HashMap<String, ()>,
}

/// The node named by `s` in a `table`, or an error naming it.
pub(super) fn node_ref(
    cx: &Ctx<'_>,
    ids: &HashMap<String, usize>,
    s: &Spanned<String>,
    table: &str,
) -> Result<usize, FramesError> {
    match ids.get(s.get_ref().trim()) {
        Some(&i) => Ok(i),
        None => cx.err(
            s.span(),
            format!("{table} node"),
            format!("unknown node \"{}\"", s.get_ref()),
        ),
    }
}

impl<'a> Reader<'a> {
    /// Parses the TOML and reads the model kind.
    pub(super) fn new(
        src: &'a str,
        file: &'a str,
        options: ReadOptions,
    ) -> Result<Reader<'a>, FramesError> {
        let raw: RawScene = toml::from_str(src).map_err(|e| toml_error(src, file, e))?;
        let cx = Ctx { src, file };
        let frame = Frame {
            title: raw.title.clone().unwrap_or_default(),
            ..Frame::default()
        };
        let ids: HashMap<String, usize> = HashMap::new();
        let node_lines = HashMap::new();
        let space = raw
            .model
            .as_ref()
            .is_some_and(|m| m.get_ref().trim() == "space");
        let model = match &raw.model {
            None => Model::Planar,
            Some(_) if space => Model::Planar,
            Some(m) => match Model::from_name(m.get_ref().trim()) {
                Some(kind) => kind,
                None => {
                    let other = m.get_ref().trim();
                    return cx.err(
                        m.span(),
                        "model",
                        format!("unknown model \"{other}\": expected \"planar\", \"grillage\" or \"space\""),
                    );
                }
            },
        };
        Ok(Reader {
            src,
            file,
            options,
            raw,
            cx,
            frame,
            ids,
            node_lines,
            load_lines: HashMap::new(),
            space,
            model,
            zs: Vec::new(),
            default_facets: DEFAULT_FACETS,
            member_ids: HashMap::new(),
        })
    }

    /// The `[[node]]`s.
    pub(super) fn nodes(&mut self) -> Result<(), FramesError> {
        let (src, space) = (self.src, self.space);
        let Reader {
            raw,
            cx,
            frame,
            ids,
            node_lines,
            zs,
            ..
        } = self;
        zs.reserve(raw.node.len());
        for n in &raw.node {
            let n = n.get_ref();
            let id = n.id.get_ref().trim().to_string();
            if id.is_empty() {
                return cx.err(n.id.span(), "node id", "must not be empty");
            }
            if ids.contains_key(&id) {
                return cx.err(
                    n.id.span(),
                    format!("node \"{id}\" id"),
                    format!("duplicate node id \"{id}\""),
                );
            }
            let x = cx.finite(&n.x, format!("node \"{id}\" x"))?;
            let y = cx.finite(&n.y, format!("node \"{id}\" y"))?;
            match (&n.z, space) {
                (Some(z), true) => zs.push(cx.finite(z, format!("node \"{id}\" z"))?),
                (None, true) => {
                    return cx.err(
                        n.id.span(),
                        format!("node \"{id}\" z"),
                        "a node of a space scene needs z",
                    )
                }
                (Some(z), false) => {
                    return cx.err(
                        z.span(),
                        format!("node \"{id}\" z"),
                        "a key of space scenes only (model = \"space\")",
                    )
                }
                (None, false) => {}
            }
            ids.insert(id.clone(), frame.nodes.len());
            node_lines.insert(frame.nodes.len(), line_of(src, n.id.span().start));
            frame.nodes.push(Node {
                id,
                x,
                y,
                z: 0.0,
                fixed: [false; 6],
                mass: 0.0,
                inertia: 0.0,
                load: [0.0; 6],
                generated: false,
            });
        }
        Ok(())
    }

    /// A space scene: the plane sought and the model it is solved as; the
    /// default number of facets.
    pub(super) fn reduce(&mut self) -> Result<(), FramesError> {
        let options = self.options;
        let space = self.space;
        let Reader {
            raw,
            cx,
            frame,
            model,
            zs,
            ..
        } = self;
        if space {
            let loads = raw
                .load
                .iter()
                .map(|l| {
                    let l = l.get_ref();
                    let v = |k: &str| l.key(k).map_or(0.0, |v| *v.get_ref());
                    ([v("fx"), v("fy"), v("fz")], [v("mx"), v("my"), v("mz")])
                })
                .filter(|l| l.0.iter().chain(&l.1).all(|v| v.is_finite()))
                .collect::<Vec<_>>();
            let mut points: Vec<[f64; 3]> = frame
                .nodes
                .iter()
                .zip(zs.iter())
                .map(|(n, &z)| [n.x, n.y, z])
                .collect();
            // the arcs' points are part of the geometry whose plane is sought
            for a in &raw.arc {
                points.extend(a.get_ref().space_points().unwrap_or_default());
            }
            let span = raw.model.as_ref().map_or(0..0, |m| m.span());
            if points.is_empty() {
                return cx.err(span, "node", "the scene has no [[node]]");
            }
            let reduced = if options.reduce_space {
                crate::space::reduce(&points, &loads)
            } else {
                crate::space::general(
                    &points,
                    "the reduction is switched off (ReadOptions::reduce_space = false)",
                )
            };
            let r = match reduced {
                Ok(r) => r,
                Err(why) => return cx.err(span, "model", why),
            };
            if !r.global_axes {
                for (n, p) in frame.nodes.iter_mut().zip(&points) {
                    let l = r.to_local(*p);
                    (n.x, n.y) = (l[0], l[1]);
                }
            }
            if r.kind == Model::Space {
                for (n, p) in frame.nodes.iter_mut().zip(&points) {
                    n.z = p[2];
                }
            }
            *model = r.kind;
            frame.reduction = Some(r);
        }
        frame.model = *model;
        self.default_facets = match raw
            .yield_table
            .as_ref()
            .and_then(|y| y.get_ref().facets.as_ref())
        {
            Some(f) => cx.facets(f, "yield facets")?,
            None => DEFAULT_FACETS,
        };
        Ok(())
    }

    /// The `[[member]]`s.
    pub(super) fn members(&mut self) -> Result<(), FramesError> {
        let (space, default_facets) = (self.space, self.default_facets);
        let Reader {
            raw,
            cx,
            frame,
            ids,
            model,
            member_ids,
            ..
        } = self;
        let model = *model;
        for m in &raw.member {
            let m = m.get_ref();
            let id = claim_id(cx, member_ids, &m.id, "member", "")?;
            let lookup = |s: &Spanned<String>, key: &str| -> Result<usize, FramesError> {
                match ids.get(s.get_ref().trim()) {
                    Some(&i) if !frame.nodes[i].generated => Ok(i),
                    _ => cx.err(
                        s.span(),
                        format!("member \"{id}\" {key}"),
                        format!("unknown node \"{}\"", s.get_ref()),
                    ),
                }
            };
            let from = lookup(&m.from, "from")?;
            let to = lookup(&m.to, "to")?;
            let mut keys = strength_keys!(m);
            if space {
                keys =
                    cx.space_keys(model, &format!("member \"{id}\""), "a member", &m.id, keys)?;
            }
            let orientation = match (&m.orientation, space) {
                (None, _) => None,
                (Some(o), false) => {
                    return cx.err(
                        o.span(),
                        format!("member \"{id}\" orientation"),
                        "a key of space scenes only (model = \"space\")",
                    )
                }
                (Some(o), true) => {
                    let v = o.get_ref();
                    if v.len() != 3 || v.iter().any(|x| !x.is_finite() || x.abs() > 1e100) {
                        return cx.err(
                            o.span(),
                            format!("member \"{id}\" orientation"),
                            format!("must be three finite numbers [vx, vy, vz], got {v:?}"),
                        );
                    }
                    let g = [v[0], v[1], v[2]];
                    // a reduced scene's axes are those of its plane
                    Some((
                        frame.reduction.as_ref().map_or(g, |r| r.to_local(g)),
                        o.span(),
                    ))
                }
            };
            let (mp, interaction, mu) = cx.strength(
                model,
                &format!("member \"{id}\""),
                &m.id,
                keys,
                default_facets,
            )?;
            let n = match &m.elements {
                Some(v) => cx.element_count(v, &format!("member \"{id}\" elements"))?,
                None => 1,
            };
            let (a, b) = (&frame.nodes[from], &frame.nodes[to]);
            let (dx, dy, dz) = (b.x - a.x, b.y - a.y, b.z - a.z);
            let length = if model == Model::Space {
                (dx * dx + dy * dy + dz * dz).sqrt()
            } else {
                dx.hypot(dy)
            };
            if length.is_nan() || length <= 0.0 || !length.is_finite() {
                return cx.err(
                    m.to.span(),
                    format!("member \"{id}\" to"),
                    format!(
                        "member of zero length (nodes \"{}\" and \"{}\" coincide)",
                        a.id, b.id
                    ),
                );
            }
            let (ax, ay, az) = (a.x, a.y, a.z);
            // the chain of nodes, generating the inner ones
            let mut chain = vec![from];
            for k in 1..n {
                let gid = format!("{id}.{k}");
                let t = k as f64 / n as f64;
                // exact at the ends of axis-parallel members: dx or dy is exactly zero
                let i = cx.generate_node(
                    frame,
                    ids,
                    gid,
                    (ax + t * dx, ay + t * dy, az + t * dz),
                    true,
                    m.elements.as_ref().map(|e| e.span()).unwrap_or(m.id.span()),
                    &format!("member \"{id}\" elements"),
                )?;
                chain.push(i);
            }
            chain.push(to);
            // equal elements share the member's direction: exact zeros for
            // axis-parallel members keep decoupled parts decoupled
            let dirs = vec![(length / n as f64, dx / length, dy / length); n];
            let axes = if model == Model::Space {
                let e1 = [dx / length, dy / length, dz / length];
                let (v, span) = match orientation {
                    Some((v, span)) => (Some(v), span),
                    None => (None, m.id.span()),
                };
                match crate::space::element_axes(e1, v) {
                    Ok(axes) => Some(axes),
                    Err(why) => return cx.err(span, format!("member \"{id}\" orientation"), why),
                }
            } else {
                None
            };
            let axes: Vec<[[f64; 3]; 3]> = axes.map_or_else(Vec::new, |a| vec![a; n]);
            push_member(frame, id, chain, &dirs, &axes, mp, interaction, mu);
        }
        Ok(())
    }

    /// The `[[arc]]`s: the strength (as a member's), the plane
    /// ([`arc_plane`]), the points, and the node chain and elements
    /// ([`ArcChain`]).
    pub(super) fn arcs(&mut self) -> Result<(), FramesError> {
        let (space, default_facets) = (self.space, self.default_facets);
        let Reader {
            raw,
            cx,
            frame,
            ids,
            model,
            member_ids,
            ..
        } = self;
        let model = *model;
        for arc in &raw.arc {
            let r = arc.get_ref();
            let id = claim_id(
                cx,
                member_ids,
                &r.id,
                "arc",
                " (arcs and members share ids)",
            )?;
            let table = format!("arc \"{id}\"");
            let mut keys = strength_keys!(r);
            if space {
                keys = cx.space_keys(model, &table, "an arc", &r.id, keys)?;
            }
            let (mp, interaction, mu) = cx.strength(model, &table, &r.id, keys, default_facets)?;
            let centre = r.centre.get_ref();
            let dims = if space { 3 } else { 2 };
            if centre.len() != dims || centre.iter().any(|v| !v.is_finite() || v.abs() > 1e100) {
                let what = if space {
                    "three finite numbers [x, y, z] (model = \"space\")"
                } else {
                    "two finite numbers [x, y]"
                };
                return cx.err(
                    r.centre.span(),
                    format!("{table} centre"),
                    format!("must be {what}, got {centre:?}"),
                );
            }
            let (normal, arc_axes) = arc_plane(cx, r, &table, space)?;
            let radius = cx.positive(&r.radius, format!("{table} radius"))?;
            let a0 = cx.finite(&r.start_angle, format!("{table} start_angle"))?;
            let a1 = cx.finite(&r.end_angle, format!("{table} end_angle"))?;
            let sweep = a1 - a0;
            if sweep == 0.0 || sweep.abs() >= 360.0 {
                return cx.err(
                    r.end_angle.span(),
                    format!("{table} end_angle"),
                    format!("the arc must sweep more than 0 and less than 360 degrees, got {sweep} (from {a0} to {a1})"),
                );
            }
            let n = cx.element_count(&r.elements, &format!("{table} elements"))?;
            let general = model == Model::Space;
            let reduction = frame.reduction.clone();
            let point = |k: usize| {
                if space {
                    let angle = a0 + sweep * k as f64 / n as f64;
                    let c = [centre[0], centre[1], centre[2]];
                    let p = crate::space::arc_point(c, radius, arc_axes, angle);
                    if general {
                        return (p[0], p[1], p[2]);
                    }
                    let l = reduction.as_ref().map_or(p, |r| r.to_local(p));
                    return (l[0], l[1], 0.0);
                }
                let t = (a0 + sweep * k as f64 / n as f64).to_radians();
                let (s, c) = t.sin_cos();
                (centre[0] + radius * c, centre[1] + radius * s, 0.0)
            };
            let arc = ArcChain {
                raw: r,
                id: &id,
                table: &table,
                points: (0..=n).map(point).collect(),
                radius,
                general,
                normal,
            };
            let chain = arc.nodes(cx, frame, ids)?;
            let (dirs, axes) = arc.elements(cx, frame, &chain)?;
            push_member(frame, id, chain, &dirs, &axes, mp, interaction, mu);
        }
        Ok(())
    }

    /// The `[[support]]`s and `[[mass]]`es.
    pub(super) fn supports_and_masses(&mut self) -> Result<(), FramesError> {
        let Reader {
            raw,
            cx,
            frame,
            ids,
            model,
            ..
        } = self;
        let model = *model;
        let node_ref = |s: &Spanned<String>, table: &str| node_ref(cx, ids, s, table);
        let mut supported: HashMap<usize, ()> = HashMap::new();
        for s in &raw.support {
            let s = s.get_ref();
            let i = node_ref(&s.node, "support")?;
            let nid = frame.nodes[i].id.clone();
            if supported.insert(i, ()).is_some() {
                return cx.err(s.node.span(), format!("support \"{nid}\" node"), format!("a second [[support]] for node \"{nid}\" (list every fixed component in one)"));
            }
            if let Some(r) = &frame.reduction {
                const SIX: [&str; 6] = ["x", "y", "z", "rx", "ry", "rz"];
                let mut fixed = [false; 6];
                for c in s.fix.get_ref() {
                    let Some(k) = SIX.iter().position(|k| *k == c.get_ref().as_str()) else {
                        return cx.err(
                            c.span(),
                            format!("support \"{nid}\" fix"),
                            format!("unknown component \"{}\": expected \"x\", \"y\", \"z\", \"rx\", \"ry\" or \"rz\" (model = \"space\")", c.get_ref()),
                        );
                    };
                    fixed[k] = true;
                }
                match crate::space::local_fixed(r, fixed) {
                    Ok(f) => frame.nodes[i].fixed = f,
                    Err(why) => return cx.err(s.fix.span(), format!("support \"{nid}\" fix"), why),
                }
                continue;
            }
            let comps = model.components();
            for c in s.fix.get_ref() {
                let Some(k) = comps.iter().find(|k| k.as_str() == c.get_ref().as_str()) else {
                    let other = c.get_ref();
                    let names: Vec<&str> = comps.iter().map(|k| k.as_str()).collect();
                    let (a, b, d) = (names[0], names[1], names[2]);
                    let hint = model.support_hint();
                    return cx.err(
                        c.span(),
                        format!("support \"{nid}\" fix"),
                        format!("unknown component \"{other}\": expected \"{a}\", \"{b}\" or \"{d}\"{hint}"),
                    );
                };
                frame.nodes[i].fixed[k.index()] = true;
            }
        }
        for m in &raw.mass {
            let m = m.get_ref();
            let i = node_ref(&m.node, "mass")?;
            let nid = frame.nodes[i].id.clone();
            if let Some(v) = &m.m {
                frame.nodes[i].mass += cx.nonnegative(v, format!("mass \"{nid}\" m"))?;
            }
            if let Some(v) = &m.j {
                frame.nodes[i].inertia += cx.nonnegative(v, format!("mass \"{nid}\" j"))?;
            }
        }
        Ok(())
    }

    /// The `[[load]]`s.
    pub(super) fn loads(&mut self) -> Result<(), FramesError> {
        let src = self.src;
        let Reader {
            raw,
            cx,
            frame,
            ids,
            load_lines,
            model,
            ..
        } = self;
        let model = *model;
        let node_ref = |s: &Spanned<String>, table: &str| node_ref(cx, ids, s, table);
        for l in &raw.load {
            let l = l.get_ref();
            let i = node_ref(&l.node, "load")?;
            let nid = frame.nodes[i].id.clone();
            if let Some(r) = &frame.reduction {
                let mut v = [0.0; 6];
                for (k, name) in ["fx", "fy", "fz", "mx", "my", "mz"].into_iter().enumerate() {
                    if let Some(x) = l.key(name) {
                        v[k] = cx.finite(x, format!("load \"{nid}\" {name}"))?;
                        let line = line_of(src, x.span().start);
                        for c in 0..6 {
                            load_lines.entry((i, c)).or_insert(line);
                        }
                    }
                }
                let local = crate::space::local_load(r, ([v[0], v[1], v[2]], [v[3], v[4], v[5]]));
                for (k, x) in local.into_iter().enumerate() {
                    frame.nodes[i].load[k] += x;
                }
                continue;
            }
            for name in model.foreign_load_keys() {
                if let Some(v) = l.key(name) {
                    let keys = model.load_keys();
                    let (a, b, c) = (keys[0], keys[1], keys[2]);
                    return cx.err(
                        v.span(),
                        format!("load \"{nid}\" {name}"),
                        format!(
                            "not a load of a {} scene (model = \"{}\": {a}, {b}, {c})",
                            model.as_str(),
                            model.as_str()
                        ),
                    );
                }
            }
            for (&name, comp) in model.load_keys().iter().zip(model.components()) {
                let k = comp.index();
                if let Some(v) = l.key(name) {
                    load_lines
                        .entry((i, k))
                        .or_insert_with(|| line_of(src, v.span().start));
                    frame.nodes[i].load[k] += cx.finite(v, format!("load \"{nid}\" {name}"))?;
                }
            }
        }
        Ok(())
    }

    /// The history and the `[[target]]`s; the scene, checked.
    pub(super) fn finish(self) -> Result<Scene, FramesError> {
        let Reader {
            file,
            raw,
            cx,
            frame,
            ids,
            node_lines,
            load_lines,
            model,
            ..
        } = self;
        let node_ref = |s: &Spanned<String>, table: &str| node_ref(&cx, &ids, s, table);
        let history = match &raw.history {
            None => History::default(),
            Some(h) => parse_history(&cx, h)?,
        };
        let mut targets = Vec::with_capacity(raw.target.len());
        for t in &raw.target {
            let t = t.get_ref();
            let node = node_ref(&t.node, "target")?;
            targets.push(parse_target(
                &cx,
                model,
                frame.reduction.as_ref(),
                &frame.nodes[node].id,
                node,
                t,
            )?);
        }
        if frame.members.is_empty() {
            return cx.err(0..0, "member", "the scene has no [[member]]");
        }
        let scene = Scene {
            file: file.to_string(),
            frame,
            history,
            load_lines,
            node_lines,
            targets,
        };
        scene.check_mechanics()?;
        Ok(scene)
    }
}

/// The strength keys of a `[[member]]` or an `[[arc]]` (the same names).
macro_rules! strength_keys {
    ($raw:expr) => {
        Keys {
            plastic_moment: &$raw.plastic_moment,
            plastic_torque: $raw.plastic_torque.as_ref(),
            plastic_axial: $raw.plastic_axial.as_ref(),
            facets: $raw.facets.as_ref(),
            mass_per_length: $raw.mass_per_length.as_ref(),
        }
    };
}
use strength_keys;

/// The id of a `[[member]]` or an `[[arc]]` (`kind`), trimmed: an error when
/// empty or taken by another member or arc (`note` ends that message).
fn claim_id(
    cx: &Ctx,
    member_ids: &mut HashMap<String, ()>,
    raw: &Spanned<String>,
    kind: &str,
    note: &str,
) -> Result<String, FramesError> {
    let id = raw.get_ref().trim().to_string();
    if id.is_empty() {
        return cx.err(raw.span(), format!("{kind} id"), "must not be empty");
    }
    if member_ids.insert(id.clone(), ()).is_some() {
        return cx.err(
            raw.span(),
            format!("{kind} \"{id}\" id"),
            format!("duplicate member id \"{id}\"{note}"),
        );
    }
    Ok(id)
}

/// A space arc's plane: its unit normal (global; `[0, 0, 1]` in a planar
/// scene) and its in-plane axes, from the keys `normal` and `reference`.
#[allow(clippy::type_complexity)]
fn arc_plane(
    cx: &Ctx,
    r: &RawArc,
    table: &str,
    space: bool,
) -> Result<([f64; 3], ([f64; 3], [f64; 3])), FramesError> {
    // a space arc: its plane's normal (global), in-plane axes
    let normal = match (&r.normal, space) {
        (Some(n), false) => {
            return cx.err(
                n.span(),
                format!("{table} normal"),
                "a key of space scenes only (model = \"space\")",
            )
        }
        (Some(n), true) => match crate::space::unit_of(n.get_ref()) {
            Some(u) => u,
            None => {
                return cx.err(
                    n.span(),
                    format!("{table} normal"),
                    format!(
                        "must be three finite numbers [nx, ny, nz], not all zero, got {:?}",
                        n.get_ref()
                    ),
                )
            }
        },
        (None, _) => [0.0, 0.0, 1.0],
    };
    let reference = match (&r.reference, space) {
        (Some(g), false) => {
            return cx.err(
                g.span(),
                format!("{table} reference"),
                "a key of space scenes only (model = \"space\")",
            )
        }
        (Some(g), true) => match crate::space::unit_of(g.get_ref()) {
            Some(u) => Some((u, g.span())),
            None => {
                return cx.err(
                    g.span(),
                    format!("{table} reference"),
                    format!(
                        "must be three finite numbers, not all zero, got {:?}",
                        g.get_ref()
                    ),
                )
            }
        },
        (None, _) => None,
    };
    let Some(arc_axes) = crate::space::arc_axes(normal, reference.as_ref().map(|g| g.0)) else {
        let span = reference.map_or(r.id.span(), |g| g.1);
        return cx.err(
            span,
            format!("{table} reference"),
            "the reference direction is along the normal: give one in the arc's plane",
        );
    };
    Ok((normal, arc_axes))
}

/// An arc's points and what its node chain needs to be read.
struct ArcChain<'a> {
    raw: &'a RawArc,
    id: &'a str,
    /// `arc "id"`, the start of its keys' names in messages.
    table: &'a str,
    /// The `n + 1` points of the chain, start to end.
    points: Vec<(f64, f64, f64)>,
    radius: f64,
    /// The general space model (not reduced to a plane).
    general: bool,
    normal: [f64; 3],
}

impl ArcChain<'_> {
    /// The node chain: the given end nodes (checked to lie on the arc's
    /// ends) and generated nodes at the other points.
    fn nodes(
        &self,
        cx: &Ctx,
        frame: &mut Frame,
        ids: &mut HashMap<String, usize>,
    ) -> Result<Vec<usize>, FramesError> {
        let ArcChain {
            raw: r,
            id,
            table,
            radius,
            general,
            ..
        } = *self;
        let n = self.points.len() - 1;
        let mut chain = Vec::with_capacity(n + 1);
        for k in 0..=n {
            let end = if k == 0 {
                Some((&r.from, "from"))
            } else if k == n {
                Some((&r.to, "to"))
            } else {
                None
            };
            let p = self.points[k];
            if let Some((Some(node), key)) = end {
                let i = match ids.get(node.get_ref().trim()) {
                    Some(&i) if !frame.nodes[i].generated => i,
                    _ => {
                        return cx.err(
                            node.span(),
                            format!("{table} {key}"),
                            format!("unknown node \"{}\"", node.get_ref()),
                        )
                    }
                };
                let nd = &frame.nodes[i];
                let off = if general {
                    (nd.x - p.0).hypot(nd.y - p.1).hypot(nd.z - p.2)
                } else {
                    (nd.x - p.0).hypot(nd.y - p.1)
                };
                if off > 1e-9 * radius.max(p.0.abs()).max(p.1.abs()).max(p.2.abs()) {
                    return cx.err(
                        node.span(),
                        format!("{table} {key}"),
                        format!(
                            "node \"{}\" at ({}, {}) is not the arc's {} point ({}, {})",
                            nd.id,
                            nd.x,
                            nd.y,
                            if k == 0 { "start" } else { "end" },
                            p.0,
                            p.1
                        ),
                    );
                }
                chain.push(i);
            } else {
                let i = cx.generate_node(
                    frame,
                    ids,
                    format!("{id}.{k}"),
                    p,
                    end.is_none(),
                    r.elements.span(),
                    &format!("{table} elements"),
                )?;
                chain.push(i);
            }
        }
        Ok(chain)
    }

    /// The elements' lengths and directions (and, in the general space
    /// model, their axes with `e3` the arc's normal). An error for an element
    /// of zero length.
    #[allow(clippy::type_complexity)]
    fn elements(
        &self,
        cx: &Ctx,
        frame: &Frame,
        chain: &[usize],
    ) -> Result<(Vec<(f64, f64, f64)>, Vec<[[f64; 3]; 3]>), FramesError> {
        let ArcChain {
            raw: r,
            table,
            general,
            normal,
            ..
        } = *self;
        let n = chain.len() - 1;
        let mut dirs = Vec::with_capacity(n);
        let mut axes = Vec::new();
        for w in chain.windows(2) {
            let (a, b) = (&frame.nodes[w[0]], &frame.nodes[w[1]]);
            let (dx, dy, dz) = (b.x - a.x, b.y - a.y, b.z - a.z);
            let h = if general {
                dx.hypot(dy).hypot(dz)
            } else {
                dx.hypot(dy)
            };
            if general && h > 0.0 && h.is_finite() {
                // e3 the arc's normal: bending in its plane is about e3
                match crate::space::element_axes([dx / h, dy / h, dz / h], Some(normal)) {
                    Ok(e) => axes.push(e),
                    Err(why) => return cx.err(r.elements.span(), format!("{table} elements"), why),
                }
            }
            if !(h > 0.0 && h.is_finite()) {
                return cx.err(
                    r.elements.span(),
                    format!("{table} elements"),
                    format!("an element of zero length between \"{}\" and \"{}\" (too many elements for the radius)", a.id, b.id),
                );
            }
            dirs.push((h, dx / h, dy / h));
        }
        Ok((dirs, axes))
    }
}
