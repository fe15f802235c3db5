"""Tests of hexaleg.outputs.viewer.keyframes: the motion resampled at keyframe times."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
from meshcat_scene import PERIOD, T, clips, draw

from hexaleg.outputs.viewer.keyframes import resample


def test_resampling_interpolates_between_samples(robot, motion):
    """At twice the sample rate, odd keyframes are midway (on SE(3) × joint angles) between
    neighbouring samples: the foot sphere sits where it is at pin.interpolate's midpoint."""
    foot = clips(draw(robot, motion, fps=2 * T / PERIOD))[
        "/meshcat/pinocchio/visuals/LF_foot_0"]["position"]
    assert len(foot["frames"]) == 2 * T + 1
    g = robot.visual_model.getGeometryId("LF_foot_0")
    data, gdata = robot.model.createData(), pin.GeometryData(robot.visual_model)
    for k in (0, 11, T - 2):
        q_mid = pin.interpolate(robot.model, motion.q[k], motion.q[k + 1], 0.5)
        pin.forwardKinematics(robot.model, data, q_mid)
        pin.updateGeometryPlacements(robot.model, data, robot.visual_model, gdata)
        np.testing.assert_allclose(foot["values"][2 * k + 1], gdata.oMg[g].translation,
                                   atol=1e-12)
        # ... which is not the average of the neighbouring keyframes' positions (the legs
        # rotate), so this checks interpolation in configuration space.
        assert np.linalg.norm(np.add(foot["values"][2 * k], foot["values"][2 * k + 2]) / 2
                              - gdata.oMg[g].translation) > 1e-5


def test_periodic_motion_closes_on_sample_zero(robot, motion, forces):
    """The keyframe at t = period carries sample 0's per-sample arrays; the base has moved one
    stride."""
    fr = resample(robot, motion, T / PERIOD, forces, motion.v[:, 6:])
    assert len(fr.frames) == T + 1 and fr.frames[-1] == pytest.approx(T)
    np.testing.assert_array_equal(fr.forces[-1], forces[0])
    np.testing.assert_array_equal(fr.joint_values[-1], motion.v[0, 6:])
    np.testing.assert_allclose(fr.q[-1, :3] - fr.q[0, :3], [motion.distance, 0, 0], atol=1e-12)


def test_keyframes_are_bounded_by_memory(robot, walk):
    from hexaleg.errors import InvalidParameterError
    from hexaleg.outputs.viewer.keyframes import MAX_FPS

    with pytest.raises(InvalidParameterError, match=r"keyframes \(fps × motion duration\) = "
                                                    r"\d+; .*lower fps"):
        resample(robot, walk, 2 * MAX_FPS, None, None)
