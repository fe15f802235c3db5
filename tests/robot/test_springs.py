"""Tests of hexaleg.robot.springs: the dead-zone spring law (paper eq. 7–8) and spring sets."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hexaleg.errors import ConfigError, HexalegError, InvalidParameterError, UnknownNameError
from hexaleg.robot.model import load_robot
from hexaleg.robot.springs import DeadZoneSpring, SpringSet


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


def test_spring_set_torques_columns(robot):
    femur = DeadZoneSpring(10.0, theta_k=0.1)
    tibia = DeadZoneSpring(4.0, theta_k=0.05, k2=0.5, damping=0.2)
    springs = SpringSet({"LF_femur": femur, "RH_tibia": tibia})
    T = 5
    q = np.tile(robot.pose("stand"), (T, 1))
    q[:, 7:] += np.linspace(0, 0.4, T)[:, None]
    v = np.ones((T, robot.model.nv))
    tau = springs.torques(robot, q, v)
    assert tau.shape == (T, robot.nj)
    cf, ct = robot.column("LF_femur"), robot.column("RH_tibia")
    np.testing.assert_allclose(tau[:, cf], femur.torque(q[:, 7 + cf], v[:, 6 + cf]))
    np.testing.assert_allclose(tau[:, ct], tibia.torque(q[:, 7 + ct], v[:, 6 + ct]))
    others = np.delete(tau, [cf, ct], axis=1)
    assert np.all(others == 0)
    e = springs.energies(robot, q)
    assert e.shape == (T, robot.nj)
    np.testing.assert_allclose(e[:, cf], femur.energy(q[:, 7 + cf]))
    # Empty set and a spring on every joint both work.
    assert np.all(SpringSet().torques(robot, q) == 0)
    full = SpringSet({j: femur for j in robot.joint_names})
    assert full.torques(robot, q).shape == (T, robot.nj)


def test_spring_set_errors(robot):
    q = np.tile(robot.pose("zero"), (2, 1))
    with pytest.raises(UnknownNameError, match="LF_femur") as e:
        SpringSet({"LF_knee": DeadZoneSpring(1.0, theta_k=0.1)}).torques(robot, q)
    assert "LF_knee" in str(e.value)
    with pytest.raises(InvalidParameterError, match=r"q\.shape"):
        SpringSet().torques(robot, q[:, :10])
    bad = q.copy()
    bad[1, 9] = np.nan
    with pytest.raises(InvalidParameterError, match="nan"):
        SpringSet().energies(robot, bad)
    with pytest.raises(InvalidParameterError):
        SpringSet({"LF_femur": 3.0})  # type: ignore[dict-item]


def test_spring_set_from_toml_table():
    s = SpringSet.from_mapping({"LF_femur": {"stiffness": 20, "theta_k": 0.12, "alpha": 1.05}})
    assert s["LF_femur"].stiffness == 20.0 and s["LF_femur"].theta_k == 0.12
    with pytest.raises(UnknownNameError, match="stiffness"):
        SpringSet.from_mapping({"LF_femur": {"stifness": 20}})
    with pytest.raises(ConfigError):
        SpringSet.from_mapping({"LF_femur": {"stiffness": "hard", "theta_k": 0.1}})


def test_spring_on_continuous_joint_uses_its_angle(tmp_path):
    # A continuous joint stores (cos θ, sin θ) in q; the spring must see θ.
    from hexaleg.robot.model import LegSpec

    inertial = ('<inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" '
                'iyz="0" izz="1e-4"/></inertial>')
    urdf = tmp_path / "one.urdf"
    urdf.write_text(
        f'<robot name="one"><link name="base">{inertial}</link><link name="arm">{inertial}</link>'
        '<link name="foot"/><joint name="j" type="continuous"><parent link="base"/>'
        '<child link="arm"/><axis xyz="0 0 1"/></joint><joint name="f" type="fixed">'
        '<parent link="arm"/><child link="foot"/><origin xyz="0.1 0 0"/></joint></robot>')
    one = load_robot(urdf, legs=[LegSpec("L", ("j",), "foot")], joint_kinds=("j",))
    assert one.model.nq == 9 and one.nj == 1
    theta = np.array([0.05, 0.5, -0.7])
    q = np.zeros((3, 9))
    q[:, 6] = 1.0  # identity base quaternion
    q[:, 7], q[:, 8] = np.cos(theta), np.sin(theta)
    s = DeadZoneSpring(2.0, theta_k=0.1)
    springs = SpringSet({"j": s})
    np.testing.assert_allclose(springs.torques(one, q)[:, 0], s.torque(theta))
    np.testing.assert_allclose(springs.energies(one, q)[:, 0], s.energy(theta))
