"""Tests of hexaleg.paper.joint: the paper's single elastic joint (eq. 13–21, Table 6,
eq. 25) and its closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hexaleg.design.rules import PAPER_ALPHA, PAPER_AMPLITUDE, PAPER_OMEGA, PAPER_THETA_K
from hexaleg.errors import HexalegError, InvalidParameterError
from hexaleg.motion.profiles import Sinusoid
from hexaleg.paper.joint import PaperJoint

J0 = PaperJoint()


def test_defaults_are_the_papers_design_constants_and_eq16_is_the_motion_sinusoid():
    assert (J0.amplitude, J0.omega, J0.theta_k, J0.alpha) == (
        PAPER_AMPLITUDE, PAPER_OMEGA, PAPER_THETA_K, PAPER_ALPHA)
    assert J0.theta_k == pytest.approx(math.radians(7.32), rel=1e-15)
    j = PaperJoint(amplitude=0.4, omega=3.0, phase=0.5, offset=0.2)
    assert j.sinusoid == Sinusoid(amplitude=0.4, omega=3.0, phase=0.5, offset=0.2)
    t = j.times(64)
    th, thd, thdd = j.trajectory(t)
    np.testing.assert_allclose(th, 0.4 * np.sin(3 * t + 0.5) + 0.2, rtol=0, atol=1e-15)
    np.testing.assert_allclose(thd, 1.2 * np.cos(3 * t + 0.5), rtol=0, atol=1e-15)
    np.testing.assert_allclose(thdd, -3.6 * np.sin(3 * t + 0.5), rtol=0, atol=1e-14)


def test_k_M_SI_by_hand():
    # ω² (m l² + I)/α in SI, typed out: 4 (0.03611·0.047141² + 107.059e-6) / 1.05 N·m/rad.
    hand = 4 * (0.03611 * 0.047141**2 + 107.059e-6) / 1.05
    assert J0.k_M() == pytest.approx(hand, rel=1e-12)
    assert hand == pytest.approx(7.1354e-4, rel=1e-4)
    # ... which is 0.01245 N·mm/deg, not 713.5 N·mm/deg.
    assert hand * 1000 * math.pi / 180 == pytest.approx(0.012454, rel=1e-4)
    # The eq. 7 convention (κ = kα²) needs α times less stiffness for the same joint stiffness.
    assert PaperJoint(convention="eq7").k_M() == pytest.approx(hand / 1.05, rel=1e-12)


def test_k_M_makes_torque_constant_while_engaged():
    # Eq. 18–19: at k_M, dM/dt = 0 while the spring is engaged, M = −J ω² θ_k there (no gravity).
    t = J0.times(4096)
    th, _, _ = J0.trajectory(t)
    tau = J0.motor_torque(t, J0.k_M(), gravity=False)
    on = th > J0.theta_k
    np.testing.assert_allclose(tau[on], -J0.J * 4 * J0.theta_k, rtol=1e-12)


def test_spring_is_conservative_over_a_period_and_eq21_is_affine_in_k():
    # Eq. 20 over a whole period: zero net motor work for any stiffness, with or without gravity.
    e = J0.energy(np.array([0.0, J0.k_M(), 30.0]), 0.0, J0.period, gravity=True, n=40001)
    np.testing.assert_allclose(e, 0.0, atol=1e-9)
    # Eq. 21 from contact to the turning point is affine in k, slope ½ α (A − θ_k)² > 0.
    tk, tq = J0.contact_time(), math.pi / 4
    e0, e1 = J0.energy(np.array([0.0, 1.0]), tk, tq, gravity=False, n=200001)
    assert e1 - e0 == pytest.approx(0.5 * 1.05 * (0.3 - J0.theta_k) ** 2, rel=1e-6)


def test_bad_input():
    with pytest.raises(InvalidParameterError, match="never engages"):
        PaperJoint(amplitude=0.1)  # θ_k = 0.1278 rad
    with pytest.raises(InvalidParameterError, match="never engages"):
        PaperJoint(amplitude=J0.theta_k)
    with pytest.raises(InvalidParameterError, match="omega"):
        PaperJoint(omega=0.0)
    with pytest.raises(InvalidParameterError, match="omega"):
        PaperJoint(omega=-2.0)
    with pytest.raises(InvalidParameterError, match="alpha"):
        PaperJoint(alpha=0.0)
    with pytest.raises(InvalidParameterError, match="nan"):
        PaperJoint(mass=float("nan"))
    with pytest.raises(InvalidParameterError, match="posture"):
        PaperJoint(posture="sideways")
    with pytest.raises(InvalidParameterError, match="k"):
        J0.motor_torque(J0.times(16), -1.0)
    with pytest.raises(InvalidParameterError, match="t"):
        J0.trajectory(np.array([0.0, np.nan]))
    with pytest.raises(HexalegError):
        PaperJoint(offset=0.1).closed_form_int_sq()
