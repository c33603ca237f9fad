//! Reprints the scaling table of `docs/scaling.md`: wall time, peak resident
//! memory (`/usr/bin/time -f %M`) and output size of
//!
//! * `frames run SCENE --lambda-max 12 --json` on the uniform cantilever
//!   (length 1, `mass_per_length = 1`, `plastic_moment = 1`, tip load
//!   `fy = 1`, clamped root) with `n` elements, and
//! * the obstacle problem on an `N x N` grid (`examples/obstacle.rs`, a sparse
//!   standard-form PLCP traced with an observer, nothing stored).
//!
//! Build first, then run (sizes optional; the defaults are the table's):
//!
//! ```text
//! cargo build --release -p frames --bin frames && cargo build --release --example obstacle
//! cargo run --release -q --example scaling_report -- --cantilever 100,1000,2000 --obstacle 32:4,100:1,316:0.8
//! cargo run --release -q --example scaling_report -- --trace 10000
//! ```
//!
//! Each case runs once (no repetition: these are minutes long at the top end).
//! `--frames PATH` and `--obstacle-bin PATH` run other binaries (a copy of an
//! older build, to compare side by side); an empty list (`--obstacle ''`)
//! skips that part.
//!
//! `--trace 10000` traces the cantilever's system (9) alone (plcp's sparse
//! long form in `f64`, `Keep::Nothing`, segments dropped as they come; no
//! hinge reading, no report), each size in a child process under
//! `/usr/bin/time`: whether `f64` traces it, its pivots and condition, and
//! the `Lambda` at which the hinge front reaches `x = 1/4, 1/2, 3/4` (the
//! first pivot that lets a yield mode there accelerate) beside the
//! continuum's `3 / (1 - x)` (`examples/cantilever_convergence.rs`).

use std::path::{Path, PathBuf};
use std::process::Command;

fn cantilever_toml(n: usize) -> String {
    format!(
        "title = \"Uniform cantilever, {n} elements\"\n[[node]]\nid = \"A\"\nx = 0.0\ny = 0.0\n[[node]]\nid = \"B\"\nx = 1.0\ny = 0.0\n[[member]]\nid = \"AB\"\nfrom = \"A\"\nto = \"B\"\nplastic_moment = 1.0\nelements = {n}\nmass_per_length = 1.0\n[[support]]\nnode = \"A\"\nfix = [\"x\", \"y\", \"rz\"]\n[[load]]\nnode = \"B\"\nfy = 1.0\n[history]\nkind = \"ramp\"\nrate = 1.0\n"
    )
}

/// The `j`-th breakpoint of the lumped cantilever of `n` elements (length 1,
/// `m = 1` per length lumped `h` at the interior nodes and `h/2` at the tip,
/// `Mp = 1`, tip load `Lambda`): the static collapse load 1, then (`j >= 1`)
/// the hinge travelling from node `k = j - 1` to `k + 1`, when the moment at
/// `k + 1` reaches `Mp` while the part beyond `k` rotates about it:
///
/// ```text
/// alpha I = Lambda (1 - x_k) - Mp,   Lambda (1 - x_{k+1}) - alpha J = Mp
/// I = sum_{i>k} m_i (x_i - x_k)^2,   J = sum_{i>k+1} m_i (x_i - x_k)(x_i - x_{k+1})
/// ```
///
/// so `Lambda = (I - J) / ((1 - x_{k+1}) I - (1 - x_k) J)`, evaluated in
/// integers (with `N = n - k`, `I - J = h^3 (N(N-1)/2 + N/2)`): exact but for
/// the final division.
fn closed_form(n: usize, j: usize) -> f64 {
    if j == 0 {
        return 1.0;
    }
    let big_n = (n - (j - 1)) as i128;
    let m = big_n - 1;
    let s1 = m * (m + 1) / 2;
    let s2 = m * (m + 1) * (2 * m + 1) / 6;
    // in units of h^3, times 2: I, J, I - J
    let i2 = 2 * s2 + big_n * big_n;
    let j2 = 2 * (s2 - s1) + big_n * (big_n - 1);
    let num = i2 - j2;
    // (1 - x_{k+1}) I - (1 - x_k) J in units of h^4, times 2
    let den = (big_n - 1) * i2 - big_n * j2;
    n as f64 * num as f64 / den as f64
}

/// Runs `cmd` under `/usr/bin/time -f "%e %M %U"`, stdout to `out`; returns
/// (seconds, peak resident MB, output bytes, the first line of the output,
/// user seconds)
/// and prints the user time and the load average to stderr (wall time on a
/// shared machine is several times the CPU time).
fn measure(cmd: &[&str], out: &Path) -> Result<(f64, f64, u64, String, f64), String> {
    let times = out.with_extension("time");
    let status = Command::new("/usr/bin/time")
        .args(["-f", "%e %M %U", "-o", times.to_str().unwrap()])
        .args(cmd)
        .stdout(std::fs::File::create(out).map_err(|e| e.to_string())?)
        .status()
        .map_err(|e| format!("{}: {e}", cmd[0]))?;
    if !status.success() {
        return Err(format!("{cmd:?} failed: {status}"));
    }
    let t = std::fs::read_to_string(&times).map_err(|e| e.to_string())?;
    let mut it = t.split_whitespace();
    let secs: f64 = it.next().and_then(|s| s.parse().ok()).unwrap_or(f64::NAN);
    let kb: f64 = it.next().and_then(|s| s.parse().ok()).unwrap_or(f64::NAN);
    let user: f64 = it.next().and_then(|s| s.parse().ok()).unwrap_or(f64::NAN);
    let load = std::fs::read_to_string("/proc/loadavg").unwrap_or_default();
    eprintln!(
        "{}: {secs:.2} s wall, {user:.2} s user, load average {}",
        cmd.join(" "),
        load.split_whitespace()
            .take(3)
            .collect::<Vec<_>>()
            .join(" ")
    );
    let bytes = std::fs::metadata(out).map(|m| m.len()).unwrap_or(0);
    let text = std::fs::read_to_string(out).unwrap_or_default();
    Ok((
        secs,
        kb / 1024.0,
        bytes,
        text.lines().next().unwrap_or("").to_string(),
        user,
    ))
}

fn list<T: std::str::FromStr>(args: &[String], flag: &str, default: &str) -> Vec<T> {
    let v = args
        .iter()
        .position(|a| a == flag)
        .and_then(|i| args.get(i + 1))
        .map_or(default, |s| s.as_str());
    v.split(',')
        .filter(|s| !s.is_empty())
        .filter_map(|s| s.parse().ok())
        .collect()
}

/// One trace of the `n`-element cantilever's system (9), nothing stored.
fn trace_one(n: usize) -> Result<(), String> {
    use plcp::{BasisKind, Control, Keep, Method, Var};
    let scene = frames::Scene::from_toml(&cantilever_toml(n), "cantilever.toml")
        .map_err(|e| e.to_string())?;
    let t0 = std::time::Instant::now();
    let system = frames::System::assemble(&scene.frame);
    let problem = system
        .plcp_sparse::<f64>(Some(12.0))
        .map_err(|e| e.to_string())?;
    let assembled = t0.elapsed().as_secs_f64();
    // frames' settings (near ties within the window are one event)
    let mut settings = frames::solve::plcp_settings::<f64>(Method::Wolfe);
    settings.basis = BasisKind::Sparse;
    // the mode (index into z) whose section sits nearest x = 1/4, 1/2, 3/4
    let xs = [0.25, 0.5, 0.75];
    let near: Vec<usize> = xs
        .iter()
        .map(|&x| {
            (0..system.modes.len())
                .min_by(|&a, &b| {
                    let d = |k: usize| {
                        let node = system.sections[system.modes[k].section].node;
                        (scene.frame.nodes[node].x - x).abs()
                    };
                    d(a).total_cmp(&d(b))
                })
                .unwrap_or(0)
        })
        .collect();
    let first = std::rc::Rc::new(std::cell::RefCell::new([f64::NAN; 3]));
    let seen = first.clone();
    let observer = move |_: &plcp::Segment<f64>, p: &plcp::Progress<'_, f64>| {
        if let Some(b) = p.breakpoint {
            if let Var::Z(k) = b.entering {
                for (f, &m) in seen.borrow_mut().iter_mut().zip(&near) {
                    if k == m && f.is_nan() {
                        *f = b.lambda;
                    }
                }
            }
        }
        Control::Continue
    };
    let run = plcp::solve_observed(&problem, &settings, observer, Keep::Nothing)
        .map_err(|e| e.to_string())?;
    let secs = t0.elapsed().as_secs_f64();
    let info = &run.path.info;
    println!(
        "n = {n}: {} unknowns, status {}, {} pivots, {} refactorisations, lambda reached {}, worst residual {:.1e}, max condition {:.1e}, path {} bytes, assembled in {assembled:.2} s, traced in {:.2} s",
        problem.dim(),
        run.path.status.as_str(),
        info.pivots,
        info.refactorisations,
        run.path.lambda_reached,
        info.residual.worst(),
        info.max_condition,
        info.path_bytes,
        secs - assembled
    );
    for (x, l) in xs.iter().zip(first.borrow().iter()) {
        println!(
            "  hinge front at x = {x}: Lambda = {l:.10} (continuum 3 / (1 - x) = {:.10})",
            3.0 / (1.0 - x)
        );
    }
    Ok(())
}

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().collect();
    if let Some(i) = args.iter().position(|a| a == "--trace-one") {
        let n: usize = args
            .get(i + 1)
            .and_then(|s| s.parse().ok())
            .ok_or("--trace-one N")?;
        return trace_one(n);
    }
    if args.iter().any(|a| a == "--trace") {
        let me = std::env::current_exe().map_err(|e| e.to_string())?;
        let dir = std::env::temp_dir().join("plcp-scaling-report");
        std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
        for n in list::<usize>(&args, "--trace", "10000") {
            let out = dir.join(format!("trace{n}.txt"));
            let (s, mb, _, _, _) =
                measure(&[me.to_str().unwrap(), "--trace-one", &n.to_string()], &out)?;
            let text = std::fs::read_to_string(&out).map_err(|e| e.to_string())?;
            print!("{text}");
            println!("  wall {s:.2} s, peak resident {mb:.0} MB");
        }
        return Ok(());
    }
    let cant: Vec<usize> = list(&args, "--cantilever", "100,1000,2000");
    let obst: Vec<String> = list(&args, "--obstacle", "32:4,100:1,316:0.8");
    let target = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/release");
    // other binaries (an older build, side by side): `--frames PATH`, `--obstacle-bin PATH`
    let path_arg = |flag: &str, default: PathBuf| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
            .map_or(default, PathBuf::from)
    };
    let frames = path_arg("--frames", target.join("frames"));
    let obstacle = path_arg("--obstacle-bin", target.join("examples/obstacle"));
    let dir = std::env::temp_dir().join("plcp-scaling-report");
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    println!("| case | n | wall s | user s | peak resident MB | output MB | status | breakpoints against the closed form |");
    println!("|---|---|---|---|---|---|---|---|");
    for n in cant {
        let scene = dir.join(format!("cantilever{n}.toml"));
        std::fs::write(&scene, cantilever_toml(n)).map_err(|e| e.to_string())?;
        let out = dir.join(format!("cantilever{n}.json"));
        let (s, mb, bytes, _, user) = measure(
            &[
                frames.to_str().unwrap(),
                "run",
                scene.to_str().unwrap(),
                "--lambda-max",
                "12",
                "--json",
            ],
            &out,
        )?;
        let doc: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&out).map_err(|e| e.to_string())?)
                .map_err(|e| e.to_string())?;
        let bps: Vec<f64> = doc["breakpoints"]
            .as_array()
            .map(|b| b.iter().filter_map(|b| b["lambda"].as_f64()).collect())
            .unwrap_or_default();
        let worst = bps
            .iter()
            .enumerate()
            .map(|(j, &l)| {
                let exact = closed_form(n, j);
                (l - exact).abs() / exact
            })
            .fold(0.0f64, f64::max);
        println!(
            "| cantilever `frames run --json --lambda-max 12` | {n} elements | {s:.2} | {user:.2} | {mb:.0} | {:.1} | {}, {} pivots | {} breakpoints, worst relative difference {worst:.1e} |",
            bytes as f64 / 1e6,
            doc["status"].as_str().unwrap_or("?"),
            doc["solver"]["pivots"],
            bps.len()
        );
    }
    for case in obst {
        let (nx, lmax) = case.split_once(':').unwrap_or((case.as_str(), "1"));
        let out = dir.join(format!("obstacle{nx}.txt"));
        let (s, mb, _, line, user) = measure(&[obstacle.to_str().unwrap(), nx, lmax], &out)?;
        let nx: usize = nx.parse().map_err(|_| format!("bad N {nx}"))?;
        let pivots = line
            .split(", ")
            .find(|p| p.ends_with(" pivots"))
            .unwrap_or("? pivots")
            .to_string();
        let status = line
            .split(", ")
            .find(|p| p.starts_with("status "))
            .unwrap_or("status ?")
            .trim_start_matches("status ")
            .to_string();
        println!(
            "| obstacle N = {nx}, L_max = {lmax} | {} unknowns | {s:.2} | {user:.2} | {mb:.0} | - | {status}, {pivots} |",
            nx * nx
        );
    }
    Ok(())
}
