"""An optimal cycle written as a log reads back through hexaleg.load_motion to the same cycle."""

from __future__ import annotations

import numpy as np
import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError
from hexaleg.optimal.motion_file import repeated, write_optimal_motion


def test_repeating_moves_each_cycle_by_a_stride(walk):
    three = repeated(walk, 3)
    n = walk.n_samples
    assert three.n_samples == 3 * n and three.distance == pytest.approx(3 * walk.distance)
    np.testing.assert_allclose(three.q[2 * n:, 0] - walk.q[:, 0], 2 * walk.distance, atol=1e-12)
    np.testing.assert_allclose(three.q[2 * n:, 1:], walk.q[:, 1:], atol=1e-12)
    np.testing.assert_allclose(three.feet[n:2 * n, :, 0] - walk.feet[:, :, 0], walk.distance,
                               atol=1e-12)


def test_the_written_cycle_reads_back(robot, walk, tmp_path):
    """The gait thinned to 50 samples stands in for an optimal cycle (same Motion, no solver):
    the log of three cycles reads back, period and joints exact, through the loader every
    command's --motion uses."""
    thin = slice(None, None, 20)
    cycle = hexaleg.Motion(t=walk.t[thin], q=walk.q[thin], v=walk.v[thin], a=walk.a[thin],
                           stance=walk.stance[thin], feet=walk.feet[thin], period=walk.period,
                           distance=walk.distance, info=dict(walk.info))
    path = write_optimal_motion(robot, cycle, tmp_path / "optimal.csv")
    back = hexaleg.load_motion(robot, path)
    assert back.period == pytest.approx(cycle.period, rel=1e-9)
    assert back.n_samples == cycle.n_samples
    np.testing.assert_allclose(back.q[:, 7:], cycle.q[:, 7:], atol=1e-9)
    np.testing.assert_array_equal(back.stance, cycle.stance)


def test_one_cycle_is_not_enough(robot, walk, tmp_path):
    with pytest.raises(InvalidParameterError, match="cycles"):
        write_optimal_motion(robot, walk, tmp_path / "x.csv", cycles=1)
