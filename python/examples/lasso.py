"""The LASSO regularization path as a monotone PLCP.

    minimize over b:  1/2 |y - X b|^2 + t |b|_1,   t from t_max = max |X'y| down to 0.

With b = b+ - b-, b+, b- >= 0, G = X'X and c = X'y, the optimality conditions
are an LCP in z = (b+, b-):

    w+ =  G (b+ - b-) - c + t 1 >= 0,   b+ >= 0,   b+' w+ = 0
    w- = -G (b+ - b-) + c + t 1 >= 0,   b- >= 0,   b-' w- = 0

and with t = t_max - L (so that L rises from 0 to t_max while t falls):

    w = q + L d + M z,   M = [[G, -G], [-G, G]] (positive semidefinite: monotone),
    q = (t_max 1 - c, t_max 1 + c) >= 0,   d = -(1, 1).

At L = 0 (t = t_max) z = 0 is the solution, so the path starts without a
start phase; every breakpoint is a LARS/LASSO knot (a coefficient enters the
active set, z_i entering, or leaves it, w_i entering), and on every piece
b is affine in t. The fit stays the same problem for collinear columns
(then b need not be unique, but X b and |b|_1 are).

Run: python python/examples/lasso.py  (diabetes data from scikit-learn, then
wide random problems), printing the knots, active sets and coefficients of
each piece and the comparison against scikit-learn's lars_path(method="lasso")
and coordinate-descent Lasso at many t.
"""

from __future__ import annotations

import dataclasses
import time

import numpy as np

import plcp


@dataclasses.dataclass
class Piece:
    """b(t) = b_hi + (t_hi - t) db on t_lo <= t <= t_hi (db = db/dL)."""

    t_hi: float
    t_lo: float
    b_hi: np.ndarray
    db: np.ndarray

    @property
    def active(self) -> list[int]:
        mid = self.b_hi + 0.5 * (self.t_hi - self.t_lo) * self.db
        return [int(i) for i in np.flatnonzero(mid != 0.0)]

    def at(self, t: float) -> np.ndarray:
        return self.b_hi + (self.t_hi - t) * self.db


@dataclasses.dataclass
class LassoPath:
    t_max: float
    knots: np.ndarray  # t at each breakpoint, descending
    events: list[tuple[str, str]]
    pieces: list[Piece]
    path: plcp.Path
    seconds: float  # forming M and tracing the path

    def coef(self, t: float) -> np.ndarray:
        """The coefficients at t (0 <= t <= t_max), evaluated by the path."""
        pt = self.path.at(self.t_max - t)
        if pt is None:
            raise ValueError(f"t = {t} outside [0, {self.t_max}]")
        p = len(pt.z) // 2
        return pt.z[:p] - pt.z[p:]


def lasso_plcp(X: np.ndarray, y: np.ndarray):
    """M, q, d and t_max of the LASSO path's PLCP (module doc)."""
    G, c = X.T @ X, X.T @ y
    t_max = float(np.abs(c).max())
    M = np.block([[G, -G], [-G, G]])
    q = np.concatenate([t_max - c, t_max + c])
    d = -np.ones(2 * X.shape[1])
    return M, q, d, t_max


def lasso_path(X: np.ndarray, y: np.ndarray, precision: str = "f64", t_min: float = 0.0) -> LassoPath:
    """The LASSO path from t_max down to t_min (default: the whole path)."""
    start = time.perf_counter()
    M, q, d, t_max = lasso_plcp(X, y)
    path = plcp.solve(M, q, d, lambda_max=t_max - t_min, precision=precision)
    seconds = time.perf_counter() - start
    if path.status != "reached":
        raise RuntimeError(f"LASSO path ended {path.status}: {path.message}")
    p = X.shape[1]
    pieces = [
        Piece(
            t_hi=t_max - s.lambda_from,
            t_lo=t_max - s.lambda_to,
            b_hi=s.z_from[:p] - s.z_from[p:],
            db=s.dz[:p] - s.dz[p:],
        )
        for s in path.segments
    ]
    return LassoPath(t_max, t_max - path.breakpoints, path.events, pieces, path, seconds)


def objective(X, y, b, t):
    return 0.5 * float(np.sum((y - X @ b) ** 2)) + t * float(np.abs(b).sum())


def kkt_violation(X, y, b, t, t_max):
    """The largest violation of the LASSO optimality conditions at t, relative
    to t_max: |g_i| <= t for all i, g_i = t sign(b_i) where b_i != 0, g = X'(y - X b)."""
    g = X.T @ (y - X @ b)
    v = max(0.0, float((np.abs(g) - t).max()))
    # a coefficient that is leaving at this knot may hold a rounding residue of
    # either sign: only the bound |g_i| <= t applies to it
    on = np.abs(b) > 1e-9 * max(1e-300, float(np.abs(b).max()))
    if on.any():
        v = max(v, float(np.abs(g[on] - t * np.sign(b[on])).max()))
    return v / t_max


def sklearn_lars(X, y):
    """scikit-learn's LARS/LASSO path: (t at each knot, coefficients there)."""
    from sklearn.linear_model import lars_path

    n, p = X.shape
    alphas, _, coefs = lars_path(X, y, method="lasso", max_iter=20 * (n + p), Gram="auto")
    return alphas * n, coefs  # lars_path's alpha is max |X'r| / n_samples


def sklearn_cd(X, y, t):
    """scikit-learn's coordinate-descent Lasso at one t (an independent solver)."""
    from sklearn.linear_model import Lasso

    n = X.shape[0]
    m = Lasso(alpha=t / n, fit_intercept=False, tol=1e-14, max_iter=1_000_000)
    m.fit(X, y)
    return m.coef_


def compare(name, X, y, n_check=25, show=True):
    """Traces the path, prints it, and compares with lars_path and coordinate descent.

    Returns the largest differences (relative to max |b|): against lars_path at
    its knots, against coordinate descent in objective (relative) at n_check t's.
    """
    lp = lasso_path(X, y)
    scale = max(1.0, max(float(np.abs(pc.b_hi).max()) for pc in lp.pieces))
    print(f"\n== {name}: X is {X.shape[0]} x {X.shape[1]}, t_max = {lp.t_max:.6g} ==")
    print(f"plcp: {len(lp.knots)} knots, {lp.path.info['pivots']} pivots, {lp.seconds * 1e3:.1f} ms")
    if show:
        print(f"{'piece':>5} {'t from':>12} {'t to':>12}  active set (coefficient at the piece's start)")
        for k, pc in enumerate(lp.pieces):
            act = ", ".join(f"b{i}={pc.b_hi[i]:+.4g}" for i in pc.active)
            print(f"{k:>5} {pc.t_hi:>12.6g} {pc.t_lo:>12.6g}  {{{act}}}")
    t0 = time.perf_counter()
    ts, coefs = sklearn_lars(X, y)
    lars_s = time.perf_counter() - t0
    lars_diff = max(float(np.abs(lp.coef(min(t, lp.t_max)) - coefs[:, k]).max()) for k, t in enumerate(ts)) / scale
    lars_obj = max(
        abs(objective(X, y, lp.coef(min(t, lp.t_max)), t) - objective(X, y, coefs[:, k], t))
        / max(1.0, objective(X, y, coefs[:, k], t))
        for k, t in enumerate(ts)
    )
    print(
        f"lars_path(method='lasso'): {len(ts)} knots, {lars_s * 1e3:.1f} ms; "
        f"largest coefficient difference at its knots {lars_diff:.2e} (relative to max |b|), objective {lars_obj:.2e}"
    )
    if show:
        print(f"{'':>5} {'t (plcp)':>12} {'t (lars)':>12}")
        for k in range(min(len(lp.knots), len(ts), 12)):
            print(f"{k:>5} {lp.knots[k]:>12.6g} {ts[k]:>12.6g}")
    cd_coef, cd_obj = 0.0, 0.0
    for t in np.linspace(0.0, lp.t_max, n_check + 2)[1:-1]:
        b, bcd = lp.coef(t), sklearn_cd(X, y, t)
        cd_coef = max(cd_coef, float(np.abs(b - bcd).max()) / scale)
        fo, fcd = objective(X, y, b, t), objective(X, y, bcd, t)
        # plcp's objective can only be lower than an inexact solver's, never higher
        cd_obj = max(cd_obj, (fo - fcd) / max(1.0, fcd))
    worst_kkt = max(kkt_violation(X, y, lp.coef(t), t, lp.t_max) for t in np.linspace(0, lp.t_max, 50))
    print(
        f"coordinate-descent Lasso at {n_check} t: largest coefficient difference {cd_coef:.2e}, "
        f"objective excess of plcp {cd_obj:.2e}; plcp's KKT violation on 50 t: {worst_kkt:.2e}"
    )
    return dict(lars_coef=lars_diff, lars_obj=lars_obj, cd_coef=cd_coef, cd_obj=cd_obj, kkt=worst_kkt, path=lp)


def wide(n, p, seed, collinear=False):
    """A wide random problem (p > n); with collinear=True, some columns repeat
    others or are their combinations."""
    rng = np.random.default_rng(seed)
    X = rng.standard_normal((n, p))
    if collinear:
        X[:, 1] = X[:, 0]  # an exact copy
        X[:, 2] = -2.0 * X[:, 3]  # a multiple
        X[:, 5] = X[:, 6] + X[:, 7]  # a combination
    b = np.zeros(p)
    b[rng.choice(p, 5, replace=False)] = rng.standard_normal(5) * 3.0
    y = X @ b + 0.5 * rng.standard_normal(n)
    return X, y


def main():
    from sklearn.datasets import load_diabetes

    X, y = load_diabetes(return_X_y=True)
    compare("diabetes (scikit-learn)", X, y - y.mean())
    X, y = wide(40, 120, 1)
    compare("wide random", X, y, show=False)
    X, y = wide(40, 120, 2, collinear=True)
    compare("wide random, collinear columns", X, y, show=False)


if __name__ == "__main__":
    main()
