//! Every tolerance of the crate, in one place, and how each is scaled.
//!
//! All tolerances are relative to the data and to the working precision
//! (`eps` = machine epsilon of the scalar type: about 1.2e-7 for `f32`,
//! 2.2e-16 for `f64`, 4.9e-32 for `fx128`).
//!
//! | name | where | value |
//! |---|---|---|
//! | pivot tolerance | an entry `a_i` of the entering column may be a pivot | `abs(a_i) > pivot_tol_eps * eps * max_k abs(a_k)` (default `pivot_tol_eps = 128`) |
//! | entry rounding | a pivot `y_r` below `sqrt(eps) * max_k abs(y_k)` of the entering column `y = B^{-1} a` must also stand above the rounding of its own entry, bounded before the solve's errors (componentwise, the stale condition estimate plays no part) | `abs(y_r) > pivot_tol_eps * eps * sum_i abs(B^{-1}_ri) (abs(B) abs(y))_i` (one transpose solve, small pivots only; else the row is no candidate) |
//! | tie tolerance | two ratios `t_i`, `t_j` of the minimum-ratio test are tied (and go to the lexicographic rule) | `abs(t_i - t_j) <= tie_tol_eps * eps * max(1, abs(t_min), scale)` (default `tie_tol_eps = 1e3`) |
//! | lexicographic tie | two scaled rows of the basis inverse are equal in an entry | same tie tolerance, relative to the largest entry compared |
//! | zero step | a step is degenerate (zero length) | ratio `<= tie tolerance` |
//! | zero in a row of `B^{-1}` | the sparse basis hands the lexicographic rule rows of `B^{-1}` (the other bases do in a long tie, after as many columns as rows tied, at least 4: `src/basis/lex.rs`); an entry is zero | `abs(v) <= ROW_NOISE_EPS * eps * max abs(row)` ([`ROW_NOISE_EPS`] `= 1e3`) |
//! | sparse full rank | Wolfe's start skips the dense LU of a sparse free block | sparse LU succeeds and `cond_1 * rank_tol(p, 1) < 1` |
//! | rank of the free block | a pivot of the full-pivoting LU counts | `abs(u_kk) > sqrt(eps) * max abs(u_11)`... see [`rank_tol`] |
//! | condition | a basis is ill-conditioned | `cond_1(B D) * eps > max_cond_eps` (default `1e-2`), `D` scaling the columns of `B` to 1-norm about one (powers of two; the estimate is then within a factor `dim` of the best column scaling, van der Sluis) |
//! | residuals at breakpoints | reported, measured by the trace with the next column solve (one pass over the basic columns, on the scaled system; under wide refinement a pass in the working precision over the refined values, once no further step follows) | equation row `r` relative to `max(1, abs(q_r), abs(L d_r), abs((B x)_r))`: at least the componentwise (Oettli-Prager) backward error, up to the floor of 1; under wide refinement also relative to `max_j abs(B_rj x_j)` |
//! | refinement | entering columns refined (one step, residual in `Scalar::Wide`); basic values at breakpoints refined | columns: `cond * eps > refine_cond_eps` (default `1e-12`); values: in the working precision while the equation residual `> refine_tol_eps * eps` (default `1e3`, two steps), with wide residuals once `cond * eps >` [`WIDE_REFINE_COND_EPS`] (`1e-9`; on a sparse `M` from `refine_cond_eps`) |
//! | idle refinement | the block basis pauses refining entering columns (then probes, pauses doubling to 64 solves) | [`REFINE_IDLE_RUN`] (`8`) corrections in a row `<= REFINE_IDLE_EPS * eps * max abs(y)` ([`REFINE_IDLE_EPS`] `= 64`) |
//! | segment evaluation | [`crate::Segment::eval`] returns a negative `z` or `w` inside its segment as zero | `-v <= abs(slope) 64 eps max(1, abs(L)) + 64 eps abs(v_from)` and `-v > sqrt(eps) max(1, max abs(x))` |
//! | residuals of points | reported ([`crate::residual::residual`]: start, end, `Path::at`, and every breakpoint for Lemke on a Schur reduction or on request, [`crate::residual::measure_path`]; the sign parts at both ends of every segment, [`crate::residual::segment_ends`]) | equation row `r` relative to `max(U, abs(q_r), abs(L d_r), abs(w_r), max_j abs(M_rj x_j))`, `U = min(max abs(q), max abs(d))` the data's unit ([`residual_unit`], no absolute floor); feasibility of `w` relative to `max(U, max abs(w))`, of `z` to `max(U / max abs(M_ij), max abs(z))` |
//! | residual guard | a path that claims success is downgraded to `ill_conditioned`; the trace stops as `ill_conditioned` at a breakpoint whose residual (after refinement) fails it | largest reported residual `> sqrt(eps)`; where the breakpoints' equation residuals (scaled system, floor one) times `kappa = max(2, max_r 1 / (R_r U))` times [`GUARD_SLACK`] reach `sqrt(eps)`, the whole path is measured on the original problem first (`residual::measure_for_guard`) |
//! | reduction ties | Lemke on the Schur reduction of a mixed problem: the tie tolerance of the reduced path | `tie_tol_eps` times [`reduction_tie_factor`] (`cond(F)`, at least 1, and the product at most `sqrt(eps)`) |
//! | covering vector | the start phase's covering vector `c` is brought by a power of two to the scale of the right-hand side, so the artificial variable is dimensionless | `c * 2^(e(max abs(q + L0 d)) - e(max c))`, `e` the binary exponent |
//! | infeasibility certificate | the start phase's ray proves `infeasible` (`src/evidence.rs`) | `v >= -CERT_EPS eps n max v`; `(M'v)_j <= CERT_EPS eps n sum_i abs(M_ij v_i)`; `(q + L0 d)'v < -CERT_EPS eps n sum_i abs((q + L0 d)_i v_i)` (`CERT_EPS = 1e3` in `src/evidence.rs`) |
//! | P-matrix check | a ray with `M`'s symmetric part positive definite is `ill_conditioned` | Cholesky of `(M + M')/2 - CERT_EPS n eps_64 max abs(M_ij) I` succeeds (orders up to `PD_CHECK_MAX_ORDER` = 4000 in `src/evidence.rs`) |
//! | underflow | a datum is rejected ([`crate::PlcpError::Underflow`]) | nonzero and below [`crate::Scalar::min_normal`] in the working type |
//! | doubtful success | with `Settings::escalate`, a path that ends `reached`, `unbounded_ray` or `secondary_ray` in `f32`/`f64` on a basis whose condition estimate times `eps` exceeded [`ESCALATE_COND_EPS`] (`1e-5`: fewer than about five digits left) is continued in `fx128` like an `ill_conditioned` one |
//! | restart check | an `fx128` warm restart inside segment `k` must be feasible back to the segment's start `L_k` (else events lie between: the basis is not the path's there) | a `z` or `w` negative at `L_k` must reach zero within `sqrt(eps) * max(1, abs(L_k), segment)` of `L_k` (`eps` of the working precision: what its breakpoint can be off by) |
//! | principal pivoting (fast path) | `plcp/src/principal.rs` hands a dense standard-form problem back to the general engine | two ratios, a ratio and zero, or a ratio and `L_max - L` within `PRINCIPAL_TIE_EPS * eps * max(1, abs(L), abs(L_max))` ([`PRINCIPAL_TIE_EPS`] `= 1e6`), or a blocking rate within `PRINCIPAL_TIE_EPS * eps` of the segment's largest rate; a pivot (`s = M_jj - M_jB G M_Bj` or `G_jj`) not above `PRINCIPAL_PIVOT_EPS * eps` times the magnitude of its terms ([`PRINCIPAL_PIVOT_EPS`] `= 1e6`); the rows of `B` off by more than `PRINCIPAL_RESIDUAL_EPS * eps` relative after a fresh inversion, or a basic value below `-PRINCIPAL_RESIDUAL_EPS * eps * max(1, max abs(x))` ([`PRINCIPAL_RESIDUAL_EPS`] `= 1e3`); the bound `max(1, max_B abs(M_j)_1) max(1, abs(G)_1 (1 + abs(M)_1))` of the basis' 1-norm condition times `eps` above [`PRINCIPAL_MAX_COND_EPS`] (`1e-8`); `G` inverted afresh every [`PRINCIPAL_REINVERT_PERIOD`] pivots, the values and slopes computed afresh every [`PRINCIPAL_REFRESH_PERIOD`] (updated by a column of `G` between); orders above [`PRINCIPAL_MAX_N`] |
//! | breakpoint re-intersection | Lemke on the Schur reduction: a breakpoint moves to where the polished segment's leaving variable is zero | only by `<= sqrt(eps) * max(1, abs(L))` |

use crate::scalar::Scalar;

/// The data's unit `U` in the residuals of a point
/// ([`crate::residual::residual`]): `min(max |q|, max |d|)` over those that
/// are nonzero. Row `r` of the equation residual is measured against
/// `max(s_r, U)`, `s_r = max(|q_r|, |L d_r|, |w_r|, max_j |M_rj x_j|)` its
/// own terms; `w` against `max(U, max |w|)`; `z` against
/// `max(U / max |M_ij|, max |z|)` (over the columns of nonzero `z`).
///
/// It replaces an absolute floor of `1` (issue 14), with which data scaled by
/// `1e-30`, or an LCP with `q` of `1e-4`, looked accurate whatever the
/// answer: `U` scales with `(M, q, d)`, so a uniform scaling leaves every
/// residual unchanged. On the frames (unit loads, capacities of one or more)
/// it is the floor of `1` it replaces.
///
/// Why the smaller of the two, and why a floor at all (measured):
///
/// * no floor (each row against its own terms only) raises false alarms on
///   correct paths: rows whose own terms are all rounding carry the rounding
///   of the others (`7.7e-14` on the 20-element cantilever at `L = 0`);
/// * a floor at the whole data's size (`max |q|`, `max(|q|, |L d|)`, the
///   normwise `max_r s_r`, or Arioli-Demmel-Duff's `max_j |M_rj| max |x|`)
///   hides in f32 the wrong path of `scenes/stiff/lengths-portal.toml`
///   (capacities up to `1e6`, unit load: an equation row off by `1.0`, all
///   its own terms of size one, read as `1e-6`; breakpoints off by 50%,
///   `tests/stiff.rs`), which `U`, the load's unit there, flags;
/// * with `U` a warm time step of `frames::timestep` (`q` of size one, `d`
///   the step's increment, `2.7e-4`) reads its rounding (`3e-18` absolute,
///   `0.01 eps` of the data, in the rows of the rigid velocities) relative
///   to the increment: `1e-14`, growing with the velocities' rounding drift
///   to about `3e-12` over `10^4` steps; far below the residual guard
///   (`sqrt(eps)`), so no step restarts cold.
pub fn residual_unit<T: Scalar>(q: faer::ColRef<'_, T>, d: faer::ColRef<'_, T>) -> f64 {
    let max = |c: faer::ColRef<'_, T>| c.iter().fold(0.0f64, |a, v| a.max(v.to_f64().abs()));
    let (mq, md) = (max(q), max(d));
    let u = match (mq > 0.0, md > 0.0) {
        (true, true) => mq.min(md),
        (true, false) => mq,
        _ => md,
    };
    u.max(f64::MIN_POSITIVE)
}

/// The margin of the residual guard's cheap measure
/// (`residual::measure_for_guard`): the trace's breakpoint residuals
/// bound the documented residual of the segments' starts (times `kappa`,
/// derived there), not of their ends, which are evaluated `z_from + dz dL`;
/// a factor two covers that evaluation (measured: the end of the segment of
/// `prop_path.rs f32_p_matrix`'s failing instance had `1.0001` times its
/// start's residual). Below the margin the path is measured whole.
pub const GUARD_SLACK: f64 = 2.0;

/// With [`crate::Settings::escalate`], a path in `f32`/`f64` that claims an
/// end (`reached`, a ray) on a basis with `cond * eps` above this is checked
/// in `fx128` ([`crate::Escalation`]): its breakpoints carry relative errors of
/// about `cond * eps`, and a column entry below that level is lost to
/// cancellation, which turns a blocking row into a false ray (the stiffest
/// frame of issue 14: `cond = 2.8e13` in f64, the event at `L = 1.02e16`
/// lost and the last segment claimed unbounded, residual `1.2e-8` just below
/// the residual guard's `sqrt(eps)`). Above the `1000`-element cantilever's
/// `cond * eps = 8.8e-7` (traced right in f64), so that stays in f64.
pub const ESCALATE_COND_EPS: f64 = 1e-5;

/// The largest order `p + n` continued in exact arithmetic by
/// [`crate::Settings::escalate_exact`]: the exact tracer solves each basis
/// from scratch in big integers (dense `n = 100` certifies in about a second,
/// `n = 200` in tens of seconds, `docs/certification.md`), so larger paths stay
/// `ill_conditioned` with a note rather than take minutes unasked.
pub const ESCALATE_EXACT_MAX_DIM: usize = 200;

/// Entries of a row of `B^{-1}` (sparse basis, lexicographic rule) below this
/// many `eps` times the row's largest entry are rounding noise, zeros of the
/// exact inverse.
pub const ROW_NOISE_EPS: f64 = 1e3;

/// Basic values at breakpoints are refined with residuals in the wide type
/// ([`Scalar::Wide`]) once the basis condition estimate times `eps` exceeds
/// this (and `Settings::refine_cond_eps`); below it, in the working precision,
/// on evidence. The wide residual is a pass over the basic columns in extended
/// arithmetic (on a dense `M`, `O(n k)` per breakpoint: ten times the path's
/// cost at `n = 1000`); below `cond ~ 4.5e6` (f64) the working precision's
/// refinement already leaves forward errors under `1e-9` relative. On a
/// sparse `M` (a pass over its stored entries) the wide residuals start with
/// the column refinement, at `Settings::refine_cond_eps`: the long cantilever's
/// degenerate plastic multipliers need them from a condition of about `1e5`.
pub const WIDE_REFINE_COND_EPS: f64 = 1e-9;

/// The block basis refines entering columns on its block while the
/// refinement does something: once [`REFINE_IDLE_RUN`] corrections in a row
/// came out below this many `eps` relative to the column's largest block
/// entry (rounding level: the solve was as good as a backward-stable one),
/// it pauses for 8, 16, ... up to 64 solves, then refines one column again
/// as a probe; a larger correction ends the pause. On the dense random
/// monotone instances (`cond ~ 2e4`) the corrections stay between 4 and 80
/// eps, and refinement was a fifth of the path's time.
pub const REFINE_IDLE_EPS: f64 = 64.0;

/// Consecutive rounding-level corrections before the block basis pauses its
/// refinement (see [`REFINE_IDLE_EPS`]).
pub const REFINE_IDLE_RUN: usize = 8;

/// The rank tolerance of the full-pivoting LU of a free block: `dim * eps * 1e2`
/// times the largest pivot. Pivots below it count as zero.
pub fn rank_tol<T: Scalar>(dim: usize, largest_pivot: T) -> T {
    T::from_f64(100.0 * (dim.max(1) as f64)) * T::eps() * largest_pivot
}

/// The factor applied to the tie tolerance of the reduced path when a mixed
/// problem is solved by Lemke on its Schur reduction: the reduced data carry an
/// error of about `eps cond(F)`, so ratios and steps of `L` within that are ties.
/// `cond(F)`, but never so much that the tie tolerance `tie_tol_eps * eps`
/// exceeds `sqrt(eps)` (beyond that a tie would hide real steps of the path;
/// the residual guard and Wolfe's long form are then the remedy), and at least 1.
pub fn reduction_tie_factor<T: Scalar>(cond_f: f64, tie_tol_eps: f64) -> f64 {
    let eps = T::eps().to_f64();
    let cap = (eps.sqrt() / (tie_tol_eps * eps)).max(1.0);
    if cond_f.is_finite() {
        cond_f.clamp(1.0, cap)
    } else {
        cap
    }
}

// ---------------------------------------------------------------------------
// The drift control of the MPC loop ([`crate::Solver`]; issue 20)
// ---------------------------------------------------------------------------

/// The end residual, in `eps`, up to which the next step of a
/// [`crate::Solver`] starts from the basic values its engine holds instead
/// of solving for them with the factorisation (when the step's data continue
/// the last end: `q_k = q_{k-1} + d_{k-1}` to one rounding of the sum).
///
/// The end residual decides because it is measured on the data every step
/// anyway ([`crate::residual::residual_parts`]'s rule): the drift of held
/// values and of an updated factorisation shows there first. Measured on
/// the MPC loop of `docs/performance.md` (n = 50, 1000 steps, 756 pivots),
/// against a loop that refactorises after every step (worst end residual
/// 2.5e-15): the earlier fixed period of 50 pivots with a fresh values solve
/// each step differed by up to 7.0e-14 in z (relative) with worst residual
/// 1.9e-14; this policy (8 here and 64 in [`FACTOR_KEPT_EPS`]) by 3.2e-14
/// with worst residual 1.5e-14, at 8 % fewer instructions a step. Looser
/// thresholds drift: kept values with no refactorisation below 1e3 `eps`
/// saved 20 % of the instructions but let residuals grow to 2.9e-14
/// (`FACTOR_KEPT_EPS = 16`: 71.6 k instructions a step, 64: 70.6 k). Most
/// end residuals of that loop are 2..18 `eps`, so the values solve still
/// runs in most steps.
pub const VALUES_KEPT_EPS: f64 = 8.0;

/// The end residual, in `eps`, up to which a [`crate::Solver`] waives the
/// periodic refactorisation for the pivots of a step (up to a cap of 1000
/// pivots); above it, it refactorises at once (see [`VALUES_KEPT_EPS`] for
/// the measurements). With an explicit [`crate::Settings::refactor_period`]
/// the user's period holds instead.
pub const FACTOR_KEPT_EPS: f64 = 64.0;

// ---------------------------------------------------------------------------
// Near ties of the minimum-ratio test (issue 14; `pivoting/ratio.rs`)
// ---------------------------------------------------------------------------

/// Safety factor of the error bounds of refined ratios (near ties): the
/// wide residual's accumulation error and the solve's backward error are
/// taken as this many roundings of the terms they come from
/// (`|B^{-1}|_r (TIE_ERROR_GAMMA eps_wide |B| |x| + eps |r| + cond eps |r| +
/// TIE_ERROR_GAMMA eps |B| |dx|)`, doubled).
pub const TIE_ERROR_GAMMA: f64 = 8.0;

/// Rows that tie in the minimum-ratio test (within the tie tolerance) are
/// read again with values and column entries refined by one step with the
/// residual in the wide type, each ratio with an error bound. Ratios
/// separated beyond their bounds are the exact order (the smallest leaves).
/// Ratios within their bounds are a tie for the lexicographic rule when the
/// bound, as a step of `L`, is within this many `eps` of `max(1, |L|)` (of
/// the ratio and `max(1, max |x|) / |col_r|` when `L` does not move): two
/// breakpoints the working precision cannot tell apart. A larger bound
/// leaves the order undecided and the trace stops `ill_conditioned` (a
/// higher precision or exact arithmetic decides).
///
/// The bound is a conservative first-order one, and fx128 has no wider type
/// to refine in (its residual is accumulated in fx128): exact ties of the
/// paper's cantilever traced with Lemke in fx128 have bounds of 1.3 to 2.2
/// thousand roundings of `L` (measured; 1e3 stopped that trace), while the
/// undecided tie of the Fibonacci block of `docs/limits.md` has a bound
/// 4.5e12 times 1e3 roundings. 1e5 keeps a factor of 45 over the first and
/// 4.5e10 under the second.
pub const TIE_RESOLUTION_EPS: f64 = 1e5;

/// A near tie is not read again once the basis condition estimate times
/// `eps` exceeds this (one refinement step no longer converges): it is
/// undecided.
pub const TIE_REFINE_MAX_COND_EPS: f64 = 0.1;

/// At most this many rows whose entering-column entry is below the pivot
/// tolerance, yet whose ratio would block first, are read again with a
/// refined column at one ratio test (the smallest ratios;
/// `pivoting/ratio.rs`, `read_small_entries`): an entry the refinement
/// separates from zero beyond its error bound blocks.
pub const SMALL_ENTRY_READS: usize = 4;

/// On a ray with no end (`L` rising, no `lambda_max`) a column entry is read
/// again as a possible block (`pivoting/ratio.rs`, `read_ray_end`) only
/// above this many roundings of the working column, `RAY_ENTRY_EPS eps
/// |col|_max`, in its working and its refined value: a floor that does not
/// grow with `L` (a step bound there is infinite). Below it a refined entry
/// of an exact zero can survive its first-order error bound (a random
/// system (9) read `1.6e-30` against a bound of `7.5e-31` at `L = 2.9e31`,
/// where the ray is certified exactly); a real event of a rate that small
/// is lost (`docs/limits.md`). The rates this reads: f32's lost event,
/// `3.1e-4` of `0.475` (5000 roundings); the block `[[1, 1], [1, 1 +
/// 2^-46]]` in f64, `2^-46` of one (64).
pub const RAY_ENTRY_EPS: f64 = 16.0;

/// Principal pivoting (`plcp/src/principal.rs`): two ratios (or a ratio and zero,
/// or a ratio and `L_max - L`) closer than this many `eps` (relative to
/// `max(1, |L|, |L_max|)`) are not decided there; the general engine takes the
/// problem.
pub const PRINCIPAL_TIE_EPS: f64 = 1e6;

/// Principal pivoting: a pivot must exceed this many `eps` times the
/// magnitude of the terms it is computed from (else it may be rounding).
pub const PRINCIPAL_PIVOT_EPS: f64 = 1e6;

/// Principal pivoting: the rows of the basic block must hold to this many
/// `eps` (relative to their terms), and no basic value may be negative beyond
/// this many `eps` of the largest.
pub const PRINCIPAL_RESIDUAL_EPS: f64 = 1e3;

/// Principal pivoting: the basis' condition bound times `eps` may not exceed
/// this (`1e-8`: about eight digits kept in `f64`); the general engine, with
/// its refinement, takes harder problems.
pub const PRINCIPAL_MAX_COND_EPS: f64 = 1e-8;

/// Principal pivoting: the explicit inverse is computed afresh (LU with
/// partial pivoting) every this many pivots.
pub const PRINCIPAL_REINVERT_PERIOD: usize = 64;

/// Principal pivoting: between fresh evaluations the basic `z` and the
/// slopes after a pivot are updated by the pivot's column of `G` (the values
/// `w` are recomputed at every pivot, so each breakpoint's residual is
/// measured afresh); every this many pivots, and after every inversion, all
/// of them are computed afresh from `G`.
pub const PRINCIPAL_REFRESH_PERIOD: usize = 8;

/// Principal pivoting: the largest order the fast path takes (above it the
/// general engine's blocked products are faster: one thread, best of 6 to
/// 15 calls alternated, the fast path took 20.4 / 59.7 / 98.7 ms against
/// the engine's 31.2 / 93.5 / 125.2 ms at n = 500 / 700 / 850 and about the
/// same at 1000; `docs/performance.md`, "The fast path's order cap").
pub const PRINCIPAL_MAX_N: usize = 800;
