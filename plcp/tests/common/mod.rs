//! Shared test oracle, instance generators and path checks for the plcp
//! integration tests.
//!
//! * [`enumerate`]: brute-force enumeration of the `2^n` complementary bases of
//!   the (mixed) LCP `w = q + L d + M x` at one `L`, each principal system
//!   solved by faer's full-pivoting LU in the test's own precision. It finds
//!   every complementary *basic* solution (nonsingular principal block). For a
//!   P-matrix that is the unique solution; for a monotone `M` a solvable LCP
//!   always has one (Lemke's method ends on a nonsingular complementary basis),
//!   so "no basic solution" certifies "no solution" up to the tolerance.
//! * [`lemke_reference`]: a textbook dense-tableau Lemke with covering vector
//!   `e` and the lexicographic ratio test, in f64, used only to count pivots
//!   (Murty's example).
//! * Generators: monotone `B B' + S`, PSD singular, P-matrices, Murty, Kostreva.
//!   Random data are dyadic rationals (`k / 2^j`, small `k`) so that `B B'` and
//!   every cast to `f32` and `fx128` is exact: all three precisions solve the
//!   very same problem, and a singular matrix stays exactly singular.
//! * [`check_path`]: every structural and numerical property a path must have.
#![allow(dead_code)]

/// Runs the `plcp` binary (the tests that need the command line).
#[cfg(feature = "cli")]
pub mod cli;

use faer::linalg::solvers::Solve;
use faer::{Col, ColRef, Mat, MatRef};
use plcp::residual::residual;
use plcp::{Path, Plcp, Point, Scalar, Status, Var};

// ---------------------------------------------------------------- conversion

/// A row-major `Vec<Vec<f64>>` as a faer matrix.
pub fn mat_from_rows(rows: &[Vec<f64>]) -> Mat<f64> {
    let n = rows.len();
    let m = rows.first().map_or(0, |r| r.len());
    Mat::from_fn(n, m, |i, j| rows[i][j])
}

/// An f64 matrix in precision `T`.
pub fn mat_t<T: Scalar>(m: MatRef<'_, f64>) -> Mat<T> {
    Mat::from_fn(m.nrows(), m.ncols(), |i, j| T::from_f64(m[(i, j)]))
}

/// An f64 slice in precision `T`.
pub fn col_t<T: Scalar>(v: &[f64]) -> Col<T> {
    Col::from_fn(v.len(), |i| T::from_f64(v[i]))
}

/// A column as f64 values.
pub fn col_f64<T: Scalar>(v: ColRef<'_, T>) -> Vec<f64> {
    (0..v.nrows()).map(|i| v[i].to_f64()).collect()
}

/// An instance in f64, convertible to any precision.
#[derive(Clone, Debug)]
pub struct Instance {
    /// Row-major matrix of order `free + n`.
    pub m: Mat<f64>,
    pub q: Vec<f64>,
    pub d: Vec<f64>,
    pub free: usize,
    pub lambda0: f64,
    pub lambda_max: Option<f64>,
    /// What kind of matrix (for messages and for what the oracle may compare).
    pub kind: Kind,
}

/// The matrix class of a generated instance: says which properties hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `B B' + S` with `B` square: positive definite symmetric part, unique solution.
    PositiveDefinite,
    /// Symmetric PSD and singular: `w` unique, `z` not.
    PsdSingularSymmetric,
    /// PSD singular plus a skew part: monotone, neither `z` nor `w` unique in general.
    PsdSingularSkew,
    /// A P-matrix that is not monotone: unique solution.
    PMatrix,
    /// Anything else (a textbook example).
    Other,
}

impl Kind {
    /// Unique solution `z` for every `q`.
    pub fn unique_z(self) -> bool {
        matches!(self, Kind::PositiveDefinite | Kind::PMatrix)
    }
    /// Unique `w` (symmetric PSD or P).
    pub fn unique_w(self) -> bool {
        self.unique_z() || self == Kind::PsdSingularSymmetric
    }
    /// Positive semidefinite (not necessarily symmetric) `M`.
    pub fn monotone(self) -> bool {
        matches!(
            self,
            Kind::PositiveDefinite | Kind::PsdSingularSymmetric | Kind::PsdSingularSkew
        )
    }
}

impl Instance {
    pub fn n(&self) -> usize {
        self.q.len() - self.free
    }
    /// The problem in precision `T`, with its range.
    pub fn plcp<T: Scalar>(&self) -> Plcp<T> {
        let m = mat_t::<T>(self.m.as_ref());
        let q = col_t::<T>(&self.q);
        let d = col_t::<T>(&self.d);
        Plcp::mixed(m.as_ref(), q.as_ref(), d.as_ref(), self.free)
            .expect("generated instance is valid")
            .with_range(T::from_f64(self.lambda0), self.lambda_max.map(T::from_f64))
            .expect("generated range is valid")
    }
    /// The instance as plcp's JSON input format (for bug reports).
    pub fn to_json(&self) -> String {
        let dim = self.q.len();
        let rows: Vec<Vec<f64>> = (0..dim)
            .map(|i| (0..dim).map(|j| self.m[(i, j)]).collect())
            .collect();
        serde_json::json!({
            "M": rows,
            "q": self.q,
            "d": self.d,
            "lambda_max": self.lambda_max,
            "lambda0": self.lambda0,
            "free": self.free,
            "kind": format!("{:?}", self.kind),
        })
        .to_string()
    }
}

/// Writes `inst` to `/work/main/out/engine-bug-<name>.json` (best effort) and
/// returns the path written, for a failure message.
pub fn dump_instance(name: &str, inst: &Instance) -> String {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../out");
    let _ = std::fs::create_dir_all(&dir);
    let file = dir.join(format!("engine-bug-{name}.json"));
    let _ = std::fs::write(&file, inst.to_json());
    file.display().to_string()
}

// ---------------------------------------------------------------- generators

/// `B B' / n + shift I` for a square `B` of order `n`, each entry summed in
/// a plain loop down `B'`'s contiguous columns (no faer product: under load
/// its thread pool made small products slow), in the same order for every
/// caller, so equal `B`s give equal bits.
pub fn gram_shifted(b: MatRef<'_, f64>, shift: f64) -> Mat<f64> {
    let n = b.nrows();
    let bt = b.transpose().to_owned();
    Mat::<f64>::from_fn(n, n, |i, j| {
        let (ci, cj) = (bt.col(i), bt.col(j));
        let mut s = 0.0;
        for l in 0..n {
            s += ci[l] * cj[l];
        }
        s / n as f64 + if i == j { shift } else { 0.0 }
    })
}

/// `B B'` for a row-major `n x r` matrix `b` (exact for dyadic entries).
pub fn gram(b: &[f64], n: usize, r: usize) -> Mat<f64> {
    Mat::from_fn(n, n, |i, j| {
        (0..r).map(|k| b[i * r + k] * b[j * r + k]).sum()
    })
}

/// A skew-symmetric matrix from the strict upper triangle in `s` (row-major n x n, lower part ignored).
pub fn skew(s: &[f64], n: usize) -> Mat<f64> {
    Mat::from_fn(n, n, |i, j| {
        if i < j {
            s[i * n + j]
        } else if i > j {
            -s[j * n + i]
        } else {
            0.0
        }
    })
}

/// Monotone `M = B B' + S (+ shift I)`: `b` is `n x r` row-major; `r < n` gives a
/// singular symmetric part. `s` (n x n, upper triangle used) may be all zero.
pub fn monotone(b: &[f64], n: usize, r: usize, s: &[f64], shift: f64) -> Mat<f64> {
    let g = gram(b, n, r);
    let k = skew(s, n);
    Mat::from_fn(n, n, |i, j| {
        g[(i, j)] + k[(i, j)] + if i == j { shift } else { 0.0 }
    })
}

/// A strictly row diagonally dominant matrix with positive diagonal (a P-matrix):
/// off-diagonal from `off` (n x n row-major, diagonal entries ignored), diagonal
/// `sum_j |off_ij| + margin_i` with `margin_i > 0`.
pub fn diag_dominant(off: &[f64], margin: &[f64], n: usize) -> Mat<f64> {
    Mat::from_fn(n, n, |i, j| {
        if i == j {
            (0..n)
                .filter(|&k| k != i)
                .map(|k| off[i * n + k].abs())
                .sum::<f64>()
                + margin[i]
        } else {
            off[i * n + j]
        }
    })
}

/// `P T P'` with `T` upper triangular (positive diagonal `diag`, any strict upper
/// part from `off`) and `P` the permutation `perm`: a P-matrix, in general neither
/// monotone nor diagonally dominant.
pub fn permuted_triangular(off: &[f64], diag: &[f64], perm: &[usize], n: usize) -> Mat<f64> {
    let t = |i: usize, j: usize| -> f64 {
        if i == j {
            diag[i]
        } else if i < j {
            off[i * n + j]
        } else {
            0.0
        }
    };
    // (P T P')_{ij} = T_{perm^-1(i), perm^-1(j)}; using perm as the inverse is just as random.
    Mat::from_fn(n, n, |i, j| t(perm[i], perm[j]))
}

/// Murty's matrix: upper triangular, 1 on the diagonal and 2 above it
/// (Murty 1988, ch. 6; the Siconos `exp_murty` instances).
pub fn murty_matrix(n: usize) -> Mat<f64> {
    Mat::from_fn(n, n, |i, j| {
        if i == j {
            1.0
        } else if i < j {
            2.0
        } else {
            0.0
        }
    })
}

/// Murty's right-hand side on which Lemke's method with covering vector `e`
/// takes `2^n` pivots: `q_i = -(2^(n+1) - 2^(i+1))` (0-based `i`); for n = 6 this
/// is the Siconos `exp_murty2` vector (-126, -124, -120, -112, -96, -64).
pub fn murty_q(n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| -((1u64 << (n + 1)) as f64 - (1u64 << (i + 1)) as f64))
        .collect()
}

/// Kostreva's (1979) cycling example: `M = [[1,2,0],[0,1,2],[2,0,1]]`, `q = -e`;
/// with covering vector `e` every ratio of Lemke's first steps ties, and a naive
/// tie rule cycles. The unique solution is `z = (1/3, 1/3, 1/3)`, `w = 0`.
pub fn kostreva_matrix() -> Mat<f64> {
    mat_from_rows(&[
        vec![1.0, 2.0, 0.0],
        vec![0.0, 1.0, 2.0],
        vec![2.0, 0.0, 1.0],
    ])
}

// ---------------------------------------------------------------- enumeration

/// A complementary basic solution found by enumeration.
#[derive(Clone, Debug)]
pub struct Basic<T: Scalar> {
    pub u: Col<T>,
    pub z: Col<T>,
    pub w: Col<T>,
    /// `alpha[i]`: `z_i` is basic (else `w_i`).
    pub alpha: Vec<bool>,
}

/// All complementary basic solutions of the mixed LCP at `lambda`:
/// `0 = (M x + r)[0..p]`, `w = (M x + r)[p..]`, `r = q + lambda d`, with the
/// principal block of `(u, z_alpha)` nonsingular (full-pivoting LU, smallest
/// pivot above `1e3 * dim * eps` times the largest), and `min(z, w) >=
/// -feas_tol * scale`, `scale = max(1, |r|_inf, |z|_inf, |w|_inf)`.
///
/// `n <= 12` (4096 bases).
pub fn enumerate<T: Scalar>(
    m: MatRef<'_, T>,
    q: ColRef<'_, T>,
    d: ColRef<'_, T>,
    p: usize,
    lambda: T,
    feas_tol: f64,
) -> Vec<Basic<T>> {
    let dim = m.nrows();
    let n = dim - p;
    assert!(n <= 12, "enumeration is for n <= 12");
    let r: Col<T> = Col::from_fn(dim, |i| q[i] + lambda * d[i]);
    let rmax = (0..dim).fold(1.0f64, |a, i| a.max(r[i].to_f64().abs()));
    let mut out = Vec::new();
    for mask in 0u32..(1u32 << n) {
        let alpha: Vec<bool> = (0..n).map(|i| mask & (1 << i) != 0).collect();
        // unknowns: u (p), then z_i for i in alpha
        let idx: Vec<usize> = (0..p)
            .chain((0..n).filter(|&i| alpha[i]).map(|i| p + i))
            .collect();
        let k = idx.len();
        let mut x = Col::<T>::zeros(dim);
        if k > 0 {
            let a = Mat::from_fn(k, k, |i, j| m[(idx[i], idx[j])]);
            let lu = a.full_piv_lu();
            let u = lu.U();
            let umax = (0..k).fold(0.0f64, |acc, i| acc.max(u[(i, i)].to_f64().abs()));
            let umin = (0..k).fold(f64::INFINITY, |acc, i| acc.min(u[(i, i)].to_f64().abs()));
            let thresh = 1e3 * (k as f64) * T::eps().to_f64() * umax;
            if umax.is_nan() || umax <= 0.0 || umin <= thresh {
                continue;
            }
            let rhs = Col::from_fn(k, |i| -r[idx[i]]);
            let sol = lu.solve(&rhs);
            for (i, &j) in idx.iter().enumerate() {
                x[j] = sol[i];
            }
        }
        let z = Col::from_fn(n, |i| x[p + i]);
        let w = Col::from_fn(n, |i| {
            if alpha[i] {
                T::zero()
            } else {
                let row = p + i;
                let mut acc = r[row];
                for j in 0..dim {
                    acc += m[(row, j)] * x[j];
                }
                acc
            }
        });
        let zmax = (0..n).fold(0.0f64, |a, i| a.max(z[i].to_f64().abs()));
        let wmax = (0..n).fold(0.0f64, |a, i| a.max(w[i].to_f64().abs()));
        let scale = rmax.max(zmax).max(wmax);
        let ok = (0..n)
            .all(|i| z[i].to_f64() >= -feas_tol * scale && w[i].to_f64() >= -feas_tol * scale);
        if ok {
            out.push(Basic {
                u: Col::from_fn(p, |i| x[i]),
                z,
                w,
                alpha,
            });
        }
    }
    out
}

/// Largest relative distance between two vectors: `max_i |a_i - b_i| / max(1, |a|_inf, |b|_inf)`.
pub fn rel_dist<T: Scalar>(a: ColRef<'_, T>, b: ColRef<'_, T>) -> f64 {
    assert_eq!(a.nrows(), b.nrows());
    let mut scale = 1.0f64;
    let mut diff = 0.0f64;
    for i in 0..a.nrows() {
        scale = scale.max(a[i].to_f64().abs()).max(b[i].to_f64().abs());
        diff = diff.max((a[i] - b[i]).abs().to_f64());
    }
    diff / scale
}

/// Compares a path point with the enumerated solutions at its `L`, according to
/// what is unique for `kind`. Returns a description of the mismatch, if any.
pub fn compare_with_enumeration<T: Scalar>(
    problem: &Plcp<T>,
    point: &Point<T>,
    kind: Kind,
    tol: f64,
    feas_tol: f64,
) -> Result<(), String> {
    let sols = enumerate(
        problem.m(),
        problem.q(),
        problem.d(),
        problem.free(),
        point.lambda,
        feas_tol,
    );
    if sols.is_empty() {
        return Err(format!(
            "L = {}: the path has a point but enumeration found no complementary basic solution",
            point.lambda.to_f64()
        ));
    }
    // Whatever the class, the path's point is a complementary basic solution: it
    // must be one of those enumerated.
    let nearest = sols
        .iter()
        .map(|s| {
            rel_dist(s.z.as_ref(), point.z.as_ref())
                .max(rel_dist(s.w.as_ref(), point.w.as_ref()))
                .max(rel_dist(s.u.as_ref(), point.u.as_ref()))
        })
        .fold(f64::INFINITY, f64::min);
    if kind.unique_z() {
        // the oracle itself: a P-matrix has exactly one solution (near-solutions
        // within the feasibility tolerance may differ by more than `tol` when the
        // problem is ill-conditioned, hence the looser sqrt(tol) for this check)
        for s in &sols[1..] {
            let dz = rel_dist(s.z.as_ref(), sols[0].z.as_ref());
            if dz > tol.sqrt() {
                return Err(format!(
                    "oracle: {} solutions for a P-matrix at L = {} (z differ by {dz:e})",
                    sols.len(),
                    point.lambda.to_f64()
                ));
            }
        }
        // and the path's z is that solution (the nearest of its near-copies)
        let dz = sols
            .iter()
            .map(|s| rel_dist(s.z.as_ref(), point.z.as_ref()))
            .fold(f64::INFINITY, f64::min);
        if dz > tol {
            return Err(format!(
                "L = {}: z differs from the unique solution by {dz:e} (tol {tol:e}): path z = {:?}, oracle z = {:?}",
                point.lambda.to_f64(),
                col_f64(point.z.as_ref()),
                col_f64(sols[0].z.as_ref())
            ));
        }
    }
    if kind.unique_w() {
        for s in &sols {
            let dw = rel_dist(s.w.as_ref(), point.w.as_ref());
            if dw > tol {
                return Err(format!(
                    "L = {}: w differs from the (unique) w of an enumerated solution by {dw:e} (tol {tol:e}): path w = {:?}, oracle w = {:?}",
                    point.lambda.to_f64(),
                    col_f64(point.w.as_ref()),
                    col_f64(s.w.as_ref())
                ));
            }
        }
    }
    if nearest > tol {
        return Err(format!(
            "L = {}: the path's point is none of the {} enumerated basic solutions (nearest {nearest:e}, tol {tol:e}): z = {:?}, w = {:?}",
            point.lambda.to_f64(),
            sols.len(),
            col_f64(point.z.as_ref()),
            col_f64(point.w.as_ref())
        ));
    }
    Ok(())
}

// ---------------------------------------------------------------- reference Lemke

/// Outcome of the reference Lemke.
#[derive(Clone, Debug)]
pub struct LemkeRef {
    /// Pivots, counting the first (artificial variable enters) and the last (it leaves).
    pub pivots: usize,
    /// Ended with the artificial variable out of the basis.
    pub solved: bool,
    pub z: Vec<f64>,
    /// Bases visited (sorted variable indices: `0..n` w, `n..2n` z, `2n` the artificial).
    pub bases: Vec<Vec<usize>>,
}

/// Textbook Lemke (Murty 1988, ch. 2) on `w - M z - e z0 = q`, dense tableau,
/// lexicographic minimum-ratio rule, exact in f64 for small integer data.
pub fn lemke_reference(m: MatRef<'_, f64>, q: &[f64], max_pivots: usize) -> LemkeRef {
    let n = q.len();
    let cols = 2 * n + 2; // w, z, z0, rhs
    let mut t = vec![vec![0.0f64; cols]; n];
    for i in 0..n {
        t[i][i] = 1.0;
        for j in 0..n {
            t[i][n + j] = -m[(i, j)];
        }
        t[i][2 * n] = -1.0;
        t[i][2 * n + 1] = q[i];
    }
    let mut basis: Vec<usize> = (0..n).collect();
    let mut bases = vec![{
        let mut b = basis.clone();
        b.sort();
        b
    }];
    if q.iter().all(|&v| v >= 0.0) {
        return LemkeRef {
            pivots: 0,
            solved: true,
            z: vec![0.0; n],
            bases,
        };
    }
    let pivot = |t: &mut Vec<Vec<f64>>, r: usize, c: usize| {
        let p = t[r][c];
        for v in t[r].iter_mut() {
            *v /= p;
        }
        let row = t[r].clone();
        for (i, ti) in t.iter_mut().enumerate() {
            if i != r {
                let f = ti[c];
                if f != 0.0 {
                    for (v, rv) in ti.iter_mut().zip(row.iter()) {
                        *v -= f * rv;
                    }
                }
            }
        }
    };
    // lexicographic comparison of rows (rhs, B^-1 columns) / |pivot entry|
    let lex_less = |t: &Vec<Vec<f64>>, a: usize, b: usize, c: usize| -> bool {
        let key = |i: usize| -> Vec<f64> {
            std::iter::once(t[i][2 * n + 1])
                .chain((0..n).map(|j| t[i][j]))
                .map(|v| v / t[i][c].abs())
                .collect()
        };
        let (ka, kb) = (key(a), key(b));
        for (x, y) in ka.iter().zip(kb.iter()) {
            if (x - y).abs() > 1e-12 * (1.0 + x.abs().max(y.abs())) {
                return x < y;
            }
        }
        false
    };
    // first pivot: z0 enters (column -e); it must rise to max(-q_i): the row of
    // the lexicographically smallest (q_i, e_i)
    let c0 = 2 * n;
    let mut r = 0;
    for i in 1..n {
        if lex_less(&t, i, r, c0) {
            r = i;
        }
    }
    let mut leaving = basis[r];
    pivot(&mut t, r, c0);
    basis[r] = c0;
    let mut pivots = 1;
    let push = |bases: &mut Vec<Vec<usize>>, basis: &Vec<usize>| {
        let mut b = basis.clone();
        b.sort();
        bases.push(b);
    };
    push(&mut bases, &basis);
    loop {
        if pivots >= max_pivots {
            break;
        }
        let entering = if leaving < n {
            leaving + n
        } else {
            leaving - n
        };
        let mut r: Option<usize> = None;
        for i in 0..n {
            if t[i][entering] > 1e-12 {
                r = match r {
                    None => Some(i),
                    Some(k) if lex_less(&t, i, k, entering) => Some(i),
                    keep => keep,
                };
            }
        }
        let Some(r) = r else {
            break; // secondary ray
        };
        leaving = basis[r];
        pivot(&mut t, r, entering);
        basis[r] = entering;
        pivots += 1;
        push(&mut bases, &basis);
        if leaving == c0 {
            let mut z = vec![0.0; n];
            for (i, &b) in basis.iter().enumerate() {
                if (n..2 * n).contains(&b) {
                    z[b - n] = t[i][2 * n + 1];
                }
            }
            return LemkeRef {
                pivots,
                solved: true,
                z,
                bases,
            };
        }
    }
    LemkeRef {
        pivots,
        solved: false,
        z: vec![0.0; n],
        bases,
    }
}

// ---------------------------------------------------------------- path checks

/// Tolerances of the path checks, all relative (see `plcp::residual::residual`
/// for how residuals are scaled).
#[derive(Clone, Copy, Debug)]
pub struct Tol {
    /// Equation, feasibility and complementarity residual at every checked point.
    pub residual: f64,
    /// Agreement of two solutions (continuity, oracle), relative to `max(1, |x|_inf)`.
    pub forward: f64,
    /// Feasibility tolerance of the enumeration oracle.
    pub enum_feas: f64,
    /// Two parameter values count as equal within `lambda * max(1, |L|)`.
    pub lambda: f64,
}

impl Tol {
    /// Every tolerance multiplied by `k`.
    pub fn scaled(self, k: f64) -> Tol {
        Tol {
            residual: self.residual * k,
            forward: self.forward * k,
            enum_feas: self.enum_feas * k,
            lambda: self.lambda * k,
        }
    }
}

/// The largest 2-norm condition number (f64 SVD) of the basis matrices of the
/// path's segments, in the unreduced system: columns `e_(p+i)` for `w_i`,
/// `M[:, p+i]` for `z_i`, `M[:, j]` for `u_j`, `e_k` for the artificial variable
/// of row `k`; a basis that lists no free variables (Lemke on the reduction)
/// holds them all.
pub fn max_basis_condition<T: Scalar>(problem: &Plcp<T>, path: &Path<T>) -> f64 {
    let p = problem.free();
    let dim = problem.dim();
    let m = problem.m();
    let mut worst = 1.0f64;
    for s in &path.segments {
        let mut vars = s.basis.clone();
        if !vars
            .iter()
            .any(|v| matches!(v, Var::U(_) | Var::Artificial(_)))
        {
            vars.extend((0..p).map(Var::U));
        }
        if vars.len() != dim {
            continue;
        }
        let b = Mat::from_fn(dim, dim, |r, c| match vars[c] {
            Var::W(i) => f64::from(u8::from(r == p + i)),
            Var::Z(i) => m[(r, p + i)].to_f64(),
            Var::U(j) => m[(r, j)].to_f64(),
            Var::Artificial(k) => f64::from(u8::from(r == k)),
            Var::Lambda => 0.0,
        });
        if let Ok(sv) = b.singular_values() {
            let smax = sv.iter().cloned().fold(0.0f64, f64::max);
            let smin = sv.iter().cloned().fold(f64::INFINITY, f64::min);
            if smin > 0.0 {
                worst = worst.max(smax / smin);
            } else {
                worst = f64::INFINITY;
            }
        }
    }
    worst
}

/// The points a path check looks at: both ends of every segment and interior
/// points at fraction `0.5` and `frac` of it; on an unbounded last segment,
/// `from + 1` and `from + 10 (1 + |from|)`.
pub fn sample_lambdas<T: Scalar>(path: &Path<T>, frac: f64) -> Vec<T> {
    let mut out = Vec::new();
    for s in &path.segments {
        let a = s.lambda_from;
        out.push(a);
        if s.unbounded {
            out.push(a + T::one());
            out.push(a + T::from_f64(10.0) * (T::one() + a.abs()));
        } else {
            let b = s.lambda_to;
            out.push(b);
            for f in [0.5, frac] {
                out.push(a + (b - a) * T::from_f64(f));
            }
        }
    }
    out
}

/// What must be continuous at a breakpoint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Continuity {
    /// `z`, `w` and `u`: the solution is unique (P-matrix, positive definite).
    All,
    /// `w` only: symmetric PSD `M` (`w` unique, `z` not).
    W,
    /// Nothing: a nonsymmetric PSD `M` may have a segment of solutions at one
    /// `L` (e.g. `M = [[0, a], [-a, 0]]`), which the path crosses at a
    /// breakpoint; both sides are checked as solutions instead.
    None,
}

impl Kind {
    /// What a path of this class must be continuous in.
    pub fn continuity(self) -> Continuity {
        if self.unique_z() {
            Continuity::All
        } else if self.unique_w() {
            Continuity::W
        } else {
            Continuity::None
        }
    }
}

/// Checks the shape of a path (ordering, contiguity, complementary bases, values
/// consistent with the bases, status and end) and the residual at the ends of
/// every segment and at interior points; the path must be continuous at every
/// breakpoint as `continuity` says. `monotone_l`: `L` never decreases (no
/// turning points: true for P-matrices and PSD `M`).
///
/// Returns the points checked.
pub fn check_path<T: Scalar>(
    problem: &Plcp<T>,
    path: &Path<T>,
    tol: Tol,
    frac: f64,
    continuity: Continuity,
    monotone_l: bool,
) -> Result<Vec<Point<T>>, String> {
    let n = problem.n();
    let p = problem.free();
    let leq = |a: T, b: T| -> bool {
        a.to_f64() <= b.to_f64() + tol.lambda * (1.0f64).max(a.to_f64().abs())
    };
    let near = |a: T, b: T| -> bool {
        (a.to_f64() - b.to_f64()).abs() <= tol.lambda * (1.0f64).max(a.to_f64().abs())
    };
    // status and range
    match (path.status, problem.lambda_max()) {
        (Status::Reached, Some(lm)) if !near(path.lambda_reached, lm) => {
            return Err(format!(
                "Reached but lambda_reached = {} != lambda_max = {}",
                path.lambda_reached.to_f64(),
                lm.to_f64()
            ));
        }
        (Status::Reached, None) => {
            return Err("status Reached with an infinite lambda_max".into());
        }
        (Status::UnboundedRay, _) => {
            let last = path
                .segments
                .last()
                .ok_or("UnboundedRay without segments")?;
            if !last.unbounded {
                return Err("UnboundedRay but the last segment is not marked unbounded".into());
            }
            if path.ray.is_none() {
                return Err("UnboundedRay without a ray".into());
            }
        }
        // a path blocked by an equality row has no ray to show (documented on Status)
        (Status::SecondaryRay, _)
            if path.ray.is_none() && !path.message.contains("cannot be continued") =>
        {
            return Err("SecondaryRay without a ray".into());
        }
        _ => {}
    }
    if path.lambda0.to_f64() != problem.lambda0().to_f64() {
        return Err("path.lambda0 differs from the problem's".into());
    }
    if let Some(lm) = problem.lambda_max() {
        if !leq(path.lambda_reached, lm) {
            return Err(format!(
                "lambda_reached {} beyond lambda_max {}",
                path.lambda_reached.to_f64(),
                lm.to_f64()
            ));
        }
    }
    // segments: ordering, contiguity, bases
    for (k, s) in path.segments.iter().enumerate() {
        if monotone_l && !leq(s.lambda_from, s.lambda_to) && !s.unbounded {
            return Err(format!("segment {k}: lambda_from > lambda_to"));
        }
        if s.unbounded && k + 1 != path.segments.len() {
            return Err(format!("segment {k} is unbounded but not the last"));
        }
        // one of w_i, z_i per pair; a mixed problem's basis may also hold free
        // variables and the artificial variables of dependent rows (Wolfe's long form)
        let mut seen = vec![false; n];
        for v in &s.basis {
            match *v {
                Var::W(i) | Var::Z(i) if i < n && !seen[i] => seen[i] = true,
                Var::U(j) | Var::Artificial(j) if j < p => {}
                other => {
                    return Err(format!(
                        "segment {k}: basis {:?} is not complementary (bad entry {other})",
                        s.basis
                    ))
                }
            }
        }
        if seen.iter().any(|s| !s) {
            return Err(format!(
                "segment {k}: basis {:?} misses a complementary pair",
                s.basis
            ));
        }
        if s.z_from.nrows() != n
            || s.w_from.nrows() != n
            || s.dz.nrows() != n
            || s.dw.nrows() != n
            || s.u_from.nrows() != p
            || s.du.nrows() != p
        {
            return Err(format!("segment {k}: vectors of the wrong size"));
        }
        // the nonbasic member of each pair is identically zero on the segment
        for v in &s.basis {
            let (val, slope, name) = match *v {
                Var::W(i) => (s.z_from[i], s.dz[i], format!("z{i}")),
                Var::Z(i) => (s.w_from[i], s.dw[i], format!("w{i}")),
                _ => continue,
            };
            if val != T::zero() || slope != T::zero() {
                // allow rounding only at the residual tolerance
                let sc = 1.0f64.max(s.lambda_from.to_f64().abs());
                if val.to_f64().abs() > tol.residual * sc || slope.to_f64().abs() > tol.residual {
                    return Err(format!(
                        "segment {k}: nonbasic {name} is not zero ({} + {} dL)",
                        val.to_f64(),
                        slope.to_f64()
                    ));
                }
            }
        }
        if k == 0 && !near(s.lambda_from, problem.lambda0()) && path.info.turning_points == 0 {
            return Err(format!(
                "the first segment starts at {} not at lambda0 = {}",
                s.lambda_from.to_f64(),
                problem.lambda0().to_f64()
            ));
        }
        if k > 0 {
            let prev = &path.segments[k - 1];
            if monotone_l && prev.lambda_to < s.lambda_from {
                // a hole between the segments: `at` must still answer inside it
                let mid = prev.lambda_to + (s.lambda_from - prev.lambda_to) * T::from_f64(0.5);
                if path.at(mid).is_none() {
                    return Err(format!(
                        "hole between segments {} and {k}: path.at({:e}) is None (segments end at {:e} and start at {:e})",
                        k - 1,
                        mid.to_f64(),
                        prev.lambda_to.to_f64(),
                        s.lambda_from.to_f64()
                    ));
                }
            }
            if !near(prev.lambda_to, s.lambda_from) {
                return Err(format!(
                    "gap between segments {} and {k}: {} vs {}",
                    k - 1,
                    prev.lambda_to.to_f64(),
                    s.lambda_from.to_f64()
                ));
            }
            let a = prev.eval(prev.lambda_to);
            let b = s.eval(s.lambda_from);
            let dw = rel_dist(a.w.as_ref(), b.w.as_ref());
            if continuity != Continuity::None && dw > tol.forward {
                return Err(format!(
                    "w jumps by {dw:e} at the breakpoint L = {} between segments {} and {k}",
                    s.lambda_from.to_f64(),
                    k - 1
                ));
            }
            if continuity == Continuity::All {
                let dz =
                    rel_dist(a.z.as_ref(), b.z.as_ref()).max(rel_dist(a.u.as_ref(), b.u.as_ref()));
                if dz > tol.forward {
                    return Err(format!(
                        "z jumps by {dz:e} at the breakpoint L = {} between segments {} and {k}",
                        s.lambda_from.to_f64(),
                        k - 1
                    ));
                }
            }
        }
    }
    // the segments' bases never repeat (no cycling)
    for a in 0..path.segments.len() {
        for b in a + 1..path.segments.len() {
            let mut ba = path.segments[a].basis.clone();
            let mut bb = path.segments[b].basis.clone();
            ba.sort();
            bb.sort();
            if ba == bb {
                return Err(format!("segments {a} and {b} have the same basis {ba:?}"));
            }
        }
    }
    // breakpoints
    let mut prev_l: Option<T> = None;
    for (k, bp) in path.breakpoints.iter().enumerate() {
        if !bp.lambda.is_finite() {
            return Err(format!("breakpoint {k} at a non-finite L"));
        }
        if monotone_l {
            // a turning point flagged on a step of L within the tolerance (Lemke
            // on a Schur reduction sees steps at the reduction's error) is no
            // reversal; one that the path then follows backwards is
            let reverses = path
                .segments
                .get(bp.segment)
                .is_some_and(|s| !leq(s.lambda_from, s.lambda_to));
            if bp.turning && reverses {
                return Err(format!(
                    "breakpoint {k} is a turning point on a monotone problem"
                ));
            }
            if let Some(pl) = prev_l {
                if !leq(pl, bp.lambda) {
                    return Err(format!(
                        "breakpoint {k}: L decreases from {} to {}",
                        pl.to_f64(),
                        bp.lambda.to_f64()
                    ));
                }
            }
            if !leq(problem.lambda0(), bp.lambda) || !leq(bp.lambda, path.lambda_reached) {
                return Err(format!(
                    "breakpoint {k} at L = {} outside [lambda0, lambda_reached]",
                    bp.lambda.to_f64()
                ));
            }
        }
        if bp.entering == bp.leaving {
            return Err(format!("breakpoint {k}: {} enters and leaves", bp.entering));
        }
        prev_l = Some(bp.lambda);
    }
    let reversals = path
        .breakpoints
        .iter()
        .filter(|bp| {
            bp.turning
                && path
                    .segments
                    .get(bp.segment)
                    .is_some_and(|s| !leq(s.lambda_from, s.lambda_to))
        })
        .count();
    if monotone_l && reversals != 0 {
        return Err(format!(
            "{reversals} turning points on a monotone problem that the path follows backwards (of {} flagged)",
            path.info.turning_points
        ));
    }
    if path.info.degenerate_pivots > path.info.pivots {
        return Err("more degenerate pivots than pivots".into());
    }
    // residuals: the stated tolerance, or 10 eps times the condition number of
    // the worst basis on the path if that is larger (the basic values solve a
    // system with that matrix: its rounding errors are the precision's)
    let cond = max_basis_condition(problem, path);
    let tol = Tol {
        residual: tol.residual.max(10.0 * T::eps().to_f64() * cond),
        ..tol
    };
    let mut points = Vec::new();
    for l in sample_lambdas(path, frac) {
        let pt = path
            .at(l)
            .ok_or_else(|| format!("path.at({}) is None inside the traced range", l.to_f64()))?;
        let res = residual(problem, &pt);
        if res.worst() > tol.residual {
            return Err(format!(
                "residual at L = {} is {res:?} (tol {:e})",
                l.to_f64(),
                tol.residual
            ));
        }
        points.push(pt);
    }
    // the end is a solution unless the status says there is none there
    // (infeasible) or that this precision cannot tell (ill-conditioned)
    if !matches!(path.status, Status::Infeasible | Status::IllConditioned) {
        let res = residual(problem, &path.end);
        if res.worst() > tol.residual {
            return Err(format!(
                "residual at the end L = {} is {res:?} (tol {:e})",
                path.end.lambda.to_f64(),
                tol.residual
            ));
        }
        if path.status == Status::UnboundedRay {
            // the end is where the ray starts; lambda_reached is infinite
            let last = path.segments.last().expect("checked above");
            if !near(path.end.lambda, last.lambda_from) {
                return Err(format!(
                    "UnboundedRay: end.lambda = {} is not the start {} of the last segment",
                    path.end.lambda.to_f64(),
                    last.lambda_from.to_f64()
                ));
            }
            if path.lambda_reached.to_f64() < path.end.lambda.to_f64() {
                return Err("UnboundedRay: lambda_reached below the ray's start".into());
            }
        } else if !near(path.end.lambda, path.lambda_reached) {
            return Err(format!(
                "end.lambda = {} != lambda_reached = {}",
                path.end.lambda.to_f64(),
                path.lambda_reached.to_f64()
            ));
        }
        points.push(path.end.clone());
        if path.info.residual.worst() > tol.residual {
            return Err(format!(
                "the path reports residual {:?} (tol {:e})",
                path.info.residual, tol.residual
            ));
        }
        // and where the delivered path comes near the tolerance, the report is
        // not a gross underestimate of its residual at the breakpoints (the ends
        // of the segments) and the end
        let mut at_breakpoints = residual(problem, &path.end).worst();
        for s in &path.segments {
            at_breakpoints = at_breakpoints.max(residual(problem, &s.eval(s.lambda_from)).worst());
            if !s.unbounded {
                at_breakpoints =
                    at_breakpoints.max(residual(problem, &s.eval(s.lambda_to)).worst());
            }
        }
        if at_breakpoints > 0.1 * tol.residual && path.info.residual.worst() < 0.01 * at_breakpoints
        {
            return Err(format!(
                "the path reports residual {:?}, but at its breakpoints it is {at_breakpoints:e}",
                path.info.residual
            ));
        }
    }
    // outside the traced range there is no point
    let below = problem.lambda0() - T::one();
    if path.at(below).is_some() && path.info.turning_points == 0 {
        return Err(format!("path.at({}) below lambda0 is Some", below.to_f64()));
    }
    if path.status != Status::UnboundedRay {
        let beyond = path.lambda_reached + T::one() + path.lambda_reached.abs();
        if path.at(beyond).is_some() {
            return Err(format!(
                "path.at({}) beyond lambda_reached is Some",
                beyond.to_f64()
            ));
        }
    }
    Ok(points)
}
