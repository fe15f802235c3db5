"""Tests of hexaleg.robot.srdf: a stand pose with a misspelt joint or a value that is not a finite
number is refused by name (Pinocchio would load it with that joint at 0), and every registered
robot's SRDF passes."""

from __future__ import annotations

import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError, RobotModelError, UnknownNameError
from hexaleg.robot.model import DEFAULT_SRDF, DEFAULT_URDF, load_robot
from hexaleg.robot.registry import DESCRIPTIONS
from hexaleg.robot.srdf import check_reference_poses


def edited_srdf(tmp_path, old, new):
    text = DEFAULT_SRDF.read_text(encoding="utf-8")
    assert old in text
    path = tmp_path / "edited.srdf"
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    return path


def test_a_misspelt_joint_in_a_pose_is_refused_with_the_joints(tmp_path):
    srdf = edited_srdf(tmp_path, '<joint name="LF_femur"', '<joint name="LF_femr"')
    with pytest.raises(UnknownNameError, match=r"unknown joint in SRDF .*edited\.srdf pose "
                                               r"'\w+' 'LF_femr' \(did you mean 'LF_femur'\?\); "
                                               r".*LF_femur"):
        load_robot(DEFAULT_URDF, srdf)


@pytest.mark.parametrize("value", ["nan", "inf", "-inf", "abc", "", "0.1 0.2"])
def test_a_value_that_is_not_one_finite_number_is_refused(tmp_path, value):
    text = DEFAULT_SRDF.read_text(encoding="utf-8")
    start = text.index('<joint name="LF_femur" value="') + len('<joint name="LF_femur" value="')
    old = text[start - len('<joint name="LF_femur" value="'):text.index('"', start) + 1]
    srdf = edited_srdf(tmp_path, old, f'<joint name="LF_femur" value="{value}"')
    with pytest.raises(InvalidParameterError, match=rf"joint LF_femur value = '{value}'; "
                                                    r"allowed: 1 finite number"):
        load_robot(DEFAULT_URDF, srdf)


def test_malformed_xml_is_a_robot_model_error(tmp_path):
    bad = tmp_path / "bad.srdf"
    bad.write_text("<robot><group_state", encoding="utf-8")
    robot = hexaleg.load()
    with pytest.raises(RobotModelError, match=r"bad\.srdf cannot be read as XML"):
        check_reference_poses(robot.model, bad)


@pytest.mark.parametrize("name", sorted(DESCRIPTIONS))
def test_every_registered_robot_passes(name):
    desc = DESCRIPTIONS[name]
    if desc.srdf_path is None:
        pytest.skip(f"{name} has no SRDF")
    check_reference_poses(desc.load().model, desc.srdf_path)
