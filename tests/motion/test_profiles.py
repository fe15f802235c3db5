"""Tests of hexaleg.motion.profiles: the swing profiles start and stop at rest with exact
derivatives; the swing curve's apex; the paper's sinusoid (eq. 16) and its derivatives."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hexaleg.motion.profiles import Sinusoid, smoothstep, swing_bump, swing_curve


def test_swing_profiles_start_and_stop_at_rest():
    ends = np.array([0.0, 1.0])
    for f in (smoothstep, swing_bump):
        _, d1, d2 = f(ends)
        assert np.allclose(d1, 0.0) and np.allclose(d2, 0.0)
    assert np.allclose(smoothstep(ends)[0], [0.0, 1.0])
    assert np.allclose(swing_bump(ends)[0], [0.0, 0.0])
    assert swing_bump(np.array([0.5]))[0][0] == pytest.approx(1.0)
    s = np.linspace(0.0, 1.0, 201)
    assert np.all(np.diff(smoothstep(s)[0]) >= 0)  # monotone ground track
    assert swing_bump(s)[0].max() == pytest.approx(1.0)


@pytest.mark.parametrize("f", [smoothstep, swing_bump])
def test_swing_profile_derivatives_equal_finite_differences(f):
    s, h = np.linspace(0.05, 0.95, 19), 1e-5
    _, d1, d2 = f(s)
    assert np.allclose((f(s + h)[0] - f(s - h)[0]) / (2 * h), d1, atol=1e-7)
    assert np.allclose((f(s + h)[1] - f(s - h)[1]) / (2 * h), d2, atol=1e-6)


def test_swing_curve_reaches_step_height_midway():
    p0, p1 = np.array([0.1, 0.2, 0.0]), np.array([0.16, 0.2, 0.0])
    p, dp, ddp = swing_curve(np.array([0.0, 0.5, 1.0]), p0, p1, 0.03)
    assert np.allclose(p, [p0, [0.13, 0.2, 0.03], p1])
    assert np.allclose(dp[[0, 2]], 0.0) and np.allclose(ddp[[0, 2]], 0.0)


def test_sinusoid_derivatives_equal_central_differences():
    f = Sinusoid(amplitude=0.4, omega=3.0, phase=0.5, offset=0.2)
    t, h = np.linspace(0.0, 2.0, 17), 1e-5
    value, d1, d2 = f(t)
    assert np.allclose((f(t + h)[0] - f(t - h)[0]) / (2 * h), d1, atol=1e-8)
    assert np.allclose((f(t + h)[1] - f(t - h)[1]) / (2 * h), d2, atol=1e-7)
    assert value[0] == pytest.approx(0.4 * math.sin(0.5) + 0.2)
