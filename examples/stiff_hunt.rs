//! Random stiff and degenerate cases, judged like the stiff suite (see
//! `examples/common/stiff_core.rs`): every case runs in f32, f64 and fx128, and
//! a run is WRONG when it reports success with an error or residual beyond its
//! precision's allowance. The suite's cases are hand-made; this draws new ones,
//! so that a rule tuned to the suite shows if it fails elsewhere.
//!
//! ```text
//! cargo run --release --example stiff_hunt -- [--cases N] [--seed S] [--all]
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

// index loops read like the formulas they build
#![allow(clippy::needless_range_loop)]

#[path = "common/stiff_core.rs"]
mod stiff_core;

use plcp::Method;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;
use stiff_core::{Case, Problem};

const FAMILIES: [&str; 5] = ["scaled", "ties", "near-ties", "mixed", "huge"];

fn gaussian(rng: &mut ChaCha8Rng) -> f64 {
    // Box-Muller
    let u: f64 = rng.gen_range(1e-12..1.0);
    let v: f64 = rng.gen_range(0.0..1.0);
    (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
}

/// `B B' + S`: PSD of rank `r` plus a skew part of weight `skew`.
fn monotone(rng: &mut ChaCha8Rng, n: usize, r: usize, skew: f64) -> Vec<Vec<f64>> {
    let b: Vec<Vec<f64>> = (0..n)
        .map(|_| (0..r).map(|_| gaussian(rng)).collect())
        .collect();
    let mut m = vec![vec![0.0; n]; n];
    for i in 0..n {
        for j in 0..n {
            m[i][j] = (0..r).map(|k| b[i][k] * b[j][k]).sum();
        }
    }
    for i in 0..n {
        for j in 0..i {
            let s = skew * gaussian(rng);
            m[i][j] += s;
            m[j][i] -= s;
        }
    }
    m
}

fn draw(rng: &mut ChaCha8Rng, family: &str, k: usize) -> Case {
    let n = rng.gen_range(2..=10);
    let (m, q, d, free, method) = match family {
        "scaled" | "huge" => {
            let r = rng.gen_range(1..=n);
            let skew = if rng.gen_bool(0.5) { 1.0 } else { 0.0 };
            let mut m = monotone(rng, n, r, skew);
            // keep it strictly monotone on half the cases
            if rng.gen_bool(0.5) {
                for (i, row) in m.iter_mut().enumerate() {
                    row[i] += 0.1;
                }
            }
            let span = rng.gen_range(0..=8);
            let dr: Vec<f64> = (0..n)
                .map(|_| 10f64.powi(rng.gen_range(-span..=span)))
                .collect();
            // the same scaling on both sides keeps D M D monotone
            let m: Vec<Vec<f64>> = (0..n)
                .map(|i| (0..n).map(|j| dr[i] * m[i][j] * dr[j]).collect())
                .collect();
            let q: Vec<f64> = (0..n).map(|i| dr[i] * rng.gen_range(0.1..1.0)).collect();
            let d: Vec<f64> = (0..n).map(|i| dr[i] * (gaussian(rng) - 0.5)).collect();
            let (m, q, d) = if family == "huge" {
                let e = rng.gen_range(20..=150) * if rng.gen_bool(0.5) { 1 } else { -1 };
                let s = 10f64.powi(e);
                let t = 10f64.powi(rng.gen_range(-20..=20));
                (
                    m.iter()
                        .map(|r| r.iter().map(|x| x * s).collect())
                        .collect(),
                    q.iter().map(|x| x * s * t).collect(),
                    d.iter().map(|x| x * s * t).collect(),
                )
            } else {
                (m, q, d)
            };
            (m, q, d, 0, Method::Lemke)
        }
        "ties" => {
            let r = rng.gen_range(1..=n);
            let b: Vec<Vec<f64>> = (0..n)
                .map(|_| (0..r).map(|_| rng.gen_range(-1i32..=1) as f64).collect())
                .collect();
            let mut m = vec![vec![0.0; n]; n];
            for i in 0..n {
                for j in 0..n {
                    m[i][j] = (0..r).map(|k| b[i][k] * b[j][k]).sum();
                }
                m[i][i] += rng.gen_range(0i32..=1) as f64;
            }
            for i in 0..n {
                for j in 0..i {
                    let s = rng.gen_range(-1i32..=1) as f64;
                    m[i][j] += s;
                    m[j][i] -= s;
                }
            }
            let q: Vec<f64> = (0..n).map(|_| rng.gen_range(0i32..=2) as f64).collect();
            let d: Vec<f64> = (0..n).map(|_| rng.gen_range(-2i32..=0) as f64).collect();
            let method = if rng.gen_bool(0.5) {
                Method::Lemke
            } else {
                Method::Wolfe
            };
            (m, q, d, 0, method)
        }
        "near-ties" => {
            let mut m = monotone(rng, n, n, 0.3);
            for (i, row) in m.iter_mut().enumerate() {
                row[i] += n as f64;
            }
            let gap = 10f64.powi(rng.gen_range(-12..=-6));
            let base = rng.gen_range(0.5..2.0);
            let q: Vec<f64> = (0..n)
                .map(|_| base * (1.0 + gap * rng.gen_range(-1i32..=1) as f64))
                .collect();
            let d = vec![-1.0; n];
            (m, q, d, 0, Method::Lemke)
        }
        _ => {
            // mixed: p free variables (accelerations) and n - p complementary
            let p = rng.gen_range(1..n);
            let c = n - p;
            let mut k_blk = monotone(rng, p, p, 0.0);
            for (i, row) in k_blk.iter_mut().enumerate() {
                row[i] += 10f64.powi(rng.gen_range(-6..=0));
            }
            let a: Vec<Vec<f64>> = (0..c)
                .map(|_| (0..p).map(|_| gaussian(rng)).collect())
                .collect();
            let mut m = vec![vec![0.0; n]; n];
            for i in 0..p {
                for j in 0..p {
                    m[i][j] = k_blk[i][j];
                }
            }
            for i in 0..c {
                for j in 0..p {
                    m[p + i][j] = a[i][j];
                    m[j][p + i] = -a[i][j];
                }
            }
            let q: Vec<f64> = (0..n)
                .map(|i| {
                    if i < p {
                        gaussian(rng)
                    } else {
                        rng.gen_range(0.1..1.0)
                    }
                })
                .collect();
            let d: Vec<f64> = (0..n).map(|_| gaussian(rng) - 0.5).collect();
            (m, q, d, p, Method::Wolfe)
        }
    };
    Case {
        name: format!("{family} #{k} (n={n})"),
        problem: Problem::Plcp {
            m,
            q,
            d,
            free,
            exact: None,
            method,
        },
        fast: true,
        fx128: true,
        f32: true,
    }
}

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
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    // family -> precision -> [runs, successes, flagged, wrong]
    let mut summary: BTreeMap<(&str, &str), [usize; 4]> = BTreeMap::new();
    print!("{}", stiff_core::header());
    let mut wrong_cases = Vec::new();
    for k in 0..count {
        let family = FAMILIES[k % FAMILIES.len()];
        let case = draw(&mut rng, family, k);
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
    for c in wrong_cases.iter().take(5) {
        println!("\n{c:?}");
    }
}
