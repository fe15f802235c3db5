"""Tests of hexaleg.robot.model: the built-in hexapod/sphere model and the loader's error paths."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
import yourdfpy

import hexaleg
from hexaleg.errors import HexalegError, RobotModelError, UnknownNameError
from hexaleg.robot.model import (
    DEFAULT_SRDF,
    DEFAULT_URDF,
    HEXALEG_LEGS,
    LEG_NAMES,
    LegSpec,
    load_robot,
)
from hexaleg.units import kgmm2_to_kgm2, mm_to_m

# Paper Table 6, in the paper's units.
TABLE6 = {"L_mm": 84.000, "l_mm": 47.141, "m_kg": 3.611e-2, "I_kgmm2": 107.059}


def test_model_dimensions(robot):
    assert robot.model.nq == 25
    assert robot.model.nv == 24
    assert robot.nj == 18
    expected = {f"{leg}_{j}" for leg in LEG_NAMES for j in ("coxa", "femur", "tibia")}
    assert set(robot.joint_names) == expected
    for name in robot.joint_names:
        joint = robot.model.joints[robot.model.getJointId(name)]
        assert joint.shortname().startswith("JointModelR"), (name, joint.shortname())
    assert robot.leg_names == LEG_NAMES
    feet = [robot.model.frames[leg.foot_frame_id].name for leg in robot.legs]
    assert feet == [f"{leg}_foot" for leg in LEG_NAMES]


def test_leg_indices_address_the_named_joints(robot):
    for leg in robot.legs:
        for name, jid, iq, iv, col in zip(leg.joint_names, leg.joint_ids, leg.q_index,
                                          leg.v_index, leg.columns, strict=True):
            assert robot.model.names[jid] == name
            assert robot.model.joints[jid].idx_q == iq
            assert robot.model.joints[jid].idx_v == iv
            assert robot.joint_names[col] == name
            assert robot.column(name) == col


def test_femur_inertia_about_axis_is_table6(robot):
    """Table 6: I about the CoM plus m l² (parallel axes) about the joint axis (−y)."""
    inertia = robot.model.inertias[robot.model.getJointId("LF_femur")]
    axis = np.array([0.0, -1.0, 0.0])
    c = inertia.lever
    i_axis = axis @ (inertia.inertia + inertia.mass * (c @ c * np.eye(3) - np.outer(c, c))) @ axis
    m, l_m = TABLE6["m_kg"], mm_to_m(TABLE6["l_mm"])
    expected = kgmm2_to_kgm2(TABLE6["I_kgmm2"]) + m * l_m**2
    assert i_axis == pytest.approx(expected, rel=1e-9)
    # The issue's 187.305 kg·mm² is this sum rounded to Table 6's 3 decimals (187.30531).
    assert i_axis == pytest.approx(kgmm2_to_kgm2(187.305), abs=kgmm2_to_kgm2(5e-4))
    assert inertia.mass == pytest.approx(m, rel=1e-12)
    assert np.allclose(c, [mm_to_m(TABLE6["l_mm"]), 0, 0], atol=1e-15)
    tibia_joint = robot.model.joints[robot.model.getJointId("LF_tibia")]
    assert robot.model.jointPlacements[tibia_joint.id].translation[0] == pytest.approx(
        mm_to_m(TABLE6["L_mm"]), rel=1e-12)


def test_limits_come_from_the_ax18a_datasheet(robot):
    iv = np.array([robot.model.joints[robot.model.getJointId(j)].idx_v for j in robot.joint_names])
    iq = iv + 1
    assert np.allclose(robot.model.effortLimit[iv], 1.8)  # N·m stall torque at 12 V
    assert np.allclose(robot.model.velocityLimit[iv], 97 * 2 * math.pi / 60)  # 97 rpm no-load
    assert np.allclose(robot.model.upperPositionLimit[iq], math.radians(150))
    assert np.allclose(robot.model.lowerPositionLimit[iq], -math.radians(150))


def test_poses(robot):
    assert set(robot.poses) == {"stand", "sphere", "zero"}
    stand = robot.pose("stand")
    assert stand.shape == (25,)
    for leg in robot.legs:
        assert np.allclose(stand[leg.q_index], np.radians([0.0, 20.0, -110.0]))
    stand[7] = 99.0  # pose() returns a copy
    assert robot.pose("stand")[7] == 0.0
    with pytest.raises(UnknownNameError, match="sphere, stand, zero"):
        robot.pose("crouch")


def test_stand_feet_are_level_below_the_hips(robot):
    feet = robot.foot_positions(robot.pose("stand"))
    assert np.allclose(feet[:, 2], feet[0, 2], atol=1e-12)
    # femur 20° up then tibia straight down: 84 sin 20° − 120 mm below the hips.
    assert feet[0, 2] == pytest.approx(0.084 * math.sin(math.radians(20)) - 0.12, abs=1e-12)
    radial = np.hypot(feet[:, 0], feet[:, 1])
    assert np.allclose(radial, 0.08 + 0.03 + 0.084 * math.cos(math.radians(20)), atol=1e-12)


def _urdf_consumer_foot(urdf: yourdfpy.URDF, robot, q: np.ndarray, leg: str) -> np.ndarray:
    cfg = {name: q[robot.model.joints[robot.model.getJointId(name)].idx_q]
           for name in robot.joint_names}
    urdf.update_cfg(cfg)
    return urdf.get_transform(f"{leg}_foot", "body")[:3, 3]


def test_yourdfpy_agrees_with_pinocchio(robot):
    urdf = yourdfpy.URDF.load(str(DEFAULT_URDF), build_scene_graph=True, load_meshes=False)
    assert urdf.validate()
    mass = sum(link.inertial.mass for link in urdf.robot.links if link.inertial is not None)
    assert mass == pytest.approx(robot.mass, rel=1e-12)
    for pose in ("stand", "sphere"):
        q = robot.pose(pose)
        feet = robot.foot_positions(q)
        for k, leg in enumerate(LEG_NAMES):
            assert np.allclose(_urdf_consumer_foot(urdf, robot, q, leg), feet[k], atol=1e-12)


def test_srdf_disables_exactly_adjacent_pairs(robot):
    names = {(robot.model.frames[robot.collision_model.geometryObjects[p.first].parentFrame].name,
              robot.model.frames[robot.collision_model.geometryObjects[p.second].parentFrame].name)
             for p in robot.collision_model.collisionPairs}
    names = {tuple(sorted(n)) for n in names}
    assert tuple(sorted(("body", "LF_coxa_link"))) not in names
    assert tuple(sorted(("LF_femur_link", "LF_tibia_link"))) not in names
    assert tuple(sorted(("body", "LF_femur_link"))) in names
    assert tuple(sorted(("LF_tibia_link", "LM_tibia_link"))) in names


def test_summary_lists_what_the_model_holds(robot):
    text = robot.summary()
    assert "nq = 25, nv = 24" in text
    assert f"{robot.mass:.4f} kg" in text
    assert "LF_femur" in text and "poses: sphere, stand, zero" in text


# --- bad input --------------------------------------------------------------------------------

def test_missing_file(tmp_path):
    with pytest.raises(RobotModelError, match="not found"):
        load_robot(tmp_path / "nope.urdf")


def test_malformed_xml(tmp_path):
    bad = tmp_path / "bad.urdf"
    bad.write_text("<robot name='x'><link name='a'></robot>")
    with pytest.raises(RobotModelError, match="not well-formed"):
        load_robot(bad)
    with pytest.raises(RobotModelError, match="SRDF"):
        load_robot(DEFAULT_URDF, bad)


def test_urdf_without_the_legs_lists_the_joints_found(tmp_path):
    urdf = tmp_path / "one.urdf"
    urdf.write_text("""<robot name="one"><link name="body"/><link name="arm"/>
      <joint name="shoulder" type="revolute"><parent link="body"/><child link="arm"/>
      <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>""")
    with pytest.raises(RobotModelError, match=r"LF_coxa.*joints found: shoulder"):
        load_robot(urdf)
    spec = [LegSpec("A", ("shoulder",), "hand")]
    with pytest.raises(RobotModelError, match=r"foot frame 'hand'.*frames found:.*arm"):
        load_robot(urdf, legs=spec)


def test_joint_classes(robot):
    classes = robot.joint_classes
    assert list(classes) == ["coxa", "femur", "tibia"]
    assert classes["femur"] == tuple(f"{leg}_femur" for leg in LEG_NAMES)
    assert robot.joints("tibia") == classes["tibia"]
    assert robot.joints("RM_coxa") == ("RM_coxa",)
    with pytest.raises(UnknownNameError, match=r"RM_tibia, coxa, femur, tibia$"):
        robot.joints("knee")


def test_custom_leg_spec_loads():
    robot = load_robot(DEFAULT_URDF, DEFAULT_SRDF, legs=HEXALEG_LEGS[:2])
    assert robot.leg_names == ("LF", "LM")


def test_errors_are_hexaleg_errors():
    with pytest.raises(HexalegError):
        load_robot(Path("/nonexistent/robot.urdf"))
    with pytest.raises(UnknownNameError, match="valid legs are: LF, LH, LM, RF, RH, RM"):
        hexaleg.load().leg("XX")
    with pytest.raises(UnknownNameError, match="valid joints are"):
        hexaleg.load().column("LF_knee")


def test_model_gravity_is_standard(robot):
    assert np.allclose(robot.model.gravity.linear, [0, 0, -9.81])
    assert isinstance(robot.model, pin.Model)
