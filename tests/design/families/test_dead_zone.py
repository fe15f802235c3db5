"""Tests of hexaleg.design.families.dead_zone: it contains a linear spring (to k·LINEAR_GAP),
and its wound-up starts engage one stop over the whole motion."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.design.families import LINEAR_GAP, LINEAR_REACH, family
from hexaleg.robot.springs import basis


@pytest.mark.parametrize("x", [[0.4, 0.1], [0.4, -0.3], [2.0, 0.0]])
def test_it_contains_a_linear_spring(residual, x):
    assert residual("dead_zone", "linear", {}, np.array(x)) < 2.0 * LINEAR_GAP + 1e-12


def test_a_constant_torque_is_no_dead_zone_law():
    """k → 0: the equilibrium lies beyond LINEAR_REACH; both stops go off the motion."""
    from hexaleg.design.families import embed

    g = embed("dead_zone", "linear", {}, {"k": 1e-6, "torque_at_reference": 0.1}, (-0.8, 0.9))
    assert g == {"theta_minus": -0.8, "theta_plus": 0.9}
    assert 0.1 / 1e-6 > LINEAR_REACH


def test_off_and_wound_geometries(motion):
    fam = family("dead_zone")
    off = fam.check(fam.off(-0.8, 0.9, 0.1), "off")
    b = basis(fam.terms(off, 0.0), motion)
    assert not b.any()  # no stop engaged on the motion
    up = fam.check(fam.wound("above", -0.9, -0.8, 0.9, 0.1), "wound")
    assert up["theta_plus"] - up["theta_minus"] == pytest.approx(LINEAR_GAP)
    assert (basis(fam.terms(up, 0.0), motion)[:, 0] != 0).all()  # engaged throughout
    down = fam.check(fam.wound("below", 0.95, -0.8, 0.9, 0.1), "wound")
    assert (basis(fam.terms(down, 0.0), motion)[:, 1] != 0).all()
