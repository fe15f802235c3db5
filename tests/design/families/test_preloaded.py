"""Tests of hexaleg.design.families.preloaded: it contains one-sided, dead-zone and linear
springs exactly, a constant torque included."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.design.families import family


@pytest.mark.parametrize(("inner", "geometry", "x"), [
    ("one_sided", {"contact": 0.1, "side": "above"}, [0.4, 0.05]),
    ("one_sided", {"contact": -0.2, "side": "below"}, [0.3, 0.02]),
    ("dead_zone", {"theta_minus": -0.2, "theta_plus": 0.3}, [0.4, 0.7]),
    ("linear", {}, [0.5, 0.1]),
    ("linear", {}, [0.0, 0.1]),   # a constant torque: both stops off, on the preload's side
    ("linear", {}, [0.0, -0.1]),
])
def test_it_contains_what_it_says(residual, inner, geometry, x):
    assert inner in family("preloaded").contains
    assert residual("preloaded", inner, family(inner).check(geometry, "g"), np.array(x)) < 1e-12


def test_its_stops_carry_preloads():
    fam = family("preloaded")
    assert fam.preloaded_stops and fam.wound("above", 1.0, -0.8, 0.9, 0.1) is None
    assert fam.stops == {"theta_plus": ("k_plus", "preload_plus"),
                         "theta_minus": ("k_minus", "preload_minus")}
