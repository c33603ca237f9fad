//! The sparse JSON input (`plcp::io::sparse_json`) through the library and the
//! command line, checked against the dense solve of the same obstacle problem
//! (cold start, block basis: an independent route to the same path).

use faer::{Col, Mat};
use plcp::io::sparse_json::parse_sparse;
use plcp::{Plcp, Settings, Var};
use std::path::PathBuf;

use crate::common::cli;

/// The 5-point Laplacian on an `nx x nx` grid, a bowl obstacle `psi < 0`:
/// `(triplets, q, d)` of `w = A psi + L h^2 1 + A z`.
type Triplets = Vec<(usize, usize, f64)>;

fn obstacle(nx: usize) -> (Triplets, Vec<f64>, Vec<f64>) {
    let n = nx * nx;
    let h = 1.0 / (nx as f64 + 1.0);
    let id = |i: usize, j: usize| i * nx + j;
    let mut t = Vec::new();
    for i in 0..nx {
        for j in 0..nx {
            t.push((id(i, j), id(i, j), 4.0));
            for (a, b) in [
                (i.wrapping_sub(1), j),
                (i + 1, j),
                (i, j.wrapping_sub(1)),
                (i, j + 1),
            ] {
                if a < nx && b < nx {
                    t.push((id(i, j), id(a, b), -1.0));
                }
            }
        }
    }
    let psi: Vec<f64> = (0..n)
        .map(|k| {
            let (x, y) = (
                (k / nx + 1) as f64 * h - 0.5,
                (k % nx + 1) as f64 * h - 0.5 + 0.03,
            );
            -0.05 - 0.5 * (x * x + y * y)
        })
        .collect();
    let mut q = vec![0.0; n];
    for &(i, j, v) in &t {
        q[i] += v * psi[j];
    }
    (t, q, vec![h * h; n])
}

fn json_triplets(t: &[(usize, usize, f64)], q: &[f64], d: &[f64], n: usize) -> String {
    let ts: Vec<String> = t.iter().map(|(i, j, v)| format!("[{i},{j},{v}]")).collect();
    format!(
        "{{\"M_sparse\":{{\"order\":{n},\"triplets\":[{}]}},\"q\":{q:?},\"d\":{d:?},\"lambda_max\":3,\"warm_basis\":\"z\",\"comment\":\"obstacle\"}}",
        ts.join(",")
    )
}

fn json_csc(t: &[(usize, usize, f64)], q: &[f64], d: &[f64], n: usize) -> String {
    let mut cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
    for &(i, j, v) in t {
        cols[j].push((i, v));
    }
    let mut ptr = vec![0];
    let (mut rows, mut vals) = (Vec::new(), Vec::new());
    for c in &cols {
        for &(i, v) in c {
            rows.push(i);
            vals.push(v);
        }
        ptr.push(rows.len());
    }
    format!(
        "{{\"M_sparse\":{{\"order\":{n},\"csc\":{{\"col_ptr\":{ptr:?},\"row_idx\":{rows:?},\"values\":{vals:?}}}}},\"q\":{q:?},\"d\":{d:?},\"lambda_max\":3,\"warm_basis\":\"z\"}}"
    )
}

fn dense_breakpoints(t: &[(usize, usize, f64)], q: &[f64], d: &[f64], n: usize) -> Vec<f64> {
    let mut m = Mat::<f64>::zeros(n, n);
    for &(i, j, v) in t {
        m[(i, j)] += v;
    }
    let p = Plcp::new(
        m.as_ref(),
        Col::from_fn(n, |i| q[i]).as_ref(),
        Col::from_fn(n, |i| d[i]).as_ref(),
    )
    .unwrap()
    .with_range(0.0, Some(3.0))
    .unwrap();
    let path = plcp::solve(&p, &Settings::default()).unwrap();
    assert!(path.status.is_success());
    path.breakpoints.iter().map(|b| b.lambda).collect()
}

fn scratch(name: &str, content: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("sparse-input");
    std::fs::create_dir_all(&dir).unwrap();
    let f = dir.join(name);
    std::fs::write(&f, content).unwrap();
    f
}

/// The breakpoints of the dense cold start include the start phase's ones at
/// `L = 0` (none here: the warm start begins where the cold start arrives) and
/// those where contacts form; both routes must agree.
fn close(a: &[f64], b: &[f64]) {
    let a: Vec<f64> = a.iter().copied().filter(|l| *l > 0.0).collect();
    let b: Vec<f64> = b.iter().copied().filter(|l| *l > 0.0).collect();
    assert_eq!(a.len(), b.len(), "{a:?} vs {b:?}");
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() <= 1e-10 * x.abs().max(1.0), "{x} vs {y}");
    }
}

#[test]
fn triplets_and_csc_give_the_dense_path() {
    let nx = 7;
    let n = nx * nx;
    let (t, q, d) = obstacle(nx);
    let dense = dense_breakpoints(&t, &q, &d, n);
    assert!(dense.iter().filter(|l| **l > 0.0).count() >= 3);
    for text in [json_triplets(&t, &q, &d, n), json_csc(&t, &q, &d, n)] {
        let (p, warm) = parse_sparse::<f64>(text.as_bytes(), "obstacle.json").unwrap();
        assert!(p.is_sparse());
        assert_eq!(
            warm.as_deref(),
            Some(&(0..n).map(Var::Z).collect::<Vec<_>>()[..])
        );
        let s = Settings {
            basis: plcp::BasisKind::Sparse,
            warm_basis: warm,
            ..Settings::default()
        };
        let path = plcp::solve(&p, &s).unwrap();
        assert!(path.info.warm_start);
        let lib: Vec<f64> = path.breakpoints.iter().map(|b| b.lambda).collect();
        close(&lib, &dense);
        // the command line
        let f = scratch("obstacle.json", &text);
        let v = cli::solve(&f);
        assert_eq!(v["status"], "reached");
        let cli: Vec<f64> = v["breakpoints"]
            .as_array()
            .unwrap()
            .iter()
            .map(|b| b["lambda"].as_f64().unwrap())
            .collect();
        close(&cli, &dense);
        assert_eq!(v["segments"].as_array().map_or(0, |s| s.len()), 0);
    }
}

#[test]
fn bad_sparse_input_is_named() {
    let cases = [
        (
            r#"{"M_sparse": {"order": 2, "triplets": [[0, 2, 1]]}, "q": [1, 1], "d": [0, 0]}"#,
            "outside the order 2",
        ),
        (
            r#"{"M_sparse": {"order": 2, "triplets": [[0, 0, "x"]]}, "q": [1, 1], "d": [0, 0]}"#,
            "line 1",
        ),
        (
            r#"{"M_sparse": {"order": 2, "csc": {"col_ptr": [0, 2], "row_idx": [0], "values": [1]}}, "q": [1, 1], "d": [0, 0]}"#,
            "col_ptr",
        ),
        (
            r#"{"M_sparse": {"order": 2, "triplets": []}, "q": [1, 1], "d": [0, 0], "warm": "z"}"#,
            "unknown field",
        ),
        (
            r#"{"M_sparse": {"order": 2, "triplets": []}, "q": [1, 1], "d": [0, 0], "warm_basis": "y"}"#,
            "warm_basis",
        ),
        (
            r#"{"M_sparse": {"order": 2, "triplets": []}, "q": [1], "d": [0, 0]}"#,
            "q",
        ),
    ];
    for (text, needle) in cases {
        let e = parse_sparse::<f64>(text.as_bytes(), "bad.json").unwrap_err();
        assert!(e.to_string().contains(needle), "{e} lacks {needle}");
    }
}
