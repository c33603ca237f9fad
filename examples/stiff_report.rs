//! The stiff and extreme suite of issue 5, all cases (see
//! `examples/common/stiff_core.rs`): for each case and precision (f32, f64,
//! fx128) the status, the breakpoint error against the exact values or the
//! fx128 path (for plain LCPs: the error of `z`), the largest residual
//! (measured in fx128 on the original data), and whether the solver flagged
//! trouble. `WRONG` marks a success whose error or residual exceeds the
//! precision's allowance (f32 1e-2, f64 1e-8, fx128 1e-16).
//!
//! ```text
//! cargo run --release --example stiff_report [-- --fast | --no-large]
//! ```

#[path = "common/stiff_core.rs"]
mod stiff_core;

fn main() {
    let fast = std::env::args().any(|a| a == "--fast");
    let quiet = std::env::args().any(|a| a == "--quiet" || a == "-q");
    let mut cases = stiff_core::cases();
    match stiff_core::siconos_cases() {
        Ok(c) => cases.extend(c),
        Err(msg) => eprintln!("{msg}"),
    }
    if !fast && !std::env::args().any(|a| a == "--no-large") {
        cases.push(stiff_core::large_case());
    }
    print!("{}", stiff_core::header());
    let mut wrong = 0;
    let mut rows = 0;
    let todo: Vec<_> = cases.iter().filter(|c| !fast || c.fast).collect();
    let bar = plcp::progress::Progress::bar(todo.len() as u64, "cases", quiet);
    for case in todo {
        bar.message(&case.name);
        let t = std::time::Instant::now();
        for r in stiff_core::run_case(case) {
            bar.suspend(|| print!("{}", stiff_core::line(&r)));
            rows += 1;
            wrong += r.wrong as usize;
        }
        if t.elapsed().as_secs_f64() > 5.0 {
            bar.println(&format!(
                "  ({}: {:.1} s)",
                case.name,
                t.elapsed().as_secs_f64()
            ));
        }
        bar.inc(1);
    }
    bar.finish();
    println!(
        "\n{rows} runs, {wrong} WRONG (success reported beyond the allowance: f32 {:e}, f64 {:e}, f128 {:e})",
        stiff_core::allowance("f32"),
        stiff_core::allowance("f64"),
        stiff_core::allowance("f128")
    );
}
