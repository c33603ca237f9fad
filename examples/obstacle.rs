//! The obstacle problem on an `N x N` grid as a large sparse standard-form PLCP,
//! traced with an observer that keeps only the contact area per segment.
//!
//! A membrane fixed on the boundary of the unit square, under a uniform
//! pressure `L` pushing it down onto a bowl-shaped obstacle `psi < 0` below it.
//! With the 5-point Laplacian `A` (times `h^2`), `z = u - psi >= 0` the gap to
//! the obstacle and `w = h^2 r >= 0` the contact reaction:
//!
//! ```text
//! w = A psi + L h^2 1 + A z,   z, w >= 0,   z'w = 0
//! ```
//!
//! so `M = A` (sparse, 5 entries a row), `q = A psi`, `d = h^2 1`. At `L = 0`
//! the membrane is flat: `z = -psi > 0` with every `z` basic (a warm start, no
//! start phase); each contact that forms as `L` rises is one pivot.
//!
//! `cargo run --release -q --example obstacle -- [N] [L_max]` (default 32 and 4).

#[path = "common/stdout.rs"]
mod stdout;

use faer::Col;
use plcp::matrix::Csc;
use plcp::{solve_observed, Control, Keep, Progress};
use plcp::{BasisKind, Method, Plcp, Segment, Settings, Var};
use std::cell::RefCell;
use std::io::Write;
use std::rc::Rc;

/// `(M, q, d)` of the obstacle problem on an `N x N` grid of interior nodes.
fn obstacle(nx: usize) -> Result<Plcp<f64>, plcp::PlcpError> {
    let n = nx * nx;
    let h = 1.0 / (nx as f64 + 1.0);
    let id = |i: usize, j: usize| i * nx + j;
    let mut t = Vec::with_capacity(5 * n);
    for i in 0..nx {
        for j in 0..nx {
            t.push((id(i, j), id(i, j), 4.0));
            if i > 0 {
                t.push((id(i, j), id(i - 1, j), -1.0));
            }
            if i + 1 < nx {
                t.push((id(i, j), id(i + 1, j), -1.0));
            }
            if j > 0 {
                t.push((id(i, j), id(i, j - 1), -1.0));
            }
            if j + 1 < nx {
                t.push((id(i, j), id(i, j + 1), -1.0));
            }
        }
    }
    // the bowl: 0.05 below the membrane at the centre, falling away
    let psi = |i: usize, j: usize| {
        let (x, y) = ((i + 1) as f64 * h - 0.5, (j + 1) as f64 * h - 0.5);
        -0.05 - 0.5 * (x * x + y * y)
    };
    // q = A psi (the boundary's psi does not enter: u = 0 there)
    let q = Col::from_fn(n, |k| {
        let (i, j) = (k / nx, k % nx);
        let mut v = 4.0 * psi(i, j);
        if i > 0 {
            v -= psi(i - 1, j);
        }
        if i + 1 < nx {
            v -= psi(i + 1, j);
        }
        if j > 0 {
            v -= psi(i, j - 1);
        }
        if j + 1 < nx {
            v -= psi(i, j + 1);
        }
        v
    });
    let d = Col::from_fn(n, |_| h * h);
    let m = Csc::try_from_triplets(n, n, &t)?;
    Plcp::mixed_sparse(m, q.as_ref(), d.as_ref(), 0)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    stdout::run(run)
}

fn run(out: &mut impl Write) -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let nx: usize = args.get(1).map_or(Ok(32), |s| s.parse())?;
    let lambda_max: f64 = args.get(2).map_or(Ok(4.0), |s| s.parse())?;
    let n = nx * nx;
    let problem = obstacle(nx)?.with_range(0.0, Some(lambda_max))?;
    let settings = Settings {
        method: Method::Lemke,
        basis: BasisKind::Sparse,
        warm_basis: Some((0..n).map(Var::Z).collect()),
        ..Settings::default()
    };
    // the observer keeps (L at the segment's end, contacts on the segment)
    let contacts = Rc::new(RefCell::new(Vec::<(f64, usize)>::new()));
    let keep = contacts.clone();
    let watch = move |s: &Segment<f64>, _: &Progress<'_, f64>| {
        let c = s.basis.iter().filter(|v| matches!(v, Var::W(_))).count();
        keep.borrow_mut().push((s.lambda_to, c));
        Control::Continue
    };
    let t = std::time::Instant::now();
    let run = solve_observed(&problem, &settings, watch, Keep::Nothing)?;
    let secs = t.elapsed().as_secs_f64();
    let path = &run.path;
    let contacts = contacts.borrow();
    writeln!(
        out,
        "obstacle N = {nx}: n = {n}, nnz(M) = {}, status {}, L reached {}, {} pivots, {} segments, {:.3} s, path held {} bytes, residual {:.1e}, warm start {}",
        5 * n - 4 * nx,
        path.status.as_str(),
        path.lambda_reached,
        path.info.pivots,
        contacts.len(),
        secs,
        path.info.path_bytes,
        path.info.residual.worst(),
        path.info.warm_start
    )?;
    if let Some((l, c)) = contacts.iter().find(|(_, c)| *c > 0) {
        writeln!(
            out,
            "first contact on the segment ending at L = {l:.6} ({c} node)"
        )?;
    }
    if let Some((l, c)) = contacts.last() {
        writeln!(out, "contact at the end (L = {l}): {c} nodes")?;
    }
    Ok(())
}
