//! Repeats one solve (or one MPC loop) many times in one process, for a
//! profiler (`perf record`) and for a steady per-call time at everyday sizes.
//!
//! ```sh
//! cargo run --release -p plcp --example everyday_profile -- solve FILE.json 2000
//! cargo run --release -p plcp --example everyday_profile -- sequence SEQ.json 20
//! cargo run --release -p plcp --example everyday_profile -- tiny - 100000
//! THREADS=default cargo run --release -p plcp --example everyday_profile -- solve FILE.json 20
//! ```
//!
//! `solve`: `plcp::solve` on one thread, `REPS` times; prints the mean and
//! the best time per call. `sequence`: the loop of `plcp sequence` (an LCP at
//! `g_0`, then one step per later target) `REPS` times, per step, with the
//! lean `Solver::step_end` (`PATHS=1`: `Solver::step`, the full path).
//! `tiny`: the tiny call of issue 20 (`n = 2`, one pivot; the file argument
//! is not read). One thread (`Settings::threads = Some(1)`) unless
//! `THREADS=default` (the library's choice by size).
//!
//! `FAULTS=1` (`solve`): each call's time and minor page faults on standard
//! error (`first` prints the faults of its two solves always). A fresh
//! process's first solve touches new memory, and on a virtualised machine a
//! new page costs microseconds.

use plcp::Settings;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let (mode, file) = (args.get(1).ok_or("mode")?, args.get(2).ok_or("file")?);
    let reps: usize = args.get(3).map_or(Ok(100), |s| s.parse())?;
    // THREADS=default: the library's thread choice (by size), else one thread
    let default_threads = std::env::var("THREADS").is_ok_and(|v| v == "default");
    if !default_threads {
        faer::set_global_parallelism(faer::Par::Seq);
    }
    let settings = Settings::<f64> {
        threads: if default_threads { None } else { Some(1) },
        ..Settings::default()
    };
    let (mut best, mut total) = (f64::INFINITY, 0.0);
    let mut calls = 0usize;
    match mode.as_str() {
        "first" => {
            // the costs a first call in a process pays, one by one
            let problem = plcp::io::json::read_plcp::<f64>(std::path::Path::new(file))?;
            let t0 = Instant::now();
            if std::env::var_os("WARM").is_some() {
                plcp::warm_up();
            }
            let w = t0.elapsed().as_secs_f64();
            let t = Instant::now();
            let v3 = std::hint::black_box(pulp::Arch::new());
            let a = t.elapsed().as_secs_f64();
            let t = Instant::now();
            let k: usize = std::env::var("FIRST_N")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(8);
            let x = faer::Mat::<f64>::identity(k, k);
            let y = std::hint::black_box(&x * &x);
            let b = t.elapsed().as_secs_f64();
            let t = Instant::now();
            let inv = faer::linalg::solvers::DenseSolveCore::inverse(&y.partial_piv_lu());
            std::hint::black_box(&inv);
            let c = t.elapsed().as_secs_f64();
            if std::env::var_os("WARM").is_some() {
                plcp::warm_up();
            }
            let f0 = minflt();
            let t = Instant::now();
            let path = plcp::solve(&problem, &settings)?;
            let d = t.elapsed().as_secs_f64();
            let f1 = minflt();
            let t = Instant::now();
            let path2 = plcp::solve(&problem, &settings)?;
            let e = t.elapsed().as_secs_f64();
            let f2 = minflt();
            eprintln!("faults: first solve {}, again {}", f1 - f0, f2 - f1);
            std::hint::black_box((&path, &path2, &v3));
            println!(
                "warm_up {:.1} us, pulp::Arch::new {:.1} us, first matmul {:.1} us, first lu inverse {:.1} us, solve {:.1} us, again {:.1} us",
                1e6 * w,
                1e6 * a,
                1e6 * b,
                1e6 * c,
                1e6 * d,
                1e6 * e
            );
        }
        "tiny" => {
            // the tiny call of issue 20: `M = [[2, 1], [1, 2]]`, `q = (1, 1)`,
            // `d = (-1, -0.5)`, `L` to 1.5, one pivot (FILE is not read)
            let m = faer::mat![[2.0, 1.0], [1.0, 2.0]];
            let (q, d) = (faer::col![1.0, 1.0], faer::col![-1.0, -0.5]);
            let problem = plcp::Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
                .and_then(|p| p.with_range(0.0, Some(1.5)))?;
            (best, total, calls) = time_solves(&problem, &settings, reps)?;
            println!(
                "tiny n=2 pivots={calls}: mean {:.2} us, best {:.2} us",
                1e6 * total / reps as f64,
                1e6 * best
            );
        }
        "solve" => {
            let problem = plcp::io::json::read_plcp::<f64>(std::path::Path::new(file))?;
            (best, total, calls) = time_solves(&problem, &settings, reps)?;
            println!(
                "solve n={} pivots={calls}: mean {:.2} us, best {:.2} us",
                problem.n(),
                1e6 * total / reps as f64,
                1e6 * best
            );
        }
        "sequence" => {
            let (m, targets) = plcp::io::json::read_sequence(std::path::Path::new(file))?;
            let k = targets.len() - 1;
            let n = m.nrows();
            // PATHS=1: the full Path of every step (Solver::step), else the lean end
            let lean = std::env::var_os("PATHS").is_none();
            let mut d = faer::Col::<f64>::zeros(n);
            for _ in 0..reps {
                let mut solver = plcp::Solver::new(m.as_ref(), &settings)?;
                let t = Instant::now();
                let mut pivots = 0;
                for (i, g) in targets.iter().enumerate() {
                    if lean {
                        let end = if i == 0 {
                            solver.lcp_end(g.as_ref())?
                        } else {
                            for r in 0..n {
                                d[r] = g[r] - targets[i - 1][r];
                            }
                            solver.step_end(targets[i - 1].as_ref(), d.as_ref())?
                        };
                        pivots += end.pivots;
                        std::hint::black_box(&end);
                    } else {
                        let path = if i == 0 {
                            solver.lcp(g.as_ref())?
                        } else {
                            let d = g - &targets[i - 1];
                            solver.step(targets[i - 1].as_ref(), d.as_ref())?
                        };
                        pivots += path.info.pivots;
                        std::hint::black_box(&path);
                    }
                }
                let s = t.elapsed().as_secs_f64() / k as f64;
                best = best.min(s);
                total += s;
                calls = pivots;
            }
            println!(
                "sequence n={} steps={k} pivots={calls}: mean {:.2} us a step, best {:.2} us",
                m.nrows(),
                1e6 * total / reps as f64,
                1e6 * best
            );
        }
        _ => return Err("mode: solve or sequence".into()),
    }
    Ok(())
}

/// `reps` timed calls of `plcp::solve`: the best and the total seconds, and
/// the pivots of a call.
fn time_solves(
    problem: &plcp::Plcp<f64>,
    settings: &Settings<f64>,
    reps: usize,
) -> Result<(f64, f64, usize), plcp::PlcpError> {
    let (mut best, mut total, mut pivots) = (f64::INFINITY, 0.0, 0);
    let faults = std::env::var_os("FAULTS").is_some();
    for _ in 0..reps {
        let f0 = if faults { minflt() } else { 0 };
        let t = Instant::now();
        let path = plcp::solve(problem, settings)?;
        let s = t.elapsed().as_secs_f64();
        if faults {
            eprintln!("{:.1} us, {} faults", 1e6 * s, minflt() - f0);
        }
        std::hint::black_box(&path);
        best = best.min(s);
        total += s;
        pivots = path.info.pivots;
    }
    Ok((best, total, pivots))
}

/// The process's minor page faults so far (`/proc/self/stat`, field 10; 0
/// where it cannot be read).
fn minflt() -> u64 {
    let s = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let rest = s.rsplit(')').next().unwrap_or("");
    rest.split_whitespace()
        .nth(7)
        .and_then(|x| x.parse().ok())
        .unwrap_or(0)
}
