//! Long ties in the lexicographic rule on the dense block basis: a monotone
//! problem whose `M = B B'/n + 0.1 I` has a `B` of rank below `n` meets ties
//! whose tied rows of `B^-1` agree over many columns. The rule then reads
//! the rows still tied (a transpose solve each) instead of one column after
//! another (`plcp/src/basis/lex.rs`, `columns_before_rows`). The path must
//! have the breakpoints and end of the sparse basis's (which always reads
//! rows), and exact certification must accept it.

use faer::{Col, Mat};
use plcp::{BasisKind, Plcp, Settings, Status};

/// `B` filled from a cycle of 199 values (rank at most 199), `q` in
/// `[0.1, 1]`, `d` in `[-1.5, 0.5]`, `L` up to 1.
fn low_rank(n: usize) -> Plcp<f64> {
    let vals: Vec<f64> = (0..199).map(|i| ((i * 37 % 101) as f64) / 101.0).collect();
    let mut it = vals.iter().cycle().copied();
    let b = Mat::<f64>::from_fn(n, n, |_, _| 2.0 * it.next().unwrap() - 1.0);
    let m = crate::common::gram_shifted(b.as_ref(), 0.1);
    let q = Col::<f64>::from_fn(n, |_| 0.1 + 0.9 * it.next().unwrap());
    let d = Col::<f64>::from_fn(n, |_| 2.0 * it.next().unwrap() - 1.5);
    Plcp::new(m.as_ref(), q.as_ref(), d.as_ref())
        .unwrap()
        .with_range(0.0, Some(1.0))
        .unwrap()
}

#[test]
fn long_ties_on_the_block_basis_follow_the_rows() {
    let p = low_rank(230);
    let engine = |basis| Settings::<f64> {
        principal: false,
        basis,
        ..Settings::default()
    };
    let block = plcp::solve(&p, &engine(BasisKind::Block)).unwrap();
    let sparse = plcp::solve(&p, &engine(BasisKind::Sparse)).unwrap();
    assert_eq!(block.status, Status::Reached, "{}", block.message);
    assert_eq!(sparse.status, Status::Reached, "{}", sparse.message);
    // the case meets ties (23 degenerate pivots when written)
    assert!(block.info.degenerate_pivots >= 15, "{:?}", block.info);
    assert_eq!(block.info.pivots, sparse.info.pivots);
    assert_eq!(block.breakpoints.len(), sparse.breakpoints.len());
    // the same breakpoints (at a degenerate breakpoint the two bases may
    // take different pivots: rounding differs in the rows compared)
    for (a, b) in block.breakpoints.iter().zip(&sparse.breakpoints) {
        assert!((a.lambda - b.lambda).abs() <= 1e-9 * b.lambda.abs().max(1.0));
    }
    let scale = sparse.end.z.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    for i in 0..p.n() {
        assert!((block.end.z[i] - sparse.end.z[i]).abs() <= 1e-9 * scale);
    }
    let cert = plcp::certify(&p, &block);
    assert!(cert.failure.is_none(), "{:?}", cert.failure);
    assert!(cert.max_rel_diff <= 1e-9, "{}", cert.max_rel_diff);
}
