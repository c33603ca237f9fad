//! The plcp command line.
//!
//! ```text
//! plcp solve FILE.json [--method lemke|wolfe] [--precision f32|f64|f128|exact] [--lambda-max X] [--at L1,L2,...] [--certify] [--escalate] [--segments all|none] [--quiet]
//! plcp lcp FILE.dat [--precision f32|f64|f128]
//! ```
//!
//! `solve` reads a PLCP in plcp's JSON format ([`plcp::io::json`]) and prints
//! its solution path as one line of JSON ([`plcp::io::json::write_path_json`]);
//! `--lambda-max` overrides the file's (`inf` for infinity). `lcp` reads a
//! Siconos `.dat` file ([`plcp::io::siconos`]) and prints the solution of the
//! LCP ([`plcp::io::json::lcp_json`]).
//!
//! `solve --certify` checks the path in exact rational arithmetic
//! ([`plcp::solve_certified`]) and adds a `certificate` object to the JSON
//! ([`plcp::Certificate::to_json`]); a success the certificate rejects is
//! reported `ill_conditioned`. `solve --escalate` continues the path in f128,
//! then exactly, where the working precision gives up (with `--certify`:
//! where the certificate rejects a segment; [`plcp::Settings::escalate`]) and
//! adds `segment_precisions` (which precision produced each segment).
//! `solve --precision exact` traces the path in
//! exact arithmetic ([`plcp::exact::trace`], the data read as `f64`, order at
//! most [`plcp::exact::EXACT_MAX_DIM`]); its JSON adds `exact_breakpoints`
//! (short fractions such as `"13/3"`, else decimals).
//!
//! On a terminal, `solve` draws a progress line per breakpoint on stderr
//! (through the path observer, [`plcp::solve_observed`]); `--quiet` or a
//! redirected stderr draws nothing.
//!
//! Exit codes: 0 when a report was printed (read its `status`), 2 for bad
//! input of any kind (command line, file, data), 3 for an internal error (a
//! panic). On a non-zero exit, stderr holds exactly one line naming the problem
//! and stdout is empty.

use clap::{ColorChoice, Parser, Subcommand};
use plcp::io::json::{lambda_max_from_f64, lcp_json, parse_plcp, write_path_json, PathJsonOptions};
use plcp::io::siconos::read_lcp;
use plcp::{Method, PlcpError, Precision, Scalar, Settings};
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Mutex;
use std::time::Instant;

#[derive(Parser)]
#[command(
    name = "plcp",
    version,
    color = ColorChoice::Never,
    about = "Parametric linear complementarity problems: the solution path of w = q + L d + M z"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Trace the solution path of a PLCP given in plcp's JSON format.
    Solve {
        /// The problem file: {"M": [[...], ...], "q": [...], "d": [...], "lambda_max": X or null, "free": p}.
        file: PathBuf,
        /// The algorithm: lemke or wolfe.
        #[arg(long, default_value = "lemke")]
        method: Method,
        /// The working precision: f32, f64, f128 (double-double) or exact (big rationals).
        #[arg(long, default_value = "f64", value_parser = parse_solve_precision)]
        precision: SolvePrecision,
        /// Certify the path in exact rational arithmetic (adds a "certificate" object).
        #[arg(long)]
        certify: bool,
        /// Continue in f128, then exactly, where the working precision gives
        /// up (with --certify: where the certificate rejects a segment).
        #[arg(long)]
        escalate: bool,
        /// End of the parameter range, overriding the file's (a number, or inf).
        #[arg(long, value_parser = parse_lambda_max, allow_hyphen_values = true)]
        lambda_max: Option<f64>,
        /// Parameter values at which to report the solution, comma-separated.
        #[arg(long, value_delimiter = ',', value_parser = parse_at, allow_hyphen_values = true)]
        at: Vec<f64>,
        /// Threads for the large products (default: by size; 1 keeps one thread).
        #[arg(long, value_parser = parse_threads)]
        threads: Option<usize>,
        /// No progress line on stderr (it is drawn only when stderr is a terminal).
        #[arg(long, short)]
        quiet: bool,
        /// Write the segments (all) or an empty "segments" array (none: the
        /// breakpoints, end and --at values only; a smaller, faster report).
        #[arg(long, default_value = "all", value_parser = ["all", "none"])]
        segments: String,
    },
    /// The MPC user's loop: one M, targets g_0..g_K; the LCP at g_0, then the
    /// path from g_(k-1) to g_k (L = 0..1) for each k, started where the last ended.
    Sequence {
        /// The file: {"M": [[...], ...], "targets": [[g_0], ..., [g_K]]}.
        file: PathBuf,
        /// Threads for the large products (default: by size; 1 keeps one thread).
        #[arg(long, value_parser = parse_threads)]
        threads: Option<usize>,
    },
    /// Solve a plain LCP given in the Siconos .dat format (dense or sparse-block).
    Lcp {
        /// The .dat file.
        file: PathBuf,
        /// The working precision: f32, f64 or f128 (double-double).
        #[arg(long, default_value = "f64")]
        precision: Precision,
    },
}

/// `solve`'s precisions: the float ones, or exact rationals.
#[derive(Clone, Copy)]
enum SolvePrecision {
    Float(Precision),
    Exact,
}

fn parse_solve_precision(s: &str) -> Result<SolvePrecision, String> {
    if s == "exact" {
        return Ok(SolvePrecision::Exact);
    }
    s.parse::<Precision>()
        .map(SolvePrecision::Float)
        .map_err(|_| format!("unknown precision '{s}': expected f32, f64, f128 or exact"))
}

fn parse_lambda_max(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if !v.is_nan() && v != f64::NEG_INFINITY => Ok(v),
        _ => Err(format!("'{s}' is not a number or inf")),
    }
}

fn parse_threads(s: &str) -> Result<usize, String> {
    match s.trim().parse::<usize>() {
        Ok(k) if k >= 1 => Ok(k),
        _ => Err(format!("'{s}' is not a number of threads (1 or more)")),
    }
}

fn parse_at(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("'{s}' is not a finite number")),
    }
}

/// Bad input: exit code 2 and this one line.
struct InputError(String);

impl<E: std::fmt::Display> From<E> for InputError {
    fn from(e: E) -> Self {
        InputError(e.to_string())
    }
}

/// Names the file in a data error (syntax and I/O errors name it already).
fn in_file(file: &std::path::Path) -> impl Fn(PlcpError) -> InputError + '_ {
    move |e| match e {
        PlcpError::Parse { .. } | PlcpError::Io { .. } => InputError(e.to_string()),
        other => InputError(format!("{}: {other}", file.display())),
    }
}

/// The options of `plcp solve`.
struct SolveOptions {
    method: Method,
    lambda_max: Option<f64>,
    at: Vec<f64>,
    certify: bool,
    /// `Settings::escalate` and `escalate_exact` (`--escalate`).
    escalate: bool,
    exact: bool,
    threads: Option<usize>,
    quiet: bool,
    /// Write every segment (`--segments all`).
    segments: bool,
}

fn solve<T: Scalar>(file: &std::path::Path, options: &SolveOptions) -> Result<Report, InputError> {
    let SolveOptions {
        method,
        lambda_max,
        ref at,
        certify,
        escalate,
        exact,
        threads,
        quiet,
        segments,
    } = *options;
    let bytes = plcp::io::read_bytes(file).map_err(in_file(file))?;
    if plcp::io::sparse_json::is_sparse_json(&bytes) && !exact && !certify && !escalate {
        return solve_sparse::<T>(&bytes, file, method, lambda_max, at);
    }
    let mut problem =
        parse_plcp::<T>(&bytes, &file.display().to_string()).map_err(in_file(file))?;
    drop(bytes);
    if lambda_max.is_some() {
        let lm = lambda_max_from_f64::<T>(lambda_max)?;
        let lambda0 = problem.lambda0();
        problem = problem.with_range(lambda0, lm)?;
    }
    let settings = Settings::<T> {
        threads,
        escalate,
        escalate_exact: escalate,
        ..Settings::with_method(method)
    };
    let start = Instant::now();
    if exact {
        let problem: plcp::Plcp<f64> = problem.cast();
        let traced = plcp::exact::trace(&problem, &Settings::with_method(method))?;
        let cert = certify.then(|| traced.path.certify(&problem));
        let seconds = start.elapsed().as_secs_f64();
        let bps: Vec<String> = traced.breakpoints.iter().map(plcp::exact::short).collect();
        let mut extra = serde_json::Map::new();
        extra.insert("exact_breakpoints".into(), bps.into());
        if let Some(c) = cert {
            extra.insert("certificate".into(), c.to_json());
        }
        return Ok(Report::path(
            problem,
            traced.path,
            at,
            seconds,
            segments,
            extra,
        ));
    }
    // on a terminal, a line per breakpoint (L, pivots, residual) through the
    // path observer: the same path, bit for bit (plcp/tests/observe.rs)
    let bar = plcp::progress::Progress::spinner("tracing", quiet);
    let path = if certify {
        bar.message("tracing, then certifying in exact arithmetic");
        plcp::solve_certified(&problem, &settings)?
    } else if plcp::progress::enabled(quiet) {
        let line = bar.clone();
        let observer = move |_: &plcp::Segment<T>, p: &plcp::Progress<'_, T>| {
            if let Some(b) = p.breakpoint {
                line.message(&format!(
                    "L = {:.6e}, {} breakpoints, {} pivots, residual {:.1e}",
                    b.lambda.to_f64(),
                    p.breakpoints,
                    p.pivots,
                    b.residual.worst()
                ));
            }
            plcp::Control::Continue
        };
        plcp::solve_observed(&problem, &settings, observer, plcp::Keep::All)?.path
    } else {
        plcp::solve(&problem, &settings)?
    };
    bar.finish();
    let seconds = start.elapsed().as_secs_f64();
    let mut extra = serde_json::Map::new();
    if let Some(c) = &path.info.certificate {
        extra.insert("certificate".into(), c.to_json());
    }
    if let Some(e) = &path.info.escalation {
        extra.insert(
            "segment_precisions".into(),
            e.segment_precisions.clone().into(),
        );
    }
    Ok(Report::path(problem, path, at, seconds, segments, extra))
}

/// Writes a report to the output.
type WriteReport = Box<dyn FnOnce(&mut dyn Write) -> std::io::Result<()>>;

/// What a command prints: a JSON text, or a path report written straight to
/// the output as it is serialised (at n = 2000 it is about 100 MB).
enum Report {
    Text(String),
    Path(WriteReport),
}

impl Report {
    fn path<T: Scalar>(
        problem: plcp::Plcp<T>,
        path: plcp::Path<T>,
        at: &[f64],
        seconds: f64,
        segments: bool,
        extra: serde_json::Map<String, serde_json::Value>,
    ) -> Self {
        let at = at.to_vec();
        Report::Path(Box::new(move |out: &mut dyn Write| {
            let options = PathJsonOptions {
                at: &at,
                solve_seconds: seconds,
                with_segments: segments,
                extra: Some(&extra),
            };
            write_path_json(out, &problem, &path, &options)
        }))
    }

    fn write(self, out: &mut dyn Write) -> std::io::Result<()> {
        match self {
            Report::Text(json) => out.write_all(json.as_bytes()),
            Report::Path(write) => write(out),
        }
    }
}

/// The sparse input (`plcp::io::sparse_json`): the sparse LU basis, the file's
/// warm basis, and segments kept only when `--at` asks for values (the output
/// then has breakpoints and the end: memory linear in `nnz(M) + n + pivots`).
fn solve_sparse<T: Scalar>(
    bytes: &[u8],
    file: &std::path::Path,
    method: Method,
    lambda_max: Option<f64>,
    at: &[f64],
) -> Result<Report, InputError> {
    let (mut problem, warm) =
        plcp::io::sparse_json::parse_sparse::<T>(bytes, &file.display().to_string())
            .map_err(in_file(file))?;
    if lambda_max.is_some() {
        let lm = lambda_max_from_f64::<T>(lambda_max)?;
        let lambda0 = problem.lambda0();
        problem = problem.with_range(lambda0, lm)?;
    }
    let mut settings = Settings::<T>::with_method(method);
    settings.basis = plcp::BasisKind::Sparse;
    settings.warm_basis = warm;
    let keep = if at.is_empty() {
        plcp::Keep::Nothing
    } else {
        plcp::Keep::All
    };
    let start = Instant::now();
    let run = plcp::solve_observed(
        &problem,
        &settings,
        |_: &plcp::Segment<T>, _: &plcp::Progress<'_, T>| plcp::Control::Continue,
        keep,
    )?;
    let seconds = start.elapsed().as_secs_f64();
    // the trace keeps no segment unless --at asks for values: none written
    Ok(Report::path(
        problem,
        run.path,
        at,
        seconds,
        true,
        serde_json::Map::new(),
    ))
}

fn lcp<T: Scalar>(file: &std::path::Path) -> Result<String, InputError> {
    let problem = read_lcp::<T>(file).map_err(in_file(file))?;
    let settings = Settings::<T>::default();
    let start = Instant::now();
    let solution = plcp::solve_lcp(&problem, &settings)?;
    let seconds = start.elapsed().as_secs_f64();
    Ok(lcp_json(&problem, &solution, seconds))
}

fn run(command: Command) -> Result<Report, InputError> {
    // the process's one-time costs (CPU feature detection, first touch of
    // the engine's code: see plcp::warm_up) before the input is read, so
    // that the solve's timing is the solve's
    plcp::warm_up();
    match command {
        Command::Solve {
            file,
            method,
            precision,
            certify,
            escalate,
            lambda_max,
            at,
            threads,
            quiet,
            segments,
        } => {
            one_thread(threads);
            let options = SolveOptions {
                segments: segments == "all",
                method,
                lambda_max,
                at,
                certify,
                escalate,
                exact: matches!(precision, SolvePrecision::Exact),
                threads,
                quiet,
            };
            match precision {
                SolvePrecision::Float(Precision::F32) => solve::<f32>(&file, &options),
                SolvePrecision::Float(Precision::F64) => solve::<f64>(&file, &options),
                SolvePrecision::Float(Precision::F128) => solve::<faer::fx128>(&file, &options),
                // the data read as f64, each number then exact
                SolvePrecision::Exact => solve::<f64>(&file, &options),
            }
        }
        Command::Sequence { file, threads } => {
            one_thread(threads);
            sequence(&file, threads).map(Report::Text)
        }
        Command::Lcp { file, precision } => match precision {
            Precision::F32 => lcp::<f32>(&file),
            Precision::F64 => lcp::<f64>(&file),
            Precision::F128 => lcp::<faer::fx128>(&file),
        }
        .map(Report::Text),
    }
}

/// With one thread asked for, faer's own kernels (outside the solver's
/// settings) stay on the calling thread too.
fn one_thread(threads: Option<usize>) {
    if threads == Some(1) {
        faer::set_global_parallelism(faer::Par::Seq);
    }
}

/// `plcp sequence`: reads `{"M": [[...]], "targets": [[...], ...]}`, runs the
/// LCP at the first target and one path per later target with
/// [`plcp::Solver`], prints `{"n", "timing": {"solve_seconds"}, "steps":
/// [{"status", "pivots", "warm", "end": {"z"}}]}` (the time of all steps, no I/O).
fn sequence(file: &std::path::Path, threads: Option<usize>) -> Result<String, InputError> {
    let (m, targets) = plcp::io::json::read_sequence(file)?;
    let settings = Settings::<f64> {
        threads,
        ..Settings::default()
    };
    let n = m.nrows();
    let mut solver = plcp::Solver::new(m.as_ref(), &settings).map_err(in_file(file))?;
    // the lean steps (plcp::StepEnd, no Path): what the loop reads is kept
    // (the z of each step into one preallocated matrix)
    let mut zs = faer::Mat::<f64>::zeros(n, targets.len());
    let mut steps: Vec<(plcp::Status, usize, bool, f64)> = Vec::with_capacity(targets.len());
    let mut d = faer::Col::<f64>::zeros(n);
    let start = Instant::now();
    for (k, g) in targets.iter().enumerate() {
        let end = if k == 0 {
            solver.lcp_end(g.as_ref())
        } else {
            let prev = &targets[k - 1];
            for i in 0..n {
                d[i] = g[i] - prev[i];
            }
            solver.step_end(prev.as_ref(), d.as_ref())
        }
        .map_err(in_file(file))?;
        zs.col_mut(k).copy_from(end.end.z.as_ref());
        steps.push((end.status, end.pivots, end.warm, end.residual.worst()));
    }
    let seconds = start.elapsed().as_secs_f64();
    let steps: Vec<serde_json::Value> = steps
        .iter()
        .enumerate()
        .map(|(k, &(status, pivots, warm, residual))| {
            serde_json::json!({
                "status": status.as_str(),
                "pivots": pivots,
                "warm": warm,
                "residual": residual,
                "end": {"z": (0..n).map(|i| zs[(i, k)]).collect::<Vec<f64>>()},
            })
        })
        .collect();
    Ok(serde_json::json!({
        "n": n,
        "timing": {"solve_seconds": seconds},
        "steps": steps,
    })
    .to_string())
}

/// Joins the first paragraph of a (possibly multi-line) message into one line.
fn one_line(s: &str) -> String {
    let para: Vec<&str> = s
        .trim_start()
        .lines()
        .take_while(|l| !l.trim().is_empty())
        .map(str::trim)
        .collect();
    para.join(" ")
}

/// The message of the last panic, recorded by the hook (which prints nothing).
static PANIC: Mutex<Option<String>> = Mutex::new(None);

/// Memory the process frees stays with it for its later allocations (glibc),
/// unless the user set `MALLOC_MMAP_THRESHOLD_` or `MALLOC_TRIM_THRESHOLD_`:
/// blocks below 32 MB come from the heap and the heap's top is never handed
/// back. The input's text and its parse are freed before the solve, which
/// then reuses those pages instead of asking the kernel for new ones: the
/// first touch of a page costs 2 to 18 us on a virtualised machine (measured
/// on this one, `docs/performance.md`). `plcp solve --threads 1` on
/// bench.py's instances, pinned, five runs each alternated with the build
/// before (medians, with the fast path's lazily touched `G`): n = 200 1.70
/// against 2.39 ms, n = 500 13.6 against 18.3 ms, n = 1000 176 against
/// 195 ms; the process's page faults 1032 against 1415, 3327 against 5721,
/// 13426 against 22571. The peak memory is unchanged (freed memory is
/// kept, not added to).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn keep_freed_memory() {
    unsafe extern "C" {
        fn mallopt(param: i32, value: i32) -> i32;
    }
    const M_TRIM_THRESHOLD: i32 = -1;
    const M_MMAP_THRESHOLD: i32 = -3;
    let set = |name: &str| std::env::var_os(name).is_some();
    if set("MALLOC_MMAP_THRESHOLD_") || set("MALLOC_TRIM_THRESHOLD_") {
        return;
    }
    // SAFETY: glibc's mallopt with valid parameters (32 MB is glibc's
    // largest mmap threshold on 64-bit targets), before any thread
    unsafe {
        mallopt(M_MMAP_THRESHOLD, 32 << 20);
        mallopt(M_TRIM_THRESHOLD, i32::MAX);
    }
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn keep_freed_memory() {}

fn main() -> ExitCode {
    keep_freed_memory();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                print!("{e}");
                return ExitCode::SUCCESS;
            }
            if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
                eprintln!("error: missing command: expected 'solve FILE.json' or 'lcp FILE.dat' (see plcp --help)");
                return ExitCode::from(2);
            }
            let line = one_line(&e.to_string());
            let line = line.strip_prefix("error: ").unwrap_or(&line);
            eprintln!("error: {line}");
            return ExitCode::from(2);
        }
    };
    std::panic::set_hook(Box::new(|info| {
        let payload = info.payload();
        let msg = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "(no message)".into());
        let at = info
            .location()
            .map(|l| format!(" at {}:{}", l.file(), l.line()))
            .unwrap_or_default();
        if let Ok(mut slot) = PANIC.lock() {
            slot.get_or_insert(format!("{msg}{at}"));
        }
    }));
    let result = std::panic::catch_unwind(move || run(cli.command));
    match result {
        Ok(Ok(report)) => {
            let mut out = std::io::stdout().lock();
            // A closed pipe is not worth a panic or a second message.
            let _ = report
                .write(&mut out)
                .and_then(|_| writeln!(out))
                .and_then(|_| out.flush());
            ExitCode::SUCCESS
        }
        Ok(Err(InputError(msg))) => {
            eprintln!("error: {}", one_line(&msg.replace('\n', " ")));
            ExitCode::from(2)
        }
        Err(_) => {
            let msg = PANIC
                .lock()
                .ok()
                .and_then(|mut s| s.take())
                .unwrap_or_else(|| "(no message)".into());
            eprintln!(
                "internal error: the solver panicked: {}",
                msg.replace('\n', " ")
            );
            ExitCode::from(3)
        }
    }
}
