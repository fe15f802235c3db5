"""Tests of hexaleg.robot.srdf: a stand pose with a misspelt joint or a value that is not a finite
number is refused by name (Pinocchio would load it with that joint at 0), and every registered
robot's SRDF passes."""

from __future__ import annotations

import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError, RobotModelError, UnknownNameError
from hexaleg.robot.description import read_description
from hexaleg.robot.model import DEFAULT_SRDF, DEFAULT_URDF, load_robot
from hexaleg.robot.registry import DESCRIPTIONS
from hexaleg.robot.sources import example_robot_data_dir
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


def solo8(tmp_path, srdf=None):
    """Solo-8 of example-robot-data described as a newcomer would (``solo.srdf``'s stand), or
    with another SRDF file."""
    robots = example_robot_data_dir() / "solo_description"
    toml = tmp_path / "solo8.toml"
    toml.write_text(f'[robot]\nname = "solo8"\nsource = "files"\n'
                    f'urdf = "{robots / "robots" / "solo.urdf"}"\n'
                    f'srdf = "{srdf or robots / "srdf" / "solo.srdf"}"\nstand = "standing"\n',
                    encoding="utf-8")
    return read_description(toml)


@pytest.mark.parametrize("name", sorted(DESCRIPTIONS))
def test_every_registered_robot_passes(name):
    desc = DESCRIPTIONS[name]
    if desc.srdf_path is None:
        pytest.skip(f"{name} has no SRDF")
    check_reference_poses(desc.load().model, desc.srdf_path)


def test_solo8_reads_the_srdf_it_shares_with_solo12_and_names_what_it_skips(tmp_path):
    """Data we did not make: example-robot-data's one ``solo.srdf`` for Solo-8 (``solo.urdf``,
    two joints a leg) and Solo-12, whose poses name the hip abduction joints Solo-8 lacks. Solo-8
    loads with its stand as the SRDF gives it (the skipped joints named in a note, as
    Pinocchio skips them), and an unknown pose is still refused."""
    robot = solo8(tmp_path).load()
    note = [n for n in robot.notes if "solo.srdf" in n]
    assert note == ["SRDF solo.srdf names joints solo does not have, skipped as Pinocchio does "
                    "(an SRDF shared with a sibling robot?): poses 'standing', "
                    "'straight_standing': FL_HAA, HL_HAA, FR_HAA, HR_HAA"]
    standing = robot.pose("standing")
    assert standing[7:] == pytest.approx([0.8, -1.6] * 2 + [-0.8, 1.6] * 2)  # FL FR HL HR
    with pytest.raises(UnknownNameError, match="unknown pose 'crouching'"):
        robot.pose("crouching")


def test_a_misspelling_of_a_joint_the_pose_leaves_unset_is_still_refused(tmp_path):
    """The sibling's joints are skipped, a near-name of a joint the pose leaves unset is not:
    Solo-8's SRDF with ``FL_KFE`` written ``FL_KFEE``."""
    robots = example_robot_data_dir() / "solo_description"
    text = (robots / "srdf" / "solo.srdf").read_text(encoding="utf-8")
    assert text.count('name="FL_KFE"') >= 2
    srdf = tmp_path / "solo.srdf"
    srdf.write_text(text.replace('<joint name="FL_KFE" value', '<joint name="FL_KFEE" value', 1),
                    encoding="utf-8")
    with pytest.raises(UnknownNameError, match=r"'FL_KFEE' \(did you mean 'FL_KFE'\?\)"):
        solo8(tmp_path, srdf).load()
