//! Wolfe's simplex method for quadratic programming, long form, on the unreduced
//! tableau of a mixed PLCP.
//!
//! The mixed system is the KKT system of a parametric QP when it is monotone
//! (after the sign changes of equality rows and free variables that KKT systems
//! allow); system (9) of the frames crate is such a system. The long form keeps
//! every row and column:
//!
//! * free variables are brought into the basis as far as the rank of the free
//!   block allows (a full-pivoting LU picks them); the others stay nonbasic at
//!   zero (their values are not unique: e.g. redundant member forces), and the
//!   dependent equality rows keep an artificial variable fixed at zero. Both sets
//!   are reported in [`crate::FreeBlockInfo`]. When a complementary variable
//!   later needs a dependent row (a hinge whose rotation a compatibility
//!   condition constrains), the artificial leaves and a nonbasic free variable
//!   takes over from `L`, which drives again;
//! * a complementary start at `L0` comes from `z = 0` when that is feasible, else
//!   from the same artificial-variable start as Lemke's method, on the long form;
//! * `L` then rises by pivots with restricted basis entry (`z_i`, `w_i` never both
//!   basic) and the lexicographic rule, as in [`crate::lemke`].
//!
//! What the method needs: a complementary start at `L0`, and a problem for which
//! the path continues (monotone problems). Where it does not, the path ends with
//! a [`crate::Status`] (`infeasible`, `secondary_ray`), never a wrong answer: every
//! breakpoint's residual is measured on the unreduced system.

use crate::path::{FreeBlockInfo, Path, Status, Var};
use crate::pivoting::run_path;
use crate::reduce::numerical_rank;
use crate::tolerance::rank_tol;
use crate::{error::PlcpError, problem::Plcp, scalar::Scalar, settings::Settings};

/// For a sparse problem: the free block is nonsingular, and well enough
/// conditioned that a full-pivoting LU would find full rank, if its sparse LU
/// succeeds with `cond_1 * rank_tol(p, 1) < 1` (the rank tolerance relative to
/// the largest pivot, against the condition estimate). Then every free variable
/// is basic and no equality row is dependent, at `O(nnz(L + U))` instead of the
/// `O(p^3)` of the dense full-pivoting LU; otherwise `None` (the dense route
/// decides the rank and the dependent rows).
fn sparse_full_rank<T: Scalar>(problem: &Plcp<T>) -> Option<f64> {
    let crate::matrix::MatrixRef::Sparse(m) = problem.matrix() else {
        return None;
    };
    let p = problem.free();
    let cond = m.block(0..p, 0..p).lu_condition()?;
    (cond * rank_tol(p, T::one()).to_f64() < 1.0).then_some(cond)
}

/// The start basis of the long form: free variables by a full-pivoting LU of the
/// free block, artificial variables in the dependent rows, all `w`. For a
/// sparse problem whose free block is nonsingular the sparse LU says so first
/// and the dense LU is skipped (see [`sparse_full_rank`]).
///
/// Also returns the largest dropped pivot relative to the largest pivot, when
/// it lies above the rounding level (`10 p eps`): the block is then nearly, not
/// exactly, singular in this precision, and its numerical rank is uncertain.
pub(crate) fn start_basis<T: Scalar>(problem: &Plcp<T>) -> (Vec<Var>, FreeBlockInfo, Option<f64>) {
    let p = problem.free();
    let n = problem.n();
    let mut basis = Vec::with_capacity(p + n);
    let mut info = FreeBlockInfo::default();
    let mut uncertain = None;
    if p > 0 && sparse_full_rank(problem).is_some() {
        basis.extend((0..p).map(Var::U));
        info.rank = p;
    } else if p > 0 {
        let f = problem.m().submatrix(0, 0, p, p);
        let lu = f.full_piv_lu();
        let u = lu.U();
        let largest = (0..p).fold(T::zero(), |a, i| a.max(u[(i, i)].abs()));
        let tol = rank_tol(p, largest);
        let rank = if largest == T::zero() {
            0
        } else {
            (0..p).filter(|&i| u[(i, i)].abs() > tol).count()
        };
        if rank < p && largest > T::zero() {
            let dropped = (rank..p).fold(T::zero(), |a, i| a.max(u[(i, i)].abs()));
            let rel = (dropped / largest).to_f64();
            if rel > 10.0 * p as f64 * T::eps().to_f64() {
                uncertain = Some(rel);
            }
        }
        let (prow, _) = lu.P().arrays();
        let (qcol, _) = lu.Q().arrays();
        for &j in &qcol[..rank] {
            basis.push(Var::U(j));
        }
        for &k in &prow[rank..] {
            basis.push(Var::Artificial(k));
        }
        info.rank = rank;
        info.nonbasic_free = qcol[rank..].to_vec();
        info.nonbasic_free.sort_unstable();
        info.dependent_rows = prow[rank..].to_vec();
        info.dependent_rows.sort_unstable();
        debug_assert_eq!(rank, numerical_rank(f));
    }
    basis.extend((0..n).map(Var::W));
    (basis, info, uncertain)
}

pub(crate) fn solve<T: Scalar>(
    problem: &Plcp<T>,
    settings: &Settings<T>,
) -> Result<Path<T>, PlcpError> {
    let (basis, info, uncertain) = start_basis(problem);
    let mut path = run_path(
        problem.matrix(),
        problem.free(),
        &problem.q().to_owned(),
        &problem.d().to_owned(),
        problem.lambda0(),
        problem.lambda_max(),
        basis,
        settings,
        crate::settings::Method::Wolfe,
        "wolfe",
        info,
    );
    // a path that stops where a nearly singular free block was taken as singular
    // may stop because of that choice: say so, never a confident stop
    if let (Some(rel), false) = (uncertain, path.status.is_success()) {
        path.message = format!(
            "the free block is nearly singular in {} (a pivot {rel:.1e} relative to the largest was taken as zero, above the rounding level), so its rank, and with it this stop, is uncertain; try a higher precision. {}",
            T::NAME,
            path.message
        );
        path.status = Status::IllConditioned;
        path.ray = None;
    }
    Ok(path)
}
