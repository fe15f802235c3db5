"""Tests of hexaleg.outputs.viewer.colours: the cool-warm map and its bins."""

from __future__ import annotations

import numpy as np

from hexaleg.outputs.viewer.colours import N_LEVELS, colours, cool_warm, value_bins


def test_cool_warm_anchors_and_symmetry():
    np.testing.assert_allclose(cool_warm(np.array([0.0, 0.5, 1.0])),
                               [[0.230, 0.299, 0.754], [0.865, 0.865, 0.865],
                                [0.706, 0.016, 0.150]])
    x = np.linspace(0, 0.5, 11)
    # Blue fades into grey on the way up: red channel rises monotonically, blue falls after grey.
    assert np.all(np.diff(cool_warm(x)[:, 0]) > 0)
    assert np.all(np.diff(cool_warm(0.5 + x)[:, 2]) < 0)


def test_bin_colours_are_the_map_at_bin_centres():
    c = colours()
    assert c.shape == (N_LEVELS, 3)
    np.testing.assert_allclose(c[N_LEVELS // 2], [0.865, 0.865, 0.865])  # 0 is neutral grey
    np.testing.assert_allclose(c[0], cool_warm(0.5 / N_LEVELS))


def test_value_bins_symmetric_and_edges():
    vmax = 2.0
    v = np.linspace(-vmax, vmax, 1001)
    b = value_bins(v, vmax)
    assert b[0] == 0 and b[-1] == N_LEVELS - 1
    assert value_bins(0.0, vmax) == N_LEVELS // 2
    assert np.all(np.diff(b) >= 0)
    # Away from bin edges, bin(−v) mirrors bin(v).
    inner = np.abs(((v + vmax) / (2 * vmax) * N_LEVELS) % 1 - 0.5) < 0.45
    np.testing.assert_array_equal(value_bins(-v[inner], vmax), N_LEVELS - 1 - b[inner])
    np.testing.assert_array_equal(value_bins(v, 0.0), N_LEVELS // 2)
