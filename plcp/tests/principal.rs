//! The principal-pivoting fast path (`Settings::principal`, `src/principal.rs`)
//! against the general engine (the same problem with `principal: false`) and
//! against exact certification; and the cases it must hand back.

use faer::{col, mat, Col, Mat};
use plcp::{solve, Plcp, Settings, Status};
use proptest::prelude::*;

const FAST: &str = "lemke (principal)";

fn engine() -> Settings<f64> {
    Settings {
        principal: false,
        ..Settings::default()
    }
}

/// Solves with both; asserts they agree. Returns whether the fast path answered.
fn compare(p: &Plcp<f64>) -> bool {
    let a = solve(p, &Settings::default()).unwrap();
    let b = solve(p, &engine()).unwrap();
    assert_eq!(b.info.method, "lemke");
    assert_eq!(a.status, b.status, "{} / {}", a.message, b.message);
    assert_eq!(a.breakpoints.len(), b.breakpoints.len());
    if a.info.method != FAST {
        // declined: the engine's own answer
        assert_eq!(a.info.method, "lemke");
        for (x, y) in a.breakpoints.iter().zip(&b.breakpoints) {
            assert_eq!(x.lambda, y.lambda);
        }
        return false;
    }
    assert_eq!(a.status, Status::Reached);
    for (x, y) in a.breakpoints.iter().zip(&b.breakpoints) {
        assert_eq!((x.entering, x.leaving), (y.entering, y.leaving));
        let tol = 1e-9 * y.lambda.abs().max(1.0);
        assert!(
            (x.lambda - y.lambda).abs() <= tol,
            "breakpoint {} against {}",
            x.lambda,
            y.lambda
        );
        assert!(!x.degenerate && !x.turning);
    }
    assert_eq!(a.segments.len(), b.segments.len());
    for (x, y) in a.segments.iter().zip(&b.segments) {
        assert_eq!(x.basis, y.basis);
    }
    let scale = |c: &Col<f64>| c.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    let (sz, sw) = (scale(&b.end.z), scale(&b.end.w));
    for i in 0..p.n() {
        assert!((a.end.z[i] - b.end.z[i]).abs() <= 1e-9 * sz);
        assert!((a.end.w[i] - b.end.w[i]).abs() <= 1e-9 * sw);
    }
    assert!(a.info.residual.worst() <= 1e-12, "{:?}", a.info.residual);
    assert_eq!(a.final_basis.as_ref().map(Vec::len), Some(p.n()));
    true
}

/// `M = B B' / n + shift I + skew (K - K')`, `q` in `[0.1, 1]`, `d` in
/// `[-1.5, 0.5]`: monotone (positive definite for `shift > 0`).
fn family(n: usize, vals: &[f64], shift: f64, skew: f64, lmax: f64) -> Plcp<f64> {
    let mut it = vals.iter().cycle().copied();
    let b = Mat::<f64>::from_fn(n, n, |_, _| 2.0 * it.next().unwrap() - 1.0);
    let k = Mat::<f64>::from_fn(n, n, |_, _| it.next().unwrap() - 0.5);
    let g = crate::common::gram_shifted(b.as_ref(), shift);
    let m = Mat::<f64>::from_fn(n, n, |i, j| g[(i, j)] + skew * (k[(i, j)] - k[(j, i)]));
    let q = Col::<f64>::from_fn(n, |_| 0.1 + 0.9 * it.next().unwrap());
    let d = Col::<f64>::from_fn(n, |_| 2.0 * it.next().unwrap() - 1.5);
    Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
        .unwrap()
        .with_range(0.0, Some(lmax))
        .unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    /// Random monotone problems: where the fast path answers, its path is
    /// the engine's (same events and bases, breakpoints and end within 1e-9).
    #[test]
    fn fast_path_matches_the_engine(
        n in 1usize..24,
        vals in proptest::collection::vec(0.0f64..1.0, 64..200),
        shift in prop_oneof![Just(0.0), 0.01f64..1.0],
        skew in prop_oneof![Just(0.0), 0.0f64..1.0],
        lmax in 0.1f64..20.0,
    ) {
        compare(&family(n, &vals, shift, skew, lmax));
    }

    /// Random matrices with no structure (not monotone: turning points,
    /// secondary rays): the fast path answers only where it can vouch.
    #[test]
    fn fast_path_on_general_matrices(
        n in 1usize..10,
        vals in proptest::collection::vec(-1.0f64..1.0, 100..101),
        lmax in 0.1f64..10.0,
    ) {
        let m = Mat::<f64>::from_fn(n, n, |i, j| vals[(i * n + j) % 100] + if i == j { 0.5 } else { 0.0 });
        let q = Col::<f64>::from_fn(n, |i| 0.2 + vals[(7 * i + 3) % 100].abs());
        let d = Col::<f64>::from_fn(n, |i| vals[(11 * i + 5) % 100] - 0.3);
        let p = Plcp::new(m.as_ref(), q.as_ref(), d.as_ref()).unwrap().with_range(0.0, Some(lmax)).unwrap();
        compare(&p);
    }
}

/// The fast path answers most of a fixed sample of the monotone family (so
/// the comparison above is not vacuous), and each of its paths is certified
/// in exact arithmetic.
#[test]
fn fast_paths_are_certified() {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut fast, mut all) = (0, 0);
    for case in 0..40 {
        let n = 2 + case % 30;
        let vals: Vec<f64> = (0..199).map(|_| next()).collect();
        let p = family(n, &vals, 0.1, 0.0, 3.0 + (case % 7) as f64);
        all += 1;
        if compare(&p) {
            fast += 1;
            let path = solve(&p, &Settings::default()).unwrap();
            let cert = plcp::certify(&p, &path);
            assert!(cert.failure.is_none(), "case {case}: {:?}", cert.failure);
            assert!(
                cert.max_rel_diff <= 1e-10,
                "case {case}: {}",
                cert.max_rel_diff
            );
        }
    }
    assert!(
        fast * 4 >= all * 3,
        "the fast path answered {fast} of {all}"
    );
}

fn method(p: &Plcp<f64>, s: &Settings<f64>) -> &'static str {
    solve(p, s).unwrap().info.method
}

/// `Info::fast_path`: why the fast path did not answer.
fn why(p: &Plcp<f64>, s: &Settings<f64>) -> &'static str {
    solve(p, s).unwrap().info.fast_path
}

#[test]
fn the_tiny_problem_takes_the_fast_path() {
    let m = mat![[2.0, 1.0], [1.0, 2.0]];
    let p = Plcp::new(
        m.as_ref(),
        col![1.0, 1.0].as_ref(),
        col![-1.0, -0.5].as_ref(),
    )
    .unwrap()
    .with_range(0.0, Some(1.5))
    .unwrap();
    assert!(compare(&p));
    let path = solve(&p, &Settings::default()).unwrap();
    assert_eq!(path.breakpoints.len(), 1);
    assert_eq!(path.breakpoints[0].lambda, 1.0);
    assert_eq!(path.info.fast_path, "");
    assert_eq!(method(&p, &engine()), "lemke");
    assert_eq!(why(&p, &engine()), "not tried: Settings::principal is off");
}

/// What the fast path hands back: each answered by the engine as before.
#[test]
fn declined_cases_go_to_the_engine() {
    struct Count(usize);
    impl plcp::Observer<f64> for Count {
        fn on_segment(
            &mut self,
            _: &plcp::Segment<f64>,
            _: &plcp::Progress<'_, f64>,
        ) -> plcp::Control {
            self.0 += 1;
            plcp::Control::Continue
        }
    }
    let m = mat![[2.0, 1.0], [1.0, 2.0]];
    let mk = |m: &Mat<f64>, q: Col<f64>, d: Col<f64>, lmax: Option<f64>| {
        Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
            .unwrap()
            .with_range(0.0, lmax)
            .unwrap()
    };
    let s = Settings::default();
    // a zero w at the start (degenerate start)
    let p = mk(&m, col![1.0, 0.0], col![-1.0, -1.0], Some(2.0));
    assert_eq!(method(&p, &s), "lemke");
    assert!(why(&p, &s).starts_with("declined: the start is not strictly feasible"));
    assert!(!compare(&p));
    // the same with an observer: the reason is the fast path's own, not
    // the observer's (the engine's call of the fast path sees the observer)
    let seen = plcp::solve_observed(&p, &s, Count(0), plcp::Keep::All)
        .unwrap()
        .path;
    assert_eq!(seen.info.method, "lemke");
    assert_eq!(seen.info.fast_path, why(&p, &s));
    // two w reach zero together (a tie)
    let p = mk(
        &(2.0 * Mat::<f64>::identity(2, 2)),
        col![1.0, 1.0],
        col![-1.0, -1.0],
        Some(3.0),
    );
    assert_eq!(method(&p, &s), "lemke");
    assert!(
        why(&p, &s).starts_with("declined: a tie"),
        "{}",
        why(&p, &s)
    );
    assert!(!compare(&p));
    // a start that is not feasible (the start phase)
    let p = mk(&m, col![-1.0, 1.0], col![1.0, -1.0], Some(2.0));
    assert_eq!(method(&p, &s), "lemke");
    assert!(why(&p, &s).starts_with("declined: the start is not strictly feasible"));
    // no finite L_max (an unbounded ray is the engine's)
    let p = mk(&m, col![1.0, 1.0], col![-1.0, -0.5], None);
    assert_eq!(method(&p, &s), "lemke");
    assert_eq!(why(&p, &s), "not tried: no finite L_max");
    // an indefinite block: the Schur complement of the second pivot is
    // negative (L turns), so the path is the engine's
    let ind = mat![[1.0, -3.0], [-3.0, 1.0]];
    let p = mk(&ind, col![1.0, 1.2], col![-1.0, -1.0], Some(5.0));
    let a = solve(&p, &s).unwrap();
    assert_eq!(a.info.method, "lemke");
    assert!(
        a.info.fast_path.starts_with("declined: "),
        "{}",
        a.info.fast_path
    );
    assert!(!compare(&p));
    // an observer: the fast path's answer is handed to it after the fact
    let p = mk(&m, col![1.0, 1.0], col![-1.0, -0.5], Some(1.5));
    let obs = plcp::solve_observed(&p, &s, Count(0), plcp::Keep::All).unwrap();
    assert_eq!(obs.path.info.method, FAST);
    assert_eq!(obs.path.info.fast_path, "");
    assert_eq!(obs.observer.0, 2);
    assert_eq!(obs.path.segments.len(), 2);
    // above the order cap (`tolerance::PRINCIPAL_MAX_N`)
    let vals: Vec<f64> = (0..199).map(|i| ((i * 37 % 101) as f64) / 101.0).collect();
    let big = family(plcp::tolerance::PRINCIPAL_MAX_N + 1, &vals, 0.1, 0.0, 0.05);
    assert_eq!(method(&big, &s), "lemke");
    assert_eq!(
        why(&big, &s),
        format!(
            "not tried: order above PRINCIPAL_MAX_N = {}",
            plcp::tolerance::PRINCIPAL_MAX_N
        )
    );
    // f32 and the other bases are the engine's
    let p32 = Plcp::new(
        mat![[2.0f32, 1.0], [1.0, 2.0]].as_ref(),
        col![1.0f32, 1.0].as_ref(),
        col![-1.0f32, -0.5].as_ref(),
    )
    .unwrap()
    .with_range(0.0, Some(1.5))
    .unwrap();
    let a32 = solve(&p32, &Settings::default()).unwrap();
    assert_eq!(a32.info.method, "lemke");
    assert_eq!(a32.info.fast_path, "not tried: a precision other than f64");
    let dense = Settings {
        basis: plcp::BasisKind::Dense,
        ..Settings::default()
    };
    assert_eq!(method(&p, &dense), "lemke");
    assert_eq!(
        why(&p, &dense),
        "not tried: a basis other than the default block basis asked for"
    );
}

/// Between the old order cap (400) and the present one the fast path answers
/// a monotone problem with many pivots and its path is the engine's.
#[test]
fn a_mid_size_problem_takes_the_fast_path() {
    let n = 600;
    assert!(n <= plcp::tolerance::PRINCIPAL_MAX_N);
    let vals: Vec<f64> = (0..997).map(|i| ((i * 389 % 997) as f64) / 997.0).collect();
    let p = family(n, &vals, 0.1, 0.0, 1.0);
    assert!(compare(&p), "{}", why(&p, &Settings::default()));
    let path = solve(&p, &Settings::default()).unwrap();
    assert!(path.info.pivots >= 50, "{} pivots", path.info.pivots);
}
