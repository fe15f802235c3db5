"""Tests of hexaleg.motion.params: GaitParams' ranges, TOML tables, updates and a robot's own
gait (robot_gait from the description's overrides)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import hexaleg
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.motion.legged import tripod_gait
from hexaleg.motion.params import TRIPODS, GaitParams, default_groups
from hexaleg.motion.scaling import robot_gait
from hexaleg.robot.registry import TROT, description


@pytest.mark.parametrize(("kwargs", "name"), [
    ({"duty_factor": 0.0}, "duty_factor"),
    ({"duty_factor": 1.0}, "duty_factor"),
    ({"period": 0.0}, "period"),
    ({"period": -1.0}, "period"),
    ({"period": math.nan}, "period"),
    ({"step_height": 0.0}, "step_height"),
    ({"step_height": -0.01}, "step_height"),
    ({"samples": 5}, "samples"),
    ({"samples": 100.0}, "samples"),
    ({"stride_length": -0.1}, "stride_length"),
    ({"body_height": 0.0}, "body_height"),
    ({"period": 1e300}, "period"),  # overflowed the swing trajectories (an OverflowError)
    ({"period": 1e-300}, "period"),  # underflowed to NaN accelerations
    ({"stride_length": 1e300}, "stride_length"),
    ({"step_height": 1e300}, "step_height"),
    ({"yaw_rate": 1e300}, "yaw_rate"),
    ({"groups": (("LF", "RM"), ("LF", "RH"))}, "groups"),
])
def test_bad_gait_parameters_are_rejected(kwargs, name):
    with pytest.raises(InvalidParameterError, match=rf"invalid {name} = .*allowed: ") as err:
        GaitParams(**kwargs)
    assert isinstance(err.value, hexaleg.HexalegError)


@pytest.mark.parametrize("value", ["fast", None, True, math.inf])
def test_non_numbers_are_invalid_parameters_not_type_errors(value):
    """Values are checked through hexaleg.checks: a string or None is named, not compared."""
    with pytest.raises(InvalidParameterError, match=r"invalid period = .*a cycle of 0\.01 s"):
        GaitParams(period=value)
    if value is None:  # None is the pattern's own β₀
        assert GaitParams(duty_factor=value).duty_factor == 0.5
        return
    with pytest.raises(InvalidParameterError, match=r"invalid duty_factor = .*β in \(0, 1\)"):
        GaitParams(duty_factor=value)


def test_speed_wins_over_stride(robot):
    gait = GaitParams(period=0.5, stride_length=0.06, speed=0.1, samples=50)
    assert gait.stride == pytest.approx(0.05) and gait.velocity == pytest.approx(0.1)
    motion = tripod_gait(robot, gait)
    assert motion.distance == pytest.approx(0.05)
    assert np.allclose(motion.q[:, 0], 0.1 * motion.t)


def test_gait_params_from_toml(tmp_path):
    path = tmp_path / "gait.toml"
    path.write_text('[gait]\nperiod = 2\nduty_factor = 0.75\nstep_height = 0.02\n'
                    'groups = [["LF"], ["RF"], ["LM"], ["RM"], ["LH"], ["RH"]]\n')
    gait = GaitParams.from_toml(path)
    assert gait.period == 2.0 and gait.duty_factor == 0.75 and gait.step_height == 0.02
    assert gait.groups[2] == ("LM",) and len(gait.groups) == 6
    assert GaitParams.from_toml({"speed": 0.05}).stride == pytest.approx(0.05)
    with pytest.raises(UnknownNameError, match=r"'stride'.*stride_length"):
        GaitParams.from_toml({"stride": 0.05})
    with pytest.raises(ConfigError, match="period"):
        GaitParams.from_toml({"period": "fast"})
    with pytest.raises(ConfigError, match="not found"):
        GaitParams.from_toml(tmp_path / "missing.toml")


def test_updated_puts_a_tables_keys_over_a_gait():
    base = GaitParams(period=0.5, stride_length=0.08, samples=400)
    new = base.updated({"period": 2, "step_height": 0.02})
    assert (new.period, new.step_height) == (2.0, 0.02)
    assert (new.stride_length, new.samples) == (0.08, 400)  # untouched keys keep base's values
    with pytest.raises(UnknownNameError, match="'periode'"):
        base.updated({"periode": 1.0})


def test_robot_gait_puts_the_descriptions_overrides_over_the_defaults():
    solo = robot_gait("solo12")
    assert solo == robot_gait(description("solo12"))
    assert (solo.period, solo.duty_factor, solo.stride_length, solo.step_height) == \
        (0.5, 0.6, 0.08, 0.04)
    assert solo.groups == TROT and solo.samples == GaitParams().samples
    assert robot_gait("hexaleg") == GaitParams() and GaitParams().groups == TRIPODS


def test_robot_gait_names_the_robot_of_a_bad_override():
    desc = description("solo12")
    with pytest.raises(UnknownNameError, match=r"robot 'solo12' gait.*'periode'"):
        robot_gait(dataclasses.replace(desc, gait={**desc.gait, "periode": 1.0}))
    with pytest.raises(InvalidParameterError, match="period"):
        robot_gait(dataclasses.replace(desc, gait={**desc.gait, "period": -1.0}))
    # No groups of its own: a quadruped trots; groups that leave a leg out are refused.
    no_groups = {k: v for k, v in desc.gait.items() if k != "groups"}
    assert robot_gait(dataclasses.replace(desc, gait=no_groups)).groups == TROT
    with pytest.raises(InvalidParameterError, match=r"solo12: gait.groups.*exactly one group"):
        robot_gait(dataclasses.replace(desc, gait={**no_groups, "groups": TRIPODS}))
    with pytest.raises(UnknownNameError, match="'spot'"):
        robot_gait("spot")


@pytest.mark.parametrize(("legs", "groups"), [
    (("LF", "LM", "LH", "RF", "RM", "RH"), TRIPODS),
    (("LF", "RF", "LH", "RH"), (("LF", "RH"), ("RF", "LH"))),
    (("L1", "L2", "L3", "L4", "R1", "R2", "R3", "R4"), (("L1", "L3", "R2", "R4"),
                                                        ("L2", "L4", "R1", "R3"))),
    (("L1", "R1"), (("L1",), ("R1",))),
    (("L1", "L3", "R1", "R3"), (("L1", "R3"), ("L3", "R1"))),  # ranks along a side, not numbers
    (("front_left", "RF"), None),
])
def test_default_groups_alternate_along_and_across_the_body(legs, groups):
    assert default_groups(legs) == groups


def test_a_found_quadruped_trots_by_default(tmp_path):
    """A quadruped whose legs are found in the URDF (no legs, no gait in its TOML) gets the
    trot, and walks."""
    toml = tmp_path / "quad.toml"
    toml.write_text('[robot]\nname = "quad"\nsource = "example-robot-data"\n'
                    'urdf = "a1_description/urdf/a1.urdf"\nstand = {body_height = 0.25}\n')
    gait = robot_gait(str(toml))
    assert gait.groups == (("LF", "RH"), ("RF", "LH"))
    robot = hexaleg.load(str(toml))
    motion = hexaleg.gait(robot, dataclasses.replace(gait, samples=60))
    assert motion.stance.sum(1).min() == 2


def test_legs_without_side_and_place_ask_for_groups(tmp_path):
    from hexaleg.robot.description import RobotDescription
    from hexaleg.robot.feet import LegSpec

    desc = RobotDescription(name="odd", urdf="x.urdf", legs=tuple(
        LegSpec(name=n, joints=(f"{n}_j",), foot=f"{n}_foot") for n in ("front", "back")))
    with pytest.raises(InvalidParameterError, match=r"groups = \[\[…\], \[…\]\]"):
        robot_gait(desc)


def test_for_robot_of_0_1_warns_and_gives_robot_gait():
    """GaitParams.for_robot (0.1) had raised AttributeError since it moved (#58)."""
    from hexaleg.motion.scaling import robot_gait

    with pytest.warns(DeprecationWarning, match=r"GaitParams\.for_robot is deprecated .*use "
                                                r"hexaleg\.motion\.scaling\.robot_gait"):
        old = GaitParams.for_robot("solo12", sized=False)
    assert old == robot_gait("solo12", sized=False)
