//! frames' system (9) in sparse form with the sparse LU basis against the dense
//! form with the dense and block bases: the same status and the same
//! accelerations along the path on the example scenes and on cantilevers of up
//! to 60 elements; and the sparse route ends on its unbounded ray with small
//! residuals, re-measured on the whole path.

use crate::common;

use frames::{Scene, System};
use plcp::{BasisKind, Method, Path};

fn scenes() -> Vec<Scene> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut out: Vec<Scene> = std::fs::read_dir(&dir)
        .expect("scenes/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .map(|p| Scene::from_file(&p).expect("valid scene"))
        .collect();
    for n in [8, 20, 60] {
        out.push(common::cantilever(n, -1.0));
    }
    out
}

/// System (9) is degenerate (tied sections, several hinges at one load level,
/// member forces not unique while an indeterminate frame is rigid): the ties
/// may be broken differently by the lexicographic rule reading rows of
/// `B^{-1}` (sparse) or its columns (dense, block), and the dense and block
/// bases already differ in the number of degenerate pivots. Different but
/// equally valid pivot sequences; what is unique is the solution: compare the
/// accelerations along the path, at every breakpoint of either path and on a
/// grid beyond the last. (Pivot-for-pivot agreement is tested on
/// nondegenerate random problems in `plcp/tests/sparse.rs`.)
fn same_accelerations(what: &str, system: &System, a: &Path<f64>, b: &Path<f64>) {
    assert_eq!(
        a.status, b.status,
        "{what}: status ({} / {})",
        a.message, b.message
    );
    let nb = system.coordinates.len();
    let mut ls: Vec<f64> = a
        .breakpoints
        .iter()
        .chain(&b.breakpoints)
        .map(|x| x.lambda)
        .collect();
    let last = ls.iter().fold(1.0f64, |m, l| m.max(*l));
    ls.extend((0..=20).map(|k| last * 1.5 * k as f64 / 20.0));
    for l in ls {
        let (x, y) = (a.at(l).unwrap(), b.at(l).unwrap());
        // norm-wise: the dense inverse's forward error is about cond * eps
        // relative to the largest acceleration
        let scale = (0..nb).fold(1.0f64, |m, j| m.max(x.u[j].abs()));
        for j in 0..nb {
            assert!(
                (x.u[j] - y.u[j]).abs() <= 1e-8 * scale,
                "{what}: acceleration {j} at L = {l}: {} vs {} (largest {scale})",
                x.u[j],
                y.u[j]
            );
        }
    }
}

#[test]
fn sparse_route_matches_dense_on_frames() {
    for scene in scenes() {
        let system = System::assemble(&scene.frame);
        let dense = system.plcp::<f64>(None).unwrap();
        let sparse = system.plcp_sparse::<f64>(None).unwrap();
        assert_eq!(dense.m(), sparse.m(), "{}", scene.file);
        // frames' settings (near ties within the window are one event:
        // with plcp's default, reading them again, the sparse basis of
        // two-storey-sway pivots on an entry below the tolerance at a
        // degenerate step and stops ill_conditioned at L = 1.4, the dense
        // one reaches its ray; docs/limits.md)
        let mut s = frames::solve::plcp_settings::<f64>(Method::Wolfe);
        s.basis = BasisKind::Sparse;
        let mut b = plcp::solve(&sparse, &s).unwrap();
        for kind in [BasisKind::Dense, BasisKind::Block] {
            s.basis = kind;
            let a = plcp::solve(&dense, &s).unwrap();
            let what = format!("{} ({kind:?})", scene.file);
            same_accelerations(&what, &system, &a, &b);
        }
        assert!(b.status.is_success(), "{}: {}", scene.file, b.message);
        plcp::residual::measure_path(&sparse, &mut b, true);
        let worst = b.info.residual.worst();
        assert!(worst < 1e-10, "{}: residual {worst:e}", scene.file);
    }
}

/// The route frames picks: dense below `SPARSE_FROM` unknowns, sparse above.
#[test]
fn frames_picks_the_sparse_route_for_large_systems() {
    for scene in scenes() {
        let system = System::assemble(&scene.frame);
        let s = system.sizes();
        let options = frames::SolveOptions::default();
        assert_eq!(
            frames::solve::uses_sparse(&system, &options),
            s.free() + s.modes >= frames::solve::SPARSE_FROM,
            "{}",
            scene.file
        );
        let sol = frames::solve::solve(&system, &options).unwrap();
        assert!(sol.status.is_success(), "{}: {}", scene.file, sol.message);
    }
}
