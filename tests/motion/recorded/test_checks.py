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
