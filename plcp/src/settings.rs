//! Settings of the solvers, with documented defaults and a `validate()`.

use crate::error::PlcpError;
use crate::path::Var;
use crate::scalar::Scalar;
use faer::Col;

/// The refactorisation period when [`Settings::refactor_period`] is `None`
/// (the block basis waits longer on large blocks, see there).
pub const DEFAULT_REFACTOR_PERIOD: usize = 50;

/// The algorithm that traces the path.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Method {
    /// Lemke-style complementary pivoting with `L` as the driving variable, on the
    /// standard form (a mixed problem is first reduced by a Schur complement,
    /// which needs a nonsingular free block).
    #[default]
    Lemke,
    /// Wolfe's simplex method for QP in its long form, on the unreduced tableau of
    /// the mixed system (free variables basic as far as the rank allows,
    /// dependent equality rows kept with artificial variables fixed at zero).
    Wolfe,
}

impl core::str::FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "lemke" => Ok(Self::Lemke),
            "wolfe" => Ok(Self::Wolfe),
            other => Err(format!("unknown method '{other}': expected lemke or wolfe")),
        }
    }
}

/// How ties of the minimum-ratio test within the tie window
/// ([`Settings::tie_tol_eps`]) are read (issue 14).
///
/// The window is wide: it absorbs the rounding of basic values that may have
/// lost digits. Two breakpoints inside it may still be distinct events of the
/// data, and taking them as one can be a wrong path that nothing else flags
/// (the block `[[1, 1], [1, 1 + 2^-46]]` of `docs/limits.md`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum NearTies {
    /// The data are exact as given (default). Tied rows are read again with
    /// values and column entries refined by one step whose residual is
    /// accumulated in the wide type, each ratio with an error bound
    /// (`pivoting/ratio.rs`). Rows the bounds separate leave in their exact
    /// order; rows within the bounds of the smallest are a tie for the
    /// lexicographic rule when the bound is within
    /// [`crate::tolerance::TIE_RESOLUTION_EPS`] roundings of `L`; a wider bound
    /// stops the trace `ill_conditioned` naming the rows (a higher precision or
    /// exact arithmetic decides). [`crate::Info::near_ties_resolved`] and
    /// `near_ties_unresolved` count them.
    #[default]
    Refine,
    /// Every tie within the window is one event for the lexicographic rule.
    /// For data that carry their own rounding, where breakpoints closer than
    /// the window are simultaneous events of the exact problem the data round:
    /// `frames` assembles system (9) in floating point, and the symmetric
    /// hinges of a scene, which reach yield at once, reach it 1..3 ulps apart
    /// in the assembled data (ordering them by those ulps loses hinge events,
    /// `frames/tests/space.rs`). A near tie of the exact data is then not told
    /// apart: [`crate::solve_certified`] checks the answer exactly.
    Window,
}

impl core::str::FromStr for NearTies {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "refine" => Ok(Self::Refine),
            "window" => Ok(Self::Window),
            other => Err(format!(
                "unknown near-tie rule '{other}': expected refine or window"
            )),
        }
    }
}

/// Settings. Every tolerance is relative; see [`crate::tolerance`] for how each
/// is scaled.
///
/// Start from [`Settings::default`] and change what you need:
///
/// ```
/// use faer::{col, mat};
/// use plcp::{BasisKind, Method, Plcp, Settings, Status};
/// let m = mat![[2.0, 1.0], [1.0, 2.0]];
/// let problem =
///     Plcp::new(m.as_ref(), col![1.0, 1.0].as_ref(), col![-1.0, -0.5].as_ref()).unwrap();
/// let settings = Settings {
///     method: Method::Wolfe,
///     basis: BasisKind::Dense,
///     max_pivots: Some(100),
///     ..Settings::default()
/// };
/// let path = plcp::solve(&problem, &settings).unwrap();
/// assert_eq!(path.status, Status::UnboundedRay);
/// assert_eq!(path.info.method, "wolfe");
/// assert_eq!(path.breakpoints[0].lambda, 1.0);
/// ```
#[derive(Clone, Debug)]
pub struct Settings<T: Scalar> {
    /// The algorithm. Default: [`Method::Lemke`].
    pub method: Method,
    /// Covering vector of the start phase (Lemke's artificial variable), one
    /// positive entry per complementary pair. Default `None`: all ones.
    pub covering: Option<Col<T>>,
    /// Largest number of pivots in all phases. Default `None`: `50 * (n + p) + 1000`
    /// ([`Self::max_pivots_for`]).
    pub max_pivots: Option<usize>,
    /// Pivot tolerance, as a multiple of the working precision's epsilon: an entry
    /// of the entering column counts only if `|a| > pivot_tol_eps * eps * scale`.
    /// Default `128` (f64: about 3e-14 relative, f32: about 2e-5).
    pub pivot_tol_eps: f64,
    /// Ratios within `tie_tol_eps * eps` (relative) count as ties and go to the
    /// lexicographic rule. Default `1e3`.
    pub tie_tol_eps: f64,
    /// How ties within that window are read. Default [`NearTies::Refine`].
    pub near_ties: NearTies,
    /// Refactorise the basis every this many pivots (a refactorisation also
    /// recomputes the basic values and estimates the condition number).
    /// Default `None`: every [`DEFAULT_REFACTOR_PERIOD`] pivots, and for the
    /// block basis ([`BasisKind::Block`]) every `max(50, k)` pivots, `k` the
    /// order of its block at the last refactorisation, so that inverting the
    /// block (`O(k^3)`) costs no more than the `O(k^2)` updates in between.
    /// The sparse basis also refactorises when its eta file grows long.
    pub refactor_period: Option<usize>,
    /// A basis whose estimated 1-norm condition number times epsilon exceeds this
    /// stops the path with `IllConditioned`. Default `1e-2`.
    pub max_cond_eps: f64,
    /// Refine the basic values at a breakpoint (iterative refinement, at most two
    /// steps) when its equation residual exceeds `refine_tol_eps * eps`.
    /// Default `1e3`.
    pub refine_tol_eps: f64,
    /// Refine every entering column (one step, its residual accumulated in
    /// [`Scalar::Wide`]) while the basis condition estimate times `eps`
    /// exceeds this; beyond [`crate::tolerance::WIDE_REFINE_COND_EPS`] the
    /// basic values at breakpoints are refined with wide residuals too.
    /// Default `1e-12`.
    pub refine_cond_eps: f64,
    /// Equilibrate `M` (rows and columns, by powers of two) before pivoting and
    /// unscale the answer. Default `true`. See [`crate::scaling`].
    pub scaling: bool,
    /// How the basis is represented. Default [`BasisKind::Block`].
    pub basis: BasisKind,
    /// Start from this basis instead of the cold start (the start phase), if it
    /// is nonsingular and its basic solution is feasible at `lambda0`; otherwise
    /// the cold start runs and [`crate::Info::warm_start`] says why. One variable
    /// per row position (`p + n` of them: `u`, `z`, `w` or artificial; not `L`),
    /// typically [`crate::Path::final_basis`] of an earlier problem with the same
    /// `M` (for a mixed problem solved by Lemke on the Schur reduction, its `u`
    /// and artificial entries are dropped). Typical use: re-solving after a change
    /// of `q`, as the path from the old `q` (`L = 0`) to the new one (`L = 1`)
    /// with `d = q_new - q_old`. Default `None`.
    pub warm_basis: Option<Vec<Var>>,
    /// Continue in double-double where the working precision gives up: a path
    /// in `f32` or `f64` that ends `IllConditioned` (basis condition, a nearly
    /// singular free block, or the residual guard) is traced on in `fx128` from
    /// the start of its last trustworthy segment, warm-started from that
    /// segment's basis, and the rest is spliced into the path rounded to the
    /// working precision; the status is then the `fx128` run's, and
    /// [`crate::Info::escalation`] says where, why, and the pivots and time in
    /// each precision. See [`crate::Escalation`]. No effect in `fx128`.
    /// Default `false`.
    pub escalate: bool,
    /// With `escalate`: a path still `ill_conditioned` after `fx128` (or in
    /// `fx128` itself) is continued in exact rational arithmetic
    /// ([`crate::exact::trace_from`]) from the last segment whose basis is
    /// exactly feasible, if its order `p + n` is at most
    /// [`crate::tolerance::ESCALATE_EXACT_MAX_DIM`]. Default `false`.
    pub escalate_exact: bool,
    /// Threads for the large products of the block basis (its refactorisation
    /// and the flush of pending updates). `Some(1)`: the calling thread only;
    /// `Some(k)`: `k` threads of rayon's pool for every product of at least
    /// 2^16 entries (`PAR_SPLIT_MIN`; inversions from order 322); `None`
    /// (default): by size,
    /// the calling thread for products under 2^19 (`PAR_MIN_ENTRIES`)
    /// entries and inversions of order under 645, faer's global parallelism
    /// above (so sizes up to n = 1000 on dense families never wake a pool).
    /// The setting holds for the inversions at refactorisation too (test
    /// `plcp/tests/threads.rs`: the default and `Some(1)` start no pool at
    /// n = 700, `Some(2)` does). The arithmetic of the passes, and so the
    /// path, is the same either way.
    pub threads: Option<usize>,
    /// Let the principal-pivoting fast path (`plcp/src/principal.rs`) trace a
    /// dense standard-form `f64` problem whose start `q + L0 d` is strictly
    /// positive, to a finite `L_max`, with the default basis
    /// ([`BasisKind::Block`]) and no warm basis. It hands the problem back to
    /// the general engine (from the start) at any tie, zero step, small pivot,
    /// condition above `1e8` or residual it cannot vouch for, so its paths
    /// are the engine's up to rounding. `info.method` says `"lemke
    /// (principal)"` where it answered. Default `true`; `false`: always the
    /// general engine.
    pub principal: bool,
}

/// The representation of the basis inverse (`src/basis.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum BasisKind {
    /// Only the inverse of the block of matrix columns on uncovered rows:
    /// `O(k^2 + (p+n) k)` per pivot for `k` basic matrix columns.
    #[default]
    Block,
    /// The explicit dense inverse: `O((p+n)^2)` per pivot.
    Dense,
    /// A sparse LU factorisation of the basis with product-form updates
    /// between refactorisations: `O(nnz(L + U) + nnz(etas))` per solve. For
    /// sparse problems ([`crate::Plcp::mixed_sparse`]) whose bases keep many
    /// matrix columns, e.g. Wolfe's long form of frames' system (9).
    Sparse,
}

impl<T: Scalar> Default for Settings<T> {
    fn default() -> Self {
        Self {
            method: Method::Lemke,
            covering: None,
            max_pivots: None,
            pivot_tol_eps: 128.0,
            tie_tol_eps: 1e3,
            near_ties: NearTies::Refine,
            refactor_period: None,
            max_cond_eps: 1e-2,
            refine_tol_eps: 1e3,
            refine_cond_eps: 1e-12,
            scaling: true,
            basis: BasisKind::Block,
            warm_basis: None,
            escalate: false,
            escalate_exact: false,
            threads: None,
            principal: true,
        }
    }
}

impl<T: Scalar> Settings<T> {
    /// Settings with the given method and defaults otherwise.
    pub fn with_method(method: Method) -> Self {
        Self {
            method,
            ..Self::default()
        }
    }

    /// The pivot limit of a problem with `dim = n + p` unknowns in `z` and
    /// `u`: [`Self::max_pivots`], or by default `50 * dim + 1000` (the one
    /// place this default is written).
    ///
    /// ```
    /// let s = plcp::Settings::<f64>::default();
    /// assert_eq!(s.max_pivots_for(10), 1500);
    /// let s = plcp::Settings::<f64> { max_pivots: Some(7), ..Default::default() };
    /// assert_eq!(s.max_pivots_for(10), 7);
    /// ```
    pub fn max_pivots_for(&self, dim: usize) -> usize {
        self.max_pivots.unwrap_or(50 * dim + 1000)
    }

    /// Checks every setting; `n` is the number of complementary pairs.
    pub fn validate(&self, n: usize) -> Result<(), PlcpError> {
        if let Some(c) = &self.covering {
            if c.nrows() != n {
                return Err(PlcpError::Dimension {
                    what: "covering vector".into(),
                    expected: format!("{n} entries (one per complementary pair)"),
                    found: format!("{} entries", c.nrows()),
                });
            }
            for i in 0..n {
                if !(c[i].is_finite() && c[i] > T::zero()) {
                    return Err(PlcpError::Invalid {
                        what: "covering vector".into(),
                        why: format!("entry [{i}] = {} is not positive and finite", c[i].to_f64()),
                    });
                }
            }
        }
        let pos = |what: &str, v: f64| -> Result<(), PlcpError> {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(PlcpError::Invalid {
                    what: what.into(),
                    why: format!("must be positive and finite, got {v}"),
                })
            }
        };
        pos("pivot_tol_eps", self.pivot_tol_eps)?;
        pos("tie_tol_eps", self.tie_tol_eps)?;
        pos("max_cond_eps", self.max_cond_eps)?;
        pos("refine_tol_eps", self.refine_tol_eps)?;
        pos("refine_cond_eps", self.refine_cond_eps)?;
        if self.refactor_period == Some(0) {
            return Err(PlcpError::Invalid {
                what: "refactor_period".into(),
                why: "must be at least 1".into(),
            });
        }
        if let Some(b) = &self.warm_basis {
            let mut seen = std::collections::HashSet::new();
            for v in b {
                let bad = match *v {
                    Var::W(i) | Var::Z(i) => {
                        (i >= n).then(|| format!("{v} with only {n} complementary pairs"))
                    }
                    Var::Lambda => Some("L cannot be basic in a start basis".into()),
                    Var::U(_) | Var::Artificial(_) => None,
                };
                if let Some(why) = bad {
                    return Err(PlcpError::Invalid {
                        what: "warm_basis".into(),
                        why,
                    });
                }
                if !seen.insert(*v) {
                    return Err(PlcpError::Invalid {
                        what: "warm_basis".into(),
                        why: format!("{v} appears twice"),
                    });
                }
            }
        }
        if self.threads == Some(0) {
            return Err(PlcpError::Invalid {
                what: "threads".into(),
                why: "must be at least 1".into(),
            });
        }
        if self.max_pivots == Some(0) {
            return Err(PlcpError::Invalid {
                what: "max_pivots".into(),
                why: "must be at least 1".into(),
            });
        }
        Ok(())
    }
}
