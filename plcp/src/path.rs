//! The answer: a piecewise-affine path of solutions, its breakpoints, and how well it is known.

use crate::linalg::{col_slice, col_slice_mut};
use crate::scalar::Scalar;
use faer::Col;

/// A variable of the problem, as events and bases name it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Var {
    /// Complementary slack `w_i` (0-based).
    W(usize),
    /// Complementary variable `z_i` (0-based).
    Z(usize),
    /// Free variable `u_j` (mixed form, 0-based).
    U(usize),
    /// The parameter `L`.
    Lambda,
    /// The artificial variable of an equality row (Wolfe long form; never part of an answer).
    Artificial(usize),
}

impl Var {
    /// The complementary partner (`w_i` <-> `z_i`), if any.
    pub fn complement(self) -> Option<Var> {
        match self {
            Var::W(i) => Some(Var::Z(i)),
            Var::Z(i) => Some(Var::W(i)),
            _ => None,
        }
    }
}

impl core::fmt::Display for Var {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Var::W(i) => write!(f, "w{i}"),
            Var::Z(i) => write!(f, "z{i}"),
            Var::U(i) => write!(f, "u{i}"),
            Var::Lambda => write!(f, "L"),
            Var::Artificial(i) => write!(f, "a{i}"),
        }
    }
}

/// How the path ended. An outcome, not an error: read it before using the path.
///
/// ```
/// use faer::{col, mat};
/// use plcp::{Plcp, Settings, Status};
/// let m = mat![[2.0, 1.0], [1.0, 2.0]];
/// let problem = Plcp::new(m.as_ref(), col![1.0, 1.0].as_ref(), col![-1.0, -0.5].as_ref())
///     .unwrap()
///     .with_range(0.0, Some(0.5))
///     .unwrap();
/// let path = plcp::solve(&problem, &Settings::default()).unwrap();
/// // lambda_max = 0.5 is reached before the first breakpoint (L = 1)
/// assert_eq!(path.status, Status::Reached);
/// assert!(path.status.is_success());
/// assert_eq!(path.status.as_str(), "reached");
/// assert_eq!(path.lambda_reached, 0.5);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// The path reached `lambda_max` (or, for a plain LCP, the LCP was solved).
    Reached,
    /// The last segment holds for every larger `L`: success when `lambda_max` is infinite.
    UnboundedRay,
    /// No solution on this path beyond `lambda_reached`: the method ended on a
    /// secondary ray (`Path::ray` holds its direction), or (mixed form) an
    /// equality row blocks every move of `L` there, in which case there is no
    /// direction to show, `Path::ray` is `None` and `Path::message` says that the
    /// path cannot be continued.
    SecondaryRay,
    /// The pivot limit was hit at `lambda_reached`.
    PivotLimit,
    /// The basis became too ill-conditioned for the working precision at
    /// `lambda_reached`; `Path::message` holds the evidence. Try a higher precision.
    IllConditioned,
    /// No solution was found at the start value `lambda0` (the start phase ended
    /// on a secondary ray; for copositive-plus `M` this proves infeasibility),
    /// or the equality rows are inconsistent.
    Infeasible,
    /// An [`crate::observe::Observer`] stopped the trace at `lambda_reached`
    /// (the end of the last segment it saw).
    StoppedByObserver,
}

impl Status {
    /// The name used in JSON output (`reached`, `unbounded_ray`, ...).
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Reached => "reached",
            Status::UnboundedRay => "unbounded_ray",
            Status::SecondaryRay => "secondary_ray",
            Status::PivotLimit => "pivot_limit",
            Status::IllConditioned => "ill_conditioned",
            Status::Infeasible => "infeasible",
            Status::StoppedByObserver => "stopped_by_observer",
        }
    }
    /// True when the path covers the whole requested range.
    pub fn is_success(self) -> bool {
        matches!(self, Status::Reached | Status::UnboundedRay)
    }
}

/// A change of basis on the path.
#[derive(Clone, Debug, PartialEq)]
pub struct Breakpoint<T: Scalar> {
    /// The parameter value.
    pub lambda: T,
    /// The variable that entered the basis.
    pub entering: Var,
    /// The variable that left it.
    pub leaving: Var,
    /// The step before this pivot had zero length (in the moving variable).
    pub degenerate: bool,
    /// From here on `L` decreases along the path (a turning point).
    pub turning: bool,
    /// The number of segments before this breakpoint: it lies at the end of
    /// `segments[segment - 1]` (or at the path's start when `segment == 0`), and
    /// `segments[segment]`, if any, is the next piece.
    pub segment: usize,
    /// The residuals at this breakpoint: of the basic solution as the trace
    /// measured it (on the scaled system; power-of-two scaling keeps relative
    /// residuals), or, for Lemke on a Schur reduction, of the path's point on the
    /// original problem. [`crate::residual::measure_path`] re-measures a whole
    /// path on the original problem.
    pub residual: Residual,
}

/// One piece of the path: every variable is affine in `L` on it.
///
/// Values are stored as the value at `lambda_from` plus a slope, which keeps
/// them accurate far from `L = 0`; [`Segment::z0`] etc. give the base at `L = 0`.
///
/// ```
/// use faer::{col, mat};
/// use plcp::{Plcp, Settings, Var};
/// let m = mat![[2.0, 1.0], [1.0, 2.0]];
/// let problem =
///     Plcp::new(m.as_ref(), col![1.0, 1.0].as_ref(), col![-1.0, -0.5].as_ref()).unwrap();
/// let path = plcp::solve(&problem, &Settings::default()).unwrap();
/// // after L = 1, z0 is basic: z0 = (L - 1) / 2 and w1 = 1/2 for every larger L
/// let seg = &path.segments[1];
/// assert_eq!(seg.basis, vec![Var::Z(0), Var::W(1)]);
/// assert!(seg.unbounded && seg.contains(10.0));
/// assert_eq!(seg.dz[0], 0.5);
/// assert_eq!(seg.eval(3.0).z[0], 1.0);
/// assert_eq!(seg.w0()[1], 0.5);
/// ```
#[derive(Clone, Debug)]
pub struct Segment<T: Scalar> {
    /// Parameter at the start of the segment.
    pub lambda_from: T,
    /// Parameter at its end (`+inf` as `T::max_value()` is never used: see `unbounded`).
    pub lambda_to: T,
    /// True for the last segment of an unbounded ray: it holds for all `L >= lambda_from`.
    pub unbounded: bool,
    /// The complementary basis on the segment: for each pair, `W(i)` or `Z(i)`.
    pub basis: Vec<Var>,
    /// `z` at `lambda_from`.
    pub z_from: Col<T>,
    /// `dz/dL`.
    pub dz: Col<T>,
    /// `w` at `lambda_from`.
    pub w_from: Col<T>,
    /// `dw/dL`.
    pub dw: Col<T>,
    /// `u` at `lambda_from` (mixed form; empty otherwise).
    pub u_from: Col<T>,
    /// `du/dL`.
    pub du: Col<T>,
}

fn affine<T: Scalar>(from: &Col<T>, slope: &Col<T>, dl: T) -> Col<T> {
    // over slices: faer's checked indexing (an assert per entry) was most
    // of an evaluation, which the end measure makes twice a path
    let (from, slope) = (col_slice(from), col_slice(slope));
    Col::from_fn(from.len(), |i| from[i] + slope[i] * dl)
}

impl<T: Scalar> Segment<T> {
    /// True if `lambda` lies in the segment's range (either order of its ends).
    pub fn contains(&self, lambda: T) -> bool {
        let (lo, hi) = if self.lambda_from <= self.lambda_to {
            (self.lambda_from, self.lambda_to)
        } else {
            (self.lambda_to, self.lambda_from)
        };
        lambda >= lo && (self.unbounded || lambda <= hi)
    }
    /// The solution on this segment at `lambda` (extrapolated if outside).
    ///
    /// Inside the segment `z` and `w` are nonnegative by construction, and a
    /// value that rounding makes negative (a basic variable that reaches zero at
    /// the segment's end, where a steep slope `dz/dL` turns the rounding of `L`
    /// into a visible error) is returned as zero: the projection can only move
    /// it closer to the exact value. Only values within that rounding (the
    /// slope times `64 eps max(1, |L|)`, plus `64 eps` of the stored value) are
    /// clamped, so a wrong path still shows, and only those beyond `sqrt(eps)`
    /// of the vector's largest entry (at least 1), which a residual check would
    /// flag; outside the segment nothing is clamped.
    pub fn eval(&self, lambda: T) -> Point<T> {
        let dl = lambda - self.lambda_from;
        let mut z = affine(&self.z_from, &self.dz, dl);
        let mut w = affine(&self.w_from, &self.dw, dl);
        if self.contains(lambda) {
            let rule = self.clamp_rule(
                lambda,
                visible_max(z.iter().copied()),
                visible_max(w.iter().copied()),
            );
            let (zf, dz) = (col_slice(&self.z_from), col_slice(&self.dz));
            let (wf, dw) = (col_slice(&self.w_from), col_slice(&self.dw));
            let (zs, ws) = (col_slice_mut(&mut z), col_slice_mut(&mut w));
            for i in 0..zs.len() {
                zs[i] = rule.z(zs[i], zf[i], dz[i]);
                ws[i] = rule.w(ws[i], wf[i], dw[i]);
            }
        }
        Point {
            lambda,
            z,
            w,
            u: affine(&self.u_from, &self.du, dl),
        }
    }

    /// [`Segment::eval`] into `pt` (its `z` and `w` reused where they have
    /// the segment's length): the same operations, so the same bits,
    /// without allocating (the end measure evaluates two points a path).
    pub(crate) fn eval_into(&self, lambda: T, pt: &mut Point<T>) {
        let dl = lambda - self.lambda_from;
        let n = self.z_from.nrows();
        if pt.z.nrows() != n {
            pt.z = Col::zeros(n);
        }
        if pt.w.nrows() != self.w_from.nrows() {
            pt.w = Col::zeros(self.w_from.nrows());
        }
        let (zf, dz) = (col_slice(&self.z_from), col_slice(&self.dz));
        let (wf, dw) = (col_slice(&self.w_from), col_slice(&self.dw));
        {
            let (zs, ws) = (col_slice_mut(&mut pt.z), col_slice_mut(&mut pt.w));
            for ((z, &f), &s) in zs.iter_mut().zip(zf).zip(dz) {
                *z = f + s * dl;
            }
            for ((w, &f), &s) in ws.iter_mut().zip(wf).zip(dw) {
                *w = f + s * dl;
            }
        }
        if self.contains(lambda) {
            let rule = self.clamp_rule(
                lambda,
                visible_max(pt.z.iter().copied()),
                visible_max(pt.w.iter().copied()),
            );
            let (zs, ws) = (col_slice_mut(&mut pt.z), col_slice_mut(&mut pt.w));
            for i in 0..zs.len() {
                zs[i] = rule.z(zs[i], zf[i], dz[i]);
                ws[i] = rule.w(ws[i], wf[i], dw[i]);
            }
        }
        pt.lambda = lambda;
        pt.u = affine(&self.u_from, &self.du, dl);
    }

    /// The clamp of [`Segment::eval`] at `lambda` (inside the segment), given
    /// the unclamped vectors' [`visible_max`]: one rule shared with the
    /// allocation-free sign measure of [`crate::residual::segment_ends`].
    pub(crate) fn clamp_rule(&self, lambda: T, z_max: T, w_max: T) -> ClampRule<T> {
        // what rounding can do: the slope times the uncertainty of `L`
        // (64 eps relative), plus 64 eps of the stored value
        let e64 = T::from_f64(64.0) * T::eps();
        let dl_err = e64
            * T::one()
                .max(lambda.abs())
                .max(self.lambda_from.abs())
                .max(self.lambda_to.abs());
        // only violations the residual check would see (beyond sqrt(eps) of
        // the vector's scale, as in `residual::residual`): smaller ones cost
        // less than the equation error a clamp would bring
        ClampRule {
            e64,
            dl_err,
            vz: T::eps().sqrt() * z_max,
            vw: T::eps().sqrt() * w_max,
        }
    }
    /// Base of `z` at `L = 0`: `z(L) = z0 + L dz`.
    pub fn z0(&self) -> Col<T> {
        affine(&self.z_from, &self.dz, -self.lambda_from)
    }
    /// Base of `w` at `L = 0`.
    pub fn w0(&self) -> Col<T> {
        affine(&self.w_from, &self.dw, -self.lambda_from)
    }
    /// Base of `u` at `L = 0`.
    pub fn u0(&self) -> Col<T> {
        affine(&self.u_from, &self.du, -self.lambda_from)
    }
}

/// `max(1, max_i |v_i|)`, folded in index order (the scale below which
/// [`Segment::eval`] leaves a negative value alone).
pub(crate) fn visible_max<T: Scalar>(v: impl Iterator<Item = T>) -> T {
    v.fold(T::one(), |m, x| m.max(x.abs()))
}

/// What [`Segment::eval`] sets to zero at one parameter value: a negative
/// value beyond `sqrt(eps)` of its vector's scale (`vz`, `vw`) and within
/// what rounding can do (`|slope| dl_err + e64 |from|`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct ClampRule<T: Scalar> {
    e64: T,
    dl_err: T,
    vz: T,
    vw: T,
}

impl<T: Scalar> ClampRule<T> {
    fn clamp(&self, v: T, from: T, slope: T, visible: T) -> T {
        if -v > visible && -v <= slope.abs() * self.dl_err + self.e64 * from.abs() {
            T::zero()
        } else {
            v
        }
    }
    /// An entry of `z` (value `v`, stored `from` and slope).
    #[inline]
    pub(crate) fn z(&self, v: T, from: T, slope: T) -> T {
        self.clamp(v, from, slope, self.vz)
    }
    /// An entry of `w`.
    #[inline]
    pub(crate) fn w(&self, v: T, from: T, slope: T) -> T {
        self.clamp(v, from, slope, self.vw)
    }
}

/// The solution at one parameter value.
#[derive(Clone, Debug)]
pub struct Point<T: Scalar> {
    /// The parameter.
    pub lambda: T,
    /// Complementary variables.
    pub z: Col<T>,
    /// Slacks.
    pub w: Col<T>,
    /// Free variables (empty in standard form).
    pub u: Col<T>,
}

/// Largest residuals seen, relative to the data's scale (see [`crate::tolerance`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Residual {
    /// `max |M x + q + L d - (0, w)|` over the rows, divided by the scale of the row data.
    pub equation: f64,
    /// `max(0, -min(z, w))`, relative.
    pub feasibility: f64,
    /// `max_i |z_i w_i|`, relative.
    pub complementarity: f64,
}

impl Residual {
    /// Element-wise maximum.
    pub fn max(self, other: Residual) -> Residual {
        Residual {
            equation: self.equation.max(other.equation),
            feasibility: self.feasibility.max(other.feasibility),
            complementarity: self.complementarity.max(other.complementarity),
        }
    }
    /// The largest of the three.
    pub fn worst(&self) -> f64 {
        self.equation
            .max(self.feasibility)
            .max(self.complementarity)
    }
}

/// What the free variables of a mixed problem look like (Wolfe long form).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FreeBlockInfo {
    /// Numerical rank of the free block.
    pub rank: usize,
    /// Free variables that could not be made basic at the start (held at zero:
    /// their values are not unique, e.g. redundant member forces).
    pub nonbasic_free: Vec<usize>,
    /// Equality rows dependent on the others at the start (compatibility conditions).
    pub dependent_rows: Vec<usize>,
}

/// How the path was computed and how well it is known.
///
/// ```
/// use faer::{col, mat};
/// let m = mat![[2.0, 1.0], [1.0, 2.0]];
/// let problem =
///     plcp::Plcp::new(m.as_ref(), col![1.0, 1.0].as_ref(), col![-1.0, -0.5].as_ref()).unwrap();
/// let path = plcp::solve(&problem, &plcp::Settings::default()).unwrap();
/// let info = &path.info;
/// // no finite `L_max`: the general engine (with one, the principal-pivoting
/// // fast path, `Settings::principal`, answers: "lemke (principal)")
/// assert_eq!((info.method, info.precision), ("lemke", "f64"));
/// assert_eq!(info.pivots, 1); // z0 replaces w0 at L = 1
/// assert!(info.residual.worst() < 1e-14);
/// assert!(info.escalation.is_none() && info.certificate.is_none());
/// ```
#[derive(Clone, Debug, Default)]
pub struct Info {
    /// Which method ran.
    pub method: &'static str,
    /// Precision name (`f32`, `f64`, `f128`).
    pub precision: &'static str,
    /// Pivots in all phases.
    pub pivots: usize,
    /// Pivots of the start phase (Lemke with an artificial variable at `lambda0`).
    pub start_pivots: usize,
    /// Pivots after a zero-length step.
    pub degenerate_pivots: usize,
    /// Basis refactorisations.
    pub refactorisations: usize,
    /// Iterative-refinement steps (basic values at breakpoints whose residual
    /// exceeded `Settings::refine_tol_eps`, entering columns while the basis
    /// condition estimate exceeded `Settings::refine_cond_eps`).
    pub refinements: usize,
    /// Points where `L` started to decrease along the path.
    pub turning_points: usize,
    /// Largest residuals at any breakpoint (and at the end).
    pub residual: Residual,
    /// Largest estimated condition number of a basis (1-norm, columns scaled to
    /// 1-norm about one; at refactorisations).
    pub max_condition: f64,
    /// The free block (mixed form).
    pub free_block: FreeBlockInfo,
    /// Why the principal-pivoting fast path ([`crate::Settings::principal`])
    /// did not answer this path, in words (`"not tried: ..."` where the
    /// problem or the settings are outside its scope, `"declined: ..."` where
    /// it started and handed the problem to the general engine); empty where
    /// it answered (`method` is `lemke (principal)`), and for the steps of
    /// [`crate::Solver`].
    pub fast_path: &'static str,
    /// The trace started from [`crate::Settings::warm_basis`] (no start phase).
    pub warm_start: bool,
    /// Why a warm basis that was given was not used (singular, or infeasible at
    /// `lambda0`); empty otherwise.
    pub warm_start_note: String,
    /// Wall-clock seconds of the solve alone (both precisions after a
    /// continuation in `fx128`).
    pub solve_seconds: f64,
    /// Set when the path was continued in `fx128` ([`crate::Settings::escalate`]):
    /// from which `L`, why, and the pivots and time in each precision. The counts
    /// above then add both runs.
    pub escalation: Option<Escalation>,
    /// The exact certificate of the path, when it came from
    /// [`crate::solve_certified`].
    pub certificate: Option<crate::exact::Certificate>,
    /// Bytes held by the returned path (segments, breakpoints, end, ray, and
    /// a [`crate::observe::CompactPath`] when one was kept): the memory model
    /// is in [`crate::observe`].
    pub path_bytes: usize,
    /// Near events of the minimum-ratio test read again with values and
    /// column entries refined with wide residuals ([`crate::NearTies::Refine`];
    /// issue 14, `docs/limits.md`) and put in their exact order: rows within
    /// the tie tolerance whose ratios differ, and rows whose column entry is
    /// below the pivot tolerance but, refined, blocks first.
    pub near_ties_resolved: usize,
    /// Near events the refined values could not order within their error
    /// bounds (the trace stopped `ill_conditioned` at the first).
    pub near_ties_unresolved: usize,
}

/// A secondary or unbounded ray: the last point plus `t` times a direction, `t >= 0`.
#[derive(Clone, Debug)]
pub struct Ray<T: Scalar> {
    /// The point where the ray starts.
    pub start: Point<T>,
    /// Direction in `z`.
    pub dz: Col<T>,
    /// Direction in `w`.
    pub dw: Col<T>,
    /// Direction in `u`.
    pub du: Col<T>,
    /// Direction in `L`.
    pub dlambda: T,
}

/// The solution path of a PLCP.
///
/// A path is read through its [`Status`] first, then its breakpoints (where the
/// basis changes), its segments (where every variable is affine in `L`), or
/// evaluated at any `L` it covers.
///
/// ```
/// use faer::{col, mat};
/// use plcp::{Plcp, Settings, Status, Var};
/// // w = q + L d + M z; w0 = 1 - L reaches zero at L = 1, then z0 grows
/// let m = mat![[2.0, 1.0], [1.0, 2.0]];
/// let problem =
///     Plcp::new(m.as_ref(), col![1.0, 1.0].as_ref(), col![-1.0, -0.5].as_ref()).unwrap();
/// let path = plcp::solve(&problem, &Settings::default()).unwrap();
/// assert_eq!(path.status, Status::UnboundedRay);
/// assert_eq!(path.breakpoints.len(), 1);
/// let b = &path.breakpoints[0];
/// assert_eq!((b.lambda, b.entering, b.leaving), (1.0, Var::Z(0), Var::W(0)));
/// assert_eq!(path.segments.len(), 2);
/// assert_eq!(path.segment_at(0.5), Some(0));
/// let at = path.at(5.0).unwrap();
/// assert!((at.z[0] - 2.0_f64).abs() < 1e-12 && (at.w[1] - 0.5_f64).abs() < 1e-12);
/// ```
#[derive(Clone, Debug)]
pub struct Path<T: Scalar> {
    /// How the path ended.
    pub status: Status,
    /// Start value of the parameter.
    pub lambda0: T,
    /// Requested end (`None`: infinity).
    pub lambda_max: Option<T>,
    /// The parameter value the path reached.
    pub lambda_reached: T,
    /// Breakpoints in path order.
    pub breakpoints: Vec<Breakpoint<T>>,
    /// Segments in path order (zero-length steps are breakpoints, not segments).
    pub segments: Vec<Segment<T>>,
    /// The solution where the path ended.
    pub end: Point<T>,
    /// The ray the path ended on, for `SecondaryRay` and `UnboundedRay`.
    pub ray: Option<Ray<T>>,
    /// Diagnostics and the evidence behind a status other than success.
    pub message: String,
    /// Counts, residuals, timing.
    pub info: Info,
    /// For `Reached`: the basis of the end point as a vertex at `L = lambda_reached`
    /// (one variable per row position, `L` not among them), to warm-start
    /// another problem with the same `M` ([`crate::Settings::warm_basis`]).
    /// For Lemke on a Schur reduction it holds the reduced problem's basis
    /// (`z` and `w` only). `None` for every other status.
    pub final_basis: Option<Vec<Var>>,
}

impl<T: Scalar> Path<T> {
    /// The solution at `lambda`, from the first segment (in path order) whose range
    /// holds it. `None` outside the traced range. On a path with turning points
    /// (possible only for non-monotone problems) several solutions may exist.
    pub fn at(&self, lambda: T) -> Option<Point<T>> {
        if let Some(seg) = self.segments.iter().find(|s| s.contains(lambda)) {
            return Some(seg.eval(lambda));
        }
        if self.segments.is_empty() && lambda == self.end.lambda {
            return Some(self.end.clone());
        }
        None
    }
    /// The segment index holding `lambda`, if any.
    pub fn segment_at(&self, lambda: T) -> Option<usize> {
        self.segments.iter().position(|s| s.contains(lambda))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One pair, `z` basic and falling steeply to zero at `lambda_to`.
    fn steep(z_from: f32, dz: f32, lambda_from: f32, lambda_to: f32) -> Segment<f32> {
        Segment {
            lambda_from,
            lambda_to,
            unbounded: false,
            basis: vec![Var::Z(0)],
            z_from: Col::from_fn(1, |_| z_from),
            dz: Col::from_fn(1, |_| dz),
            w_from: Col::zeros(1),
            dw: Col::zeros(1),
            u_from: Col::zeros(0),
            du: Col::zeros(0),
        }
    }

    #[test]
    fn rounding_of_a_steep_end_is_clamped() {
        // z = 3e6 - 1.2e7 L reaches zero at L = 0.25; a start value one ulp low
        // (3e6 - 0.25, as a rounded solve gives) ends at -0.25, well within the
        // slope times the rounding of L (1.2e7 * 64 eps = 92)
        let s = steep(3e6 - 0.25, -1.2e7, 0.0, 0.25);
        let raw = s.z_from[0] + s.dz[0] * (s.lambda_to - s.lambda_from);
        assert_eq!(raw, -0.25);
        assert_eq!(s.eval(s.lambda_to).z[0], 0.0);
        // outside the segment: extrapolated, not clamped
        assert!(s.eval(0.5).z[0] < 0.0);
    }

    #[test]
    fn a_wrong_value_beyond_rounding_still_shows() {
        // a path error of 1 in a value of scale 1: not what rounding of L can do
        let s = steep(1.0, -1.0, 0.0, 2.0);
        assert_eq!(s.eval(2.0).z[0], -1.0);
    }
}

/// What a continuation in `fx128` did ([`crate::Info::escalation`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Escalation {
    /// The precision the path started in (`f32`, `f64`).
    pub from: &'static str,
    /// The start of the segment from which the path was traced in `fx128`
    /// (traced from inside it, on its basis; `lambda0` for a whole re-solve).
    pub lambda: f64,
    /// Why: the status and message of the path in the working precision.
    pub reason: String,
    /// The `fx128` run was warm-started from the basis of the path's segment
    /// at `lambda`; `false`: the whole path was re-solved in `fx128` from
    /// `lambda0`, and `note` says why.
    pub warm: bool,
    /// Why no warm start (empty when `warm`).
    pub note: String,
    /// Segments of the working-precision path kept (before `lambda`).
    pub kept_segments: usize,
    /// Pivots and seconds in the working precision (the abandoned run, all of it).
    pub pivots_before: usize,
    /// Seconds of the working-precision run.
    pub seconds_before: f64,
    /// Pivots of the `fx128` run.
    pub pivots_fx128: usize,
    /// Seconds of the `fx128` run (conversion and splicing included).
    pub seconds_fx128: f64,
    /// The last part was traced in exact arithmetic
    /// ([`crate::Settings::escalate_exact`]) from `lambda_exact`.
    pub exact: bool,
    /// Where the exact part starts (the start of a kept segment, or `lambda0`).
    pub lambda_exact: f64,
    /// Why no exact continuation ran where one was asked for (empty otherwise).
    pub exact_note: String,
    /// The precision that produced each segment of the path (`f32`, `f64`,
    /// `f128`, `exact`), in the order of `Path::segments`.
    pub segment_precisions: Vec<&'static str>,
}
