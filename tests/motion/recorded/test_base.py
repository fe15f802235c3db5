"""Leg odometry: the gait's base from its feet; the LOCAL twist from Euler angles."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.motion.recorded import base
from hexaleg.motion.recorded.checks import feet_world


def test_odometry_recovers_the_gait_base(robot, gait_100hz):
    feet = feet_world(robot, gait_100hz.q[:, 7:], None)
    odo = base.leg_odometry(feet, gait_100hz.stance, 0.01, periodic=True)
    assert odo.slip.max() < 1e-6
    travel = odo.position[-1] - odo.position[0]
    assert travel[:2] == pytest.approx([gait_100hz.distance, 0.0], abs=1e-6)
    height = odo.position[:-1, 2] - odo.position[0, 2]
    assert height == pytest.approx(gait_100hz.q[:, 2] - gait_100hz.q[0, 2], abs=1e-6)


def test_quaternion_euler_round_trip_and_twist():
    rpy = np.array([[0.1, -0.2, 3.0]])
    quat = base.quaternion_from_euler(rpy)
    assert base.euler_from_rotation(base.rotation_from_quaternion(quat)) == pytest.approx(rpy)
    v, _a = base.twist(rpy, np.array([[0.0, 0.0, 1.0]]), np.zeros((1, 3)),
                      np.array([[1.0, 0.0, 0.0]]), np.zeros((1, 3)))
    assert v[0, 3:] == pytest.approx(base.rotation_from_euler(rpy)[0].T @ [0, 0, 1])
