//! `Settings::escalate`: a path that ends `ill_conditioned` in `f32` or `f64` is
//! continued in `fx128` from its last trustworthy segment, and matches the plain
//! `fx128` path (breakpoints and `z` along it).

use faer::{fx128, Col, Mat};
use plcp::{Method, Path, Plcp, Scalar, Settings, Status};

/// `M` = the 1-D Laplacian `tridiag(-1, 2, -1)` of order `n` with ends
/// `1 + delta` (Neumann ends: nearly singular, the constant vector is almost a
/// null vector, condition about `n^2 / delta`); an M-matrix, so every `z_i`
/// that enters stays: with `q_i = 1 + i / 10`, `d = -1` the basis grows to
/// all of the block, whose basis is ill-conditioned. One more decoupled pair
/// (`M = 1`, `q = 10`) gives the path a breakpoint after that, at `L = 10`.
fn neumann<T: Scalar>(n: usize, delta: f64) -> Plcp<T> {
    let m = Mat::<T>::from_fn(n + 1, n + 1, |i, j| {
        T::from_f64(if i == n || j == n {
            if i == j {
                1.0
            } else {
                0.0
            }
        } else if i == j {
            if i == 0 || i == n - 1 {
                1.0 + delta
            } else {
                2.0
            }
        } else if i.abs_diff(j) == 1 {
            -1.0
        } else {
            0.0
        })
    });
    let q = Col::<T>::from_fn(n + 1, |i| {
        T::from_f64(if i == n { 10.0 } else { 1.0 + i as f64 / 10.0 })
    });
    let d = Col::<T>::from_fn(n + 1, |_| T::from_f64(-1.0));
    Plcp::new(m.as_ref(), q.as_ref(), d.as_ref()).unwrap()
}

fn lambdas<T: Scalar>(p: &Path<T>) -> Vec<f64> {
    p.breakpoints.iter().map(|b| b.lambda.to_f64()).collect()
}

/// Largest relative difference of `z` between `a` and the reference at the
/// midpoints of the reference's bounded segments and one past the last start.
fn z_error<T: Scalar>(a: &Path<T>, reference: &Path<fx128>) -> f64 {
    let mut worst = 0.0f64;
    for s in &reference.segments {
        let l = if s.unbounded {
            s.lambda_from.to_f64() + 1.0
        } else {
            0.5 * (s.lambda_from.to_f64() + s.lambda_to.to_f64())
        };
        let r = s.eval(fx128::from_f64(l));
        let Some(x) = a.at(T::from_f64(l)) else {
            return f64::INFINITY;
        };
        let big = (0..r.z.nrows()).fold(1e-300f64, |m, i| m.max(r.z[i].to_f64().abs()));
        for i in 0..r.z.nrows() {
            worst = worst.max((x.z[i].to_f64() - r.z[i].to_f64()).abs() / big);
        }
    }
    worst
}

/// The settings of the cases: the basis refactorised (and its condition
/// estimated) at every pivot, and the working precision asked to give up at a
/// condition of `max_cond_eps / eps`.
fn settings<T: Scalar>(method: Method, max_cond_eps: f64, escalate: bool) -> Settings<T> {
    Settings {
        escalate,
        refactor_period: Some(1),
        max_cond_eps,
        ..Settings::with_method(method)
    }
}

/// Runs the case in `T` with and without the setting and checks the continued
/// path against the plain fx128 one to `tol` (breakpoints and z, relative).
fn check<T: Scalar>(delta: f64, max_cond_eps: f64, method: Method, tol: f64) {
    let n = 6;
    let plain = plcp::solve(
        &neumann::<T>(n, delta),
        &settings(method, max_cond_eps, false),
    )
    .unwrap();
    assert_eq!(
        plain.status,
        Status::IllConditioned,
        "{}: the case must really end ill_conditioned without the setting: {}",
        T::NAME,
        plain.message
    );
    assert!(plain.info.escalation.is_none());
    let reference =
        plcp::solve(&neumann::<fx128>(n, delta), &Settings::with_method(method)).unwrap();
    assert_eq!(
        reference.status,
        Status::UnboundedRay,
        "{}",
        reference.message
    );
    let cont = plcp::solve(
        &neumann::<T>(n, delta),
        &settings(method, max_cond_eps, true),
    )
    .unwrap();
    let esc = cont.info.escalation.as_ref().expect("escalated");
    assert_eq!(
        cont.status,
        reference.status,
        "{}: {}",
        T::NAME,
        cont.message
    );
    assert!(esc.warm, "{}: {}", T::NAME, esc.note);
    assert_eq!(esc.from, T::NAME);
    assert!(esc.lambda <= plain.lambda_reached.to_f64());
    assert!(esc.pivots_fx128 > 0 && cont.info.pivots == esc.pivots_before + esc.pivots_fx128);
    assert!(
        cont.message.contains("continued in f128"),
        "{}",
        cont.message
    );
    // the part before the restart is the working precision's own
    assert!(esc.kept_segments > 0, "{}: nothing kept", T::NAME);
    let (a, b) = (lambdas(&cont), lambdas(&reference));
    assert_eq!(a.len(), b.len(), "{}: {a:?} vs {b:?}", T::NAME);
    for (x, y) in a.iter().zip(&b) {
        assert!(
            (x - y).abs() <= tol * y.abs().max(1.0),
            "{}: {a:?} vs {b:?}",
            T::NAME
        );
    }
    let ze = z_error(&cont, &reference);
    assert!(ze <= tol, "{}: z error {ze:e}", T::NAME);
    // residuals measured on the original problem, within the precision's guard
    assert!(
        cont.info.residual.worst() <= T::eps().to_f64().sqrt(),
        "{:?}",
        cont.info.residual
    );
}

// the full block's basis has condition about 2.9 / delta, the earlier ones at
// most 84: f64 gives up at 4.5e6 (max_cond_eps 1e-9), f32 at 126 (1.5e-5)

#[test]
fn f64_ill_conditioned_path_is_continued_in_fx128() {
    check::<f64>(1e-5, 1e-9, Method::Lemke, 1e-9);
    check::<f64>(1e-5, 1e-9, Method::Wolfe, 1e-9);
}

#[test]
fn f32_ill_conditioned_path_is_continued_in_fx128() {
    check::<f32>(1e-1, 1.5e-5, Method::Lemke, 1e-5);
}

#[test]
fn setting_off_or_in_fx128_changes_nothing() {
    // the setting off is the default; on, a path that does not end
    // ill_conditioned is left as it is
    assert!(!Settings::<f64>::default().escalate);
    let pr = neumann::<f64>(6, 1e-5);
    let a = plcp::solve(&pr, &settings(Method::Lemke, 1e-2, false)).unwrap();
    let b = plcp::solve(&pr, &settings(Method::Lemke, 1e-2, true)).unwrap();
    assert!(a.status.is_success() && b.info.escalation.is_none());
    assert_eq!(lambdas(&a), lambdas(&b));
    // fx128 itself never escalates
    let c = plcp::solve(
        &neumann::<fx128>(6, 1e-5),
        &settings(Method::Lemke, 1e-28, true),
    )
    .unwrap();
    assert_eq!(c.status, Status::IllConditioned);
    assert!(c.info.escalation.is_none());
}

/// Issue 14: the last step of the escalation on a path that reaches `L_max`.
/// The Neumann case in fx128 (`delta = 1e-5`, `L_max = 20`, the basis
/// refactorised at every pivot) with fx128 asked to give up at a condition of
/// `1e-28 / eps = 2e3`: the full block's basis stops it `ill_conditioned`
/// after six segments (conditions up to 84); with `Settings::escalate_exact`
/// the exact tracer finishes the path from inside a kept fx128 segment and
/// reaches `L_max`, with the exact tracer's breakpoints, and the escalation
/// names each segment's precision (fx128 first, exact from `lambda_exact`
/// on). The end at `L_max` had residual 0.5 (the exact tracer read its
/// tableau's basic values without the part-way driver); it is now the last
/// segment there. The exact tail comes back rounded once from its exact
/// values to fx128, so the path ends `reached` and is certified; it came back
/// rounded to `f64`, and its first segment, extended back into the kept
/// fx128 segment in `f64`, had residual `5e-11`, above fx128's residual
/// guard, which turned the answer `ill_conditioned`.
#[test]
fn exact_tail_reaches_l_max_after_float_segments() {
    let problem = neumann::<fx128>(6, 1e-5)
        .with_range(fx128::from_f64(0.0), Some(fx128::from_f64(20.0)))
        .unwrap();
    let base = settings::<fx128>(Method::Lemke, 1e-28, true);
    let plain = plcp::solve(&problem, &base).unwrap();
    assert_eq!(plain.status, Status::IllConditioned, "{}", plain.message);
    let path = plcp::solve(
        &problem,
        &Settings {
            escalate_exact: true,
            ..base
        },
    )
    .unwrap();
    let esc = path.info.escalation.as_ref().expect("escalated");
    println!(
        "{} {:?} {:?} from {}: {}",
        path.status.as_str(),
        lambdas(&path),
        esc.segment_precisions,
        esc.lambda_exact,
        path.message
    );
    assert!(esc.exact, "{}", esc.exact_note);
    assert!(
        path.message.contains("the exact run ended reached"),
        "{}",
        path.message
    );
    assert_eq!(path.end.lambda.to_f64(), 20.0);
    let end = plcp::residual::residual(&problem, &path.end);
    assert!(end.worst() <= 1e-28, "the end at L_max: {end:?}");
    assert_eq!(path.status, Status::Reached, "{}", path.message);
    // the exact breakpoints keep the residuals the exact tracer measured in f64
    assert!(
        path.info.residual.worst() <= 1e-15,
        "{:?}",
        path.info.residual
    );
    let cert = path.certify(&problem);
    assert!(cert.certified(), "{}", cert.summary());
    assert_eq!(esc.segment_precisions.len(), path.segments.len());
    let float = <fx128 as Scalar>::NAME;
    let first_exact = esc
        .segment_precisions
        .iter()
        .position(|p| *p == "exact")
        .expect("an exact part");
    assert!(first_exact > 0, "{:?}", esc.segment_precisions);
    assert!(esc.segment_precisions[..first_exact]
        .iter()
        .all(|p| *p == float));
    assert!(esc.segment_precisions[first_exact..]
        .iter()
        .all(|p| *p == "exact"));
    assert_eq!(
        esc.lambda_exact,
        path.segments[first_exact].lambda_from.to_f64(),
        "{:?}",
        esc.segment_precisions
    );
    // the exact tracer's breakpoints
    let exact = plcp::exact::trace(&problem, &Settings::default()).unwrap();
    assert_eq!(exact.path.status, Status::Reached, "{}", exact.path.message);
    assert_eq!(path.breakpoints.len(), exact.breakpoints.len());
    for (a, b) in path.breakpoints.iter().zip(&exact.breakpoints) {
        let (a, e) = (a.lambda.to_f64(), plcp::exact::rational_to_f64(b));
        assert!((a - e).abs() <= 1e-15 * e.abs().max(1.0), "{a} vs {e}");
    }
}

/// Issue 14: a problem on which f64 and then fx128 both give a wrong path
/// that they report `reached` (no basis looks ill-conditioned to them), so
/// that only the certificate sees it; block diagonal, `L_max = 6`:
///
/// * `w_0 = 1 - L + z_0`: an event at `L = 1` that every precision gets;
/// * `[[1, 1], [1, 1 + delta]]`, `delta = 2^-46`, `q = (1.5, 1.5 + 2.5 delta)`,
///   `d = (-1, -(1 + delta))`: `z_1` enters at `L = 1.5` and `z_2` at `2.5`
///   (`w_2 = delta (2.5 - L)` in between); `w_2` reaches zero `1.4e-14` after
///   `w_1`, inside f64's tie window, and f64 enters `z_2` first: its path has
///   `w_1 = -1.4e-14` and `z_1 = 0` for ever (exactly `z_1 = 1` from
///   `L = 2.5`);
/// * the Fibonacci block `[[F73, F72], [F72, F71]]` (determinant 1, condition
///   `1.7e30`), `d = -M (1, 1)`, `q = M (3, 4)`: `z_3` enters at
///   `L = 3.38...` and `z_4` at `4` (`w_4 = (4 - L) / F73` in between, below
///   fx128's resolution of the row): fx128 enters `z_4` at `3.38` instead.
///
/// `solve_certified` with `Settings::escalate` and `escalate_exact` lets the
/// certificate drive the chain: the rejected f64 segment is traced again in
/// fx128 from the certified segment before it, the rejected fx128 segment
/// exactly, and the path ends `reached`, certified, with the exact path's
/// breakpoints. Before, the rejection only turned the answer
/// `ill_conditioned` (the chain was never reached: neither float path ended
/// `ill_conditioned`). Since the tracer reads near ties and small entries
/// again with refined values ([`plcp::NearTies::Refine`]), neither float
/// path claims success: f64 takes the block at 2.5 and stops
/// `ill_conditioned` on the near-singular basis after it, fx128 stops at the
/// undecided tie of the Fibonacci block, and the chain ends in exact
/// arithmetic from `L = 1.5` (`segment_precisions` f64, then exact).
fn f64_and_fx128_both_wrong() -> Plcp<f64> {
    let mut f = vec![0.0f64, 1.0];
    for i in 2..=73 {
        let next = f[i - 1] + f[i - 2];
        f.push(next);
    }
    let (a, b, c) = (f[73], f[72], f[71]);
    let (ai, bi, ci) = (a as i128, b as i128, c as i128);
    assert_eq!(ai * ci - bi * bi, 1, "Cassini: a determinant of one");
    let delta = 2f64.powi(-46);
    let m = faer::mat![
        [1.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 1.0, 1.0, 0.0, 0.0],
        [0.0, 1.0, 1.0 + delta, 0.0, 0.0],
        [0.0, 0.0, 0.0, a, b],
        [0.0, 0.0, 0.0, b, c],
    ];
    let q = faer::col![
        1.0,
        1.5,
        1.5 + 2.5 * delta,
        3.0 * a + 4.0 * b,
        3.0 * b + 4.0 * c
    ];
    let d = faer::col![-1.0, -1.0, -(1.0 + delta), -(a + b), -(b + c)];
    // every entry exact in f64 (below 2^53, or a short binary fraction)
    assert!(q[3] < 2f64.powi(53) && q[3] as i128 == 3 * ai + 4 * bi);
    Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
        .unwrap()
        .with_range(0.0, Some(6.0))
        .unwrap()
}

#[test]
fn certificate_drives_the_chain_f64_fx128_exact_to_reached() {
    let problem = f64_and_fx128_both_wrong();
    let exact = plcp::exact::trace(&problem, &Settings::default()).unwrap();
    assert_eq!(exact.path.status, Status::Reached, "{}", exact.path.message);
    let shorts: Vec<String> = exact.breakpoints.iter().map(plcp::exact::short).collect();
    assert_eq!(shorts[..3], ["1", "3/2", "5/2"], "{shorts:?}");
    assert_eq!(shorts[4], "4", "{shorts:?}");
    // the case: both float paths used to claim reached on a wrong path (the
    // certificate rejected both); the tracer now reads the near ties again
    // with refined values and refuses what it cannot order
    let plain = plcp::solve(&problem, &Settings::default()).unwrap();
    println!("f64: {} {}", plain.status.as_str(), plain.message);
    // f64 now orders the near tie at L = 1.5 (w_1 leaves first, resolved by
    // the refined ratios) and finds the block of w_2 = delta (2.5 - L) at
    // 2.5, whose entry (delta = 1.4e-14) is below the noise level of a
    // column of one (read again with the refined column); the basis after
    // that pivot holds the near-singular block, and f64 stops there
    // `ill_conditioned` (it used to report reached on a wrong path that only
    // the certificate caught)
    assert!(plain.info.near_ties_resolved >= 2, "{:?}", plain.info);
    assert_eq!(plain.status, Status::IllConditioned, "{}", plain.message);
    assert!(plain.message.contains("L = 2.5"), "{}", plain.message);
    let last = plain.segments.last().expect("segments");
    assert!((last.lambda_to - 2.5).abs() < 1e-12, "{}", last.lambda_to);
    // fx128 no longer claims success: its near tie on the Fibonacci block is
    // undecided within the refined ratios' error bounds
    let wide = problem.cast::<fx128>();
    let plain128 = plcp::solve(&wide, &Settings::default()).unwrap();
    println!("f128: {} {}", plain128.status.as_str(), plain128.message);
    assert_eq!(
        plain128.status,
        Status::IllConditioned,
        "{}",
        plain128.message
    );
    assert!(
        plain128.message.contains("near tie"),
        "{}",
        plain128.message
    );
    assert!(
        plain128.info.near_ties_unresolved > 0,
        "{:?}",
        plain128.info
    );
    // and with escalate_exact the plain fx128 solve continues exactly to
    // L_max, certified
    let exact128 = Settings::<fx128> {
        escalate: true,
        escalate_exact: true,
        ..Settings::default()
    };
    let esc = plcp::solve(&wide, &exact128).unwrap();
    println!("f128 escalated: {} {}", esc.status.as_str(), esc.message);
    assert_eq!(esc.status, Status::Reached, "{}", esc.message);
    let c = esc.certify(&wide);
    assert!(c.certified(), "{}", c.summary());
    let chain = Settings::<f64> {
        escalate: true,
        escalate_exact: true,
        ..Settings::default()
    };
    // certified without escalation: refused, not a wrong success
    let refused = plcp::solve_certified(&problem, &Settings::default()).unwrap();
    assert_eq!(
        refused.status,
        Status::IllConditioned,
        "{}",
        refused.message
    );
    // up to fx128 only: its path is rejected too, so still refused
    let to128 = plcp::solve_certified(
        &problem,
        &Settings {
            escalate_exact: false,
            ..chain.clone()
        },
    )
    .unwrap();
    assert_eq!(to128.status, Status::IllConditioned, "{}", to128.message);
    let precs = &to128
        .info
        .escalation
        .as_ref()
        .expect("escalated")
        .segment_precisions;
    assert!(
        precs.contains(&"f128") && !precs.contains(&"exact"),
        "{precs:?}"
    );
    // the whole chain
    let path = plcp::solve_certified(&problem, &chain).unwrap();
    println!("{}", path.message);
    assert_eq!(path.status, Status::Reached, "{}", path.message);
    let cert = path.info.certificate.as_ref().unwrap();
    assert!(cert.certified(), "{}", cert.summary());
    let e = path.info.escalation.as_ref().expect("escalated");
    assert!(e.exact, "{}", e.exact_note);
    let precs = &e.segment_precisions;
    println!("{precs:?}");
    assert_eq!(precs.len(), path.segments.len());
    // f64 first and exact last; fx128, which stops at its own undecided tie
    // at L = 2.5 (above), keeps no segment of its own since the near-tie
    // reading (the exact tail restarts from the last exactly feasible basis,
    // L = 1.5); any f128 segment must lie between
    let first = |name: &str| precs.iter().position(|p| *p == name);
    let (Some(a), Some(c)) = (first("f64"), first("exact")) else {
        panic!("f64 and exact segments: {precs:?}");
    };
    assert!(a < c, "{precs:?}");
    let last = |name: &str| precs.iter().rposition(|p| *p == name);
    assert!(last("f64").unwrap() < c, "{precs:?}");
    if let Some(b) = first("f128") {
        assert!(a < b && last("f128").unwrap() < c, "{precs:?}");
    }
    assert_eq!(e.lambda_exact, path.segments[c].lambda_from.to_f64());
    // the exact path's breakpoints (and L_max)
    assert_eq!(path.breakpoints.len(), exact.breakpoints.len());
    for (x, y) in path.breakpoints.iter().zip(&exact.breakpoints) {
        let y = plcp::exact::rational_to_f64(y);
        assert!((x.lambda - y).abs() <= 1e-15 * y.abs(), "{x:?} vs {y}");
    }
    assert_eq!(path.lambda_reached, 6.0);
    let z = path.at(5.0).unwrap().z;
    assert!((z[1] - 1.0).abs() <= 1e-12, "z_1 = 1 beyond L = 2.5: {z:?}");
}

/// The same chain from the command line: `plcp solve --certify --escalate`
/// reports `reached` with a certificate and `segment_precisions` f64 then
/// exact; `--certify` alone reports `ill_conditioned`.
#[cfg(feature = "cli")]
#[test]
fn the_command_line_runs_the_chain() {
    use serde_json::{json, Value};
    let problem = f64_and_fx128_both_wrong();
    let n = problem.n();
    let m = problem.m();
    let rows: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..n).map(|j| m[(i, j)]).collect())
        .collect();
    let col = |c: faer::ColRef<'_, f64>| (0..n).map(|i| c[i]).collect::<Vec<f64>>();
    let text = json!({
        "M": rows,
        "q": col(problem.q()),
        "d": col(problem.d()),
        "lambda_max": 6.0,
    })
    .to_string();
    let file = std::env::temp_dir().join(format!("plcp-chain-{}.json", std::process::id()));
    std::fs::write(&file, text).unwrap();
    let run = |extra: &[&str]| -> Value {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_plcp"))
            .arg("solve")
            .arg(&file)
            .args(["--certify", "--quiet"])
            .args(extra)
            .output()
            .expect("run plcp");
        assert_eq!(
            out.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice(&out.stdout).expect("one JSON object")
    };
    let refused = run(&[]);
    let chained = run(&["--escalate"]);
    let _ = std::fs::remove_file(&file);
    assert_eq!(refused["status"], "ill_conditioned", "{refused}");
    assert_eq!(chained["status"], "reached", "{chained}");
    assert_eq!(chained["certificate"]["certified"], true, "{chained}");
    let precs: Vec<&str> = chained["segment_precisions"]
        .as_array()
        .expect("segment_precisions")
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    let mut order = precs.clone();
    order.dedup();
    // (fx128 stops at its own undecided tie where f64 stops, and keeps no
    // segment: see certificate_drives_the_chain_f64_fx128_exact_to_reached)
    order.retain(|p| *p != "f128");
    assert_eq!(order, ["f64", "exact"], "{precs:?}");
}
