//! Grillages (pipe whip out of plane), yield polygons and arcs, against
//! independent computations: the compatibility matrix against 3D vector
//! kinematics, collapse loads against vector statics with the polygon, the
//! first breakpoint against limit analysis (an LP) and the accelerations
//! against the convex QP of the notes (both by Clarabel), the planar
//! cantilever reproduced out of plane, and the reduced against the full
//! assembly.

use crate::common;
use common::reference::{lp_collapse_load, qp_accelerations};
use frames::assemble::MemberForce;
use frames::model::{Component, Model};
use frames::yield_surface::{Curve, Polygon};
use frames::{Analysis, AnalysisOptions, Scene, System};

const TP: f64 = 0.906_899_682_117_108_9; // pi / (2 sqrt 3): thin-walled pipe, von Mises

fn scene_file(name: &str) -> String {
    format!("{}/../scenes/{name}", env!("CARGO_MANIFEST_DIR"))
}

fn read(name: &str) -> String {
    std::fs::read_to_string(scene_file(name)).unwrap()
}

fn run(scene: &Scene) -> Analysis {
    let a = Analysis::run(
        scene.clone(),
        &AnalysisOptions {
            samples: 11,
            ..AnalysisOptions::default()
        },
    )
    .unwrap();
    assert!(
        a.solution.status.is_success(),
        "{}: {:?} {}",
        scene.file,
        a.solution.status,
        a.solution.message
    );
    assert!(
        a.solution.info.residual.worst() < 1e-8,
        "{}: residual {:?}",
        scene.file,
        a.solution.info.residual
    );
    a
}

fn critical(a: &Analysis) -> Vec<f64> {
    a.reading.breakpoints.iter().map(|b| b.lambda).collect()
}

/// A small deterministic generator (no rand in this crate's dev-dependencies).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((self.0 >> 11) as f64) / ((1u64 << 53) as f64)
    }
}

/// Accelerations of the path at `lambda`, per kept coordinate.
fn path_accelerations(a: &Analysis, lambda: f64) -> Vec<f64> {
    let iv = a
        .reading
        .intervals
        .iter()
        .position(|i| lambda >= i.lambda_from && lambda <= i.lambda_to)
        .unwrap();
    let r = &a.response.intervals[iv];
    a.system
        .coordinates
        .iter()
        .map(|c| {
            let [b, s] = r.accelerations[c.node][c.component.index()];
            b + s * lambda
        })
        .collect()
}

/// The collapse load of a cantilever loaded at one node by vector statics:
/// at every section between the root and the load, the moment of the load
/// about the section split into the element's bending moment and torque
/// (grillage) or bending moment and axial force (planar), scaled by the
/// section's capacities; the polygon (or `|m| <= 1`) gives each section's load
/// factor, and one hinge makes a cantilever a mechanism.
fn vector_statics_collapse(scene: &Scene) -> f64 {
    let fr = &scene.frame;
    let (tip, f) = fr
        .nodes
        .iter()
        .find(|n| n.load != [0.0; 6])
        .map(|n| (n, n.load))
        .unwrap();
    // force vector and its point
    let force = match fr.model {
        Model::Grillage => [0.0, 0.0, f[3]],
        Model::Planar => [f[0], f[1], 0.0],
        Model::Space => unreachable!("a planar or grillage scene"),
    };
    let mut best = f64::INFINITY;
    for e in &fr.elements {
        for node in [e.from, e.to] {
            let p = &fr.nodes[node];
            let r = [tip.x - p.x, tip.y - p.y, 0.0];
            let m = [
                r[1] * force[2] - r[2] * force[1],
                r[2] * force[0] - r[0] * force[2],
                r[0] * force[1] - r[1] * force[0],
            ];
            let (bending, second) = match fr.model {
                // torque about the axis, bending about the in-plane normal
                Model::Grillage => (-e.sin * m[0] + e.cos * m[1], e.cos * m[0] + e.sin * m[1]),
                // moment about z, axial force along the axis
                Model::Planar => (m[2], e.cos * force[0] + e.sin * force[1]),
                Model::Space => unreachable!("a planar or grillage scene"),
            };
            let factor = match e.interaction {
                Some(it) => Polygon::new(it.curve, it.facets)
                    .unwrap()
                    .load_factor(bending.abs() / e.plastic_moment, second.abs() / it.capacity),
                None => e.plastic_moment / bending.abs(),
            };
            best = best.min(factor);
        }
    }
    best
}

fn l_shaped(facets: usize, elements: usize) -> Scene {
    let src = read("pipe-whip/l-shaped.toml")
        .replace("facets = 16", &format!("facets = {facets}"))
        .replace("elements = 4", &format!("elements = {elements}"));
    Scene::from_toml(&src, &format!("l-shaped k={facets} n={elements}")).unwrap()
}

fn semicircle(facets: usize, elements: usize) -> Scene {
    let src = read("pipe-whip/semicircle.toml")
        .replace("facets = 16", &format!("facets = {facets}"))
        .replace("elements = 8", &format!("elements = {elements}"));
    Scene::from_toml(&src, &format!("semicircle k={facets} n={elements}")).unwrap()
}

#[test]
fn compatibility_matches_3d_vector_kinematics() {
    // a skew grillage: the semicircle plus an inclined member off its tip
    let src = read("pipe-whip/semicircle.toml").replace(
        "[[support]]",
        "[[node]]\nid = \"D\"\nx = -1.7\ny = 0.9\n[[member]]\nid = \"CD\"\nfrom = \"C\"\nto = \"D\"\nplastic_moment = 2.0\nplastic_torque = 1.5\nmass_per_length = 1.0\nelements = 3\n[[support]]",
    );
    let scene = Scene::from_toml(&src, "skew.toml").unwrap();
    let fr = &scene.frame;
    let sys = System::assemble_full(fr);
    assert_eq!(sys.forces.len(), 3 * fr.elements.len());
    let mut rng = Lcg(11);
    for _ in 0..5 {
        let q: Vec<f64> = sys.coordinates.iter().map(|_| rng.next() - 0.5).collect();
        let at =
            |node: usize, c: Component| sys.coordinate_index(node, c).map(|j| q[j]).unwrap_or(0.0);
        for (r, f) in sys.forces.iter().enumerate() {
            let aq: f64 = (0..q.len()).map(|j| sys.a[(r, j)] * q[j]).sum();
            let (e, which) = match *f {
                MemberForce::Moment(k) => (sys.sections[k].element, k % 2),
                MemberForce::Torque(e) => (e, 2),
                MemberForce::Axial(_) | MemberForce::Moment2(_) => {
                    panic!("an axial force or a second moment in a grillage")
                }
            };
            let el = &fr.elements[e];
            let (a, b) = (el.from, el.to);
            // rotation vectors of the nodes and of the chord: e x (0, 0, dw) / h
            let ra = [at(a, Component::Rx), at(a, Component::Ry)];
            let rb = [at(b, Component::Rx), at(b, Component::Ry)];
            let dw = at(b, Component::Z) - at(a, Component::Z);
            let chord = [el.sin * dw / el.length, -el.cos * dw / el.length];
            let axis = [el.cos, el.sin];
            let normal = [-el.sin, el.cos];
            let dot = |u: [f64; 2], v: [f64; 2]| u[0] * v[0] + u[1] * v[1];
            let sub = |u: [f64; 2], v: [f64; 2]| [u[0] - v[0], u[1] - v[1]];
            let expected = match which {
                0 => -dot(normal, sub(ra, chord)),
                1 => dot(normal, sub(rb, chord)),
                _ => dot(axis, sub(rb, ra)),
            };
            assert!(
                (aq - expected).abs() < 1e-12,
                "row {r} ({f:?}): A q = {aq}, vector kinematics {expected}"
            );
        }
    }
    // rigid-body motions of the whole grillage deform nothing
    let mut free = scene.frame.clone();
    for n in &mut free.nodes {
        n.fixed = [false; 6];
    }
    let sys = System::assemble_full(&free);
    for motion in 0..3 {
        let q: Vec<f64> = sys
            .coordinates
            .iter()
            .map(|c| {
                let n = &free.nodes[c.node];
                match (motion, c.component) {
                    (0, Component::Z) => 1.0,
                    (1, Component::Z) => n.y, // rotation about x: w = y
                    (1, Component::Rx) => 1.0,
                    (2, Component::Z) => -n.x, // rotation about y: w = -x
                    (2, Component::Ry) => 1.0,
                    _ => 0.0,
                }
            })
            .collect();
        for r in 0..sys.forces.len() {
            let v: f64 = (0..q.len()).map(|j| sys.a[(r, j)] * q[j]).sum();
            assert!(v.abs() < 1e-12, "motion {motion}, row {r}: {v}");
        }
    }
}

#[test]
fn l_shaped_statics_and_collapse_load_converge_in_facets() {
    // A^T X = a_o for a unit tip load: root M = L1 P, T = L2 P; corner of AB:
    // torque only; corner of BC: bending L2 P, no torque
    let scene = l_shaped(16, 1);
    let sys = System::assemble(&scene.frame);
    assert!(sys.is_determinate());
    let n = sys.coordinates.len();
    let mut m: Vec<Vec<f64>> = (0..n)
        .map(|j| {
            let mut r: Vec<f64> = (0..n).map(|i| sys.a[(i, j)]).collect();
            r.push(sys.load[j]);
            r
        })
        .collect();
    for c in 0..n {
        let p = (c..n)
            .max_by(|&x, &y| m[x][c].abs().total_cmp(&m[y][c].abs()))
            .unwrap();
        m.swap(c, p);
        let pv = m[c][c];
        for v in m[c].iter_mut() {
            *v /= pv;
        }
        for r in 0..n {
            if r != c {
                let f = m[r][c];
                let row = m[c].clone();
                for (x, y) in m[r].iter_mut().zip(row) {
                    *x -= f * y;
                }
            }
        }
    }
    let x: Vec<f64> = m.iter().map(|r| r[n]).collect();
    let moment = |k: usize| x[sys.moment_index(k).unwrap()].abs();
    let torque = |k: usize| x[sys.second_force_index(k).unwrap()].abs();
    assert!((moment(0) - 1.0).abs() < 1e-12 && (torque(0) - 1.0).abs() < 1e-12);
    assert!(moment(1).abs() < 1e-12);
    assert!((moment(2) - 1.0).abs() < 1e-12 && torque(2).abs() < 1e-12);

    // the first breakpoint: vector statics with the polygon, the LP, and the
    // circle as the facets double (inscribed: from below)
    let circle = 1.0 / (1.0f64 + 1.0 / (TP * TP)).sqrt();
    let mut last = 0.0;
    for k in [4, 8, 16, 32, 64] {
        let scene = l_shaped(k, 2);
        let a = run(&scene);
        let first = a.reading.collapse_load().unwrap();
        let statics = vector_statics_collapse(&scene);
        let lp = lp_collapse_load(&a.system);
        assert!(
            (first - statics).abs() < 1e-9,
            "k = {k}: {first} vs {statics}"
        );
        assert!((first - lp).abs() < 1e-6, "k = {k}: {first} vs LP {lp}");
        assert!(first <= circle + 1e-12 && first > last, "k = {k}: {first}");
        let bound = (1.0 - (std::f64::consts::PI / k as f64).cos()) * circle;
        assert!(
            circle - first <= bound + 1e-12,
            "k = {k}: {first} vs {circle}"
        );
        // the first hinge is at the root, on a facet between pure bending and pure torsion
        let h = &a.reading.hinges[0];
        assert_eq!(scene.frame.nodes[h.node].id, "A");
        last = first;
    }
    assert!(circle - last < 2e-3);
}

#[test]
fn straight_out_of_plane_cantilever_reproduces_the_planar_path() {
    let planar = run(&Scene::from_file(scene_file("cantilever.toml")).unwrap());
    let expected = [("A", 1.0), ("AB.1", 4.0), ("AB.2", 6.0), ("AB.3", 12.0)];
    for k in [4, 8, 32] {
        let src = read("pipe-whip/straight.toml").replace("facets = 8", &format!("facets = {k}"));
        let scene = Scene::from_toml(&src, "straight.toml").unwrap();
        let a = run(&scene);
        assert_eq!(a.reading.hinges.len(), expected.len(), "k = {k}");
        for (h, (node, l)) in a.reading.hinges.iter().zip(expected) {
            assert_eq!(scene.frame.nodes[h.node].id, node, "k = {k}");
            assert!((h.lambda - l).abs() < 1e-9, "k = {k}: {} vs {l}", h.lambda);
        }
        let (cg, cp) = (critical(&a), critical(&planar));
        assert_eq!(cg.len(), cp.len());
        for (g, p) in cg.iter().zip(&cp) {
            assert!((g - p).abs() < 1e-9, "k = {k}: {cg:?} vs {cp:?}");
        }
        // the same accelerations: z out of plane, y in plane
        for l in [2.0, 5.0, 8.0, 20.0] {
            let idx = [&a, &planar].map(|x| {
                x.reading
                    .intervals
                    .iter()
                    .position(|i| l >= i.lambda_from && l <= i.lambda_to)
                    .unwrap()
            });
            let (ia, ip) = (idx[0], idx[1]);
            for node in 0..scene.frame.nodes.len() {
                let [b, s] = a.response.intervals[ia].accelerations[node][3]; // z (slot 3)
                let [bp, sp] = planar.response.intervals[ip].accelerations[node][1];
                assert!(
                    ((b + s * l) - (bp + sp * l)).abs() < 1e-9 * (1.0 + (bp + sp * l).abs()),
                    "k = {k}, Lambda = {l}, node {node}"
                );
            }
        }
        assert!(a.reading.deactivations().is_empty());
    }
}

#[test]
fn pipe_whip_scenes_agree_with_limit_analysis_and_the_qp() {
    let mut rng = Lcg(7);
    for name in [
        "l-shaped.toml",
        "semicircle.toml",
        "quadrant.toml",
        "quadrant-axial.toml",
        "straight.toml",
    ] {
        let scene = Scene::from_file(scene_file(&format!("pipe-whip/{name}"))).unwrap();
        let a = run(&scene);
        let first = a.reading.collapse_load().unwrap();
        let lp = lp_collapse_load(&a.system);
        let statics = vector_statics_collapse(&scene);
        assert!(
            (first - lp).abs() <= 1e-6 * lp,
            "{name}: {first} vs LP {lp}"
        );
        assert!(
            (first - statics).abs() <= 1e-9 * statics,
            "{name}: {first} vs statics {statics}"
        );
        let bps = critical(&a);
        let last = bps[bps.len().min(6) - 1];
        for _ in 0..3 {
            let l = first * 0.5 + rng.next() * (1.5 * last - 0.5 * first);
            let qp = qp_accelerations(&a.system, l);
            let path = path_accelerations(&a, l);
            let scale = qp.iter().fold(1.0f64, |m, v| m.max(v.abs()));
            for j in 0..qp.len() {
                if a.system.mass[j] > 0.0 {
                    assert!(
                        (path[j] - qp[j]).abs() <= 1e-5 * scale,
                        "{name} at {l}: coordinate {j}: path {}, QP {}",
                        path[j],
                        qp[j]
                    );
                }
            }
        }
        for r in &a.response.intervals {
            assert!(r.residual.worst() < 1e-9, "{name}: {:?}", r.residual);
        }
    }
}

#[test]
fn reduced_and_full_assembly_give_the_same_path() {
    use frames::solve::{solve, SolveOptions};
    for scene in [
        l_shaped(8, 2),
        Scene::from_file(scene_file("cantilever.toml")).unwrap(),
        Scene::from_file(scene_file("pipe-whip/quadrant-axial.toml")).unwrap(),
    ] {
        let reduced = run(&scene);
        let full = System::assemble_full(&scene.frame);
        assert!(full.sizes().free() >= reduced.system.sizes().free());
        assert!(full.modes.len() >= reduced.system.modes.len());
        let sol = solve(&full, &SolveOptions::default()).unwrap();
        assert!(sol.status.is_success(), "{}: {:?}", scene.file, sol.status);
        let reading = frames::hinge::read(&scene.frame, &full, &sol.pieces, sol.tolerance);
        let (cr, cf) = (
            critical(&reduced),
            reading
                .breakpoints
                .iter()
                .map(|b| b.lambda)
                .collect::<Vec<_>>(),
        );
        // hinge formation: the first hinge at every node, at the same Lambda
        // (the full assembly has two sections where the reduced one ties them)
        let first_at = |hs: &[frames::hinge::Hinge]| {
            let mut m = std::collections::BTreeMap::new();
            for h in hs {
                m.entry(h.node).or_insert(h.lambda);
            }
            m
        };
        let (hr, hf) = (first_at(&reduced.reading.hinges), first_at(&reading.hinges));
        assert_eq!(
            hr.keys().collect::<Vec<_>>(),
            hf.keys().collect::<Vec<_>>(),
            "{}: {cr:?} vs {cf:?}",
            scene.file
        );
        for (node, l) in &hr {
            assert!(
                (l - hf[node]).abs() < 1e-9,
                "{}: node {node}: {l} vs {}",
                scene.file,
                hf[node]
            );
        }
        // accelerations of every coordinate with mass, at Lambda across the path
        let last = cr.last().copied().unwrap_or(1.0);
        for t in [0.3, 0.9, 1.1, 1.7, 2.5] {
            let l = t * last;
            let pr = path_accelerations(&reduced, l);
            let piece = sol
                .pieces
                .iter()
                .find(|p| l >= p.lambda_from && l <= p.lambda_to)
                .unwrap();
            let u = piece.u(l);
            for (j, c) in full.coordinates.iter().enumerate() {
                if full.mass[j] == 0.0 {
                    continue;
                }
                let vr = reduced
                    .system
                    .coordinate_index(c.node, c.component)
                    .map(|i| pr[i])
                    .unwrap_or(0.0);
                assert!(
                    (u[j] - vr).abs() < 1e-8 * (1.0 + vr.abs()),
                    "{} at {l}: {:?}: full {}, reduced {vr}",
                    scene.file,
                    c,
                    u[j]
                );
            }
        }
    }
}

#[test]
fn sizes_leave_out_what_the_scene_does_not_need() {
    // planar, bending only: no out-of-plane coordinate, no torque, no facet
    let q = Scene::from_file(scene_file("pipe-whip/quadrant.toml")).unwrap();
    let s = System::assemble(&q.frame);
    assert!(s
        .coordinates
        .iter()
        .all(|c| matches!(c.component, Component::X | Component::Y | Component::Rz)));
    assert!(s
        .forces
        .iter()
        .all(|f| !matches!(f, MemberForce::Torque(_))));
    assert!(s.modes.iter().all(|m| m.facet.is_none()));
    // 8 elements: 2 modes per kept section (the root and 7 tied pairs: 9 sections)
    assert_eq!(s.modes.len(), 18);
    // the axial force enters a yield condition only where asked for
    let qa = Scene::from_file(scene_file("pipe-whip/quadrant-axial.toml")).unwrap();
    let s = System::assemble(&qa.frame);
    assert_eq!(s.modes.len(), 16 * 16);
    let axial_rows: Vec<usize> = (0..s.forces.len())
        .filter(|&r| matches!(s.forces[r], MemberForce::Axial(_)))
        .collect();
    assert_eq!(axial_rows.len(), 8);
    assert!(axial_rows
        .iter()
        .all(|&r| (0..s.modes.len()).any(|k| s.tn[(r, k)] != 0.0)));
    // grillage: only z, rx, ry; torques, no axial forces; the straight
    // cantilever ties its inner sections
    let st = Scene::from_file(scene_file("pipe-whip/straight.toml")).unwrap();
    let s = System::assemble(&st.frame);
    assert!(s
        .coordinates
        .iter()
        .all(|c| matches!(c.component, Component::Z | Component::Rx | Component::Ry)));
    assert!(s.forces.iter().all(|f| !matches!(f, MemberForce::Axial(_))));
    assert_eq!(
        (s.full.coordinates, s.full.forces, s.full.modes),
        (12, 12, 64)
    );
    assert_eq!(
        (s.coordinates.len(), s.forces.len(), s.modes.len()),
        (12, 12, 40)
    );
    // an unloaded grillage branch decoupled from the loaded one drops out
    let src = read("pipe-whip/straight.toml").replace(
        "[[support]]",
        "[[node]]\nid = \"P\"\nx = 0.0\ny = 3.0\n[[node]]\nid = \"R\"\nx = 1.0\ny = 3.0\n[[member]]\nid = \"PR\"\nfrom = \"P\"\nto = \"R\"\nplastic_moment = 1.0\nplastic_torque = 1.0\nmass_per_length = 1.0\nelements = 2\n[[support]]\nnode = \"P\"\nfix = [\"z\", \"rx\", \"ry\"]\n[[support]]",
    );
    let two = Scene::from_toml(&src, "two.toml").unwrap();
    let s = System::assemble(&two.frame);
    assert_eq!(s.coordinates.len(), 12);
    assert_eq!(s.left_out.decoupled_coordinates.len(), 6);
    assert_eq!(s.left_out.decoupled_forces.len(), 6);
    // two elements, four sections of 16 facets (the default)
    assert_eq!(s.left_out.decoupled_modes, 2 * 2 * 16);
    let a = run(&two);
    assert!(a.to_text().contains("an unloaded part decoupled"));
}

#[test]
fn semicircle_collapse_load_converges_in_elements() {
    // continuum with the same polygon: at the angle theta from the root the
    // tip load P gives (M, T) = R P (sin theta, 1 + cos theta); the collapse
    // load is the least load factor along the arc (the root alone, pure
    // torsion at a vertex, would give Tp / 2R; the cut corners of the polygon
    // make sections near the root a little weaker)
    let polygon = Polygon::new(Curve::BendingTorsion, 16).unwrap();
    let continuum = (0..=20_000)
        .map(|i| {
            let t = std::f64::consts::PI * i as f64 / 20_000.0;
            polygon.load_factor(t.sin(), (1.0 + t.cos()) / TP)
        })
        .fold(f64::INFINITY, f64::min);
    assert!(continuum <= TP / 2.0 && continuum > 0.97 * TP / 2.0);
    let mut errors = Vec::new();
    for n in [8, 16, 32, 64] {
        let scene = semicircle(16, n);
        let a = run(&scene);
        let first = a.reading.collapse_load().unwrap();
        assert!((first - vector_statics_collapse(&scene)).abs() < 1e-9);
        errors.push((continuum - first).abs());
    }
    // the discrete sections sample the weak zone near the root ever closer
    for w in errors.windows(2) {
        assert!(w[1] < 0.8 * w[0], "{errors:?}");
    }
    assert!(errors[3] < 0.35 * errors[0], "{errors:?}");
}

#[test]
fn grillage_scene_errors_name_file_line_and_key() {
    let base = read("pipe-whip/straight.toml");
    let err = |src: String| Scene::from_toml(&src, "g.toml").unwrap_err().to_string();
    let e = err(base.replace("fz = -1.0", "fy = -1.0"));
    assert!(
        e.contains("load \"B\" fy: not a load of a grillage scene"),
        "{e}"
    );
    let e = err(base.replace("[\"z\", \"rx\", \"ry\"]", "[\"z\", \"rz\"]"));
    assert!(
        e.contains("support \"A\" fix: unknown component \"rz\": expected \"z\", \"rx\" or \"ry\""),
        "{e}"
    );
    let e = err(base.replace("plastic_torque = 0.9068996821171089\n", ""));
    assert!(
        e.contains("member \"AB\" plastic_torque: a grillage member needs plastic_torque"),
        "{e}"
    );
    let e = err(base.replace("facets = 8", "facets = 6"));
    assert!(
        e.starts_with("g.toml:25: member \"AB\" facets: must be a multiple of 4"),
        "{e}"
    );
    let e = err(base.replace("model = \"grillage\"", "model = \"spatial\""));
    assert!(e.contains("model: unknown model \"spatial\""), "{e}");
    let e =
        err(read("cantilever.toml")
            .replace("plastic_moment = 1.0", "plastic_moment = 1.0\nfacets = 8"));
    assert!(e.contains("give plastic_axial too"), "{e}");
    let e = err(read("cantilever.toml").replace(
        "plastic_moment = 1.0",
        "plastic_moment = 1.0\nplastic_torque = 1.0",
    ));
    assert!(
        e.contains("plastic_torque: a key of grillage members only"),
        "{e}"
    );
    let e = err(read("pipe-whip/semicircle.toml").replace("x = -1.0", "x = -1.1"));
    assert!(
        e.contains("arc \"S\" to: node \"C\" at (-1.1, 0) is not the arc's end point"),
        "{e}"
    );
    let e = err(read("pipe-whip/semicircle.toml").replace("end_angle = 180.0", "end_angle = 0.0"));
    assert!(e.contains("arc \"S\" end_angle: the arc must sweep"), "{e}");
    // a tip moment on a node without rotary inertia is a massless mechanism
    let e = err(base.replace("fz = -1.0", "mx = 1.0"));
    assert!(
        e.contains("load \"B\" mx: the load acts on a mechanism with no mass"),
        "{e}"
    );
    // the old planar files stay valid
    assert_eq!(
        Scene::from_toml(&read("cantilever.toml"), "c.toml")
            .unwrap()
            .frame
            .model,
        Model::Planar
    );
    // the polygon choice is fixed: inscribed
    let p = Polygon::new(Curve::BendingTorsion, 4).unwrap();
    assert!((p.radius(std::f64::consts::FRAC_PI_4) - 0.5f64.sqrt()).abs() < 1e-15);
}

/// `hinge::moment_positions` (found once) reads the same moments as
/// `hinge::moment` (a search per call), on planar and grillage scenes, with
/// sections whose moments are left out included.
#[test]
fn moment_positions_agree_with_moment() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes");
    for name in [
        "cantilever.toml",
        "two-storey.toml",
        "pipe-whip/l-shaped.toml",
    ] {
        let scene = Scene::from_file(format!("{dir}/{name}")).expect("scene");
        let system = System::assemble(&scene.frame);
        let nu = system.coordinates.len() + system.forces.len();
        let u: Vec<f64> = (0..nu).map(|i| (i as f64 * 0.7).sin() + 0.1).collect();
        let pos = frames::hinge::moment_positions(&system);
        assert_eq!(pos.len(), system.sections.len());
        for (k, p) in pos.iter().enumerate() {
            let direct = frames::hinge::moment(&system, &u, k);
            assert_eq!(p.map_or(0.0, |r| u[r]), direct, "{name}: section {k}");
        }
    }
}
