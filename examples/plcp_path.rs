//! A small PLCP traced by both methods: prints the breakpoints, the segments and
//! the residuals.
//!
//! `cargo run --release -q --example plcp_path`

use faer::{col, mat};
use plcp::{Method, Plcp, Settings};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // M = B B' + S (positive semidefinite plus skew), q with a negative entry.
    let m = mat![
        [2.0, 1.0, 0.0, -1.0],
        [-1.0, 3.0, 1.0, 0.0],
        [0.0, -1.0, 2.0, 1.0],
        [1.0, 0.0, -1.0, 1.0],
    ];
    let q = col![1.0, -0.5, 2.0, 0.5];
    let d = col![-1.0, -1.0, -0.5, -2.0];
    let problem = Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())?.with_range(0.0, Some(10.0))?;
    for method in [Method::Lemke, Method::Wolfe] {
        let path = plcp::solve(&problem, &Settings::with_method(method))?;
        println!(
            "{:?}: status {}, L reached {}, {} pivots ({} in the start phase), residual {:.1e}",
            method,
            path.status.as_str(),
            path.lambda_reached,
            path.info.pivots,
            path.info.start_pivots,
            path.info.residual.worst()
        );
        for b in &path.breakpoints {
            println!(
                "  breakpoint L = {:.6}: {} enters, {} leaves{}",
                b.lambda,
                b.entering,
                b.leaving,
                if b.degenerate { " (degenerate)" } else { "" }
            );
        }
        for s in &path.segments {
            let basis: Vec<String> = s.basis.iter().map(|v| v.to_string()).collect();
            println!(
                "  segment [{:.6}, {:.6}] basis {{{}}}  z(L) = {:?} + L {:?}",
                s.lambda_from,
                s.lambda_to,
                basis.join(","),
                s.z0()
                    .iter()
                    .map(|v: &f64| (v * 1e6).round() / 1e6)
                    .collect::<Vec<_>>(),
                s.dz.iter()
                    .map(|v: &f64| (v * 1e6).round() / 1e6)
                    .collect::<Vec<_>>()
            );
        }
    }
    Ok(())
}
