"""The optimal problem's per-knot bounds: the ground under a swing foot is the lower of its two
footholds (across the cycle's displacement), and the knee's bound holds the foot the reach
margin short of full stretch on the side the warm start bends it, the knee being the last
joint that can stretch the leg."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import hexaleg
from hexaleg.optimal.bounds import ground_heights, knee_bounds
from hexaleg.robot.description import read_description


def test_the_ground_under_a_swing_foot_is_the_lower_of_its_two_footholds():
    """One leg, six knots: down at 0–1 and 5, in swing at 2–4; the cycle climbs 30 mm (a
    slope's stride), so the foothold it lands on at knot 5 … and the one of the next cycle's
    knot 0 are 30 mm higher than this cycle's."""
    stance = np.array([[True], [True], [False], [False], [False], [True]])
    footholds = np.zeros((6, 1, 3))
    footholds[[0, 1], 0] = [0.0, 0.0, 0.10]
    footholds[5, 0] = [0.2, 0.0, 0.12]
    displacement = np.eye(4)
    displacement[:3, 3] = [0.3, 0.0, 0.03]
    ground = ground_heights(stance, footholds, displacement)
    np.testing.assert_allclose(ground[2:5, 0], 0.10)
    assert np.isnan(ground[[0, 1, 5], 0]).all()
    # the swing that runs past the cycle's end lands on the next cycle's foothold
    stance = np.array([[True], [True], [True], [True], [False], [False]])
    footholds[:4, 0] = [0.0, 0.0, 0.10]
    ground = ground_heights(stance, footholds, displacement)
    np.testing.assert_allclose(ground[4:, 0], 0.10)  # min(0.10, 0.13)
    displacement[2, 3] = -0.03  # downhill: the next cycle's foothold is the lower
    np.testing.assert_allclose(ground_heights(stance, footholds, displacement)[4:, 0], 0.07)


BIPED = Path(__file__).resolve().parents[1] / "data" / "biped6.toml"
"""A test biped whose legs end in an ankle: hip yaw, roll, pitch, knee, ankle pitch and roll
(the two ankle axes through one point, its sole 6 cm below it)."""


def _warm_start(name):
    """The robot and one warm-start configuration (1, nq): the registered robots' gait's first
    sample; the biped's stand pose (its knees bent as in its gait, which takes seconds to make)."""
    if name == "biped6":
        robot = read_description(BIPED).load()
        return robot, robot.poses["stand"][None]
    run = hexaleg.Scenario.load(name)
    return run.model, run.motion().q[:1]


def _hip_to_end(robot, leg, b, q):
    """Distance from the joint before the leg's joint ``b`` (its knee) to the leg's end past it
    (the next joint's origin; the foot past the last joint) at ``q``, m."""
    import pinocchio as pin

    pin.framesForwardKinematics(robot.model, robot.data, q)
    end = robot.data.oMf[leg.foot_frame_id] if b == len(leg.joint_ids) - 1 else \
        robot.data.oMi[leg.joint_ids[b + 1]]
    return float(np.linalg.norm(end.translation - robot.data.oMi[leg.joint_ids[b - 1]].translation))


@pytest.mark.parametrize(("name", "knee"), [("hexaleg", 2), ("solo12", 2), ("biped6", 3)])
def test_the_knee_bound_holds_the_leg_s_end_the_margin_short_of_full_stretch(name, knee):
    """At the bound the hip-to-end distance is the leg's reach less the margin, the reach
    being the largest distance over a sweep of the knee (Solo-12's front and hind knees bend
    opposite ways: each is bounded on its own side), and no joint but the knee is bounded. A
    leg that ends in its knee holds its foot; the biped's, which end in an ankle whose pitch and
    roll axes pass through one point, hold that point, their knee the fourth joint. Catches a
    bound on the wrong side of the stretched angle, a margin taken as an angle, a stretched
    angle that is not the reach's, and the knee taken as the last joint (the biped's ankle
    roll, whose hip, the ankle pitch's origin, lies on its axis: no bound at all)."""
    robot, q = _warm_start(name)
    lower, upper = knee_bounds(robot, q, 3e-3)
    limits = robot.model.lowerPositionLimit, robot.model.upperPositionLimit
    for leg in robot.legs:
        i = leg.q_index[knee]
        sweep = np.linspace(-np.pi, np.pi, 20001)
        reach = max(_hip_to_end(robot, leg, knee,
                                np.concatenate([q[0, :i], [t], q[0, i + 1:]])) for t in sweep)
        bent_up = lower[0, i] > limits[0][i]
        bound = lower[0, i] if bent_up else upper[0, i]
        assert (q[0, i] >= bound) if bent_up else (q[0, i] <= bound)  # the warm start's side
        at = q[0].copy()
        at[i] = bound
        assert _hip_to_end(robot, leg, knee, at) == pytest.approx(reach - 3e-3, abs=1e-6)
        assert lower[0, i] == limits[0][i] or upper[0, i] == limits[1][i]  # one side bounded
        others = [int(j) for j in leg.q_index if j != i]
        assert (lower[0, others] == limits[0][others]).all()  # the knee alone
        assert (upper[0, others] == limits[1][others]).all()
