//! Error against run time on the benches' instances (issue 6).
//!
//! ```sh
//! cargo run --release --example speed_report                 # n = 50 ... 2000
//! cargo run --release --example speed_report -- --max-n 1000
//! cargo run --release --example speed_report -- --only 2000 --quick
//! ```
//!
//! Options: `--max-n N` (largest n, default 2000), `--only N` (one size),
//! `--ref-max-n N` (largest n with the fx128 reference, default 500),
//! `--quick` (the default refactorisation period only), `--repeats R` (best of at most
//! R runs, default 3; a configuration stops repeating once its runs have
//! taken 3 s), `--out DIR` (default `out/speed`), `--quiet` (no progress bar;
//! the bar is drawn on stderr only when it is a terminal).
//!
//! Instances: `plcp_workspace::random::path_instance(n, 1)` (as the benches):
//! `M = B B'/n + 0.1 I`, `q` uniform in `[0.1, 1]`, `d = N(0,1) - 0.5`,
//! `L_max` midway between the `n/2`-th and `(n/2+1)`-th breakpoint.
//!
//! Candidates: plcp with method lemke / wolfe, precision f32 / f64,
//! refactorisation period default (`auto`) / 10 / 50 / 200, basis block /
//! dense, and for the block basis in f64 without column refinement
//! (`norefine`: `refine_cond_eps` never reached); Clarabel (the
//! QP `min 1/2 z'Mz + (q + L d)'z, z >= 0`) at `L_max`, and at K = 10 and 100
//! evenly spaced `L`, with its default tolerances (1e-8) and tight ones (1e-12).
//!
//! Reference: the fx128 path (Lemke, block basis) for n <= `--ref-max-n`;
//! beyond, the f64 path with the dense basis refactorised every 10 pivots
//! (said in the table as `ref`).
//!
//! Errors: `z err` is the largest `|z(L) - z_ref(L)|` (max norm) over the
//! sample set: every breakpoint of the reference, the midpoint of every
//! reference segment, and `L_max` (for Clarabel: its own sampled `L`).
//! `bp err` is `max_k |L_k - L_k(ref)|`, breakpoints matched in order (a `*`
//! marks a different number of breakpoints, compared on the common prefix).
//!
//! Output: the table on stdout, `report.csv` and `report.svg` (log-log, run
//! time against z error) in the output directory, then the time per
//! breakpoint against n (where the time goes inside a path:
//! `examples/profile_path.rs` under `perf`).

use plcp::{BasisKind, Method, Path, Plcp, Scalar, Settings};
use plcp_workspace::random::path_instance;
use std::fmt::Write as _;
use std::time::Instant;

#[path = "common/speed/peer.rs"]
mod peer;
#[path = "common/speed/svg.rs"]
mod svg;

struct Options {
    sizes: Vec<usize>,
    ref_max_n: usize,
    quick: bool,
    repeats: usize,
    out: std::path::PathBuf,
    quiet: bool,
}

fn options() -> Options {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut o = Options {
        sizes: vec![50, 200, 500, 1000, 2000],
        ref_max_n: 500,
        quick: false,
        repeats: 3,
        out: "out/speed".into(),
        quiet: false,
    };
    let mut max_n = usize::MAX;
    let mut i = 0;
    let val = |i: usize| -> &str {
        args.get(i + 1)
            .map(String::as_str)
            .unwrap_or_else(|| panic!("{} needs a value", args[i]))
    };
    while i < args.len() {
        match args[i].as_str() {
            "--max-n" => max_n = val(i).parse().expect("--max-n N"),
            "--only" => o.sizes = vec![val(i).parse().expect("--only N")],
            "--ref-max-n" => o.ref_max_n = val(i).parse().expect("--ref-max-n N"),
            "--repeats" => o.repeats = val(i).parse().expect("--repeats R"),
            "--out" => o.out = val(i).into(),
            "--quick" => {
                o.quick = true;
                i += 1;
                continue;
            }
            "--quiet" => {
                o.quiet = true;
                i += 1;
                continue;
            }
            other => panic!("unknown option {other}"),
        }
        i += 2;
    }
    o.sizes.retain(|&n| n <= max_n);
    o
}

/// Best wall-clock time of at most `repeats` runs (stop repeating after 3 s).
fn best_of<R>(repeats: usize, mut f: impl FnMut() -> R) -> (f64, R) {
    let start = Instant::now();
    let t = Instant::now();
    let mut out = f();
    let mut best = t.elapsed().as_secs_f64();
    for _ in 1..repeats {
        if start.elapsed().as_secs_f64() > 3.0 {
            break;
        }
        let t = Instant::now();
        out = f();
        best = best.min(t.elapsed().as_secs_f64());
    }
    (best, out)
}

/// The reference path read in f64 where needed (fx128 kept for evaluation).
enum Reference {
    F128(Path<faer::fx128>),
    F64(Path<f64>),
}

impl Reference {
    fn z_at(&self, l: f64) -> Option<Vec<f64>> {
        match self {
            Reference::F128(p) => z_at(p, l),
            Reference::F64(p) => z_at(p, l),
        }
    }
    fn breakpoints(&self) -> Vec<f64> {
        match self {
            Reference::F128(p) => p.breakpoints.iter().map(|b| b.lambda.to_f64()).collect(),
            Reference::F64(p) => p.breakpoints.iter().map(|b| b.lambda.to_f64()).collect(),
        }
    }
    fn name(&self) -> &'static str {
        match self {
            Reference::F128(_) => "fx128",
            Reference::F64(_) => "f64 dense rp10",
        }
    }
}

fn z_at<T: Scalar>(p: &Path<T>, l: f64) -> Option<Vec<f64>> {
    p.at(T::from_f64(l))
        .map(|pt| (0..pt.z.nrows()).map(|i| pt.z[i].to_f64()).collect())
}

fn max_dev(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// One row of the table.
#[derive(Clone, Debug)]
struct Row {
    n: usize,
    candidate: String,
    family: String,
    basis: String,
    refactor: String,
    seconds: f64,
    z_err: f64,
    bp_err: Option<f64>,
    bp_mismatch: bool,
    breakpoints: usize,
    pivots: usize,
    residual: f64,
    status: String,
}

fn samples(reference: &Reference, lmax: f64) -> Vec<f64> {
    let bps = reference.breakpoints();
    let mut s = bps.clone();
    let mut prev = 0.0;
    for &b in &bps {
        s.push(0.5 * (prev + b));
        prev = b;
    }
    s.push(0.5 * (prev + lmax));
    s.push(lmax);
    s
}

#[allow(clippy::too_many_arguments)]
fn run_plcp<T: Scalar>(
    problem: &Plcp<f64>,
    n: usize,
    method: Method,
    basis: BasisKind,
    refactor: Option<usize>,
    refine: bool,
    repeats: usize,
    reference: &Reference,
    points: &[f64],
    ref_z: &[Vec<f64>],
) -> Row {
    let problem: Plcp<T> = problem.cast();
    let mut settings = Settings::<T>::with_method(method);
    settings.basis = basis;
    settings.refactor_period = refactor;
    let rp = refactor.map_or("auto".to_string(), |p| format!("rp{p}"));
    if !refine {
        // column refinement never (the basic values at breakpoints are still
        // refined on evidence)
        settings.refine_cond_eps = f64::MAX;
    }
    let (seconds, path) = best_of(repeats, || plcp::solve(&problem, &settings).expect("valid"));
    let mut z_err = 0.0f64;
    for (l, zr) in points.iter().zip(ref_z) {
        z_err = z_err.max(match z_at(&path, *l) {
            Some(z) => max_dev(&z, zr),
            None => f64::INFINITY,
        });
    }
    let rb = reference.breakpoints();
    let cb: Vec<f64> = path.breakpoints.iter().map(|b| b.lambda.to_f64()).collect();
    let bp_err = rb
        .iter()
        .zip(&cb)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let m = match method {
        Method::Lemke => "lemke",
        Method::Wolfe => "wolfe",
    };
    let b = match basis {
        BasisKind::Block => "block",
        BasisKind::Dense => "dense",
        BasisKind::Sparse => "sparse",
    };
    Row {
        n,
        candidate: format!(
            "{m} {} {b} {rp}{}",
            T::NAME,
            if refine { "" } else { " norefine" }
        ),
        family: format!("{m} {}", T::NAME),
        basis: b.into(),
        refactor: refactor.map_or("auto".into(), |p| p.to_string()),
        seconds,
        z_err,
        bp_err: Some(bp_err),
        bp_mismatch: rb.len() != cb.len(),
        breakpoints: cb.len(),
        pivots: path.info.pivots,
        residual: path.info.residual.worst(),
        status: path.status.as_str().into(),
    }
}

fn run_clarabel(
    problem: &Plcp<f64>,
    n: usize,
    lmax: f64,
    k: usize,
    tol: peer::Tolerance,
    repeats: usize,
    reference: &Reference,
) -> Row {
    let (seconds, out) = best_of(repeats, || peer::clarabel_samples(problem, lmax, k, tol));
    let mut z_err = 0.0f64;
    let mut failed = 0;
    for (l, z, ok) in &out {
        if !ok {
            failed += 1;
        }
        let zr = reference.z_at(*l).expect("inside the reference path");
        z_err = z_err.max(max_dev(z, &zr));
    }
    let t = match tol {
        peer::Tolerance::Default => "1e-8",
        peer::Tolerance::Tight => "1e-12",
    };
    let what = if k == 1 {
        "L_max".to_string()
    } else {
        format!("K={k}")
    };
    Row {
        n,
        candidate: format!("clarabel {what} tol {t}"),
        family: format!("clarabel {what} tol {t}"),
        basis: "-".into(),
        refactor: "-".into(),
        seconds,
        z_err,
        bp_err: None,
        bp_mismatch: false,
        breakpoints: 0,
        pivots: 0,
        residual: f64::NAN,
        status: if failed == 0 {
            "solved".into()
        } else {
            format!("{failed}/{k} not solved")
        },
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let o = options();
    std::fs::create_dir_all(&o.out)?;
    let mut rows: Vec<Row> = Vec::new();
    let mut per_bp: Vec<(usize, usize, f64, f64)> = Vec::new();
    let mut refs: Vec<(usize, String)> = Vec::new();
    println!(
        "{:>5} {:<32} {:>10} {:>9} {:>9} {:>5} {:>9} {:<10}",
        "n", "candidate", "time [s]", "z err", "bp err", "bps", "residual", "status"
    );
    let bar = plcp::progress::Progress::bar(o.sizes.len() as u64, "sizes", o.quiet);
    for &n in &o.sizes {
        bar.message(&format!("n = {n}: instance and reference"));
        let t0 = Instant::now();
        let inst = path_instance(n, 1);
        let problem = &inst.problem;
        let lmax = problem.lambda_max().expect("finite lambda_max");
        let setup = t0.elapsed().as_secs_f64();
        let t1 = Instant::now();
        let reference = if n <= o.ref_max_n {
            let p: Plcp<faer::fx128> = problem.cast();
            Reference::F128(plcp::solve(&p, &Settings::default()).expect("valid"))
        } else {
            let settings = Settings::<f64> {
                basis: BasisKind::Dense,
                refactor_period: Some(10),
                ..Settings::default()
            };
            Reference::F64(plcp::solve(problem, &settings).expect("valid"))
        };
        let ref_seconds = t1.elapsed().as_secs_f64();
        bar.suspend(|| {
            eprintln!(
                "n = {n}: instance {setup:.1} s, reference ({}) {ref_seconds:.1} s",
                reference.name()
            )
        });
        refs.push((n, format!("{} ({ref_seconds:.1} s)", reference.name())));
        let points = samples(&reference, lmax);
        let ref_z: Vec<Vec<f64>> = points
            .iter()
            .map(|&l| reference.z_at(l).expect("inside the reference path"))
            .collect();
        let periods: &[Option<usize>] = if o.quick {
            &[None]
        } else {
            &[None, Some(10), Some(50), Some(200)]
        };
        for method in [Method::Lemke, Method::Wolfe] {
            for basis in [BasisKind::Block, BasisKind::Dense] {
                for &rp in periods {
                    for f32_run in [false, true] {
                        let row = if f32_run {
                            run_plcp::<f32>(
                                problem, n, method, basis, rp, true, o.repeats, &reference,
                                &points, &ref_z,
                            )
                        } else {
                            run_plcp::<f64>(
                                problem, n, method, basis, rp, true, o.repeats, &reference,
                                &points, &ref_z,
                            )
                        };
                        bar.suspend(|| print_row(&row));
                        rows.push(row);
                    }
                    bar.message(&format!("n = {n}: {method:?} {basis:?}"));
                    if basis == BasisKind::Block {
                        // the column refinement's share: the same without it
                        let row = run_plcp::<f64>(
                            problem, n, method, basis, rp, false, o.repeats, &reference, &points,
                            &ref_z,
                        );
                        bar.suspend(|| print_row(&row));
                        rows.push(row);
                    }
                }
            }
        }
        // Clarabel: at L_max first; K samples only when affordable (<= 120 s estimated)
        bar.message(&format!("n = {n}: clarabel"));
        for tol in [peer::Tolerance::Default, peer::Tolerance::Tight] {
            let one = run_clarabel(problem, n, lmax, 1, tol, o.repeats, &reference);
            let single = one.seconds;
            bar.suspend(|| print_row(&one));
            rows.push(one);
            for k in [10usize, 100] {
                if single * k as f64 > 120.0 {
                    bar.suspend(|| {
                        println!(
                            "{n:>5} clarabel K={k} skipped (about {:.0} s estimated)",
                            single * k as f64
                        )
                    });
                    continue;
                }
                let row = run_clarabel(problem, n, lmax, k, tol, o.repeats, &reference);
                bar.suspend(|| print_row(&row));
                rows.push(row);
            }
        }
        // time per breakpoint (default settings)
        let base = rows
            .iter()
            .find(|r| r.n == n && r.candidate == "lemke f64 block auto")
            .expect("default configuration ran");
        per_bp.push((
            n,
            base.breakpoints,
            base.seconds,
            base.seconds / base.breakpoints.max(1) as f64,
        ));
        bar.inc(1);
    }
    bar.finish();
    // CSV
    let mut csv = String::from(
        "n,candidate,family,basis,refactor_period,seconds,z_err,bp_err,bp_count_differs,breakpoints,pivots,residual,status\n",
    );
    for r in &rows {
        writeln!(
            csv,
            "{},{},{},{},{},{:.6e},{:.3e},{},{},{},{},{:.3e},{}",
            r.n,
            r.candidate,
            r.family,
            r.basis,
            r.refactor,
            r.seconds,
            r.z_err,
            r.bp_err.map_or(String::new(), |e| format!("{e:.3e}")),
            r.bp_mismatch,
            r.breakpoints,
            r.pivots,
            r.residual,
            r.status
        )?;
    }
    std::fs::write(o.out.join("report.csv"), csv)?;
    // left out of the plot: runs that did not reach L_max (infinite error) and
    // the reference configuration itself (zero error)
    let points: Vec<svg::Point> = rows
        .iter()
        .filter(|r| r.z_err.is_finite() && r.z_err > 0.0)
        .map(|r| svg::Point {
            x: r.seconds,
            y: r.z_err,
            series: r.family.clone(),
            label: r.n.to_string(),
        })
        .collect();
    std::fs::write(
        o.out.join("report.svg"),
        svg::log_log(
            "error against run time (label: n; early stops and the reference left out)",
            "run time [s]",
            "max |z - z_ref| along the path",
            &points,
        ),
    )?;
    println!("\nreferences: {refs:?}");
    println!("\ntime per breakpoint (lemke f64 block, default settings)");
    println!(
        "{:>5} {:>6} {:>10} {:>14}",
        "n", "bps", "path [s]", "per bp [ms]"
    );
    for (n, b, t, tb) in &per_bp {
        println!("{n:>5} {b:>6} {t:>10.4} {:>14.4}", tb * 1e3);
    }
    for w in per_bp.windows(2) {
        let (n0, _, _, t0) = w[0];
        let (n1, _, _, t1) = w[1];
        println!(
            "cost per breakpoint grows as n^{:.2} from n = {n0} to {n1}",
            (t1 / t0).ln() / (n1 as f64 / n0 as f64).ln()
        );
    }
    println!(
        "\nwrote {} and {}",
        o.out.join("report.csv").display(),
        o.out.join("report.svg").display()
    );
    Ok(())
}

fn print_row(r: &Row) {
    println!(
        "{:>5} {:<32} {:>10.4e} {:>9.1e} {:>9} {:>5} {:>9.1e} {:<10}",
        r.n,
        r.candidate,
        r.seconds,
        r.z_err,
        r.bp_err.map_or("-".to_string(), |e| format!(
            "{e:.1e}{}",
            if r.bp_mismatch { "*" } else { "" }
        )),
        r.breakpoints,
        r.residual,
        r.status
    );
}
