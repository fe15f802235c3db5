"""The log's checks: missing joints, units that leave the limits, feet underground."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.motion.recorded.checks import check_columns, check_ground, check_limits
from hexaleg.motion.recorded.read import Log


def test_missing_joint_lists_the_robot_joints(robot):
    with pytest.raises(InvalidParameterError, match="LF_coxa, LF_femur"):
        check_columns(robot, Log(t=np.zeros(2), columns={}), None, "log")


def test_degrees_read_as_radians_get_a_hint(robot):
    q = np.zeros((2, robot.nj))
    q[1, 1] = 60.0
    with pytest.raises(InvalidParameterError, match=r"LF_femur \[deg\]"):
        check_limits(robot, q, np.array([0.0, 0.01]), {}, "log")


def test_feet_underground_are_named(robot):
    feet = np.zeros((2, 6, 3))
    feet[1, 2, 2] = -0.03
    with pytest.raises(InvalidParameterError, match=r"LH foot 30\.0 mm underground"):
        check_ground(robot, feet, np.array([0.0, 0.01]), "log")


def test_attitude_names_a_w_first_order_and_an_upside_down_body():
    from hexaleg.motion.recorded.checks import check_attitude

    level = np.tile([0.0, 0.0, 0.0, 1.0], (10, 1))
    check_attitude(level, "log")
    with pytest.raises(InvalidParameterError, match="w-first"):
        check_attitude(level[:, [3, 0, 1, 2]], "log")
    with pytest.raises(InvalidParameterError, match="upside down in most rows"):
        check_attitude(np.tile([0.0, 1.0, 0.0, 0.0], (10, 1)), "log")  # 180° about y, either order


def test_whole_cycle_names_the_joint_that_does_not_come_back():
    from hexaleg.motion.recorded.checks import check_whole

    phase = np.linspace(0.0, 2 * np.pi, 100, endpoint=False)
    q = np.stack([np.sin(phase), 0.1 * np.cos(phase)], axis=1)
    check_whole(q, ["a", "b"], "log")
    with pytest.raises(InvalidParameterError, match=r"on b \(16\.9 times"):
        check_whole(q[:75], ["a", "b"], "log")
