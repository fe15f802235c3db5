"""The checked fields of a robot description: stand, heading, legs tables, moves."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.robot.fields import axis, check_stand, heading, legs_table


def test_stand_forms():
    assert check_stand("r", None) is None and check_stand("r", "standing") == "standing"
    assert dict(check_stand("r", {"LF_KFE": -1})) == {"LF_KFE": -1.0}
    feet = check_stand("r", {"body_height": 0.1, "feet": {"LF": [0.1, 0.2]}})
    assert feet["body_height"] == 0.1 and feet["feet"]["LF"] == (0.1, 0.2)


@pytest.mark.parametrize(("stand", "match"), [
    ({"body_height": -0.1}, "body_height"), ({"body_height": 0.1, "feet": {"LF": [1]}},
                                             "stand.feet"),
    ({"body_height": 0.1, "height": 1}, "height"), ({"LF_KFE": "bent"}, "joint name"),
    (3, "group_state")])
def test_bad_stands_are_named(stand, match):
    with pytest.raises((InvalidParameterError, UnknownNameError), match=match):
        check_stand("r", stand)


def test_headings():
    assert heading("r", "+y") == (0.0, 1.0, 0.0) and heading("r", [1, 1, 0]) == (1.0, 1.0, 0.0)
    assert axis("-x", "w") == (-1.0, 0.0, 0.0)
    for bad in ([0, 0, 1], [0, 0, 0], "up", [1, 2]):
        with pytest.raises((InvalidParameterError, UnknownNameError), match="heading"):
            heading("r", bad)


def test_legs_tables():
    (leg,) = legs_table([{"name": "LF", "joints": ["a", "b", "c"],
                          "foot": {"link": "shin", "point": [0, 0, -0.1]}}], "w")
    assert (leg.foot, leg.point, leg.joints) == ("shin", (0.0, 0.0, -0.1), ("a", "b", "c"))
    (bare,) = legs_table([{"name": "LF", "joints": ["a"]}], "w")
    assert bare.foot is None
    with pytest.raises(ConfigError, match="link"):
        legs_table([{"name": "LF", "joints": ["a"], "foot": {"frame": "x"}}], "w")
    with pytest.raises(ConfigError, match=r"\[\[robot.legs\]\]"):
        legs_table([], "w")


WHEELED = Path(__file__).resolve().parents[1] / "data" / "wheeled.toml"
"""The wheeled test quadruped with a two-joint arm (arm_yaw, arm_pitch) on its back."""


def wheeled_moving(tmp_path: Path, moves: str) -> Path:
    """The wheeled test robot's description with ``moves = {…}`` added (its URDF absolute)."""
    text = WHEELED.read_text().replace(
        'urdf = "wheeled.urdf"', f'urdf = "{WHEELED.with_suffix(".urdf")}"\nmoves = {moves}')
    path = tmp_path / "w.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize(("moves", "error", "says"), [
    ("{arm_pitch = {amplitude = -0.1}}", InvalidParameterError, "an amplitude ≥ 0"),
    ("{arm_pitch = {amplitude = 0.1, period = 2}}", UnknownNameError, "'period'"),
    ("{arm_pitch = 0.3}", InvalidParameterError, "{amplitude = rad, phase = rad}"),
    ("{arm_pitch = {amplitude = 0.1, phase = nan}}", InvalidParameterError, "a finite phase"),
])
def test_a_bad_moves_entry_is_named(tmp_path, moves, error, says):
    from hexaleg.robot.description import read_description

    with pytest.raises(error, match=re.escape(says)):
        read_description(wheeled_moving(tmp_path, moves))


@pytest.mark.parametrize(("moves", "error", "says"), [
    ("{LF_KFE = {amplitude = 0.1}}", UnknownNameError, "valid joints in wheeled's moves (one "
                                                       "on no leg) are: arm_pitch, arm_yaw"),
    ("{arm_pitch = {amplitude = 1.0}}", InvalidParameterError,
     "a swing within the joint's limits [-1.5, 0.3] rad about its stand angle -0.5 rad (at most "
     "0.8)"),
])
def test_moves_are_checked_against_the_robot_on_loading(tmp_path, moves, error, says):
    from hexaleg.robot.description import read_description

    with pytest.raises(error, match=re.escape(says)):
        read_description(wheeled_moving(tmp_path, moves)).load()
