"""Tests of hexaleg.design.rules: the paper's spring rules carried over to the robot's joints."""

from __future__ import annotations

import math

import numpy as np
import pytest

import hexaleg
from hexaleg.design.rules import (
    PAPER_DEAD_ZONE_RATIO,
    centred_spring,
    centred_springs,
    k_M,
    paper_style_springs,
)
from hexaleg.dynamics.inertia import apparent_inertia, joint_range
from hexaleg.dynamics.prepare import analyze
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.motion.joint_motion import joint_motion
from hexaleg.motion.profiles import Sinusoid


@pytest.fixture(scope="module")
def gait(robot):
    return hexaleg.gait(robot, hexaleg.GaitParams(samples=200))


def test_paper_ratio():
    assert PAPER_DEAD_ZONE_RATIO == pytest.approx(math.radians(7.32) / 0.3)
    assert PAPER_DEAD_ZONE_RATIO == pytest.approx(0.4259, abs=1e-4)


def test_eq25_on_the_robot_gives_the_papers_dead_zone(robot):
    """f = 0.3 sin 2t (eq. 25) about the stand angle: θ_k = 7.32°, neutral = the stand angle."""
    stand = robot.pose("stand")[robot.leg("LF").q_index[1]]
    motion = joint_motion(robot, {"LF_femur": Sinusoid(0.3, 2.0, offset=stand)}, samples=400)
    spring = centred_spring(robot, motion, "LF_femur", 1.0)
    assert spring.neutral == pytest.approx(stand, abs=1e-5)
    assert spring.th_plus == pytest.approx(math.radians(7.32), rel=1e-4)
    assert spring.th_minus == pytest.approx(-math.radians(7.32), rel=1e-4)


def test_k_M_is_eq19(robot, gait):
    j = apparent_inertia(robot, gait, "LF_femur")
    assert k_M(robot, gait, "LF_femur") == pytest.approx((2 * math.pi) ** 2 * j / 1.05)
    with pytest.raises(InvalidParameterError, match="alpha"):
        k_M(robot, gait, "LF_femur", alpha=0.0)


def test_centred_springs_sit_on_each_joints_motion(robot, gait):
    springs = centred_springs(robot, gait, "femur", 2.0, dead_zone=0.5)
    assert set(springs) == set(robot.joint_classes["femur"])
    for joint, spring in springs.items():
        lo, hi = joint_range(robot, gait, joint)
        assert spring.neutral == pytest.approx((lo + hi) / 2)
        assert spring.th_plus == pytest.approx(0.25 * (hi - lo))
        q = gait.q[:, 7 + robot.column(joint)]
        engaged = spring.engaged(q)
        assert engaged.any() and not engaged.all()


def test_paper_style_springs_use_eq14_and_alpha(robot, gait):
    springs = paper_style_springs(robot, gait)
    s = springs["RM_femur"]
    assert (s.alpha, s.convention) == (1.05, "eq14")
    assert s.stiffness == pytest.approx(k_M(robot, gait, "RM_femur"))
    assert np.isfinite(analyze(robot, gait, springs).metrics["total"]["joule"])


def test_bad_input(robot, gait):
    for bad in (0.0, 1.0):
        with pytest.raises(InvalidParameterError, match=r"dead_zone.*\(0, 1\)"):
            centred_spring(robot, gait, "LF_femur", 1.0, dead_zone=bad)
    with pytest.raises(UnknownNameError):
        centred_springs(robot, gait, "knee", 1.0)


def test_a_centred_spring_on_a_joint_that_does_not_move_is_refused(robot):
    still = hexaleg.gait(robot, hexaleg.GaitParams(stride_length=0.0, samples=40))
    lo, hi = joint_range(robot, still, "LF_coxa")
    assert hi - lo < 1e-9  # no stride: the coxa stands still
    with pytest.raises(InvalidParameterError, match=r"centred spring on LF_coxa = 'a joint that "
                                                    r"does not move.*spring another joint"):
        centred_springs(robot, still, "coxa", 1.0)
