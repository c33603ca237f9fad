//! What `plcp solve` spends besides the solve: reading the input and writing
//! the report, for one problem given three ways (`M` inline in JSON, as a
//! Matrix Market file, as a NumPy `.npy` file) and with and without the
//! segments in the report.
//!
//! ```text
//! cargo build --release --bin plcp --example input_report
//! target/release/examples/input_report PROBLEM.json [--reps 3] [--threads 1]
//! ```
//!
//! `PROBLEM.json` is a dense problem in plcp's JSON format (for example an
//! instance `bench.py` of the qpOASES peer caches in `/tmp/qpoases-bench`).
//! Its `M` is written as `.mtx` and `.npy` into a scratch directory, and each
//! form is solved `reps` times by the `plcp` binary next to this program
//! (`target/release/plcp`), one after the other; the table keeps each case's
//! fastest run: wall time of the process, the solve's own
//! `timing.solve_seconds`, their ratio, and the report's size. Run it on a
//! quiet machine: the wall time counts waiting for a core.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Instant;

fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(2);
    }
}

fn run() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut file = None;
    let (mut reps, mut threads) = (3usize, "1".to_string());
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--reps" => {
                reps = it
                    .next()
                    .and_then(|v| v.parse().ok())
                    .filter(|&r| r >= 1)
                    .ok_or("--reps needs a number >= 1")?
            }
            "--threads" => threads = it.next().ok_or("--threads needs a value")?.clone(),
            "-h" | "--help" => {
                println!("input_report PROBLEM.json [--reps 3] [--threads 1]");
                return Ok(());
            }
            f if file.is_none() => file = Some(PathBuf::from(f)),
            other => return Err(format!("unexpected argument {other}")),
        }
    }
    let file = file.ok_or("give a problem file (plcp's dense JSON format)")?;
    let plcp = std::env::current_exe()
        .map_err(|e| e.to_string())?
        .parent()
        .and_then(Path::parent)
        .map(|d| d.join("plcp"))
        .filter(|p| p.is_file())
        .ok_or("the plcp binary is not built: cargo build --release --bin plcp")?;

    // the three forms of the same problem
    let problem = plcp::io::json::read_plcp::<f64>(&file).map_err(|e| e.to_string())?;
    let n = problem.n();
    let dir = std::env::temp_dir().join(format!("plcp-input-report-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let text = std::fs::read_to_string(&file).map_err(|e| e.to_string())?;
    let mut value: serde_json::Value = serde_json::from_str(&text).map_err(|e| e.to_string())?;
    let m = problem.m();
    let column_major: Vec<f64> = (0..n)
        .flat_map(|j| (0..n).map(move |i| m[(i, j)]))
        .collect();
    let mut mtx = Vec::new();
    plcp::io::mtx::write_mtx_dense(&mut mtx, n, n, &column_major).map_err(|e| e.to_string())?;
    std::fs::write(dir.join("m.mtx"), &mtx).map_err(|e| e.to_string())?;
    std::fs::write(dir.join("m.npy"), npy_fortran(n, &column_major)).map_err(|e| e.to_string())?;
    let inline = dir.join("inline.json");
    std::fs::copy(&file, &inline).map_err(|e| e.to_string())?;
    let mut forms = vec![("JSON, M inline", inline)];
    for (label, name) in [("JSON + m.mtx", "m.mtx"), ("JSON + m.npy", "m.npy")] {
        value["M"] = serde_json::Value::String(name.into());
        let f = dir.join(format!("{name}.json"));
        std::fs::write(&f, value.to_string()).map_err(|e| e.to_string())?;
        forms.push((label, f));
    }

    println!(
        "plcp solve, n = {n}, --threads {threads}, best of {reps} (load {})",
        std::fs::read_to_string("/proc/loadavg")
            .ok()
            .and_then(|l| l.split_whitespace().next().map(str::to_string))
            .unwrap_or_else(|| "?".into())
    );
    println!();
    println!("| input | segments | input size | wall s | solve s | wall / solve | report |");
    println!("|---|---|---|---|---|---|---|");
    for (label, f) in &forms {
        let input_size = std::fs::metadata(f).map(|m| m.len()).unwrap_or(0)
            + if label.contains("mtx") {
                mtx.len() as u64
            } else if label.contains("npy") {
                8 * (n * n) as u64
            } else {
                0
            };
        for segments in ["all", "none"] {
            let mut best: Option<(f64, f64, usize)> = None;
            for _ in 0..reps {
                let start = Instant::now();
                let out = Command::new(&plcp)
                    .args([
                        "solve",
                        "--quiet",
                        "--threads",
                        &threads,
                        "--segments",
                        segments,
                    ])
                    .arg(f)
                    .stderr(Stdio::inherit())
                    .output()
                    .map_err(|e| e.to_string())?;
                let wall = start.elapsed().as_secs_f64();
                if !out.status.success() {
                    return Err(format!("plcp solve failed on {}", f.display()));
                }
                let v: serde_json::Value =
                    serde_json::from_slice(&out.stdout).map_err(|e| e.to_string())?;
                let solve = v["timing"]["solve_seconds"].as_f64().unwrap_or(f64::NAN);
                if best.is_none_or(|(w, _, _)| wall < w) {
                    best = Some((wall, solve, out.stdout.len()));
                }
            }
            if let Some((wall, solve, bytes)) = best {
                println!(
                    "| {label} | {segments} | {} | {wall:.3} | {solve:.3} | {:.2} | {} |",
                    mb(input_size),
                    wall / solve,
                    mb(bytes as u64)
                );
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    Ok(())
}

fn mb(bytes: u64) -> String {
    format!("{:.1} MB", bytes as f64 / 1e6)
}

/// `numpy.save` of a float64 matrix in Fortran order (format 1.0).
fn npy_fortran(n: usize, column_major: &[f64]) -> Vec<u8> {
    let header = format!("{{'descr': '<f8', 'fortran_order': True, 'shape': ({n}, {n}), }}");
    let total = (10 + header.len() + 1).div_ceil(64) * 64;
    let padded = format!("{header:<width$}\n", width = total - 11);
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(padded.len() as u16).to_le_bytes());
    out.extend_from_slice(padded.as_bytes());
    for v in column_major {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out
}
