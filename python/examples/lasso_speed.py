"""Speed of the full LASSO path: plcp against scikit-learn's lars_path(method="lasso").

Run: python python/examples/lasso_speed.py [--repeat R]

For dense problems n x p = 200 x 100 ... 2000 x 1000 (X and y Gaussian, seeded;
y = X b + noise with 20 nonzero b, so the path has about min(n, p) knots or
more), both codes trace the whole path from t = max |X'y| down to 0 in the same
run. Times are the best of R runs (default 3) and include, for plcp, forming
G = X'X and the 2p x 2p matrix M (numpy) and the solve; for lars_path, its own
Gram matrix (Gram="auto" precomputes it when n > p, as LassoLars does).

Accuracy, side by side: the largest coefficient difference between the two
at lars_path's knots (relative to max |b|), and each code's largest violation
of the LASSO optimality conditions at those knots (relative to t_max).
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from sklearn.linear_model import lars_path

import plcp
from lasso import kkt_violation, lasso_plcp


def problem(n, p, seed=0):
    rng = np.random.default_rng(seed)
    X = rng.standard_normal((n, p))
    b = np.zeros(p)
    b[rng.choice(p, 20, replace=False)] = 3.0 * rng.standard_normal(20)
    return X, X @ b + rng.standard_normal(n)


def best_of(repeat, f):
    """The shortest of `repeat` runs, with that run's output."""
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        o = f()
        t = time.perf_counter() - t0
        if t < best:
            best, out = t, o
    return best, out


def run_plcp(X, y):
    M, q, d, t_max = lasso_plcp(X, y)
    return plcp.solve(M, q, d, lambda_max=t_max), t_max


def run_lars(X, y):
    n, p = X.shape
    return lars_path(X, y, method="lasso", max_iter=20 * (n + p), Gram="auto")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--sizes", default="200x100,500x250,1000x500,2000x1000")
    args = ap.parse_args()
    print(
        f"{'n x p':>11} {'plcp s':>8} {'solve s':>8} {'lars s':>8} {'ratio':>6} {'knots':>11} "
        f"{'max |db|':>9} {'KKT plcp':>9} {'KKT lars':>9}"
    )
    for size in args.sizes.split(","):
        n, p = map(int, size.split("x"))
        X, y = problem(n, p)
        tp, (path, t_max) = best_of(args.repeat, lambda: run_plcp(X, y))
        tl, (alphas, _, coefs) = best_of(args.repeat, lambda: run_lars(X, y))
        assert path.status == "reached", path.message
        ts = alphas * n
        scale = float(np.abs(coefs).max())
        diff, kkt_p, kkt_l = 0.0, 0.0, 0.0
        for k, t in enumerate(ts):
            t = min(float(t), t_max)
            z = path.at(t_max - t).z
            b = z[:p] - z[p:]
            diff = max(diff, float(np.abs(b - coefs[:, k]).max()) / scale)
            kkt_p = max(kkt_p, kkt_violation(X, y, b, t, t_max))
            kkt_l = max(kkt_l, kkt_violation(X, y, coefs[:, k], t, t_max))
        knots = f"{len(path.breakpoints)}/{len(ts) - 1}"
        print(
            f"{size:>11} {tp:>8.3f} {path.info['seconds']:>8.3f} {tl:>8.3f} {tp / tl:>6.2f} {knots:>11} "
            f"{diff:>9.1e} {kkt_p:>9.1e} {kkt_l:>9.1e}",
            flush=True,
        )


if __name__ == "__main__":
    main()
