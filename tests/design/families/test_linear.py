"""Tests of hexaleg.design.families.linear: τ = τ₀ − k (q − c), whatever reference angle."""

from __future__ import annotations

import numpy as np

from hexaleg.design.families import family
from hexaleg.robot.springs import LinearSpring


def test_the_law_is_a_linear_spring_about_the_centre():
    fam = family("linear")
    spring = fam.spring({}, 0.3, [0.5, -0.2])
    assert isinstance(spring, LinearSpring)
    q = np.linspace(-1.0, 1.0, 11)
    np.testing.assert_allclose(spring.torque(q), -0.2 - 0.5 * (q - 0.3), atol=1e-15)
    assert fam.check({}, "g") == {} and fam.off(-1.0, 1.0, 0.1) == {}
    assert fam.wound("above", 1.2, -1.0, 1.0, 0.1) is None  # no stops to wind


def test_a_rounding_error_below_zero_is_clipped_but_the_constant_keeps_its_sign():
    spring = family("linear").spring({}, 0.0, [-1e-17, -0.3])
    assert spring.stiffness == 0.0 and spring.torque(np.array([0.0]))[0] == -0.3
