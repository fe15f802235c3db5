"""Tests of hexaleg.robot.description: a description loads its robot (standing pose from the SRDF
or joint values), checks its fields (legs, joint classes, gait groups, actuator), keeps its gait
as read-only plain overrides, and can be read from one's own TOML file."""

from __future__ import annotations

import copy
import dataclasses
import pickle

import numpy as np
import pytest

import hexaleg
from hexaleg.errors import ConfigError, InvalidParameterError, RobotModelError, UnknownNameError
from hexaleg.robot.description import RobotDescription, read_description
from hexaleg.robot.model import LegSpec
from hexaleg.robot.registry import TROT, description, load


@pytest.mark.parametrize("name", ["solo12", "go2"])  # not ANYmal: its meshes take 3.5 s to load
def test_a_urdf_whose_feet_are_missing_lists_the_frames(name):
    desc = description(name)
    legs = (LegSpec(desc.legs[0].name, desc.legs[0].joints, "LF_toe"), *desc.legs[1:])
    with pytest.raises(RobotModelError) as err:
        dataclasses.replace(desc, legs=legs).load()
    msg = str(err.value)
    assert "'LF_toe'" in msg and "frames found" in msg
    for spec in desc.legs:
        assert spec.foot in msg


def test_bad_descriptions():
    desc = description("solo12")
    with pytest.raises(UnknownNameError, match="kfe"):
        dataclasses.replace(desc, spring_class="ankle")
    with pytest.raises(hexaleg.HexalegError, match="exactly one group"):
        dataclasses.replace(desc, gait={**desc.gait, "groups": (("LF", "RH"),)})
    with pytest.raises(UnknownNameError, match="FL_KFE"):
        dataclasses.replace(desc, stand={"FL_knee": 1.0}).load()


def test_stand_from_joint_values():
    desc = description("solo12")
    robot = dataclasses.replace(desc, stand={"FL_KFE": -1.2, "HR_KFE": 1.2}).load()
    q = robot.pose("stand")
    assert q[7 + robot.column("FL_KFE")] == -1.2 and q[7 + robot.column("HR_KFE")] == 1.2
    assert np.count_nonzero(q[7:]) == 2


def test_own_robot_from_toml(tmp_path):
    """A TOML description of Solo-12's files (paths relative to the TOML) loads the same robot."""
    desc = description("solo12")
    robots_dir = desc.urdf_path.parents[2]
    (tmp_path / "robots").symlink_to(robots_dir)
    legs = "".join(f'[[robot.legs]]\nname = "{s.name}"\njoints = {list(s.joints)!r}\n'
                   f'foot = "{s.foot}"\n' for s in desc.legs).replace("'", '"')
    (tmp_path / "solo.toml").write_text(
        '[robot]\nname = "mysolo"\ntitle = "Solo-12 by hand"\n'
        f'urdf = "robots/{desc.urdf}"\nsrdf = "robots/{desc.srdf}"\n'
        'stand = {FL_KFE = -1.6, FR_KFE = -1.6, HL_KFE = 1.6, HR_KFE = 1.6}\n'
        'joint_kinds = ["haa", "hfe", "kfe"]\nspring_class = "kfe"\n'
        f'mesh_dirs = ["{robots_dir.parents[1]}"]\n'
        '[robot.gait]\nperiod = 0.5\ngroups = [["LF", "RH"], ["RF", "LH"]]\n' + legs)
    own = RobotDescription.from_toml(tmp_path / "solo.toml")
    assert own.source == "files" and own.gait["groups"] == TROT and own.legs == desc.legs
    robot, ref = load(str(tmp_path / "solo.toml")), load("solo12")
    assert robot.joint_names == ref.joint_names and robot.leg_names == ref.leg_names
    assert np.isclose(robot.mass, ref.mass, rtol=1e-12)
    q = robot.pose("stand")
    assert q[7 + robot.column("HL_KFE")] == 1.6 and q[7 + robot.column("FL_HFE")] == 0.0

    (tmp_path / "bad.toml").write_text('[robot]\nname = "x"\nwheels = 4\n[[robot.legs]]\n'
                                       'name = "LF"\njoints = ["a"]\nfoot = "f"\n')
    with pytest.raises(UnknownNameError, match="wheels"):
        RobotDescription.from_toml(tmp_path / "bad.toml")
    (tmp_path / "nourdf.toml").write_text('[robot]\nname = "x"\n')
    with pytest.raises(ConfigError, match=r"missing urdf; required keys: name, urdf"):
        load(str(tmp_path / "nourdf.toml"))


@pytest.mark.parametrize(("text", "error", "says"), [
    ('[robot]\nname = "x"\nurdf = "x.urdf"\nspeeed = 3\n', UnknownNameError, "speeed"),
    ('[robot]\nname = "x"\nurdf = "x.urdf"\njoint_kinds = ["a", "b"]\n'
     '[robot.arbor_diameter]\na = -0.001\n', InvalidParameterError, r"arbor_diameter\.a"),
])
def test_a_bad_value_of_a_description_file_is_named(tmp_path, text, error, says):
    """The file's table parsed (tests/robot/test_description_file.py), the description checks
    every key and value."""
    path = tmp_path / "robot.toml"
    path.write_text(text)
    with pytest.raises(error, match=says):
        read_description(path)


def test_a_description_names_a_catalogue_actuator(tmp_path):
    assert description("solo12").motor == "ODRI-4004" and description("hexaleg").motor == "AX-18A"
    assert description("go2").motor is None
    with pytest.raises(UnknownNameError, match=r"'T-Motor'.*ODRI-4004"):
        dataclasses.replace(description("solo12"), motor="T-Motor")


def test_gait_is_a_read_only_mapping_of_plain_overrides():
    """The robot layer keeps gait overrides as plain values (lists become tuples); it checks the
    leg names of ``groups``, and robot_gait (the motion layer) the rest."""
    desc = description("solo12")
    assert desc.gait["groups"] == TROT and desc.gait["period"] == 0.5
    with pytest.raises(TypeError):
        desc.gait["period"] = 1.0  # type: ignore[index]
    listed = dataclasses.replace(desc, gait={"groups": [["LF", "RH"], ["RF", "LH"]]})
    assert listed.gait == {"groups": TROT}
    assert description("hexaleg").gait == {}
    # Like the frozen dataclass it sits in: hashable, picklable, deep-copyable.
    assert pickle.loads(pickle.dumps(desc)) == desc == copy.deepcopy(desc)
    assert hash(desc) == hash(dataclasses.replace(desc))
    with pytest.raises(hexaleg.HexalegError, match=r"solo12: gait = .*GaitParams keys"):
        dataclasses.replace(desc, gait=[("period", 0.5)])
    with pytest.raises(hexaleg.HexalegError, match="exactly one group"):
        dataclasses.replace(desc, gait={"groups": "LF RH RF LH"})
