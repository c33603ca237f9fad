//! Writing plcp's JSON reports of a path and of a plain LCP (see the module
//! documentation of [`super`] for the keys).
//!
//! The output is serialised from views of the path (no copy of its columns)
//! straight into the writer: at n = 2000 a path of 1000 segments is 109 MB of
//! JSON, and building it as owned vectors and one `String` first cost more
//! than the solve (`docs/performance.md`, Input).

use crate::lemke::LcpSolution;
use crate::path::{Path, Point, Residual, Status};
use crate::problem::{Lcp, Plcp};
use crate::residual::residual;
use crate::scalar::Scalar;
use faer::Col;
use serde::Serialize;

type Num64 = Option<f64>;

fn num<T: Scalar>(x: T) -> Num64 {
    f(x.to_f64())
}

fn f(v: f64) -> Num64 {
    v.is_finite().then_some(v)
}

/// A column written as a JSON array of numbers (`null` where not finite).
struct ColOut<'a, T: Scalar>(&'a Col<T>);

impl<T: Scalar> Serialize for ColOut<'_, T> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq((0..self.0.nrows()).map(|i| num(self.0[i])))
    }
}

/// `from + slope * dl`, element by element as [`crate::path::Segment::z0`]
/// computes it (the same numbers), written without storing the column.
struct AffineOut<'a, T: Scalar> {
    from: &'a Col<T>,
    slope: &'a Col<T>,
    dl: T,
}

impl<T: Scalar> Serialize for AffineOut<'_, T> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let (from, slope, dl) = (self.from, self.slope, self.dl);
        s.collect_seq((0..from.nrows()).map(|i| num(from[i] + slope[i] * dl)))
    }
}

/// `Some(column)` in the mixed form, `None` (key omitted) in the standard form.
fn free_col<T: Scalar>(free: usize, c: &Col<T>) -> Option<ColOut<'_, T>> {
    (free > 0).then_some(ColOut(c))
}

#[derive(Serialize)]
#[serde(bound = "")]
struct PointOut<'a, T: Scalar> {
    lambda: Num64,
    z: ColOut<'a, T>,
    w: ColOut<'a, T>,
    #[serde(skip_serializing_if = "Option::is_none")]
    u: Option<ColOut<'a, T>>,
}

impl<'a, T: Scalar> PointOut<'a, T> {
    fn new(free: usize, p: &'a Point<T>) -> Self {
        Self {
            lambda: num(p.lambda),
            z: ColOut(&p.z),
            w: ColOut(&p.w),
            u: free_col(free, &p.u),
        }
    }
}

#[derive(Serialize)]
#[serde(bound = "")]
struct AtOut<'a, T: Scalar> {
    lambda: Num64,
    #[serde(skip_serializing_if = "Option::is_none")]
    z: Option<ColOut<'a, T>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    w: Option<ColOut<'a, T>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    u: Option<ColOut<'a, T>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    residual: Option<ResidualOut>,
    #[serde(skip_serializing_if = "Option::is_none")]
    error: Option<String>,
}

#[derive(Serialize)]
struct BreakpointOut {
    lambda: Num64,
    entering: String,
    leaving: String,
    degenerate: bool,
    turning: bool,
}

/// Names written as a JSON array of strings.
struct NamesOut<'a>(&'a [crate::path::Var]);

impl Serialize for NamesOut<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeSeq;
        // each name written through its `Display`, without a `String` each
        struct Name<'a>(&'a crate::path::Var);
        impl Serialize for Name<'_> {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.collect_str(self.0)
            }
        }
        let mut seq = s.serialize_seq(Some(self.0.len()))?;
        for v in self.0 {
            seq.serialize_element(&Name(v))?;
        }
        seq.end()
    }
}

#[derive(Serialize)]
#[serde(bound = "")]
struct SegmentOut<'a, T: Scalar> {
    lambda_from: Num64,
    lambda_to: Num64,
    unbounded: bool,
    basis: NamesOut<'a>,
    z0: AffineOut<'a, T>,
    dz: ColOut<'a, T>,
    w0: AffineOut<'a, T>,
    dw: ColOut<'a, T>,
    #[serde(skip_serializing_if = "Option::is_none")]
    u0: Option<AffineOut<'a, T>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    du: Option<ColOut<'a, T>>,
}

/// The segments through serde: what `plcp lcp` writes (no segments), and
/// the reference the raw writer below is checked against, byte for byte.
struct SegmentsOut<'a, T: Scalar> {
    free: usize,
    segments: &'a [crate::path::Segment<T>],
}

impl<T: Scalar> Serialize for SegmentsOut<'_, T> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let p = self.free;
        s.collect_seq(self.segments.iter().map(|s| {
            let dl = -s.lambda_from;
            SegmentOut {
                lambda_from: num(s.lambda_from),
                lambda_to: if s.unbounded { None } else { num(s.lambda_to) },
                unbounded: s.unbounded,
                basis: NamesOut(&s.basis),
                z0: AffineOut {
                    from: &s.z_from,
                    slope: &s.dz,
                    dl,
                },
                dz: ColOut(&s.dz),
                w0: AffineOut {
                    from: &s.w_from,
                    slope: &s.dw,
                    dl,
                },
                dw: ColOut(&s.dw),
                u0: (p > 0).then_some(AffineOut {
                    from: &s.u_from,
                    slope: &s.du,
                    dl,
                }),
                du: free_col(p, &s.du),
            }
        }))
    }
}

/// The `segments` array written straight into byte chunks: the bytes serde
/// and serde_json write for the same segments (numbers by the same `zmij`
/// shortest round-trip formatter serde_json uses, `null` where not finite;
/// names as `"z3"`), without serde's calls and two small writes per number.
/// At n = 2000 the segments are 8 million numbers and 2 million names, and
/// through serde they cost half a solve (`docs/performance.md`, Input).
struct RawSegments<'a, T: Scalar> {
    free: usize,
    segments: &'a [crate::path::Segment<T>],
}

/// A chunk of output with the number formatter; flushed past `FLUSH` bytes.
struct Chunk {
    buf: Vec<u8>,
    float: zmij::Buffer,
    int: itoa::Buffer,
}

impl Chunk {
    const FLUSH: usize = 1 << 20;

    fn num<T: Scalar>(&mut self, x: T) {
        let v = x.to_f64();
        if v.is_finite() {
            self.buf
                .extend_from_slice(self.float.format_finite(v).as_bytes());
        } else {
            self.buf.extend_from_slice(b"null");
        }
    }

    fn key(&mut self, key: &str) {
        self.buf.push(b'"');
        self.buf.extend_from_slice(key.as_bytes());
        self.buf.extend_from_slice(b"\":");
    }

    /// `[x_0,x_1,...]` for `x_i = f(i)`, `i < len`, flushing as it goes.
    fn seq<T: Scalar, W: std::io::Write>(
        &mut self,
        out: &mut W,
        len: usize,
        f: impl Fn(usize) -> T,
    ) -> std::io::Result<()> {
        self.buf.push(b'[');
        for i in 0..len {
            if i > 0 {
                self.buf.push(b',');
            }
            self.num(f(i));
            if self.buf.len() >= Self::FLUSH {
                self.flush(out)?;
            }
        }
        self.buf.push(b']');
        Ok(())
    }

    fn name(&mut self, v: &crate::path::Var) {
        use crate::path::Var;
        let (prefix, i) = match *v {
            Var::W(i) => (b'w', i),
            Var::Z(i) => (b'z', i),
            Var::U(i) => (b'u', i),
            Var::Artificial(i) => (b'a', i),
            Var::Lambda => {
                self.buf.extend_from_slice(b"\"L\"");
                return;
            }
        };
        self.buf.push(b'"');
        self.buf.push(prefix);
        self.buf.extend_from_slice(self.int.format(i).as_bytes());
        self.buf.push(b'"');
    }

    fn flush<W: std::io::Write>(&mut self, out: &mut W) -> std::io::Result<()> {
        out.write_all(&self.buf)?;
        self.buf.clear();
        Ok(())
    }
}

impl<T: Scalar> RawSegments<'_, T> {
    fn write<W: std::io::Write>(&self, out: &mut W) -> std::io::Result<()> {
        let mut c = Chunk {
            buf: Vec::with_capacity(Chunk::FLUSH + 4096),
            float: zmij::Buffer::new(),
            int: itoa::Buffer::new(),
        };
        c.buf.push(b'[');
        for (k, s) in self.segments.iter().enumerate() {
            if k > 0 {
                c.buf.push(b',');
            }
            let dl = -s.lambda_from;
            c.buf.push(b'{');
            c.key("lambda_from");
            c.num(s.lambda_from);
            c.buf.push(b',');
            c.key("lambda_to");
            if s.unbounded {
                c.buf.extend_from_slice(b"null");
            } else {
                c.num(s.lambda_to);
            }
            c.buf.push(b',');
            c.key("unbounded");
            c.buf
                .extend_from_slice(if s.unbounded { b"true" } else { b"false" });
            c.buf.push(b',');
            c.key("basis");
            c.buf.push(b'[');
            for (i, v) in s.basis.iter().enumerate() {
                if i > 0 {
                    c.buf.push(b',');
                }
                c.name(v);
            }
            c.buf.push(b']');
            let mut columns = vec![
                ("z0", &s.z_from, Some(&s.dz)),
                ("dz", &s.dz, None),
                ("w0", &s.w_from, Some(&s.dw)),
                ("dw", &s.dw, None),
            ];
            if self.free > 0 {
                columns.push(("u0", &s.u_from, Some(&s.du)));
                columns.push(("du", &s.du, None));
            }
            for (key, from, slope) in columns {
                c.buf.push(b',');
                c.key(key);
                match slope {
                    // `from + slope * dl` as `Segment::z0` computes it
                    Some(slope) => c.seq(out, from.nrows(), |i| from[i] + slope[i] * dl)?,
                    None => c.seq(out, from.nrows(), |i| from[i])?,
                }
            }
            c.buf.push(b'}');
            if c.buf.len() >= Chunk::FLUSH {
                c.flush(out)?;
            }
        }
        c.buf.push(b']');
        c.flush(out)
    }
}

#[derive(Serialize, Clone, Copy)]
struct ResidualOut {
    equation: Num64,
    feasibility: Num64,
    complementarity: Num64,
}

impl From<Residual> for ResidualOut {
    fn from(r: Residual) -> Self {
        Self {
            equation: f(r.equation),
            feasibility: f(r.feasibility),
            complementarity: f(r.complementarity),
        }
    }
}

#[derive(Serialize)]
struct TimingOut {
    solve_seconds: Num64,
}

#[derive(Serialize)]
struct FreeBlockOut {
    rank: usize,
    nonbasic_free: Vec<usize>,
    dependent_rows: Vec<usize>,
}

#[derive(Serialize)]
struct InfoOut {
    method: &'static str,
    precision: &'static str,
    pivots: usize,
    start_pivots: usize,
    degenerate_pivots: usize,
    refactorisations: usize,
    turning_points: usize,
    max_condition: Num64,
    free_block: FreeBlockOut,
    fast_path: &'static str,
}

impl InfoOut {
    fn new<T: Scalar>(info: &crate::path::Info) -> Self {
        Self {
            method: info.method,
            precision: if info.precision.is_empty() {
                T::NAME
            } else {
                info.precision
            },
            pivots: info.pivots,
            start_pivots: info.start_pivots,
            degenerate_pivots: info.degenerate_pivots,
            refactorisations: info.refactorisations,
            turning_points: info.turning_points,
            max_condition: f(info.max_condition),
            free_block: FreeBlockOut {
                rank: info.free_block.rank,
                nonbasic_free: info.free_block.nonbasic_free.clone(),
                dependent_rows: info.free_block.dependent_rows.clone(),
            },
            fast_path: info.fast_path,
        }
    }
}

#[derive(Serialize)]
#[serde(bound = "")]
struct RayOut<'a, T: Scalar> {
    start: PointOut<'a, T>,
    dlambda: Num64,
    dz: ColOut<'a, T>,
    dw: ColOut<'a, T>,
    #[serde(skip_serializing_if = "Option::is_none")]
    du: Option<ColOut<'a, T>>,
}

/// The keys `plcp solve` and `plcp lcp` share, in both outputs in this order
/// (one reader handles both): `lambda_reached`, `pivots`, `breakpoints`,
/// `segments`, `end`.
#[derive(Serialize)]
#[serde(bound = "")]
struct TraceOut<'a, T: Scalar> {
    lambda_reached: Num64,
    pivots: usize,
    breakpoints: Vec<BreakpointOut>,
    segments: SegmentsOut<'a, T>,
    end: PointOut<'a, T>,
}

impl<'a, T: Scalar> TraceOut<'a, T> {
    /// `free` is the number of free variables (`u` is written when positive).
    fn new(free: usize, path: &'a Path<T>) -> Self {
        Self {
            lambda_reached: num(path.lambda_reached),
            pivots: path.info.pivots,
            breakpoints: path
                .breakpoints
                .iter()
                .map(|b| BreakpointOut {
                    lambda: num(b.lambda),
                    entering: b.entering.to_string(),
                    leaving: b.leaving.to_string(),
                    degenerate: b.degenerate,
                    turning: b.turning,
                })
                .collect(),
            segments: SegmentsOut {
                free,
                segments: &path.segments,
            },
            end: PointOut::new(free, &path.end),
        }
    }
}

#[derive(Serialize)]
#[serde(bound = "")]
struct PathOut<'a, T: Scalar> {
    status: &'static str,
    n: usize,
    free: usize,
    lambda0: Num64,
    lambda_max: Num64,
    #[serde(flatten)]
    trace: TraceOut<'a, T>,
    at: Vec<AtOut<'a, T>>,
    residual: ResidualOut,
    timing: TimingOut,
    info: InfoOut,
    message: &'a str,
    #[serde(skip_serializing_if = "Option::is_none")]
    ray: Option<RayOut<'a, T>>,
    #[serde(flatten)]
    extra: &'a serde_json::Map<String, serde_json::Value>,
}

/// The JSON report of a solved path (one line, no trailing newline): what
/// [`write_path_json`] writes, as a `String`.
///
/// Keys, in order: `status` ([`Status::as_str`]), `n`, `free`, `lambda0`,
/// `lambda_max` (`null`: infinity), `lambda_reached`, `pivots`, `breakpoints`
/// (each `lambda`, `entering`, `leaving` (variable names `"z3"`, `"w3"`,
/// `"u0"`, `"L"`, 0-based), `degenerate`, `turning`), `segments` (each
/// `lambda_from`, `lambda_to` (`null` when unbounded), `unbounded`, `basis`
/// (names), `z0`, `dz`, `w0`, `dw` and, when `free > 0`, `u0`, `du`: the
/// solution on the segment is `z0 + L dz` etc.), `end` (`lambda`, `z`, `w`,
/// and `u` when `free > 0`), `at` (one entry per value of `at`: `lambda`, `z`,
/// `w`, (`u`), `residual`; or `lambda` and `error` when the value lies outside
/// the traced range), `residual` (`equation`, `feasibility`, `complementarity`:
/// the largest of the solver's own record over its breakpoints and a fresh
/// evaluation at `end` and at every `at` point, each relative as in
/// [`crate::residual::residual`]), `timing` (`solve_seconds`, as passed in),
/// `info` (`method`, `precision`, `pivots`, `start_pivots`,
/// `degenerate_pivots`, `refactorisations`, `turning_points`, `max_condition`,
/// `free_block` {`rank`, `nonbasic_free`, `dependent_rows`}, `fast_path`:
/// [`crate::Info::fast_path`]), `message`, and
/// `ray` (`start` point, `dlambda`, `dz`, `dw`, (`du`)) when the path ended on one.
/// Non-finite numbers are `null`.
pub fn path_json<T: Scalar>(
    problem: &Plcp<T>,
    path: &Path<T>,
    at: &[f64],
    solve_seconds: f64,
) -> String {
    let mut out = Vec::new();
    let options = PathJsonOptions {
        at,
        solve_seconds,
        ..PathJsonOptions::default()
    };
    let written = write_path_json(&mut out, problem, path, &options);
    match written.map(|_| String::from_utf8(out)) {
        Ok(Ok(text)) => text,
        // Serialising these plain structs into memory cannot fail, and
        // serde_json writes UTF-8; keep the output valid JSON anyway.
        Ok(Err(e)) => serde_json::json!({"status": "error", "message": e.to_string()}).to_string(),
        Err(e) => serde_json::json!({"status": "error", "message": e.to_string()}).to_string(),
    }
}

/// What the JSON report of a path holds besides the path itself (see
/// [`write_path_json`]). The default: no `at` values, `solve_seconds` 0, the
/// segments written, nothing extra.
#[derive(Clone, Copy, Debug)]
pub struct PathJsonOptions<'a> {
    /// Parameter values at which to report the solution (the `at` array).
    pub at: &'a [f64],
    /// The solve time written as `timing.solve_seconds`.
    pub solve_seconds: f64,
    /// `false`: the `segments` array is written empty (the breakpoints, the
    /// end point and the `at` values are all there; at n = 2000 the segments
    /// are 100 MB of the output and most of its writing time).
    pub with_segments: bool,
    /// Fields written after the report's own, in order (for example a
    /// `certificate`).
    pub extra: Option<&'a serde_json::Map<String, serde_json::Value>>,
}

impl Default for PathJsonOptions<'_> {
    fn default() -> Self {
        PathJsonOptions {
            at: &[],
            solve_seconds: 0.0,
            with_segments: true,
            extra: None,
        }
    }
}

/// Writes the report of [`path_json`] to `out` as it is built (the path's
/// columns are read in place, nothing of the size of the output is held),
/// with the `at` values, timing, segments and extra fields of `options`.
/// An error is the writer's.
///
/// ```
/// use plcp::io::json::{write_path_json, PathJsonOptions};
/// let p = plcp::Plcp::<f64>::new(
///     faer::mat![[2.0, 1.0], [1.0, 2.0]].as_ref(),
///     faer::col![1.0, 1.0].as_ref(),
///     faer::col![-1.0, -0.5].as_ref(),
/// )
/// .unwrap();
/// let path = plcp::solve(&p, &plcp::Settings::default()).unwrap();
/// let mut out = Vec::new();
/// let options = PathJsonOptions { at: &[0.5], with_segments: false, ..Default::default() };
/// write_path_json(&mut out, &p, &path, &options).unwrap();
/// let text = String::from_utf8(out).unwrap();
/// assert!(text.contains(r#""segments":[]"#) && text.contains(r#""at":[{"lambda":0.5"#));
/// ```
pub fn write_path_json<T: Scalar, W: std::io::Write>(
    out: W,
    problem: &Plcp<T>,
    path: &Path<T>,
    options: &PathJsonOptions<'_>,
) -> std::io::Result<()> {
    let PathJsonOptions {
        at,
        solve_seconds,
        with_segments,
        extra,
    } = *options;
    let no_extra = serde_json::Map::new();
    let extra = extra.unwrap_or(&no_extra);
    let p = problem.free();
    let mut res = path.info.residual.max(residual(problem, &path.end));
    let points: Vec<Option<(Point<T>, Residual)>> = at
        .iter()
        .map(|&l| {
            let point = if l.is_finite() {
                path.at(T::from_f64(l))
            } else {
                None
            };
            point.map(|pt| {
                let r = residual(problem, &pt);
                res = res.max(r);
                (pt, r)
            })
        })
        .collect();
    let at: Vec<AtOut<'_, T>> = at
        .iter()
        .zip(&points)
        .map(|(&l, point)| match point {
            Some((pt, r)) => AtOut {
                lambda: f(l),
                z: Some(ColOut(&pt.z)),
                w: Some(ColOut(&pt.w)),
                u: free_col(p, &pt.u),
                residual: Some((*r).into()),
                error: None,
            },
            None => AtOut {
                lambda: f(l),
                z: None,
                w: None,
                u: None,
                residual: None,
                error: Some(format!(
                    "lambda = {l} lies outside the traced range [{}, {}] (status {})",
                    path.lambda0.to_f64(),
                    path.lambda_reached.to_f64(),
                    path.status.as_str()
                )),
            },
        })
        .collect();
    // The segments are most of the report (at n = 2000, 8 million numbers):
    // the rest is serialised with an empty `segments` array, and the raw
    // writer fills it in at its place.
    let mut trace = TraceOut::new(p, path);
    let segments = RawSegments {
        free: p,
        segments: if with_segments {
            trace.segments.segments
        } else {
            &[]
        },
    };
    trace.segments.segments = &[];
    let report = PathOut {
        status: path.status.as_str(),
        n: problem.n(),
        free: p,
        lambda0: num(path.lambda0),
        lambda_max: path.lambda_max.and_then(num),
        trace,
        at,
        residual: res.into(),
        timing: TimingOut {
            solve_seconds: f(solve_seconds),
        },
        info: InfoOut::new::<T>(&path.info),
        message: &path.message,
        ray: path.ray.as_ref().map(|r| RayOut {
            start: PointOut::new(p, &r.start),
            dlambda: num(r.dlambda),
            dz: ColOut(&r.dz),
            dw: ColOut(&r.dw),
            du: free_col(p, &r.du),
        }),
        extra,
    };
    let rest = serde_json::to_vec(&report).map_err(std::io::Error::other)?;
    // The first `"segments":[]`: the keys before it are numbers, booleans,
    // and variable names, none of which holds a quote.
    const KEY: &[u8] = b"\"segments\":[]";
    let at = rest
        .windows(KEY.len())
        .position(|w| w == KEY)
        .ok_or_else(|| std::io::Error::other("the report has no `segments` key"))?
        + KEY.len()
        - 2;
    let mut out = std::io::BufWriter::with_capacity(1 << 16, out);
    std::io::Write::write_all(&mut out, &rest[..at])?;
    segments.write(&mut out)?;
    std::io::Write::write_all(&mut out, &rest[at + 2..])?;
    std::io::Write::flush(&mut out)
}

#[derive(Serialize)]
#[serde(bound = "")]
struct LcpOut<'a, T: Scalar> {
    status: &'static str,
    n: usize,
    z: ColOut<'a, T>,
    w: ColOut<'a, T>,
    #[serde(flatten)]
    trace: TraceOut<'a, T>,
    residual: ResidualOut,
    siconos_error: Num64,
    timing: TimingOut,
    info: InfoOut,
    message: &'a str,
}

/// The name of an LCP outcome: `"solved"` for [`Status::Reached`] (and for an
/// unbounded ray, which cannot end a plain LCP but would mean the same), else
/// [`Status::as_str`].
pub fn lcp_status(status: Status) -> &'static str {
    if status.is_success() {
        "solved"
    } else {
        status.as_str()
    }
}

/// `w = q + M z`, recomputed in `T` (the Siconos measure does the same).
fn fresh_w<T: Scalar>(lcp: &Lcp<T>, z: &Col<T>) -> Col<T> {
    let (m, q) = (lcp.m(), lcp.q());
    Col::from_fn(lcp.n(), |i| {
        (0..lcp.n()).fold(q[i], |acc, j| acc + m[(i, j)] * z[j])
    })
}

/// The JSON report of a plain LCP (one line): `status` ([`lcp_status`]), `n`,
/// `z`, `w`, then the keys shared with [`path_json`], written by the same code
/// from [`LcpSolution::as_path`] (the single point `L = 0`): `lambda_reached`
/// (0), `pivots`, `breakpoints` (empty), `segments` (empty), `end` (`lambda` 0,
/// `z`, `w`), then `residual` (as in [`path_json`]: the solver's record and
/// a fresh evaluation of `(z, w)`), `siconos_error`
/// ([`crate::io::siconos::siconos_error`] of `z` and `w = q + M z` recomputed from
/// `z`, as Siconos does), `timing` (`solve_seconds`), `info`,
/// `message`. Non-finite numbers are `null`.
pub fn lcp_json<T: Scalar>(lcp: &Lcp<T>, sol: &LcpSolution<T>, solve_seconds: f64) -> String {
    let n = lcp.n();
    let zero = Col::<T>::zeros(n);
    let fresh = Plcp::new(lcp.m(), lcp.q(), zero.as_ref())
        .map(|p| {
            residual(
                &p,
                &Point {
                    lambda: T::zero(),
                    z: sol.z.clone(),
                    w: sol.w.clone(),
                    u: Col::zeros(0),
                },
            )
        })
        .unwrap_or_default();
    let as_path = sol.as_path();
    let out = LcpOut {
        status: lcp_status(sol.status),
        n,
        z: ColOut(&sol.z),
        w: ColOut(&sol.w),
        trace: TraceOut::new(0, &as_path),
        residual: sol.info.residual.max(fresh).into(),
        siconos_error: f(crate::io::siconos::siconos_error(
            lcp.q(),
            sol.z.as_ref(),
            fresh_w(lcp, &sol.z).as_ref(),
        )),
        timing: TimingOut {
            solve_seconds: f(solve_seconds),
        },
        info: InfoOut::new::<T>(&sol.info),
        message: &sol.message,
    };
    serde_json::to_string(&out).unwrap_or_else(|e| {
        serde_json::json!({"status": "error", "message": e.to_string()}).to_string()
    })
}

#[cfg(test)]
mod raw_tests {
    use super::*;
    use crate::path::{Segment, Var};

    /// Segments of every shape: random magnitudes over the whole exponent
    /// range, signed zeros, infinities and NaN, every kind of name, an
    /// unbounded last segment, with and without free variables.
    fn segments<T: Scalar>(free: usize, seed: u64) -> Vec<Segment<T>> {
        let mut u = crate::test_rng::unit(seed);
        let mut x = move || -> T {
            let r = u();
            let v = match (r * 16.0) as u32 {
                0 => 0.0,
                1 => -0.0,
                2 => f64::INFINITY,
                3 => f64::NAN,
                4 => f64::NEG_INFINITY,
                5 => (u() - 0.5) * 1e-300,
                6 => (u() - 0.5) * 1e300,
                7 => (u() * 40.0).round() - 20.0,
                _ => (u() - 0.5) * 10f64.powf(u() * 40.0 - 20.0),
            };
            T::from_f64(v)
        };
        (0..7)
            .map(|k| {
                let n = k * 3 % 5;
                let col = |x: &mut dyn FnMut() -> T, len| Col::from_fn(len, |_| x());
                Segment {
                    lambda_from: x(),
                    lambda_to: x(),
                    unbounded: k == 6,
                    basis: (0..n + free)
                        .map(|i| match (i + k) % 5 {
                            0 => Var::W(i * 1009),
                            1 => Var::Z(i),
                            2 => Var::U(i + 10),
                            3 => Var::Artificial(usize::MAX - i),
                            _ => Var::Lambda,
                        })
                        .collect(),
                    z_from: col(&mut x, n),
                    dz: col(&mut x, n),
                    w_from: col(&mut x, n),
                    dw: col(&mut x, n),
                    u_from: col(&mut x, free),
                    du: col(&mut x, free),
                }
            })
            .collect()
    }

    fn same_bytes<T: Scalar>() {
        for (free, seed) in [(0, 3), (2, 5), (0, 11), (1, 17)] {
            let segments = segments::<T>(free, seed);
            for s in [&segments[..], &segments[..0], &segments[..1]] {
                let serde = serde_json::to_vec(&SegmentsOut { free, segments: s }).unwrap();
                let mut raw = Vec::new();
                RawSegments { free, segments: s }.write(&mut raw).unwrap();
                assert_eq!(
                    String::from_utf8(raw).unwrap(),
                    String::from_utf8(serde).unwrap()
                );
            }
        }
    }

    #[test]
    fn raw_segments_are_serdes_bytes() {
        same_bytes::<f64>();
        same_bytes::<f32>();
        same_bytes::<faer::fx128>();
    }

    /// Past the chunk size (flushes inside a column and between segments).
    #[test]
    fn long_columns_flush_in_place() {
        let n = 40_000;
        let seg = |k: usize| Segment::<f64> {
            lambda_from: k as f64,
            lambda_to: k as f64 + 0.5,
            unbounded: false,
            basis: (0..n).map(Var::Z).collect(),
            z_from: Col::from_fn(n, |i| (i * k) as f64 / 7.0),
            dz: Col::from_fn(n, |i| -(i as f64) / 3.0),
            w_from: Col::from_fn(n, |i| i as f64 * 1e-9),
            dw: Col::from_fn(n, |i| i as f64),
            u_from: Col::zeros(0),
            du: Col::zeros(0),
        };
        let segments: Vec<_> = (0..3).map(seg).collect();
        let serde = serde_json::to_vec(&SegmentsOut {
            free: 0,
            segments: &segments,
        })
        .unwrap();
        let mut raw = Vec::new();
        RawSegments {
            free: 0,
            segments: &segments,
        }
        .write(&mut raw)
        .unwrap();
        assert!(serde.len() > 4 * Chunk::FLUSH);
        assert!(raw == serde);
    }
}
