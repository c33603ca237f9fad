//! # plcp from Python
//!
//! The native half of the `plcp` Python package (`plcp._plcp`): it copies the
//! caller's numpy data into a [`plcp::Plcp`] in the requested precision, traces
//! the path with the Python thread state detached (other Python threads run
//! meanwhile), and hands back a `PyPath` that evaluates the path in its
//! working precision and shows every number as a float64 numpy array. The
//! argument handling that is easier in Python (scipy.sparse to triplets,
//! `ndim` checks, keyword defaults) lives in `plcp/__init__.py`; the contract
//! of the package is its stub file `plcp/_plcp.pyi` and `plcp/__init__.py`.
//!
//! Bad input is a `ValueError` carrying the library's [`plcp::PlcpError`]
//! message; an outcome of the algorithm is the path's `status` string.

use faer::{fx128, Col, Mat};
use numpy::{PyArray1, PyReadonlyArray1, PyReadonlyArray2};
use plcp::matrix::Csc;
use plcp::{Method, Plcp, PlcpError, Precision, Scalar, Settings};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// `M` as the caller gave it, in float64: dense (row-major) or triplets.
enum Matrix {
    Dense {
        nrows: usize,
        ncols: usize,
        data: Vec<f64>,
    },
    Triplets {
        nrows: usize,
        ncols: usize,
        entries: Vec<(usize, usize, f64)>,
    },
}

/// Everything a solve needs, owned, so that it can run without the GIL.
struct Request {
    m: Matrix,
    q: Vec<f64>,
    d: Vec<f64>,
    lambda0: f64,
    lambda_max: Option<f64>,
    free: usize,
    method: Method,
}

fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

fn col<T: Scalar>(v: &[f64]) -> Col<T> {
    Col::from_fn(v.len(), |i| T::from_f64(v[i]))
}

/// Builds the problem in `T` (so an entry that `T` cannot represent, e.g.
/// 1e300 in f32, is the library's non-finite error) and traces its path.
fn trace<T: Scalar>(r: &Request) -> Result<plcp::Path<T>, PlcpError> {
    let (q, d) = (col::<T>(&r.q), col::<T>(&r.d));
    let problem = match &r.m {
        Matrix::Dense { nrows, ncols, data } => {
            let m = Mat::from_fn(*nrows, *ncols, |i, j| T::from_f64(data[i * ncols + j]));
            Plcp::mixed(m.as_ref(), q.as_ref(), d.as_ref(), r.free)?
        }
        Matrix::Triplets {
            nrows,
            ncols,
            entries,
        } => {
            let t: Vec<(usize, usize, T)> = entries
                .iter()
                .map(|&(i, j, v)| (i, j, T::from_f64(v)))
                .collect();
            let m = Csc::try_from_triplets(*nrows, *ncols, &t)?;
            Plcp::mixed_sparse(m, q.as_ref(), d.as_ref(), r.free)?
        }
    };
    let problem = problem.with_range(T::from_f64(r.lambda0), r.lambda_max.map(T::from_f64))?;
    plcp::solve(&problem, &Settings::with_method(r.method))
}

/// A path in the precision it was traced in.
enum AnyPath {
    F32(plcp::Path<f32>),
    F64(plcp::Path<f64>),
    F128(plcp::Path<fx128>),
}

/// Runs `$body` with `$p` bound to the path of whichever precision.
macro_rules! with_path {
    ($any:expr, $p:ident => $body:expr) => {
        match $any {
            AnyPath::F32($p) => $body,
            AnyPath::F64($p) => $body,
            AnyPath::F128($p) => $body,
        }
    };
}

fn to_f64<T: Scalar>(c: &Col<T>) -> Vec<f64> {
    c.iter().map(|v| v.to_f64()).collect()
}

fn array<'py>(py: Python<'py>, v: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_vec(py, v)
}

fn parse_precision(s: &str) -> PyResult<Precision> {
    s.parse().map_err(value_error)
}

fn parse_method(s: &str) -> PyResult<Method> {
    s.parse().map_err(value_error)
}

fn vector(name: &str, a: &PyReadonlyArray1<'_, f64>) -> PyResult<Vec<f64>> {
    a.as_array()
        .as_slice()
        .map(<[f64]>::to_vec)
        .or_else(|| Some(a.as_array().iter().copied().collect()))
        .ok_or_else(|| value_error(format!("{name} could not be read")))
}

/// The solution at one value of `L` (`z`, `w`, `u` as float64 arrays).
#[pyclass(frozen, module = "plcp._plcp", name = "Point")]
struct PyPoint {
    lambda: f64,
    z: Vec<f64>,
    w: Vec<f64>,
    u: Vec<f64>,
}

#[pymethods]
impl PyPoint {
    /// The parameter value.
    #[getter]
    fn lambda_(&self) -> f64 {
        self.lambda
    }
    #[getter]
    fn z<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.z.clone())
    }
    #[getter]
    fn w<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.w.clone())
    }
    #[getter]
    fn u<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.u.clone())
    }
    fn __repr__(&self) -> String {
        format!(
            "Point(lambda={}, n={}, p={})",
            self.lambda,
            self.z.len(),
            self.u.len()
        )
    }
}

impl PyPoint {
    fn from<T: Scalar>(p: &plcp::Point<T>) -> Self {
        Self {
            lambda: p.lambda.to_f64(),
            z: to_f64(&p.z),
            w: to_f64(&p.w),
            u: to_f64(&p.u),
        }
    }
}

/// One piece of the path: `x(L) = x_from + (L - lambda_from) dx` for x in z, w, u.
#[pyclass(frozen, module = "plcp._plcp", name = "Segment")]
struct PySegment {
    lambda_from: f64,
    lambda_to: f64,
    unbounded: bool,
    basis: Vec<String>,
    cols: [Vec<f64>; 6],
}

#[pymethods]
impl PySegment {
    #[getter]
    fn lambda_from(&self) -> f64 {
        self.lambda_from
    }
    /// `inf` for the last piece of an unbounded ray.
    #[getter]
    fn lambda_to(&self) -> f64 {
        if self.unbounded {
            f64::INFINITY
        } else {
            self.lambda_to
        }
    }
    #[getter]
    fn unbounded(&self) -> bool {
        self.unbounded
    }
    /// The complementary basis on the piece: `"z3"` or `"w3"` for each pair.
    #[getter]
    fn basis(&self) -> Vec<String> {
        self.basis.clone()
    }
    #[getter]
    fn z_from<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.cols[0].clone())
    }
    #[getter]
    fn dz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.cols[1].clone())
    }
    #[getter]
    fn w_from<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.cols[2].clone())
    }
    #[getter]
    fn dw<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.cols[3].clone())
    }
    #[getter]
    fn u_from<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.cols[4].clone())
    }
    #[getter]
    fn du<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.cols[5].clone())
    }
    fn __repr__(&self) -> String {
        format!(
            "Segment(lambda_from={}, lambda_to={})",
            self.lambda_from,
            self.lambda_to()
        )
    }
}

impl PySegment {
    fn from<T: Scalar>(s: &plcp::Segment<T>) -> Self {
        Self {
            lambda_from: s.lambda_from.to_f64(),
            lambda_to: s.lambda_to.to_f64(),
            unbounded: s.unbounded,
            basis: s.basis.iter().map(ToString::to_string).collect(),
            cols: [
                to_f64(&s.z_from),
                to_f64(&s.dz),
                to_f64(&s.w_from),
                to_f64(&s.dw),
                to_f64(&s.u_from),
                to_f64(&s.du),
            ],
        }
    }
}

/// The solution path of a PLCP, kept in its working precision.
#[pyclass(frozen, module = "plcp._plcp", name = "Path")]
struct PyPath {
    path: AnyPath,
}

#[pymethods]
impl PyPath {
    /// `"reached"`, `"unbounded_ray"`, `"secondary_ray"`, `"pivot_limit"`,
    /// `"ill_conditioned"` or `"infeasible"`.
    #[getter]
    fn status(&self) -> &'static str {
        with_path!(&self.path, p => p.status.as_str())
    }
    /// True for `"reached"` and `"unbounded_ray"`.
    #[getter]
    fn success(&self) -> bool {
        with_path!(&self.path, p => p.status.is_success())
    }
    /// The diagnostics behind a status other than success (often empty otherwise).
    #[getter]
    fn message(&self) -> String {
        with_path!(&self.path, p => p.message.clone())
    }
    #[getter]
    fn lambda0(&self) -> f64 {
        with_path!(&self.path, p => p.lambda0.to_f64())
    }
    /// The value of `L` the path reached: `inf` on an unbounded ray.
    #[getter]
    fn lambda_reached(&self) -> f64 {
        with_path!(&self.path, p => {
            if p.status == plcp::Status::UnboundedRay {
                f64::INFINITY
            } else {
                p.lambda_reached.to_f64()
            }
        })
    }
    /// The breakpoints' values of `L`, in path order.
    #[getter]
    fn breakpoints<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let v =
            with_path!(&self.path, p => p.breakpoints.iter().map(|b| b.lambda.to_f64()).collect());
        array(py, v)
    }
    /// `(entering, leaving)` at each breakpoint, e.g. `("z3", "w3")`.
    #[getter]
    fn events(&self) -> Vec<(String, String)> {
        with_path!(&self.path, p => p
            .breakpoints
            .iter()
            .map(|b| (b.entering.to_string(), b.leaving.to_string()))
            .collect())
    }
    #[getter]
    fn segments(&self) -> Vec<PySegment> {
        with_path!(&self.path, p => p.segments.iter().map(PySegment::from).collect())
    }
    /// The solution where the path ended.
    #[getter]
    fn end(&self) -> PyPoint {
        with_path!(&self.path, p => PyPoint::from(&p.end))
    }
    /// The solution at `lambda_` (evaluated in the working precision), or
    /// `None` outside the traced range.
    fn at(&self, lambda_: f64) -> Option<PyPoint> {
        with_path!(&self.path, p => p.at(Scalar::from_f64(lambda_)).as_ref().map(PyPoint::from))
    }
    /// Counts, residuals and time: a dict.
    #[getter]
    fn info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        with_path!(&self.path, p => info_dict(py, &p.info))
    }
    fn __repr__(&self) -> String {
        format!(
            "Path(status={:?}, lambda_reached={}, breakpoints={})",
            self.status(),
            self.lambda_reached(),
            with_path!(&self.path, p => p.breakpoints.len())
        )
    }
}

fn info_dict<'py>(py: Python<'py>, info: &plcp::Info) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("method", info.method)?;
    d.set_item("precision", info.precision)?;
    d.set_item("pivots", info.pivots)?;
    d.set_item("start_pivots", info.start_pivots)?;
    d.set_item("degenerate_pivots", info.degenerate_pivots)?;
    d.set_item("refactorisations", info.refactorisations)?;
    d.set_item("refinements", info.refinements)?;
    d.set_item("turning_points", info.turning_points)?;
    let r = PyDict::new(py);
    r.set_item("equation", info.residual.equation)?;
    r.set_item("feasibility", info.residual.feasibility)?;
    r.set_item("complementarity", info.residual.complementarity)?;
    d.set_item("residuals", r)?;
    d.set_item("max_condition", info.max_condition)?;
    d.set_item("free_rank", info.free_block.rank)?;
    d.set_item("seconds", info.solve_seconds)?;
    d.set_item("escalated", info.escalation.is_some())?;
    d.set_item("fast_path", info.fast_path)?;
    Ok(d)
}

/// The solution of a plain LCP `w = q + M z`.
#[pyclass(frozen, module = "plcp._plcp", name = "LcpSolution")]
struct PyLcpSolution {
    status: &'static str,
    z: Vec<f64>,
    w: Vec<f64>,
    message: String,
    info: plcp::Info,
}

#[pymethods]
impl PyLcpSolution {
    #[getter]
    fn status(&self) -> &'static str {
        self.status
    }
    #[getter]
    fn z<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.z.clone())
    }
    #[getter]
    fn w<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.w.clone())
    }
    #[getter]
    fn message(&self) -> String {
        self.message.clone()
    }
    #[getter]
    fn info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        info_dict(py, &self.info)
    }
    fn __repr__(&self) -> String {
        format!("LcpSolution(status={:?}, n={})", self.status, self.z.len())
    }
}

fn solve_request(py: Python<'_>, r: Request, precision: &str) -> PyResult<PyPath> {
    let precision = parse_precision(precision)?;
    let path = py
        .detach(|| -> Result<AnyPath, PlcpError> {
            Ok(match precision {
                Precision::F32 => AnyPath::F32(trace::<f32>(&r)?),
                Precision::F64 => AnyPath::F64(trace::<f64>(&r)?),
                Precision::F128 => AnyPath::F128(trace::<fx128>(&r)?),
            })
        })
        .map_err(value_error)?;
    Ok(PyPath { path })
}

/// Traces the path of a PLCP whose `M` is a dense 2-D float64 array.
#[pyfunction]
#[pyo3(signature = (m, q, d, lambda_max, lambda0, free, method, precision))]
#[allow(clippy::too_many_arguments)]
fn solve_dense(
    py: Python<'_>,
    m: PyReadonlyArray2<'_, f64>,
    q: PyReadonlyArray1<'_, f64>,
    d: PyReadonlyArray1<'_, f64>,
    lambda_max: Option<f64>,
    lambda0: f64,
    free: usize,
    method: &str,
    precision: &str,
) -> PyResult<PyPath> {
    let a = m.as_array();
    let (nrows, ncols) = a.dim();
    let data: Vec<f64> = a.iter().copied().collect(); // row-major (logical order)
    let r = Request {
        m: Matrix::Dense { nrows, ncols, data },
        q: vector("q", &q)?,
        d: vector("d", &d)?,
        lambda0,
        lambda_max,
        free,
        method: parse_method(method)?,
    };
    solve_request(py, r, precision)
}

/// Traces the path of a PLCP whose `M` is given as COO triplets.
#[pyfunction]
#[pyo3(signature = (shape, rows, cols, vals, q, d, lambda_max, lambda0, free, method, precision))]
#[allow(clippy::too_many_arguments)]
fn solve_sparse(
    py: Python<'_>,
    shape: (usize, usize),
    rows: PyReadonlyArray1<'_, i64>,
    cols: PyReadonlyArray1<'_, i64>,
    vals: PyReadonlyArray1<'_, f64>,
    q: PyReadonlyArray1<'_, f64>,
    d: PyReadonlyArray1<'_, f64>,
    lambda_max: Option<f64>,
    lambda0: f64,
    free: usize,
    method: &str,
    precision: &str,
) -> PyResult<PyPath> {
    let (r, c, v) = (rows.as_array(), cols.as_array(), vals.as_array());
    if r.len() != c.len() || r.len() != v.len() {
        return Err(value_error(format!(
            "sparse M: {} row indices, {} column indices, {} values",
            r.len(),
            c.len(),
            v.len()
        )));
    }
    let mut entries = Vec::with_capacity(r.len());
    for k in 0..r.len() {
        let (i, j) = (r[k], c[k]);
        if i < 0 || j < 0 {
            return Err(value_error(format!(
                "sparse M: negative index ({i}, {j}) in entry {k}"
            )));
        }
        entries.push((i as usize, j as usize, v[k]));
    }
    let req = Request {
        m: Matrix::Triplets {
            nrows: shape.0,
            ncols: shape.1,
            entries,
        },
        q: vector("q", &q)?,
        d: vector("d", &d)?,
        lambda0,
        lambda_max,
        free,
        method: parse_method(method)?,
    };
    solve_request(py, req, precision)
}

fn lcp<T: Scalar>(
    nrows: usize,
    ncols: usize,
    data: &[f64],
    q: &[f64],
) -> Result<PyLcpSolution, PlcpError> {
    let m = Mat::from_fn(nrows, ncols, |i, j| T::from_f64(data[i * ncols + j]));
    let lcp = plcp::Lcp::new(m.as_ref(), col::<T>(q).as_ref())?;
    let s = plcp::solve_lcp(&lcp, &Settings::default())?;
    Ok(PyLcpSolution {
        status: s.status.as_str(),
        z: to_f64(&s.z),
        w: to_f64(&s.w),
        message: s.message,
        info: s.info,
    })
}

/// Solves the LCP `w = q + M z` (dense `M`) by Lemke's method.
#[pyfunction]
#[pyo3(signature = (m, q, precision))]
fn solve_lcp_dense(
    py: Python<'_>,
    m: PyReadonlyArray2<'_, f64>,
    q: PyReadonlyArray1<'_, f64>,
    precision: &str,
) -> PyResult<PyLcpSolution> {
    let precision = parse_precision(precision)?;
    let a = m.as_array();
    let (nrows, ncols) = a.dim();
    let data: Vec<f64> = a.iter().copied().collect();
    let q = vector("q", &q)?;
    py.detach(|| match precision {
        Precision::F32 => lcp::<f32>(nrows, ncols, &data, &q),
        Precision::F64 => lcp::<f64>(nrows, ncols, &data, &q),
        Precision::F128 => lcp::<fx128>(nrows, ncols, &data, &q),
    })
    .map_err(value_error)
}

/// The native module `plcp._plcp`.
#[pymodule]
fn _plcp(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(solve_dense, m)?)?;
    m.add_function(wrap_pyfunction!(solve_sparse, m)?)?;
    m.add_function(wrap_pyfunction!(solve_lcp_dense, m)?)?;
    m.add_class::<PyPath>()?;
    m.add_class::<PySegment>()?;
    m.add_class::<PyPoint>()?;
    m.add_class::<PyLcpSolution>()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request(m: Matrix, q: Vec<f64>, d: Vec<f64>) -> Request {
        Request {
            m,
            q,
            d,
            lambda0: 0.0,
            lambda_max: None,
            free: 0,
            method: Method::Lemke,
        }
    }

    /// The dense data is read row-major and the triplets as (row, column):
    /// both give the library's path of the same problem (M not symmetric, so a
    /// transposed copy would show).
    #[test]
    fn dense_and_triplets_trace_the_same_path() {
        let (q, d) = (vec![1.0, 1.0], vec![-1.0, -0.5]);
        let dense = request(
            Matrix::Dense {
                nrows: 2,
                ncols: 2,
                data: vec![2.0, 1.5, 0.5, 2.0],
            },
            q.clone(),
            d.clone(),
        );
        let sparse = request(
            Matrix::Triplets {
                nrows: 2,
                ncols: 2,
                entries: vec![(0, 0, 2.0), (0, 1, 1.5), (1, 0, 0.5), (1, 1, 2.0)],
            },
            q.clone(),
            d.clone(),
        );
        let (a, b) = (
            trace::<f64>(&dense).unwrap(),
            trace::<f64>(&sparse).unwrap(),
        );
        let m = faer::mat![[2.0, 1.5], [0.5, 2.0]];
        let (qc, dc) = (col::<f64>(&q), col::<f64>(&d));
        let direct = plcp::solve(
            &Plcp::new(m.as_ref(), qc.as_ref(), dc.as_ref()).unwrap(),
            &Settings::default(),
        )
        .unwrap();
        for p in [&a, &b] {
            assert_eq!(p.status, direct.status);
            let l: Vec<f64> = p.breakpoints.iter().map(|b| b.lambda).collect();
            let e: Vec<f64> = direct.breakpoints.iter().map(|b| b.lambda).collect();
            assert_eq!(l, e);
            let (x, y) = (p.at(2.5).unwrap(), direct.at(2.5).unwrap());
            assert_eq!(to_f64(&x.z), to_f64(&y.z));
        }
    }

    /// An entry that f32 cannot represent is the library's non-finite error.
    #[test]
    fn unrepresentable_in_f32_is_an_error() {
        let r = request(
            Matrix::Dense {
                nrows: 1,
                ncols: 1,
                data: vec![1e300],
            },
            vec![1.0],
            vec![-1.0],
        );
        assert!(trace::<f64>(&r).is_ok());
        let e = trace::<f32>(&r).unwrap_err().to_string();
        assert!(e.contains("non-finite entry in M"), "{e}");
    }
}
