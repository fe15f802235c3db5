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


def test_a_sole_is_four_contact_spheres_at_its_corners():
    """biped6's soles: a sphere and a site at each corner, where Pinocchio puts the foot frame
    plus its rotation times the corner, at the stand and at a bent pose; no sphere at the
    centre (the site there stays: foot positions are read at it). The point-foot biped has no
    corners."""
    from pathlib import Path

    from hexaleg.robot.description import read_description
    from hexaleg.simulation.mjcf import contact_geoms, contact_sites, corner_geom, corner_site
    from hexaleg.simulation.state import JointMap

    data_dir = Path(__file__).parents[1] / "data"
    robot = read_description(data_dir / "biped6.toml").load()
    tree = tree_xml(robot, 1e-4)
    m = mujoco.MjModel.from_xml_string(
        '<mujoco><default><default class="robot"/><default class="foot"/></default>'
        f"<worldbody>{tree.xml}</worldbody></mujoco>")
    joints = JointMap.build(robot, m)
    data, pdata = mujoco.MjData(m), robot.model.createData()
    assert mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, foot_geom("L1")) == -1
    bent = robot.pose("stand").copy()
    bent[7:] += np.linspace(-0.3, 0.3, robot.nj)
    for q in (robot.pose("stand"), bent):
        data.qpos[:] = joints.to_mujoco(q, np.zeros(robot.model.nv))[0]
        mujoco.mj_kinematics(m, data)
        pin.framesForwardKinematics(robot.model, pdata, q)
        for leg in robot.legs:
            frame = pdata.oMf[leg.foot_frame_id]
            at = frame.translation + robot.soles[leg.name].corners() @ frame.rotation.T
            for j in range(4):
                np.testing.assert_allclose(data.geom(corner_geom(leg.name, j)).xpos, at[j],
                                           atol=1e-12)
                np.testing.assert_allclose(data.site(corner_site(leg.name, j)).xpos, at[j],
                                           atol=1e-12)
    assert contact_sites(robot) == [corner_site(leg, j) for leg in ("L1", "R1")
                                    for j in range(4)]
    biped = read_description(data_dir / "biped.toml").load()
    assert contact_geoms(biped) == [[foot_geom("L1")], [foot_geom("R1")]]
    assert "_sole" not in tree_xml(biped, 1e-4).xml
