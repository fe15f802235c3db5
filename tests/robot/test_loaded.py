"""Tests of hexaleg.robot.loaded: the loaded robot's type, its legs, names and poses."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.robot import model
from hexaleg.robot.loaded import JOINT_KINDS, Leg, Robot


def _copy(robot: Robot, **changes) -> Robot:
    """A new Robot over ``robot``'s Pinocchio objects (its __post_init__ runs again)."""
    keep = {f.name: getattr(robot, f.name) for f in dataclasses.fields(Robot) if f.init}
    return Robot(**{**keep, **changes})


def test_the_loader_makes_this_type_and_imports_it():
    assert model.Robot is Robot and model.Leg is Leg and model.JOINT_KINDS is JOINT_KINDS
    assert JOINT_KINDS == ("coxa", "femur", "tibia")


def test_mass_and_joint_names_are_derived_from_the_model(robot):
    again = _copy(robot)
    assert again.mass == pytest.approx(robot.mass) and again.mass > 0
    assert again.joint_names == tuple(robot.model.names[2:]) and len(again.joint_names) == 18
    assert again.nj == robot.model.nv - 6 == 18


def test_heading_is_checked_and_normalised(robot):
    turned = _copy(robot, heading=np.array([0.0, 2.0, 0.0]))
    np.testing.assert_array_equal(turned.heading, [0.0, 1.0, 0.0])
    with pytest.raises(InvalidParameterError, match="heading"):
        _copy(robot, heading=np.array([0.0, 0.0, 1.0]))  # vertical: not a walking direction


def test_joint_classes_joints_and_columns(robot):
    classes = robot.joint_classes
    assert list(classes) == list(JOINT_KINDS)
    assert classes["femur"] == tuple(f"{leg}_femur" for leg in robot.leg_names)
    assert robot.joints("tibia") == classes["tibia"]
    assert robot.joints("LF_coxa") == ("LF_coxa",)
    assert robot.column("LF_coxa") == robot.joint_names.index("LF_coxa")
    for spec, call in (("knee", robot.joints), ("LF_knee", robot.column)):
        with pytest.raises(UnknownNameError, match="LF_coxa"):
            call(spec)


def test_legs_by_name_address_their_joints(robot):
    leg = robot.leg("RM")
    assert isinstance(leg, Leg) and leg.joint_names == ("RM_coxa", "RM_femur", "RM_tibia")
    assert [robot.joint_names[c] for c in leg.columns] == list(leg.joint_names)
    np.testing.assert_array_equal(leg.columns, leg.v_index - 6)
    with pytest.raises(UnknownNameError, match="LF"):
        robot.leg("XX")


def test_poses_are_copies(robot):
    q = robot.pose("stand")
    q[:] = 7.0
    assert not np.any(robot.pose("stand") == 7.0)
    with pytest.raises(UnknownNameError, match="stand"):
        robot.pose("sitting_on_the_moon")


def test_geometry_model_is_chosen_by_name(robot):
    q = robot.pose("stand")
    assert robot.max_extent(q, "collision") > 0
    with pytest.raises(UnknownNameError, match="visual"):
        robot.max_extent(q, "both")


def test_joints_on_no_leg_are_listed_with_their_stand(tmp_path):
    """A humanoid's waist and arms are on no leg: named, in column order, with their stand
    angle in the summary (issue #55); a robot of legs alone has none."""
    from pathlib import Path

    import hexaleg

    humanoid = hexaleg.load(str(Path(__file__).resolve().parents[1] / "data" / "humanoid.toml"))
    assert humanoid.other_joints == ("waist", "L_shoulder", "L_elbow", "R_shoulder", "R_elbow")
    assert set(humanoid.other_joints).isdisjoint(j for js in humanoid.joint_classes.values()
                                                 for j in js)
    text = humanoid.summary()
    assert "other joints (5, on no leg" in text
    # its zero clipped into [0.1, 2]:
    assert "L_elbow               stand +0.1000 rad from its zero" in text
    assert "L_shoulder            stand +0.3000 rad from its zero" in text  # given by stand.joints
    assert hexaleg.load().other_joints == ()
    assert "other joints" not in hexaleg.load().summary()


def test_a_swinging_joint_is_listed_with_its_swing(tmp_path):
    """``hexaleg robot`` lists a joint of ``[robot] moves`` with its swing, the held ones
    without (issue #55): the line a user checks their description against."""
    from pathlib import Path

    import hexaleg

    data = Path(__file__).resolve().parents[1] / "data"
    text = (data / "humanoid.toml").read_text().replace(
        'urdf = "humanoid.urdf"', f'urdf = "{data / "humanoid.urdf"}"'
    ) + "\n"
    described = text.replace("stand = {", "moves = {waist = {amplitude = 0.2, phase = 0.5}}\n"
                                          "stand = {", 1)
    (tmp_path / "swing.toml").write_text(described)
    summary = hexaleg.load(str(tmp_path / "swing.toml")).summary()
    assert ("waist                 stand +0.0000 rad from its zero, swings ±0.2000 rad about the "
            "stand with phase +0.5000 rad each gait cycle") in summary
    assert "L_shoulder            stand +0.3000 rad from its zero\n" in summary
    assert "every angle here is the joint's coordinate, from its zero in the URDF" in summary
    assert "or swinging about it ([robot] moves)" in summary


def test_a_robot_survives_a_pickle_round_trip():
    """A forked worker sends robots back pickled; ``data`` is rebuilt, not pickled (pin 4.0.0's
    Data fails its own round trip, and the optimal extra pins pin 4.0)."""
    import pickle

    import hexaleg

    robot = hexaleg.load()
    back = pickle.loads(pickle.dumps(robot))
    assert back.model.nframes == robot.model.nframes and back.joint_names == robot.joint_names
    assert back.data is not robot.data and len(back.data.oMf) == back.model.nframes
    assert back.mass == robot.mass
