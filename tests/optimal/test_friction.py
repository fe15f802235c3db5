"""The friction pyramid: zero inside the cone, positive outside, its gradient the slope."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError

pytest.importorskip("crocoddyl")

from hexaleg.optimal.friction import FrictionPyramid, pyramid


def _value(act, r):
    data = act.createData()
    act.calc(data, r)
    return data.a_value, data


def test_inside_the_pyramid_costs_nothing_outside_it_does():
    act = FrictionPyramid(0.5)
    assert _value(act, np.array([0.1, -0.1, 1.0]))[0] == 0.0  # |f_t| ≤ μ f_z / √2 per axis
    assert _value(act, np.array([0.4, 0.0, 1.0]))[0] > 0.0  # sliding along x
    # pulling: the normal row and the four facets, each μ/√2 over
    assert _value(act, np.array([0.0, 0.0, -1.0]))[0] == pytest.approx(0.5 * (1 + 2 * 0.5**2))


def test_the_pyramid_is_inside_the_cone():
    """Every force the pyramid admits is in the cone ‖f_t‖ ≤ μ f_z (its inner approximation)."""
    rows = pyramid(0.6)
    rng = np.random.default_rng(0)
    f = rng.normal(size=(2000, 3)) * [1, 1, 0.5] + [0, 0, 1]
    inside = (f @ rows.T <= 0).all(axis=1)
    assert inside.sum() > 100
    assert np.all(np.hypot(f[inside, 0], f[inside, 1]) <= 0.6 * f[inside, 2] + 1e-12)


def test_gradient_matches_finite_differences():
    act = FrictionPyramid(0.5)
    r = np.array([0.7, -0.2, 0.5])
    _, data = _value(act, r)
    act.calcDiff(data, r)
    h = 1e-7
    fd = [(_value(act, r + h * e)[0] - _value(act, r - h * e)[0]) / (2 * h) for e in np.eye(3)]
    np.testing.assert_allclose(data.Ar, fd, atol=1e-6)


def test_a_bad_coefficient_is_named():
    with pytest.raises(InvalidParameterError, match="friction coefficient"):
        pyramid(-0.1)
