//! The lexicographic rule reads the tied rows of `B^-1` lazily since issue
//! 15 (`plcp/src/basis/lex.rs`): with `plcp::lex_check` on, every tie met
//! by the sparse basis is also broken the way it was before (each tied row
//! solved in full through faer, gathered and cleaned of noise, then
//! compared), every entry of the rows compared bit for bit, and a different
//! choice panics. Here on frames' system (9) of every scene and of
//! cantilevers (sections tied at every hinge event) and on random
//! degenerate sparse problems; each case must meet ties.

use crate::common;

use faer::{Col, Mat};
use frames::{Scene, System};
use plcp::matrix::Csc;
use plcp::{BasisKind, Method, Plcp, Settings};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn scenes() -> Vec<Scene> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut files = Vec::new();
    for d in [dir.clone(), dir.join("pipe-whip"), dir.join("stiff")] {
        for e in std::fs::read_dir(&d).expect("scenes/").flatten() {
            let p = e.path();
            if p.extension().is_some_and(|x| x == "toml") {
                files.push(p);
            }
        }
    }
    files.sort();
    let mut out: Vec<Scene> = files
        .iter()
        .map(|p| Scene::from_file(p).expect("valid scene"))
        .collect();
    for n in [20, 100, 250] {
        out.push(common::cantilever(n, 1.0));
    }
    out
}

/// frames' system (9), sparse form and basis, Wolfe's method, `Lambda` up
/// to 12: every tie checked; the cantilevers meet one at every hinge event.
#[test]
fn lazy_rows_break_the_ties_of_frames_as_before() {
    plcp::lex_check(true);
    let (mut total, mut scene_ties) = (0, 0);
    for scene in scenes() {
        let system = System::assemble(&scene.frame);
        let sparse = system.plcp_sparse::<f64>(Some(12.0)).unwrap();
        let mut s = Settings::<f64>::with_method(Method::Wolfe);
        s.basis = BasisKind::Sparse;
        let before = plcp::lex_check(true);
        let path = plcp::solve(&sparse, &s).unwrap();
        let ties = plcp::lex_check(true) - before;
        eprintln!("{}: {ties} ties, {:?}", scene.file, path.status);
        // (the stiff scenes' f64 paths may end ill-conditioned: frames
        // continues them in f128; their ties up to there are checked)
        if scene.file.starts_with("cantilever-") {
            assert!(path.status.is_success(), "{}: {}", scene.file, path.message);
            let n: usize = scene.file["cantilever-".len()..scene.file.len() - 5]
                .parse()
                .unwrap();
            // each hinge event ties the two sections at a node
            assert!(ties >= n / 2, "{}: {ties} ties", scene.file);
        }
        if !scene.file.starts_with("cantilever-") {
            scene_ties += ties;
        }
        total += ties;
    }
    // (425 ties in all when written, 68 of them in the scenes' files)
    assert!(
        scene_ties > 20 && total > 300,
        "{scene_ties} / {total} ties checked"
    );
}

/// Random sparse standard-form problems built to tie: `q` and `d` from a
/// few values (many rows reach zero at once), integer `M` with a dominant
/// diagonal, some rows of `q` zero (degenerate from the start); Lemke and
/// Wolfe.
#[test]
fn lazy_rows_break_random_degenerate_ties_as_before() {
    plcp::lex_check(true);
    let mut rng = ChaCha8Rng::seed_from_u64(20261127);
    let mut total = 0;
    for case in 0..60 {
        let n = 5 + case % 30;
        let mut m = Mat::<f64>::zeros(n, n);
        for j in 0..n {
            for i in 0..n {
                if i == j {
                    m[(i, j)] = (n as f64) + rng.gen_range(0..3) as f64;
                } else if rng.gen_bool(0.2) {
                    m[(i, j)] = rng.gen_range(-2..=2) as f64;
                }
            }
        }
        let q = Col::<f64>::from_fn(n, |_| [0.0, 1.0, 1.0, 2.0][rng.gen_range(0..4)]);
        let d = Col::<f64>::from_fn(n, |_| [-1.0, -1.0, -2.0, 0.5][rng.gen_range(0..4)]);
        let problem = Plcp::mixed_sparse(Csc::from_dense(m.as_ref()), q.as_ref(), d.as_ref(), 0)
            .unwrap()
            .with_range(0.0, Some(10.0))
            .unwrap();
        for method in [Method::Lemke, Method::Wolfe] {
            let mut s = Settings::<f64>::with_method(method);
            s.basis = BasisKind::Sparse;
            let before = plcp::lex_check(true);
            let path = plcp::solve(&problem, &s).unwrap();
            total += plcp::lex_check(true) - before;
            assert!(
                path.status.is_success(),
                "case {case} {method:?}: {}",
                path.message
            );
        }
    }
    eprintln!("{total} ties checked");
    assert!(total > 100, "{total} ties checked");
}
