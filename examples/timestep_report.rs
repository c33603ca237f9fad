//! Time stepping against the PLCP path of system (9), scene by scene (issue 6):
//! error and run time of the velocity-level integrator
//! ([`frames::timestep`]) for steps from 1e-1 to 1e-5 of the response time,
//! with the PLCP analysis's own run time on the same rows as a ratio, and the
//! deactivation verdict of each.
//!
//! ```sh
//! cargo run --release --example timestep_report                  # h/T = 1e-1 .. 1e-4
//! cargo run --release --example timestep_report -- --finest 1e-5 # adds 1e-5 (about a minute per scene)
//! cargo run --release --example timestep_report -- --scenes cantilever,portal-sway
//! ```
//!
//! Options: `--finest X` (smallest h/T, default 1e-4; 1e-5 takes longer than a
//! minute over all scenes), `--scenes a,b,...` (names in `scenes/`, default
//! all seven), `--repeats R` (PLCP analysis: best of R runs, default 5),
//! `--out DIR` (default `out/timestep`), `--quiet` (no progress bar; the bar
//! is drawn on stderr only when it is a terminal).
//!
//! The pipe-whip scenes run with `--scenes pipe-whip/l-shaped,pipe-whip/straight`
//! etc. They are not in the default list: at h/T down to 1e-4 the five take
//! about a minute on two cores, and the in-plane quadrant's T is about 9e4
//! (its last critical value is huge), so h/T says little there; their check
//! against the PLCP path's first unloading is `examples/pipe_whip.rs`.
//!
//! Per scene: `T` is the analysis's response time (the end of its time
//! response: `Lambda` reaches 1.5 times the last critical value). The PLCP row
//! is `frames::Analysis::run` (solve, hinge reading, exact response). Each
//! time-stepping row runs from rest to `T` (or, where the PLCP path shows a
//! deactivation, compares at the time of that deactivation and keeps stepping
//! to `T` for the verdict). Columns: `disp err` is the largest difference of a
//! nodal translation against the exact PLCP response, relative to the largest
//! translation; `act err` the largest difference of a hinge's start-of-flow
//! time, relative to `T`; `stops` the deactivations seen by the integrator
//! (flowing modes whose rate returned to zero); `ratio` the run time over the
//! PLCP analysis's. The order is the slope of log(disp err) between
//! consecutive rows.
//!
//! Output: the table on stdout, `report.csv` (with the PLCP run times),
//! `report.svg` (log-log: displacement error against the run-time ratio to the
//! PLCP analysis, one series per scene) and `order.svg` (displacement error
//! against h/T) in the output directory.

use frames::timestep::{compare, StepOptions, StepState, TimeStepping};
use frames::{Analysis, AnalysisOptions, Scene};
use std::fmt::Write as _;
use std::time::Instant;

#[path = "common/speed/svg.rs"]
mod svg;

const SCENES: [&str; 7] = [
    "cantilever",
    "cantilever-halftip",
    "portal-sway",
    "portal-vertical",
    "portal-combined",
    "two-storey",
    "two-storey-sway",
];

struct Options {
    finest: f64,
    scenes: Vec<String>,
    repeats: usize,
    out: std::path::PathBuf,
    quiet: bool,
}

fn options() -> Options {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut o = Options {
        finest: 1e-4,
        scenes: SCENES.iter().map(|s| s.to_string()).collect(),
        repeats: 5,
        out: "out/timestep".into(),
        quiet: false,
    };
    let mut i = 0;
    while i < args.len() {
        if args[i] == "--quiet" {
            o.quiet = true;
            i += 1;
            continue;
        }
        let val = args
            .get(i + 1)
            .unwrap_or_else(|| panic!("{} needs a value", args[i]));
        match args[i].as_str() {
            "--finest" => o.finest = val.parse().expect("--finest X"),
            "--scenes" => o.scenes = val.split(',').map(str::to_string).collect(),
            "--repeats" => o.repeats = val.parse().expect("--repeats R"),
            "--out" => o.out = val.into(),
            other => panic!("unknown option {other}"),
        }
        i += 2;
    }
    o
}

fn main() {
    let o = options();
    std::fs::create_dir_all(&o.out).expect("create the output directory");
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes");
    let mut csv = String::from(
        "scene,h_over_T,h,steps,seconds,plcp_seconds,ratio,disp_err_rel,act_err_rel,pivots,cold_restarts,worst_residual,stops,plcp_deactivations,t_compare,T\n",
    );
    let mut points = Vec::new();
    let mut order_points = Vec::new();
    let mut verdicts = Vec::new();
    let mut rels = vec![1e-1, 1e-2, 1e-3, 1e-4, 1e-5];
    rels.retain(|&r| r >= o.finest * 0.999);
    // one tick per (scene, step): the finest steps dominate the time
    let bar = plcp::progress::Progress::bar((o.scenes.len() * rels.len()) as u64, "runs", o.quiet);
    for name in &o.scenes {
        bar.message(name);
        let scene = Scene::from_file(format!("{root}/{name}.toml")).expect("scene");
        let mut best = f64::INFINITY;
        let mut analysis = None;
        for _ in 0..o.repeats.max(1) {
            let timer = Instant::now();
            let a = Analysis::run(scene.clone(), &AnalysisOptions::default()).expect("analysis");
            best = best.min(timer.elapsed().as_secs_f64());
            analysis = Some(a);
        }
        let a = analysis.expect("at least one run");
        let t_end = *a.response.time.times.last().expect("a time response");
        let plcp_dea = a.reading.deactivations().len();
        bar.suspend(|| println!(
            "\n{name}: T = {t_end:.4}, PLCP analysis {:.3} ms ({} pivots), PLCP deactivations: {plcp_dea}{}",
            best * 1e3,
            a.solution.info.pivots,
            frames::timestep::plcp_valid_until(&a)
                .map(|(l, t)| format!(" (first at Lambda = {l:.4}, t = {t:.4}: compared there)"))
                .unwrap_or_default()
        ));
        bar.suspend(|| {
            println!(
                "{:>8} {:>10} {:>8} {:>11} {:>9} {:>10} {:>10} {:>6} {:>8} {:>9} {:>5}",
                "h/T",
                "h",
                "steps",
                "time",
                "ratio",
                "disp err",
                "act err",
                "order",
                "pivots",
                "residual",
                "stops"
            )
        });
        let mut prev: Option<(f64, f64)> = None;
        let mut stops_at_finest = Vec::new();
        let mut decel_at_finest = None;
        for &rel in &rels {
            let opts = StepOptions {
                h: rel * t_end,
                t_end,
                ..StepOptions::default()
            };
            let ts = TimeStepping::new(&a.system, &a.scene.history, &opts).expect("options");
            bar.message(&format!("{name}, h/T = {rel:.0e}"));
            let run = ts.run(&StepState::rest(&a.system)).expect("run");
            bar.inc(1);
            let c = compare(&a, &run);
            let rel_disp = c.displacement_error / c.displacement_scale.max(f64::MIN_POSITIVE);
            let rel_act = c.activation_error / t_end;
            let order = prev
                .map(|(r0, e0)| format!("{:.2}", (e0 / rel_disp).log10() / (r0 / rel).log10()))
                .unwrap_or_default();
            prev = Some((rel, rel_disp));
            let stops = run.deactivations();
            let ratio = run.seconds / best;
            let status = if run.outcome.is_completed() {
                ""
            } else {
                " STOPPED"
            };
            bar.suspend(|| println!(
                "{:>8.0e} {:>10.3e} {:>8} {:>9.3}ms {:>9.1} {:>10.2e} {:>10.2e} {:>6} {:>8} {:>9.1e} {:>5}{status}",
                rel,
                run.h,
                run.steps.len(),
                run.seconds * 1e3,
                ratio,
                rel_disp,
                rel_act,
                order,
                run.pivots(),
                run.worst_residual(),
                stops.len()
            ));
            let _ = writeln!(
                csv,
                "{name},{rel:e},{:e},{},{:e},{best:e},{ratio:e},{rel_disp:e},{rel_act:e},{},{},{:e},{},{plcp_dea},{:e},{t_end:e}",
                run.h,
                run.steps.len(),
                run.seconds,
                run.pivots(),
                run.cold_restarts,
                run.worst_residual(),
                stops.len(),
                c.t
            );
            points.push(svg::Point {
                x: ratio,
                y: rel_disp,
                series: name.clone(),
                label: format!("h/T={rel:.0e}"),
            });
            order_points.push(svg::Point {
                x: rel,
                y: rel_disp,
                series: name.clone(),
                label: String::new(),
            });
            decel_at_finest = run.decelerations().first().map(|e| (e.t, e.lambda));
            stops_at_finest = stops
                .iter()
                .map(|e| {
                    let n = frames::hinge::section_name(&a.scene.frame, &a.system, e.section);
                    format!(
                        "{} ({} {}, {}) at t = {:.4} (Lambda = {:.4}, y/X* = {:.2e})",
                        n.node,
                        n.member,
                        n.end.as_str(),
                        e.sign.as_str(),
                        e.t,
                        e.lambda,
                        e.y_relative
                    )
                })
                .collect();
        }
        let decel = decel_at_finest
            .map(|(t, l)| format!(" (decelerating from t = {t:.4}, Lambda = {l:.4})"))
            .unwrap_or_default();
        let verdict = match (plcp_dea, stops_at_finest.is_empty()) {
            (0, true) if decel.is_empty() => {
                "no deactivation (PLCP path and time stepping agree)".to_string()
            }
            (0, true) => format!("no deactivation, but a hinge decelerates{decel}"),
            (0, false) => format!(
                "time stepping sees deactivations the PLCP path does not: {}",
                stops_at_finest.join("; ")
            ),
            (_, true) => "the PLCP path unloads, time stepping sees no deactivation".to_string(),
            (_, false) => format!(
                "deactivation confirmed by time stepping{decel}: {}",
                stops_at_finest.join("; ")
            ),
        };
        bar.suspend(|| println!("verdict: {verdict}"));
        verdicts.push(format!("{name}: {verdict}"));
    }
    bar.finish();
    println!("\nverdicts (at the finest step):");
    for v in &verdicts {
        println!("  {v}");
    }
    std::fs::write(o.out.join("report.csv"), csv).expect("write report.csv");
    let svg = svg::log_log(
        "time stepping: displacement error against run time (PLCP analysis = 1)",
        "run time / PLCP analysis run time",
        "relative displacement error",
        &points,
    );
    std::fs::write(o.out.join("report.svg"), svg).expect("write report.svg");
    let svg = svg::log_log(
        "time stepping: displacement error against step (first order)",
        "h / T",
        "relative displacement error",
        &order_points,
    );
    std::fs::write(o.out.join("order.svg"), svg).expect("write order.svg");
    println!(
        "wrote report.csv, report.svg and order.svg in {}",
        o.out.display()
    );
}
