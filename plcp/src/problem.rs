//! The problem: a parametric LCP in standard or mixed form, checked at construction.

use crate::error::PlcpError;
use crate::matrix::{Csc, MatrixRef};
use crate::scalar::Scalar;
use faer::{Col, ColRef, Mat, MatRef};
use std::sync::OnceLock;

/// How `M` is held: dense, or sparse with a dense copy made on demand (only
/// for callers of [`Plcp::m`]; the solvers use [`Plcp::matrix`]).
#[derive(Clone, Debug)]
enum Storage<T: Scalar> {
    Dense(Mat<T>),
    Sparse { m: Csc<T>, dense: OnceLock<Mat<T>> },
}

/// A parametric linear complementarity problem.
///
/// With `x = (u, z)`, `u` the `p` free variables and `z` the `n` complementary ones,
/// and `L` the parameter rising from `lambda0` to `lambda_max`:
///
/// ```text
/// 0 = (M x + q + L d)[0..p]                 (p equality rows)
/// w = (M x + q + L d)[p..p+n],  w >= 0,  z >= 0,  w'z = 0.
/// ```
///
/// The standard form is `p = 0`.
///
/// ```
/// use faer::{mat, col};
/// let m = mat![[2.0, 1.0], [1.0, 2.0]];
/// let q = col![1.0, 1.0];
/// let d = col![-1.0, -0.5];
/// let problem = plcp::Plcp::new(m.as_ref(), q.as_ref(), d.as_ref()).unwrap();
/// assert_eq!(problem.n(), 2);
/// ```
#[derive(Clone, Debug)]
pub struct Plcp<T: Scalar> {
    m: Storage<T>,
    q: Col<T>,
    d: Col<T>,
    free: usize,
    lambda0: T,
    lambda_max: Option<T>,
}

/// One datum: finite, and zero or a normal number of `T` (a subnormal entry
/// has lost digits, or is what an underflow left: [`PlcpError::Underflow`]).
pub(crate) fn check_entry<T: Scalar>(
    what: &str,
    position: impl FnOnce() -> String,
    v: T,
) -> Result<(), PlcpError> {
    if !v.is_finite() {
        return Err(PlcpError::NonFinite {
            what: what.into(),
            position: position(),
            value: v.to_f64(),
        });
    }
    let x = v.to_f64().abs();
    if v != T::zero() && x < T::min_normal() {
        return Err(PlcpError::Underflow {
            what: what.into(),
            position: position(),
            value: v.to_f64(),
            precision: T::NAME.into(),
            min_normal: T::min_normal(),
        });
    }
    Ok(())
}

fn check_finite_mat<T: Scalar>(what: &str, a: MatRef<'_, T>) -> Result<(), PlcpError> {
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            check_entry(what, || format!("({i}, {j})"), a[(i, j)])?;
        }
    }
    Ok(())
}

fn check_finite_col<T: Scalar>(what: &str, a: ColRef<'_, T>) -> Result<(), PlcpError> {
    for i in 0..a.nrows() {
        check_entry(what, || format!("[{i}]"), a[i])?;
    }
    Ok(())
}

impl<T: Scalar> Plcp<T> {
    /// A standard-form PLCP `w = q + L d + M z` (no free variables).
    pub fn new(m: MatRef<'_, T>, q: ColRef<'_, T>, d: ColRef<'_, T>) -> Result<Self, PlcpError> {
        Self::mixed(m, q, d, 0)
    }

    /// A mixed PLCP whose first `free` unknowns are free and first `free` rows equalities.
    pub fn mixed(
        m: MatRef<'_, T>,
        q: ColRef<'_, T>,
        d: ColRef<'_, T>,
        free: usize,
    ) -> Result<Self, PlcpError> {
        let dim = m.nrows();
        // shapes before the (costlier) finiteness of M, as the errors rank
        Self::check_shapes("M", (dim, m.ncols()), q, d, free)?;
        check_finite_mat("M", m)?;
        Self::checked(Storage::Dense(m.to_owned()), q, d, free)
    }

    /// [`Plcp::mixed`] taking `M` by value, for a copy whose entries the
    /// caller has checked as [`check_entry`] does (the scaled problem of
    /// [`crate::scaling`]): no second copy of `M`, no second pass over it.
    pub(crate) fn mixed_owned_checked(
        m: Mat<T>,
        q: ColRef<'_, T>,
        d: ColRef<'_, T>,
        free: usize,
    ) -> Result<Self, PlcpError> {
        Self::check_shapes("M", (m.nrows(), m.ncols()), q, d, free)?;
        Self::checked(Storage::Dense(m), q, d, free)
    }

    /// A mixed PLCP with a sparse `M` (see [`Csc::try_from_triplets`]): the same
    /// problem as [`Plcp::mixed`], checked the same way, for which the solvers
    /// touch only the stored entries. [`Plcp::m`] makes a dense copy on its first
    /// call; the solvers never call it for [`crate::Method::Wolfe`].
    ///
    /// ```
    /// use faer::col;
    /// use plcp::matrix::Csc;
    /// // 0 = -u + 1 - z,  w = u + L (-1) + 0 z: one free variable, one pair
    /// let m = Csc::try_from_triplets(2, 2, &[(0, 0, -1.0), (0, 1, -1.0), (1, 0, 1.0)]).unwrap();
    /// let problem = plcp::Plcp::mixed_sparse(m, col![1.0, 0.0].as_ref(), col![0.0, -1.0].as_ref(), 1).unwrap();
    /// assert!(problem.is_sparse());
    /// assert_eq!(problem.m()[(0, 1)], -1.0);
    /// ```
    pub fn mixed_sparse(
        m: Csc<T>,
        q: ColRef<'_, T>,
        d: ColRef<'_, T>,
        free: usize,
    ) -> Result<Self, PlcpError> {
        Self::check_shapes("M (sparse)", (m.nrows(), m.ncols()), q, d, free)?;
        // Csc keeps only finite entries (checked when it was built)
        Self::checked(
            Storage::Sparse {
                m,
                dense: OnceLock::new(),
            },
            q,
            d,
            free,
        )
    }

    /// `M` (named `what`, of shape `(dim, ncols)`) square, `q` and `d` of
    /// length `dim`, at most `dim` free variables.
    fn check_shapes(
        what: &str,
        (dim, ncols): (usize, usize),
        q: ColRef<'_, T>,
        d: ColRef<'_, T>,
        free: usize,
    ) -> Result<(), PlcpError> {
        if ncols != dim {
            return Err(PlcpError::Dimension {
                what: what.into(),
                expected: format!("a square matrix ({dim} x {dim})"),
                found: format!("{dim} x {ncols}"),
            });
        }
        if q.nrows() != dim {
            return Err(PlcpError::Dimension {
                what: "q".into(),
                expected: format!("{dim} entries (the order of M)"),
                found: format!("{} entries", q.nrows()),
            });
        }
        if d.nrows() != dim {
            return Err(PlcpError::Dimension {
                what: "d".into(),
                expected: format!("{dim} entries (the order of M)"),
                found: format!("{} entries", d.nrows()),
            });
        }
        if free > dim {
            return Err(PlcpError::Invalid {
                what: "free".into(),
                why: format!("{free} free variables but M has order {dim}"),
            });
        }
        Ok(())
    }

    /// The problem from data whose shapes [`Self::check_shapes`] accepted:
    /// `q` and `d` must still be finite.
    fn checked(
        m: Storage<T>,
        q: ColRef<'_, T>,
        d: ColRef<'_, T>,
        free: usize,
    ) -> Result<Self, PlcpError> {
        check_finite_col("q", q)?;
        check_finite_col("d", d)?;
        Ok(Self {
            m,
            q: q.to_owned(),
            d: d.to_owned(),
            free,
            lambda0: T::zero(),
            lambda_max: None,
        })
    }

    /// Sets the parameter range: from `lambda0` up to `lambda_max` (`None`: infinity).
    pub fn with_range(mut self, lambda0: T, lambda_max: Option<T>) -> Result<Self, PlcpError> {
        if !lambda0.is_finite() {
            return Err(PlcpError::Invalid {
                what: "lambda0".into(),
                why: format!("must be finite, got {}", lambda0.to_f64()),
            });
        }
        if let Some(lm) = lambda_max {
            if lm.to_f64().is_nan() || (lm.to_f64().is_infinite() && lm.to_f64() < 0.0) {
                return Err(PlcpError::Invalid {
                    what: "lambda_max".into(),
                    why: format!("must be a number >= lambda0, got {}", lm.to_f64()),
                });
            }
            if lm < lambda0 {
                return Err(PlcpError::Invalid {
                    what: "lambda_max".into(),
                    why: format!(
                        "lambda_max = {} is below lambda0 = {}",
                        lm.to_f64(),
                        lambda0.to_f64()
                    ),
                });
            }
        }
        self.lambda0 = lambda0;
        self.lambda_max = lambda_max.filter(|l| l.is_finite());
        Ok(self)
    }

    /// Number of complementary pairs `n`.
    pub fn n(&self) -> usize {
        self.dim() - self.free
    }
    /// Number of free variables `p`.
    pub fn free(&self) -> usize {
        self.free
    }
    /// Order of `M`, `p + n`.
    pub fn dim(&self) -> usize {
        self.matrix().nrows()
    }
    /// The matrix `M`, dense. For a sparse problem the first call makes a
    /// dense copy (`O((p + n)^2)` memory); prefer [`Plcp::matrix`].
    pub fn m(&self) -> MatRef<'_, T> {
        match &self.m {
            Storage::Dense(m) => m.as_ref(),
            Storage::Sparse { m, dense } => dense.get_or_init(|| m.to_dense()).as_ref(),
        }
    }
    /// The matrix `M` as stored: a dense or a sparse view.
    pub fn matrix(&self) -> MatrixRef<'_, T> {
        match &self.m {
            Storage::Dense(m) => MatrixRef::Dense(m.as_ref()),
            Storage::Sparse { m, .. } => MatrixRef::Sparse(m),
        }
    }
    /// True if `M` is held in sparse form ([`Plcp::mixed_sparse`]).
    pub fn is_sparse(&self) -> bool {
        matches!(self.m, Storage::Sparse { .. })
    }
    /// The constant vector `q`.
    pub fn q(&self) -> ColRef<'_, T> {
        self.q.as_ref()
    }
    /// The parameter direction `d`.
    pub fn d(&self) -> ColRef<'_, T> {
        self.d.as_ref()
    }
    /// Start value of the parameter.
    pub fn lambda0(&self) -> T {
        self.lambda0
    }
    /// End value of the parameter (`None`: infinity).
    pub fn lambda_max(&self) -> Option<T> {
        self.lambda_max
    }

    /// Converts the data to another precision (through `f64`), checked like
    /// the constructors: an entry that overflows `U`, or a nonzero entry that
    /// becomes zero or subnormal in `U` ([`PlcpError::Underflow`]), is an
    /// error naming it. Use this to narrow (`f64` to `f32`).
    pub fn try_cast<U: Scalar>(&self) -> Result<Plcp<U>, PlcpError> {
        let dim = self.dim();
        let conv = |what: &str, pos: String, v: T| crate::io::convert::<U>(what, &pos, v.to_f64());
        let q = (0..dim)
            .map(|i| conv("q", format!("[{i}]"), self.q[i]))
            .collect::<Result<Vec<U>, _>>()?;
        let d = (0..dim)
            .map(|i| conv("d", format!("[{i}]"), self.d[i]))
            .collect::<Result<Vec<U>, _>>()?;
        let (q, d) = (Col::from_fn(dim, |i| q[i]), Col::from_fn(dim, |i| d[i]));
        let problem = match &self.m {
            Storage::Dense(m) => {
                let mut mu = Mat::<U>::zeros(dim, dim);
                for j in 0..dim {
                    for i in 0..dim {
                        mu[(i, j)] = conv("M", format!("({i}, {j})"), m[(i, j)])?;
                    }
                }
                Plcp::mixed(mu.as_ref(), q.as_ref(), d.as_ref(), self.free)?
            }
            Storage::Sparse { m, .. } => {
                let mut trip = Vec::with_capacity(m.nnz());
                for j in 0..dim {
                    let (rows, vals) = m.col(j);
                    for (&i, &v) in rows.iter().zip(vals) {
                        trip.push((i, j, conv("M", format!("({i}, {j})"), v)?));
                    }
                }
                let mu = Csc::try_from_triplets(dim, dim, &trip)?;
                Plcp::mixed_sparse(mu, q.as_ref(), d.as_ref(), self.free)?
            }
        };
        problem.with_range(
            crate::io::convert::<U>("lambda0", "", self.lambda0.to_f64())?,
            match self.lambda_max {
                Some(l) => Some(crate::io::convert::<U>("lambda_max", "", l.to_f64())?),
                None => None,
            },
        )
    }

    /// Converts the data to another precision (through `f64`) without checks:
    /// for widening (`f32` or `f64` to `fx128`, `f32` to `f64`), where every
    /// entry is exact. Narrowing may overflow or underflow an entry
    /// silently: use [`Self::try_cast`] there.
    pub fn cast<U: Scalar>(&self) -> Plcp<U> {
        let dim = self.dim();
        let m = match &self.m {
            Storage::Dense(m) => Storage::Dense(Mat::from_fn(dim, dim, |i, j| {
                U::from_f64(m[(i, j)].to_f64())
            })),
            Storage::Sparse { m, .. } => Storage::Sparse {
                m: m.cast(),
                dense: OnceLock::new(),
            },
        };
        Plcp {
            m,
            q: Col::from_fn(dim, |i| U::from_f64(self.q[i].to_f64())),
            d: Col::from_fn(dim, |i| U::from_f64(self.d[i].to_f64())),
            free: self.free,
            lambda0: U::from_f64(self.lambda0.to_f64()),
            lambda_max: self.lambda_max.map(|l| U::from_f64(l.to_f64())),
        }
    }
}

/// A plain LCP: `w = q + M z`, `w, z >= 0`, `w'z = 0`.
#[derive(Clone, Debug)]
pub struct Lcp<T: Scalar> {
    pub(crate) m: Mat<T>,
    pub(crate) q: Col<T>,
}

impl<T: Scalar> Lcp<T> {
    /// Checks dimensions and finiteness.
    pub fn new(m: MatRef<'_, T>, q: ColRef<'_, T>) -> Result<Self, PlcpError> {
        let zero = Col::<T>::zeros(q.nrows());
        let p = Plcp::new(m, q, zero.as_ref())?;
        Ok(Self {
            m: p.m().to_owned(),
            q: p.q,
        })
    }
    /// Order of the problem.
    pub fn n(&self) -> usize {
        self.q.nrows()
    }
    /// The matrix.
    pub fn m(&self) -> MatRef<'_, T> {
        self.m.as_ref()
    }
    /// The vector.
    pub fn q(&self) -> ColRef<'_, T> {
        self.q.as_ref()
    }
    /// Converts the data to another precision (through `f64`), checked like
    /// [`Plcp::try_cast`].
    pub fn try_cast<U: Scalar>(&self) -> Result<Lcp<U>, PlcpError> {
        let n = self.n();
        let zero = Col::<T>::zeros(n);
        let p = Plcp::new(self.m(), self.q(), zero.as_ref())?.try_cast::<U>()?;
        Lcp::new(p.m(), p.q())
    }

    /// Converts the data to another precision (through `f64`) without checks
    /// (see [`Plcp::cast`]; [`Self::try_cast`] to narrow).
    pub fn cast<U: Scalar>(&self) -> Lcp<U> {
        let n = self.n();
        Lcp {
            m: Mat::from_fn(n, n, |i, j| U::from_f64(self.m[(i, j)].to_f64())),
            q: Col::from_fn(n, |i| U::from_f64(self.q[i].to_f64())),
        }
    }
}
