//! The Markowitz efficient frontier (the critical line algorithm) as a mixed PLCP.
//!
//! `min_w 1/2 w'S w - L mu'w` subject to `1'w = 1` (the budget row) and
//! `w >= 0` (no short sales), `L = 1/gamma` the risk tolerance from 0 (infinite
//! risk aversion: the minimum-variance portfolio) to infinity (the asset with
//! the largest mean). With the budget multiplier `nu` as the one free variable:
//! `0 = 1'w - 1`, `s = S w - nu 1 - L mu >= 0`, `s'w = 0` (see
//! `plcp_workspace::everyday`), traced by Wolfe's long form (the free block is
//! zero). The breakpoints are the corner portfolios; between them `w` is affine
//! in `L` and the frontier a parabola in (variance, return).
//!
//! Prints the corner portfolios, the frontier at a few `L`, and the comparison
//! with Clarabel's QP at 40 values of `L` and at the corners.
//!
//! `cargo run --release -q --example efficient_frontier`

#[allow(dead_code)] // each example runs one of the checks
#[path = "common/everyday_checks.rs"]
mod everyday_checks;
#[path = "common/qp.rs"]
mod qp;

use plcp_workspace::everyday;

fn main() {
    let n = 10;
    let (s, mu) = everyday::portfolio(n, 3);
    let c = everyday_checks::frontier(s.as_ref(), mu.as_ref(), 40);
    let stats = |w: &faer::Col<f64>| {
        let ret: f64 = (0..n).map(|i| mu[i] * w[i]).sum();
        let var: f64 = (0..n)
            .map(|i| (0..n).map(|j| w[i] * s[(i, j)] * w[j]).sum::<f64>())
            .sum();
        (ret, var.sqrt())
    };
    println!(
        "status {}, {} corner portfolios, {} pivots",
        c.path.status.as_str(),
        c.path.breakpoints.len(),
        c.path.info.pivots
    );
    println!(
        "{:>9} {:>9} {:>9} {:>7} {:>7}  weights",
        "L", "gamma", "event", "return", "stdev"
    );
    for b in &c.path.breakpoints {
        let w = c.path.at(b.lambda).unwrap().z;
        let (ret, sd) = stats(&w);
        let ws: Vec<String> = w.iter().map(|v| format!("{v:.3}")).collect();
        let event = format!("{}/{}", b.entering, b.leaving);
        println!(
            "{:>9.4} {:>9.4} {event:>9} {ret:>7.4} {sd:>7.4}  {}",
            b.lambda,
            1.0 / b.lambda,
            ws.join(" ")
        );
    }
    let last = c.path.breakpoints.last().map_or(1.0, |b| b.lambda);
    println!("the frontier between the corners:");
    for i in 0..7 {
        let l = 1.2 * last * i as f64 / 6.0;
        let (ret, sd) = stats(&c.path.at(l).unwrap().z);
        println!("  L = {l:8.4}: return {ret:.5}, stdev {sd:.5}");
    }
    println!(
        "against Clarabel at {} values of L: largest weight difference {:.2e}, objective excess of plcp {:.2e}",
        c.points, c.worst_x, c.excess
    );
}
