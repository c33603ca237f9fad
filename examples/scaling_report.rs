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
//! ```
//!
//! Each case runs once (no repetition: these are minutes long at the top end).

use std::path::{Path, PathBuf};
use std::process::Command;

fn cantilever_toml(n: usize) -> String {
    format!(
        "title = \"Uniform cantilever, {n} elements\"\n[[node]]\nid = \"A\"\nx = 0.0\ny = 0.0\n[[node]]\nid = \"B\"\nx = 1.0\ny = 0.0\n[[member]]\nid = \"AB\"\nfrom = \"A\"\nto = \"B\"\nplastic_moment = 1.0\nelements = {n}\nmass_per_length = 1.0\n[[support]]\nnode = \"A\"\nfix = [\"x\", \"y\", \"rz\"]\n[[load]]\nnode = \"B\"\nfy = 1.0\n[history]\nkind = \"ramp\"\nrate = 1.0\n"
    )
}

/// Runs `cmd` under `/usr/bin/time -f "%e %M"`, stdout to `out`; returns
/// (seconds, peak resident MB, output bytes, the first line of the output).
fn measure(cmd: &[&str], out: &Path) -> Result<(f64, f64, u64, String), String> {
    let times = out.with_extension("time");
    let status = Command::new("/usr/bin/time")
        .args(["-f", "%e %M", "-o", times.to_str().unwrap()])
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
    let bytes = std::fs::metadata(out).map(|m| m.len()).unwrap_or(0);
    let text = std::fs::read_to_string(out).unwrap_or_default();
    Ok((
        secs,
        kb / 1024.0,
        bytes,
        text.lines().next().unwrap_or("").to_string(),
    ))
}

fn list<T: std::str::FromStr>(args: &[String], flag: &str, default: &str) -> Vec<T> {
    let v = args
        .iter()
        .position(|a| a == flag)
        .and_then(|i| args.get(i + 1))
        .map_or(default, |s| s.as_str());
    v.split(',').filter_map(|s| s.parse().ok()).collect()
}

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().collect();
    let cant: Vec<usize> = list(&args, "--cantilever", "100,1000,2000");
    let obst: Vec<String> = list(&args, "--obstacle", "32:4,100:1,316:0.8");
    let target = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/release");
    let frames = target.join("frames");
    let obstacle = target.join("examples/obstacle");
    let dir = std::env::temp_dir().join("plcp-scaling-report");
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    println!("| case | n | wall s | peak resident MB | output MB | status |");
    println!("|---|---|---|---|---|---|");
    for n in cant {
        let scene = dir.join(format!("cantilever{n}.toml"));
        std::fs::write(&scene, cantilever_toml(n)).map_err(|e| e.to_string())?;
        let out = dir.join(format!("cantilever{n}.json"));
        let (s, mb, bytes, _) = measure(
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
        println!(
            "| cantilever `frames run --json --lambda-max 12` | {n} elements | {s:.2} | {mb:.0} | {:.1} | {}, {} pivots |",
            bytes as f64 / 1e6,
            doc["status"].as_str().unwrap_or("?"),
            doc["solver"]["pivots"]
        );
    }
    for case in obst {
        let (nx, lmax) = case.split_once(':').unwrap_or((case.as_str(), "1"));
        let out = dir.join(format!("obstacle{nx}.txt"));
        let (s, mb, _, line) = measure(&[obstacle.to_str().unwrap(), nx, lmax], &out)?;
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
            "| obstacle N = {nx}, L_max = {lmax} | {} unknowns | {s:.2} | {mb:.0} | - | {status}, {pivots} |",
            nx * nx
        );
    }
    Ok(())
}
