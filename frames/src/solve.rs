//! Solving system (9) with plcp in the chosen precision, and reading the path
//! back in `f64` as pieces on which every unknown is affine in `Lambda`.

use crate::assemble::System;
use crate::error::FramesError;
use plcp::{Control, Keep, Method, Observer, Path, Precision, Scalar, Segment, Settings, Status};
use std::cell::RefCell;
use std::rc::Rc;

/// How to solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolveOptions {
    /// [`Method::Wolfe`] (long form on the unreduced system, the default) or
    /// [`Method::Lemke`] (on the Schur reduction: statically determinate frames only).
    pub method: Method,
    /// Working precision of the solve (the report is in `f64`).
    pub precision: Precision,
    /// Largest `Lambda` (`None`: infinity).
    pub lambda_max: Option<f64>,
}

impl Default for SolveOptions {
    fn default() -> Self {
        Self {
            method: Method::Wolfe,
            precision: Precision::F64,
            lambda_max: None,
        }
    }
}

/// A piece of the path: on `[lambda_from, lambda_to]` every unknown is affine in `Lambda`.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// Start.
    pub lambda_from: f64,
    /// End (`f64::INFINITY` for the last piece of an unbounded ray).
    pub lambda_to: f64,
    /// Free variables `(q_dd, X)` at `lambda_from`.
    pub u_from: Vec<f64>,
    /// Their slopes.
    pub du: Vec<f64>,
    /// Plastic multiplier accelerations `x*_dd` at `lambda_from`.
    pub z_from: Vec<f64>,
    /// Their slopes.
    pub dz: Vec<f64>,
    /// Plastic potentials `y*` at `lambda_from`.
    pub w_from: Vec<f64>,
    /// Their slopes.
    pub dw: Vec<f64>,
}

fn affine(from: &[f64], slope: &[f64], dl: f64) -> Vec<f64> {
    from.iter().zip(slope).map(|(a, b)| a + b * dl).collect()
}

impl Piece {
    /// `(q_dd, X)` at `lambda`.
    pub fn u(&self, lambda: f64) -> Vec<f64> {
        affine(&self.u_from, &self.du, lambda - self.lambda_from)
    }
    /// `x*_dd` at `lambda`.
    pub fn z(&self, lambda: f64) -> Vec<f64> {
        affine(&self.z_from, &self.dz, lambda - self.lambda_from)
    }
    /// `y*` at `lambda`.
    pub fn w(&self, lambda: f64) -> Vec<f64> {
        affine(&self.w_from, &self.dw, lambda - self.lambda_from)
    }
    /// A value of `Lambda` inside the piece, away from its ends.
    pub fn representative(&self) -> f64 {
        if self.lambda_to.is_finite() {
            0.5 * (self.lambda_from + self.lambda_to)
        } else {
            self.lambda_from + self.lambda_from.abs().max(1.0)
        }
    }
}

/// The path of system (9), read in `f64`.
#[derive(Clone, Debug)]
pub struct Solution {
    /// How the path ended (see [`plcp::Status`]).
    pub status: Status,
    /// plcp's message (evidence behind a status other than success).
    pub message: String,
    /// The `Lambda` the path reached.
    pub lambda_reached: f64,
    /// The pieces in order of rising `Lambda`.
    pub pieces: Vec<Piece>,
    /// plcp's diagnostics (pivots, residuals, free block).
    pub info: plcp::Info,
    /// Relative tolerance for reading signs off the path in this precision.
    pub tolerance: f64,
}

/// The entries of `c` in `f64`, read over its slice (an owned column is
/// contiguous): for `f64` a plain copy that vectorises, not an indexed,
/// bounds-checked read per entry (this runs on the trace thread, once per
/// segment for six vectors of the system's size).
fn to_vec<T: Scalar>(c: &faer::Col<T>) -> Vec<f64> {
    match c.as_ref().try_as_col_major() {
        Some(s) => s.as_slice().iter().map(|x| x.to_f64()).collect(),
        None => (0..c.nrows()).map(|i| c[i].to_f64()).collect(),
    }
}

fn piece<T: Scalar>(s: &Segment<T>) -> Piece {
    Piece {
        lambda_from: s.lambda_from.to_f64(),
        lambda_to: if s.unbounded {
            f64::INFINITY
        } else {
            s.lambda_to.to_f64()
        },
        u_from: to_vec(&s.u_from),
        du: to_vec(&s.du),
        z_from: to_vec(&s.z_from),
        dz: to_vec(&s.dz),
        w_from: to_vec(&s.w_from),
        dw: to_vec(&s.dw),
    }
}

fn read<T: Scalar>(path: Path<T>) -> Solution {
    let pieces = path.segments.iter().map(piece).collect();
    solution(path, pieces)
}

fn solution<T: Scalar>(path: Path<T>, pieces: Vec<Piece>) -> Solution {
    let eps = T::eps().to_f64();
    Solution {
        status: path.status,
        message: path.message,
        lambda_reached: path.lambda_reached.to_f64(),
        pieces,
        info: path.info,
        tolerance: (eps.sqrt() * 10.0).max(1e-13),
    }
}

/// Where the trace of system (9) stands after a segment: what a progress
/// display shows ([`solve_watched`], [`crate::Analysis::run_watched`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tick {
    /// `Lambda` at the end of the segment just traced (`inf` for a ray).
    pub lambda: f64,
    /// Pivots so far (for a path certified in exact arithmetic, told after
    /// the trace: the breakpoints so far).
    pub pivots: usize,
    /// Breakpoints so far.
    pub breakpoints: usize,
}

/// A watcher of a trace, called once per segment (shared, so that a re-solve
/// in a higher precision reports to the same display).
pub type Watch = Rc<RefCell<dyn FnMut(&Tick)>>;

/// The observer of the trace: each segment read into a [`Piece`] as soon as
/// it is traced, so that plcp keeps no segment of its own (its memory is the
/// pieces', not twice that), and the watcher told.
struct Reader {
    pieces: Vec<Piece>,
    watch: Option<Watch>,
}

impl<T: Scalar> Observer<T> for Reader {
    fn on_segment(&mut self, segment: &Segment<T>, progress: &plcp::Progress<'_, T>) -> Control {
        let p = piece(segment);
        if let Some(w) = &self.watch {
            (w.borrow_mut())(&Tick {
                lambda: p.lambda_to,
                pivots: progress.pivots,
                breakpoints: progress.breakpoints,
            });
        }
        self.pieces.push(p);
        Control::Continue
    }
}

/// Traces `problem` with the pieces read as the segments come
/// ([`plcp::solve_observed`], [`Keep::Nothing`]): the same numbers as
/// [`plcp::solve`] then [`read`], bit for bit (a test checks it on every
/// scene).
fn trace_read<T: Scalar + 'static>(
    problem: &plcp::Plcp<T>,
    settings: &Settings<T>,
    watch: Option<Watch>,
) -> Result<Solution, FramesError> {
    let reader = Reader {
        pieces: Vec::new(),
        watch,
    };
    let mut run = plcp::solve_observed(problem, settings, reader, Keep::Nothing)?;
    if run.path.info.escalation.is_some() {
        // The escalation picks its restart among the segments the path holds,
        // and a streamed path holds only its first and latest: traced again
        // whole, so that the answer is the one plcp::solve gives (a stiff
        // path pays the f64 trace twice; large paths rarely escalate).
        return Ok(read(plcp::solve(problem, settings)?));
    }
    let mut pieces = std::mem::take(&mut run.observer.pieces);
    // the residual guard of plcp::solve, applied after the segments were
    // seen, turns a success into ill_conditioned and claims nothing beyond the
    // last finite point: the unbounded last segment is cut to its start
    if run.path.status == Status::IllConditioned {
        if let Some(last) = pieces.last_mut().filter(|p| p.lambda_to == f64::INFINITY) {
            last.lambda_to = last.lambda_from;
        }
    }
    Ok(solution(run.path, pieces))
}

/// Traces system (9) in `f64` as [`solve_escalating`] does (the same
/// settings, so the same pieces, bit for bit), handing each piece to `each`
/// (its index, the piece) as soon as it is traced and keeping none: the
/// solution's `pieces` is empty. `each` may stop the trace
/// ([`Control::Stop`]: status `stopped_by_observer`). For a path that ends
/// `ill_conditioned` or is continued in `fx128` (`info.escalation`), `each`
/// has seen the `f64` pieces only: the caller checks and traces again
/// whole ([`crate::stream`]).
pub(crate) fn trace_pieces(
    system: &System,
    options: &SolveOptions,
    escalate: bool,
    watch: Option<Watch>,
    mut each: impl FnMut(usize, Piece) -> Control,
) -> Result<Solution, FramesError> {
    if let Some(l) = options.lambda_max {
        if l.is_nan() || l <= 0.0 {
            return Err(FramesError::invalid(
                "lambda_max",
                format!("must be positive, got {l}"),
            ));
        }
    }
    // plcp's observer is 'static (moved into the trace): the trace runs on
    // a thread of its own and hands the pieces over a short channel to
    // `each`, which may borrow (two pieces in flight at most)
    enum Msg {
        Tick(Tick),
        Piece(Piece),
    }
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let stopped = stop.clone();
    std::thread::scope(|scope| {
        let (tx, rx) = std::sync::mpsc::sync_channel::<Msg>(1);
        let tracer = scope.spawn(move || -> Result<Solution, FramesError> {
            let mut settings = plcp_settings::<f64>(options.method);
            settings.escalate = escalate;
            let problem = if uses_sparse(system, options) {
                settings.basis = plcp::BasisKind::Sparse;
                system.plcp_sparse::<f64>(options.lambda_max)?
            } else {
                system.plcp::<f64>(options.lambda_max)?
            };
            let observer = move |segment: &Segment<f64>, progress: &plcp::Progress<'_, f64>| {
                let p = piece(segment);
                let tick = Tick {
                    lambda: p.lambda_to,
                    pivots: progress.pivots,
                    breakpoints: progress.breakpoints,
                };
                let gone = tx.send(Msg::Tick(tick)).is_err() || tx.send(Msg::Piece(p)).is_err();
                if gone || stopped.load(std::sync::atomic::Ordering::Relaxed) {
                    Control::Stop
                } else {
                    Control::Continue
                }
            };
            let run = plcp::solve_observed(&problem, &settings, observer, Keep::Nothing)?;
            Ok(solution(run.path, Vec::new()))
        });
        let mut index = 0;
        for msg in rx {
            match msg {
                Msg::Tick(t) => {
                    if let Some(w) = &watch {
                        (w.borrow_mut())(&t);
                    }
                }
                Msg::Piece(p) => {
                    if stop.load(std::sync::atomic::Ordering::Relaxed) {
                        continue;
                    }
                    if matches!(each(index, p), Control::Stop) {
                        stop.store(true, std::sync::atomic::Ordering::Relaxed);
                    }
                    index += 1;
                }
            }
        }
        match tracer.join() {
            Ok(r) => r,
            Err(panic) => std::panic::resume_unwind(panic),
        }
    })
}

/// Systems of at least this many unknowns (`beta + s + p`) go to plcp in
/// sparse form with the sparse LU basis ([`System::plcp_sparse`],
/// [`plcp::BasisKind::Sparse`]); smaller ones stay dense with the block basis.
///
/// Measured on the cantilever (Wolfe, f64, 2 cores): at 62 unknowns (10
/// elements) both take about 1 ms; at 302 (50 elements) the sparse route takes
/// 5 ms against 38 ms, at 602 (100 elements) 30 ms against 1.6 s. Below a
/// hundred unknowns the dense route is kept: it is as fast there, and the
/// small examples keep the paths their tests check against independent
/// references pivot for pivot.
pub const SPARSE_FROM: usize = 100;

/// The settings with which frames traces system (9): `method`, and every
/// tie within the tie window taken as one event ([`plcp::NearTies::Window`]):
/// the system is assembled in floating point, so hinges that reach yield
/// at once in the scene (symmetric sections) reach it a few ulps apart in
/// the assembled data, and reading those ulps as the order of events would
/// lose hinges (`tests/space.rs`). `--certify` checks the answer exactly.
pub fn plcp_settings<T: Scalar>(method: Method) -> Settings<T> {
    Settings {
        near_ties: plcp::NearTies::Window,
        ..Settings::with_method(method)
    }
}

/// True if [`solve`] hands `system` to plcp in sparse form (see [`SPARSE_FROM`]).
pub fn uses_sparse(system: &System, options: &SolveOptions) -> bool {
    let s = system.sizes();
    options.method == Method::Wolfe && s.free() + s.modes >= SPARSE_FROM
}

fn solve_in<T: Scalar + 'static>(
    system: &System,
    options: &SolveOptions,
    escalate: bool,
    certify: bool,
    watch: Option<Watch>,
) -> Result<Solution, FramesError> {
    let mut settings = plcp_settings::<T>(options.method);
    settings.escalate = escalate;
    let problem = if uses_sparse(system, options) {
        settings.basis = plcp::BasisKind::Sparse;
        system.plcp_sparse::<T>(options.lambda_max)?
    } else {
        system.plcp::<T>(options.lambda_max)?
    };
    if certify {
        // the certificate needs every segment: stored whole, and the watcher
        // told after the trace
        let path = plcp::solve_certified(&problem, &settings)?;
        if let Some(w) = &watch {
            for (k, seg) in path.segments.iter().enumerate() {
                let bps = path.breakpoints.iter().filter(|b| b.segment <= k).count();
                (w.borrow_mut())(&Tick {
                    lambda: if seg.unbounded {
                        f64::INFINITY
                    } else {
                        seg.lambda_to.to_f64()
                    },
                    pivots: bps,
                    breakpoints: bps,
                });
            }
        }
        Ok(read(path))
    } else {
        trace_read(&problem, &settings, watch)
    }
}

/// [`solve_escalating`], then the path certified in exact rational
/// arithmetic ([`plcp::solve_certified`]): the certificate is
/// `Solution::info.certificate`, and a success it rejects is reported
/// `ill_conditioned` with its reason.
pub fn solve_certified(
    system: &System,
    options: &SolveOptions,
    escalate: bool,
) -> Result<Solution, FramesError> {
    solve_checked(system, options, escalate, true, None)
}

/// Solves system (9) in exact rational arithmetic ([`plcp::exact::trace`],
/// the dense system read in `f64`), then certifies the exact path (which
/// gives `Solution::info.certificate` with the exact breakpoints; a failure
/// there would be a bug of the tracer). `Err` for a system above
/// [`plcp::exact::EXACT_MAX_DIM`] unknowns or with a singular free block (a
/// statically indeterminate frame whose redundants are not unique).
pub fn solve_exact(system: &System, options: &SolveOptions) -> Result<Solution, FramesError> {
    if let Some(l) = options.lambda_max {
        if l.is_nan() || l <= 0.0 {
            return Err(FramesError::invalid(
                "lambda_max",
                format!("must be positive, got {l}"),
            ));
        }
    }
    let problem = system.plcp::<f64>(options.lambda_max)?;
    let traced = plcp::exact::trace(&problem, &Settings::with_method(options.method))?;
    let mut path = traced.path;
    let cert = plcp::exact::certify(&problem, &path);
    path.info.certificate = Some(cert);
    Ok(read(path))
}

/// Solves system (9) with plcp.
///
/// Errors only for input plcp refuses, e.g. [`Method::Lemke`] on a statically
/// indeterminate frame (`PlcpError::SingularFreeBlock`); every outcome of the
/// path itself is a [`Status`] in the solution.
pub fn solve(system: &System, options: &SolveOptions) -> Result<Solution, FramesError> {
    solve_escalating(system, options, false)
}

/// [`solve`], and with `escalate` a path that ends `ill_conditioned` in `f32`
/// or `f64` is continued in `fx128` from where it failed
/// ([`plcp::Settings::escalate`]; `Solution::info.escalation` says where and why).
pub fn solve_escalating(
    system: &System,
    options: &SolveOptions,
    escalate: bool,
) -> Result<Solution, FramesError> {
    solve_checked(system, options, escalate, false, None)
}

/// [`solve_escalating`] with `watch` called after every segment of the trace
/// (for a progress display: `Lambda`, pivots and breakpoints so far).
pub fn solve_watched(
    system: &System,
    options: &SolveOptions,
    escalate: bool,
    watch: Watch,
) -> Result<Solution, FramesError> {
    solve_checked(system, options, escalate, false, Some(watch))
}

fn solve_checked(
    system: &System,
    options: &SolveOptions,
    escalate: bool,
    certify: bool,
    watch: Option<Watch>,
) -> Result<Solution, FramesError> {
    if let Some(l) = options.lambda_max {
        if l.is_nan() || l <= 0.0 {
            return Err(FramesError::invalid(
                "lambda_max",
                format!("must be positive, got {l}"),
            ));
        }
    }
    // small escalating f64 paths of stiff scenes are checked in exact
    // arithmetic even when no certificate is asked for (milliseconds at this
    // size): a rejected one ends ill_conditioned and is traced again exactly
    let sizes = system.sizes();
    let check = escalate
        && !certify
        && options.precision == Precision::F64
        && sizes.free() + sizes.modes <= EXACT_ESCALATION_MAX_DIM
        && (span(&system.mass) > STIFF_SPAN || span(&system.capacities) > STIFF_SPAN);
    let mut floats = match options.precision {
        Precision::F32 => solve_in::<f32>(system, options, escalate, certify, watch)?,
        Precision::F64 => solve_in::<f64>(system, options, escalate, certify || check, watch)?,
        Precision::F128 => solve_in::<faer::fx128>(system, options, false, certify, watch)?,
    };
    if check && floats.status != Status::IllConditioned {
        // certified (or an honest failure): reported as if not asked
        floats.info.certificate = None;
    }
    Ok(escalate_to_exact(system, options, escalate, floats))
}

/// A scene whose masses or plastic capacities span more than this ratio is
/// stiff: its small `f64` paths are certified even when not asked (see
/// [`EXACT_ESCALATION_MAX_DIM`]). The residual's floor of 1
/// (`plcp::tolerance`) does not see an error of 1e-8 on data of scale 1e-8,
/// and such data come with such spans. Ordinary scenes (spans of 1 to 100)
/// are not checked: a float path of data rounded by a rotation can split a
/// degenerate tie the exact path keeps, which the certificate rejects, and
/// exact arithmetic cannot retrace a statically indeterminate frame.
pub const STIFF_SPAN: f64 = 1e6;

/// Largest over smallest of the positive entries (1 if there are none).
fn span(v: &[f64]) -> f64 {
    let (lo, hi) = v
        .iter()
        .filter(|x| **x > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
    if hi > 0.0 {
        hi / lo
    } else {
        1.0
    }
}

/// The largest system (unknowns `beta + s + p`) that the escalation hands to
/// exact arithmetic on its own when the floats end `ill_conditioned`: the
/// exact tracer's cost grows like `dim^2` big-integer operations a pivot on
/// integers of up to `60 dim` bits (`docs/certification.md`), a few seconds
/// at this size.
pub const EXACT_ESCALATION_MAX_DIM: usize = 64;

/// The last step of the escalation (f64, then fx128, then exact). An
/// escalating `f64` path of a stiff scene ([`STIFF_SPAN`]) of at most
/// [`EXACT_ESCALATION_MAX_DIM`] unknowns is also certified in
/// exact arithmetic ([`plcp::solve_certified`]) even when no certificate is
/// asked for, so that a float path the certificate rejects (for example
/// breakpoints off by 1e-8 on data of scale 1e-8, which the residual's floor
/// of 1 does not see) is never reported as a success: it is traced exactly.
/// A path that still ends `ill_conditioned` after the float precisions is traced
/// again from `L0` in exact rational arithmetic ([`solve_exact`]) when the
/// system is small enough ([`EXACT_ESCALATION_MAX_DIM`]) and its free block
/// has full rank; the exact path (certified) replaces the float one and its
/// message says which precisions failed and why. Otherwise the float answer
/// stands, with its honest status.
fn escalate_to_exact(
    system: &System,
    options: &SolveOptions,
    escalate: bool,
    floats: Solution,
) -> Solution {
    let sizes = system.sizes();
    let dim = sizes.free() + sizes.modes;
    if !escalate || floats.status != Status::IllConditioned || dim > EXACT_ESCALATION_MAX_DIM {
        return floats;
    }
    let precisions = match &floats.info.escalation {
        Some(_) => format!("{} and fx128", floats.info.precision),
        None => floats.info.precision.to_string(),
    };
    match solve_exact(system, options) {
        Ok(mut exact) if exact.status.is_success() => {
            exact.message = format!(
                "traced in exact rational arithmetic from L0: {precisions} ended ill_conditioned at Lambda = {:.6e} ({}). {}",
                floats.lambda_reached, floats.message, exact.message
            );
            exact
        }
        Ok(_) | Err(_) => floats,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Scene;

    fn scenes() -> Vec<std::path::PathBuf> {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
        let mut files = Vec::new();
        for dir in [root.clone(), root.join("pipe-whip"), root.join("stiff")] {
            for e in std::fs::read_dir(dir).unwrap() {
                let p = e.unwrap().path();
                if p.extension().is_some_and(|x| x == "toml") {
                    files.push(p);
                }
            }
        }
        files.sort();
        files
    }

    fn bits(v: &[f64]) -> Vec<u64> {
        v.iter().map(|x| x.to_bits()).collect()
    }

    fn same(a: &Solution, b: &Solution, what: &str) {
        assert_eq!(a.status, b.status, "{what}");
        assert_eq!(
            a.lambda_reached.to_bits(),
            b.lambda_reached.to_bits(),
            "{what}"
        );
        assert_eq!(a.pieces.len(), b.pieces.len(), "{what}");
        for (k, (p, q)) in a.pieces.iter().zip(&b.pieces).enumerate() {
            let w = format!("{what}, piece {k}");
            assert_eq!(p.lambda_from.to_bits(), q.lambda_from.to_bits(), "{w}");
            assert_eq!(p.lambda_to.to_bits(), q.lambda_to.to_bits(), "{w}");
            for (x, y) in [
                (&p.u_from, &q.u_from),
                (&p.du, &q.du),
                (&p.z_from, &q.z_from),
                (&p.dz, &q.dz),
                (&p.w_from, &q.w_from),
                (&p.dw, &q.dw),
            ] {
                assert_eq!(bits(x), bits(y), "{w}");
            }
        }
    }

    fn stored<T: Scalar>(system: &System, o: &SolveOptions, escalate: bool) -> Solution {
        let mut settings = plcp_settings::<T>(o.method);
        settings.escalate = escalate;
        let problem = if uses_sparse(system, o) {
            settings.basis = plcp::BasisKind::Sparse;
            system.plcp_sparse::<T>(o.lambda_max).unwrap()
        } else {
            system.plcp::<T>(o.lambda_max).unwrap()
        };
        read(plcp::solve(&problem, &settings).unwrap())
    }

    fn streamed<T: Scalar + 'static>(
        system: &System,
        o: &SolveOptions,
        escalate: bool,
    ) -> Option<Solution> {
        let mut settings = plcp_settings::<T>(o.method);
        settings.escalate = escalate;
        let problem = if uses_sparse(system, o) {
            settings.basis = plcp::BasisKind::Sparse;
            system.plcp_sparse::<T>(o.lambda_max).unwrap()
        } else {
            system.plcp::<T>(o.lambda_max).unwrap()
        };
        trace_read(&problem, &settings, None).ok()
    }

    /// Reading the path as it is traced (the observer) gives the pieces that
    /// reading the stored path gives, bit for bit, on every scene, in f32
    /// (paths the residual guard fails), f64 with the escalation (paths
    /// continued in fx128) and Lemke where the frame allows it.
    #[test]
    fn streamed_pieces_equal_stored_pieces_on_every_scene() {
        let files = scenes();
        assert!(files.len() >= 20, "{files:?}");
        let mut escalated = 0;
        for f in files {
            let scene = Scene::from_file(&f).unwrap();
            let system = System::assemble(&scene.frame);
            let name = f.display().to_string();
            for (method, precision, escalate) in [
                (Method::Wolfe, Precision::F64, true),
                (Method::Wolfe, Precision::F32, false),
                (Method::Lemke, Precision::F64, false),
            ] {
                let o = SolveOptions {
                    method,
                    precision,
                    lambda_max: None,
                };
                let what = format!("{name} {method:?} {precision:?}");
                let streamed = match precision {
                    Precision::F32 => streamed::<f32>(&system, &o, escalate),
                    _ => streamed::<f64>(&system, &o, escalate),
                };
                let Some(streamed) = streamed else {
                    continue; // Lemke on an indeterminate frame
                };
                let reference = match precision {
                    Precision::F32 => stored::<f32>(&system, &o, escalate),
                    _ => stored::<f64>(&system, &o, escalate),
                };
                escalated += streamed.info.escalation.is_some() as usize;
                same(&streamed, &reference, &what);
            }
        }
        assert!(escalated > 0, "no scene exercised the escalation");
    }
}
