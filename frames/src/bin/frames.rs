//! The frames command line: `frames run SCENE.toml [...]`, `frames export SCENE.toml`.
//!
//! Bad input (a scene error, an unknown option, Lemke on an indeterminate
//! frame) ends with exit code 2 and one line naming what is wrong.

use clap::{Parser, Subcommand};
use frames::report::format_number;
use frames::{Analysis, AnalysisOptions, FramesError, Scene, SolveOptions};
use plcp::{Method, Precision};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "frames",
    version,
    about = "Dynamic response of rigid-plastic planar frames under a monotone pulse: system (9) solved as a parametric LCP"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// No progress display on stderr (it is shown only on a terminal anyway).
    #[arg(long, short, global = true)]
    quiet: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Analyse a scene: critical Lambda values, hinges, intervals, response.
    Run {
        /// The scene file (TOML).
        scene: PathBuf,
        /// Print the JSON document instead of the text report.
        #[arg(long)]
        json: bool,
        /// Write SVG plots and CSV tables to this directory.
        #[arg(long, value_name = "DIR")]
        plots: Option<PathBuf>,
        /// Projection of a space scene's plots: auto (the nodes' coordinate plane, else iso), xy, xz, yz or iso.
        #[arg(long, default_value = "auto", value_parser = frames::plot::View::parse)]
        view: frames::plot::View,
        /// wolfe (long form, any frame) or lemke (Schur reduction, statically determinate frames).
        #[arg(long, default_value = "wolfe", value_parser = parse_method)]
        method: Method,
        /// Working precision of the solve: f32, f64, f128, or exact (big rationals).
        /// (Default f64, re-solved in f128 when the f64 path is not a solution.)
        #[arg(long, value_parser = parse_precision)]
        precision: Option<FramePrecision>,
        /// Certify the path in exact rational arithmetic; the report shows the
        /// exact critical loads.
        #[arg(long)]
        certify: bool,
        /// Largest Lambda to trace (default: infinity).
        #[arg(long, value_name = "X")]
        lambda_max: Option<f64>,
        /// End time of the time response (default: Lambda reaches 1.5 x the last critical value).
        #[arg(long, value_name = "T")]
        t_end: Option<f64>,
        /// Where the PLCP path shows a deactivation (its response is not valid
        /// beyond that Lambda), continue from there by time stepping.
        #[arg(long)]
        timestep_after: bool,
        /// Time step of --timestep-after, as a fraction of the response time.
        #[arg(long, value_name = "H", default_value_t = 1e-3)]
        step: f64,
        /// JSON moment distributions: all, a count N (sampled evenly), or
        /// Lambda values L1,L2,... (the nearest breakpoints). Default: all for
        /// scenes of at most 200 nodes and breakpoints, else 20.
        #[arg(long, value_name = "all|N|L1,L2,...", value_parser = parse_moments)]
        moments: Option<frames::report::MomentPick>,
        /// JSON node accelerations and series: all, a count N (sampled evenly),
        /// or node ids A,B,... Default: all up to 200 nodes, else 20.
        #[arg(long, value_name = "all|N|ID,ID,...", value_parser = parse_nodes)]
        nodes: Option<frames::report::NodePick>,
        /// JSON hinge sets per interval: full (the lists) or changes (what
        /// starts and stops; linear in the events). Default: full up to 200
        /// nodes, else changes.
        #[arg(long, value_name = "full|changes", value_parser = parse_hinge_sets)]
        hinge_sets: Option<frames::report::HingeSets>,
    },
    /// Print the mixed PLCP of system (9) as plcp's JSON input.
    Export {
        /// The scene file (TOML).
        scene: PathBuf,
        /// lambda_max to write (default: null, infinity).
        #[arg(long, value_name = "X")]
        lambda_max: Option<f64>,
    },
}

fn parse_method(s: &str) -> Result<Method, String> {
    s.parse()
}

/// A float precision or exact rationals.
#[derive(Clone, Copy)]
enum FramePrecision {
    Float(Precision),
    Exact,
}

fn parse_precision(s: &str) -> Result<FramePrecision, String> {
    if s == "exact" {
        return Ok(FramePrecision::Exact);
    }
    s.parse::<Precision>()
        .map(FramePrecision::Float)
        .map_err(|_| format!("unknown precision '{s}': expected f32, f64, f128 or exact"))
}

fn parse_hinge_sets(s: &str) -> Result<frames::report::HingeSets, String> {
    match s {
        "full" => Ok(frames::report::HingeSets::Full),
        "changes" => Ok(frames::report::HingeSets::Changes),
        _ => Err(format!(
            "unknown hinge sets '{s}': expected full or changes"
        )),
    }
}

fn parse_moments(s: &str) -> Result<frames::report::MomentPick, String> {
    use frames::report::MomentPick;
    if s == "all" {
        return Ok(MomentPick::All);
    }
    if let Ok(n) = s.parse::<usize>() {
        return Ok(MomentPick::Count(n));
    }
    s.split(',')
        .map(|x| {
            x.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    format!("'{x}' is not a Lambda value (expected all, a count, or L1,L2,...)")
                })
        })
        .collect::<Result<Vec<_>, _>>()
        .map(MomentPick::At)
}

fn parse_nodes(s: &str) -> Result<frames::report::NodePick, String> {
    use frames::report::NodePick;
    if s == "all" {
        return Ok(NodePick::All);
    }
    if let Ok(n) = s.parse::<usize>() {
        return Ok(NodePick::Count(n));
    }
    Ok(NodePick::Ids(
        s.split(',').map(|x| x.trim().to_string()).collect(),
    ))
}

/// Writes to stdout; a closed pipe (`frames run ... | head`) is not an error.
fn out(text: &str) {
    let _ = std::io::stdout().write_all(text.as_bytes());
}

/// What `frames run` reports beyond the defaults (`--moments`, `--nodes`,
/// `--hinge-sets`).
struct Picks {
    moments: Option<frames::report::MomentPick>,
    nodes: Option<frames::report::NodePick>,
    hinge_sets: Option<frames::report::HingeSets>,
}

/// `frames run`'s report on stdout: the JSON document (`json`) or the text,
/// with the no-unloading warning when a hinge unloads at `valid`.
fn write_report(
    analysis: &Analysis,
    valid: Option<(f64, f64)>,
    json: bool,
    picks: Picks,
) -> Result<(), FramesError> {
    let Picks {
        moments,
        nodes,
        hinge_sets,
    } = picks;
    if json {
        let mut sel = frames::report::OutputSelection::default_for(analysis);
        if let Some(m) = moments {
            sel.moments = m;
        }
        if let Some(n) = nodes {
            sel.nodes = n;
        }
        if let Some(h) = hinge_sets {
            sel.hinge_sets = h;
        }
        let mut doc = analysis
            .json_report(&sel)
            .map_err(|message| FramesError::Scene {
                file: analysis.scene.file.clone(),
                line: 0,
                key: "--nodes".into(),
                message,
            })?;
        if let Some((lambda, _)) = valid {
            doc.insert("plcp_valid_up_to_lambda", lambda.into());
            if let Some(c) = &analysis.time_stepping {
                doc.insert("time_stepping", c.to_json(analysis));
            }
        }
        // written as it is serialised, one entry at a time, not built
        // as one document
        let mut w = std::io::BufWriter::new(std::io::stdout().lock());
        // pretty for small scenes, compact (about 40 % of the size) for large
        let _ = if analysis.scene.frame.nodes.len() <= frames::report::SMALL_SCENE {
            serde_json::to_writer_pretty(&mut w, &doc)
        } else {
            serde_json::to_writer(&mut w, &doc)
        };
        let _ = w.write_all(b"\n");
        let _ = w.flush();
    } else {
        // written line by line (the intervals' hinge sets of a large scene)
        let mut w = std::io::BufWriter::new(std::io::stdout().lock());
        let _ = analysis.write_text(&mut w);
        let _ = w.flush();
        drop(w);
        if let Some((lambda, t)) = valid {
            out(&format!(
                "\nWARNING: the PLCP response is NOT VALID beyond Lambda = {} (t = {}): a flowing hinge unloads there{}\n",
                format_number(lambda),
                format_number(t),
                if analysis.time_stepping.is_some() { "" } else { "; --timestep-after continues by time stepping" }
            ));
        }
        if let Some(c) = &analysis.time_stepping {
            out(&c.to_text(analysis));
        }
    }
    Ok(())
}

fn run(cli: Cli) -> Result<(), FramesError> {
    let progress = plcp::progress::Progress::spinner("reading the scene", cli.quiet);
    match cli.command {
        Command::Run {
            scene,
            json,
            plots,
            view,
            method,
            precision,
            certify,
            lambda_max,
            t_end,
            timestep_after,
            step,
            moments,
            nodes,
            hinge_sets,
        } => {
            let scene = Scene::from_file(&scene)?;
            let options = AnalysisOptions {
                solve: SolveOptions {
                    method,
                    precision: match precision {
                        Some(FramePrecision::Float(p)) => p,
                        _ => Precision::F64,
                    },
                    lambda_max,
                },
                t_end,
                escalate: precision.is_none(),
                certify,
                exact: matches!(precision, Some(FramePrecision::Exact)),
                ..AnalysisOptions::default()
            };
            progress.message("tracing the path of system (9)");
            // a large scene without plots or time stepping: in one pass, or two
            // over the path, keeping what the report asks for (memory linear
            // in the structure; frames::stream)
            let large = scene.frame.nodes.len() > frames::report::SMALL_SCENE;
            let passes = large && plots.is_none() && !timestep_after;
            // per segment: where the trace stands (only drawn on a terminal)
            let watch_with = |what: &'static str| {
                plcp::progress::enabled(cli.quiet).then(|| {
                    let bar = progress.clone();
                    let w: frames::solve::Watch = std::rc::Rc::new(std::cell::RefCell::new(
                        move |t: &frames::solve::Tick| {
                            bar.message(&format!(
                                "{what}: Lambda = {:.6e}, {} pivots, {} breakpoints",
                                t.lambda, t.pivots, t.breakpoints
                            ))
                        },
                    ));
                    w
                })
            };
            let mut analysis = if passes {
                frames::stream::run_in_passes(
                    scene,
                    &options,
                    moments.clone(),
                    nodes.clone(),
                    watch_with("tracing system (9) (hinge reading, response)"),
                    watch_with("tracing system (9) again (response, moments)"),
                )?
            } else {
                let watch = watch_with("tracing system (9)");
                Analysis::run_watched(scene, &options, watch)?
            };
            progress.finish();
            let valid = frames::timestep::plcp_valid_until(&analysis);
            if let Some((lambda, t)) = valid {
                let _ = writeln!(
                    std::io::stderr(),
                    "WARNING: a hinge unloads at Lambda = {} (t = {}): the PLCP response is NOT VALID beyond it{}",
                    format_number(lambda),
                    format_number(t),
                    if timestep_after {
                        "; continuing from there by time stepping"
                    } else {
                        " (rerun with --timestep-after for the time-stepping response from there on)"
                    }
                );
                if timestep_after {
                    let progress = plcp::progress::Progress::spinner("time stepping", cli.quiet);
                    analysis.continue_by_time_stepping(step)?;
                    progress.finish();
                }
            }
            if let Some(dir) = plots {
                let progress = plcp::progress::Progress::spinner("writing plots", cli.quiet);
                let files = frames::plot::write_all_with(&analysis, &dir, view)?;
                progress.finish();
                if !json {
                    for f in files {
                        let _ = writeln!(std::io::stderr(), "wrote {}", f.display());
                    }
                }
            }
            let picks = Picks {
                moments,
                nodes,
                hinge_sets,
            };
            write_report(&analysis, valid, json, picks)
        }
        Command::Export { scene, lambda_max } => {
            if let Some(l) = lambda_max {
                if l.is_nan() || l <= 0.0 {
                    return Err(FramesError::Invalid {
                        what: "lambda_max".into(),
                        why: format!("must be positive, got {l}"),
                    });
                }
            }
            let scene = Scene::from_file(&scene)?;
            let system = frames::System::assemble(&scene.frame);
            out(&(serde_json::to_string(&system.plcp_json(lambda_max)).unwrap_or_default() + "\n"));
            Ok(())
        }
    }
}

/// One malloc arena for the whole process (glibc), unless the user set
/// `MALLOC_ARENA_MAX`. glibc gives each thread that allocates an arena of its
/// own: the trace thread allocates every piece of the path, the reading on
/// the main thread frees it, and memory freed in one arena is not reused by
/// the other. Measured on the 10^4-element cantilever (`--json --lambda-max
/// 12`, one run each at load 7 to 10): peak resident 957 MB with the default
/// arenas, 430 MB with `MALLOC_ARENA_MAX=1` (the same trace, CPU time 160 s
/// against 153 s). Called before any thread is started.
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn one_malloc_arena() {
    unsafe extern "C" {
        fn mallopt(param: i32, value: i32) -> i32;
    }
    const M_ARENA_MAX: i32 = -8;
    if std::env::var_os("MALLOC_ARENA_MAX").is_none() {
        // SAFETY: glibc's mallopt, with a valid parameter, before any thread
        unsafe {
            mallopt(M_ARENA_MAX, 1);
        }
    }
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn one_malloc_arena() {}

fn main() -> ExitCode {
    one_malloc_arena();
    let cli = Cli::parse();
    // a panic is a bug, reported on one line with exit code 3, never a backtrace
    static PANIC: std::sync::Mutex<String> = std::sync::Mutex::new(String::new());
    std::panic::set_hook(Box::new(|info| {
        let msg = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_default();
        let at = info
            .location()
            .map(|l| format!(" at {}:{}", l.file(), l.line()))
            .unwrap_or_default();
        if let Ok(mut p) = PANIC.lock() {
            *p = format!("{msg}{at}");
        }
    }));
    let result = match std::panic::catch_unwind(|| run(cli)) {
        Ok(r) => r,
        Err(_) => {
            let msg = PANIC.lock().map(|p| p.clone()).unwrap_or_default();
            let _ = writeln!(
                std::io::stderr(),
                "error: internal error (a bug, please report): {}",
                msg.replace('\n', " ")
            );
            return ExitCode::from(3);
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            let line = e.to_string().replace('\n', " ");
            let _ = writeln!(std::io::stderr(), "error: {line}");
            match e {
                FramesError::Io { .. } if line.contains("write") => ExitCode::from(1),
                _ => ExitCode::from(2),
            }
        }
    }
}
