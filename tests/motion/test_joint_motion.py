"""Tests of hexaleg.motion.joint_motion: the paper's sinusoid (eq. 16, eq. 25) embedded in the
robot on a fixed base, and the errors on bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.motion.joint_motion import joint_motion
from hexaleg.motion.profiles import Sinusoid


def test_joint_motion_embeds_the_papers_sinusoid(robot):
    """Paper eq. 25: f(t) = 0.3 sin(2t), with exact derivatives, other joints at stand."""
    motion = joint_motion(robot, {"LF_femur": Sinusoid(amplitude=0.3, omega=2.0)}, samples=400)
    col = robot.column("LF_femur")
    t = motion.t
    assert motion.period == pytest.approx(math.pi) and motion.periodic
    assert motion.fixed_base and not motion.stance.any() and motion.distance == 0.0
    assert np.allclose(motion.q[:, 7 + col], 0.3 * np.sin(2 * t))
    assert np.allclose(motion.v[:, 6 + col], 0.6 * np.cos(2 * t))
    assert np.allclose(motion.a[:, 6 + col], -1.2 * np.sin(2 * t))
    others = np.delete(np.arange(robot.nj), col)
    assert np.allclose(motion.q[:, 7 + others], robot.pose("stand")[7 + others])
    assert np.allclose(motion.v[:, 6 + others], 0) and np.allclose(motion.a[:, 6 + others], 0)
    assert np.allclose(motion.feet[7], robot.foot_positions(motion.q[7]))


def test_joint_motion_errors(robot):
    with pytest.raises(UnknownNameError, match=r"'LF_knee'.*LF_femur"):
        joint_motion(robot, {"LF_knee": Sinusoid(0.3, 2.0)})
    with pytest.raises(InvalidParameterError, match="period"):
        joint_motion(robot, {"LF_femur": Sinusoid(0.3, 2.0), "RF_femur": Sinusoid(0.3, 3.0)})
    with pytest.raises(InvalidParameterError, match="samples"):
        joint_motion(robot, {"LF_femur": Sinusoid(0.3, 2.0)}, samples=3)
    with pytest.raises(InvalidParameterError, match=r"LF_femur.*joint limits"):
        joint_motion(robot, {"LF_femur": Sinusoid(3.0, 2.0)})
    with pytest.raises(InvalidParameterError, match=r"Sinusoid\.omega"):
        Sinusoid(0.3, math.inf)
    two = joint_motion(robot, {"LF_femur": Sinusoid(0.3, 2.0), "RF_femur": Sinusoid(0.3, 3.0)},
                       period=2 * math.pi, samples=100)
    assert two.periodic
    assert not joint_motion(robot, {"LF_femur": Sinusoid(0.3, 2.0)}, period=1.0).periodic
