//! Solving system (9) with plcp in the chosen precision, and reading the path
//! back in `f64` as pieces on which every unknown is affine in `Lambda`.

use crate::assemble::System;
use crate::error::FramesError;
use plcp::{Method, Path, Precision, Scalar, Settings, Status};

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

fn to_vec<T: Scalar>(c: &faer::Col<T>) -> Vec<f64> {
    (0..c.nrows()).map(|i| c[i].to_f64()).collect()
}

fn read<T: Scalar>(path: Path<T>) -> Solution {
    let pieces = path
        .segments
        .iter()
        .map(|s| Piece {
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
        })
        .collect();
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

/// True if [`solve`] hands `system` to plcp in sparse form (see [`SPARSE_FROM`]).
pub fn uses_sparse(system: &System, options: &SolveOptions) -> bool {
    let s = system.sizes();
    options.method == Method::Wolfe && s.free() + s.modes >= SPARSE_FROM
}

fn solve_in<T: Scalar>(
    system: &System,
    options: &SolveOptions,
    escalate: bool,
    certify: bool,
) -> Result<Solution, FramesError> {
    let mut settings = Settings::<T>::with_method(options.method);
    settings.escalate = escalate;
    let problem = if uses_sparse(system, options) {
        settings.basis = plcp::BasisKind::Sparse;
        system.plcp_sparse::<T>(options.lambda_max)?
    } else {
        system.plcp::<T>(options.lambda_max)?
    };
    let path = if certify {
        plcp::solve_certified(&problem, &settings)?
    } else {
        plcp::solve(&problem, &settings)?
    };
    Ok(read(path))
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
    solve_checked(system, options, escalate, true)
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
    solve_checked(system, options, escalate, false)
}

fn solve_checked(
    system: &System,
    options: &SolveOptions,
    escalate: bool,
    certify: bool,
) -> Result<Solution, FramesError> {
    if let Some(l) = options.lambda_max {
        if l.is_nan() || l <= 0.0 {
            return Err(FramesError::invalid(
                "lambda_max",
                format!("must be positive, got {l}"),
            ));
        }
    }
    let floats = match options.precision {
        Precision::F32 => solve_in::<f32>(system, options, escalate, certify)?,
        Precision::F64 => solve_in::<f64>(system, options, escalate, certify)?,
        Precision::F128 => solve_in::<faer::fx128>(system, options, false, certify)?,
    };
    Ok(escalate_to_exact(system, options, escalate, floats))
}

/// The largest system (unknowns `beta + s + p`) that the escalation hands to
/// exact arithmetic on its own when the floats end `ill_conditioned`: the
/// exact tracer's cost grows like `dim^2` big-integer operations a pivot on
/// integers of up to `60 dim` bits (`docs/certification.md`), a few seconds
/// at this size.
pub const EXACT_ESCALATION_MAX_DIM: usize = 64;

/// The last step of the escalation (f64, then fx128, then exact): a path
/// that still ends `ill_conditioned` after the float precisions is traced
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
