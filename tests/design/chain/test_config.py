"""Tests of hexaleg.design.chain.config: the [design] table and the document around it."""

from __future__ import annotations

import math

import pytest

from hexaleg.design.chain.config import DesignConfig, DesignParams
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError


def test_defaults_and_the_gait_of_the_robot():
    c = DesignConfig.from_mapping({"gait": {"period": 1.5}, "design": {"samples": 150}})
    assert c.gait.period == 1.5 and c.gait.samples == 150
    assert c.design.deflection_bound == math.pi
    assert DesignParams(max_deflection="none").deflection_bound is None
    assert DesignParams(max_deflection=3).deflection_bound == 3.0  # an int bound is a bound
    run = c.design.run("hexaleg", c.contact)
    assert run.objective == "joule" and run.motor is None  # the robot's own actuator


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
        DesignConfig.from_mapping(table)


def test_an_unknown_robot_lists_the_registry():
    with pytest.raises(UnknownNameError, match="hexaleg"):
        DesignConfig.from_mapping({}, robot="atlas")
