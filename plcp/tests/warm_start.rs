//! Warm starts (`Settings::warm_basis`, `Path::final_basis`): re-solving after a
//! change of `q` as the path from the old `q` to the new one, against cold solves.

use faer::{Col, Mat};
use plcp::{Method, Plcp, Settings, Status, Var};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A positive definite `M` (unique solution for every `q`), and two right-hand sides.
fn instance(n: usize, seed: u64) -> (Mat<f64>, Col<f64>, Col<f64>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let b = Mat::<f64>::from_fn(n, n, |_, _| rng.gen_range(-1.0..1.0));
    let m = Mat::<f64>::from_fn(n, n, |i, j| {
        (0..n).map(|k| b[(i, k)] * b[(j, k)]).sum::<f64>() / n as f64
            + if i == j { 0.1 } else { 0.0 }
    });
    let q1 = Col::<f64>::from_fn(n, |_| rng.gen_range(-1.0..1.0));
    let q2 = Col::<f64>::from_fn(n, |i| q1[i] + rng.gen_range(-0.2..0.2));
    (m, q1, q2)
}

/// The solution of LCP(M, q), cold: a PLCP with `d = 0` at `L = 0`.
fn cold(m: &Mat<f64>, q: &Col<f64>, method: Method) -> plcp::Path<f64> {
    let n = q.nrows();
    let pr = Plcp::new(m.as_ref(), q.as_ref(), Col::<f64>::zeros(n).as_ref())
        .unwrap()
        .with_range(0.0, Some(0.0))
        .unwrap();
    let path = plcp::solve(&pr, &Settings::with_method(method)).unwrap();
    assert_eq!(path.status, Status::Reached, "{}", path.message);
    path
}

#[test]
fn warm_path_from_the_old_q_matches_a_cold_solve() {
    for seed in 0..20u64 {
        let n = 12 + (seed as usize % 7);
        let (m, q1, q2) = instance(n, seed);
        for method in [Method::Lemke, Method::Wolfe] {
            let first = cold(&m, &q1, method);
            let basis = first
                .final_basis
                .clone()
                .expect("Reached gives a final basis");
            assert_eq!(basis.len(), n);
            assert!(!basis.contains(&Var::Lambda));
            // the path from q1 (L = 0) to q2 (L = 1)
            let d = Col::<f64>::from_fn(n, |i| q2[i] - q1[i]);
            let pr = Plcp::new(m.as_ref(), q1.as_ref(), d.as_ref())
                .unwrap()
                .with_range(0.0, Some(1.0))
                .unwrap();
            let settings = Settings {
                warm_basis: Some(basis),
                ..Settings::with_method(method)
            };
            let warm = plcp::solve(&pr, &settings).unwrap();
            assert_eq!(warm.status, Status::Reached, "{}", warm.message);
            assert!(
                warm.info.warm_start,
                "seed {seed}: {}",
                warm.info.warm_start_note
            );
            assert_eq!(warm.info.start_pivots, 0);
            let reference = cold(&m, &q2, method);
            let scale = 1.0 + (0..n).fold(0.0f64, |a, i| a.max(reference.end.z[i].abs()));
            for i in 0..n {
                let e = (warm.end.z[i] - reference.end.z[i]).abs();
                assert!(
                    e <= 1e-10 * scale,
                    "seed {seed} {method:?}: z[{i}] warm {} vs cold {}",
                    warm.end.z[i],
                    reference.end.z[i]
                );
            }
            assert!(warm.info.residual.worst() < 1e-12);
        }
    }
}

#[test]
fn an_infeasible_or_singular_warm_basis_falls_back_to_the_cold_start() {
    let (m, q1, q2) = instance(10, 7);
    let n = 10;
    let zero = Col::<f64>::zeros(n);
    let reference = cold(&m, &q2, Method::Lemke);
    // all z basic: feasible only if the unconstrained solution is nonnegative
    let all_z: Vec<Var> = (0..n).map(Var::Z).collect();
    let pr = Plcp::new(m.as_ref(), q2.as_ref(), zero.as_ref())
        .unwrap()
        .with_range(0.0, Some(0.0))
        .unwrap();
    let s = Settings {
        warm_basis: Some(all_z),
        ..Settings::default()
    };
    let path = plcp::solve(&pr, &s).unwrap();
    assert_eq!(path.status, Status::Reached);
    let unconstrained_feasible = reference.end.w.iter().all(|&w| w == 0.0);
    if !unconstrained_feasible {
        assert!(!path.info.warm_start);
        assert!(
            path.info.warm_start_note.contains("not used"),
            "{}",
            path.info.warm_start_note
        );
    }
    for i in 0..n {
        assert!((path.end.z[i] - reference.end.z[i]).abs() < 1e-10);
    }
    // a singular basis: z_0 in the place of w_0 with column 0 of M zeroed
    let mut ms = m.clone();
    for i in 0..n {
        ms[(i, 0)] = 0.0;
        ms[(0, i)] = 0.0;
    }
    ms[(0, 0)] = 0.0;
    let pr = Plcp::new(ms.as_ref(), q1.as_ref(), zero.as_ref())
        .unwrap()
        .with_range(0.0, Some(0.0))
        .unwrap();
    let mut b: Vec<Var> = (0..n).map(Var::W).collect();
    b[0] = Var::Z(0);
    let s = Settings {
        warm_basis: Some(b),
        ..Settings::default()
    };
    let path = plcp::solve(&pr, &s).unwrap();
    assert!(!path.info.warm_start);
    assert!(!path.info.warm_start_note.is_empty());
}

#[test]
fn malformed_warm_bases_are_errors_that_name_the_problem() {
    let (m, q1, _) = instance(6, 3);
    let zero = Col::<f64>::zeros(6);
    let pr = Plcp::new(m.as_ref(), q1.as_ref(), zero.as_ref()).unwrap();
    let cases: Vec<(Vec<Var>, &str)> = vec![
        ((0..5).map(Var::W).collect(), "5 variables for 6 rows"),
        (
            (0..5).map(Var::W).chain([Var::W(0)]).collect(),
            "appears twice",
        ),
        (
            (0..5).map(Var::W).chain([Var::Lambda]).collect(),
            "L cannot be basic",
        ),
        (
            (0..5).map(Var::W).chain([Var::Z(9)]).collect(),
            "only 6 complementary pairs",
        ),
        (
            (0..5).map(Var::W).chain([Var::U(0)]).collect(),
            "only 0 free variables",
        ),
    ];
    for (b, want) in cases {
        let s = Settings {
            warm_basis: Some(b),
            ..Settings::default()
        };
        let e = plcp::solve(&pr, &s).unwrap_err().to_string();
        assert!(e.contains("warm_basis") && e.contains(want), "{e}");
    }
}
