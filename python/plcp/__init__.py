"""plcp: the whole solution path of a parametric linear complementarity problem.

With ``x = (u, z)``, ``u`` the ``free`` (p) free variables and ``z`` the n
complementary ones, and the parameter ``L`` rising from ``lambda0`` to
``lambda_max``::

    0 = (M x + q + L d)[:p]                     equality rows
    w = (M x + q + L d)[p:],  w >= 0, z >= 0, w'z = 0

``solve`` traces the solution as a piecewise-affine path (breakpoints, the
variable that entered and left at each, ``z, w, u`` affine in ``L`` on every
segment); ``solve_lcp`` solves a plain LCP ``w = q + M z``. Bad input raises
``ValueError`` with the library's message; how the path ended is
``path.status``, never an exception. The solve runs with the GIL released.
"""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from . import _plcp
from ._plcp import LcpSolution, Path, Point, Segment

__all__ = ["solve", "solve_lcp", "Path", "Segment", "Point", "LcpSolution"]


def _vector(name: str, v: Any) -> np.ndarray:
    a = np.asarray(v, dtype=np.float64)
    if a.ndim != 1:
        raise ValueError(f"{name} must be a 1-D array, got shape {a.shape}")
    return np.ascontiguousarray(a)


def _is_sparse(m: Any) -> bool:
    try:
        import scipy.sparse as sp
    except ImportError:  # no scipy: nothing can be a scipy.sparse matrix
        return False
    return bool(sp.issparse(m))


def _dense(m: Any) -> np.ndarray:
    a = np.asarray(m, dtype=np.float64)
    if a.ndim != 2:
        raise ValueError(
            f"M must be a 2-D array or a scipy.sparse matrix, got shape {a.shape}"
        )
    return np.ascontiguousarray(a)


def solve(
    M: Any,
    q: Any,
    d: Any,
    *,
    lambda_max: Optional[float] = None,
    lambda0: float = 0.0,
    free: int = 0,
    method: str = "lemke",
    precision: str = "f64",
) -> Path:
    """Traces the solution path of ``w = q + L d + M z`` (mixed form with ``free`` > 0).

    M: 2-D array or scipy.sparse matrix of order p + n; q, d: 1-D arrays of
    length p + n; lambda_max: end of the range (None: infinity); method:
    "lemke" (a mixed problem needs a nonsingular free block) or "wolfe"
    (Wolfe's long form on the unreduced mixed system); precision: "f32",
    "f64" or "f128" (double-double; all results come back as float64).
    """
    qv, dv = _vector("q", q), _vector("d", d)
    if isinstance(free, bool) or int(free) != free or free < 0:
        raise ValueError(f"free must be a nonnegative integer, got {free!r}")
    lmax = None if lambda_max is None else float(lambda_max)
    args = (lmax, float(lambda0), int(free), str(method), str(precision))
    if _is_sparse(M):
        coo = M.tocoo()
        rows = np.ascontiguousarray(coo.row, dtype=np.int64)
        cols = np.ascontiguousarray(coo.col, dtype=np.int64)
        vals = np.ascontiguousarray(coo.data, dtype=np.float64)
        return _plcp.solve_sparse(tuple(coo.shape), rows, cols, vals, qv, dv, *args)
    return _plcp.solve_dense(_dense(M), qv, dv, *args)


def solve_lcp(M: Any, q: Any, *, precision: str = "f64") -> LcpSolution:
    """Solves the LCP ``w = q + M z``, ``w, z >= 0``, ``w'z = 0`` by Lemke's method.

    A scipy.sparse ``M`` is made dense (the plain LCP solver works on a dense M).
    """
    if _is_sparse(M):
        M = M.toarray()
    return _plcp.solve_lcp_dense(_dense(M), _vector("q", q), str(precision))
