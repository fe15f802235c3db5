"""Tests of hexaleg.design.chain.groups: classes, mirrored pairs, single joints."""

from __future__ import annotations

import pytest

from hexaleg.design.chain.groups import class_of, design_groups, sprung_classes
from hexaleg.errors import UnknownNameError


def test_groupings_cover_the_same_joints(robot):
    classes = sprung_classes(robot, ())
    assert classes == ("coxa", "femur", "tibia")
    by_class = design_groups(robot, ("femur",), "class")
    mirrored = design_groups(robot, ("femur",), "mirrored")
    joints = design_groups(robot, ("femur",), "joint")
    assert by_class == {"femur": robot.joints("femur")}
    assert set(mirrored) == {"femur LF/RF", "femur LM/RM", "femur LH/RH"}
    assert mirrored["femur LF/RF"] == ("LF_femur", "RF_femur")
    assert sorted(j for js in mirrored.values() for j in js) == sorted(robot.joints("femur"))
    assert joints == {j: (j,) for j in robot.joints("femur")}
    assert class_of(robot, ("LM_femur", "RM_femur")) == "femur"


def test_an_unknown_class_lists_the_classes(robot):
    with pytest.raises(UnknownNameError, match="coxa, femur, tibia"):
        sprung_classes(robot, ("knee",))
