"""The robot's tree as MJCF: one body per joint, the joints' axes, foot spheres and sites at the
foot frames, the foot links' own geometry left out."""

from __future__ import annotations

import mujoco
import numpy as np
import pinocchio as pin
import pytest

from hexaleg.errors import RobotModelError
from hexaleg.simulation.mjcf import fmt, foot_geom, motion_axis, tree_xml, wxyz
from hexaleg.simulation.model import build_model


@pytest.fixture(scope="module")
def sim(prepared):
    return build_model(prepared.robot, prepared.motion, prepared.motor)


def test_one_body_per_joint_and_their_axes(sim, robot):
    m = sim.model
    assert m.nbody == robot.model.njoints  # the world and one body per Pinocchio joint
    for name in ("LF_coxa", "LF_femur", "RH_tibia"):
        kind, axis = motion_axis(robot, robot.model.getJointId(name))
        assert kind == "hinge"
        assert np.allclose(m.joint(name).axis, axis)
    assert np.allclose(motion_axis(robot, robot.model.getJointId("LF_femur"))[1], [0, -1, 0])
    with pytest.raises(RobotModelError, match="degrees of freedom"):
        motion_axis(robot, 1)  # the free flyer


def test_feet_are_spheres_at_the_foot_frames(sim, robot, walk):
    """The foot sites and spheres sit at Pinocchio's foot frames; the foot links' own collision
    spheres are not built."""
    m = sim.model
    data = mujoco.MjData(m)
    for k in (0, 250, 700):
        data.qpos[:], data.qvel[:] = sim.joints.to_mujoco(walk.q[k], walk.v[k])
        mujoco.mj_kinematics(m, data)
        feet = robot.foot_positions(walk.q[k])
        assert np.allclose([data.site(f"{leg}_foot").xpos for leg in robot.leg_names], feet,
                           atol=1e-12)
        assert np.allclose([data.geom(foot_geom(leg)).xpos for leg in robot.leg_names], feet,
                           atol=1e-12)
    tree = tree_xml(robot, 1e-4)
    assert not any(g.startswith(tuple(f"{leg}_foot_" for leg in robot.leg_names)) for g in
                   tree.geoms)
    assert len(tree.geoms) == robot.collision_model.ngeoms - len(robot.legs)


def test_numbers_keep_full_precision():
    assert fmt([0.1, 1 / 3]) == "0.1 0.3333333333333333"
    rot = pin.utils.rpyToMatrix(0.1, -0.2, 0.3)
    w, x, y, z = map(float, wxyz(rot).split())
    assert np.allclose(pin.Quaternion(w, x, y, z).toRotationMatrix(), rot, atol=1e-15)
