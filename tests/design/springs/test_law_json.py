"""Tests of hexaleg.design.springs.law_json: every family's law survives JSON exactly."""

from __future__ import annotations

import json

import numpy as np
import pytest

from hexaleg.design.springs.law_json import spring_entry, spring_from_entry
from hexaleg.errors import ConfigError, UnknownNameError
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
