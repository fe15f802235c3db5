"""Tests of hexaleg.design.springs.law_json: every family's law survives JSON exactly."""

from __future__ import annotations

import json

import numpy as np
import pytest

from hexaleg.design.springs.law_json import spring_entry, spring_from_entry
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.robot.springs import (
    DeadZoneSpring,
    LinearSpring,
    OneSidedSpring,
    PreloadedSpring,
    StiffeningSpring,
)

LAWS = [LinearSpring(0.02, 0.3, -0.06), DeadZoneSpring(0.1, theta_minus=-0.2, theta_plus=0.1,
                                                       stiffness_minus=0.05, neutral=0.4),
        PreloadedSpring(stiffness=0.01, preload=0.05, theta_minus=-0.1, theta_plus=0.2,
                        stiffness_minus=0.0, preload_minus=0.02, neutral=-0.3),
        OneSidedSpring(0.03, 0.61, "below", 0.08),
        StiffeningSpring(above=((0.1, 0.02), (0.3, 0.05)), below=((-0.2, 0.01),))]


@pytest.mark.parametrize("law", LAWS, ids=lambda s: type(s).__name__)
def test_round_trip_through_json_is_the_same_law(law):
    entry = json.loads(json.dumps(spring_entry("LF_femur", law), ensure_ascii=False))
    assert entry["joint"] == "LF_femur"
    back = spring_from_entry(entry)
    assert back == law
    q = np.linspace(-1.5, 1.5, 301)
    np.testing.assert_array_equal(back.torque(q), law.torque(q))


def test_bad_entries_are_named():
    entry = spring_entry("LF_femur", LAWS[0])
    with pytest.raises(UnknownNameError, match="linear"):
        spring_from_entry({**entry, "family": "spiral"})
    with pytest.raises(ConfigError, match="N·m/rad"):
        spring_from_entry({**entry, "parameters": {"stiffness": {"value": 1, "unit": "N·m"}}})
    with pytest.raises(UnknownNameError, match="stiffness"):
        spring_from_entry({**entry, "parameters": {"k": {"value": 1, "unit": "N·m/rad"}}})
    with pytest.raises(UnknownNameError, match="linear"):
        spring_from_entry({**entry, "family": ["linear"]})
    stiffening = spring_entry("LF_femur", LAWS[-1])
    half = [{"breakpoint": {"value": 0.1, "unit": "rad"}}]  # no stiffness
    for above in ({"breakpoint": 0.1}, [0.1, 0.02], half):
        bad = {**stiffening, "parameters": {**stiffening["parameters"], "above": above}}
        with pytest.raises(ConfigError, match=r"spring\.above"):
            spring_from_entry(bad)


IDLE_LAWS = [
    PreloadedSpring(stiffness=0.0, preload=0.0, theta_minus=0.197, theta_plus=0.317,
                    stiffness_minus=0.0265, preload_minus=0.0724, neutral=-2.0),
    PreloadedSpring(stiffness=0.02, preload=0.04, theta_minus=-0.4, theta_plus=-0.2,
                    stiffness_minus=4e-10, preload_minus=0.0, neutral=0.5),
    DeadZoneSpring(0.0136, theta_minus=-2.934043301, theta_plus=-2.934043300, stiffness_minus=0.0,
                   neutral=0.546),
    OneSidedSpring(0.0, 0.61, "below", 0.0),
    StiffeningSpring(above=((0.1, 0.0), (0.3, 0.05)), below=((-0.2, 0.0),)),
    StiffeningSpring(above=((0.1, 0.0),), below=((-0.2, 0.0),))]
IDLE = [("theta_plus",), ("theta_minus",), ("theta_minus",), ("contact",),
        ("above[0]", "below[0]"), ("above[0]", "below[0]")]


@pytest.mark.parametrize(("law", "idle"), list(zip(IDLE_LAWS, IDLE, strict=True)),
                         ids=lambda s: type(s).__name__ if not isinstance(s, tuple) else "")
def test_an_angle_past_which_nothing_acts_is_written_without_a_value(law, idle):
    """An angle whose terms' magnitudes are all at most ZERO_MAGNITUDE (design.json wrote the
    search's leftover, e.g. a preloaded tibia's θ⁺ = 0.3166 rad past k⁺ = P⁺ = 0) is null with
    the reason, as the design's tables write it; read back, the law is the same at every angle.
    Fails on a writer that writes the idle angle's number."""
    from hexaleg.design.families import IDLE as WHY
    from hexaleg.design.families import ZERO_MAGNITUDE
    from hexaleg.design.springs.law_json import idle_fields

    assert idle_fields(law) == idle
    entry = json.loads(json.dumps(spring_entry("LF_tibia", law), ensure_ascii=False))
    params = entry["parameters"]
    for name in idle:
        if "[" in name:
            side, i = name[:-3], int(name[-2])
            value = params[side][i]["breakpoint"]
        else:
            value = params[name]
        assert value == {"value": None, "unit": "rad", "note": WHY}
    back = spring_from_entry(entry)
    q = np.linspace(-4.0, 1.5, 2201)
    # exactly the same law where the idle magnitudes are 0; at most their round-off times the
    # angle moved (5.5 rad here) where one is below the zero but not 0 (k⁻ = 4e-10 N·m/rad)
    np.testing.assert_allclose(back.torque(q), law.torque(q), rtol=0, atol=6 * ZERO_MAGNITUDE)
    np.testing.assert_allclose(back.energy(q), law.energy(q), rtol=0, atol=20 * ZERO_MAGNITUDE)
    if law is not IDLE_LAWS[1]:
        np.testing.assert_array_equal(back.torque(q), law.torque(q))
        np.testing.assert_array_equal(back.energy(q), law.energy(q))


def test_a_null_angle_something_acts_past_is_refused():
    """Null only where nothing acts: a θ⁺ with k⁺ past it, a stage with its stiffness, a
    neutral, are refused naming the field."""
    entry = spring_entry("LF_femur", LAWS[2])
    bad = {**entry, "parameters": {**entry["parameters"],
                                   "theta_plus": {"value": None, "unit": "rad"}}}
    with pytest.raises(InvalidParameterError, match=r"theta_plus.*something acts"):
        spring_from_entry(bad)
    bad = {**entry, "parameters": {**entry["parameters"],
                                   "neutral": {"value": None, "unit": "rad"}}}
    with pytest.raises(ConfigError, match="neutral"):
        spring_from_entry(bad)
    stiffening = spring_entry("LF_femur", LAWS[-1])
    stages = [{"breakpoint": {"value": None, "unit": "rad"},
               "stiffness": {"value": 0.02, "unit": "N·m/rad"}}]
    with pytest.raises(InvalidParameterError, match=r"above\[0\]\.breakpoint"):
        spring_from_entry({**stiffening,
                           "parameters": {**stiffening["parameters"], "above": stages}})
