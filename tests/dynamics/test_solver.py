"""Tests of hexaleg.dynamics.solver: the quadratic program's gains and the fast path's checks."""

from __future__ import annotations

import numpy as np
import pytest

import hexaleg
from hexaleg.dynamics.prepare import prepare
from hexaleg.dynamics.solver import quadratic_gains
from hexaleg.errors import InfeasibleForcesError


def test_quadratic_gains_give_the_constrained_optimum(robot, walk200):
    """KKT: base rows hold and no direction in their null space lowers Σ w τ²."""
    prepared = prepare(robot, walk200)
    sys = prepared.system
    w = prepared.weights("joule")
    gains = quadratic_gains(sys, w)
    f = gains.f0
    assert np.max(np.abs(np.einsum("tik,tk->ti", sys.A, f) - sys.b_base)) <= 1e-9
    rng = np.random.default_rng(0)
    for k in rng.choice(walk200.n_samples, 10, replace=False):
        cols = np.flatnonzero(np.repeat(sys.stance[k], 3))
        A = sys.A[k][:, cols]
        null = np.linalg.svd(A)[2][6:].T  # basis of A's null space
        tau = sys.b_joint[k] - sys.D[k] @ f[k]
        grad = -2 * sys.D[k][:, cols].T @ (w * tau)
        assert np.max(np.abs(null.T @ grad)) <= 1e-9 * np.max(np.abs(grad))


@pytest.mark.parametrize("objective", ["joule", "positive_work"])
def test_unreachable_wrench_is_caught_on_every_path(robot, walk200, objective):
    """LF and LM alone: gravity has a moment about the line through them that no foot force can
    balance (the KKT system is singular). Both the KKT path and the conic path (which drops
    redundant base rows) say so with the time and the feet, not a numpy traceback."""
    motion = walk200
    stance = motion.stance.copy()
    stance[5] = False
    stance[5, [0, 1]] = True  # LF, LM
    two = hexaleg.Motion(t=motion.t, q=motion.q, v=motion.v, a=motion.a, stance=stance,
                         feet=motion.feet, period=motion.period, distance=motion.distance)
    expected = r"feet LF, LM cannot .*\(sample 5\).*miss the base rows"
    with pytest.raises(InfeasibleForcesError, match=expected):
        prepare(robot, two).evaluate(objective=objective)
