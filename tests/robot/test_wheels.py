"""Tests of hexaleg.robot.wheels: a wheel at a foot is locked and walks as a round foot; a joint
that is not one angle elsewhere is refused by name (issue #55)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.errors import RobotModelError
from hexaleg.robot.description import RobotDescription

DATA = Path(__file__).resolve().parents[1] / "data"
WHEELED = DATA / "wheeled.urdf"


@pytest.fixture(scope="module")
def wheeled() -> hexaleg.Robot:
    return hexaleg.load(str(DATA / "wheeled.toml"))


def test_wheels_are_locked_and_their_mass_kept(wheeled):
    raw = pin.buildModelFromUrdf(str(WHEELED), pin.JointModelFreeFlyer())
    assert raw.nq == 7 + 14 + 4 * 2 and raw.nv == 6 + 14 + 4  # 4 wheels of (cos, sin)
    assert wheeled.model.nq == 7 + 14 and wheeled.nj == 14
    assert not any("wheel" in j for j in wheeled.joint_names)
    assert wheeled.mass == pytest.approx(pin.computeTotalMass(raw), rel=1e-12)
    assert any("4 wheel(s) locked" in n for n in wheeled.notes)


def test_a_wheeled_leg_stands_on_its_wheel(wheeled):
    """The foot is the wheel's lowest point in the stand: the wheel's centre (the URDF wheel
    joint's origin, 2 cm out from the shank's tip) one radius (3 cm) above it."""
    q = wheeled.pose("stand")
    feet = wheeled.foot_positions(q)
    np.testing.assert_allclose(feet[:, 2], -0.19, atol=1e-9)
    data = wheeled.model.createData()
    pin.framesForwardKinematics(wheeled.model, data, q)
    for k, leg in enumerate(wheeled.legs):
        sphere = wheeled.foot_spheres[leg.name]
        assert sphere.radius == pytest.approx(0.03)
        centre = data.oMi[leg.joint_ids[-1]].act(sphere.centre)
        np.testing.assert_allclose(centre - feet[k], [0, 0, 0.03], atol=1e-9)
        side = 1.0 if leg.name[0] == "L" else -1.0
        np.testing.assert_allclose(sphere.centre, [0, 0.02 * side, -0.13], atol=1e-12)


def test_a_wheel_listed_in_a_leg_is_the_legs_and_its_kinematics_name_it(tmp_path):
    """A joint the description puts in a leg is never locked; a leg's inverse kinematics
    refuses a continuous joint by name."""
    from hexaleg.motion.leg_chain import leg_chain

    toml = tmp_path / "w.toml"
    toml.write_text(f'[robot]\nname = "w"\nurdf = "{WHEELED}"\n'
                    '[[robot.legs]]\nname = "LF"\njoints = ["LF_HAA", "LF_HFE", "LF_KFE", '
                    '"LF_wheel"]\n')
    robot = RobotDescription.from_toml(toml).load()
    assert "LF_wheel" in robot.joint_names and "RF_wheel" not in robot.joint_names
    with pytest.raises(RobotModelError, match=r"LF_wheel is a JointModelRUBY .*continuous"):
        leg_chain(robot, robot.legs[0], robot.pose("stand"))


def test_a_continuous_joint_above_other_joints_is_refused_by_name(tmp_path):
    text = WHEELED.read_text().replace(
        '<joint name="arm_yaw" type="revolute"', '<joint name="arm_yaw" type="continuous"')
    urdf = tmp_path / "spin.urdf"
    urdf.write_text(text)
    with pytest.raises(RobotModelError, match=r"joint arm_yaw is a JointModelRUBZ .* below it"):
        hexaleg.robot.model.load_robot(urdf, legs="auto")


def test_a_wheel_written_as_a_revolute_joint_without_a_range_is_locked_too(tmp_path):
    """Centauro's ``j_wheel_*`` are revolute joints with no lower or upper limit ("actually
    continuous"): a leaf joint of range [0, 0] is a wheel; an SRDF state may name it."""
    urdf = tmp_path / "r.urdf"
    urdf.write_text(WHEELED.read_text().replace('type="continuous"', 'type="revolute"'))
    srdf = tmp_path / "r.srdf"
    srdf.write_text('<robot name="r"><group_state name="standing" group="all">'
                    '<joint name="LF_wheel" value="0"/><joint name="LF_KFE" value="-1.2"/>'
                    '</group_state></robot>')
    legs = [hexaleg.robot.model.LegSpec(leg, (f"{leg}_HAA", f"{leg}_HFE", f"{leg}_KFE"))
            for leg in ("LF", "RF", "LH", "RH")]
    robot = hexaleg.robot.model.load_robot(urdf, srdf, legs=legs, joint_kinds=("a", "b", "c"))
    assert robot.nj == 14 and set(robot.foot_spheres) == {"LF", "RF", "LH", "RH"}
    assert robot.pose("standing")[7 + robot.column("LF_KFE")] == -1.2
    bounded = tmp_path / "b.urdf"  # a leaf joint with a range is an ordinary joint
    bounded.write_text(WHEELED.read_text().replace(
        '<limit effort="1" velocity="30"/>', '<limit lower="-1" upper="1" effort="1" '
        'velocity="30"/>').replace('type="continuous"', 'type="revolute"'))
    assert hexaleg.robot.model.load_robot(bounded, legs=legs,
                                          joint_kinds=("a", "b", "c")).nj == 18


def test_a_range_less_knee_whose_shank_hangs_off_its_axis_is_no_wheel(tmp_path):
    """Data we did not make: example-robot-data's ``quadruped_description`` gives its knees no
    lower/upper (read as [0, 0]) at leaves of the tree, their shanks' centres of mass 0.103 m
    off the knee's axis. They stay joints (two a leg; its round feet of 2.5 cm), not wheels
    of radius 0.185 m, and the
    stand says the knee cannot bend; Centauro's balanced ``j_wheel_*`` are still wheels."""
    from hexaleg.robot.sources import example_robot_data_dir

    toml = tmp_path / "quadruped.toml"
    toml.write_text('[robot]\nname = "quadruped"\nsource = "example-robot-data"\n'
                    'urdf = "quadruped_description/urdf/quadruped.urdf"\n'
                    'stand = {body_height = 0.25}\n')
    description = RobotDescription.from_toml(toml)
    with pytest.raises(hexaleg.errors.InvalidParameterError,
                       match=r"KFE has no range \(lower = upper: a URDF <limit> without lower and "
                             r"upper reads as 0\), so no body_height bends this leg"):
        description.load()
    robot = hexaleg.robot.model.load_robot(
        example_robot_data_dir() / "quadruped_description" / "urdf" / "quadruped.urdf",
        legs="auto")
    assert robot.nj == 8 and {f.radius for f in robot.foot_spheres.values()} == {0.025}
    knee = robot.model.getJointId("FL_KFE")  # its shank's centre of mass, off the x axis
    lever = robot.model.inertias[knee].lever
    assert np.hypot(lever[1], lever[2]) == pytest.approx(0.1028, abs=1e-4)  # docs/robots.md
    assert not any("wheel" in n for n in robot.notes)
    centauro = hexaleg.load(str(DATA / "centauro.toml"))
    assert any("4 wheel(s) locked" in n and "j_wheel_1" in n for n in centauro.notes)
