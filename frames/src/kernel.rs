//! Null spaces and ranks of small dense matrices (Gauss-Jordan elimination with
//! full pivoting in `f64`): used for the checks that need the kinematics of a
//! frame (mechanisms without mass, static determinacy, uniqueness of the stress).

use faer::Mat;

/// Rank and a basis of the null space of `a`, with entries counted as zero below
/// `1e-10 * max |a_ij| * max(rows, cols)`.
pub(crate) fn null_space(a: &Mat<f64>) -> (usize, Vec<Vec<f64>>) {
    let (m, n) = (a.nrows(), a.ncols());
    let mut r = a.clone();
    let scale = (0..n)
        .flat_map(|j| (0..m).map(move |i| (i, j)))
        .fold(0.0f64, |s, (i, j)| s.max(a[(i, j)].abs()));
    if scale == 0.0 {
        let basis = (0..n)
            .map(|j| (0..n).map(|k| if k == j { 1.0 } else { 0.0 }).collect())
            .collect();
        return (0, basis);
    }
    let tol = 1e-10 * scale * (m.max(n) as f64);
    let mut cols: Vec<usize> = (0..n).collect();
    let mut rank = 0;
    while rank < m.min(n) {
        // full pivoting on the remaining block
        let (mut bi, mut bj, mut best) = (rank, rank, 0.0);
        for jj in rank..n {
            for i in rank..m {
                let v = r[(i, cols[jj])].abs();
                if v > best {
                    (bi, bj, best) = (i, jj, v);
                }
            }
        }
        if best <= tol {
            break;
        }
        cols.swap(rank, bj);
        let pc = cols[rank];
        if bi != rank {
            for j in 0..n {
                let t = r[(bi, j)];
                r[(bi, j)] = r[(rank, j)];
                r[(rank, j)] = t;
            }
        }
        let piv = r[(rank, pc)];
        for j in 0..n {
            r[(rank, j)] /= piv;
        }
        for i in 0..m {
            if i != rank {
                let f = r[(i, pc)];
                if f != 0.0 {
                    for j in 0..n {
                        let v = r[(rank, j)];
                        r[(i, j)] -= f * v;
                    }
                }
            }
        }
        rank += 1;
    }
    let mut basis = Vec::new();
    for &fc in &cols[rank..] {
        let mut v = vec![0.0; n];
        v[fc] = 1.0;
        for (k, &pc) in cols[..rank].iter().enumerate() {
            v[pc] = -r[(k, fc)];
        }
        basis.push(v);
    }
    (rank, basis)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rank_and_kernel() {
        let a = Mat::from_fn(3, 4, |i, j| {
            [
                [1.0, 2.0, 3.0, 4.0],
                [2.0, 4.0, 6.0, 8.0],
                [0.0, 1.0, 0.0, 1.0],
            ][i][j]
        });
        let (rank, basis) = null_space(&a);
        assert_eq!(rank, 2);
        assert_eq!(basis.len(), 2);
        for v in &basis {
            for i in 0..3 {
                let s: f64 = (0..4).map(|j| a[(i, j)] * v[j]).sum();
                assert!(s.abs() < 1e-12);
            }
        }
        assert_eq!(null_space(&Mat::<f64>::zeros(2, 3)).1.len(), 3);
    }
}
