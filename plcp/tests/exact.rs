//! Exact rational arithmetic: certification of float paths, rejection of
//! tampered ones, agreement of the exact tracer with the float path, and the
//! property that a success status never comes with a rejected certificate.

use crate::common;

use common::{col_t, mat_t, monotone};
use faer::{col, mat, Mat};
use plcp::exact::{self, short};
use plcp::{Plcp, Scalar, Settings, Status, Var};
use proptest::prelude::*;
use proptest::test_runner::{Config as ProptestConfig, FileFailurePersistence};

fn small() -> Plcp<f64> {
    // w = q + L d + M z, M positive definite: breakpoints at L = 1 (w0) and
    // then where w1 = 1 - L/2 - (z0 contribution) reaches zero
    let m = mat![[2.0, 1.0], [1.0, 2.0]];
    Plcp::new(
        m.as_ref(),
        col![1.0, 1.0].as_ref(),
        col![-1.0, -0.5].as_ref(),
    )
    .unwrap()
}

#[test]
fn a_float_path_is_certified_with_its_exact_breakpoints() {
    let problem = small();
    let path = plcp::solve(&problem, &Settings::default()).unwrap();
    let cert = path.certify(&problem);
    assert!(cert.certified(), "{}", cert.summary());
    assert_eq!(cert.segments, path.segments.len());
    assert_eq!(short(&cert.breakpoints[0]), "1");
    // after L = 1: z0 = (L - 1)/2, w1 = 1 - L/2 + z0 = 1/2 - L/2 + L/2 ... never
    // zero: the path is an unbounded ray after its first breakpoint
    assert_eq!(path.status, Status::UnboundedRay);
    assert_eq!(cert.breakpoints.len(), path.segments.len() - 1);
}

#[test]
fn a_wrong_basis_is_rejected() {
    let problem = small();
    let mut path = plcp::solve(&problem, &Settings::default()).unwrap();
    // segment 1 has z0 basic; claim w0 instead
    assert_eq!(path.segments[1].basis[0], Var::Z(0));
    path.segments[1].basis[0] = Var::W(0);
    let cert = exact::certify(&problem, &path);
    let f = cert.failure.expect("rejected");
    assert_eq!(f.segment, 1, "{}", f.reason);
    // a basis that is not complementary
    let mut path = plcp::solve(&problem, &Settings::default()).unwrap();
    path.segments[0].basis[1] = Var::W(0);
    let f = exact::certify(&problem, &path).failure.expect("rejected");
    assert_eq!(f.segment, 0);
    assert!(f.reason.contains("complementary"), "{}", f.reason);
}

#[test]
fn a_shifted_breakpoint_is_rejected() {
    let problem = small();
    let mut path = plcp::solve(&problem, &Settings::default()).unwrap();
    // the exact breakpoint is 1; move it by 1e-6 (relative), far above sqrt(eps)
    path.segments[0].lambda_to = 1.0 + 1e-6;
    path.segments[1].lambda_from = 1.0 + 1e-6;
    path.breakpoints[0].lambda = 1.0 + 1e-6;
    let f = exact::certify(&problem, &path).failure.expect("rejected");
    assert_eq!(f.segment, 0, "{}", f.reason);
    assert!(f.reason.contains("breakpoint"), "{}", f.reason);
}

#[test]
fn wrong_values_on_a_right_basis_are_rejected() {
    let problem = small();
    let mut path = plcp::solve(&problem, &Settings::default()).unwrap();
    path.segments[0].w_from[1] *= 1.001;
    let f = exact::certify(&problem, &path).failure.expect("rejected");
    assert_eq!(f.segment, 0);
    assert!(f.reason.contains("w1"), "{}", f.reason);
}

#[test]
fn a_claimed_unbounded_ray_that_ends_is_rejected() {
    // w = (1 - L, 2 - L) + I z: z0 enters at 1, z1 at 2 ... truncate after the
    // first breakpoint and claim a ray
    let m = Mat::<f64>::identity(2, 2);
    let problem = Plcp::new(
        m.as_ref(),
        col![1.0, 2.0].as_ref(),
        col![-1.0, -1.0].as_ref(),
    )
    .unwrap();
    let mut path = plcp::solve(&problem, &Settings::default()).unwrap();
    assert_eq!(path.segments.len(), 3);
    path.segments.truncate(2);
    path.breakpoints.truncate(1);
    path.segments[1].unbounded = true;
    let f = exact::certify(&problem, &path).failure.expect("rejected");
    assert_eq!(f.segment, 1, "{}", f.reason);
    // and solve_certified turns such a success into ill_conditioned: here via
    // the library path, which is right, so it stays a success
    let ok = plcp::solve_certified(&problem, &Settings::default()).unwrap();
    assert_eq!(ok.status, Status::UnboundedRay);
    let c = ok.info.certificate.as_ref().unwrap();
    let bps: Vec<String> = c.breakpoints.iter().map(short).collect();
    assert_eq!(bps, ["1", "2"]);
}

/// Dyadic monotone instances (exact in f32, f64 and fx128), `q` of both
/// signs so that the start phase runs, `L` from 0 to `lambda_max` or infinity.
fn instance() -> impl Strategy<Value = (Mat<f64>, Vec<f64>, Vec<f64>, Option<f64>)> {
    (1usize..=7).prop_flat_map(|n| {
        (
            prop::collection::vec(-8i32..=8, n * n),
            prop::collection::vec(-8i32..=8, n * n),
            prop::collection::vec(-64i32..=64, n),
            prop::collection::vec(-64i32..=64, n),
            prop_oneof![Just(None), (1i32..=64).prop_map(Some)],
            prop_oneof![Just(0.125), Just(0.0)],
        )
            .prop_map(move |(b, s, q, d, lm, shift)| {
                let b: Vec<f64> = b.iter().map(|k| *k as f64 / 8.0).collect();
                let s: Vec<f64> = s.iter().map(|k| *k as f64 / 8.0).collect();
                let m = monotone(&b, n, n, &s, shift);
                let q = q.iter().map(|k| *k as f64 / 64.0).collect();
                let d = d.iter().map(|k| *k as f64 / 64.0).collect();
                (m, q, d, lm.map(|k| k as f64 / 8.0))
            })
    })
}

fn build<T: Scalar>(inst: &(Mat<f64>, Vec<f64>, Vec<f64>, Option<f64>)) -> Plcp<T> {
    let (m, q, d, lm) = inst;
    let m = mat_t::<T>(m.as_ref());
    Plcp::new(m.as_ref(), col_t::<T>(q).as_ref(), col_t::<T>(d).as_ref())
        .unwrap()
        .with_range(T::zero(), lm.map(T::from_f64))
        .unwrap()
}

/// A success status never comes with a rejected certificate; on these
/// well-conditioned data (`shift > 0`: positive definite) the f64 and fx128
/// paths are certified outright.
fn never_success_uncertified<T: Scalar>(
    inst: &(Mat<f64>, Vec<f64>, Vec<f64>, Option<f64>),
    must_certify: bool,
) -> Result<(), TestCaseError> {
    let problem = build::<T>(inst);
    let path = plcp::solve_certified(&problem, &Settings::default()).unwrap();
    let cert = path.info.certificate.as_ref().unwrap();
    prop_assert!(
        !path.status.is_success() || cert.certified(),
        "[{}] {} with {}",
        T::NAME,
        path.status.as_str(),
        cert.summary()
    );
    if must_certify {
        prop_assert!(
            path.status.is_success() && cert.certified(),
            "[{}] {} / {} / {}",
            T::NAME,
            path.status.as_str(),
            cert.summary(),
            path.message
        );
    }
    Ok(())
}

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(
            "proptest-regressions/exact.txt",
        ))),
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config(200))]

    #[test]
    fn f64_success_is_certified(inst in instance()) {
        let pd = inst.0[(0, 0)] >= 0.0 && is_pd(&inst.0);
        never_success_uncertified::<f64>(&inst, pd)?;
    }

    #[test]
    fn f32_success_is_never_uncertified(inst in instance()) {
        never_success_uncertified::<f32>(&inst, false)?;
    }

    #[test]
    fn fx128_success_is_certified(inst in instance()) {
        let pd = is_pd(&inst.0);
        never_success_uncertified::<faer::fx128>(&inst, pd)?;
    }

    /// The exact tracer and the float path agree: same statuses, the float
    /// breakpoints within 1e-9 of the exact ones, and the exact path certifies.
    #[test]
    fn exact_tracer_agrees_with_the_float_path(inst in instance()) {
        let problem = build::<f64>(&inst);
        if !is_pd(&inst.0) {
            return Ok(());
        }
        let float = plcp::solve(&problem, &Settings::default()).unwrap();
        let exact = exact::trace(&problem, &Settings::default()).unwrap();
        prop_assert_eq!(exact.path.status, float.status, "{}", exact.path.message);
        prop_assert_eq!(exact.path.info.precision, "exact");
        let fb: Vec<f64> = float.segments.iter().map(|s| s.lambda_to).collect();
        let eb: Vec<f64> = exact.path.segments.iter().map(|s| s.lambda_to).collect();
        prop_assert_eq!(fb.len(), eb.len(), "float {:?} exact {:?}", fb, eb);
        for (f, e) in fb.iter().zip(&eb) {
            prop_assert!(f == e || (f - e).abs() <= 1e-9 * e.abs().max(1.0), "float {:?} exact {:?}", fb, eb);
        }
        let cert = exact::certify(&problem, &exact.path);
        prop_assert!(cert.certified(), "{}", cert.summary());
    }
}

/// Positive definite symmetric part (Cholesky in f64 of `(M + M')/2`, with margin).
fn is_pd(m: &Mat<f64>) -> bool {
    let n = m.nrows();
    let s = Mat::from_fn(n, n, |i, j| 0.5 * (m[(i, j)] + m[(j, i)]));
    let mut l = Mat::<f64>::zeros(n, n);
    for j in 0..n {
        let mut d = s[(j, j)];
        for k in 0..j {
            d -= l[(j, k)] * l[(j, k)];
        }
        if d <= 1e-3 {
            return false;
        }
        l[(j, j)] = d.sqrt();
        for i in j + 1..n {
            let mut v = s[(i, j)];
            for k in 0..j {
                v -= l[(i, k)] * l[(j, k)];
            }
            l[(i, j)] = v / l[(j, j)];
        }
    }
    true
}

#[test]
fn exact_precision_has_a_size_limit() {
    let n = exact::EXACT_MAX_DIM + 1;
    let m = Mat::<f64>::identity(n, n);
    let q = faer::Col::<f64>::from_fn(n, |_| 1.0);
    let problem = Plcp::new(m.as_ref(), q.as_ref(), q.as_ref()).unwrap();
    let err = exact::trace(&problem, &Settings::default()).unwrap_err();
    assert!(err.to_string().contains("limit"), "{err}");
}

#[test]
fn exact_continuation_from_a_segment_basis() {
    let m = Mat::<f64>::identity(2, 2);
    let problem = Plcp::new(
        m.as_ref(),
        col![1.0, 2.0].as_ref(),
        col![-1.0, -1.0].as_ref(),
    )
    .unwrap();
    let float = plcp::solve(&problem, &Settings::default()).unwrap();
    let seg = &float.segments[1];
    let cont =
        exact::trace_from(&problem, &Settings::default(), &seg.basis, seg.lambda_from).unwrap();
    assert_eq!(cont.path.status, Status::UnboundedRay);
    let bps: Vec<String> = cont.breakpoints.iter().map(short).collect();
    assert_eq!(bps, ["2"]);
    assert_eq!(cont.path.lambda0, 1.0);
    // an infeasible basis at that L is an error
    let bad = exact::trace_from(&problem, &Settings::default(), &[Var::W(0), Var::W(1)], 1.5);
    assert!(bad.is_err());
}

/// `plcp solve --certify` (issue 14: certification from the command line):
/// the JSON carries a certificate, certified, with the exact breakpoint `1`.
#[cfg(feature = "cli")]
#[test]
fn the_command_line_certifies() {
    let dir = std::env::temp_dir().join(format!("plcp-certify-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("small.json");
    std::fs::write(
        &file,
        r#"{"M": [[2, 1], [1, 2]], "q": [1, 1], "d": [-1, -0.5]}"#,
    )
    .unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_plcp"))
        .args(["solve", file.to_str().unwrap(), "--certify"])
        .output()
        .expect("run plcp");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout} {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let compact: String = stdout.chars().filter(|c| !c.is_whitespace()).collect();
    assert!(compact.contains(r#""certificate":{"#), "{stdout}");
    assert!(compact.contains(r#""certified":true"#), "{stdout}");
    assert!(compact.contains(r#""breakpoints":["1"]"#), "{stdout}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The exact path names its breakpoints as the float paths do: the variable
/// that enters is the leaving one's complement (`z_0` for `w_0` at `L = 1`).
/// It named the column pivoted in at the breakpoint, the one that had been
/// moving: `L` at the first, then the previous complement (`in L out w0`,
/// `in z0 out w1`), and an escalated path mixed both conventions.
#[test]
fn exact_breakpoints_name_the_entering_variable_as_the_float_paths_do() {
    let m = faer::mat![[4.0, 1.0, 0.5], [1.0, 3.0, 1.0], [0.5, 1.0, 2.0]];
    let q = faer::col![1.0, 2.0, 3.0];
    let d = faer::col![-1.0, -1.0, -1.0];
    let problem = plcp::Plcp::new(m.as_ref(), q.as_ref(), d.as_ref()).unwrap();
    let float = plcp::solve(&problem, &Settings::default()).unwrap();
    let exact = plcp::exact::trace(&problem, &Settings::default()).unwrap();
    assert_eq!(float.breakpoints.len(), 3);
    let names = |p: &plcp::Path<f64>| -> Vec<(plcp::Var, plcp::Var)> {
        p.breakpoints
            .iter()
            .map(|b| (b.entering, b.leaving))
            .collect()
    };
    assert_eq!(names(&exact.path), names(&float));
    assert_eq!(names(&exact.path)[0], (plcp::Var::Z(0), plcp::Var::W(0)));
}
