//! The fast share of the stiff and extreme suite (`examples/stiff_report.rs`
//! runs every case): in f32, f64 and fx128, no answer may be reported as a
//! success (`reached`, `unbounded_ray`) with a breakpoint error or residual
//! beyond what the precision allows (f32 1e-2, f64 1e-8, fx128 1e-16; see
//! `allowance` in `examples/common/stiff_core.rs` for the reasons).

#[path = "../examples/common/stiff_core.rs"]
mod stiff_core;
#[path = "../examples/common/stiff_random.rs"]
mod stiff_random;

use plcp::Scalar;
use rand::SeedableRng;

fn check(cases: &[stiff_core::Case]) {
    let mut table = stiff_core::header();
    let mut wrong = Vec::new();
    for case in cases.iter().filter(|c| c.fast) {
        for r in stiff_core::run_case(case) {
            table += &stiff_core::line(&r);
            if r.wrong || r.status == "PANIC" {
                wrong.push(stiff_core::line(&r));
            }
        }
    }
    println!("{table}");
    assert!(
        wrong.is_empty(),
        "wrong answers reported as success (or panics):\n{}{}",
        stiff_core::header(),
        wrong.concat()
    );
}

#[test]
fn stiff_plcp_and_frames_cases_no_confident_wrong_answer() {
    check(&stiff_core::cases());
}

#[test]
fn siconos_degenerate_lcps_no_confident_wrong_answer() {
    match stiff_core::siconos_cases() {
        Ok(c) => check(&c),
        Err(msg) => eprintln!("{msg}"),
    }
}

/// Cases drawn at random (`examples/stiff_hunt.rs` draws more): cases the suite's
/// authors did not pick, so a rule tuned to the hand-made cases shows here.
#[test]
fn random_stiff_and_degenerate_cases_no_confident_wrong_answer() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(20261123);
    let families = stiff_random::FAMILIES;
    let cases: Vec<stiff_core::Case> = (0..500)
        .map(|k| stiff_random::draw(&mut rng, families[k % families.len()], k))
        .collect();
    check(&cases);
}

#[test]
fn breakpoint_distance_is_order_insensitive() {
    assert_eq!(
        stiff_core::breakpoint_error(&[1.0, 1.0, 2.0], &[2.0, 1.0], f64::INFINITY),
        0.0
    );
    assert!(stiff_core::breakpoint_error(&[1.0], &[1.0, 3.0], f64::INFINITY) > 0.5);
    assert_eq!(stiff_core::breakpoint_error(&[1.0], &[1.0, 3.0], 2.0), 0.0);
}

/// Issue 14: the random case "huge #9" (n = 5, the draws of the test above)
/// traced in exact arithmetic. Its lexicographic rule read only part of
/// `B^-1` and cycled on the turning path to the pivot limit; the path must
/// end as fx128's does, with the same breakpoints, and fx128's path must
/// be certified.
#[test]
fn huge_9_traced_exactly_agrees_with_fx128() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(20261123);
    let families = stiff_random::FAMILIES;
    let case = (0..=9)
        .map(|k| stiff_random::draw(&mut rng, families[k % families.len()], k))
        .last()
        .expect("ten cases");
    assert!(case.name.starts_with("huge #9"), "{}", case.name);
    let stiff_core::Problem::Plcp { m, q, d, .. } = &case.problem else {
        panic!("a PLCP")
    };
    let n = q.len();
    let m = faer::Mat::<f64>::from_fn(n, n, |i, j| m[i][j]);
    let q = faer::Col::<f64>::from_fn(n, |i| q[i]);
    let d = faer::Col::<f64>::from_fn(n, |i| d[i]);
    let p64 = plcp::Plcp::new(m.as_ref(), q.as_ref(), d.as_ref()).unwrap();
    let settings = plcp::Settings::<f64>::default();
    let exact = plcp::exact::trace(&p64, &settings).unwrap();
    let p128: plcp::Plcp<faer::fx128> = p64.cast();
    let path128 = plcp::solve(&p128, &plcp::Settings::default()).unwrap();
    // the exact path is a closed loop through L0 (12 breakpoints round,
    // L in [-1.766, 0.273]): found and said, never a pivot limit or success
    assert_eq!(
        exact.path.status,
        plcp::Status::SecondaryRay,
        "{}",
        exact.path.message
    );
    assert!(
        exact.path.message.contains("closed loop"),
        "{}",
        exact.path.message
    );
    assert!(exact.path.info.pivots < 30, "{}", exact.path.info.pivots);
    // fx128 agrees on the breakpoints it has before it stops, and claims no
    // success (its fourth segment is already off: the exact certificate
    // rejects it)
    assert!(!path128.status.is_success(), "{}", path128.message);
    let agree = path128
        .breakpoints
        .iter()
        .zip(&exact.breakpoints)
        .take_while(|(a, b)| {
            let e = plcp::exact::rational_to_f64(b);
            (a.lambda.to_f64() - e).abs() <= 1e-12 * e.abs().max(1.0)
        })
        .count();
    assert!(agree >= 3, "fx128 and exact agree on {agree} breakpoints");
    // the exact path, rounded, is certified; fx128's is not past the agreement
    let cert = plcp::certify(&p64, &exact.path);
    assert!(cert.certified(), "{}", cert.summary());
    let cert = plcp::certify(&p128, &path128);
    assert!(!cert.certified() || agree == path128.breakpoints.len());
}

/// Issue 14: the last step of the escalation, f64 then fx128 then exact
/// (`Settings::escalate_exact`). The random case "scaled #0" (n = 10, the
/// draws of the test above; `D M D` with `D` spanning up to 1e+-8) traced in
/// fx128 ends `ill_conditioned`; with the exact tail the path is
/// finished in exact arithmetic, certified, ends as the exact tracer's, and
/// the escalation says which precision produced each segment.
#[test]
fn escalation_ends_in_exact_arithmetic_and_is_certified() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(20261123);
    let case = stiff_random::draw(&mut rng, stiff_random::FAMILIES[0], 0);
    assert!(case.name.starts_with("scaled #0"), "{}", case.name);
    let stiff_core::Problem::Plcp { m, q, d, free, .. } = &case.problem else {
        panic!("a PLCP")
    };
    let n = q.len();
    let m = faer::Mat::<f64>::from_fn(n, n, |i, j| m[i][j]);
    let q = faer::Col::<f64>::from_fn(n, |i| q[i]);
    let d = faer::Col::<f64>::from_fn(n, |i| d[i]);
    let problem = plcp::Plcp::mixed(m.as_ref(), q.as_ref(), d.as_ref(), *free).unwrap();
    let p128: plcp::Plcp<faer::fx128> = problem.cast();
    let mut settings = plcp::Settings::<faer::fx128> {
        escalate: true,
        ..Default::default()
    };
    let floats = plcp::solve(&p128, &settings).unwrap();
    println!(
        "floats: {} {:?} {:?}",
        floats.status.as_str(),
        floats
            .breakpoints
            .iter()
            .map(|b| b.lambda.to_f64())
            .collect::<Vec<_>>(),
        floats
            .info
            .escalation
            .as_ref()
            .map(|e| &e.segment_precisions)
    );
    assert_eq!(
        floats.status,
        plcp::Status::IllConditioned,
        "fx128: {}",
        floats.message
    );
    settings.escalate_exact = true;
    let path = plcp::solve(&p128, &settings).unwrap();
    let esc = path.info.escalation.clone().expect("escalated");
    println!(
        "exact tail: {} {:?} {:?} from {}: {}",
        path.status.as_str(),
        path.breakpoints
            .iter()
            .map(|b| b.lambda.to_f64())
            .collect::<Vec<_>>(),
        esc.segment_precisions,
        esc.lambda_exact,
        path.message
    );
    assert!(esc.exact, "{}", esc.exact_note);
    assert_ne!(
        path.status,
        plcp::Status::IllConditioned,
        "{}",
        path.message
    );
    assert_eq!(esc.segment_precisions.len(), path.segments.len());
    assert_eq!(esc.segment_precisions.last(), Some(&"exact"));
    // as the exact tracer ends, with its breakpoints
    let exact = plcp::exact::trace(&problem, &plcp::Settings::default()).unwrap();
    assert_eq!(path.status, exact.path.status, "{}", exact.path.message);
    assert_eq!(path.breakpoints.len(), exact.breakpoints.len());
    for (a, b) in path.breakpoints.iter().zip(&exact.breakpoints) {
        let (a, e) = (a.lambda.to_f64(), plcp::exact::rational_to_f64(b));
        assert!((a - e).abs() <= 1e-9 * e.abs().max(1e-300), "{a} vs {e}");
    }
    if path.status.is_success() {
        let cert = plcp::certify(&p128, &path);
        assert!(cert.certified(), "{}", cert.summary());
    }
}
