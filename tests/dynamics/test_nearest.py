"""Tests of hexaleg.dynamics.nearest: a wrench the contacts can produce is kept; one they
cannot is replaced by the nearest they can (an exact projection where it is known in closed
form); a residual beyond the bound is a named error."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hexaleg.dynamics.nearest import BOUND, EDGES, nearest_wrench
from hexaleg.errors import InfeasibleForcesError

WEIGHT = 10.0


def _feet(*positions: tuple[float, float, float]) -> np.ndarray:
    """Base rows of point feet at ``positions`` (base frame): force, and moment r × f."""
    blocks = []
    for r in positions:
        skew = np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])
        blocks.append(np.vstack([np.eye(3), skew]))
    return np.concatenate(blocks, axis=1)[None]


def test_a_wrench_the_feet_can_push_is_kept():
    A = _feet((0.1, 0.1, -0.1), (-0.1, 0.1, -0.1), (0.0, -0.1, -0.1))
    b = np.array([[0.5, -0.2, WEIGHT, 0.0, 0.0, 0.0]])
    out, found = nearest_wrench(A, b, np.ones((1, 3), bool), 0.6, 0.0, WEIGHT, np.zeros(1))
    np.testing.assert_array_equal(out, b)
    assert found.samples.size == 0 and found.line() is None


def test_a_pull_is_replaced_by_no_force_and_reported():
    """The base accelerating down faster than gravity needs the feet to pull: the nearest
    wrench they can push is none, the residual all of it."""
    A = _feet((0.1, 0.0, -0.1), (-0.1, 0.0, -0.1))
    b = np.array([[0.0, 0.0, -0.2 * WEIGHT, 0.0, 0.0, 0.0]])
    out, found = nearest_wrench(A, b, np.ones((1, 2), bool), 0.6, 0.0, WEIGHT, np.array([0.3]))
    np.testing.assert_allclose(out, 0.0, atol=1e-12)
    np.testing.assert_allclose(found.residual, b, atol=1e-12)
    assert found.fraction[0] == pytest.approx(0.2)
    assert "1 of 1 samples" in found.line() and "20.0 % of the weight (t = 0.3000 s)" in \
        found.line()


def test_a_slide_beyond_friction_is_projected_onto_the_cone():
    """One foot under the base pushed along x beyond μ: the nearest force is the projection of
    (f_x, f_z) onto the cone's edge f_x = μ f_z (an edge of the pyramid), in closed form."""
    mu, p = 0.3, np.array([0.5 * WEIGHT, 0.0, WEIGHT])
    A = _feet((0.0, 0.0, 0.0))
    out, found = nearest_wrench(A, np.r_[p, np.zeros(3)][None], np.ones((1, 1), bool), mu, 0.0,
                                WEIGHT, np.zeros(1))
    d = np.array([mu, 0.0, 1.0]) / math.hypot(mu, 1.0)
    np.testing.assert_allclose(out[0, :3], (p @ d) * d, rtol=1e-9)
    assert found.fraction[0] == pytest.approx(np.linalg.norm(p - (p @ d) * d) / WEIGHT)
    assert EDGES % 4 == 0  # the x edge is one of the pyramid's


def test_the_minimum_normal_force_is_kept_in_the_nearest_wrench():
    A = _feet((0.1, 0.0, -0.1), (-0.1, 0.0, -0.1))
    b = np.zeros((1, 6))
    out, found = nearest_wrench(A, b, np.ones((1, 2), bool), 0.6, 1.0, WEIGHT, np.zeros(1))
    assert out[0, 2] == pytest.approx(2.0) and found.residual[0, 2] == pytest.approx(-2.0)


def test_a_residual_beyond_the_bound_is_an_error_naming_the_samples():
    A = np.repeat(_feet((0.1, 0.0, -0.1), (-0.1, 0.0, -0.1)), 2, axis=0)
    b = np.array([[0.0, 0.0, WEIGHT, 0, 0, 0], [0.0, 0.0, -(BOUND + 0.1) * WEIGHT, 0, 0, 0]])
    with pytest.raises(InfeasibleForcesError, match=r"1 samples \(from t = 0\.0100 s\).*60 % "
                       r"of the weight.*Likely causes"):
        nearest_wrench(A, b, np.ones((2, 2), bool), 0.6, 0.0, WEIGHT, np.array([0.0, 0.01]))
