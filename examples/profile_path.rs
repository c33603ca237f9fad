//! One path traced repeatedly, for a profiler (`perf record`): where the time
//! of a dense solve goes (issue 6).
//!
//! ```sh
//! cargo run --release --example profile_path -- 1000 5 lemke f64
//! perf record -g target/release/examples/profile_path 1000 20 lemke f64
//! ```
//!
//! Arguments: `n` (default 1000), repeats (default 5), method `lemke` or
//! `wolfe`, precision `f32` or `f64`, refactorisation period (default: the
//! solver's, `auto`), `refine_cond_eps` (default: the solver's). Instance: `path_instance(n, 1)`, as the
//! benches. Prints the best time, pivots and largest breakpoint residual.

use plcp::{Method, Settings};
use plcp_workspace::random::path_instance;
use std::time::Instant;

fn run<T: plcp::Scalar>(
    problem: &plcp::Plcp<f64>,
    method: Method,
    repeats: usize,
    period: Option<usize>,
    refine_cond_eps: Option<f64>,
) {
    let p = problem.cast::<T>();
    let s = Settings::<T> {
        refactor_period: period,
        ..Settings::<T>::with_method(method)
    };
    let s = Settings {
        refine_cond_eps: refine_cond_eps.unwrap_or(s.refine_cond_eps),
        ..s
    };
    let mut best = f64::INFINITY;
    for _ in 0..repeats {
        let t = Instant::now();
        let path = plcp::solve(&p, &s).expect("valid settings");
        let dt = t.elapsed().as_secs_f64();
        best = best.min(dt);
        let res = path.info.residual.worst();
        println!(
            "{}: {:.4} s, {} pivots, {} breakpoints, residual {:.1e}, {} refactorisations, {} refinements, condition {:.1e}",
            path.status.as_str(),
            dt,
            path.info.pivots,
            path.breakpoints.len(),
            res,
            path.info.refactorisations,
            path.info.refinements,
            path.info.max_condition
        );
    }
    println!("best {best:.4} s");
    // a fingerprint of the pivot sequence's arithmetic (the same with one thread or two)
    let path = plcp::solve(&p, &s).expect("valid settings");
    let sum: f64 = path.breakpoints.iter().map(|b| b.lambda.to_f64()).sum();
    println!("sum of breakpoint L: {sum:.17e}");
    let t = Instant::now();
    let eq = plcp::scaling::Equilibration::ruiz(&p, 8);
    println!(
        "of which equilibration (Ruiz, 8 sweeps): {:.4} s (identity: {})",
        t.elapsed().as_secs_f64(),
        eq.is_identity()
    );
}

fn main() {
    let a: Vec<String> = std::env::args().skip(1).collect();
    let n = a.first().map_or(1000, |s| s.parse().expect("n"));
    let repeats = a.get(1).map_or(5, |s| s.parse().expect("repeats"));
    let method = match a.get(2).map_or("lemke", String::as_str) {
        "wolfe" => Method::Wolfe,
        _ => Method::Lemke,
    };
    let period = a.get(4).and_then(|s| s.parse().ok());
    let refine = a.get(5).and_then(|s| s.parse().ok());
    if std::env::var_os("PLCP_SEQ").is_some() {
        // one thread: faer's global parallelism off
        faer::set_global_parallelism(faer::Par::Seq);
    }
    let inst = path_instance(n, 1);
    match a.get(3).map_or("f64", String::as_str) {
        "f32" => run::<f32>(&inst.problem, method, repeats, period, refine),
        _ => run::<f64>(&inst.problem, method, repeats, period, refine),
    }
}
