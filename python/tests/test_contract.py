"""The Python interface as a contract: names, types, shapes, errors, GIL."""

import ast
import math
import pathlib
import threading
import time

import numpy as np
import pytest
import scipy.sparse as sp

import plcp
from conftest import enumerate_lcp

M2 = np.array([[2.0, 1.0], [1.0, 2.0]])
Q2 = np.array([1.0, 1.0])
D2 = np.array([-1.0, -0.5])


def random_pd(rng, n):
    A = rng.standard_normal((n, n))
    # positive definite but not symmetric: a unique solution for every L
    return A @ A.T + 0.5 * np.eye(n) + 0.3 * (A - A.T)


def test_small_path_against_closed_form():
    path = plcp.solve(M2, Q2, D2)
    assert path.status == "unbounded_ray"
    assert path.success
    assert path.lambda_reached == math.inf
    assert isinstance(path.breakpoints, np.ndarray) and path.breakpoints.ndim == 1
    # w0 = 1 - L reaches zero at L = 1 and z0 enters
    assert path.breakpoints[0] == 1.0
    assert path.events[0] == ("z0", "w0")
    assert all(isinstance(a, str) and isinstance(b, str) for a, b in path.events)
    # beyond L = 1: z0 = (L - 1) / 2, w1 = 1 - L/2 + z0 = (1 - 0.0 L)... check by the equation
    for L in [0.0, 0.5, 1.0, 1.5, 1.9]:
        pt = path.at(L)
        z0 = max(0.0, (L - 1.0) / 2.0)
        np.testing.assert_allclose(pt.z, [z0, 0.0], atol=1e-14)
        np.testing.assert_allclose(pt.w, Q2 + L * D2 + M2 @ pt.z, atol=1e-14)
        assert pt.u.shape == (0,)
        assert pt.lambda_ == L


def test_segments_fields_and_continuity(rng):
    M = random_pd(rng, 6)
    q = rng.uniform(0.5, 2.0, 6)
    d = rng.standard_normal(6)
    path = plcp.solve(M, q, d, lambda_max=10.0)
    assert path.status == "reached" and path.lambda_reached == 10.0
    segs = path.segments
    assert len(segs) >= 1
    for s in segs:
        for name in ["z_from", "dz", "w_from", "dw", "u_from", "du"]:
            a = getattr(s, name)
            assert isinstance(a, np.ndarray) and a.dtype == np.float64
        assert s.z_from.shape == (6,) and s.u_from.shape == (0,)
        assert len(s.basis) == 6
        # the equation holds on the whole piece
        for L in [s.lambda_from, 0.5 * (s.lambda_from + s.lambda_to), s.lambda_to]:
            z = s.z_from + (L - s.lambda_from) * s.dz
            w = s.w_from + (L - s.lambda_from) * s.dw
            np.testing.assert_allclose(w, q + L * d + M @ z, atol=1e-11)
    for a, b in zip(segs, segs[1:]):
        assert a.lambda_to == b.lambda_from
        np.testing.assert_allclose(a.z_from + (a.lambda_to - a.lambda_from) * a.dz, b.z_from, atol=1e-11)
    # the breakpoints lie where the segments meet (degenerate steps may add more)
    assert set(s.lambda_to for s in segs[:-1]) <= set(path.breakpoints.tolist())
    assert path.at(10.5) is None
    assert path.at(-0.1) is None


@pytest.mark.parametrize("method", ["lemke", "wolfe"])
@pytest.mark.parametrize("precision,tol", [("f32", 2e-3), ("f64", 1e-10), ("f128", 1e-10)])
def test_random_paths_against_enumeration(rng, method, precision, tol):
    for trial in range(4):
        n = 5
        M = random_pd(rng, n)
        q = rng.standard_normal(n)  # not feasible at L = 0: the start phase runs
        d = rng.standard_normal(n)
        path = plcp.solve(M, q, d, lambda_max=5.0, method=method, precision=precision)
        assert path.status == "reached", path.message
        assert path.info["precision"] == precision
        assert path.info["method"].startswith(method)  # "lemke (principal)": the fast path
        for L in np.linspace(0.0, 5.0, 11):
            pt = path.at(L)
            sols = enumerate_lcp(M, q + L * d)
            assert len(sols) == 1  # positive definite: unique
            z, w = sols[0]
            scale = 1.0 + np.abs(z).max()
            assert np.abs(pt.z - z).max() <= tol * scale
            assert np.abs(pt.w - w).max() <= tol * (1.0 + np.abs(w).max())


def test_f128_is_more_accurate_than_f32(rng):
    M = random_pd(rng, 6)
    q, d = rng.uniform(0.1, 1.0, 6), -rng.uniform(0.1, 1.0, 6)
    exact = enumerate_lcp(M, q + 2.0 * d)[0][0]
    err = {p: np.abs(plcp.solve(M, q, d, lambda_max=2.0, precision=p).at(2.0).z - exact).max() for p in ["f32", "f128"]}
    assert err["f128"] < 1e-12 < err["f32"]


@pytest.mark.parametrize("fmt", ["csr", "csc", "coo"])
def test_sparse_input_traces_the_dense_path(rng, fmt):
    n = 7
    A = random_pd(rng, n)
    A[np.abs(A) < 0.8] = 0.0
    A += 3.0 * n * np.eye(n)  # diagonally dominant: still positive definite
    q, d = rng.uniform(0.2, 1.0, n), -rng.uniform(0.2, 1.0, n)
    dense = plcp.solve(A, q, d, lambda_max=4.0)
    sparse = plcp.solve(sp.coo_matrix(A).asformat(fmt), q, d, lambda_max=4.0)
    assert sparse.status == dense.status == "reached"
    np.testing.assert_allclose(sparse.breakpoints, dense.breakpoints, rtol=1e-12)
    assert sparse.events == dense.events
    for L in [0.3, 1.7, 4.0]:
        np.testing.assert_allclose(sparse.at(L).z, dense.at(L).z, atol=1e-12)


@pytest.mark.parametrize("sparse", [False, True])
def test_mixed_form_with_free_variables(sparse):
    # 0 = -u + 1 - z (u free), w = u + 2 z - L = 1 + z - L: one free variable,
    # one pair; for L <= 1: z = 0, u = 1, w = 1 - L; beyond: z = L - 1, u = 2 - L
    M = np.array([[-1.0, -1.0], [1.0, 2.0]])
    q, d = np.array([1.0, 0.0]), np.array([0.0, -1.0])
    Mi = sp.csr_matrix(M) if sparse else M
    for method in ["wolfe", "lemke"]:
        path = plcp.solve(Mi, q, d, free=1, method=method, lambda_max=3.0)
        assert path.status == "reached", path.message
        np.testing.assert_allclose(path.breakpoints, [1.0])
        for L in [0.0, 0.5, 1.0, 2.0, 3.0]:
            pt = path.at(L)
            np.testing.assert_allclose(pt.u, [1.0 - max(0.0, L - 1.0)], atol=1e-13)
            np.testing.assert_allclose(pt.z, [max(0.0, L - 1.0)], atol=1e-13)
            np.testing.assert_allclose(pt.w, [max(0.0, 1.0 - L)], atol=1e-13)
    # the secondary ray where the continuation is infeasible: w = 1 - z - L
    M[1, 1] = 0.0
    path = plcp.solve(M, q, d, free=1, method="wolfe", lambda_max=3.0)
    assert path.status == "secondary_ray"
    assert path.lambda_reached == pytest.approx(1.0)


def test_info_dict():
    info = plcp.solve(M2, Q2, D2).info
    for key in ["method", "precision", "pivots", "start_pivots", "degenerate_pivots",
                "refactorisations", "turning_points", "residuals", "max_condition", "seconds",
                "fast_path"]:
        assert key in info
    assert isinstance(info["fast_path"], str)
    assert info["pivots"] >= 1
    assert set(info["residuals"]) == {"equation", "feasibility", "complementarity"}
    assert info["seconds"] >= 0.0


def test_secondary_ray_is_a_status_not_an_exception():
    # w = q + L d + M z with M = -I: no solution once q + L d has a negative entry
    path = plcp.solve(-np.eye(2), np.array([1.0, 1.0]), np.array([-1.0, 0.0]), lambda_max=5.0)
    assert path.status == "secondary_ray"
    assert not path.success
    assert path.lambda_reached == pytest.approx(1.0)


@pytest.mark.parametrize(
    "kwargs,match",
    [
        (dict(M=np.ones((2, 3))), "dimension mismatch"),
        (dict(M=np.ones(4)), "2-D"),
        (dict(q=np.array([1.0, np.nan])), "non-finite entry in q"),
        (dict(d=np.array([1.0, 2.0, 3.0])), "dimension mismatch: d"),
        (dict(q=np.ones((2, 1))), "1-D"),
        (dict(method="simplex"), "unknown method 'simplex'"),
        (dict(precision="f16"), "unknown precision 'f16'"),
        (dict(lambda_max=-1.0), "lambda_max"),
        (dict(lambda0=math.inf), "lambda0"),
        (dict(free=3), "free"),
        (dict(free=-1), "free"),
        (dict(M=np.array([[1e300, 0.0], [0.0, 1.0]]), precision="f32"), "non-finite entry in M"),
        (dict(M=sp.csr_matrix(np.ones((2, 3)))), "dimension mismatch"),
    ],
)
def test_bad_input_raises_value_error(kwargs, match):
    args = dict(M=M2, q=Q2, d=D2)
    args.update(kwargs)
    M, q, d = args.pop("M"), args.pop("q"), args.pop("d")
    with pytest.raises(ValueError, match=match):
        plcp.solve(M, q, d, **args)


def test_solve_lcp_against_enumeration(rng):
    M = random_pd(rng, 6)
    q = rng.standard_normal(6)
    sol = plcp.solve_lcp(M, q)
    assert sol.status == "reached", sol.message
    z, w = enumerate_lcp(M, q)[0]
    np.testing.assert_allclose(sol.z, z, atol=1e-12)
    np.testing.assert_allclose(sol.w, w, atol=1e-12)
    np.testing.assert_allclose(plcp.solve_lcp(sp.csr_matrix(M), q, precision="f128").z, z, atol=1e-12)
    with pytest.raises(ValueError, match="non-finite"):
        plcp.solve_lcp(M, np.full(6, np.inf))
    with pytest.raises(ValueError, match="dimension mismatch"):
        plcp.solve_lcp(M, np.ones(5))


def test_the_solve_releases_the_gil(rng):
    # a LASSO path with a few hundred pivots: long enough to watch
    X = rng.standard_normal((500, 400))
    y = rng.standard_normal(500)
    G, c = X.T @ X, X.T @ y
    M = np.block([[G, -G], [-G, G]])
    tmax = np.abs(c).max()
    q = np.concatenate([tmax - c, tmax + c])
    d = -np.ones(800)
    window = []

    def work():
        t0 = time.perf_counter()
        plcp.solve(M, q, d, lambda_max=tmax)
        window.append((t0, time.perf_counter()))

    t = threading.Thread(target=work)
    ticks = []
    t.start()
    while t.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    t.join()
    (t0, t1), = window
    assert t1 - t0 > 0.05, "the solve is too short to tell"
    # with the GIL held for the whole solve this thread could not tick inside it
    inside = [s for s in ticks if t0 + 0.01 < s < t1 - 0.01]
    assert len(inside) >= 3, f"{len(inside)} ticks in a {t1 - t0:.3f} s solve"


def stub_properties():
    stub = pathlib.Path(plcp.__file__).parent / "_plcp.pyi"
    tree = ast.parse(stub.read_text())
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            yield node.name, [f.name for f in node.body if isinstance(f, ast.FunctionDef)]
        elif isinstance(node, ast.FunctionDef):
            yield None, node.name


def test_stubs_ship_and_match_the_module():
    pkg = pathlib.Path(plcp.__file__).parent
    assert (pkg / "py.typed").exists()
    classes = 0
    for cls, names in stub_properties():
        if cls is None:
            assert hasattr(plcp._plcp, names), names
            continue
        classes += 1
        runtime = getattr(plcp._plcp, cls)
        assert getattr(plcp, cls) is runtime
        for name in names:
            assert hasattr(runtime, name), f"{cls}.{name}"
        # and nothing public at run time is missing from the stubs
        public = {a for a in dir(runtime) if not a.startswith("_")}
        assert public <= set(names), f"{cls}: {public - set(names)} not in the stubs"
    assert classes == 4
