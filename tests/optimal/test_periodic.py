"""Periodicity: the cycle's displacement of the gait, the shifted state, the gap."""

from __future__ import annotations

import dataclasses

import numpy as np
import pinocchio as pin
import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.optimal.periodic import cycle_displacement, periodicity_gap, shifted_state


def test_the_gaits_cycle_is_its_stride(walk):
    h = cycle_displacement(walk)
    np.testing.assert_allclose(h[:3, :3], np.eye(3))
    np.testing.assert_allclose(h[:3, 3], [walk.distance, 0.0, 0.0])


def test_without_a_stated_cycle_the_distance_along_the_direction(walk):
    info = {k: v for k, v in walk.info.items() if k != "cycle"}
    info["direction"] = [0.0, 2.0, 0.0]
    h = cycle_displacement(dataclasses.replace(walk, info=info))
    np.testing.assert_allclose(h[:3, 3], [0.0, walk.distance, 0.0])


def test_the_shift_moves_the_base_only(walk):
    x = np.concatenate([walk.q[7], walk.v[7]])
    h = np.eye(4)
    h[:3, :3] = pin.rpy.rpyToMatrix(0.0, 0.0, 0.3)
    h[:3, 3] = [0.1, 0.2, 0.0]
    y = shifted_state(x, h)
    np.testing.assert_allclose(y[7:], x[7:])
    base = pin.XYZQUATToSE3(x[:7])
    np.testing.assert_allclose(pin.XYZQUATToSE3(y[:7]).homogeneous, h @ base.homogeneous,
                               atol=1e-12)
    assert periodicity_gap([x, y], h, lambda a, b: b - a) < 1e-12
    assert periodicity_gap([x, x], h, lambda a, b: b - a) > 0.1


def test_a_motion_that_does_not_repeat_is_refused(walk):
    with pytest.raises(InvalidParameterError, match="periodic"):
        cycle_displacement(dataclasses.replace(walk, periodic=False))
    bad = dict(walk.info, cycle=[[2.0, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
    with pytest.raises(InvalidParameterError, match="cycle"):
        cycle_displacement(dataclasses.replace(walk, info=bad))
