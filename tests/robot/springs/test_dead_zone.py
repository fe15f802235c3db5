"""Tests of hexaleg.robot.springs.dead_zone: the dead-zone spring law (paper eq. 7–8, 14)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hexaleg.errors import HexalegError, InvalidParameterError
from hexaleg.robot.springs import DeadZoneSpring


def _asym() -> DeadZoneSpring:
    return DeadZoneSpring(stiffness=3.0, theta_minus=-0.3, theta_plus=0.1, stiffness_minus=7.0,
                          k2=0.2, alpha=1.3, damping=0.05, neutral=0.4)


@pytest.mark.parametrize("convention", ["eq7", "eq14"])
def test_torque_is_minus_gradient_of_energy(convention):
    s = DeadZoneSpring(stiffness=3.0, theta_minus=-0.3, theta_plus=0.1, stiffness_minus=7.0,
                       k2=0.2, alpha=1.3, neutral=0.4, convention=convention)
    q = np.linspace(-1.0, 1.5, 2001) + 1.234e-5  # off the kinks at the contact angles
    h = 1e-6
    fd = -(s.energy(q + h) - s.energy(q - h)) / (2 * h)
    np.testing.assert_allclose(s.elastic_torque(q), fd, atol=1e-7)


def test_dead_zone_torque_is_exactly_zero():
    s = DeadZoneSpring(stiffness=50.0, theta_k=0.2, alpha=1.05, damping=2.0, neutral=0.1)
    q = np.linspace(-0.1, 0.3, 101)  # neutral ± theta_k, boundaries included
    assert np.all(s.torque(q, np.full_like(q, 3.0)) == 0.0)
    assert np.all(s.energy(q) == 0.0)
    assert not s.engaged(q).any()
    assert s.engaged(np.array([-0.1001, 0.3001])).all()


def test_conservative_part_does_zero_net_work_over_a_closed_cycle():
    s = _asym()
    t = np.linspace(0.0, 2 * np.pi, 20001)
    q = 0.4 + 0.6 * np.sin(t) + 0.2 * np.sin(3 * t + 0.5)  # closed, irregular path
    qdot = 0.6 * np.cos(t) + 0.6 * np.cos(3 * t + 0.5)
    power = s.elastic_torque(q) * qdot
    work = np.trapezoid(power, t)
    # The spring did work while it was engaged, but it all came back.
    assert np.trapezoid(np.abs(power), t) > 1.0
    assert abs(work) < 1e-6
    # Damping only dissipates.
    damp = (s.torque(q, qdot) - s.elastic_torque(q)) * qdot
    assert np.all(damp <= 0) and np.trapezoid(damp, t) < 0


def test_asymmetric_contact_angles_and_stiffnesses():
    s = DeadZoneSpring(stiffness=3.0, theta_minus=-0.3, theta_plus=0.1, stiffness_minus=7.0,
                       alpha=1.0, neutral=0.4)
    # 0.2 rad past θ⁺ = 0.5 rad and 0.2 rad past θ⁻ = 0.1 rad.
    assert s.torque(0.7) == pytest.approx(-3.0 * 0.2)
    assert s.torque(-0.1) == pytest.approx(+7.0 * 0.2)
    assert s.energy(0.7) == pytest.approx(0.5 * 3.0 * 0.04)
    assert s.energy(-0.1) == pytest.approx(0.5 * 7.0 * 0.04)
    # Restoring: the torque always pushes back toward the dead zone.
    q = np.linspace(-1, 1.5, 501)
    assert np.all(s.elastic_torque(q) * (q - 0.4) <= 0)


def test_alpha_conventions():
    k, a, th = 20.0, 1.05, 0.12
    e7 = DeadZoneSpring(k, theta_k=th, alpha=a)
    e14 = DeadZoneSpring(k, theta_k=th, alpha=a, convention="eq14")
    q = 0.3
    # eq. 7: U = ½ k (α Δ)², torque = −k α² Δ; eq. 14: torque = −k α Δ (the paper's M_k term).
    assert e7.energy(q) == pytest.approx(0.5 * k * (a * (q - th)) ** 2)
    assert e7.torque(q) == pytest.approx(-k * a**2 * (q - th))
    assert e14.torque(q) == pytest.approx(-k * a * (q - th))
    assert e14.torque(-q) == pytest.approx(+k * a * (q - th))  # symmetric: −kα(θ + θ_k) below
    # An eq14 spring of stiffness k is the eq7 spring of stiffness k/α.
    qs = np.linspace(-0.5, 0.5, 51)
    np.testing.assert_allclose(e14.torque(qs), DeadZoneSpring(k / a, theta_k=th, alpha=a)
                               .torque(qs), rtol=1e-13, atol=0)


def test_torque_basis_is_linear_decomposition():
    s = _asym()
    q = np.linspace(-1, 1.5, 303).reshape(3, 101)
    v = np.cos(q)
    b = s.torque_basis(q, v)
    recon = s.stiffness * b.plus + s.k_minus * b.minus + s.k2 * b.k2 + s.damping * b.damping
    np.testing.assert_allclose(recon, s.torque(q, v), rtol=0, atol=1e-15)
    assert recon.shape == q.shape
    assert np.all(b.plus[q < 0.5] == 0) and np.all(b.minus[q > 0.1] == 0)


def test_paper_units_round_trip_table4():
    # Table 4: k₁ = 400 N·mm/deg, damping 1 N·mm·s/deg; Section 4.2: θ_k = 7.32°.
    s = DeadZoneSpring.from_paper(400.0, 7.32, 1.05, damping_nmms_per_deg=1.0)
    assert s.stiffness == pytest.approx(400.0 * 1e-3 * 180 / math.pi)  # 22.918 N·m/rad
    assert s.damping == pytest.approx(1e-3 * 180 / math.pi)
    assert s.theta_k == pytest.approx(7.32 * math.pi / 180)
    # 10° past contact at α = 1 gives 400 N·mm/deg × 10° = 4 N·m.
    s1 = DeadZoneSpring.from_paper(400.0, 7.32)
    assert s1.torque(math.radians(17.32)) == pytest.approx(-4.0)


def test_bad_input():
    with pytest.raises(InvalidParameterError, match="stiffness"):
        DeadZoneSpring(-1.0, theta_k=0.1)
    with pytest.raises(InvalidParameterError, match="k2"):
        DeadZoneSpring(1.0, theta_k=0.1, k2=-0.1)
    with pytest.raises(InvalidParameterError, match="theta_minus"):
        DeadZoneSpring(1.0, theta_minus=0.2, theta_plus=0.1)
    with pytest.raises(InvalidParameterError, match="theta_minus"):
        DeadZoneSpring(1.0)
    with pytest.raises(InvalidParameterError, match="alpha"):
        DeadZoneSpring(1.0, theta_k=0.1, alpha=0.0)
    with pytest.raises(InvalidParameterError, match="convention"):
        DeadZoneSpring(1.0, theta_k=0.1, convention="eq9")
    with pytest.raises(InvalidParameterError, match="nan"):
        DeadZoneSpring(float("nan"), theta_k=0.1)
    with pytest.raises(InvalidParameterError, match="q"):
        DeadZoneSpring(1.0, theta_k=0.1).torque(np.array([0.0, np.nan]))
    with pytest.raises(InvalidParameterError, match="v"):
        DeadZoneSpring(1.0, theta_k=0.1).torque(np.zeros(3), np.array([0.0, np.inf, 0.0]))
    with pytest.raises(HexalegError):
        DeadZoneSpring.from_paper(float("nan"), 7.32)


def test_theta_k_zero_says_there_is_no_dead_zone_and_none_is_not_a_number():
    with pytest.raises(InvalidParameterError, match=r"theta_k = 0\.0; allowed: > 0 rad.*no dead "
                                                    r"zone at all.*LinearSpring"):
        DeadZoneSpring(stiffness=1.0, theta_k=0)
    assert DeadZoneSpring(stiffness=1.0, theta_k=0, theta_minus=-0.1, theta_plus=0.1).th_plus == 0.1
    for name in ("neutral", "k2", "alpha", "damping"):
        with pytest.raises(InvalidParameterError, match=rf"{name} = None"):
            DeadZoneSpring(stiffness=1.0, theta_k=0.1, **{name: None})


def test_many_laws_at_once_are_each_law_s_numbers_to_the_bit():
    """:func:`zone_basis` and :func:`zone_torque` with parameter arrays (one entry a law, as the
    optimal actuation's groups call them) give each law's own torque, with and without damping,
    exactly. The law calls them with its scalars, so this checks the array form: each entry
    computed from its own law's parameters alone (a formula that mixed entries, e.g. a
    ``max`` over the array or a parameter taken as a scalar, fails); the formula itself is
    checked against the energy above."""
    from hexaleg.robot.springs.dead_zone import zone_basis, zone_torque

    laws = [_asym(), DeadZoneSpring(0.3, theta_k=0.15, neutral=0.2, alpha=1.3, convention="eq14"),
            DeadZoneSpring(50.0, theta_k=0.2, alpha=1.05, damping=2.0, neutral=0.1)]
    rng = np.random.default_rng(3)
    q, v = rng.uniform(-1.0, 1.5, (400, len(laws))), rng.uniform(-3.0, 3.0, (400, len(laws)))

    def each(name):
        return np.array([getattr(s, name) for s in laws])

    neutral, minus, plus, a = each("neutral"), each("th_minus"), each("th_plus"), \
        each("transmission")
    coefficients = each("stiffness"), each("k_minus"), each("k2"), each("damping")
    for speed in (v, None):
        got = zone_torque(zone_basis(q - neutral, speed, minus, plus, a), *coefficients)
        for j, s in enumerate(laws):
            own = s.torque(q[:, j], None if speed is None else speed[:, j])
            assert got[:, j].tobytes() == own.tobytes()
