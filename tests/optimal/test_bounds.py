"""The optimal problem's per-knot bounds: the ground under a swing foot is the lower of its two
footholds (across the cycle's displacement), and the knee's bound holds the foot the reach
margin short of full stretch on the side the warm start bends it."""

from __future__ import annotations

import numpy as np
import pytest

import hexaleg
from hexaleg.optimal.bounds import ground_heights, knee_bounds


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


def _hip_to_foot(robot, leg, q):
    """Distance from the joint before the leg's knee to its foot at ``q``, m."""
    import pinocchio as pin

    pin.framesForwardKinematics(robot.model, robot.data, q)
    return float(np.linalg.norm(robot.data.oMf[leg.foot_frame_id].translation
                                - robot.data.oMi[leg.joint_ids[-2]].translation))


@pytest.mark.parametrize("name", ["hexaleg", "solo12"])
def test_the_knee_bound_holds_the_foot_the_margin_short_of_full_stretch(name):
    """At the bound the hip-to-foot distance is the leg's reach less the margin, the reach
    being the largest distance over a sweep of the knee (Solo-12's front and hind knees bend
    opposite ways: each is bounded on its own side). Catches a bound on the wrong side of the
    stretched angle, a margin taken as an angle, or a stretched angle that is not the reach's."""
    run = hexaleg.Scenario.load(name)
    robot, q = run.model, run.motion().q[:1]
    lower, upper = knee_bounds(robot, q, 3e-3)
    for leg in robot.legs:
        i = leg.q_index[-1]
        sweep = np.linspace(-np.pi, np.pi, 20001)
        reach = max(_hip_to_foot(robot, leg, np.concatenate([q[0, :i], [t], q[0, i + 1:]]))
                    for t in sweep)
        bent_up = lower[0, i] > robot.model.lowerPositionLimit[i]
        bound = lower[0, i] if bent_up else upper[0, i]
        assert (q[0, i] >= bound) if bent_up else (q[0, i] <= bound)  # the warm start's side
        at = q[0].copy()
        at[i] = bound
        assert _hip_to_foot(robot, leg, at) == pytest.approx(reach - 3e-3, abs=1e-6)
        assert lower[0, i] == robot.model.lowerPositionLimit[i] or \
            upper[0, i] == robot.model.upperPositionLimit[i]  # one side bounded
