"""Tests of hexaleg.design.chain.config: the [design] table and the document around it."""

from __future__ import annotations

import math

import pytest

from hexaleg.design.chain.config import DesignParams, design_params, design_run, mission
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.scenario.scenario import Scenario


def _design(tables, robot="hexaleg"):
    """The design's run and its [design] settings from a parsed document."""
    s = Scenario.from_tables(robot, tables)
    d = design_params(s)
    return design_run(s, d), d


def test_defaults_and_the_gait_of_the_robot():
    run, d = _design({"gait": {"period": 1.5}, "design": {"samples": 150}})
    assert run.gait.period == 1.5 and run.gait.samples == 150
    assert d.deflection_bound == math.pi
    assert DesignParams(max_deflection="none").deflection_bound is None
    assert DesignParams(max_deflection=3).deflection_bound == 3.0  # an int bound is a bound
    assert run.objective == "joule"
    own = Scenario.load()
    assert run.actuator.name == own.actuator.name  # the robot's own actuator


def test_the_controller_replaces_the_tables_and_the_mission_is_read():
    s = Scenario.from_tables("hexaleg", {"design": {"controller": "position"},
                                         "mission": {"metres_per_fold": 15.0}})
    assert design_params(s).controller == "position"
    assert design_params(s, "both").controller == "both"
    assert mission(s).metres_per_fold == 15.0
    with pytest.raises(UnknownNameError, match="both"):
        design_params(s, "torque-ish")


@pytest.mark.parametrize(("table", "error", "match"), [
    ({"design": {"families": ["spiral"]}}, UnknownNameError, "dead_zone, linear"),
    ({"design": {"materials": ["bronze"]}}, UnknownNameError, "music_wire"),
    ({"design": {"grouping": "legs"}}, UnknownNameError, "class, joint, mirrored"),
    ({"design": {"metric": "rms_torque"}}, UnknownNameError, "electrical, joule"),
    ({"design": 3}, ConfigError, r"\[design\]: expected a table"),
    ({"design": {"max_torque": -1.0}}, InvalidParameterError, "max_torque"),
    ({"design": {"robust_mu": [1.0, 0.5]}}, InvalidParameterError, "low <= high"),
    ({"design": {"colour": 1}}, UnknownNameError, "families"),
    ({"simulat": {}}, UnknownNameError, "design"),
])
def test_bad_configuration_is_named(table, error, match):
    with pytest.raises(error, match=match):
        _design(table)


def test_an_unknown_robot_lists_the_registry():
    with pytest.raises(UnknownNameError, match="hexaleg"):
        _design({}, robot="atlas")


def test_a_design_factor_or_an_arbor_far_out_of_range_is_named():
    """Issue #58: ``[design] safety_factor = 100`` bought 1.7 kg of springs and ``arbor_diameter
    = 5.0`` ended in a motor torque limit; each is now refused by name with what is allowed."""
    from hexaleg.design.chain.chain import DesignChain

    with pytest.raises(InvalidParameterError, match=r"safety_factor.*1 to 10 .*Shigley"):
        _design({"design": {"safety_factor": 100.0}})
    scenario = Scenario.from_tables("hexaleg", {"design": {"arbor_diameter": 5.0,
                                                           "samples": 60}})
    with pytest.raises(InvalidParameterError, match=r"arbor_diameter = 5\.0.*< 30 mm, the "
                                                    r"largest spring outer diameter"):
        DesignChain(scenario).run(stages=("candidates",))
