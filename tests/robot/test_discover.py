"""Legs and joint classes found from the kinematic tree."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.errors import RobotModelError
from hexaleg.robot.model import AUTO, load_robot
from hexaleg.robot.registry import description


def test_spider_legs_are_named_along_its_heading(spider):
    """The test hexapod faces +y, so its left legs are on −x; front is +y."""
    assert spider.leg_names == ("LF", "LM", "LH", "RF", "RM", "RH")
    assert spider.joint_kinds == ("coxa", "femur", "tibia")
    feet = spider.foot_positions(spider.pose("stand"))
    for k, leg in enumerate(spider.legs):
        assert (feet[k, 0] < 0) == leg.name.startswith("L")
    assert spider.leg("LF").joint_names == ("a_j1", "a_j2", "a_j3")  # x < 0, y = +0.08
    assert spider.leg("RH").joint_names == ("f_j1", "f_j2", "f_j3")  # x > 0, y = −0.08
    assert np.allclose(spider.heading, [0.0, 1.0, 0.0])


def test_the_builtin_robot_found_is_the_builtin_robot(robot):
    found = load_robot(legs=AUTO)
    assert found.leg_names == robot.leg_names and found.joint_kinds == robot.joint_kinds
    for a, b in zip(found.legs, robot.legs, strict=True):
        assert a.joint_names == b.joint_names


def test_a_quadruped_gets_hip_thigh_knee():
    desc = description("solo12")
    solo = load_robot(desc.urdf_path, None, legs=AUTO, package_dirs=desc.package_dirs)
    assert solo.leg_names == ("LF", "RF", "LH", "RH")
    assert solo.joint_kinds == ("hip", "thigh", "knee")
    assert solo.leg("LF").joint_names == ("FL_HAA", "FL_HFE", "FL_KFE")


def test_a_tree_that_is_not_legs_is_refused(tmp_path):
    urdf = tmp_path / "tree.urdf"
    link = '<link name="{0}"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" ' \
           'izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial></link>'
    joint = '<joint name="{0}" type="revolute"><parent link="{1}"/><child link="{2}"/>' \
            '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
    urdf.write_text("<robot name='t'>" + "".join(link.format(n) for n in "base a b c".split())
                    + joint.format("j1", "base", "a") + joint.format("j2", "a", "b")
                    + joint.format("j3", "a", "c") + "</robot>")
    with pytest.raises(RobotModelError, match=r"joint j1 has children \['j2', 'j3'\]"):
        load_robot(urdf, legs=AUTO)


def test_listed_legs_without_joint_kinds_get_the_documented_classes(tmp_path):
    """docs/robots.md: ``joint1 …`` unless three joints — for legs listed as for legs found
    (issue #55: listed legs got the hexapod's three names and a refusal)."""
    from pathlib import Path

    from hexaleg.robot.description import RobotDescription

    data = Path(__file__).resolve().parents[1] / "data"
    legs = "".join(f'[[robot.legs]]\nname = "{leg}"\njoints = ["{leg}_HAA", "{leg}_HFE", '
                   f'"{leg}_KFE", "{leg}_AFE"]\n' for leg in ("LF", "RF", "LH", "RH"))
    toml = tmp_path / "q.toml"
    toml.write_text(f'[robot]\nname = "q"\nurdf = "{data / "quad4dof.urdf"}"\n'
                    'stand = {body_height = 0.22}\n' + legs)
    robot = RobotDescription.from_toml(toml).load()
    assert robot.joint_kinds == ("joint1", "joint2", "joint3", "joint4")
    humanoid = RobotDescription.from_toml(data / "humanoid.toml").load()
    assert humanoid.joint_kinds == ("hip", "thigh", "knee")


@pytest.mark.parametrize(("urdf", "legs", "others"), [
    ("humanoid.urdf", ("L1", "R1"), ("waist", "L_shoulder", "L_elbow", "R_shoulder", "R_elbow")),
    ("wheeled.urdf", ("LF", "RF", "LH", "RH"), ("arm_yaw", "arm_pitch")),
])
def test_legs_are_found_beside_a_torso_or_an_arm(urdf, legs, others):
    """A torso that branches into arms, an arm on the back: the chains hanging below the body
    are the legs, the rest are joints on no leg (issue #55: both were refused)."""
    from pathlib import Path

    data = Path(__file__).resolve().parents[1] / "data"
    robot = load_robot(data / urdf, legs=AUTO)
    assert robot.leg_names == legs
    assert robot.other_joints == others
    assert any("not legs" in n for n in robot.notes)

