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
    PRINCIPAL_MAX_COND_EPS, PRINCIPAL_PIVOT_EPS, PRINCIPAL_RESIDUAL_EPS, PRINCIPAL_TIE_EPS,
};
use faer::{Col, MatRef};

/// The kernel's state: the basic set, the inverse of its block, the values and
/// slopes at the current `L`.
struct Kernel<'a, T: Scalar> {
    n: usize,
    cols: Vec<&'a [T]>,
    q: &'a [T],
    d: &'a [T],
    /// `B` in the order of `G`'s rows and columns.
    set: Vec<usize>,
    /// position of `i` in `set`, or `usize::MAX`
    pos: Vec<usize>,
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
    lambda: T,
    // work vectors of length n
    u: Vec<T>,
    v: Vec<T>,
    gu: Vec<T>,
    vg: Vec<T>,
    /// `||M_{:,j}||_1` of every column, and their largest (`||M||_1`)
    col_norm1: Vec<T>,
    m_norm1: T,
    max_cond: f64,
    inversions: usize,
    pivots_since_inversion: usize,
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
    PivotLimit,
}

/// Traces a dense standard-form problem by principal pivoting, or declines.
#[allow(clippy::too_many_arguments)]
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
    let n = m.nrows();
    let Some(lmax) = lambda_max.filter(|l| l.is_finite()) else {
        return Err(Decline::NotEligible);
    };
    if n == 0
        || n > crate::tolerance::PRINCIPAL_MAX_N
        || m.ncols() != n
        || lmax < lambda0
        || crate::observe::observing()
    {
        return Err(Decline::NotEligible);
    }
    let (Some(q), Some(d)) = (q.try_as_col_major(), d.try_as_col_major()) else {
        return Err(Decline::NotEligible);
    };
    let (q, d) = (q.as_slice(), d.as_slice());
    let mut cols = Vec::with_capacity(n);
    for j in 0..n {
        match m.col(j).try_as_col_major() {
            Some(c) => cols.push(c.as_slice()),
            None => return Err(Decline::NotEligible),
        }
    }
    let col_norm1: Vec<T> = cols
        .iter()
        .map(|c| c.iter().fold(T::zero(), |a, &x| a + x.abs()))
        .collect();
    let m_norm1 = col_norm1.iter().fold(T::zero(), |a, &x| a.max(x));
    let mut k = Kernel {
        n,
        cols,
        q,
        d,
        set: Vec::with_capacity(n),
        pos: vec![usize::MAX; n],
        g: Vec::new(),
        mb: Vec::new(),
        rhs2: vec![T::zero(); 2 * n],
        zb2: vec![T::zero(); 2 * n],
        w2: vec![T::zero(); 2 * n],
        z: vec![T::zero(); n],
        dz: vec![T::zero(); n],
        w: vec![T::zero(); n],
        dw: vec![T::zero(); n],
        lambda: lambda0,
        u: vec![T::zero(); n],
        v: vec![T::zero(); n],
        gu: vec![T::zero(); n],
        vg: vec![T::zero(); n],
        col_norm1,
        m_norm1,
        max_cond: 1.0,
        inversions: 0,
        pivots_since_inversion: 0,
    };
    k.values()?;
    // a strictly feasible start: every w clear of zero (a zero w is a
    // degenerate start, which the general engine's lexicographic rule takes)
    let eps = T::eps();
    let tie = T::from_f64(PRINCIPAL_TIE_EPS) * eps;
    for i in 0..n {
        let s = T::one().max(k.q[i].abs()).max((lambda0 * k.d[i]).abs());
        if !clearly_above(k.w[i], tie * s) {
            return Err(Decline::StartNotInterior);
        }
    }
    let mut segments: Vec<Segment<T>> = Vec::with_capacity(n / 2 + 2);
    let mut breakpoints: Vec<Breakpoint<T>> = Vec::with_capacity(n / 2 + 1);
    loop {
        // ratio test: the smallest step of L to a zero of a basic variable
        let (mut best, mut second, mut arg) = (T::max_value(), T::max_value(), usize::MAX);
        let (mut rate_max, mut rate_arg) = (T::zero(), T::zero());
        for i in 0..n {
            let (x, dx) = if k.pos[i] != usize::MAX {
                (k.z[i], k.dz[i])
            } else {
                (k.w[i], k.dw[i])
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
        let room = lmax - k.lambda;
        let scale = T::one().max(k.lambda.abs()).max(lmax.abs());
        let window = tie * scale;
        if arg == usize::MAX || best > room + window {
            // L_max is reached inside this segment
            let seg = k.segment(lmax, false);
            segments.push(seg);
            let end = k.point_at(lmax);
            let final_basis = Some(k.basis());
            let info = Info {
                method: label,
                precision: T::NAME,
                pivots: breakpoints.len(),
                refactorisations: k.inversions,
                max_condition: k.max_cond,
                solve_seconds: timer.elapsed().as_secs_f64(),
                ..Info::default()
            };
            return Ok(Path {
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
                final_basis,
            });
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
        if breakpoints.len() >= max_pivots {
            return Err(Decline::PivotLimit);
        }
        let at = k.lambda + best;
        segments.push(k.segment(at, false));
        let (leaving, entering) = if k.pos[arg] != usize::MAX {
            k.remove(arg)?;
            (Var::Z(arg), Var::W(arg))
        } else {
            k.add(arg)?;
            (Var::W(arg), Var::Z(arg))
        };
        k.lambda = at;
        let residual = k.values()?;
        breakpoints.push(Breakpoint {
            lambda: at,
            entering,
            leaving,
            degenerate: false,
            turning: false,
            segment: segments.len(),
            residual,
        });
    }
}

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

/// `dst (+)= alpha a b` on the calling thread.
fn gemm<T: Scalar>(
    dst: faer::MatMut<'_, T>,
    add: bool,
    a: MatRef<'_, T>,
    b: MatRef<'_, T>,
    alpha: T,
) {
    let accum = if add {
        faer::Accum::Add
    } else {
        faer::Accum::Replace
    };
    faer::linalg::matmul::matmul(dst, accum, a, b, alpha, faer::Par::Seq);
}

/// `x > bound`, false where either is NaN (a NaN declines).
fn clearly_above<T: Scalar>(x: T, bound: T) -> bool {
    x.partial_cmp(&bound) == Some(core::cmp::Ordering::Greater)
}

impl<T: Scalar> Kernel<'_, T> {
    fn m(&self, i: usize, j: usize) -> T {
        self.cols[j][i]
    }

    /// Adds `j` to `B`: `G` bordered by `s = M_jj - v G u`.
    fn add(&mut self, j: usize) -> Result<(), Decline> {
        let (n, kk) = (self.n, self.set.len());
        if self.g.is_empty() {
            self.g = vec![T::zero(); n * n];
            self.mb = vec![T::zero(); n * n];
        }
        // u = M_Bj, v = M_jB; gu = G u, vg = G' v
        for a in 0..kk {
            self.u[a] = self.m(self.set[a], j);
            self.v[a] = self.m(j, self.set[a]);
        }
        let g = view(&self.g, kk, kk, n);
        gemm(
            view_mut(&mut self.gu, kk, 1, n),
            false,
            g,
            view(&self.u, kk, 1, n),
            T::one(),
        );
        gemm(
            view_mut(&mut self.vg, kk, 1, n),
            false,
            g.transpose(),
            view(&self.v, kk, 1, n),
            T::one(),
        );
        let mjj = self.m(j, j);
        let (mut vgu, mut mag) = (T::zero(), mjj.abs());
        for a in 0..kk {
            let t = self.v[a] * self.gu[a];
            vgu += t;
            mag += t.abs();
        }
        let s = mjj - vgu;
        if !clearly_above(s, T::from_f64(PRINCIPAL_PIVOT_EPS) * T::eps() * mag) {
            return Err(Decline::SmallPivot);
        }
        let inv = T::one() / s;
        // G + gu vg' / s, bordered by -gu / s, -vg' / s and 1 / s
        gemm(
            view_mut(&mut self.g, kk, kk, n),
            true,
            view(&self.gu, kk, 1, n),
            view(&self.vg, kk, 1, n).transpose(),
            inv,
        );
        for b in 0..kk {
            self.g[b * n + kk] = -(self.vg[b] * inv);
            self.g[kk * n + b] = -(self.gu[b] * inv);
        }
        self.g[kk * n + kk] = inv;
        self.mb[kk * n..kk * n + n].copy_from_slice(&self.cols[j][..n]);
        self.pos[j] = kk;
        self.set.push(j);
        self.after_pivot()
    }

    /// Takes `j` out of `B`: `G` contracted by its pivot `G_jj`.
    fn remove(&mut self, j: usize) -> Result<(), Decline> {
        let (n, kk) = (self.n, self.set.len());
        let p = self.pos[j];
        let gpp = self.g[p * n + p];
        // G_jj = 1 / (Schur complement of S_{-j,-j} in S): positive beyond its
        // rounding (the terms of that complement are bounded by |G| |S|)
        let mag = (0..kk).fold(T::zero(), |a, b| a.max(self.g[b * n + p].abs()));
        if !clearly_above(gpp, T::from_f64(PRINCIPAL_PIVOT_EPS) * T::eps() * mag) {
            return Err(Decline::SmallPivot);
        }
        for a in 0..kk {
            self.u[a] = self.g[p * n + a]; // column p
            self.v[a] = self.g[a * n + p]; // row p
        }
        // G - G_{:,p} G_{p,:} / G_pp (row and column p become junk, then the
        // last index moves into them)
        gemm(
            view_mut(&mut self.g, kk, kk, n),
            true,
            view(&self.u, kk, 1, n),
            view(&self.v, kk, 1, n).transpose(),
            -(T::one() / gpp),
        );
        // the last index takes position p
        let last = kk - 1;
        if p != last {
            for a in 0..kk {
                self.g[p * n + a] = self.g[last * n + a];
            }
            for b in 0..kk {
                self.g[b * n + p] = self.g[b * n + last];
            }
            self.mb.copy_within(last * n..last * n + n, p * n);
            let moved = self.set[last];
            self.set[p] = moved;
            self.pos[moved] = p;
        }
        self.set.pop();
        self.pos[j] = usize::MAX;
        self.after_pivot()
    }

    /// The condition bound after a pivot, and the periodic fresh inversion.
    fn after_pivot(&mut self) -> Result<(), Decline> {
        self.pivots_since_inversion += 1;
        if self.pivots_since_inversion >= crate::tolerance::PRINCIPAL_REINVERT_PERIOD {
            self.invert()?;
        }
        Ok(())
    }

    /// `G` afresh from `S = M_BB` (LU with partial pivoting).
    fn invert(&mut self) -> Result<(), Decline> {
        let (n, kk) = (self.n, self.set.len());
        self.inversions += 1;
        self.pivots_since_inversion = 0;
        if kk == 0 {
            return Ok(());
        }
        let s = faer::Mat::<T>::from_fn(kk, kk, |a, b| self.m(self.set[a], self.set[b]));
        let Some((inv, _, _)) = crate::linalg::inverse_par(s.as_ref(), faer::Par::Seq) else {
            return Err(Decline::SmallPivot);
        };
        for b in 0..kk {
            for a in 0..kk {
                self.g[b * n + a] = inv[(a, b)];
            }
        }
        Ok(())
    }

    /// Values and slopes at `self.lambda` from `G`; the residual of the rows
    /// of `B` (which the values must satisfy) and the condition bound of the
    /// complementary basis. One fresh inversion if those rows are off.
    fn values(&mut self) -> Result<Residual, Decline> {
        let first = self.values_once();
        let limit = PRINCIPAL_RESIDUAL_EPS * T::eps().to_f64();
        if first.equation <= limit {
            return self.checked(first);
        }
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
        let (n, kk) = (self.n, self.set.len());
        let mut g1 = T::zero();
        let mut mb1 = T::zero();
        for b in 0..kk {
            g1 = g1.max(
                self.g[b * n..b * n + kk]
                    .iter()
                    .fold(T::zero(), |a, &x| a + x.abs()),
            );
            mb1 = mb1.max(self.col_norm1[self.set[b]]);
        }
        let cond =
            T::one().max(mb1).to_f64() * T::one().max(g1 * (T::one() + self.m_norm1)).to_f64();
        if !cond.is_finite() || cond * T::eps().to_f64() > PRINCIPAL_MAX_COND_EPS {
            return Err(Decline::Condition);
        }
        self.max_cond = self.max_cond.max(cond);
        if r.feasibility > 0.0 {
            return Err(Decline::Residual);
        }
        Ok(r)
    }

    fn values_once(&mut self) -> Residual {
        let (n, kk) = (self.n, self.set.len());
        let l = self.lambda;
        // [z_B | dz_B] = -G [q_B + L d_B | d_B]
        for a in 0..kk {
            let i = self.set[a];
            self.rhs2[a] = self.q[i] + l * self.d[i];
            self.rhs2[n + a] = self.d[i];
        }
        // [w | dw] = [q + L d | d] + M_{:,B} [z_B | dz_B]
        for i in 0..n {
            self.w2[i] = self.q[i] + l * self.d[i];
            self.w2[n + i] = self.d[i];
        }
        if kk > 0 {
            gemm(
                view_mut(&mut self.zb2, kk, 2, n),
                false,
                view(&self.g, kk, kk, n),
                view(&self.rhs2, kk, 2, n),
                -T::one(),
            );
            gemm(
                view_mut(&mut self.w2, n, 2, n),
                true,
                view(&self.mb, n, kk, n),
                view(&self.zb2, kk, 2, n),
                T::one(),
            );
        }
        self.z.iter_mut().for_each(|x| *x = T::zero());
        self.dz.iter_mut().for_each(|x| *x = T::zero());
        for a in 0..kk {
            let i = self.set[a];
            self.z[i] = self.zb2[a];
            self.dz[i] = self.zb2[n + a];
        }
        self.w.copy_from_slice(&self.w2[..n]);
        self.dw.copy_from_slice(&self.w2[n..]);
        // B's rows: w_B must vanish (relative to the row's terms, as the
        // engine's breakpoint residuals)
        let mut eq = 0.0f64;
        for a in 0..kk {
            let i = self.set[a];
            let s = T::one()
                .max(self.q[i].abs())
                .max((l * self.d[i]).abs())
                .max((self.w[i] - self.q[i] - l * self.d[i]).abs());
            eq = eq.max((self.w[i].abs() / s).to_f64());
            self.w[i] = T::zero();
            self.dw[i] = T::zero();
        }
        // feasibility: every basic value nonnegative beyond its rounding
        let zmax = self.z.iter().fold(T::one(), |a, &x| a.max(x.abs()));
        let wmax = self.w.iter().fold(T::one(), |a, &x| a.max(x.abs()));
        let tol = T::from_f64(PRINCIPAL_RESIDUAL_EPS) * T::eps();
        let mut feas = 0.0f64;
        for i in 0..n {
            if self.z[i] < -(tol * zmax) {
                feas = feas.max((-self.z[i] / zmax).to_f64());
            }
            if self.w[i] < -(tol * wmax) {
                feas = feas.max((-self.w[i] / wmax).to_f64());
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
            z_from: col(&self.z),
            dz: col(&self.dz),
            w_from: col(&self.w),
            dw: col(&self.dw),
            u_from: Col::zeros(0),
            du: Col::zeros(0),
        }
    }

    fn point_at(&self, l: T) -> Point<T> {
        let t = l - self.lambda;
        Point {
            lambda: l,
            z: Col::from_fn(self.n, |i| self.z[i] + self.dz[i] * t),
            w: Col::from_fn(self.n, |i| self.w[i] + self.dw[i] * t),
            u: Col::zeros(0),
        }
    }

    /// The complementary basis: `Z(i)` for `i` in `B`, else `W(i)`.
    fn basis(&self) -> Vec<Var> {
        (0..self.n)
            .map(|i| {
                if self.pos[i] != usize::MAX {
                    Var::Z(i)
                } else {
                    Var::W(i)
                }
            })
            .collect()
    }
}
