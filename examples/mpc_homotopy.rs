//! A parametric convex QP whose linear term and bounds move with `L`: the
//! homotopy of an active-set MPC solver, as a mixed PLCP.
//!
//! MPC of a double integrator over 10 steps (inputs `|u_k| <= 1`, positions
//! `<= 1`), condensed to `min_U 1/2 U'H U + (F x0)'U` subject to
//! `A U <= b + E x0`. Moving the initial state along
//! `x0(L) = x0a + L (x0b - x0a)`, `L` from 0 to 1, moves the linear term and the
//! bounds: `0 = H U + A'y + f + L g`, `s = -A U + b + L e >= 0 ⊥ y >= 0` (see
//! `plcp_workspace::everyday`). The breakpoints are the changes of the active
//! set, traced by Lemke (on the Schur reduction) and by Wolfe's long form.
//!
//! `cargo run --release -q --example mpc_homotopy`

#[allow(dead_code)] // each example runs one of the checks
#[path = "common/everyday_checks.rs"]
mod everyday_checks;
#[path = "common/qp.rs"]
mod qp;

use plcp::{Method, Var};
use plcp_workspace::everyday::Mpc;

fn main() {
    let n = 10;
    let mpc = Mpc::double_integrator(n, 0.2, 1.0);
    let name = |i: usize| match i / n {
        0 => format!("u{} <= 1", i % n),
        1 => format!("u{} >= -1", i % n),
        _ => format!("p{} <= 1", i % n + 1),
    };
    for method in [Method::Lemke, Method::Wolfe] {
        let c = everyday_checks::mpc(&mpc, [-1.0, -0.5], [0.6, 0.8], method, 41);
        println!(
            "{method:?}: status {}, {} active-set changes, {} pivots",
            c.path.status.as_str(),
            c.path.breakpoints.len(),
            c.path.info.pivots
        );
        for b in &c.path.breakpoints {
            let what = match (b.entering, b.leaving) {
                (Var::Z(i), _) => format!("{} enters the active set", name(i)),
                (_, Var::Z(i)) => format!("{} leaves the active set", name(i)),
                (e, l) => format!("{e} in, {l} out"),
            };
            println!("  L = {:.6}: {what}", b.lambda);
        }
        println!(
            "  against Clarabel at {} values of L: largest input difference {:.2e}, objective excess of plcp {:.2e}",
            c.points, c.worst_x, c.excess
        );
    }
}
