import itertools
import pathlib
import sys

import numpy as np
import pytest

# the examples hold the formulations (LASSO, Markowitz, MPC); the tests import them
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "examples"))


def enumerate_lcp(M, q, tol=1e-9):
    """All solutions of w = q + M z, w, z >= 0, w'z = 0 by trying every
    complementary basis (2^n linear solves): an independent check for small n."""
    n = len(q)
    scale = max(1.0, np.abs(q).max(), np.abs(M).max())
    found = []
    for k in range(n + 1):
        for S in itertools.combinations(range(n), k):
            S = list(S)
            z = np.zeros(n)
            if S:
                A = M[np.ix_(S, S)]
                if abs(np.linalg.det(A)) < 1e-12 * scale**k:
                    continue
                z[S] = np.linalg.solve(A, -q[S])
            w = q + M @ z
            if z.min() >= -tol * scale and w.min() >= -tol * scale:
                found.append((z, w))
    return found


@pytest.fixture
def rng():
    return np.random.default_rng(20261125)
