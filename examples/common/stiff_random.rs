//! Random stiff and degenerate cases for `examples/stiff_hunt.rs` and
//! `tests/stiff.rs` (the families are described in the example). Not an
//! example itself; it needs `stiff_core` as a sibling module.
#![allow(dead_code)]
// index loops read like the formulas they build
#![allow(clippy::needless_range_loop)]

use super::stiff_core::{Case, Problem};
use plcp::Method;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// The families, drawn in turn.
pub const FAMILIES: [&str; 5] = ["scaled", "ties", "near-ties", "mixed", "huge"];

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

/// Case number `k` of `family`, drawn from `rng`.
pub fn draw(rng: &mut ChaCha8Rng, family: &str, k: usize) -> Case {
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
