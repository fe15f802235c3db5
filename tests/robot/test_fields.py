"""The checked fields of a robot description: stand, heading, legs tables."""

from __future__ import annotations

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
