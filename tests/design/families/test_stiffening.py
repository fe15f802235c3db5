"""Tests of hexaleg.design.families.stiffening: it contains a dead zone exactly (second stages
off), and its off and wound geometries are ordered and leave the motion as they say."""

from __future__ import annotations

import numpy as np

from hexaleg.design.families import STAGE_OFF, embed, family
from hexaleg.robot.springs import basis


def test_it_contains_a_dead_zone(residual):
    geometry = {"theta_minus": -0.2, "theta_plus": 0.25}
    assert residual("stiffening", "dead_zone", geometry, np.array([0.4, 0.7])) < 1e-12
    g = embed("stiffening", "dead_zone", geometry, {}, (-0.8, 0.9))
    assert g["above_2"] == 0.9 + STAGE_OFF and g["below_2"] == -0.8 - STAGE_OFF


def test_off_and_wound_geometries_are_ordered(motion):
    fam = family("stiffening")
    off = fam.check(fam.off(-0.8, 0.9, 0.1), "off")
    assert not basis(fam.terms(off, 0.0), motion).any()
    for side, first in (("above", -0.9), ("below", 0.95)):
        g = fam.check(fam.wound(side, first, -0.8, 0.9, 0.1), "wound")
        engaged = basis(fam.terms(g, 0.0), motion).any(axis=0)
        assert list(engaged) == ([True, False, False, False] if side == "above"
                                 else [False, False, True, False])
