//! The stiff and extreme suite shared by `examples/stiff_report.rs` (all cases)
//! and `tests/stiff.rs` (the fast ones). Not an example itself.
//!
//! Every case runs in f32, f64 and fx128. For each run: the status, the error
//! of the breakpoints (or, for a plain LCP, of `z`) against the exact answer
//! where one is known, else against the fx128 run, the largest residual, and
//! whether the solver flagged trouble (status other than `reached` /
//! `unbounded_ray`, or an error).
//!
//! The residual is measured here, not taken from the solver: every computed
//! point (segment ends and midpoints, a point on an unbounded last segment)
//! is lifted to fx128 and put into the *original* f64 data, relative as in
//! `plcp::residual::residual`; it is combined (max) with `path.info.residual`.
//!
//! Breakpoint error: the symmetric (Hausdorff) distance between the sets of
//! breakpoint values of the two paths, relative to `max(1, largest |L|)`,
//! over the range both paths reached. Order-insensitive, so exact ties may come
//! out in either order, and near-ties merged by a low precision cost only
//! their gap.
//!
//! A run is WRONG when it reports success and its error or residual exceeds
//! the precision's allowance ([`allowance`]).
#![allow(dead_code)]
// index loops read like the formulas they build
#![allow(clippy::needless_range_loop)]

use faer::{Col, Mat};
use plcp::{Lcp, Method, Plcp, Point, Scalar, Settings, Status};

type F128 = faer::fx128;

/// What a precision may be off by and still call its answer a success.
///
/// * f64: `1e-8` relative, about `sqrt(eps)`: half the digits survive a
///   basis of condition up to `1e8`, which is what users of a double-precision
///   collapse load reasonably rely on;
/// * f32: `1e-2`: `sqrt(eps_f32)` is `3e-4`, but the data themselves are
///   rounded to f32 (`6e-8` relative), and the stiff cases amplify that by
///   their condition (`1e4`..`1e5` for masses over 16 orders); two digits
///   is the honest promise;
/// * fx128: `1e-16`: about `sqrt(eps_fx128)`, the library's own guard on
///   success claims; a nearly singular free block (condition `1e15`) on the
///   Schur reduction legitimately loses fifteen of the 32 digits, so a
///   tighter promise would flag conditioning, not failure.
pub fn allowance(precision: &str) -> f64 {
    match precision {
        "f32" => 1e-2,
        "f64" => 1e-8,
        _ => 1e-16,
    }
}

/// A problem of the suite, in f64 data.
#[derive(Clone, Debug)]
pub enum Problem {
    /// A (mixed) PLCP, with the exact breakpoints where known.
    Plcp {
        /// `M` rows.
        m: Vec<Vec<f64>>,
        /// `q`.
        q: Vec<f64>,
        /// `d`.
        d: Vec<f64>,
        /// Free variables.
        free: usize,
        /// Exact breakpoint values (with multiplicity ignored).
        exact: Option<Vec<f64>>,
        /// Method.
        method: Method,
    },
    /// A plain LCP, with the exact solution where unique and known.
    Lcp {
        /// `M` rows.
        m: Vec<Vec<f64>>,
        /// `q`.
        q: Vec<f64>,
        /// Exact `z`.
        exact: Option<Vec<f64>>,
        /// A solution must not be reported (no solution exists).
        infeasible: bool,
    },
    /// A frames scene (TOML), solved as system (9) with Wolfe.
    Scene(String),
}

/// One case.
#[derive(Clone, Debug)]
pub struct Case {
    /// Name.
    pub name: String,
    /// The problem.
    pub problem: Problem,
    /// Part of the fast subset (the test).
    pub fast: bool,
    /// Run in fx128 (slow cases skip it).
    pub fx128: bool,
    /// Run in f32 (the 1000-element cantilever runs in f64 only).
    pub f32: bool,
}

/// One row of the table.
#[derive(Clone, Debug)]
pub struct Row {
    /// Case name.
    pub case: String,
    /// f32, f64, f128.
    pub precision: &'static str,
    /// Status, or `error: ...`, or `n/a: ...`.
    pub status: String,
    /// Error against the exact answer or the fx128 run (`NaN`: none to compare).
    pub error: f64,
    /// What `error` is measured against: `exact`, `f128`, `-`.
    pub against: &'static str,
    /// Largest residual.
    pub residual: f64,
    /// The solver flagged trouble.
    pub flagged: bool,
    /// Success reported with error or residual beyond the allowance.
    pub wrong: bool,
    /// Breakpoints found.
    pub breakpoints: usize,
    /// Seconds.
    pub seconds: f64,
}

fn mat_of<T: Scalar>(m: &[Vec<f64>]) -> Mat<T> {
    Mat::from_fn(m.len(), m.len(), |i, j| T::from_f64(m[i][j]))
}

fn col_of<T: Scalar>(v: &[f64]) -> Col<T> {
    Col::from_fn(v.len(), |i| T::from_f64(v[i]))
}

fn representable<T: Scalar>(vals: impl Iterator<Item = f64>) -> Result<(), String> {
    for v in vals {
        let t = T::from_f64(v);
        if !t.is_finite() || (v != 0.0 && t.to_f64() == 0.0) {
            return Err(format!("n/a: {v:e} not representable in {}", T::NAME));
        }
    }
    Ok(())
}

fn lift<T: Scalar>(c: &Col<T>) -> Col<F128> {
    Col::from_fn(c.nrows(), |i| {
        let v = c[i];
        // exact for f32/f64; for fx128 keep both parts
        if T::NAME == "f128" {
            // SAFETY-free: fx128 to fx128 through f64 parts would lose the low
            // part; the generic path has no access, so go through to_f64 of the
            // value and of the remainder
            let hi = v.to_f64();
            let lo = (v - T::from_f64(hi)).to_f64();
            F128::from_f64(hi) + F128::from_f64(lo)
        } else {
            F128::from_f64(v.to_f64())
        }
    })
}

fn lift_point<T: Scalar>(p: &Point<T>) -> Point<F128> {
    let hi = p.lambda.to_f64();
    let lo = (p.lambda - T::from_f64(hi)).to_f64();
    Point {
        lambda: F128::from_f64(hi) + F128::from_f64(lo),
        z: lift(&p.z),
        w: lift(&p.w),
        u: lift(&p.u),
    }
}

/// Hausdorff distance between breakpoint sets, relative to `max(1, max |L|)`,
/// over values up to `upto`.
pub fn breakpoint_error(a: &[f64], b: &[f64], upto: f64) -> f64 {
    let a: Vec<f64> = a.iter().copied().filter(|&l| l <= upto).collect();
    let b: Vec<f64> = b.iter().copied().filter(|&l| l <= upto).collect();
    if a.is_empty() && b.is_empty() {
        return 0.0;
    }
    if a.is_empty() || b.is_empty() {
        return f64::INFINITY;
    }
    let scale = a
        .iter()
        .chain(b.iter())
        .fold(1.0f64, |s, &l| s.max(l.abs()));
    let d = |x: &[f64], y: &[f64]| {
        x.iter()
            .map(|&l| {
                y.iter()
                    .map(|&k| (l - k).abs())
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0f64, f64::max)
    };
    d(&a, &b).max(d(&b, &a)) / scale
}

/// What one precision's run produced, in f64 terms.
#[derive(Clone, Debug)]
struct Outcome {
    status: String,
    success: bool,
    flagged: bool,
    breakpoints: Vec<f64>,
    reached: f64,
    z: Vec<f64>,
    residual: f64,
    seconds: f64,
}

fn na(status: String) -> Outcome {
    Outcome {
        status,
        success: false,
        flagged: true,
        breakpoints: vec![],
        reached: f64::NAN,
        z: vec![],
        residual: f64::NAN,
        seconds: 0.0,
    }
}

fn run_plcp<T: Scalar>(
    ref128: &Plcp<F128>,
    m: &Mat<f64>,
    q: &Col<f64>,
    d: &Col<f64>,
    free: usize,
    method: Method,
) -> Outcome {
    let vals = (0..m.nrows())
        .flat_map(|i| (0..m.ncols()).map(move |j| (i, j)))
        .map(|(i, j)| m[(i, j)])
        .chain((0..q.nrows()).map(|i| q[i]))
        .chain((0..d.nrows()).map(|i| d[i]));
    if let Err(s) = representable::<T>(vals) {
        return na(s);
    }
    let mt = Mat::<T>::from_fn(m.nrows(), m.ncols(), |i, j| T::from_f64(m[(i, j)]));
    let qt = Col::<T>::from_fn(q.nrows(), |i| T::from_f64(q[i]));
    let dt = Col::<T>::from_fn(d.nrows(), |i| T::from_f64(d[i]));
    let pb = match Plcp::mixed(mt.as_ref(), qt.as_ref(), dt.as_ref(), free) {
        Ok(p) => p,
        Err(e) => return na(format!("error: {e}")),
    };
    let settings = Settings::<T>::with_method(method);
    let t = std::time::Instant::now();
    let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| plcp::solve(&pb, &settings)));
    let seconds = t.elapsed().as_secs_f64();
    let path = match r {
        Ok(Ok(p)) => p,
        Ok(Err(e)) => {
            let mut o = na(format!("error: {}", short(&e.to_string(), 60)));
            o.seconds = seconds;
            return o;
        }
        Err(_) => {
            let mut o = na("PANIC".into());
            o.seconds = seconds;
            return o;
        }
    };
    // residuals at segment ends and midpoints, in fx128 on the original data
    let mut res = path.info.residual.worst();
    let mut check = |pt: &Point<T>| {
        let r = plcp::residual::residual(ref128, &lift_point(pt)).worst();
        if r.is_nan() {
            res = f64::INFINITY;
        } else {
            res = res.max(r);
        }
    };
    for s in &path.segments {
        check(&s.eval(s.lambda_from));
        if s.unbounded {
            let l = s.lambda_from + (s.lambda_from.abs() + T::one());
            check(&s.eval(l));
        } else {
            check(&s.eval(s.lambda_to));
            check(&s.eval((s.lambda_from + s.lambda_to) * T::from_f64(0.5)));
        }
    }
    if path.end.lambda.is_finite() {
        check(&path.end);
    }
    let reached = if path.status == Status::UnboundedRay {
        f64::INFINITY
    } else {
        path.lambda_reached.to_f64()
    };
    Outcome {
        status: path.status.as_str().to_string(),
        success: path.status.is_success(),
        flagged: !path.status.is_success(),
        breakpoints: path.breakpoints.iter().map(|b| b.lambda.to_f64()).collect(),
        reached,
        z: vec![],
        residual: res,
        seconds,
    }
}

fn run_lcp<T: Scalar>(ref128: &Plcp<F128>, m: &Mat<f64>, q: &Col<f64>) -> Outcome {
    let vals = (0..m.nrows())
        .flat_map(|i| (0..m.ncols()).map(move |j| (i, j)))
        .map(|(i, j)| m[(i, j)])
        .chain((0..q.nrows()).map(|i| q[i]));
    if let Err(s) = representable::<T>(vals) {
        return na(s);
    }
    let mt = Mat::<T>::from_fn(m.nrows(), m.ncols(), |i, j| T::from_f64(m[(i, j)]));
    let qt = Col::<T>::from_fn(q.nrows(), |i| T::from_f64(q[i]));
    let lcp = match Lcp::new(mt.as_ref(), qt.as_ref()) {
        Ok(l) => l,
        Err(e) => return na(format!("error: {e}")),
    };
    let t = std::time::Instant::now();
    let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        plcp::solve_lcp(&lcp, &Settings::<T>::default())
    }));
    let seconds = t.elapsed().as_secs_f64();
    let sol = match r {
        Ok(Ok(s)) => s,
        Ok(Err(e)) => return na(format!("error: {}", short(&e.to_string(), 60))),
        Err(_) => return na("PANIC".into()),
    };
    let z = lift(&sol.z);
    // w recomputed in fx128 from z and the original data
    let n = q.nrows();
    let w = Col::<F128>::from_fn(n, |i| {
        let mut s = F128::from_f64(q[i]);
        for j in 0..n {
            s += F128::from_f64(m[(i, j)]) * z[j];
        }
        s
    });
    let pt = Point {
        lambda: F128::from_f64(0.0),
        z,
        w,
        u: Col::zeros(0),
    };
    let r = plcp::residual::residual(ref128, &pt).worst();
    Outcome {
        status: sol.status.as_str().to_string(),
        success: sol.status.is_success(),
        flagged: !sol.status.is_success(),
        breakpoints: vec![],
        reached: 0.0,
        z: (0..n).map(|i| sol.z[i].to_f64()).collect(),
        residual: if r.is_nan() {
            f64::INFINITY
        } else {
            r.max(sol.info.residual.worst())
        },
        seconds,
    }
}

fn short(s: &str, n: usize) -> String {
    if s.len() <= n {
        s.to_string()
    } else {
        let mut e = n;
        while !s.is_char_boundary(e) {
            e -= 1;
        }
        format!("{}...", &s[..e])
    }
}

/// Runs a case in the three precisions.
pub fn run_case(case: &Case) -> Vec<Row> {
    // the data in f64, the method, the exact answer
    let (m, q, d, free, method, exact_bp, exact_z, infeasible, is_lcp) = match &case.problem {
        Problem::Plcp {
            m,
            q,
            d,
            free,
            exact,
            method,
        } => (
            mat_of::<f64>(m),
            col_of::<f64>(q),
            col_of::<f64>(d),
            *free,
            *method,
            exact.clone(),
            None,
            false,
            false,
        ),
        Problem::Lcp {
            m,
            q,
            exact,
            infeasible,
        } => (
            mat_of::<f64>(m),
            col_of::<f64>(q),
            Col::zeros(q.len()),
            0,
            Method::Lemke,
            None,
            exact.clone(),
            *infeasible,
            true,
        ),
        Problem::Scene(src) => {
            let scene = match frames::Scene::from_toml(src, &case.name) {
                Ok(s) => s,
                Err(e) => {
                    return vec![Row {
                        case: case.name.clone(),
                        precision: "-",
                        status: format!("scene error: {e}"),
                        error: f64::NAN,
                        against: "-",
                        residual: f64::NAN,
                        flagged: true,
                        wrong: false,
                        breakpoints: 0,
                        seconds: 0.0,
                    }]
                }
            };
            let sys = frames::System::assemble(&scene.frame);
            let (m, q, d) = sys.blocks();
            (
                m,
                q,
                d,
                sys.sizes().free(),
                Method::Wolfe,
                None,
                None,
                false,
                false,
            )
        }
    };
    let m128 = Mat::<F128>::from_fn(m.nrows(), m.ncols(), |i, j| F128::from_f64(m[(i, j)]));
    let q128 = Col::<F128>::from_fn(q.nrows(), |i| F128::from_f64(q[i]));
    let d128 = Col::<F128>::from_fn(d.nrows(), |i| F128::from_f64(d[i]));
    let ref128 = Plcp::mixed(m128.as_ref(), q128.as_ref(), d128.as_ref(), free)
        .expect("suite data are finite and consistent");
    let run = |prec: &str| -> Outcome {
        match (prec, is_lcp) {
            ("f32", false) => run_plcp::<f32>(&ref128, &m, &q, &d, free, method),
            ("f64", false) => run_plcp::<f64>(&ref128, &m, &q, &d, free, method),
            ("f128", false) => run_plcp::<F128>(&ref128, &m, &q, &d, free, method),
            ("f32", true) => run_lcp::<f32>(&ref128, &m, &q),
            ("f64", true) => run_lcp::<f64>(&ref128, &m, &q),
            (_, true) => run_lcp::<F128>(&ref128, &m, &q),
            _ => unreachable!(),
        }
    };
    let o128 = if case.fx128 {
        run("f128")
    } else {
        na("skipped (slow)".into())
    };
    let o64 = run("f64");
    let o32 = if case.f32 {
        run("f32")
    } else {
        na("skipped (slow)".into())
    };
    let mut rows = Vec::new();
    for (prec, o) in [("f32", &o32), ("f64", &o64), ("f128", &o128)] {
        let (error, against) = if is_lcp {
            match &exact_z {
                Some(z) if o.success => (rel_diff(&o.z, z), "exact"),
                None if o.success && o128.success && prec != "f128" => {
                    (rel_diff(&o.z, &o128.z), "f128")
                }
                _ => (f64::NAN, "-"),
            }
        } else if !o.success && o.breakpoints.is_empty() {
            (f64::NAN, "-")
        } else if let Some(ex) = &exact_bp {
            let upto = if o.success { f64::INFINITY } else { o.reached };
            (breakpoint_error(&o.breakpoints, ex, upto), "exact")
        } else if prec != "f128"
            && !o128.status.starts_with("n/a")
            && !o128.status.starts_with("skipped")
            && !o128.status.starts_with("error")
            && o128.status != "PANIC"
        {
            // the shorter run's end, with room for its last breakpoint to
            // round to either side of the longer run's (both end there)
            let upto = o.reached.min(o128.reached);
            let upto = upto + allowance(prec) * upto.abs().max(1.0);
            (
                breakpoint_error(&o.breakpoints, &o128.breakpoints, upto),
                "f128",
            )
        } else {
            (f64::NAN, "-")
        };
        let allow = allowance(prec);
        let wrong = o.success && (error > allow || o.residual > allow || o.residual.is_nan());
        // a known-infeasible LCP reported solved shows as a residual at least
        // the distance to the nearest solvable data (the criterion above)
        let _ = infeasible;
        rows.push(Row {
            case: case.name.clone(),
            precision: prec,
            status: o.status.clone(),
            error,
            against,
            residual: o.residual,
            flagged: o.flagged,
            wrong,
            breakpoints: o.breakpoints.len(),
            seconds: o.seconds,
        });
    }
    rows
}

/// Relative max-norm difference of two vectors.
pub fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    if a.len() != b.len() {
        return f64::INFINITY;
    }
    let scale = b.iter().fold(1.0f64, |s, v| s.max(v.abs()));
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / scale
}

/// The table header.
pub fn header() -> String {
    format!(
        "{:<44} {:<5} {:<18} {:>9} {:<5} {:>9} {:>4} {:>5} {:>5} {:>8}\n",
        "case", "prec", "status", "error", "vs", "residual", "bps", "flag", "WRONG", "seconds"
    )
}

/// One table line.
pub fn line(r: &Row) -> String {
    let num = |v: f64| {
        if v.is_nan() {
            "-".to_string()
        } else {
            format!("{v:.1e}")
        }
    };
    format!(
        "{:<44} {:<5} {:<18} {:>9} {:<5} {:>9} {:>4} {:>5} {:>5} {:>8.3}\n",
        short(&r.case, 44),
        r.precision,
        short(&r.status, 18),
        num(r.error),
        r.against,
        num(r.residual),
        r.breakpoints,
        if r.flagged { "yes" } else { "no" },
        if r.wrong { "WRONG" } else { "" },
        r.seconds
    )
}

// ------------------------------------------------------------ the cases

fn diag(v: &[f64]) -> Vec<Vec<f64>> {
    let n = v.len();
    (0..n)
        .map(|i| (0..n).map(|j| if i == j { v[i] } else { 0.0 }).collect())
        .collect()
}

fn plcp_case(
    name: &str,
    m: Vec<Vec<f64>>,
    q: Vec<f64>,
    d: Vec<f64>,
    free: usize,
    exact: Option<Vec<f64>>,
    method: Method,
) -> Case {
    Case {
        name: name.into(),
        problem: Problem::Plcp {
            m,
            q,
            d,
            free,
            exact,
            method,
        },
        fast: true,
        fx128: true,
        f32: true,
    }
}

/// Murty's lower-triangular matrix: 1 on the diagonal, 2 below.
pub fn murty(n: usize) -> Vec<Vec<f64>> {
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| match i.cmp(&j) {
                    std::cmp::Ordering::Equal => 1.0,
                    std::cmp::Ordering::Greater => 2.0,
                    _ => 0.0,
                })
                .collect()
        })
        .collect()
}

/// Kostreva's cyclic matrix `I + 2 P` (`P` the cyclic shift), a P-matrix for odd `n`.
pub fn kostreva(n: usize) -> Vec<Vec<f64>> {
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    if i == j {
                        1.0
                    } else if j == (i + 1) % n {
                        2.0
                    } else {
                        0.0
                    }
                })
                .collect()
        })
        .collect()
}

fn base3() -> (Vec<Vec<f64>>, Vec<f64>, Vec<f64>) {
    (
        vec![
            vec![4.0, 1.0, 0.5],
            vec![1.0, 3.0, 1.0],
            vec![0.5, 1.0, 2.0],
        ],
        vec![1.0, 2.0, 3.0],
        vec![-1.0, -1.0, -1.0],
    )
}

fn scaled(s_m: f64, s_qd: f64) -> (Vec<Vec<f64>>, Vec<f64>, Vec<f64>) {
    let (m, q, d) = base3();
    (
        m.iter()
            .map(|r| r.iter().map(|v| v * s_m).collect())
            .collect(),
        q.iter().map(|v| v * s_qd).collect(),
        d.iter().map(|v| v * s_qd).collect(),
    )
}

/// A frame with masses over 1e-8..1e8, plastic moments over 1e-6..1e6 and
/// member lengths over 1e-2..1e2, in one scene.
pub fn stiff_frame_scene() -> String {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(root.join("scenes/stiff/extremes-chain.toml"))
        .expect("scenes/stiff/extremes-chain.toml")
}

fn scene_file(name: &str) -> String {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(root.join("scenes/stiff").join(name))
        .unwrap_or_else(|e| panic!("scenes/stiff/{name}: {e}"))
}

/// A cantilever of `n` elements, `mass_per_length = 1`, tip load.
pub fn cantilever_scene(n: usize) -> String {
    format!(
        r#"title = "cantilever, {n} elements"
[[node]]
id = "A"
x = 0.0
y = 0.0
[[node]]
id = "B"
x = 1.0
y = 0.0
[[member]]
id = "AB"
from = "A"
to = "B"
plastic_moment = 1.0
elements = {n}
mass_per_length = 1.0
[[support]]
node = "A"
fix = ["x", "y", "rz"]
[[load]]
node = "B"
fy = -1.0
"#
    )
}

/// Every case; `fast` marks the test's subset.
pub fn cases() -> Vec<Case> {
    let mut v = Vec::new();
    let e = |x: &[f64]| Some(x.to_vec());
    // near-ties and exact ties
    let q1 = 1.0 + 1e-12;
    v.push(plcp_case(
        "near tie: breakpoints 1 and 1+1e-12",
        diag(&[1.0, 1.0]),
        vec![1.0, q1],
        vec![-1.0, -1.0],
        0,
        e(&[1.0, q1]),
        Method::Lemke,
    ));
    let q1 = 1e6 * (1.0 + 1e-12);
    v.push(plcp_case(
        "near tie at 1e6 (1e-12 relative), coupled",
        vec![vec![2.0, 1.0], vec![1.0, 2.0]],
        vec![1e6, q1],
        vec![-1.0, -1.0],
        0,
        None,
        Method::Lemke,
    ));
    v.push(plcp_case(
        "exact tie: three breakpoints at 1",
        diag(&[1.0, 2.0, 3.0]),
        vec![1.0, 1.0, 1.0],
        vec![-1.0, -1.0, -1.0],
        0,
        e(&[1.0]),
        Method::Lemke,
    ));
    v.push(plcp_case(
        "Kostreva cyclic n=5 as PLCP (5-fold tie)",
        kostreva(5),
        vec![1.0; 5],
        vec![-1.0; 5],
        0,
        e(&[1.0]),
        Method::Lemke,
    ));
    // PSD singular M
    v.push(plcp_case(
        "PSD singular M = [[1,1],[1,1]]",
        vec![vec![1.0, 1.0], vec![1.0, 1.0]],
        vec![1.0, 2.0],
        vec![-1.0, -1.0],
        0,
        e(&[1.0]),
        Method::Lemke,
    ));
    v.push(plcp_case(
        "PSD singular rank 1 (3x3), Wolfe",
        vec![
            vec![1.0, 2.0, 3.0],
            vec![2.0, 4.0, 6.0],
            vec![3.0, 6.0, 9.0],
        ],
        vec![1.0, 3.0, 2.0],
        vec![-1.0, -1.0, -1.0],
        0,
        None,
        Method::Wolfe,
    ));
    // singular and nearly singular free blocks (KKT of min 1/2 z'z + ... with
    // a free block F)
    let kkt = |eps: f64| -> Vec<Vec<f64>> {
        vec![
            vec![1.0, 1.0, 1.0, 0.0],
            vec![1.0, 1.0 + eps, 0.0, 1.0],
            vec![-1.0, 0.0, 1.0, 0.0],
            vec![0.0, -1.0, 0.0, 1.0],
        ]
    };
    for (name, eps, method) in [
        ("singular free block, Wolfe", 0.0, Method::Wolfe),
        (
            "singular free block, Lemke (must refuse)",
            0.0,
            Method::Lemke,
        ),
        (
            "nearly singular free block 1e-10, Wolfe",
            1e-10,
            Method::Wolfe,
        ),
        (
            "nearly singular free block 1e-10, Lemke",
            1e-10,
            Method::Lemke,
        ),
        (
            "nearly singular free block 1e-15, Lemke",
            1e-15,
            Method::Lemke,
        ),
    ] {
        v.push(plcp_case(
            name,
            kkt(eps),
            vec![0.0, 0.0, 1.0, 2.0],
            vec![1.0, 0.5, -1.0, -1.0],
            2,
            None,
            method,
        ));
    }
    // scaled data: the breakpoints do not change when M, q, d scale together
    let (m, q, d) = base3();
    let _ = (&m, &q, &d);
    for (name, sm, sqd) in [
        ("base 3x3 (unscaled)", 1.0, 1.0),
        ("data scaled by 1e+150", 1e150, 1e150),
        ("data scaled by 1e-150", 1e-150, 1e-150),
        ("M by 1e+150, q and d by 1e-150", 1e150, 1e-150),
        ("data scaled by 1e+300", 1e300, 1e300),
    ] {
        let (m, q, d) = scaled(sm, sqd);
        v.push(plcp_case(name, m, q, d, 0, None, Method::Lemke));
    }
    // values near the f32 range
    v.push(plcp_case(
        "near f32 range: diag(3e38, 1e-37)",
        diag(&[3e38, 1e-37]),
        vec![3e38, 2e-37],
        vec![-3e38, -1e-37],
        0,
        e(&[1.0, 2.0]),
        Method::Lemke,
    ));
    v.push(plcp_case(
        "near f32 range: entries 1e38 and 1e-38 mixed",
        vec![vec![1e38, 1e-38], vec![1e-38, 1e-30]],
        vec![1e38, 1e-30],
        vec![-1e38, -0.5e-30],
        0,
        None,
        Method::Wolfe,
    ));
    // Murty and Kostreva families as plain LCPs (unique solutions known)
    for n in [4, 8, 12, 16] {
        let mut ex = vec![0.0; n];
        ex[0] = 1.0;
        v.push(Case {
            name: format!("Murty n={n} (2^n Lemke pivots)"),
            problem: Problem::Lcp {
                m: murty(n),
                q: vec![-1.0; n],
                exact: Some(ex),
                infeasible: false,
            },
            fast: n <= 8,
            fx128: true,
            f32: true,
        });
    }
    for n in [3, 7, 15] {
        v.push(Case {
            name: format!("Kostreva cyclic n={n} (fully degenerate)"),
            problem: Problem::Lcp {
                m: kostreva(n),
                q: vec![-1.0; n],
                exact: Some(vec![1.0 / 3.0; n]),
                infeasible: false,
            },
            fast: n <= 7,
            fx128: true,
            f32: true,
        });
    }
    // frames
    for (file, fast) in [
        ("extremes-chain.toml", true),
        ("symmetric-beam.toml", true),
        ("symmetric-portal.toml", true),
        ("lengths-portal.toml", true),
    ] {
        v.push(Case {
            name: format!("frame {file}"),
            problem: Problem::Scene(scene_file(file)),
            fast,
            fx128: true,
            f32: true,
        });
    }
    v.push(Case {
        name: "frame cantilever 100 elements".into(),
        problem: Problem::Scene(cantilever_scene(100)),
        fast: false,
        fx128: true,
        f32: true,
    });
    v
}

/// The 1000-element cantilever (report only: minutes in f64, so f64 only).
pub fn large_case() -> Case {
    Case {
        name: "frame cantilever 1000 elements".into(),
        problem: Problem::Scene(cantilever_scene(1000)),
        fast: false,
        fx128: false,
        f32: false,
    }
}

/// The degenerate Siconos LCPs, read from `../shared/lcp-corpus/siconos`
/// (`None` with a message when absent).
pub fn siconos_cases() -> Result<Vec<Case>, String> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = root.join("../shared/lcp-corpus/siconos");
    let rd = std::fs::read_dir(&dir)
        .map_err(|e| format!("skipping the Siconos corpus: {}: {e}", dir.display()))?;
    let mut files: Vec<_> = rd
        .filter_map(|e| e.ok())
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "dat"))
        .collect();
    files.sort();
    let mut v = Vec::new();
    for f in files {
        let name = f
            .file_stem()
            .unwrap_or_default()
            .to_string_lossy()
            .to_string();
        let lcp: Lcp<f64> = match plcp::io::siconos::read_lcp(&f) {
            Ok(l) => l,
            Err(e) => return Err(format!("{}: {e}", f.display())),
        };
        let n = lcp.n();
        let m: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..n).map(|j| lcp.m()[(i, j)]).collect())
            .collect();
        let q: Vec<f64> = (0..n).map(|i| lcp.q()[i]).collect();
        let exact = match name.as_str() {
            "lcp_CPS_2" => Some(vec![0.0, 1.0, 3.0]),
            "lcp_CPS_4" => Some(vec![2.0, 2.0, 2.0, 92.0]),
            "lcp_CPS_4bis" => Some(vec![3.0, 3.0, 0.0, 83.0]),
            "lcp_CPS_5" => Some(vec![0.0, 1.0]),
            "lcp_deudeu" | "lcp_deudeu_block" => Some(vec![4.0 / 3.0, 7.0 / 3.0]),
            "lcp_ortiz" | "lcp_ortiz_block" => Some(vec![2.0 / 3.0, 0.0, 1.0 / 3.0, 0.0]),
            "lcp_trivial" | "lcp_trivial_block" => Some((1..=n).map(|i| 1.0 / i as f64).collect()),
            _ => None,
        };
        v.push(Case {
            name: format!("siconos {}", name.trim_start_matches("lcp_")),
            problem: Problem::Lcp {
                m,
                q,
                exact,
                infeasible: name == "lcp_Pang_isolated_sol_perturbed",
            },
            fast: n <= 26,
            fx128: true,
            f32: true,
        });
    }
    Ok(v)
}
