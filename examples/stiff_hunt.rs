//! Random stiff and degenerate cases, judged like the stiff suite (see
//! `examples/common/stiff_core.rs`): every case runs in f32, f64 and fx128, and
//! a run is WRONG when it reports success with an error or residual beyond its
//! precision's allowance. The suite's cases are hand-made; this draws new ones,
//! so that a rule tuned to the suite shows if it fails elsewhere.
//!
//! ```text
//! cargo run --release --example stiff_hunt -- [--cases N] [--seed S] [--all] [--only K]
//! ```
//!
//! Families (each case draws one, sizes 2..=10):
//! - `scaled`: `D (B B' + S) E` with `B` of deficient rank, `S` skew, and
//!   diagonal `D`, `E` of powers of ten spanning up to 1e±8 (monotone up to the
//!   scaling, which the solver's equilibration should undo);
//! - `ties`: small integer entries of a PSD-plus-skew `M`, integer `q`, `d`
//!   (many exact ties and degenerate bases);
//! - `near-ties`: a diagonal-dominant `M` with `q` equal up to 1e-12..1e-6
//!   relative (breakpoints that nearly coincide);
//! - `mixed`: free variables, `M = [[K, -A'], [A, H]]` with `K` PSD and
//!   nonsingular, solved by Wolfe;
//! - `huge`: the `scaled` family multiplied as a whole by 1e±(20..150).
//!
//! Prints the WRONG rows (and with `--all` every row) and a summary per
//! family and precision: runs, successes, flagged, WRONG.

#[path = "common/stiff_core.rs"]
mod stiff_core;

#[path = "common/stiff_random.rs"]
mod stiff_random;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;
use stiff_random::{draw, FAMILIES};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |key: &str, default: u64| {
        args.iter()
            .position(|a| a == key)
            .and_then(|i| args.get(i + 1))
            .and_then(|s| s.parse().ok())
            .unwrap_or(default)
    };
    let count = value("--cases", 200) as usize;
    let seed = value("--seed", 20261123);
    let all = args.iter().any(|a| a == "--all");
    // --only K: run (and print the data of) case K alone, drawn as in the full run
    let only = args
        .iter()
        .position(|a| a == "--only")
        .and_then(|i| args.get(i + 1))
        .and_then(|s| s.parse::<usize>().ok());
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    // family -> precision -> [runs, successes, flagged, wrong]
    let mut summary: BTreeMap<(&str, &str), [usize; 4]> = BTreeMap::new();
    print!("{}", stiff_core::header());
    let mut wrong_cases = Vec::new();
    for k in 0..count {
        let family = FAMILIES[k % FAMILIES.len()];
        let case = draw(&mut rng, family, k);
        if only.is_some_and(|o| o != k) {
            continue;
        }
        if only.is_some() {
            println!("{case:?}");
        }
        for row in stiff_core::run_case(&case) {
            let e = summary.entry((family, row.precision)).or_default();
            e[0] += 1;
            if !row.flagged && !row.status.starts_with("n/a") {
                e[1] += 1;
            }
            if row.flagged {
                e[2] += 1;
            }
            if row.wrong {
                e[3] += 1;
                wrong_cases.push(case.clone());
            }
            if all || row.wrong {
                print!("{}", stiff_core::line(&row));
            }
        }
    }
    println!(
        "\nseed {seed}, {count} cases\n{:<10} {:<5} {:>5} {:>9} {:>8} {:>6}",
        "family", "prec", "runs", "successes", "flagged", "WRONG"
    );
    for ((f, p), [runs, ok, flagged, wrong]) in &summary {
        println!("{f:<10} {p:<5} {runs:>5} {ok:>9} {flagged:>8} {wrong:>6}");
    }
    for c in wrong_cases.iter().take(3) {
        println!("\n{c:?}");
    }
}
