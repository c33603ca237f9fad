//! The LASSO regularization path as a monotone PLCP.
//!
//! `min_b 1/2 |y - X b|^2 + t |b|_1` for every `t` from `t_max = max |X'y|` down
//! to 0: with `b = b+ - b-` and `t = t_max - L` the optimality conditions are
//! `w = q + L d + M z`, `z = (b+, b-)`, `M = [[G, -G], [-G, G]]` (`G = X'X`),
//! `q = (t_max - X'y, t_max + X'y)`, `d = -1`, `L` from 0 to `t_max` (see
//! `plcp_workspace::everyday`). Every breakpoint is a knot: a coefficient
//! enters the active set (`z_i` enters) or leaves it (`w_i` enters); on every
//! piece the coefficients are affine in `t`.
//!
//! Prints the knots, active sets and coefficients of each piece for a wide
//! random problem (60 features, 20 samples) and one with collinear columns,
//! and the comparison with Clarabel's QP at 25 values of `t`. (The Python
//! example `python/examples/lasso.py` runs the same on scikit-learn's diabetes
//! data, side by side with scikit-learn's `lars_path`.)
//!
//! `cargo run --release -q --example lasso_path`

#[allow(dead_code)] // each example runs one of the checks
#[path = "common/everyday_checks.rs"]
mod everyday_checks;
#[path = "common/qp.rs"]
mod qp;

#[path = "common/stdout.rs"]
mod stdout;

use plcp::Var;
use plcp_workspace::everyday;
use std::io::Write;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    stdout::run(|out| {
        for (name, collinear) in [
            ("wide random", false),
            ("wide random, collinear columns", true),
        ] {
            let (x, y) = everyday::lasso_data(20, 60, 1, collinear);
            let (c, t_max) = everyday_checks::lasso(x.as_ref(), y.as_ref(), 25);
            let p = x.ncols();
            writeln!(out, "== {name}: X is 20 x 60, t_max = {t_max:.6} ==")?;
            writeln!(
                out,
                "status {}, {} knots, {} pivots, {:.2} ms",
                c.path.status.as_str(),
                c.path.breakpoints.len(),
                c.path.info.pivots,
                c.path.info.solve_seconds * 1e3
            )?;
            writeln!(out, "{:>5} {:>11} {:>11}  event, then the active set with the coefficients at the piece's start", "piece", "t from", "t to")?;
            for (k, s) in c.path.segments.iter().enumerate() {
                let (t_hi, t_lo) = (t_max - s.lambda_from, t_max - s.lambda_to);
                let event = c
                    .path
                    .breakpoints
                    .iter()
                    .rfind(|b| b.segment == k)
                    .map(|b| match b.entering {
                        Var::Z(i) => format!("b{} enters", i % p),
                        Var::W(i) => format!("b{} leaves", i % p),
                        v => format!("{v} enters"),
                    });
                // the active coefficients (z_i basic: b+_i for i < p, b-_{i-p} above), in order
                let mut active: Vec<usize> = s
                    .basis
                    .iter()
                    .filter_map(|v| match *v {
                        Var::Z(i) => Some(i % p),
                        _ => None,
                    })
                    .collect();
                active.sort_unstable();
                let active: Vec<String> = active
                    .iter()
                    .map(|&j| format!("b{j}={:+.4}", s.z_from[j] - s.z_from[p + j]))
                    .collect();
                writeln!(
                    out,
                    "{k:>5} {t_hi:>11.5} {t_lo:>11.5}  {}: {{{}}}",
                    event.unwrap_or_default(),
                    active.join(", ")
                )?;
            }
            writeln!(
                out,
            "against Clarabel at {} values of t: largest coefficient difference {:.2e}, objective excess of plcp {:.2e}\n",
            c.points, c.worst_x, c.excess
        )?;
        }
        Ok(())
    })
}
