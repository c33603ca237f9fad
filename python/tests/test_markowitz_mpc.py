"""The efficient frontier and the MPC homotopy against clarabel's interior-point QP."""

import numpy as np
import pytest

import markowitz
import mpc


@pytest.mark.parametrize("seed", [3, 4, 5])
def test_frontier_against_clarabel(seed):
    S, mu = markowitz.example_data(n=8, seed=seed)
    path, worst, excess = markowitz.compare(S, mu, show=False)
    assert path.status == "unbounded_ray"
    # clarabel converges to about 1e-6 near degenerate corners; the objective
    # tells which answer is better: plcp's is never worse beyond rounding
    assert worst < 1e-4
    assert excess < 1e-12
    # the last corner: all in the asset with the largest mean, for every larger L
    w_end = markowitz.weights(path, 10 * path.breakpoints[-1] + 1.0)
    np.testing.assert_allclose(w_end, np.eye(len(mu))[np.argmax(mu)], atol=1e-12)
    # along the frontier the return rises and so does the variance
    Ls = np.linspace(0.0, path.breakpoints[-1], 30)
    ret = [mu @ markowitz.weights(path, L) for L in Ls]
    var = [markowitz.weights(path, L) @ S @ markowitz.weights(path, L) for L in Ls]
    assert np.all(np.diff(ret) >= -1e-14) and np.all(np.diff(var) >= -1e-14)
    for L in Ls:
        w = markowitz.weights(path, L)
        assert abs(w.sum() - 1.0) < 1e-13 and w.min() >= 0.0


@pytest.mark.parametrize("method", ["lemke", "wolfe"])
def test_mpc_homotopy_against_clarabel(method):
    path, worst, excess = mpc.compare(method, show=False)
    assert path.status == "reached"
    assert len(path.breakpoints) >= 5
    assert worst < 1e-4
    assert excess < 1e-12


def test_mpc_lemke_and_wolfe_agree():
    a, _, _ = mpc.compare("lemke", show=False)
    b, _, _ = mpc.compare("wolfe", show=False)
    np.testing.assert_allclose(a.breakpoints, b.breakpoints, rtol=1e-12)
    for L in np.linspace(0.0, 1.0, 11):
        np.testing.assert_allclose(a.at(L).u, b.at(L).u, atol=1e-12)
