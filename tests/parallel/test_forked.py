"""Tests of hexaleg.parallel.forked: a map over forked processes is the map in turn, in order, with
the shared objects coming back as this process's own, and a worker's error raised here."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.parallel.forked import fork_map, robot_objects


def test_forked_map_is_the_map_in_turn_and_shares_the_robot(robot):
    def work(k: int) -> tuple[object, np.ndarray]:
        return robot, robot.model.inertias[k].mass * np.arange(3.0)

    seen: list[int] = []
    forked = fork_map(work, [3, 1, 2], shared=robot_objects(robot), workers=2,
                      done=lambda i, _: seen.append(i))
    in_turn = fork_map(work, [3, 1, 2], workers=1)
    assert sorted(seen) == [0, 1, 2]
    for (r, a), (s, b) in zip(forked, in_turn, strict=True):
        assert r is robot and s is robot  # the robot itself, not a pickled copy
        assert np.array_equal(a, b)


def test_without_sharing_a_result_is_a_copy(robot):
    forked = fork_map(lambda k: robot.legs[k], [0, 1], workers=2)
    assert forked[0].name == robot.legs[0].name and forked[0] is not robot.legs[0]


def test_a_worker_error_is_raised_here():
    def work(k: int) -> int:
        if k == 2:
            raise InvalidParameterError("k", k, "not 2")
        return k

    with pytest.raises(InvalidParameterError, match="k = 2"):
        fork_map(work, [1, 2, 3], workers=2)


def test_a_map_inside_a_worker_of_another():
    def inner(k: int) -> list[int]:
        return fork_map(lambda j: 10 * k + j, [0, 1], workers=2)

    assert fork_map(inner, [1, 2, 3, 4], workers=2) == [[10, 11], [20, 21], [30, 31], [40, 41]]
