//! Parametric principal pivoting on an explicit inverse: the fast path of a
//! dense standard-form problem at everyday sizes.
//!
//! For `w = q + L d + M z`, `w, z >= 0`, `w'z = 0` with `q + L0 d > 0` the
//! path starts with every `w` basic. Away from ties, zero steps, small pivots
//! and ill-conditioning, every breakpoint of Lemke's parametric path is then a
//! principal pivot: `w_j` reaching zero adds `j` to the set `B` of basic `z`
//! (and `z_j` grows from zero), `z_j` reaching zero takes `j` out of it. With
//! `S = M_BB` and its explicit inverse `G = S^-1` (bordered on an addition,
//! contracted on a removal, `O(k^2)` for `k = |B|`), a segment's values are
//!
//! ```text
//! z_B = -G (q_B + L d_B),   w = q + L d + M_{:,B} z_B   (w_B = 0),
//! ```
//!
//! and their slopes the same with `d` alone: `O(k^2 + n k)` a pivot (faer's
//! products over `G` and a copy of `M_{:,B}`), no factorisation of the whole
//! basis, no refinement, no lexicographic rows.
//! Between fresh evaluations (every
//! [`crate::tolerance::PRINCIPAL_REFRESH_PERIOD`] pivots and at every
//! inversion) the basic `z` move to the breakpoint along their slopes and
//! the slopes change by the pivot's column of `G` (`w` afresh and `dw`
//! updated in one product over `M_{:,B}`): no product over `G`.
//!
//! The kernel decides only what it decides with margin. It hands the problem
//! back (an `Err` saying why, before any segment is handed out) on: an order
//! above [`crate::tolerance::PRINCIPAL_MAX_N`]; a start that is not
//! strictly feasible; two ratios within [`crate::tolerance::PRINCIPAL_TIE_EPS`]
//! of each other, or a ratio that close to zero or to `L_max`; a blocking
//! rate within that many `eps` of the segment's largest rate; a pivot (the
//! Schur complement `s = M_jj - M_jB G M_Bj` of an addition, `G_jj` of a
//! removal) not positive beyond the rounding of its terms, so `L` never turns;
//! the condition bound of the complementary basis times `eps` above
//! [`crate::tolerance::PRINCIPAL_MAX_COND_EPS`]; the rows of `B` not satisfied
//! to [`crate::tolerance::PRINCIPAL_RESIDUAL_EPS`] after a fresh inversion; no
//! finite `L_max`; an observer; the pivot limit. The caller then traces the
//! problem from the start with the general engine ([`crate::pivoting`]), so
//! every case the kernel declines is answered as before. What it returns is
//! measured on the original problem and guarded like every path.

use crate::path::{Breakpoint, Info, Path, Point, Residual, Segment, Status, Var};
use crate::scalar::Scalar;
use crate::tolerance::{
    PRINCIPAL_MAX_COND_EPS, PRINCIPAL_PIVOT_EPS, PRINCIPAL_REFRESH_PERIOD,
    PRINCIPAL_REINVERT_PERIOD, PRINCIPAL_RESIDUAL_EPS, PRINCIPAL_TIE_EPS,
};
use faer::{Col, MatRef};

/// The kernel's state: the basic set, the inverse of its block, the values and
/// slopes at the current `L`.
pub(crate) struct Kernel<'a, T: Scalar> {
    n: usize,
    cols: Vec<&'a [T]>,
    /// the vectors and matrices, sized by `n` (kept on the thread after the
    /// kernel for the next one: [`Buffers::swap_with_thread`])
    buf: Buffers<T>,
    lambda: T,
    /// the largest of `||M_{:,j}||_1` (`||M||_1`)
    m_norm1: T,
    /// `M_BB` symmetric (exactly): then so is `G` (to rounding), and an
    /// addition with `M_jB = M_Bj'` takes `G' v = G u` (one product)
    block_symmetric: bool,
    max_cond: f64,
    /// the condition bound of the current basis, `None` after a pivot
    cond_now: Option<f64>,
    inversions: usize,
    pivots_since_inversion: usize,
    /// pivots since the values and slopes were last computed afresh
    since_fresh: usize,
}

/// A kernel's vectors and matrices. They outlive it on its thread, for the
/// next kernel (`f64` only): a small solve paid about 18 allocations and the
/// zeroing of `G` and `M_{:,B}` (`n^2` each) for every call. A thread keeps at
/// most one kernel's buffers, and only of a kernel of order at most
/// [`SPARE_MAX_N`] (`2 n^2 + 18 n` numbers, 0.3 MB there): above it the
/// allocations are a small part of a solve and the memory would stay with
/// the thread.
struct Buffers<T: Scalar> {
    q: Vec<T>,
    d: Vec<T>,
    /// `B` in the order of `G`'s rows and columns.
    set: Vec<usize>,
    /// position of `i` in `set`, or `usize::MAX`
    pos: Vec<usize>,
    /// the complementary basis (`Z(i)` for `i` in `B`, else `W(i)`)
    vars: Vec<Var>,
    /// `G = S^-1`, column-major with stride `n` (`G[a + b n]`).
    g: Vec<T>,
    /// `M_{:,B}`: column `a` is `M`'s column `set[a]` (stride `n`), for the
    /// blocked product of the values
    mb: Vec<T>,
    /// work: `[q_B + L d_B | d_B]` and `[z_B | dz_B]` (`k x 2`, stride `n`),
    /// `[w | dw]` (`n x 2`)
    rhs2: Vec<T>,
    zb2: Vec<T>,
    w2: Vec<T>,
    /// values and slopes: `z` (all `n`, zero off `B`), `w` (zero on `B`)
    z: Vec<T>,
    dz: Vec<T>,
    w: Vec<T>,
    dw: Vec<T>,
    // work vectors of length n
    u: Vec<T>,
    v: Vec<T>,
    gu: Vec<T>,
    vg: Vec<T>,
    /// `|G_{:,b}|_1` of `G`'s columns, kept with `G` (the condition bound)
    gsum: Vec<T>,
    /// `||M_{:,j}||_1` of every column
    col_norm1: Vec<T>,
}

impl<T: Scalar> Buffers<T> {
    fn empty() -> Self {
        let e = Vec::new;
        Buffers {
            q: e(),
            d: e(),
            set: Vec::new(),
            pos: Vec::new(),
            vars: Vec::new(),
            g: e(),
            mb: e(),
            rhs2: e(),
            zb2: e(),
            w2: e(),
            z: e(),
            dz: e(),
            w: e(),
            dw: e(),
            u: e(),
            v: e(),
            gu: e(),
            vg: e(),
            gsum: e(),
            col_norm1: e(),
        }
    }

    /// Sized and set for a kernel of order `n` with every `w` basic. The old
    /// contents are never read before they are written: `G` and `M_{:,B}`
    /// (kept if already `n x n`) only over the current `B`.
    fn reset(&mut self, n: usize) {
        for v in [
            &mut self.q,
            &mut self.d,
            &mut self.z,
            &mut self.dz,
            &mut self.w,
            &mut self.dw,
            &mut self.u,
            &mut self.v,
            &mut self.gu,
            &mut self.vg,
            &mut self.gsum,
        ] {
            v.clear();
            v.resize(n, T::zero());
        }
        for v in [&mut self.rhs2, &mut self.zb2, &mut self.w2] {
            v.clear();
            v.resize(2 * n, T::zero());
        }
        if self.g.len() != n * n || self.mb.len() != n * n {
            self.g.clear();
            self.mb.clear();
        }
        self.set.clear();
        self.pos.clear();
        self.pos.resize(n, usize::MAX);
        self.vars.clear();
        self.vars.extend((0..n).map(Var::W));
        self.col_norm1.clear();
    }

    /// `G` and `M_{:,B}` sized `n x n` (their entries are written before
    /// they are read). Allocated zeroed where they have no room: the
    /// allocator's zero pages, so that only the columns the basis reaches
    /// are ever touched (a solve at `n = 200` paid one page fault per 4 kB of
    /// the two, about 160, in a fresh process).
    fn square(&mut self, n: usize) {
        for v in [&mut self.g, &mut self.mb] {
            if v.len() < n * n {
                if v.capacity() < n * n {
                    *v = vec![T::zero(); n * n];
                } else {
                    v.resize(n * n, T::zero());
                }
            }
        }
    }

    /// Swaps `self` with the thread's spare buffers (`f64` only; else, or
    /// where the thread's are in use or gone, nothing).
    fn swap_with_thread(&mut self) {
        if let Some(mine) = (self as &mut dyn core::any::Any).downcast_mut::<Buffers<f64>>() {
            let _ = SPARE.try_with(|s| {
                if let Ok(mut s) = s.try_borrow_mut() {
                    core::mem::swap(&mut *s, mine);
                }
            });
        }
    }
}

std::thread_local! {
    static SPARE: core::cell::RefCell<Buffers<f64>> = core::cell::RefCell::new(Buffers::empty());
}

/// The largest order whose buffers a thread keeps ([`Buffers`]).
const SPARE_MAX_N: usize = 128;

impl<T: Scalar> Drop for Kernel<'_, T> {
    fn drop(&mut self) {
        if self.n <= SPARE_MAX_N {
            // (the thread's previous buffers are freed with `self.buf`)
            self.buf.swap_with_thread();
        }
    }
}

/// Why the kernel handed a problem back (for tests and the trace log).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Decline {
    NotEligible,
    StartNotInterior,
    Tie,
    SmallPivot,
    Condition,
    Residual,
    Negative,
    PivotLimit,
}

impl Decline {
    /// Why, in words ([`crate::Info::fast_path`]).
    pub(crate) fn reason(self) -> &'static str {
        match self {
            Decline::NotEligible => {
                "not tried: outside its scope (L_max below L0, or M not stored by contiguous columns)"
            }
            Decline::StartNotInterior => {
                "declined: the start is not strictly feasible (a basic value at or below zero at L0)"
            }
            Decline::Tie => {
                "declined: a tie (two events, or an event and L_max, within the tie tolerance; a zero step; or a blocking rate that may be rounding)"
            }
            Decline::SmallPivot => {
                "declined: a pivot below its tolerance (a turning point or a nearly singular block)"
            }
            Decline::Condition => "declined: the basis' condition bound above 1e8",
            Decline::Residual => "declined: the basis' rows off after a fresh inversion",
            Decline::Negative => "declined: a basic value below zero after a pivot",
            Decline::PivotLimit => "declined: the pivot limit",
        }
    }
}

/// Traces a dense standard-form problem by principal pivoting, or declines.
pub(crate) fn trace<T: Scalar>(
    m: MatRef<'_, T>,
    q: faer::ColRef<'_, T>,
    d: faer::ColRef<'_, T>,
    lambda0: T,
    lambda_max: Option<T>,
    max_pivots: usize,
    label: &'static str,
) -> Result<Path<T>, Decline> {
    let timer = std::time::Instant::now();
    let Some(lmax) = lambda_max.filter(|l| l.is_finite()) else {
        return Err(Decline::NotEligible);
    };
    if lmax < lambda0 || crate::observe::observing() {
        return Err(Decline::NotEligible);
    }
    let mut k = Kernel::new(m).ok_or(Decline::NotEligible)?;
    k.load(q, d, lambda0)?;
    let n = k.n;
    let mut rec = (Vec::with_capacity(n / 2 + 2), Vec::with_capacity(n / 2 + 1));
    k.run(lmax, max_pivots, Some(&mut rec))?;
    let (segments, breakpoints) = rec;
    let end = k.point_at(lmax);
    let info = Info {
        method: label,
        precision: T::NAME,
        pivots: breakpoints.len(),
        refactorisations: k.inversions,
        max_condition: k.max_cond,
        solve_seconds: timer.elapsed().as_secs_f64(),
        ..Info::default()
    };
    Ok(Path {
        status: Status::Reached,
        lambda0,
        lambda_max,
        lambda_reached: lmax,
        breakpoints,
        segments,
        end,
        ray: None,
        message: String::new(),
        info,
        final_basis: Some(k.basis()),
    })
}

/// What a traced path records: its segments and breakpoints.
pub(crate) type Record<T> = (Vec<Segment<T>>, Vec<Breakpoint<T>>);

/// `k x c` view of `buf` (column-major, stride `n`).
fn view<T: Scalar>(buf: &[T], k: usize, c: usize, n: usize) -> MatRef<'_, T> {
    MatRef::from_column_major_slice_with_stride(&buf[..(c.max(1) - 1) * n + k], k, c, n)
}

fn view_mut<T: Scalar>(buf: &mut [T], k: usize, c: usize, n: usize) -> faer::MatMut<'_, T> {
    faer::MatMut::from_column_major_slice_with_stride_mut(
        &mut buf[..(c.max(1) - 1) * n + k],
        k,
        c,
        n,
    )
}

/// `dst[:rows, :cols] (+)= alpha a[:rows, :k] b[:k, :cols]` (all
/// column-major, stride `n`) on the calling thread.
fn axpys<T: Scalar>(
    dst: &mut [T],
    add: bool,
    a: &[T],
    b: &[T],
    alpha: T,
    (rows, k, cols, n): (usize, usize, usize, usize),
) {
    if k == 0 {
        if !add {
            for c in 0..cols {
                dst[c * n..c * n + rows]
                    .iter_mut()
                    .for_each(|x| *x = T::zero());
            }
        }
        return;
    }
    let accum = if add {
        faer::Accum::Add
    } else {
        faer::Accum::Replace
    };
    faer::linalg::matmul::matmul(
        view_mut(dst, rows, cols, n),
        accum,
        view(a, rows, k, n),
        view(b, k, cols, n),
        alpha,
        faer::Par::Seq,
    );
}

/// `G[:k, :k] += x (alpha y)'` (column-major, stride `n`), and the
/// absolute sums of the updated columns over their rows other than `skip`
/// into `sums` (the condition bound's `|G|_1`, kept with `G`: no pass of
/// its own). Pulp's dispatch as [`axpys`].
#[allow(clippy::too_many_arguments)]
fn rank_one<T: Scalar>(
    g: &mut [T],
    n: usize,
    k: usize,
    x: &[T],
    y: &[T],
    alpha: T,
    skip: usize,
    sums: &mut [T],
) {
    if k == 0 {
        return;
    }
    pulp::Arch::new().dispatch(RankOne {
        g,
        n,
        k,
        x,
        y,
        alpha,
        skip,
        sums,
    });
}

struct RankOne<'a, T: Scalar> {
    g: &'a mut [T],
    n: usize,
    k: usize,
    x: &'a [T],
    y: &'a [T],
    alpha: T,
    skip: usize,
    sums: &'a mut [T],
}

impl<T: Scalar> pulp::WithSimd for RankOne<'_, T> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        let Self {
            g,
            n,
            k,
            x,
            y,
            alpha,
            skip,
            sums,
        } = self;
        let x = &x[..k];
        for b in 0..k {
            let c = alpha * y[b];
            let col = &mut g[b * n..b * n + k];
            for (gv, &xv) in col.iter_mut().zip(x) {
                *gv += xv * c;
            }
            sums[b] = if skip < k {
                abs_sum(&col[..skip]) + abs_sum(&col[skip + 1..])
            } else {
                abs_sum(col)
            };
        }
    }
}

/// `vg[b] = G_{:,b}' v` for `G`'s first `k` columns (over their first `k`
/// rows), each in four running sums; pulp's dispatch as [`axpys`].
fn col_dots<T: Scalar>(g: &[T], n: usize, k: usize, v: &[T], vg: &mut [T]) {
    struct Pass<'a, T: Scalar>(&'a [T], usize, usize, &'a [T], &'a mut [T]);
    impl<T: Scalar> pulp::WithSimd for Pass<'_, T> {
        type Output = ();
        #[inline(always)]
        fn with_simd<S: pulp::Simd>(self, _simd: S) {
            let Pass(g, n, k, v, vg) = self;
            let v = &v[..k];
            for b in 0..k {
                let col = &g[b * n..b * n + k];
                let mut acc = [T::zero(); 4];
                let (mut cc, mut vc) = (col.chunks_exact(4), v.chunks_exact(4));
                for (c, w) in (&mut cc).zip(&mut vc) {
                    for l in 0..4 {
                        acc[l] += c[l] * w[l];
                    }
                }
                let mut s = (acc[0] + acc[1]) + (acc[2] + acc[3]);
                for (&c, &w) in cc.remainder().iter().zip(vc.remainder()) {
                    s += c * w;
                }
                vg[b] = s;
            }
        }
    }
    pulp::Arch::new().dispatch(Pass(g, n, k, v, vg));
}

/// The absolute sums of `G`'s first `k` columns (over their first `k`
/// rows) into `sums`, pulp's dispatch as [`axpys`].
fn col_sums<T: Scalar>(g: &[T], n: usize, k: usize, sums: &mut [T]) {
    struct Pass<'a, T: Scalar>(&'a [T], usize, usize, &'a mut [T]);
    impl<T: Scalar> pulp::WithSimd for Pass<'_, T> {
        type Output = ();
        #[inline(always)]
        fn with_simd<S: pulp::Simd>(self, _simd: S) {
            let Pass(g, n, k, sums) = self;
            for b in 0..k {
                sums[b] = abs_sum(&g[b * n..b * n + k]);
            }
        }
    }
    pulp::Arch::new().dispatch(Pass(g, n, k, sums));
}

/// `sum_i abs(x_i)`, in four running sums (the order of a bound's terms
/// does not matter; four lanes let the compiler vectorise).
#[inline(always)]
fn abs_sum<T: Scalar>(x: &[T]) -> T {
    let mut acc = [T::zero(); 4];
    let mut chunks = x.chunks_exact(4);
    for c in &mut chunks {
        for (a, &v) in acc.iter_mut().zip(c) {
            *a += v.abs();
        }
    }
    let mut s = (acc[0] + acc[1]) + (acc[2] + acc[3]);
    for &v in chunks.remainder() {
        s += v.abs();
    }
    s
}

/// `x > bound`, false where either is NaN (a NaN declines).
fn clearly_above<T: Scalar>(x: T, bound: T) -> bool {
    x.partial_cmp(&bound) == Some(core::cmp::Ordering::Greater)
}

impl<'a, T: Scalar> Kernel<'a, T> {
    /// The kernel for `M` (square, dense, contiguous columns, order at most
    /// [`crate::tolerance::PRINCIPAL_MAX_N`]), with every `w` basic.
    pub(crate) fn new(m: MatRef<'a, T>) -> Option<Self> {
        let n = m.nrows();
        if n == 0 || n > crate::tolerance::PRINCIPAL_MAX_N || m.ncols() != n || T::NAME != "f64" {
            return None;
        }
        let mut cols = Vec::with_capacity(n);
        for j in 0..n {
            cols.push(m.col(j).try_as_col_major()?.as_slice());
        }
        // the buffers of the last kernel dropped on this thread, if any
        let mut buf = Buffers::empty();
        buf.swap_with_thread();
        buf.reset(n);
        buf.col_norm1.extend(
            cols.iter()
                .map(|c| c.iter().fold(T::zero(), |a, &x| a + x.abs())),
        );
        let m_norm1 = buf.col_norm1.iter().fold(T::zero(), |a, &x| a.max(x));
        Some(Kernel {
            n,
            cols,
            buf,
            lambda: T::zero(),
            m_norm1,
            block_symmetric: true,
            max_cond: 1.0,
            cond_now: None,
            inversions: 0,
            pivots_since_inversion: 0,
            since_fresh: 0,
        })
    }

    /// Makes `set` the basic `z` (`G` inverted afresh).
    pub(crate) fn set_basis(&mut self, set: &[usize]) -> Result<(), Decline> {
        let n = self.n;
        if set.iter().any(|&i| i >= n) {
            return Err(Decline::NotEligible);
        }
        for &i in &self.buf.set {
            self.buf.pos[i] = usize::MAX;
            self.buf.vars[i] = Var::W(i);
        }
        self.buf.set.clear();
        if !set.is_empty() {
            self.buf.square(n);
        }
        for (a, &i) in set.iter().enumerate() {
            if self.buf.pos[i] != usize::MAX {
                return Err(Decline::NotEligible);
            }
            self.buf.pos[i] = a;
            self.buf.vars[i] = Var::Z(i);
            self.buf.set.push(i);
            self.buf.mb[a * n..a * n + n].copy_from_slice(&self.cols[i][..n]);
        }
        self.block_symmetric = set
            .iter()
            .enumerate()
            .all(|(a, &i)| set[..a].iter().all(|&h| self.m(h, i) == self.m(i, h)));
        self.invert()
    }

    /// The largest condition bound met so far.
    pub(crate) fn max_condition(&self) -> f64 {
        self.max_cond
    }

    /// The basic `z` (in `G`'s order).
    pub(crate) fn basic_set(&self) -> &[usize] {
        &self.buf.set
    }

    /// Takes the data `q`, `d` at `lambda0` on the current basis: the values
    /// there, which must be strictly feasible (every basic value clear of
    /// zero; a zero one is a degenerate start, for the engine's
    /// lexicographic rule).
    pub(crate) fn load(
        &mut self,
        q: faer::ColRef<'_, T>,
        d: faer::ColRef<'_, T>,
        lambda0: T,
    ) -> Result<(), Decline> {
        let n = self.n;
        if q.nrows() != n || d.nrows() != n {
            return Err(Decline::NotEligible);
        }
        for (dst, &x) in self.buf.q[..n].iter_mut().zip(q.iter()) {
            *dst = x;
        }
        for (dst, &x) in self.buf.d[..n].iter_mut().zip(d.iter()) {
            *dst = x;
        }
        self.lambda = lambda0;
        // a basic value below zero here is a start that is not feasible
        self.values().map_err(|e| match e {
            Decline::Negative => Decline::StartNotInterior,
            e => e,
        })?;
        let tie = T::from_f64(PRINCIPAL_TIE_EPS) * T::eps();
        let zmax = self.buf.z.iter().fold(T::one(), |a, &x| a.max(x.abs()));
        let (pos, z, w) = (&self.buf.pos[..n], &self.buf.z[..n], &self.buf.w[..n]);
        let (qs, ds) = (&self.buf.q[..n], &self.buf.d[..n]);
        for i in 0..n {
            let ok = if pos[i] != usize::MAX {
                clearly_above(z[i], tie * zmax)
            } else {
                let s = T::one().max(qs[i].abs()).max((lambda0 * ds[i]).abs());
                clearly_above(w[i], tie * s)
            };
            if !ok {
                return Err(Decline::StartNotInterior);
            }
        }
        Ok(())
    }

    /// Traces from the loaded start to `lmax` (at most `max_pivots` pivots),
    /// recording segments and breakpoints into `rec` if given; returns the
    /// pivots. The kernel then stands on the last segment's basis with its
    /// values at that segment's start ([`Self::point_at`] gives the end).
    pub(crate) fn run(
        &mut self,
        lmax: T,
        max_pivots: usize,
        mut rec: Option<&mut Record<T>>,
    ) -> Result<usize, Decline> {
        let n = self.n;
        let tie = T::from_f64(PRINCIPAL_TIE_EPS) * T::eps();
        let mut pivots = 0;
        loop {
            // ratio test: the smallest step of L to a zero of a basic variable
            let (mut best, mut second, mut arg) = (T::max_value(), T::max_value(), usize::MAX);
            let (mut rate_max, mut rate_arg) = (T::zero(), T::zero());
            // (over slices of length n: no bounds checks in the loop)
            let (pos, z, dz) = (&self.buf.pos[..n], &self.buf.z[..n], &self.buf.dz[..n]);
            let (w, dw) = (&self.buf.w[..n], &self.buf.dw[..n]);
            for i in 0..n {
                let (x, dx) = if pos[i] != usize::MAX {
                    (z[i], dz[i])
                } else {
                    (w[i], dw[i])
                };
                rate_max = rate_max.max(dx.abs());
                if dx < T::zero() {
                    let t = x / -dx;
                    if t < best {
                        second = best;
                        best = t;
                        arg = i;
                        rate_arg = dx;
                    } else if t < second {
                        second = t;
                    }
                }
            }
            let room = lmax - self.lambda;
            let scale = T::one().max(self.lambda.abs()).max(lmax.abs());
            let window = tie * scale;
            if arg == usize::MAX || best > room + window {
                // L_max is reached inside this segment
                if let Some(rec) = rec.as_deref_mut() {
                    let seg = self.segment(lmax, false);
                    rec.0.push(seg);
                }
                return Ok(pivots);
            }
            // too close to L_max, to zero, or to the next ratio, or a blocking
            // rate that may be rounding (small against the segment's largest):
            // not decided here
            if (best - room).abs() <= window
                || best <= window
                || second - best <= window
                || rate_arg.abs() <= tie * rate_max
            {
                return Err(Decline::Tie);
            }
            if pivots >= max_pivots {
                return Err(Decline::PivotLimit);
            }
            let at = self.lambda + best;
            if let Some(rec) = rec.as_deref_mut() {
                let seg = self.segment(at, false);
                rec.0.push(seg);
            }
            // values and slopes afresh from G every PRINCIPAL_REFRESH_PERIOD
            // pivots and at every inversion; else updated by the pivot
            let fresh = self.since_fresh + 1 >= PRINCIPAL_REFRESH_PERIOD
                || self.pivots_since_inversion + 1 >= PRINCIPAL_REINVERT_PERIOD;
            if !fresh {
                self.advance(best, at);
            }
            let (leaving, entering) = if self.buf.pos[arg] != usize::MAX {
                if !fresh {
                    self.update_removal(arg);
                }
                self.remove(arg)?;
                (Var::Z(arg), Var::W(arg))
            } else {
                let dwj = self.buf.dw[arg];
                self.add(arg)?;
                if !fresh {
                    self.update_addition(arg, dwj);
                }
                (Var::W(arg), Var::Z(arg))
            };
            pivots += 1;
            self.lambda = at;
            let residual = if fresh {
                self.values()?
            } else {
                self.values_updated()?
            };
            if let Some(rec) = rec.as_deref_mut() {
                let segment = rec.0.len();
                rec.1.push(Breakpoint {
                    lambda: at,
                    entering,
                    leaving,
                    degenerate: false,
                    turning: false,
                    segment,
                    residual,
                });
            }
        }
    }

    /// The point at `l` on the current segment, written into `pt` (sized to
    /// `n`, no `u`).
    pub(crate) fn point_into(&self, l: T, pt: &mut Point<T>) {
        let n = self.n;
        if pt.z.nrows() != n || pt.w.nrows() != n {
            pt.z = Col::zeros(n);
            pt.w = Col::zeros(n);
        }
        pt.u = Col::zeros(0);
        pt.lambda = l;
        let t = l - self.lambda;
        let (z, w) = (crate::linalg::col_slice_mut(&mut pt.z), &mut pt.w);
        for i in 0..n {
            z[i] = self.buf.z[i] + self.buf.dz[i] * t;
        }
        let w = crate::linalg::col_slice_mut(w);
        for i in 0..n {
            w[i] = self.buf.w[i] + self.buf.dw[i] * t;
        }
    }
}

impl<T: Scalar> Kernel<'_, T> {
    fn m(&self, i: usize, j: usize) -> T {
        self.cols[j][i]
    }

    /// Adds `j` to `B`: `G` bordered by `s = M_jj - v G u`.
    fn add(&mut self, j: usize) -> Result<(), Decline> {
        let (n, kk) = (self.n, self.buf.set.len());
        self.buf.square(n);
        // u = M_Bj, v = M_jB; gu = G u, vg = G' v
        for a in 0..kk {
            self.buf.u[a] = self.m(self.buf.set[a], j);
            self.buf.v[a] = self.m(j, self.buf.set[a]);
        }
        axpys(
            &mut self.buf.gu,
            false,
            &self.buf.g,
            &self.buf.u,
            T::one(),
            (kk, kk, 1, n),
        );
        let symmetric = self.block_symmetric && self.buf.u[..kk] == self.buf.v[..kk];
        if symmetric {
            // v = u and G = G' (to rounding): G' v = G u
            self.buf.vg[..kk].copy_from_slice(&self.buf.gu[..kk]);
        } else {
            col_dots(&self.buf.g, n, kk, &self.buf.v, &mut self.buf.vg);
        }
        let mjj = self.m(j, j);
        let (mut vgu, mut mag) = (T::zero(), mjj.abs());
        for a in 0..kk {
            let t = self.buf.v[a] * self.buf.gu[a];
            vgu += t;
            mag += t.abs();
        }
        let s = mjj - vgu;
        if !clearly_above(s, T::from_f64(PRINCIPAL_PIVOT_EPS) * T::eps() * mag) {
            return Err(Decline::SmallPivot);
        }
        let inv = T::one() / s;
        self.block_symmetric = symmetric;
        // G + gu vg' / s, bordered by -gu / s, -vg' / s and 1 / s
        rank_one(
            &mut self.buf.g,
            n,
            kk,
            &self.buf.gu,
            &self.buf.vg,
            inv,
            usize::MAX,
            &mut self.buf.gsum,
        );
        for b in 0..kk {
            let gb = -(self.buf.vg[b] * inv);
            self.buf.g[b * n + kk] = gb;
            self.buf.gsum[b] += gb.abs();
            self.buf.g[kk * n + b] = -(self.buf.gu[b] * inv);
        }
        self.buf.g[kk * n + kk] = inv;
        self.buf.gsum[kk] = abs_sum(&self.buf.g[kk * n..kk * n + kk + 1]);
        self.buf.mb[kk * n..kk * n + n].copy_from_slice(&self.cols[j][..n]);
        self.buf.pos[j] = kk;
        self.buf.vars[j] = Var::Z(j);
        self.buf.set.push(j);
        self.after_pivot()
    }

    /// Takes `j` out of `B`: `G` contracted by its pivot `G_jj`.
    fn remove(&mut self, j: usize) -> Result<(), Decline> {
        let (n, kk) = (self.n, self.buf.set.len());
        let p = self.buf.pos[j];
        let gpp = self.buf.g[p * n + p];
        // G_jj = 1 / (Schur complement of S_{-j,-j} in S): positive beyond its
        // rounding (the terms of that complement are bounded by |G| |S|)
        let mag = (0..kk).fold(T::zero(), |a, b| a.max(self.buf.g[b * n + p].abs()));
        if !clearly_above(gpp, T::from_f64(PRINCIPAL_PIVOT_EPS) * T::eps() * mag) {
            return Err(Decline::SmallPivot);
        }
        for a in 0..kk {
            self.buf.u[a] = self.buf.g[p * n + a]; // column p
            self.buf.v[a] = self.buf.g[a * n + p]; // row p
        }
        // G - G_{:,p} G_{p,:} / G_pp (row and column p become junk, then the
        // last index moves into them)
        rank_one(
            &mut self.buf.g,
            n,
            kk,
            &self.buf.u,
            &self.buf.v,
            -(T::one() / gpp),
            p,
            &mut self.buf.gsum,
        );
        // the last index takes position p
        let last = kk - 1;
        if p != last {
            for a in 0..kk {
                self.buf.g[p * n + a] = self.buf.g[last * n + a];
            }
            for b in 0..kk {
                self.buf.g[b * n + p] = self.buf.g[b * n + last];
            }
            self.buf.gsum[p] = self.buf.gsum[last];
            self.buf.mb.copy_within(last * n..last * n + n, p * n);
            let moved = self.buf.set[last];
            self.buf.set[p] = moved;
            self.buf.pos[moved] = p;
        }
        self.buf.set.pop();
        self.buf.pos[j] = usize::MAX;
        self.buf.vars[j] = Var::W(j);
        self.after_pivot()
    }

    /// The condition bound after a pivot, and the periodic fresh inversion.
    fn after_pivot(&mut self) -> Result<(), Decline> {
        self.cond_now = None;
        self.pivots_since_inversion += 1;
        if self.pivots_since_inversion >= PRINCIPAL_REINVERT_PERIOD {
            self.invert()?;
        }
        Ok(())
    }

    /// `G` afresh from `S = M_BB` (LU with partial pivoting).
    fn invert(&mut self) -> Result<(), Decline> {
        let (n, kk) = (self.n, self.buf.set.len());
        self.inversions += 1;
        self.pivots_since_inversion = 0;
        self.cond_now = None;
        if kk == 0 {
            return Ok(());
        }
        let s = faer::Mat::<T>::from_fn(kk, kk, |a, b| self.m(self.buf.set[a], self.buf.set[b]));
        let Some((inv, _, _)) = crate::linalg::inverse_par(s.as_ref(), faer::Par::Seq) else {
            return Err(Decline::SmallPivot);
        };
        for b in 0..kk {
            for a in 0..kk {
                self.buf.g[b * n + a] = inv[(a, b)];
            }
        }
        col_sums(&self.buf.g, n, kk, &mut self.buf.gsum);
        Ok(())
    }

    /// Values and slopes at `self.lambda` from `G`; the residual of the rows
    /// of `B` (which the values must satisfy) and the condition bound of the
    /// complementary basis. One fresh inversion if those rows are off.
    fn values(&mut self) -> Result<Residual, Decline> {
        self.since_fresh = 0;
        let first = self.values_once();
        self.settle(first)
    }

    /// The rows of `B` checked after an evaluation `first`: on, or one fresh
    /// inversion and evaluation.
    fn settle(&mut self, first: Residual) -> Result<Residual, Decline> {
        let limit = PRINCIPAL_RESIDUAL_EPS * T::eps().to_f64();
        if first.equation <= limit {
            return self.checked(first);
        }
        self.since_fresh = 0;
        self.invert()?;
        let again = self.values_once();
        if again.equation <= limit {
            self.checked(again)
        } else {
            Err(Decline::Residual)
        }
    }

    fn checked(&mut self, r: Residual) -> Result<Residual, Decline> {
        // cond_1 of the basis [M_{:,B} | -I_N] is at most
        // max(1, |M_{:,B}|_1) * max(1, |G|_1 (1 + |M|_1))
        // (G changes only at a pivot or an inversion)
        let cond = match self.cond_now {
            Some(c) => c,
            None => {
                // (|G|_1 from the column sums kept with G)
                let kk = self.buf.set.len();
                let mut g1 = T::zero();
                let mut mb1 = T::zero();
                for b in 0..kk {
                    g1 = g1.max(self.buf.gsum[b]);
                    mb1 = mb1.max(self.buf.col_norm1[self.buf.set[b]]);
                }
                let c = T::one().max(mb1).to_f64()
                    * T::one().max(g1 * (T::one() + self.m_norm1)).to_f64();
                self.cond_now = Some(c);
                c
            }
        };
        if !cond.is_finite() || cond * T::eps().to_f64() > PRINCIPAL_MAX_COND_EPS {
            return Err(Decline::Condition);
        }
        self.max_cond = self.max_cond.max(cond);
        if r.feasibility > 0.0 {
            return Err(Decline::Negative);
        }
        Ok(r)
    }

    /// The values at the breakpoint `at`, `t` past the segment's start: the
    /// basic `z` moved along their slopes (the blocking one is set to zero by
    /// the pivot's update), `[q_B + L d_B | ...]` readied for the product of
    /// [`Self::values_updated`].
    fn advance(&mut self, t: T, at: T) {
        let n = self.n;
        for &i in &self.buf.set {
            self.buf.z[i] += self.buf.dz[i] * t;
        }
        // [w | dw] = [q + L d | dw] + M_{:,B} [z_B | delta]
        let (w2, dw2) = self.buf.w2.split_at_mut(n);
        for ((w2, &q), &d) in w2.iter_mut().zip(&self.buf.q[..n]).zip(&self.buf.d[..n]) {
            *w2 = q + at * d;
        }
        dw2[..n].copy_from_slice(&self.buf.dw[..n]);
    }

    /// The update of a removal of `j` (before `G` is contracted): the slopes
    /// of `z_B` change by `delta = -(dz_j / G_pp) G_{:,p}` (so `dz_j` becomes
    /// zero), those of `w` by `M_{:,B} delta`; `w` afresh from `z_B` (with
    /// `z_j = 0`), one product over `M_{:,B}`.
    fn update_removal(&mut self, j: usize) {
        let p = self.buf.pos[j];
        let c = -(self.buf.dz[j] / self.buf.g[p * self.n + p]);
        self.buf.z[j] = T::zero();
        self.update_along(p, c);
        self.buf.dz[j] = T::zero();
    }

    /// The update of an addition of `j` (after `G` is bordered), `dwj` the
    /// slope `w_j` had: `delta = -dwj G'_{:,j}` (so the slope of `w_j`
    /// becomes zero), as [`Self::update_removal`].
    fn update_addition(&mut self, j: usize, dwj: T) {
        self.buf.z[j] = T::zero();
        self.buf.dz[j] = T::zero();
        self.update_along(self.buf.pos[j], -dwj);
    }

    /// The slopes of `z_B` by `delta = c G_{:,p}` (`G[a + p n]`), and
    /// `[w | dw]` from `[z_B | delta]` by one product over `M_{:,B}`.
    fn update_along(&mut self, p: usize, c: T) {
        let (n, kk) = (self.n, self.buf.set.len());
        for a in 0..kk {
            let i = self.buf.set[a];
            let delta = c * self.buf.g[p * n + a];
            self.buf.zb2[a] = self.buf.z[i];
            self.buf.zb2[n + a] = delta;
            self.buf.dz[i] += delta;
        }
        self.product(kk);
    }

    /// `w2 += M_{:,B} zb2` over the first `kk` columns of `M_{:,B}`.
    fn product(&mut self, kk: usize) {
        let n = self.n;
        axpys(
            &mut self.buf.w2,
            true,
            &self.buf.mb,
            &self.buf.zb2,
            T::one(),
            (n, kk, 2, n),
        );
    }

    /// The values and slopes after an update ([`Self::advance`] and the
    /// pivot's update), checked as [`Self::values`] checks fresh ones: the
    /// rows of `B` as `w` afresh from the updated `z_B` leaves them.
    fn values_updated(&mut self) -> Result<Residual, Decline> {
        self.since_fresh += 1;
        let n = self.n;
        self.buf.w.copy_from_slice(&self.buf.w2[..n]);
        self.buf.dw.copy_from_slice(&self.buf.w2[n..]);
        let r = self.rows_and_signs();
        self.settle(r)
    }

    fn values_once(&mut self) -> Residual {
        let (n, kk) = (self.n, self.buf.set.len());
        let l = self.lambda;
        // [z_B | dz_B] = -G [q_B + L d_B | d_B]
        for a in 0..kk {
            let i = self.buf.set[a];
            self.buf.rhs2[a] = self.buf.q[i] + l * self.buf.d[i];
            self.buf.rhs2[n + a] = self.buf.d[i];
        }
        // [w | dw] = [q + L d | d] + M_{:,B} [z_B | dz_B]
        let (w2, dw2) = self.buf.w2.split_at_mut(n);
        for ((w2, &q), &d) in w2.iter_mut().zip(&self.buf.q[..n]).zip(&self.buf.d[..n]) {
            *w2 = q + l * d;
        }
        dw2[..n].copy_from_slice(&self.buf.d[..n]);
        axpys(
            &mut self.buf.zb2,
            false,
            &self.buf.g,
            &self.buf.rhs2,
            -T::one(),
            (kk, kk, 2, n),
        );
        self.product(kk);
        self.buf.z.iter_mut().for_each(|x| *x = T::zero());
        self.buf.dz.iter_mut().for_each(|x| *x = T::zero());
        for a in 0..kk {
            let i = self.buf.set[a];
            self.buf.z[i] = self.buf.zb2[a];
            self.buf.dz[i] = self.buf.zb2[n + a];
        }
        self.buf.w.copy_from_slice(&self.buf.w2[..n]);
        self.buf.dw.copy_from_slice(&self.buf.w2[n..]);
        self.rows_and_signs()
    }

    /// The residual of `B`'s rows in `w` (then zeroed with their slopes) and
    /// the signs of the basic values.
    fn rows_and_signs(&mut self) -> Residual {
        let (n, kk) = (self.n, self.buf.set.len());
        let l = self.lambda;
        // B's rows: w_B must vanish (relative to the row's terms, as the
        // engine's breakpoint residuals)
        let mut eq = 0.0f64;
        for a in 0..kk {
            let i = self.buf.set[a];
            let s = T::one()
                .max(self.buf.q[i].abs())
                .max((l * self.buf.d[i]).abs())
                .max((self.buf.w[i] - self.buf.q[i] - l * self.buf.d[i]).abs());
            eq = eq.max((self.buf.w[i].abs() / s).to_f64());
            self.buf.w[i] = T::zero();
            self.buf.dw[i] = T::zero();
        }
        // feasibility: every basic value nonnegative beyond its rounding
        // (nothing to measure where no value is below zero, the usual case)
        let mut feas = 0.0f64;
        let negative = self
            .buf
            .z
            .iter()
            .chain(self.buf.w.iter())
            .fold(false, |a, &x| a | (x < T::zero()));
        if !negative {
            return Residual {
                equation: eq,
                feasibility: feas,
                complementarity: 0.0,
            };
        }
        let zmax = self.buf.z.iter().fold(T::one(), |a, &x| a.max(x.abs()));
        let wmax = self.buf.w.iter().fold(T::one(), |a, &x| a.max(x.abs()));
        let tol = T::from_f64(PRINCIPAL_RESIDUAL_EPS) * T::eps();
        for i in 0..n {
            if self.buf.z[i] < -(tol * zmax) {
                feas = feas.max((-self.buf.z[i] / zmax).to_f64());
            }
            if self.buf.w[i] < -(tol * wmax) {
                feas = feas.max((-self.buf.w[i] / wmax).to_f64());
            }
        }
        Residual {
            equation: eq,
            feasibility: feas,
            complementarity: 0.0,
        }
    }

    /// The segment from `self.lambda` to `to`.
    fn segment(&self, to: T, unbounded: bool) -> Segment<T> {
        // zeros and a copy: faer's `from_fn` writes entry by entry
        let col = |x: &[T]| {
            let mut c = Col::zeros(self.n);
            crate::linalg::col_slice_mut(&mut c).copy_from_slice(x);
            c
        };
        Segment {
            lambda_from: self.lambda,
            lambda_to: to,
            unbounded,
            basis: self.basis(),
            z_from: col(&self.buf.z),
            dz: col(&self.buf.dz),
            w_from: col(&self.buf.w),
            dw: col(&self.buf.dw),
            u_from: Col::zeros(0),
            du: Col::zeros(0),
        }
    }

    pub(crate) fn point_at(&self, l: T) -> Point<T> {
        let t = l - self.lambda;
        Point {
            lambda: l,
            z: Col::from_fn(self.n, |i| self.buf.z[i] + self.buf.dz[i] * t),
            w: Col::from_fn(self.n, |i| self.buf.w[i] + self.buf.dw[i] * t),
            u: Col::zeros(0),
        }
    }

    /// The complementary basis: `Z(i)` for `i` in `B`, else `W(i)`.
    pub(crate) fn basis(&self) -> Vec<Var> {
        self.buf.vars.clone()
    }
}
