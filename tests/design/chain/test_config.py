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


def test_a_design_factor_or_an_arbor_far_out_of_range_is_named():
    """Issue #58: ``[design] safety_factor = 100`` bought 1.7 kg of springs and ``arbor_diameter
    = 5.0`` ended in a motor torque limit; each is now refused by name with what is allowed."""
    from hexaleg.design.chain.chain import DesignChain
    from hexaleg.design.chain.config import DesignConfig
    from hexaleg.errors import InvalidParameterError

    with pytest.raises(InvalidParameterError, match=r"safety_factor.*1 to 10 .*Shigley"):
        DesignConfig.from_mapping({"design": {"safety_factor": 100.0}})
    cfg = DesignConfig.from_mapping({"design": {"arbor_diameter": 5.0, "samples": 60}})
    with pytest.raises(InvalidParameterError, match=r"arbor_diameter = 5\.0.*< 30 mm, the "
                                                    r"largest spring outer diameter"):
        DesignChain(cfg).run(stages=("candidates",))
