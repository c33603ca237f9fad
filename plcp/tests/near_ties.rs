//! Issue 14: near ties of the minimum-ratio test. Random monotone PLCPs with a
//! planted near tie, two rows whose breakpoints differ by a few to about a
//! thousand ulps (inside the tie window `tie_tol_eps * eps = 1e3 eps`), traced
//! by `plcp::solve` in f64 and fx128: whenever the status is `reached`, the
//! exact certificate accepts the path (a success status is never reported on
//! a path certification rejects). Before the tracer read such ties again with
//! refined values, the lexicographic rule ordered them by row, not by
//! breakpoint, and about half the cases ended `reached` on a wrong path.
//!
//! Two plantings (all data dyadic with few bits, exact in every precision):
//!
//! * **first step**: `M = B B' + S + I/8` of order 3..6, `d = -1`, `q > 0`
//!   with its two smallest entries `t` and `t + k ulp(t)` in random rows: the
//!   first breakpoint is the near tie;
//! * **inside the path**: the same random block (random `q`, `d`, so events
//!   come first) beside the block `[[1, 1], [1, 1 + delta]]`,
//!   `q = (s, s + (s + 1) delta)`, `d = (-1, -(1 + delta))` (in either row
//!   order), `delta = 2^-k`: `w` of the first row reaches zero at `L = s`,
//!   of the second `delta / (1 + delta)` later (`2^(52 - k)` ulps of `s`);
//!   the wrong order leaves `z` of the first row at zero for ever.
//!
//! Run with `PROPTEST_RNG_SEED=20261121` for the recorded cases.

use faer::{fx128, Col, Mat};
use plcp::{Plcp, Scalar, Settings, Status};
use proptest::prelude::*;
use proptest::test_runner::{FileFailurePersistence, TestCaseError};

/// A random monotone block `B B' + S + I/8` of order `n` (entries `k / 4`).
fn monotone(n: usize) -> impl Strategy<Value = Vec<f64>> {
    (
        prop::collection::vec(-4i32..=4, n * n),
        prop::collection::vec(-4i32..=4, n * n),
    )
        .prop_map(move |(b, s)| {
            let b = |i: usize, j: usize| b[i * n + j] as f64 / 4.0;
            let mut m = vec![0.0; n * n];
            for i in 0..n {
                for j in 0..n {
                    let bb: f64 = (0..n).map(|k| b(i, k) * b(j, k)).sum();
                    let skew = if i < j {
                        s[i * n + j] as f64 / 4.0
                    } else if i > j {
                        -(s[j * n + i] as f64) / 4.0
                    } else {
                        0.0
                    };
                    m[i * n + j] = bb + skew + if i == j { 0.125 } else { 0.0 };
                }
            }
            m
        })
}

#[derive(Clone, Debug)]
struct Case {
    m: Vec<f64>,
    q: Vec<f64>,
    d: Vec<f64>,
    lambda_max: f64,
    note: String,
}

impl Case {
    fn problem(&self) -> Plcp<f64> {
        let n = self.q.len();
        let m = Mat::from_fn(n, n, |i, j| self.m[i * n + j]);
        let q = Col::from_fn(n, |i| self.q[i]);
        let d = Col::from_fn(n, |i| self.d[i]);
        Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
            .unwrap()
            .with_range(0.0, Some(self.lambda_max))
            .unwrap()
    }
}

/// The near tie at the first breakpoint: rows `i`, `j` of `q` at `t` and
/// `t + k ulp(t)`, every other entry larger, `d = -1`.
fn first_step() -> impl Strategy<Value = Case> {
    (3usize..=6)
        .prop_flat_map(|n| {
            (
                monotone(n),
                prop::collection::vec(20i32..=64, n),
                0..n,
                1..n,
                4i32..=12,
                1u32..=1000,
            )
        })
        .prop_map(|(m, qs, i, dj, tq, k)| {
            let n = qs.len();
            let j = (i + dj) % n;
            let t = tq as f64 / 8.0; // below every other q (>= 20 / 8)
            let ulp = t * f64::EPSILON / 2.0; // t in [0.5, 1.5]: at most one ulp off
            let mut q: Vec<f64> = qs.iter().map(|&v| v as f64 / 8.0).collect();
            q[i] = t;
            q[j] = t + k as f64 * ulp;
            Case {
                m,
                q,
                d: vec![-1.0; n],
                lambda_max: 12.0,
                note: format!("first step: rows {i} < {j}? gap {k} ulps"),
            }
        })
}

/// The random block beside the near-tie block `[[1, 1], [1, 1 + delta]]`.
fn inside_path() -> impl Strategy<Value = Case> {
    (2usize..=4)
        .prop_flat_map(|n| {
            (
                monotone(n),
                prop::collection::vec(-16i32..=32, n),
                prop::collection::vec(-16i32..=4, n),
                4i32..=24,
                42i32..=51,
                any::<bool>(),
            )
        })
        .prop_map(|(a, qs, ds, s8, k, swap)| {
            let n1 = qs.len();
            let n = n1 + 2;
            let mut m = vec![0.0; n * n];
            for i in 0..n1 {
                for j in 0..n1 {
                    m[i * n + j] = a[i * n1 + j];
                }
            }
            let delta = 2f64.powi(-k);
            let s = s8 as f64 / 8.0;
            let (r1, r2) = if swap { (n1 + 1, n1) } else { (n1, n1 + 1) };
            m[r1 * n + r1] = 1.0;
            m[r1 * n + r2] = 1.0;
            m[r2 * n + r1] = 1.0;
            m[r2 * n + r2] = 1.0 + delta;
            let mut q: Vec<f64> = qs.iter().map(|&v| v as f64 / 8.0).collect();
            let mut d: Vec<f64> = ds.iter().map(|&v| v as f64 / 8.0).collect();
            q.resize(n, 0.0);
            d.resize(n, 0.0);
            q[r1] = s;
            q[r2] = s + (s + 1.0) * delta;
            d[r1] = -1.0;
            d[r2] = -(1.0 + delta);
            Case {
                m,
                q,
                d,
                lambda_max: 4.0 + s,
                note: format!("inside: s = {s}, delta = 2^-{k}, rows {r1} then {r2}"),
            }
        })
}

/// `plcp::solve` in `T` (default settings): a `reached` path must certify.
/// Returns whether it was `reached`.
fn reached_is_certified<T: Scalar>(case: &Case) -> Result<bool, TestCaseError> {
    let problem: Plcp<T> = case.problem().cast();
    let path = plcp::solve(&problem, &Settings::default()).unwrap();
    if path.status != Status::Reached {
        return Ok(false);
    }
    let cert = path.certify(&problem);
    prop_assert!(
        cert.certified(),
        "{}: {} reported reached on a path the certificate rejects: {} ({:?})",
        T::NAME,
        case.note,
        cert.summary(),
        case
    );
    Ok(true)
}

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        max_shrink_iters: 256,
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "proptest-regressions/near_ties.txt",
        ))),
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config(48))]

    #[test]
    fn f64_near_tie_at_the_first_step(case in first_step()) {
        // well-conditioned: the refined ratios separate the rows, so the
        // path is traced to L_max (and certified)
        prop_assert!(reached_is_certified::<f64>(&case)?, "{case:?}");
    }

    // fails (2026-11-26): f64 now orders the near tie, but the later block
    // `w_2 = delta (s - L)`-like entry of size `delta` is below the pivot
    // tolerance's noise level and is lost (not a tie; docs/limits.md)
    #[test]
    fn f64_near_tie_inside_the_path(case in inside_path()) {
        reached_is_certified::<f64>(&case)?;
    }

    #[test]
    fn fx128_near_tie_inside_the_path(case in inside_path()) {
        reached_is_certified::<fx128>(&case)?;
    }
}

/// The planted block alone with no `L_max`: `M = [[1, 1], [1, 1 + delta]]`,
/// `q = (1, 1 + 2 delta)`, `d = (-1, -(1 + delta))`. `w_1` leaves at
/// `L = 1`; then `w_2 = delta (2 - L)` falls at the rate `delta`, below the
/// pivot tolerance of a column of one, and leaves at `L = 2`; the ray from
/// there is `z = (1, L - 2)`. Where no row blocks on a ray with no end the
/// small entries were not read again: f64 claimed `unbounded_ray` from
/// `L = 1`, `w_2` negative beyond `L = 2` (the rate below the pivot
/// tolerance, above 16 roundings of the column: f32 at `2^-12`, f64 at
/// `2^-30`, `2^-40`; fx128 at `2^-50`, the data exact in f64). With the
/// basis of the last segment (condition about `4 / delta`) within the
/// precision's limit the path is the exact one, certified; with
/// `delta = 2^-46` in f64 the
/// basis at `L = 2` is beyond it and the trace stops `ill_conditioned`
/// there: never a ray the certificate rejects.
#[test]
fn small_rate_on_a_ray_with_no_end_blocks() {
    fn check<T: Scalar>(k: i32) -> (Status, Vec<f64>, String) {
        let delta = 2f64.powi(-k);
        let m = Mat::<T>::from_fn(2, 2, |i, j| {
            T::from_f64(if i == 1 && j == 1 { 1.0 + delta } else { 1.0 })
        });
        let q = Col::<T>::from_fn(2, |i| T::from_f64([1.0, 1.0 + 2.0 * delta][i]));
        let d = Col::<T>::from_fn(2, |i| T::from_f64([-1.0, -(1.0 + delta)][i]));
        let problem = Plcp::new(m.as_ref(), q.as_ref(), d.as_ref()).unwrap();
        assert_eq!(problem.lambda_max(), None);
        let path = plcp::solve(&problem, &Settings::default()).unwrap();
        let cert = path.certify(&problem);
        let at: Vec<f64> = path.breakpoints.iter().map(|b| b.lambda.to_f64()).collect();
        let got = format!(
            "{} delta 2^-{k}: {} at {at:?}: {} ({})",
            T::NAME,
            path.status.as_str(),
            cert.summary(),
            path.message
        );
        if path.status.is_success() {
            assert!(cert.certified(), "{got}");
        }
        (path.status, at, got)
    }
    for (status, at, got) in [
        check::<f64>(40),
        check::<f64>(30),
        check::<f32>(12),
        check::<fx128>(50),
    ] {
        assert_eq!(status, Status::UnboundedRay, "{got}");
        assert_eq!(at.len(), 2, "{got}");
        assert!(
            (at[0] - 1.0).abs() <= 1e-6 && (at[1] - 2.0).abs() <= 1e-6,
            "{got}"
        );
    }
    let (status, at, got) = check::<f64>(46);
    assert_eq!(status, Status::IllConditioned, "{got}");
    assert!(at.len() == 1 && got.contains("at L = 2e0"), "{got}");
}
