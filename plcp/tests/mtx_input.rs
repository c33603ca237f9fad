//! `M` handed over as a Matrix Market file (`plcp::io::mtx`): the problem
//! file names it (`"M": "m.mtx"`, `"M_sparse": "m.mtx"`), and the path traced
//! must be the one of the same `M` written inline, bit for bit, through the
//! library and the command line.

use plcp::io::json::parse_plcp;
use plcp::io::mtx::write_mtx_dense;
use plcp::io::sparse_json::parse_sparse;
use plcp::Settings;
use std::path::PathBuf;

use crate::common::cli;

fn dir(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("mtx-input")
        .join(name);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A dense P-matrix PLCP with awkward decimals (`M = B B'/n + I`, mixed-sign
/// `q`): entries that a reader rounding to a neighbouring `f64` would change.
fn instance(n: usize) -> (Vec<Vec<f64>>, Vec<f64>, Vec<f64>) {
    let b = |i: usize, j: usize| ((i * 31 + j * 17) as f64 * 0.618_033_988_749_895).sin();
    let m: Vec<Vec<f64>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    let s: f64 = (0..n).map(|k| b(i, k) * b(j, k)).sum::<f64>() / n as f64;
                    s + if i == j { 1.0 } else { 0.0 }
                })
                .collect()
        })
        .collect();
    let q = (0..n).map(|i| ((i as f64) * 1.3).cos() / 3.0).collect();
    let d = (0..n)
        .map(|i| -0.5 - ((i as f64) * 0.7).sin() / 7.0)
        .collect();
    (m, q, d)
}

/// The bytes `numpy.save` writes for a float64 matrix in C order (format 1.0).
fn npy_c_order(m: &[Vec<f64>]) -> Vec<u8> {
    let header = format!(
        "{{'descr': '<f8', 'fortran_order': False, 'shape': ({}, {}), }}",
        m.len(),
        m[0].len()
    );
    // the header is padded with spaces to a multiple of 64 bytes with the preamble
    let total = (10 + header.len() + 1).div_ceil(64) * 64;
    let padded = format!("{header:<width$}\n", width = total - 10 - 1);
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(padded.len() as u16).to_le_bytes());
    out.extend_from_slice(padded.as_bytes());
    for row in m {
        for v in row {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    out
}

/// The output without its timing (the only key that may differ).
fn without_timing(mut v: serde_json::Value) -> serde_json::Value {
    v.as_object_mut().unwrap().remove("timing");
    v
}

#[test]
fn dense_matrix_market_m_gives_the_inline_path_bit_for_bit() {
    let n = 12;
    let (m, q, d) = instance(n);
    let dir = dir("dense");
    let inline = format!(
        "{{\"M\": {m:?}, \"q\": {q:?}, \"d\": {d:?}, \"lambda_max\": 5, \"comment\": \"inline\"}}"
    );
    let values: Vec<f64> = (0..n).flat_map(|j| m.iter().map(move |r| r[j])).collect();
    let mut mtx = Vec::new();
    write_mtx_dense(&mut mtx, n, n, &values).unwrap();
    std::fs::write(dir.join("m.mtx"), &mtx).unwrap();
    let by_file = format!("{{\"M\": \"m.mtx\", \"q\": {q:?}, \"d\": {d:?}, \"lambda_max\": 5}}");
    std::fs::write(dir.join("inline.json"), &inline).unwrap();
    std::fs::write(dir.join("file.json"), &by_file).unwrap();
    // the same M as NumPy writes it (numpy.save, C order, little-endian f8)
    std::fs::write(dir.join("m.npy"), npy_c_order(&m)).unwrap();
    let by_npy = by_file.replace("m.mtx", "m.npy");
    std::fs::write(dir.join("npy.json"), &by_npy).unwrap();

    // the library: the same problem, entry for entry, and the same path
    let a =
        parse_plcp::<f64>(inline.as_bytes(), dir.join("inline.json").to_str().unwrap()).unwrap();
    let b = parse_plcp::<f64>(by_file.as_bytes(), dir.join("file.json").to_str().unwrap()).unwrap();
    for (i, row) in m.iter().enumerate() {
        for (j, x) in row.iter().enumerate() {
            let (ea, eb) = (a.m()[(i, j)], b.m()[(i, j)]);
            assert_eq!(ea.to_bits(), eb.to_bits(), "M({i}, {j})");
            // and both exactly the decimal written (correct rounding)
            assert_eq!(ea.to_bits(), x.to_bits(), "M({i}, {j})");
        }
    }
    let pa = plcp::solve(&a, &Settings::default()).unwrap();
    let pb = plcp::solve(&b, &Settings::default()).unwrap();
    assert!(
        pa.status.is_success() && pa.breakpoints.len() >= 3,
        "{:?}",
        pa.status
    );
    let la: Vec<u64> = pa.breakpoints.iter().map(|b| b.lambda.to_bits()).collect();
    let lb: Vec<u64> = pb.breakpoints.iter().map(|b| b.lambda.to_bits()).collect();
    assert_eq!(la, lb);

    let c = parse_plcp::<f64>(by_npy.as_bytes(), dir.join("npy.json").to_str().unwrap()).unwrap();
    assert!((0..n).all(|i| (0..n).all(|j| a.m()[(i, j)].to_bits() == c.m()[(i, j)].to_bits())));

    // the command line: identical reports
    let va = without_timing(cli::solve(&dir.join("inline.json")));
    let vb = without_timing(cli::solve(&dir.join("file.json")));
    let vc = without_timing(cli::solve(&dir.join("npy.json")));
    assert_eq!(va["status"], "reached");
    assert_eq!(va, vb);
    assert_eq!(va, vc);
}

#[test]
fn symmetric_coordinate_file_as_dense_and_sparse_m() {
    // the 1-D Laplacian, stored as its lower triangle
    let n = 9;
    let mut text = format!(
        "%%MatrixMarket matrix coordinate real symmetric\n% 1-D Laplacian\n{n} {n} {}\n",
        2 * n - 1
    );
    for i in 1..=n {
        text += &format!("{i} {i} 2\n");
        if i < n {
            text += &format!("{} {i} -1\n", i + 1);
        }
    }
    let dir = dir("coordinate");
    std::fs::write(dir.join("lap.mtx"), &text).unwrap();
    let q: Vec<f64> = (0..n).map(|i| 0.1 * (i as f64) - 0.3).collect();
    let d = vec![-0.25; n];
    let dense = format!("{{\"M\": \"lap.mtx\", \"q\": {q:?}, \"d\": {d:?}, \"lambda_max\": 4}}");
    let sparse =
        format!("{{\"M_sparse\": \"lap.mtx\", \"q\": {q:?}, \"d\": {d:?}, \"lambda_max\": 4}}");
    let file = dir.join("p.json");
    let name = file.to_str().unwrap();
    let a = parse_plcp::<f64>(dense.as_bytes(), name).unwrap();
    for i in 0..n {
        for j in 0..n {
            let want = match i.abs_diff(j) {
                0 => 2.0,
                1 => -1.0,
                _ => 0.0,
            };
            assert_eq!(a.m()[(i, j)], want, "M({i}, {j})");
        }
    }
    let (b, warm) = parse_sparse::<f64>(sparse.as_bytes(), name).unwrap();
    assert!(b.is_sparse() && warm.is_none());
    let pa = plcp::solve(&a, &Settings::default()).unwrap();
    let pb = plcp::solve(&b, &Settings::default()).unwrap();
    assert!(pa.status.is_success() && pb.status.is_success());
    assert_eq!(pa.breakpoints.len(), pb.breakpoints.len());
    for (x, y) in pa.breakpoints.iter().zip(&pb.breakpoints) {
        assert!((x.lambda - y.lambda).abs() <= 1e-12 * x.lambda.abs().max(1.0));
    }
}

#[test]
fn bad_matrix_files_are_named() {
    let dir = dir("bad");
    let json = |m: &str| format!("{{\"M\": \"{m}\", \"q\": [1, 1], \"d\": [-1, -1]}}");
    let cases: [(&str, Option<&str>, &str); 4] = [
        ("missing.mtx", None, "missing.mtx"),
        (
            "bad.mtx",
            Some("%%MatrixMarket matrix array real general\n2 2\n1\n2\nx\n4\n"),
            "bad.mtx:5:1: \"x\" is not a number",
        ),
        (
            "rect.mtx",
            Some("%%MatrixMarket matrix array real general\n2 3\n1\n2\n3\n4\n5\n6\n"),
            "2 rows of 3 entries",
        ),
        (
            "nan.mtx",
            Some("%%MatrixMarket matrix array real general\n2 2\n1\nNaN\n0\n1\n"),
            "M",
        ),
    ];
    for (name, content, want) in cases {
        if let Some(c) = content {
            std::fs::write(dir.join(name), c).unwrap();
        }
        let f = dir.join(format!("{name}.json"));
        std::fs::write(&f, json(name)).unwrap();
        let out = cli::solve_output(&f);
        assert_eq!(out.status.code(), Some(2), "{name}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(want), "{name}: {err}");
        assert!(out.stdout.is_empty());
    }
}
