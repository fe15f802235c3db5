"""How to simulate: bad settings are named, and the simulated ground is sized to the robot (issue
#39, 7): the built-in robot's 2·10⁴ N/m and 100 N·s/m at its mass, scaled by the mass for another
robot (the same sink under the same share of the weight, the same damping ratio); a value given
is kept."""

from __future__ import annotations

import math

import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError
from hexaleg.simulation.settings import GROUND_MASS, Settings


def test_the_ground_scales_with_the_mass_and_keeps_the_sink_and_damping_ratio(robot):
    built_in = Settings().sized(robot.mass)
    assert (built_in.stiffness, built_in.damping) == (2e4, 100.0)  # exactly: the kept logs
    heavy = Settings().sized(31.0)
    share = 31.0 / 3 * 9.81  # a third of the weight on a foot
    assert share / heavy.stiffness == pytest.approx(GROUND_MASS / 3 * 9.81 / 2e4, rel=1e-12)
    ratio = heavy.damping / (2 * math.sqrt(heavy.stiffness * 31.0 / 3))
    assert ratio == pytest.approx(100.0 / (2 * math.sqrt(2e4 * GROUND_MASS / 3)), rel=1e-12)
    given = Settings(stiffness=5e4, damping=20.0).sized(31.0)
    assert (given.stiffness, given.damping) == (5e4, 20.0)


@pytest.mark.parametrize("kwargs, match", [({"cycles": 1}, "cycles"),
                                           ({"cycles": 3, "evaluate": 3}, "evaluate"),
                                           ({"controller": "torque"}, "controller"),
                                           ({"kp_scale": 0.0}, "kp_scale"),
                                           ({"stiffness": -5.0}, "stiffness")])
def test_bad_settings_are_named(kwargs, match):
    with pytest.raises(hexaleg.HexalegError, match=match):
        Settings(**kwargs)


@pytest.mark.parametrize("timestep", [float("nan"), 0.0, float("inf"), -1e-4, True, "1e-3"])
def test_a_timestep_that_is_not_a_positive_number_is_named(timestep):
    """--timestep nan, 0 or inf used to end in a ValueError or ZeroDivisionError traceback."""
    with pytest.raises(InvalidParameterError, match=r"invalid timestep = .*a finite timestep > 0"):
        Settings(timestep=timestep)
