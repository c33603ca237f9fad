//! [`SparseBlock`]: the sparse storage of `A` and `T N`.

use faer::Mat;

/// A sparse block of system (9) (`A` or `T N`), stored by columns with sorted
/// row indices and no zeros (so `==` compares the matrices). `A` and `T N`
/// hold a few entries per row: stored densely they were quadratic in the
/// elements (64 MB at 1000 elements, 6.4 GB at 10^4). Read an entry with
/// `block[(i, j)]` (zero if not stored), a column with [`SparseBlock::col`].
///
/// ```
/// let src = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenes/cantilever.toml")).unwrap();
/// let scene = frames::Scene::from_toml(&src, "cantilever.toml").unwrap();
/// let sys = frames::System::assemble(&scene.frame);
/// let dense = sys.a.to_dense();
/// assert_eq!((sys.a.nrows(), sys.a.ncols()), (dense.nrows(), dense.ncols()));
/// assert_eq!(sys.a[(0, 0)], dense[(0, 0)]);
/// assert!(sys.a.nnz() < sys.a.nrows() * sys.a.ncols());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct SparseBlock(plcp::matrix::Csc<f64>);

static ZERO: f64 = 0.0;

impl SparseBlock {
    /// From `(row, column, value)` entries (zeros dropped; a position given
    /// twice keeps its last value, as writing them into a dense block would).
    pub(super) fn from_entries(
        nrows: usize,
        ncols: usize,
        entries: Vec<(usize, usize, f64)>,
    ) -> Self {
        let mut last: std::collections::HashMap<(usize, usize), f64> =
            std::collections::HashMap::with_capacity(entries.len());
        for (i, j, v) in entries {
            last.insert((i, j), v);
        }
        let triplets: Vec<(usize, usize, f64)> = last
            .into_iter()
            .filter(|&(_, v)| v != 0.0)
            .map(|((i, j), v)| (i, j, v))
            .collect();
        // assembled from finite geometry and strengths: an entry that is not
        // finite (or out of range) is a bug of the assembly
        Self(
            plcp::matrix::Csc::try_from_triplets(nrows, ncols, &triplets)
                .expect("the assembled blocks of system (9) are finite and in range"),
        )
    }
    /// Number of rows.
    pub fn nrows(&self) -> usize {
        self.0.nrows()
    }
    /// Number of columns.
    pub fn ncols(&self) -> usize {
        self.0.ncols()
    }
    /// Number of stored (nonzero) entries.
    pub fn nnz(&self) -> usize {
        self.0.nnz()
    }
    /// Row indices (ascending) and values of column `j`.
    pub fn col(&self, j: usize) -> (&[usize], &[f64]) {
        self.0.col(j)
    }
    /// The compressed sparse column form.
    pub fn csc(&self) -> &plcp::matrix::Csc<f64> {
        &self.0
    }
    /// The dense matrix (for small systems and checks).
    pub fn to_dense(&self) -> Mat<f64> {
        self.0.to_dense()
    }
}

impl std::ops::Index<(usize, usize)> for SparseBlock {
    type Output = f64;
    fn index(&self, (i, j): (usize, usize)) -> &f64 {
        assert!(
            i < self.nrows() && j < self.ncols(),
            "index ({i}, {j}) out of a {} x {} block",
            self.nrows(),
            self.ncols()
        );
        let (col_ptr, _, vals) = self.0.parts();
        let (col_rows, _) = self.0.col(j);
        match col_rows.binary_search(&i) {
            Ok(k) => &vals[col_ptr[j] + k],
            Err(_) => &ZERO,
        }
    }
}
