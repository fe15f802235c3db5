"""Tests of hexaleg.design.search.bundle: the proximal bundle method finds known minima of max and
mean of convex functions, keeps the constraints and never ends worse than its feasible start."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.design.search.bundle import minimise
from hexaleg.errors import UnknownNameError


def _quadratic(centre, weight=1.0):
    c = np.asarray(centre, dtype=float)

    def f(x):
        return weight * float(np.sum((x - c) ** 2)), 2 * weight * (x - c)
    return f


def test_worst_of_two_quadratics_is_their_crossing_midpoint():
    """max(|x − a|², |x − b|²) is least at the midpoint of a and b."""
    r = minimise([_quadratic([1.0, 0.0]), _quadratic([-1.0, 2.0])], np.array([3.0, -2.0]))
    np.testing.assert_allclose(r.x, [0.0, 1.0], atol=1e-4)
    assert r.values.max() == pytest.approx(2.0, rel=1e-7)


def test_mean_of_quadratics_is_the_weighted_centre():
    r = minimise([_quadratic([1.0, 0.0], 1.0), _quadratic([-1.0, 2.0], 3.0)],
                 np.array([0.3, 0.3]), "mean")
    np.testing.assert_allclose(r.x, [-0.5, 1.5], atol=1e-4)


def test_constraints_hold_and_the_start_is_never_beaten_by_the_result():
    fs = [_quadratic([1.0, 1.0]), _quadratic([2.0, -1.0])]
    G, h = np.array([[1.0, 1.0]]), np.array([0.5])  # x + y ≤ 0.5
    x0 = np.array([0.0, 0.0])
    r = minimise(fs, x0, G=G, h=h, nonneg=np.array([True, True]))
    assert G @ r.x <= h + 1e-9 and np.all(r.x >= -1e-9)
    start = max(f(x0)[0] for f in fs)
    assert r.values.max() <= start
    # brute force over the feasible triangle: nothing beats the result
    grid = np.linspace(0, 0.5, 201)
    best = min(max(f(np.array([a, b]))[0] for f in fs) for a in grid for b in grid
               if a + b <= 0.5)
    assert r.values.max() <= best + 1e-9


def test_an_infeasible_start_is_projected_and_fixed_variables_stay_zero():
    r = minimise([_quadratic([1.0, 1.0])], np.array([-1.0, 5.0]),
                 nonneg=np.array([True, False]), fixed=np.array([False, True]))
    np.testing.assert_allclose(r.x, [1.0, 0.0], atol=1e-5)


def test_an_unknown_mode_is_named():
    with pytest.raises(UnknownNameError, match="mean, worst"):
        minimise([_quadratic([1.0, 0.0])], np.array([0.0, 0.0]), "median")


def test_csc_is_scipys_own() -> None:
    """The model step's cheap CSC assembly gives scipy's arrays exactly (so Clarabel solves the
    same program): nonzeros column-major, rows sorted, explicit zeros dropped."""
    import scipy.sparse as sp

    from hexaleg.design.search.bundle import csc

    rng = np.random.default_rng(3)
    for shape in ((7, 5), (1, 3), (12, 12)):
        dense = rng.normal(size=shape) * (rng.random(shape) < 0.4)
        ours, ref = csc(dense), sp.csc_matrix(dense)
        for name in ("data", "indices", "indptr"):
            np.testing.assert_array_equal(getattr(ours, name), getattr(ref, name))
        np.testing.assert_array_equal(ours.toarray(), dense)


def test_a_model_step_the_solver_fails_stops_at_the_best_point(monkeypatch):
    """A QP failure after the start (a numerical one: the start is feasible) ends the method
    with its best point so far and says so, instead of ending the design."""
    from hexaleg.design.search import bundle
    from hexaleg.errors import InfeasibleForcesError

    fs = [_quadratic([1.0, 0.0]), _quadratic([-1.0, 2.0])]
    full = minimise(fs, np.array([3.0, -2.0]))
    solve, calls = bundle._qp, []

    def flaky(*args, **kwargs):
        calls.append(1)
        if len(calls) == 12:
            raise InfeasibleForcesError("the robust program's model step has no solution "
                                        "(Clarabel: AlmostSolved)")
        return solve(*args, **kwargs)

    monkeypatch.setattr(bundle, "_qp", flaky)
    r = minimise(fs, np.array([3.0, -2.0]))
    assert r.iterations == 12 and r.stopped.startswith("model step 12 failed")
    assert r.serious_steps > 0
    assert "AlmostSolved" in r.stopped and full.stopped == ""
    assert full.values.max() <= r.values.max() < max(f(np.array([3.0, -2.0]))[0] for f in fs)


def test_dropping_old_cuts_keeps_the_minimum(monkeypatch):
    """Bundle compression (cuts off the model for CUT_AGE steps dropped) finds the minimum the
    full bundle finds, on the worst of many quadratics with constraints, with fewer cuts."""
    from hexaleg.design.search import bundle

    rng = np.random.default_rng(7)
    fs = [_quadratic(rng.normal(size=6), w) for w in rng.uniform(0.5, 2.0, 15)]
    G, h = rng.normal(size=(4, 6)), np.ones(4)
    kept = []
    prune = bundle._Cuts.prune

    def spy(self, y, n):
        prune(self, y, n)
        kept.append(self.c.size)

    monkeypatch.setattr(bundle._Cuts, "prune", spy)
    short = minimise(fs, np.zeros(6), G=G, h=h)
    monkeypatch.setattr(bundle, "CUT_AGE", 10**9)
    kept_short, kept[:] = list(kept), []
    full = minimise(fs, np.zeros(6), G=G, h=h)
    assert short.values.max() == pytest.approx(full.values.max(), rel=1e-8)
    # the value is certified to 1e-10; the minimiser only to about its square root
    np.testing.assert_allclose(short.x, full.x, atol=1e-4)
    assert max(kept_short) < max(kept)  # cuts were dropped


def test_a_function_left_out_of_the_working_set_joins_when_it_becomes_the_worst():
    """max((x − 4)², 2x²) from x = 0: the second is 0 there, far below the first's 16, so the
    model starts without it; at the first's minimum it is 32 and joins. The minimum is where
    they cross, x = √32 − 4, at the crossing's value (analytic)."""
    fs = [_quadratic([4.0]), _quadratic([0.0], 2.0)]
    r = minimise(fs, np.zeros(1))
    x = np.sqrt(32.0) - 4.0
    assert r.held == 2
    assert r.x[0] == pytest.approx(x, abs=1e-4)
    assert r.values.max() == pytest.approx((x - 4.0) ** 2, rel=1e-9)
    np.testing.assert_allclose(r.values, [f(r.x)[0] for f in fs], rtol=1e-15)


def test_the_working_set_finds_the_minimum_every_function_held_finds(monkeypatch):
    """The worst of 40 quadratics with constraints: started with the few near the worst, the
    model ends holding fewer than all, at the minimum the model with every function finds (to
    the value's tolerance), and reports every function's value at its point."""
    from hexaleg.design.search import bundle

    rng = np.random.default_rng(11)
    fs = [_quadratic(rng.normal(size=5), w) for w in rng.uniform(0.5, 2.0, 40)]
    G, h = rng.normal(size=(3, 5)), np.ones(3)
    ws = minimise(fs, np.zeros(5), G=G, h=h)
    monkeypatch.setattr(bundle, "WORKING_SET", np.inf)
    every = minimise(fs, np.zeros(5), G=G, h=h)
    assert every.held == 40 and 1 < ws.held < 40
    assert ws.values.max() == pytest.approx(every.values.max(), rel=1e-9)
    np.testing.assert_allclose(ws.values, [f(ws.x)[0] for f in fs], rtol=1e-15)
    assert (G @ ws.x <= h + 1e-9).all()
