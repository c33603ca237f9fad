//! Checks of the assembly against the dense form and closed forms.

use super::full::full_blocks;
use super::*;
use crate::model::Scene;
use faer::Mat;

/// The sparse `A` and `T N` hold exactly what the dense assembly wrote
/// (entries written into a zero matrix, a later write of a position
/// replacing an earlier one) on every scene, and the mixed PLCP built from
/// them in sparse form equals the dense one.
#[test]
fn sparse_blocks_equal_the_dense_assembly_on_every_scene() {
    let checked = for_every_assembly(|path, scene, leave_out, sys| {
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
    });
    assert!(checked >= 40, "{checked}");
}

/// The second forces of all sections at once are the ones found section by
/// section, on every scene (planar, grillage, space; left out or not).
#[test]
fn second_force_indices_match_the_search_on_every_scene() {
    let mut found = 0;
    let checked = for_every_assembly(|path, _, _, sys| {
        let all = sys.second_force_indices();
        assert_eq!(all.len(), sys.sections.len());
        for (k, &idx) in all.iter().enumerate() {
            assert_eq!(idx, sys.second_force_index(k), "{}", path.display());
            found += usize::from(idx.is_some());
        }
    });
    assert!(checked >= 40 && found > 0, "{checked} {found}");
}

/// The moments of all sections at once are the ones found section by
/// section, on every scene.
#[test]
fn moment_indices_match_the_search_on_every_scene() {
    let mut found = 0;
    let checked = for_every_assembly(|path, _, _, sys| {
        let all = sys.moment_indices();
        assert_eq!(all.len(), sys.sections.len());
        for (k, &idx) in all.iter().enumerate() {
            assert_eq!(idx, sys.moment_index(k), "{}", path.display());
            found += usize::from(idx.is_some());
        }
    });
    assert!(checked >= 40 && found > 0, "{checked} {found}");
}

/// Calls `check` with every scene of `scenes/` (and its `pipe-whip` and
/// `stiff` folders) assembled with and without leaving out; returns the
/// number of assemblies checked.
fn for_every_assembly(mut check: impl FnMut(&std::path::Path, &Scene, bool, System)) -> usize {
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
                check(
                    &path,
                    &scene,
                    leave_out,
                    System::assemble_with(&scene.frame, leave_out),
                );
                checked += 1;
            }
        }
    }
    checked
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
