//! The two ways of solving a segment's basis exactly, p-adic lifting
//! (`Engine::Modular`, the default) and the fraction-free tableau
//! (`Engine::Bareiss`), give the same certificate: the same outcome, the same
//! failing segment and the same exact breakpoints, on dense monotone problems
//! with full-mantissa data, on mixed (KKT) problems with and without a
//! dependent equality row, on random dyadic problems (a property test), and on
//! float paths tampered with (a shifted breakpoint, a wrong basis), which both
//! reject.

use crate::common;

use common::monotone;
use faer::{Col, Mat};
use plcp::exact::{self, Certificate, Engine};
use plcp::{Method, Path, Plcp, Scalar, Settings, Var};
use proptest::prelude::*;
use proptest::test_runner::{Config as ProptestConfig, FileFailurePersistence};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Both engines on one path; asserts they agree and returns the modular one.
fn both<T: Scalar>(problem: &Plcp<T>, path: &Path<T>) -> Certificate {
    let m = exact::certify_with(problem, path, Engine::Modular);
    let b = exact::certify_with(problem, path, Engine::Bareiss);
    assert_eq!(
        m.certified(),
        b.certified(),
        "modular: {} / bareiss: {}",
        m.summary(),
        b.summary()
    );
    assert_eq!(
        m.failure.as_ref().map(|f| f.segment),
        b.failure.as_ref().map(|f| f.segment),
        "modular: {} / bareiss: {}",
        m.summary(),
        b.summary()
    );
    assert_eq!(m.breakpoints, b.breakpoints);
    assert_eq!(m.max_rel_diff.to_bits(), b.max_rel_diff.to_bits());
    assert_eq!(m.segments, b.segments);
    assert_eq!(b.modular, 0);
    m
}

/// `M = B B'/n + I` with full-mantissa entries, `q` of both signs, `d < 0`
/// mostly: Lemke's start phase runs and the path has many segments.
fn dense(n: usize, seed: u64) -> Plcp<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let b = Mat::<f64>::from_fn(n, n, |_, _| rng.gen_range(-1.0..1.0));
    let m = Mat::<f64>::from_fn(n, n, |i, j| {
        let s: f64 = (0..n).map(|k| b[(i, k)] * b[(j, k)]).sum::<f64>() / n as f64;
        s + if i == j { 1.0 } else { 0.0 }
    });
    let q = Col::<f64>::from_fn(n, |_| rng.gen_range(-0.5..1.0));
    let d = Col::<f64>::from_fn(n, |_| rng.gen_range(-1.0..0.2));
    Plcp::new(m.as_ref(), q.as_ref(), d.as_ref()).unwrap()
}

/// The KKT system of `min x'Hx/2 + (c + L e)'x` subject to
/// `A x = b + L bd`, `x_j >= 0` for the last `nb` variables: free `x_f`
/// (`nf`) and multipliers `y` (`m`) first, then the bounded pairs. With
/// `dependent`, the last row of `A` repeats the first (with its right-hand
/// side): the free block is singular and Wolfe keeps an artificial variable.
fn kkt(nf: usize, m: usize, nb: usize, dependent: bool, seed: u64) -> Plcp<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let nx = nf + nb;
    let g = Mat::<f64>::from_fn(nx, nx, |_, _| rng.gen_range(-1.0..1.0));
    let h = Mat::<f64>::from_fn(nx, nx, |i, j| {
        (0..nx).map(|k| g[(i, k)] * g[(j, k)]).sum::<f64>() / nx as f64
            + if i == j { 0.5 } else { 0.0 }
    });
    let mut a = Mat::<f64>::from_fn(m, nx, |_, _| rng.gen_range(-1.0..1.0));
    let mut bv: Vec<f64> = (0..m).map(|_| rng.gen_range(-1.0..1.0)).collect();
    let mut bd: Vec<f64> = (0..m).map(|_| rng.gen_range(-0.5..0.5)).collect();
    if dependent {
        for j in 0..nx {
            a[(m - 1, j)] = a[(0, j)];
        }
        bv[m - 1] = bv[0];
        bd[m - 1] = bd[0];
    }
    let p = nf + m;
    let dim = p + nb;
    let xi = |j: usize| if j < nf { j } else { p + (j - nf) };
    let yi = |k: usize| nf + k;
    let mut mm = Mat::<f64>::zeros(dim, dim);
    let mut q = Col::<f64>::zeros(dim);
    let mut d = Col::<f64>::zeros(dim);
    for i in 0..nx {
        for j in 0..nx {
            mm[(xi(i), xi(j))] = h[(i, j)];
        }
        for k in 0..m {
            mm[(xi(i), yi(k))] = a[(k, i)];
            mm[(yi(k), xi(i))] = -a[(k, i)];
        }
        q[xi(i)] = rng.gen_range(-1.0..1.0);
        d[xi(i)] = rng.gen_range(-1.0..1.0);
    }
    for k in 0..m {
        q[yi(k)] = bv[k];
        d[yi(k)] = bd[k];
    }
    Plcp::mixed(mm.as_ref(), q.as_ref(), d.as_ref(), p)
        .unwrap()
        .with_range(0.0, Some(20.0))
        .unwrap()
}

#[test]
fn dense_monotone_paths_give_the_same_exact_breakpoints() {
    for (n, seed) in [(8, 1), (15, 2), (25, 3), (40, 4)] {
        let problem = dense(n, seed);
        let path = plcp::solve(&problem, &Settings::default()).unwrap();
        assert!(path.segments.len() > 2, "n = {n}: a short path");
        let cert = both(&problem, &path);
        assert!(cert.certified(), "n = {n}: {}", cert.summary());
        // every segment's basis went through the lifting
        assert_eq!(cert.modular, path.segments.len(), "n = {n}");
        assert_eq!(cert.pivots, 0, "n = {n}");
    }
}

#[test]
fn mixed_kkt_paths_give_the_same_exact_breakpoints() {
    let mut lifted = 0;
    for seed in 0..6 {
        for dependent in [false, true] {
            let problem = kkt(4, 3, 8, dependent, seed);
            for method in [Method::Wolfe, Method::Lemke] {
                if dependent && method == Method::Lemke {
                    continue; // the Schur reduction needs a nonsingular free block
                }
                let path = plcp::solve(&problem, &Settings::with_method(method)).unwrap();
                let cert = both(&problem, &path);
                if path.status.is_success() {
                    assert!(cert.certified(), "seed {seed}: {}", cert.summary());
                }
                lifted += cert.modular;
                if dependent {
                    // a dependent row keeps an artificial: the tableau answers
                    assert_eq!(cert.modular, 0, "seed {seed}");
                }
            }
        }
    }
    assert!(lifted > 0);
}

#[test]
fn tampered_paths_are_rejected_by_both() {
    let problem = dense(30, 7);
    let path = plcp::solve(&problem, &Settings::default()).unwrap();
    assert!(both(&problem, &path).certified());
    let k = path.segments.len() / 2;
    // a breakpoint moved by 1e-6 relative (far above sqrt(eps))
    let mut shifted = path.clone();
    let l = shifted.segments[k].lambda_to * (1.0 + 1e-6);
    shifted.segments[k].lambda_to = l;
    shifted.segments[k + 1].lambda_from = l;
    if let Some(bp) = shifted.breakpoints.iter_mut().find(|b| b.segment == k + 1) {
        bp.lambda = l;
    }
    let cert = both(&problem, &shifted);
    let f = cert.failure.expect("a shifted breakpoint is rejected");
    assert_eq!(f.segment, k, "{}", f.reason);
    // a wrong basis: one pair swapped in the middle segment
    let mut wrong = path.clone();
    let i = wrong.segments[k]
        .basis
        .iter()
        .position(|v| matches!(v, Var::Z(_)))
        .expect("a basic z");
    let Var::Z(j) = wrong.segments[k].basis[i] else {
        unreachable!()
    };
    wrong.segments[k].basis[i] = Var::W(j);
    let cert = both(&problem, &wrong);
    let f = cert.failure.expect("a wrong basis is rejected");
    assert_eq!(f.segment, k, "{}", f.reason);
    // a wrong value on the right basis
    let mut value = path.clone();
    value.segments[k].w_from[0] += 1e-3;
    value.segments[k].z_from[0] += 1e-3;
    let cert = both(&problem, &value);
    assert_eq!(cert.failure.expect("rejected").segment, k);
}

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "proptest-regressions/certify_engines.txt",
        ))),
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config(100))]

    /// Random monotone PLCPs in f64 (`q` of both signs, `L` to a bound or to
    /// infinity): the engines agree on every path, certified or not.
    #[test]
    fn engines_agree_on_random_monotone_problems(
        n in 1usize..=8,
        seed in any::<u64>(),
        shift in prop_oneof![Just(0.0), Just(0.125)],
        lmax in prop_oneof![Just(None), (1u32..=64).prop_map(|k| Some(f64::from(k) / 8.0))],
    ) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let b: Vec<f64> = (0..n * n).map(|_| rng.gen_range(-1.0..1.0)).collect();
        let s: Vec<f64> = (0..n * n).map(|_| rng.gen_range(-1.0..1.0)).collect();
        let m = monotone(&b, n, n, &s, shift);
        let q = Col::<f64>::from_fn(n, |_| rng.gen_range(-1.0..1.0));
        let d = Col::<f64>::from_fn(n, |_| rng.gen_range(-1.0..1.0));
        let problem = Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
            .unwrap()
            .with_range(0.0, lmax)
            .unwrap();
        let path = plcp::solve(&problem, &Settings::default()).unwrap();
        both(&problem, &path);
    }
}
