"""A parametric convex QP whose linear term and bounds move with L: the
homotopy of an active-set MPC solver, as a mixed PLCP.

Model predictive control of a double integrator (position, velocity; input
u = acceleration, |u_k| <= 1, position <= p_max) over N steps, condensed to
the inputs U: the states are X = Phi x0 + Gamma U, and

    minimize over U:  1/2 U' H U + (F x0)' U   subject to  A U <= b + E x0,

H = Gamma' Qbar Gamma + R (positive definite), F = Gamma' Qbar Phi. When the
initial state moves along x0(L) = x0a + L (x0b - x0a), L from 0 to 1, the
linear term f + L g and the bounds b + L e move with L (an active-set solver
warm-started from one sample to the next follows exactly this path). With
the multipliers y >= 0 and slacks s = b + L e - A U >= 0, the KKT conditions
are the mixed PLCP with x = (U, y) (p = N free variables):

    0 = H U + A' y + f + L g                 (stationarity)
    s = -A U + b + L e >= 0,  y >= 0,  s'y = 0

M = [[H, A'], [-A, 0]] is monotone and its free block H nonsingular, so both
Lemke (on the Schur reduction) and Wolfe trace it; the breakpoints are the
changes of the active set.

Run: python python/examples/mpc.py
"""

from __future__ import annotations

import numpy as np

import plcp


def mpc_qp(N=10, dt=0.2, p_max=1.0):
    """H, F, A, b, E of the condensed MPC problem (module doc)."""
    Ad = np.array([[1.0, dt], [0.0, 1.0]])
    Bd = np.array([[0.5 * dt * dt], [dt]])
    Phi = np.zeros((2 * N, 2))
    Gamma = np.zeros((2 * N, N))
    P = np.eye(2)
    for k in range(N):
        P = Ad @ P
        Phi[2 * k:2 * k + 2] = P
        for j in range(k + 1):
            Gamma[2 * k:2 * k + 2, j] = (np.linalg.matrix_power(Ad, k - j) @ Bd)[:, 0]
    Qbar = np.kron(np.eye(N), np.diag([10.0, 1.0]))
    H = Gamma.T @ Qbar @ Gamma + 0.1 * np.eye(N)
    F = Gamma.T @ Qbar @ Phi
    Pos = Gamma[0::2]  # positions: Phi[0::2] x0 + Pos U
    A = np.vstack([np.eye(N), -np.eye(N), Pos])
    b = np.concatenate([np.ones(N), np.ones(N), p_max * np.ones(N)])
    E = np.vstack([np.zeros((2 * N, 2)), -Phi[0::2]])
    return H, F, A, b, E


def homotopy_plcp(H, F, A, b, E, x0a, x0b):
    """M, q, d, p of the path from x0a (L = 0) to x0b (L = 1)."""
    N, m = H.shape[0], A.shape[0]
    M = np.block([[H, A.T], [-A, np.zeros((m, m))]])
    dx = x0b - x0a
    q = np.concatenate([F @ x0a, b + E @ x0a])
    d = np.concatenate([F @ dx, E @ dx])
    return M, q, d, N


def qp_clarabel(H, f, A, bb):
    import clarabel
    import scipy.sparse as sp

    s = clarabel.DefaultSettings()
    s.verbose = False
    s.tol_gap_abs = s.tol_gap_rel = s.tol_feas = 1e-12
    solver = clarabel.DefaultSolver(sp.csc_matrix(np.triu(H)), f, sp.csc_matrix(A), bb,
                                    [clarabel.NonnegativeConeT(A.shape[0])], s)
    sol = solver.solve()
    assert str(sol.status) == "Solved", sol.status
    return np.array(sol.x)


def compare(method="lemke", show=True, x0a=(-1.0, -0.5), x0b=(0.6, 0.8)):
    H, F, A, b, E = mpc_qp()
    x0a, x0b = np.array(x0a), np.array(x0b)
    M, q, d, N = homotopy_plcp(H, F, A, b, E, x0a, x0b)
    path = plcp.solve(M, q, d, free=N, lambda_max=1.0, method=method)
    if path.status != "reached":
        raise RuntimeError(f"MPC homotopy ended {path.status}: {path.message}")
    if show:
        print(f"{method}: {len(path.breakpoints)} active-set changes, {path.info['pivots']} pivots")
        names = [f"u{k}<=1" for k in range(N)] + [f"u{k}>=-1" for k in range(N)] + [f"p{k + 1}<=pmax" for k in range(N)]
        for L, (e, l) in zip(path.breakpoints, path.events):
            which = int(e[1:]) if e[0] == "z" else int(l[1:])
            act = "enters" if e[0] == "z" else "leaves"
            print(f"  L = {L:.6f}: constraint {names[which]} {act} the active set ({e} in, {l} out)")
    worst, excess = 0.0, 0.0
    for L in np.concatenate([np.linspace(0.0, 1.0, 41), path.breakpoints]):
        x0 = x0a + L * (x0b - x0a)
        U = path.at(L).u
        Uc = qp_clarabel(H, F @ x0, A, b + E @ x0)
        worst = max(worst, float(np.abs(U - Uc).max()))
        f = lambda V: 0.5 * V @ H @ V + (F @ x0) @ V
        excess = max(excess, f(U) - f(Uc))
        # plcp's inputs are feasible
        assert (A @ U <= b + E @ x0 + 1e-12).all()
    if show:
        print(f"  against clarabel at 41 values of L and the breakpoints: largest input difference {worst:.2e}, "
              f"objective excess {excess:.2e}")
    return path, worst, excess


if __name__ == "__main__":
    compare("lemke")
    compare("wolfe")
