"""Tests of hexaleg.design.families.one_sided: the side is part of the geometry — checked,
flipped by the mirror, the only label a family has."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.design.families import family
from hexaleg.errors import UnknownNameError
from hexaleg.robot.springs import OneSidedSpring


def test_the_side_is_checked_and_defaults_to_above():
    fam = family("one_sided")
    assert fam.check({"contact": 0.1}, "g") == {"contact": 0.1, "side": "above"}
    with pytest.raises(UnknownNameError, match="above, below"):
        fam.check({"contact": 0.1, "side": "left"}, "g")
    assert fam.side("contact", {"contact": 0.1, "side": "below"}) == "below"


def test_the_law_acts_on_its_side_only():
    fam = family("one_sided")
    spring = fam.spring({"contact": 0.1, "side": "below"}, 0.3, [0.5, 0.02])
    assert isinstance(spring, OneSidedSpring)
    q = np.array([0.0, 0.3, 0.39, 0.41, 0.8])
    tau = spring.torque(q)
    assert (tau[q > 0.4] == 0).all() and (tau[q < 0.4] > 0).all()


def test_mirror_and_off():
    fam = family("one_sided")
    g, x = fam.mirror({"contact": 0.1, "side": "below"}, [0.5, 0.02])
    assert g == {"contact": -0.1, "side": "above"} and list(x) == [0.5, 0.02]
    assert fam.off(-0.8, 0.9, 0.1) == {"contact": 0.9, "side": "above"}
