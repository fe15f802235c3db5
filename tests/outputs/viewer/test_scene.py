"""Tests of hexaleg.outputs.viewer.scene: the scene sent to Meshcat.

The commands are recorded as the viewer sends them, decoded, and checked against Pinocchio's
kinematics (that the offline page embeds exactly these commands is a test of the page).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
from meshcat_scene import ARROW, DISTANCE, PERIOD, T, at, clips, draw

from hexaleg.dynamics.prepare import analyze
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.trajectory import Motion
from hexaleg.motion.transform import transform_motion
from hexaleg.outputs.viewer.colours import N_LEVELS, value_bins


def test_visual_geometry_follows_the_motion(robot, motion, scene_clips):
    """Keyframe k of every visual's position/quaternion track is its placement at sample k
    (fps = sample rate), and the closing keyframe returns to sample 0 shifted by the stride."""
    data, gdata = robot.model.createData(), pin.GeometryData(robot.visual_model)
    for k in (0, 7, T - 1):
        pin.forwardKinematics(robot.model, data, motion.q[k])
        pin.updateGeometryPlacements(robot.model, data, robot.visual_model, gdata)
        for g, obj in enumerate(robot.visual_model.geometryObjects):
            tr = scene_clips[f"/meshcat/pinocchio/visuals/{obj.name}"]
            assert tr["position"]["frames"][k] == pytest.approx(k)
            np.testing.assert_allclose(tr["position"]["values"][k], gdata.oMg[g].translation,
                                       atol=1e-12)
            quat = pin.Quaternion(np.array(tr["quaternion"]["values"][k]))
            np.testing.assert_allclose(quat.toRotationMatrix(), gdata.oMg[g].rotation,
                                       atol=1e-12)
    body = scene_clips["/meshcat/pinocchio/visuals/body_0"]["position"]
    assert len(body["frames"]) == T + 1 and body["frames"][-1] == pytest.approx(T)
    np.testing.assert_allclose(np.subtract(body["values"][-1], body["values"][0]),
                               [DISTANCE, 0, 0], atol=1e-12)


def test_force_arrows_point_along_the_forces(robot, motion, forces, scene_clips):
    mags = np.linalg.norm(forces, axis=-1)
    fmax = mags.max()
    for i, leg in enumerate(robot.legs):
        node = f"/meshcat/forces/{leg.name}"
        tr = scene_clips[node]
        head = scene_clips[node + "/head"]["position"]["values"]
        for k in (0, T // 2 + 3):
            visible = at(tr["visible"], k)
            assert visible == bool(motion.stance[k, i])
            if not visible:
                continue
            np.testing.assert_allclose(tr["position"]["values"][k],
                                       robot.foot_positions(motion.q[k])[i], atol=1e-12)
            R = pin.Quaternion(np.array(tr["quaternion"]["values"][k])).toRotationMatrix()
            # The arrow's axis is its local +y (three.js convention).
            np.testing.assert_allclose(R[:, 1], forces[k, i] / mags[k, i], atol=1e-12)
            length = ARROW * mags[k, i] / fmax
            shaft = scene_clips[node + "/shaft"]
            assert shaft["scale"]["values"][k][1] == pytest.approx(length)
            assert shaft["position"]["values"][k][1] == pytest.approx(length / 2)
            assert head[k][1] > length


def test_joint_markers_show_one_binned_colour(robot, motion, scene_clips):
    values = motion.v[:, 6:]
    bins = value_bins(values, np.abs(values).max())
    data = robot.model.createData()
    for k in (0, 13, T - 1):
        pin.forwardKinematics(robot.model, data, motion.q[k])
        for c, name in enumerate(robot.joint_names):
            node = f"/meshcat/joint_values/{name}"
            np.testing.assert_allclose(scene_clips[node]["position"]["values"][k],
                                       data.oMi[robot.model.getJointId(name)].translation,
                                       atol=1e-12)
            shown = [b for b in range(N_LEVELS)
                     if at(scene_clips[f"{node}/bin{b}"]["visible"], k)]
            assert shown == [bins[k, c]]


def test_real_gait_arrows_are_the_analysis_forces(robot, walk):
    """Tripod gait with the analysis' foot forces (30 keyframes/s between 1000 samples/s): each
    arrow, read back as direction × length / arrow_length × max|f|, is the force linearly
    interpolated at the keyframe time, and the stance feet carry the weight (Σ f_z ≈ m g, up
    to the CoM's vertical acceleration)."""
    result = analyze(robot, walk)
    tracks = clips(draw(robot, walk, forces=result.forces, joint_values=result.power,
                        joint_label="motor power (W)"))
    fmax = np.linalg.norm(result.forces, axis=-1).max()
    frames = tracks["/meshcat/forces/LF/shaft"]["scale"]["frames"]
    assert frames[-1] == pytest.approx(30 * walk.period)
    t_ext = np.append(walk.t, walk.period)
    for j in (0, 9, 21):
        t = frames[j] / 30.0
        total = np.zeros(3)
        for i, leg in enumerate(robot.legs):
            node = f"/meshcat/forces/{leg.name}"
            expected = [np.interp(t, t_ext, np.append(result.forces[:, i, c],
                                                      result.forces[0, i, c]))
                        for c in range(3)]
            if not at(tracks[node]["visible"], j):
                assert np.linalg.norm(expected) < 1e-6 * fmax
                continue
            R = pin.Quaternion(np.array(tracks[node]["quaternion"]["values"][j]))
            length = tracks[node + "/shaft"]["scale"]["values"][j][1]
            drawn = R.toRotationMatrix()[:, 1] * length / ARROW * fmax
            np.testing.assert_allclose(drawn, expected, atol=1e-9 * fmax)
            total += drawn
        assert total[2] == pytest.approx(robot.mass * 9.81, rel=0.1)


def test_transformation_ends_in_the_sphere_pose(robot):
    """A non-periodic motion (stand → sphere, 2 s) has keyframes up to its last sample, where
    the body shells sit as in the SRDF ``sphere`` pose (the body resting on the ground)."""
    motion = transform_motion(robot)
    tracks = clips(draw(robot, motion, fps=10))
    q_end = robot.pose("sphere")
    q_end[:3] = motion.q[-1, :3]
    data, gdata = robot.model.createData(), pin.GeometryData(robot.visual_model)
    pin.forwardKinematics(robot.model, data, q_end)
    pin.updateGeometryPlacements(robot.model, data, robot.visual_model, gdata)
    for g, obj in enumerate(robot.visual_model.geometryObjects):
        tr = tracks[f"/meshcat/pinocchio/visuals/{obj.name}"]["position"]
        assert len(tr["frames"]) == 21 and tr["frames"][-1] == pytest.approx(20)
        np.testing.assert_allclose(tr["values"][-1], gdata.oMg[g].translation, atol=1e-9)


def test_single_pose_is_drawn_without_animation(robot):
    """One sample: no animation, the scene is set to the pose (scale 1 from the URDF)."""
    q = robot.pose("stand")
    motion = Motion(t=np.zeros(1), q=q[None], v=np.zeros((1, robot.model.nv)),
                    a=np.zeros((1, robot.model.nv)), stance=np.ones((1, 6), dtype=bool),
                    feet=robot.foot_positions(q)[None], period=1.0, periodic=False)
    commands = draw(robot, motion)
    assert not [c for c in commands if c["type"] == "set_animation"]
    last = {c["path"]: c["matrix"] for c in commands if c["type"] == "set_transform"}
    M = np.array(last["/meshcat/pinocchio/visuals/LF_foot_0"]).reshape(4, 4).T
    data, gdata = robot.model.createData(), pin.GeometryData(robot.visual_model)
    pin.forwardKinematics(robot.model, data, q)
    pin.updateGeometryPlacements(robot.model, data, robot.visual_model, gdata)
    np.testing.assert_allclose(M, gdata.oMg[robot.visual_model.getGeometryId("LF_foot_0")]
                               .homogeneous, atol=1e-12)


def test_wrong_shapes_name_the_expected_shape(robot, motion):
    with pytest.raises(InvalidParameterError, match=r"\(40, 6, 3\)"):
        draw(robot, motion, forces=np.zeros((T, 6)))
    with pytest.raises(InvalidParameterError, match=r"\(40, 18\)"):
        draw(robot, motion, joint_values=np.zeros((T - 1, 18)))
    bad = np.zeros((T, 18))
    bad[5, 3] = np.nan
    with pytest.raises(InvalidParameterError, match="sample 5"):
        draw(robot, motion, joint_values=bad)
    other = Motion(t=motion.t, q=motion.q[:, :-3], v=motion.v[:, :-3], a=motion.a[:, :-3],
                   stance=motion.stance, feet=motion.feet, period=PERIOD)
    with pytest.raises(InvalidParameterError, match=r"q \(T, 25\) and v \(T, 24\)"):
        draw(robot, other)
