//! The sparse form ([`Plcp::mixed_sparse`], [`BasisKind::Sparse`]) against the
//! dense one: the same path (statuses, breakpoints with their entering and
//! leaving variables, segments) on seeded random problems, in f64 and fx128;
//! construction errors name the input.

use faer::{Col, Mat};
use plcp::matrix::Csc;
use plcp::{BasisKind, Method, Path, Plcp, PlcpError, Scalar, Settings};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A random mixed problem shaped like frames' system (9):
///
/// ```text
/// M = [ -D   -A'   0 ]   q = [ 0 ]   d = [ a ]
///     [ -A    0    T ]       [ 0 ]       [ 0 ]
///     [  0   -T'   0 ]       [ c ]       [ 0 ]
/// ```
///
/// with `D` diagonal positive (some entries zero when `massless`), `A` sparse,
/// square and diagonally dominant, `T` sparse with entries +-1 and `c > 0`:
/// the KKT system of a convex parametric QP, nonsingular free block.
fn system9(
    rng: &mut ChaCha8Rng,
    k: usize,
    np: usize,
    massless: bool,
) -> (Mat<f64>, Col<f64>, Col<f64>, usize) {
    let dim = 2 * k + np;
    let mut m = Mat::<f64>::zeros(dim, dim);
    for j in 0..k {
        let mass = if massless && j % 3 == 2 {
            0.0
        } else {
            rng.gen_range(0.5..2.0)
        };
        m[(j, j)] = -mass;
    }
    for r in 0..k {
        let mut a = vec![0.0; k];
        a[r] = rng.gen_range(3.0..5.0) * if rng.gen_bool(0.5) { 1.0 } else { -1.0 };
        for _ in 0..2 {
            let j = rng.gen_range(0..k);
            if j != r {
                a[j] = rng.gen_range(-1.0..1.0);
            }
        }
        for j in 0..k {
            if a[j] != 0.0 {
                m[(j, k + r)] = -a[j];
                m[(k + r, j)] = -a[j];
            }
        }
    }
    for c in 0..np {
        let r = c % k;
        let v = [1.0, -1.0][(c / k) % 2];
        m[(k + r, 2 * k + c)] = v;
        m[(2 * k + c, k + r)] = -v;
    }
    let q = Col::from_fn(dim, |i| {
        if i >= 2 * k {
            rng.gen_range(0.5..2.0)
        } else {
            0.0
        }
    });
    let d = Col::from_fn(dim, |i| if i < k { rng.gen_range(-1.0..1.0) } else { 0.0 });
    (m, q, d, 2 * k)
}

fn cast<T: Scalar>(m: &Mat<f64>, q: &Col<f64>, d: &Col<f64>) -> (Mat<T>, Col<T>, Col<T>) {
    (
        Mat::from_fn(m.nrows(), m.ncols(), |i, j| T::from_f64(m[(i, j)])),
        Col::from_fn(q.nrows(), |i| T::from_f64(q[i])),
        Col::from_fn(d.nrows(), |i| T::from_f64(d[i])),
    )
}

fn solve_both<T: Scalar>(
    m: &Mat<f64>,
    q: &Col<f64>,
    d: &Col<f64>,
    p: usize,
    method: Method,
    dense_basis: BasisKind,
) -> (Path<T>, Path<T>) {
    let (mt, qt, dt) = cast::<T>(m, q, d);
    let dense = Plcp::mixed(mt.as_ref(), qt.as_ref(), dt.as_ref(), p).unwrap();
    let sparse =
        Plcp::mixed_sparse(Csc::from_dense(mt.as_ref()), qt.as_ref(), dt.as_ref(), p).unwrap();
    assert!(sparse.is_sparse() && !dense.is_sparse());
    let mut s = Settings::<T>::with_method(method);
    s.basis = dense_basis;
    let a = plcp::solve(&dense, &s).unwrap();
    s.basis = BasisKind::Sparse;
    let b = plcp::solve(&sparse, &s).unwrap();
    (a, b)
}

/// Same status, same breakpoints (L within `tol` relative, same entering and
/// leaving variables), same segment bases, and small residuals on the sparse side.
fn same_path<T: Scalar>(what: &str, a: &Path<T>, b: &Path<T>, tol: f64) {
    assert_eq!(
        a.status, b.status,
        "{what}: status ({} / {})",
        a.message, b.message
    );
    assert_eq!(
        a.breakpoints.len(),
        b.breakpoints.len(),
        "{what}: number of breakpoints"
    );
    for (k, (x, y)) in a.breakpoints.iter().zip(&b.breakpoints).enumerate() {
        let (lx, ly) = (x.lambda.to_f64(), y.lambda.to_f64());
        assert!(
            (lx - ly).abs() <= tol * lx.abs().max(1.0),
            "{what}: breakpoint {k}: L {lx} vs {ly}"
        );
        assert_eq!(
            (x.entering, x.leaving),
            (y.entering, y.leaving),
            "{what}: breakpoint {k}"
        );
    }
    assert_eq!(
        a.segments.len(),
        b.segments.len(),
        "{what}: number of segments"
    );
    for (k, (x, y)) in a.segments.iter().zip(&b.segments).enumerate() {
        assert_eq!(x.basis, y.basis, "{what}: segment {k} basis");
        for i in 0..x.z_from.nrows() {
            let (u, v) = (x.z_from[i].to_f64(), y.z_from[i].to_f64());
            assert!(
                (u - v).abs() <= tol * u.abs().max(1.0),
                "{what}: segment {k} z[{i}] {u} vs {v}"
            );
        }
    }
    let res = b.info.residual.worst();
    assert!(res <= tol, "{what}: sparse residual {res:e}");
}

#[test]
fn random_system9_sparse_basis_matches_dense_and_block() {
    let mut rng = ChaCha8Rng::seed_from_u64(20261123);
    let mut successes = 0;
    for case in 0..40 {
        let k = rng.gen_range(2..25);
        let np = rng.gen_range(1..2 * k + 1);
        let massless = case % 2 == 1;
        let (m, q, d, p) = system9(&mut rng, k, np, massless);
        for kind in [BasisKind::Dense, BasisKind::Block] {
            let (a, b) = solve_both::<f64>(&m, &q, &d, p, Method::Wolfe, kind);
            same_path(
                &format!("case {case} (k = {k}, np = {np}) vs {kind:?}"),
                &a,
                &b,
                1e-9,
            );
            successes += usize::from(a.status.is_success());
        }
    }
    // massless coordinates can make the path end on a secondary ray (a
    // mechanism without mass); most instances must still be whole paths
    assert!(successes >= 50, "only {successes} of 80 paths succeeded");
}

#[test]
fn random_system9_in_fx128() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for case in 0..8 {
        let k = rng.gen_range(2..12);
        let np = rng.gen_range(1..2 * k + 1);
        let (m, q, d, p) = system9(&mut rng, k, np, case % 2 != 1);
        let (a, b) = solve_both::<faer::fx128>(&m, &q, &d, p, Method::Wolfe, BasisKind::Dense);
        same_path(&format!("fx128 case {case}"), &a, &b, 1e-24);
    }
}

/// Standard-form monotone problems (`p = 0`) by Lemke on a sparse `M`:
/// `M = B B' + S` with `B` sparse and `S` skew.
#[test]
fn random_standard_lemke_sparse_matches_dense() {
    let mut rng = ChaCha8Rng::seed_from_u64(99);
    for case in 0..30 {
        let n = rng.gen_range(2..30);
        let mut b = Mat::<f64>::zeros(n, n);
        let mut s = Mat::<f64>::zeros(n, n);
        for i in 0..n {
            b[(i, i)] = rng.gen_range(0.5..1.5);
            let j = rng.gen_range(0..n);
            b[(i, j)] += rng.gen_range(-1.0..1.0);
            let j = rng.gen_range(0..n);
            if j != i {
                let v = rng.gen_range(-1.0..1.0);
                s[(i, j)] += v;
                s[(j, i)] -= v;
            }
        }
        let m = &b * b.transpose() + &s;
        let q = Col::from_fn(n, |_| rng.gen_range(-1.0..1.0));
        let d = Col::from_fn(n, |_| rng.gen_range(-1.0..0.5));
        let (x, y) = solve_both::<f64>(&m, &q, &d, 0, Method::Lemke, BasisKind::Dense);
        same_path(&format!("standard case {case} (n = {n})"), &x, &y, 1e-9);
    }
}

#[test]
fn sparse_construction_errors_name_the_input() {
    let q = Col::<f64>::zeros(2);
    let d = Col::<f64>::zeros(2);
    // non-finite value, index out of range, non-square
    let e = Csc::try_from_triplets(2, 2, &[(0, 0, 1.0), (1, 1, f64::NAN)]).unwrap_err();
    assert!(
        matches!(&e, PlcpError::NonFinite { what, position, .. } if what == "M" && position == "(1, 1)"),
        "{e}"
    );
    let e = Csc::try_from_triplets(2, 2, &[(0, 2, 1.0)]).unwrap_err();
    assert!(
        matches!(&e, PlcpError::Dimension { found, .. } if found == "(0, 2)"),
        "{e}"
    );
    let e = Csc::<f64>::try_from_triplets(2, 2, &[(0, 0, f64::MAX), (0, 0, f64::MAX)]).unwrap_err();
    assert!(e.to_string().contains("duplicate"), "{e}");
    let rect = Csc::<f64>::try_from_triplets(2, 3, &[(0, 0, 1.0)]).unwrap();
    let e = Plcp::mixed_sparse(rect, q.as_ref(), d.as_ref(), 0).unwrap_err();
    assert!(
        matches!(&e, PlcpError::Dimension { what, .. } if what == "M (sparse)"),
        "{e}"
    );
    let m = Csc::<f64>::try_from_triplets(2, 2, &[(0, 0, 1.0)]).unwrap();
    let e =
        Plcp::mixed_sparse(m.clone(), Col::<f64>::zeros(3).as_ref(), d.as_ref(), 0).unwrap_err();
    assert!(
        matches!(&e, PlcpError::Dimension { what, .. } if what == "q"),
        "{e}"
    );
    let e =
        Plcp::mixed_sparse(m.clone(), q.as_ref(), Col::<f64>::zeros(1).as_ref(), 0).unwrap_err();
    assert!(
        matches!(&e, PlcpError::Dimension { what, .. } if what == "d"),
        "{e}"
    );
    let e = Plcp::mixed_sparse(m.clone(), q.as_ref(), d.as_ref(), 3).unwrap_err();
    assert!(
        matches!(&e, PlcpError::Invalid { what, .. } if what == "free"),
        "{e}"
    );
    let mut bad = q.clone();
    bad[1] = f64::INFINITY;
    let e = Plcp::mixed_sparse(m, bad.as_ref(), d.as_ref(), 0).unwrap_err();
    assert!(
        matches!(&e, PlcpError::NonFinite { what, .. } if what == "q"),
        "{e}"
    );
}

/// The sparse and dense forms are the same problem: same `m()`, same
/// residuals, same scaling, and `cast` keeps the form.
#[test]
fn sparse_problem_is_the_same_problem() {
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let (m, q, d, p) = system9(&mut rng, 6, 9, true);
    let dense = Plcp::mixed(m.as_ref(), q.as_ref(), d.as_ref(), p).unwrap();
    let sparse =
        Plcp::mixed_sparse(Csc::from_dense(m.as_ref()), q.as_ref(), d.as_ref(), p).unwrap();
    assert_eq!(dense.m(), sparse.m());
    let a = plcp::scaling::Equilibration::ruiz(&dense, 8);
    let b = plcp::scaling::Equilibration::ruiz(&sparse, 8);
    assert_eq!(
        (a.rows.clone(), a.cols.clone()),
        (b.rows.clone(), b.cols.clone())
    );
    assert_eq!(a.scale(&dense).unwrap().m(), b.scale(&sparse).unwrap().m());
    let c = sparse.cast::<faer::fx128>();
    assert!(c.is_sparse());
    let path = plcp::solve(&dense, &Settings::with_method(Method::Wolfe)).unwrap();
    let end = path.end.clone();
    assert_eq!(
        plcp::residual::residual(&dense, &end),
        plcp::residual::residual(&sparse, &end)
    );
}
