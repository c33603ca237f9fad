"""The Markowitz efficient frontier (critical line algorithm) as a PLCP.

    minimize over w:  1/2 w' S w - L mu' w   subject to  1'w = 1,  w >= 0,

S the covariance, mu the expected returns, and L = 1/gamma the risk tolerance
rising from 0 (infinite risk aversion: the minimum-variance portfolio) to
infinity (gamma = 0: the asset with the largest mean). With the budget's
multiplier nu as the free variable and s the multipliers of w >= 0, the KKT
conditions are the mixed PLCP (p = 1 free variable, n assets):

    0 = 1'w - 1                                   (the budget row)
    s = S w - nu 1 - L mu >= 0,  w >= 0,  s'w = 0

i.e. x = (nu, w), M = [[0, 1'], [-1, S]] (monotone: a skew part plus S),
q = (-1, 0), d = (0, -mu). Its free block is the 1 x 1 zero, so it is traced
by Wolfe's long form (method="wolfe"), which works on the unreduced system.
The breakpoints are the corner portfolios (an asset enters or leaves); on
every segment w is affine in L, and the frontier between two corners is a
parabola in (variance, return).

Run: python python/examples/markowitz.py
"""

from __future__ import annotations

import numpy as np

import plcp


def frontier_plcp(S, mu):
    n = len(mu)
    M = np.zeros((n + 1, n + 1))
    M[0, 1:] = 1.0
    M[1:, 0] = -1.0
    M[1:, 1:] = S
    q = np.concatenate([[-1.0], np.zeros(n)])
    d = np.concatenate([[0.0], -mu])
    return M, q, d


def frontier(S, mu, precision="f64"):
    M, q, d = frontier_plcp(S, mu)
    path = plcp.solve(M, q, d, free=1, method="wolfe", precision=precision)
    if not path.success:
        raise RuntimeError(f"frontier path ended {path.status}: {path.message}")
    return path


def weights(path, L):
    return path.at(L).z


def qp_clarabel(S, mu, L):
    """The same QP at one L by clarabel's interior-point method (independent)."""
    import clarabel
    import scipy.sparse as sp

    n = len(mu)
    A = sp.csc_matrix(np.vstack([np.ones((1, n)), -np.eye(n)]))
    b = np.concatenate([[1.0], np.zeros(n)])
    s = clarabel.DefaultSettings()
    s.verbose = False
    s.tol_gap_abs = s.tol_gap_rel = s.tol_feas = 1e-12
    solver = clarabel.DefaultSolver(sp.csc_matrix(np.triu(S)), -L * mu, A, b,
                                    [clarabel.ZeroConeT(1), clarabel.NonnegativeConeT(n)], s)
    sol = solver.solve()
    assert str(sol.status) == "Solved", sol.status
    return np.array(sol.x)


def example_data(n=8, seed=3):
    rng = np.random.default_rng(seed)
    F = rng.standard_normal((n, 3)) * 0.1
    S = F @ F.T + np.diag(rng.uniform(0.01, 0.04, n))
    mu = rng.uniform(0.02, 0.12, n)
    return S, mu


def compare(S, mu, show=True):
    """Prints the corner portfolios and the frontier; returns the largest weight
    difference against clarabel at many L and the objective excess."""
    path = frontier(S, mu)
    if show:
        print(f"status {path.status}, {len(path.breakpoints)} corner portfolios, {path.info['pivots']} pivots")
        print(f"{'L':>10} {'gamma':>10} {'event':>10} {'return':>8} {'stdev':>8}  weights")
        for L, (e, l) in zip(path.breakpoints, path.events):
            w = weights(path, L)
            g = np.inf if L == 0 else 1 / L
            print(f"{L:>10.4g} {g:>10.4g} {e + '/' + l:>10} {mu @ w:>8.4f} {np.sqrt(w @ S @ w):>8.4f}  "
                  + " ".join(f"{x:.3f}" for x in w))
        print("the frontier between the corners (return, stdev) at a few L:")
        for L in np.linspace(0.0, 1.2 * path.breakpoints[-1], 7):
            w = weights(path, L)
            print(f"  L = {L:8.4g}: return {mu @ w:.5f}, stdev {np.sqrt(w @ S @ w):.5f}")
    Ls = np.concatenate([np.linspace(0.0, 1.5 * path.breakpoints[-1], 40), path.breakpoints])
    worst, excess = 0.0, 0.0
    for L in Ls:
        w, wc = weights(path, L), qp_clarabel(S, mu, L)
        worst = max(worst, float(np.abs(w - wc).max()))
        f = lambda x: 0.5 * x @ S @ x - L * mu @ x
        excess = max(excess, f(w) - f(wc))
    if show:
        print(f"against clarabel at {len(Ls)} values of L: largest weight difference {worst:.2e}, "
              f"objective excess {excess:.2e}")
    return path, worst, excess


if __name__ == "__main__":
    compare(*example_data())
