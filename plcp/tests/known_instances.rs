//! Known instances with known answers, and every status and error, in f32, f64
//! and fx128.
//!
//! * Murty's exponential example (Murty 1988, ch. 6; Siconos `exp_murty2` is
//!   n = 6): `M` upper triangular with 1 on the diagonal and 2 above,
//!   `q_i = -(2^(n+1) - 2^(i+1))`. Lemke's method with covering vector `e` takes
//!   exactly `2^n` pivots (counting the pivot where the artificial variable enters
//!   and the one where it leaves; a textbook lexicographic Lemke in
//!   `common::lemke_reference` confirms the count). As a PLCP (`q + (a+1) e`,
//!   `d = -e`, `a = 2^(n+1) - 2`) the unique solution path has `2^n - 1`
//!   breakpoints, at `L = 1, 3, 5, ...` (confirmed by enumeration).
//! * Kostreva's (1979) cycling example `M = [[1,2,0],[0,1,2],[2,0,1]]`, `q = -e`
//!   (and its transpose): ties in every ratio test of the first steps. As an LCP
//!   and in PLCP forms with three-way ties at a breakpoint and at the start.
//!   The path must end with the right solution, and no basis may repeat (the
//!   sequence of complementary bases rebuilt from the breakpoints is free of
//!   duplicates).
//! * Cottle-Pang-Stone (2009) examples 4.4.7 (nonsymmetric, unique solution
//!   (0, 1, 3)), remark 4.1.14 (PSD singular, z1 + z2 = 1), 4.4.16 (PSD singular,
//!   w = 0), 4.4.23 (a bimatrix game: Lemke with covering vector e ends on a
//!   secondary ray), the fully degenerate QP-type instances of the Siconos
//!   corpus `CPS_4`, `CPS_4bis`; Murty's textbook examples 2.8, 2.10 (solved) and
//!   2.2, 2.9 (no solution: a secondary ray).
//! * Statuses on tiny problems: reached, unbounded ray, secondary ray,
//!   infeasible, pivot limit; invalid settings and bad input are `Err`s naming the
//!   input.
//!
//! Tolerances (absolute on these O(1)..O(256) integer-data problems, relative
//! where stated): f64 1e-10, f32 1e-3, fx128 1e-26.

use crate::common;

use common::*;
use faer::{Col, Mat};
use plcp::residual::residual;
use plcp::{Lcp, Plcp, PlcpError, Point, Scalar, Settings, Status, Var};

// ---------------------------------------------------------------- helpers

fn tol<T: Scalar>() -> f64 {
    match T::NAME {
        "f32" => 1e-3,
        "f64" => 1e-10,
        _ => 1e-26,
    }
}

fn path_tol<T: Scalar>() -> Tol {
    match T::NAME {
        "f32" => Tol {
            residual: 2e-5,
            forward: 1e-3,
            enum_feas: 1e-5,
            lambda: 1e-5,
        },
        "f64" => Tol {
            residual: 1e-12,
            forward: 1e-10,
            enum_feas: 1e-10,
            lambda: 1e-12,
        },
        _ => Tol {
            residual: 1e-28,
            forward: 1e-26,
            enum_feas: 1e-26,
            lambda: 1e-28,
        },
    }
}

fn lcp<T: Scalar>(m: &Mat<f64>, q: &[f64]) -> Lcp<T> {
    let mt = mat_t::<T>(m.as_ref());
    let qt = col_t::<T>(q);
    Lcp::new(mt.as_ref(), qt.as_ref()).unwrap()
}

fn plcp_of<T: Scalar>(m: &Mat<f64>, q: &[f64], d: &[f64], lambda_max: Option<f64>) -> Plcp<T> {
    let mt = mat_t::<T>(m.as_ref());
    let qt = col_t::<T>(q);
    let dt = col_t::<T>(d);
    Plcp::new(mt.as_ref(), qt.as_ref(), dt.as_ref())
        .unwrap()
        .with_range(T::zero(), lambda_max.map(T::from_f64))
        .unwrap()
}

fn assert_close<T: Scalar>(what: &str, got: &Col<T>, want: &[f64], tol: f64) {
    assert_eq!(got.nrows(), want.len(), "{what}: length");
    for i in 0..want.len() {
        let g = got[i].to_f64();
        assert!(
            (g - want[i]).abs() <= tol * want[i].abs().max(1.0),
            "[{}] {what}[{i}] = {g}, expected {} (tol {tol:e}); got {:?}",
            T::NAME,
            want[i],
            col_f64(got.as_ref())
        );
    }
}

/// The LCP residual of a solution `z, w` of `w = q + M z`, through the PLCP residual at L = 0.
fn lcp_residual<T: Scalar>(l: &Lcp<T>, z: &Col<T>, w: &Col<T>) -> f64 {
    let n = l.n();
    let zero = Col::<T>::zeros(n);
    let p = Plcp::new(l.m(), l.q(), zero.as_ref()).unwrap();
    residual(
        &p,
        &Point {
            lambda: T::zero(),
            z: z.clone(),
            w: w.clone(),
            u: Col::zeros(0),
        },
    )
    .worst()
}

/// Rebuilds the sequence of complementary bases from the breakpoints, starting
/// from the all-`w` basis (valid when `q + lambda0 d >= 0`): every breakpoint
/// must swap a basic variable for its complement, and no basis may repeat. The
/// segments' bases must appear in the sequence, in order.
fn check_no_repeated_basis<T: Scalar>(path: &plcp::Path<T>, n: usize) {
    let mut basis: Vec<Var> = (0..n).map(Var::W).collect();
    let mut seq = vec![basis.clone()];
    for (k, bp) in path.breakpoints.iter().enumerate() {
        let pos = basis
            .iter()
            .position(|v| *v == bp.leaving)
            .unwrap_or_else(|| {
                panic!(
                    "breakpoint {k}: leaving {} is not basic in {basis:?}",
                    bp.leaving
                )
            });
        assert_eq!(
            Some(bp.entering),
            bp.leaving.complement(),
            "breakpoint {k}: {} enters for {} (not its complement) on a P-matrix problem",
            bp.entering,
            bp.leaving
        );
        basis[pos] = bp.entering;
        assert!(
            !seq.iter().any(|b| {
                let mut a = b.clone();
                let mut c = basis.clone();
                a.sort();
                c.sort();
                a == c
            }),
            "[{}] breakpoint {k} returns to the basis {basis:?}: the path cycles",
            T::NAME
        );
        seq.push(basis.clone());
    }
    let sorted = |b: &Vec<Var>| {
        let mut b = b.clone();
        b.sort();
        b
    };
    let seq_sorted: Vec<Vec<Var>> = seq.iter().map(sorted).collect();
    let mut from = 0;
    for (k, s) in path.segments.iter().enumerate() {
        let b = sorted(&s.basis);
        let at = seq_sorted[from..]
            .iter()
            .position(|x| *x == b)
            .unwrap_or_else(|| {
                panic!(
                    "segment {k}'s basis {b:?} is not in the sequence rebuilt from the breakpoints"
                )
            });
        from += at;
    }
}

macro_rules! in_three_precisions {
    ($($name:ident => $f:ident;)*) => {
        mod f32_ { use super::*; $( #[test] fn $name() { $f::<f32>(); } )* }
        mod f64_ { use super::*; $( #[test] fn $name() { $f::<f64>(); } )* }
        mod f128 { use super::*; $( #[test] fn $name() { $f::<faer::fx128>(); } )* }
    };
}

in_three_precisions! {
    murty_lemke_takes_2_pow_n_pivots => murty_lcp;
    murty_parametric_path_has_2_pow_n_minus_1_breakpoints => murty_plcp;
    murty_pivot_limit => pivot_limit;
    kostreva_lcp_terminates_with_the_solution => kostreva_lcp;
    kostreva_three_way_tie_at_a_breakpoint => kostreva_tie_at_breakpoint;
    kostreva_three_way_tie_at_the_start => kostreva_tie_at_start;
    kostreva_start_phase_then_path => kostreva_start_phase;
    cps_textbook_examples => cps_examples;
    cps4_fully_degenerate => cps4_degenerate;
    murty_textbook_examples => murty_textbook;
    secondary_ray_beyond_l_star => secondary_ray;
    unbounded_ray_and_reached => unbounded_and_reached;
    infeasible_at_start => infeasible_start;
    widely_scaled_d_keeps_every_breakpoint => widely_scaled_d;
    invalid_settings_are_errors => invalid_settings;
    construction_errors_name_the_input => construction_errors;
}

// ---------------------------------------------------------------- Murty

fn murty_lcp<T: Scalar>() {
    for n in 1..=8 {
        let m = murty_matrix(n);
        let q = murty_q(n);
        // the oracle agrees on the count
        let reference = lemke_reference(m.as_ref(), &q, 1 << 12);
        assert!(reference.solved);
        assert_eq!(reference.pivots, 1 << n, "reference Lemke on Murty n = {n}");
        let l = lcp::<T>(&m, &q);
        let sol = plcp::solve_lcp(&l, &Settings::default()).unwrap();
        assert_eq!(
            sol.status,
            Status::Reached,
            "[{}] n = {n}: {}",
            T::NAME,
            sol.message
        );
        assert_eq!(
            sol.info.pivots,
            1 << n,
            "[{}] Murty n = {n}: Lemke with covering vector e takes 2^n pivots",
            T::NAME
        );
        let mut want = vec![0.0; n];
        want[n - 1] = (1u64 << n) as f64;
        assert_close("z", &sol.z, &want, tol::<T>());
        assert!(lcp_residual(&l, &sol.z, &sol.w) <= tol::<T>());
    }
}

fn murty_plcp_instance(n: usize) -> (Mat<f64>, Vec<f64>, Vec<f64>, f64) {
    let m = murty_matrix(n);
    let q = murty_q(n);
    let a = ((1u64 << (n + 1)) - 2) as f64;
    let q0: Vec<f64> = q.iter().map(|v| v + a + 1.0).collect();
    (m, q0, vec![-1.0; n], a + 1.0)
}

#[test]
fn oracle_murty_parametric_breakpoints_are_at_odd_integers() {
    for n in 1..=5 {
        let (m, q0, d, lmax) = murty_plcp_instance(n);
        let qc = Col::from_fn(n, |i| q0[i]);
        let dc = Col::from_fn(n, |i| d[i]);
        let support = |l: f64| -> Vec<bool> {
            let s = enumerate(m.as_ref(), qc.as_ref(), dc.as_ref(), 0, l, 1e-12);
            assert_eq!(s.len(), 1);
            (0..n).map(|i| s[0].z[i] > 1e-9).collect()
        };
        let mut changes = 0;
        let mut k = 0.0;
        while k + 0.75 < lmax {
            // the support changes across each odd integer and nowhere between
            let (a, b, c) = (support(k + 0.25), support(k + 0.75), support(k + 1.25));
            assert_eq!(a, b);
            if k + 1.0 < lmax {
                assert_ne!(b, c, "n = {n}: no breakpoint at L = {}", k + 1.0);
                changes += 1;
            }
            k += 2.0;
        }
        assert_eq!(changes, (1 << n) - 1);
    }
}

fn murty_plcp<T: Scalar>() {
    for n in 1..=8 {
        let (m, q0, d, lmax) = murty_plcp_instance(n);
        let p = plcp_of::<T>(&m, &q0, &d, Some(lmax));
        let path = plcp::solve(&p, &Settings::default()).unwrap();
        assert_eq!(
            path.status,
            Status::Reached,
            "[{}] n = {n}: {}",
            T::NAME,
            path.message
        );
        check_path(&p, &path, path_tol::<T>(), 0.3, Continuity::All, true)
            .unwrap_or_else(|e| panic!("[{}] Murty PLCP n = {n}: {e}", T::NAME));
        assert_eq!(
            path.breakpoints.len(),
            (1 << n) - 1,
            "[{}] Murty PLCP n = {n}: breakpoints",
            T::NAME
        );
        for (k, bp) in path.breakpoints.iter().enumerate() {
            let want = (2 * k + 1) as f64;
            assert!(
                (bp.lambda.to_f64() - want).abs() <= tol::<T>() * want,
                "[{}] n = {n}: breakpoint {k} at {} (expected {want})",
                T::NAME,
                bp.lambda.to_f64()
            );
            assert!(!bp.degenerate && !bp.turning);
        }
        assert_eq!(path.segments.len(), 1 << n);
        let mut want = vec![0.0; n];
        want[n - 1] = (1u64 << n) as f64;
        assert_close("end z", &path.end.z, &want, tol::<T>());
        check_no_repeated_basis(&path, n);
    }
}

fn pivot_limit<T: Scalar>() {
    let n = 6;
    let (m, q0, d, lmax) = murty_plcp_instance(n);
    let p = plcp_of::<T>(&m, &q0, &d, Some(lmax));
    let settings = Settings::<T> {
        max_pivots: Some(5),
        ..Settings::default()
    };
    let path = plcp::solve(&p, &settings).unwrap();
    assert_eq!(
        path.status,
        Status::PivotLimit,
        "[{}] {}",
        T::NAME,
        path.message
    );
    assert!(
        path.info.pivots <= 5,
        "{} pivots with max_pivots = 5",
        path.info.pivots
    );
    assert!(path.lambda_reached.to_f64() < lmax);
    assert!(
        path.lambda_reached.to_f64() >= 4.0,
        "five pivots pass L = 1, 3, 5, 7, 9"
    );
    // what was traced is right
    let pt = path.at(path.lambda_reached).unwrap();
    assert!(residual(&p, &pt).worst() <= path_tol::<T>().residual);
    check_path(&p, &path, path_tol::<T>(), 0.5, Continuity::All, true).unwrap();
    // and the LCP form
    let l = lcp::<T>(&m, &murty_q(n));
    let sol = plcp::solve_lcp(&l, &settings).unwrap();
    assert_eq!(
        sol.status,
        Status::PivotLimit,
        "[{}] solve_lcp: {}",
        T::NAME,
        sol.message
    );
}

// ---------------------------------------------------------------- Kostreva

fn kostreva_matrices() -> [Mat<f64>; 2] {
    let k = kostreva_matrix();
    let kt = Mat::from_fn(3, 3, |i, j| k[(j, i)]);
    [k, kt]
}

#[test]
fn oracle_reference_lemke_does_not_cycle_on_kostreva() {
    for m in kostreva_matrices() {
        let r = lemke_reference(m.as_ref(), &[-1.0; 3], 100);
        assert!(r.solved);
        for a in 0..r.bases.len() {
            for b in a + 1..r.bases.len() {
                assert_ne!(r.bases[a], r.bases[b]);
            }
        }
        for z in r.z {
            assert!((z - 1.0 / 3.0).abs() < 1e-15);
        }
    }
}

fn kostreva_lcp<T: Scalar>() {
    for m in kostreva_matrices() {
        let l = lcp::<T>(&m, &[-1.0; 3]);
        let sol = plcp::solve_lcp(&l, &Settings::default()).unwrap();
        assert_eq!(sol.status, Status::Reached, "[{}] {}", T::NAME, sol.message);
        assert_close("z", &sol.z, &[1.0 / 3.0; 3], tol::<T>());
        assert_close("w", &sol.w, &[0.0; 3], tol::<T>());
        assert!(
            sol.info.pivots <= 20,
            "{} pivots for n = 3",
            sol.info.pivots
        );
    }
}

/// `q = e`, `d = -e`: all three `w` reach zero together at `L = 1`; beyond it
/// `z = (L - 1)/3 e`, `w = 0`.
fn kostreva_tie_at_breakpoint<T: Scalar>() {
    for m in kostreva_matrices() {
        let p = plcp_of::<T>(&m, &[1.0; 3], &[-1.0; 3], None);
        let path = plcp::solve(&p, &Settings::default()).unwrap();
        assert_eq!(
            path.status,
            Status::UnboundedRay,
            "[{}] {}",
            T::NAME,
            path.message
        );
        check_path(&p, &path, path_tol::<T>(), 0.4, Continuity::All, true)
            .unwrap_or_else(|e| panic!("[{}] {e}", T::NAME));
        check_no_repeated_basis(&path, 3);
        for bp in &path.breakpoints {
            assert!((bp.lambda.to_f64() - 1.0).abs() <= tol::<T>());
        }
        let last = path.segments.last().unwrap();
        let mut b = last.basis.clone();
        b.sort();
        assert_eq!(b, vec![Var::Z(0), Var::Z(1), Var::Z(2)]);
        for l in [1.0, 1.5, 4.0, 100.0] {
            let pt = path.at(T::from_f64(l)).unwrap();
            assert_close("z", &pt.z, &[(l - 1.0) / 3.0; 3], tol::<T>());
            assert_close("w", &pt.w, &[0.0; 3], tol::<T>());
        }
        let pt = path.at(T::from_f64(0.5)).unwrap();
        assert_close("z", &pt.z, &[0.0; 3], tol::<T>());
        assert_close("w", &pt.w, &[0.5; 3], tol::<T>());
    }
}

/// `q = 0`, `d = -e`: fully degenerate from the start value on.
fn kostreva_tie_at_start<T: Scalar>() {
    for m in kostreva_matrices() {
        let p = plcp_of::<T>(&m, &[0.0; 3], &[-1.0; 3], Some(6.0));
        let path = plcp::solve(&p, &Settings::default()).unwrap();
        assert_eq!(
            path.status,
            Status::Reached,
            "[{}] {}",
            T::NAME,
            path.message
        );
        check_path(&p, &path, path_tol::<T>(), 0.4, Continuity::All, true)
            .unwrap_or_else(|e| panic!("[{}] {e}", T::NAME));
        check_no_repeated_basis(&path, 3);
        assert_close("end z", &path.end.z, &[2.0; 3], tol::<T>());
        assert_close("end w", &path.end.w, &[0.0; 3], tol::<T>());
    }
}

/// `q = -e`, `d = -e`: the start phase solves Kostreva's LCP at `L = 0` (the
/// cycling instance), then the path continues: `z = (1 + L)/3 e`.
fn kostreva_start_phase<T: Scalar>() {
    for m in kostreva_matrices() {
        let p = plcp_of::<T>(&m, &[-1.0; 3], &[-1.0; 3], Some(2.0));
        let path = plcp::solve(&p, &Settings::default()).unwrap();
        assert_eq!(
            path.status,
            Status::Reached,
            "[{}] {}",
            T::NAME,
            path.message
        );
        check_path(&p, &path, path_tol::<T>(), 0.4, Continuity::All, true)
            .unwrap_or_else(|e| panic!("[{}] {e}", T::NAME));
        assert!(path.info.start_pivots > 0, "q < 0 needs the start phase");
        for l in [0.0, 1.0, 2.0] {
            let pt = path.at(T::from_f64(l)).unwrap();
            assert_close("z", &pt.z, &[(1.0 + l) / 3.0; 3], tol::<T>());
        }
        // d = 0: the start phase alone, the solution constant in L
        let p0 = plcp_of::<T>(&m, &[-1.0; 3], &[0.0; 3], None);
        let path0 = plcp::solve(&p0, &Settings::default()).unwrap();
        assert_eq!(
            path0.status,
            Status::UnboundedRay,
            "[{}] {}",
            T::NAME,
            path0.message
        );
        let pt = path0.at(T::from_f64(10.0)).unwrap();
        assert_close("z", &pt.z, &[1.0 / 3.0; 3], tol::<T>());
    }
}

// ---------------------------------------------------------------- Cottle-Pang-Stone, Murty

fn solve_lcp_checked<T: Scalar>(
    name: &str,
    rows: Vec<Vec<f64>>,
    q: &[f64],
) -> plcp::LcpSolution<T> {
    let m = mat_from_rows(&rows);
    let l = lcp::<T>(&m, q);
    let sol = plcp::solve_lcp(&l, &Settings::default()).unwrap();
    if sol.status == Status::Reached {
        let r = lcp_residual(&l, &sol.z, &sol.w);
        assert!(r <= tol::<T>(), "[{}] {name}: residual {r:e}", T::NAME);
    }
    sol
}

fn cps_examples<T: Scalar>() {
    let t = tol::<T>();
    // CPS 2009 example 4.4.7: nonsymmetric, indefinite; unique solution (0, 1, 3)
    let s = solve_lcp_checked::<T>(
        "CPS 4.4.7",
        vec![vec![0., -1., 2.], vec![2., 0., -2.], vec![-1., 1., 0.]],
        &[-3., 6., -1.],
    );
    assert_eq!(s.status, Status::Reached, "CPS 4.4.7: {}", s.message);
    assert_close("CPS 4.4.7 z", &s.z, &[0., 1., 3.], t);
    // remark 4.1.14: PSD singular, the solutions are z1 + z2 = 1
    let s = solve_lcp_checked::<T>("CPS 4.1.14", vec![vec![1., 1.], vec![1., 1.]], &[-1., -1.]);
    assert_eq!(s.status, Status::Reached, "CPS 4.1.14: {}", s.message);
    assert!((s.z[0].to_f64() + s.z[1].to_f64() - 1.0).abs() <= t);
    assert_close("CPS 4.1.14 w", &s.w, &[0., 0.], t);
    // example 4.4.16: PSD singular, w = 0 and z2 = z1 + 1
    let s = solve_lcp_checked::<T>("CPS 4.4.16", vec![vec![1., -1.], vec![-1., 1.]], &[1., -1.]);
    assert_eq!(s.status, Status::Reached, "CPS 4.4.16: {}", s.message);
    assert!((s.z[1].to_f64() - s.z[0].to_f64() - 1.0).abs() <= t);
    assert_close("CPS 4.4.16 w", &s.w, &[0., 0.], t);
    // example 4.4.23, a bimatrix game: Lemke with covering vector e ends on a
    // secondary ray at once, although three solutions exist
    let s = solve_lcp_checked::<T>(
        "CPS 4.4.23",
        vec![
            vec![0., 0., 10., 20.],
            vec![0., 0., 30., 15.],
            vec![10., 20., 0., 0.],
            vec![30., 15., 0., 0.],
        ],
        &[-1.; 4],
    );
    assert_eq!(s.status, Status::SecondaryRay, "CPS 4.4.23: {}", s.message);
}

fn cps4_degenerate<T: Scalar>() {
    let rows = vec![
        vec![11., 0., 10., -1.],
        vec![0., 11., 10., -1.],
        vec![10., 10., 21., -1.],
        vec![1., 1., 1., 0.],
    ];
    let t = tol::<T>() * 10.0;
    let s = solve_lcp_checked::<T>("CPS_4", rows.clone(), &[50., 50., 10., -6.]);
    assert_eq!(s.status, Status::Reached, "CPS_4: {}", s.message);
    assert_close("CPS_4 z", &s.z, &[2., 2., 2., 92.], t);
    assert_close("CPS_4 w", &s.w, &[0.; 4], t * 92.0);
    let s = solve_lcp_checked::<T>("CPS_4bis", rows, &[50., 50., 23., -6.]);
    assert_eq!(s.status, Status::Reached, "CPS_4bis: {}", s.message);
    assert_close("CPS_4bis z", &s.z, &[3., 3., 0., 83.], t);
    assert_close("CPS_4bis w", &s.w, &[0.; 4], t * 83.0);
}

fn murty_textbook<T: Scalar>() {
    let t = tol::<T>();
    let s = solve_lcp_checked::<T>(
        "Murty 2.8",
        vec![
            vec![1., -1., -1., -1.],
            vec![-1., 1., -1., -1.],
            vec![1., 1., 2., 0.],
            vec![1., 1., 0., 2.],
        ],
        &[3., 5., -9., -5.],
    );
    assert_eq!(s.status, Status::Reached, "Murty 2.8: {}", s.message);
    assert_close("Murty 2.8 z", &s.z, &[2., 1., 3., 1.], t);
    let s = solve_lcp_checked::<T>(
        "Murty 2.10",
        vec![vec![1., 0., 0.], vec![2., 1., 0.], vec![2., 2., 1.]],
        &[-8., -12., -14.],
    );
    assert_eq!(s.status, Status::Reached, "Murty 2.10: {}", s.message);
    assert_close("Murty 2.10 z", &s.z, &[8., 0., 0.], t);
    assert_eq!(
        s.info.pivots, 8,
        "Murty 2.10 is the n = 3 exponential example: 2^3 pivots"
    );
    for (name, rows, q) in [
        (
            "Murty 2.2",
            vec![vec![-2., 1.], vec![1., -2.]],
            vec![-1., -1.],
        ),
        (
            "Murty 2.9",
            vec![vec![-1., 0., -3.], vec![1., -2., -5.], vec![-2., -1., -2.]],
            vec![-3., -2., -1.],
        ),
    ] {
        let s = solve_lcp_checked::<T>(name, rows, &q);
        assert_eq!(
            s.status,
            Status::SecondaryRay,
            "{name} has no solution: {}",
            s.message
        );
    }
}

// ---------------------------------------------------------------- statuses

/// `M = [0]`, `q = 1`, `d = -1`: `w = 1 - L` and `z` has no effect, so there is
/// no solution beyond `L* = 1`.
fn secondary_ray<T: Scalar>() {
    let m = mat_from_rows(&[vec![0.0]]);
    let p = plcp_of::<T>(&m, &[1.0], &[-1.0], None);
    let path = plcp::solve(&p, &Settings::default()).unwrap();
    assert_eq!(
        path.status,
        Status::SecondaryRay,
        "[{}] {}",
        T::NAME,
        path.message
    );
    assert!((path.lambda_reached.to_f64() - 1.0).abs() <= tol::<T>());
    assert!(path.ray.is_some());
    assert!(!path.status.is_success());
    assert_close("end w", &path.end.w, &[0.0], tol::<T>());
    let pt = path.at(T::from_f64(0.5)).unwrap();
    assert_close("w(0.5)", &pt.w, &[0.5], tol::<T>());
    assert!(path.at(T::from_f64(2.0)).is_none(), "no solution at L = 2");
    // with a finite lambda_max beyond L*: still the secondary ray
    let p = plcp_of::<T>(&m, &[1.0], &[-1.0], Some(5.0));
    let path = plcp::solve(&p, &Settings::default()).unwrap();
    assert_eq!(path.status, Status::SecondaryRay);
    // with lambda_max before L*: reached
    let p = plcp_of::<T>(&m, &[1.0], &[-1.0], Some(0.75));
    let path = plcp::solve(&p, &Settings::default()).unwrap();
    assert_eq!(path.status, Status::Reached);
    assert_close("end w", &path.end.w, &[0.25], tol::<T>());
}

/// `M = [1]`, `q = 1`, `d = -1`: `z = max(0, L - 1)`.
fn unbounded_and_reached<T: Scalar>() {
    let m = mat_from_rows(&[vec![1.0]]);
    let p = plcp_of::<T>(&m, &[1.0], &[-1.0], None);
    let path = plcp::solve(&p, &Settings::default()).unwrap();
    assert_eq!(
        path.status,
        Status::UnboundedRay,
        "[{}] {}",
        T::NAME,
        path.message
    );
    assert!(path.status.is_success());
    check_path(&p, &path, path_tol::<T>(), 0.5, Continuity::All, true).unwrap();
    assert_eq!(path.breakpoints.len(), 1);
    let bp = &path.breakpoints[0];
    assert!((bp.lambda.to_f64() - 1.0).abs() <= tol::<T>());
    assert_eq!((bp.entering, bp.leaving), (Var::Z(0), Var::W(0)));
    assert_eq!(path.segments.len(), 2);
    assert!(path.segments[1].unbounded);
    let pt = path.at(T::from_f64(1000.0)).unwrap();
    assert_close("z(1000)", &pt.z, &[999.0], tol::<T>());
    assert_close("w(1000)", &pt.w, &[0.0], tol::<T>());
    let ray = path.ray.as_ref().unwrap();
    assert!(ray.dlambda.to_f64() > 0.0);
    assert!((ray.dz[0].to_f64() / ray.dlambda.to_f64() - 1.0).abs() <= tol::<T>());
    // finite lambda_max
    let p = plcp_of::<T>(&m, &[1.0], &[-1.0], Some(3.0));
    let path = plcp::solve(&p, &Settings::default()).unwrap();
    assert_eq!(
        path.status,
        Status::Reached,
        "[{}] {}",
        T::NAME,
        path.message
    );
    assert!((path.lambda_reached.to_f64() - 3.0).abs() <= tol::<T>());
    assert_close("end z", &path.end.z, &[2.0], tol::<T>());
    assert!(path.at(T::from_f64(3.5)).is_none());
    // lambda0 above the breakpoint: the start phase finds z = L0 - 1 at once
    let mt = mat_t::<T>(m.as_ref());
    let p = Plcp::new(
        mt.as_ref(),
        col_t::<T>(&[1.0]).as_ref(),
        col_t::<T>(&[-1.0]).as_ref(),
    )
    .unwrap()
    .with_range(T::from_f64(2.0), Some(T::from_f64(4.0)))
    .unwrap();
    let path = plcp::solve(&p, &Settings::default()).unwrap();
    assert_eq!(path.status, Status::Reached);
    assert!(path.at(T::from_f64(1.5)).is_none(), "below lambda0");
    assert_close(
        "z(2)",
        &path.at(T::from_f64(2.0)).unwrap().z,
        &[1.0],
        tol::<T>(),
    );
    assert_close("end z", &path.end.z, &[3.0], tol::<T>());
}

/// `M = I`, `q = e`, `d = (-1, -1e-3)`: breakpoints at `L = 1` and `L = 1000`. A
/// slope a thousand times smaller than the other is far above any precision's
/// rounding (f32 included) and must not be taken for zero: missing the second
/// breakpoint would claim an unbounded ray on which `w1` goes negative.
fn widely_scaled_d<T: Scalar>() {
    let m = mat_from_rows(&[vec![1.0, 0.0], vec![0.0, 1.0]]);
    let p = plcp_of::<T>(&m, &[1.0, 1.0], &[-1.0, -1e-3], None);
    let path = plcp::solve(&p, &Settings::default()).unwrap();
    assert_eq!(
        path.status,
        Status::UnboundedRay,
        "[{}] {}",
        T::NAME,
        path.message
    );
    let ls: Vec<f64> = path.breakpoints.iter().map(|b| b.lambda.to_f64()).collect();
    assert_eq!(
        ls.len(),
        2,
        "[{}] breakpoints at {ls:?}, expected 1 and 1000",
        T::NAME
    );
    assert!((ls[0] - 1.0).abs() <= tol::<T>() && (ls[1] - 1000.0).abs() <= 1000.0 * tol::<T>());
    let pt = path.at(T::from_f64(3000.0)).unwrap();
    assert_close("z(3000)", &pt.z, &[2999.0, 2.0], tol::<T>());
    assert_close("w(3000)", &pt.w, &[0.0, 0.0], tol::<T>());
}

/// `M = [[0, 0], [0, 1]]`, `q = (-1, 1)`: row 0 reads `w0 = -1`, for every `L` (d = 0).
fn infeasible_start<T: Scalar>() {
    let m = mat_from_rows(&[vec![0.0, 0.0], vec![0.0, 1.0]]);
    let p = plcp_of::<T>(&m, &[-1.0, 1.0], &[0.0, 0.0], None);
    let path = plcp::solve(&p, &Settings::default()).unwrap();
    assert_eq!(
        path.status,
        Status::Infeasible,
        "[{}] {}",
        T::NAME,
        path.message
    );
    assert!(!path.status.is_success());
    assert!(path.at(T::from_f64(1.0)).is_none());
    let l = lcp::<T>(&m, &[-1.0, 1.0]);
    let s = plcp::solve_lcp(&l, &Settings::default()).unwrap();
    assert_eq!(
        s.status,
        Status::SecondaryRay,
        "[{}] {}",
        T::NAME,
        s.message
    );
}

// ---------------------------------------------------------------- errors

fn invalid_what<T: Scalar>(settings: Settings<T>, what: &str) {
    let m = mat_from_rows(&[vec![1.0, 0.0], vec![0.0, 1.0]]);
    let p = plcp_of::<T>(&m, &[1.0, -1.0], &[-1.0, 0.0], None);
    let l = lcp::<T>(&m, &[1.0, -1.0]);
    for r in [
        plcp::solve(&p, &settings).map(|_| ()),
        plcp::solve_lcp(&l, &settings).map(|_| ()),
    ] {
        match r {
            Err(PlcpError::Invalid { what: w, .. }) | Err(PlcpError::Dimension { what: w, .. }) => {
                assert_eq!(w, what)
            }
            other => panic!(
                "[{}] settings with a bad {what}: expected Err naming it, got {other:?}",
                T::NAME
            ),
        }
    }
}

fn invalid_settings<T: Scalar>() {
    let d = Settings::<T>::default;
    invalid_what(
        Settings {
            covering: Some(col_t::<T>(&[1.0, 1.0, 1.0])),
            ..d()
        },
        "covering vector",
    );
    invalid_what(
        Settings {
            covering: Some(col_t::<T>(&[1.0, 0.0])),
            ..d()
        },
        "covering vector",
    );
    invalid_what(
        Settings {
            covering: Some(col_t::<T>(&[1.0, f64::NAN])),
            ..d()
        },
        "covering vector",
    );
    invalid_what(
        Settings {
            pivot_tol_eps: f64::NAN,
            ..d()
        },
        "pivot_tol_eps",
    );
    invalid_what(
        Settings {
            tie_tol_eps: 0.0,
            ..d()
        },
        "tie_tol_eps",
    );
    invalid_what(
        Settings {
            max_cond_eps: -1.0,
            ..d()
        },
        "max_cond_eps",
    );
    invalid_what(
        Settings {
            refactor_period: Some(0),
            ..d()
        },
        "refactor_period",
    );
    invalid_what(
        Settings {
            max_pivots: Some(0),
            ..d()
        },
        "max_pivots",
    );
    // a valid covering vector other than e gives the same solution
    let m = mat_from_rows(&[vec![2.0, 1.0], vec![1.0, 2.0]]);
    let l = lcp::<T>(&m, &[-1.0, -1.0]);
    let s = plcp::solve_lcp(
        &l,
        &Settings {
            covering: Some(col_t::<T>(&[1.0, 3.0])),
            ..d()
        },
    )
    .unwrap();
    assert_eq!(s.status, Status::Reached);
    assert_close("z", &s.z, &[1.0 / 3.0, 1.0 / 3.0], tol::<T>());
}

fn construction_errors<T: Scalar>() {
    let m22 = mat_t::<T>(mat_from_rows(&[vec![1.0, 0.0], vec![0.0, 1.0]]).as_ref());
    let m23 = Mat::<T>::zeros(2, 3);
    let q2 = col_t::<T>(&[1.0, 1.0]);
    let q3 = col_t::<T>(&[1.0, 1.0, 1.0]);
    let dim_what = |r: Result<Plcp<T>, PlcpError>| match r {
        Err(e @ PlcpError::Dimension { .. }) => {
            let PlcpError::Dimension { ref what, .. } = e else {
                unreachable!()
            };
            assert!(e.to_string().contains(what.as_str()));
            what.clone()
        }
        other => panic!("expected a dimension error, got {other:?}"),
    };
    assert_eq!(
        dim_what(Plcp::new(m23.as_ref(), q2.as_ref(), q2.as_ref())),
        "M"
    );
    assert_eq!(
        dim_what(Plcp::new(m22.as_ref(), q3.as_ref(), q2.as_ref())),
        "q"
    );
    assert_eq!(
        dim_what(Plcp::new(m22.as_ref(), q2.as_ref(), q3.as_ref())),
        "d"
    );
    match Lcp::new(m22.as_ref(), q3.as_ref()) {
        Err(PlcpError::Dimension { what, .. }) => assert_eq!(what, "q"),
        other => panic!("{other:?}"),
    }
    // non-finite entries: which input, where
    let mut bad = m22.clone();
    bad[(1, 0)] = T::from_f64(f64::NAN);
    match Plcp::new(bad.as_ref(), q2.as_ref(), q2.as_ref()) {
        Err(e @ PlcpError::NonFinite { .. }) => {
            let PlcpError::NonFinite {
                ref what,
                ref position,
                ..
            } = e
            else {
                unreachable!()
            };
            assert_eq!((what.as_str(), position.as_str()), ("M", "(1, 0)"));
            assert!(e.to_string().contains("M") && e.to_string().contains("(1, 0)"));
        }
        other => panic!("{other:?}"),
    }
    let mut badq = q2.clone();
    badq[1] = T::from_f64(f64::INFINITY);
    match Plcp::new(m22.as_ref(), badq.as_ref(), q2.as_ref()) {
        Err(PlcpError::NonFinite { what, position, .. }) => {
            assert_eq!((what.as_str(), position.as_str()), ("q", "[1]"))
        }
        other => panic!("{other:?}"),
    }
    match Plcp::new(m22.as_ref(), q2.as_ref(), badq.as_ref()) {
        Err(PlcpError::NonFinite { what, position, .. }) => {
            assert_eq!((what.as_str(), position.as_str()), ("d", "[1]"))
        }
        other => panic!("{other:?}"),
    }
    match Lcp::new(bad.as_ref(), q2.as_ref()) {
        Err(PlcpError::NonFinite { what, .. }) => assert_eq!(what, "M"),
        other => panic!("{other:?}"),
    }
    // mixed: more free variables than the order
    match Plcp::mixed(m22.as_ref(), q2.as_ref(), q2.as_ref(), 3) {
        Err(PlcpError::Invalid { what, .. }) => assert_eq!(what, "free"),
        other => panic!("{other:?}"),
    }
    // ranges
    let ok = || Plcp::new(m22.as_ref(), q2.as_ref(), q2.as_ref()).unwrap();
    let range_what =
        |l0: f64, lm: Option<f64>| match ok().with_range(T::from_f64(l0), lm.map(T::from_f64)) {
            Err(PlcpError::Invalid { what, .. }) => what,
            other => panic!("range ({l0}, {lm:?}): expected Err, got {other:?}"),
        };
    assert_eq!(range_what(f64::NAN, None), "lambda0");
    assert_eq!(range_what(f64::INFINITY, None), "lambda0");
    assert_eq!(range_what(1.0, Some(0.5)), "lambda_max");
    assert_eq!(range_what(0.0, Some(f64::NAN)), "lambda_max");
    assert_eq!(range_what(0.0, Some(f64::NEG_INFINITY)), "lambda_max");
    let p = ok()
        .with_range(T::from_f64(-1.0), Some(T::from_f64(f64::INFINITY)))
        .unwrap();
    assert!(p.lambda_max().is_none(), "+inf means no end");
    assert_eq!(p.lambda0().to_f64(), -1.0);
}
