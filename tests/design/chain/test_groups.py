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


def test_a_class_whose_members_work_apart_is_split(robot):
    """Two knees at −110…−60°, two at +60…+110°: two parts named after their legs, a note
    with the ranges; overlapping ranges keep the class; a mirrored joint counts its range the
    other way round (its sign −1 brings it into its twin's)."""
    from hexaleg.design.chain.groups import split_by_motion

    femurs = robot.joints("femur")
    angles = {j: ((-1.9, -1.0) if j.startswith(("LF", "RF")) else (-0.4, 0.3)) for j in femurs}
    parts, notes = split_by_motion(robot, {"femur": femurs}, angles)
    assert set(parts) == {"femur LF/RF", "femur LM/LH/RM/RH"}
    assert parts["femur LF/RF"] == tuple(j for j in femurs if j.startswith(("LF", "RF")))
    assert len(notes) == 1 and "LF/RF at -109…-57°" in notes[0]
    same, none = split_by_motion(robot, {"femur": femurs}, dict.fromkeys(femurs, (-0.5, 0.5)))
    assert same == {"femur": femurs} and none == []
    flipped = {j: ((0.5, 1.0) if j.startswith("R") else (-1.0, -0.5)) for j in femurs}
    signs = {j: (-1 if j.startswith("R") else 1) for j in femurs}
    assert split_by_motion(robot, {"femur": femurs}, flipped, signs)[0] == {"femur": femurs}


def test_an_x_configured_quadruped_designs_within_a_point_of_per_joint():
    """Issue #39: the X-configured test quadruped's front knees bend one way, its hind knees the
    other; one class spring served both (+0.4 %). Split by their motion, the class design is
    within one point of the per-joint design (which contains it)."""
    from pathlib import Path

    import hexaleg
    from hexaleg.design.chain.chain import DesignChain
    from hexaleg.design.chain.config import DesignParams

    xquad = str(Path(__file__).resolve().parents[2] / "data" / "xquad.toml")
    scenario = hexaleg.Scenario.load(xquad)
    found = {}
    for grouping in ("class", "joint"):
        params = DesignParams(grouping=grouping, robustness=False, families=("one_sided",))
        r = DesignChain(scenario, design=params).run(stages=("candidates",))
        found[grouping] = r.recommended.row["saving.electrical"]
        assert any(n.startswith("joint class knee split by its motion: LF/RF at -1")
                   for n in r.notes)
    assert found["class"] > 0.2  # its default trot, 0.86 s since the stands are held (#54)
    assert found["joint"] - 0.01 <= found["class"] <= found["joint"] + 1e-9
