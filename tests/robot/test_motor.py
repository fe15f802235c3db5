"""Tests of hexaleg.robot.motor: datasheet reproduction, the power model's physics, convexity,
errors."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from hexaleg.errors import ConfigError, HexalegError, InvalidParameterError, UnknownNameError
from hexaleg.robot.motor import (
    CATALOGUE,
    DEFAULT_MOTOR,
    RPM,
    Motor,
    catalogue_table,
    from_datasheet,
    motor,
    motor_from_mapping,
)

# ROBOTIS e-Manual figures at 12 V: gear ratio, stall torque N·m, stall current A, no-load rpm.
DATASHEET = {
    "AX-12A": (254.0, 1.5, 1.5, 59.0),
    "AX-18A": (254.0, 1.8, 2.2, 97.0),
    "MX-28": (193.0, 2.5, 1.4, 55.0),
    "XM540-W150": (152.3, 7.3, 4.4, 53.0),
    "XM540-W270": (272.5, 10.6, 4.4, 30.0),
}


def ideal(eta: float = 1.0, regeneration: bool = True) -> Motor:
    return dataclasses.replace(motor("AX-18A"), gearbox_efficiency=eta, regeneration=regeneration)


def test_catalogue_matches_datasheets() -> None:
    assert set(CATALOGUE) == set(DATASHEET) | {"ODRI-4004"}
    for name, (ratio, tau_s, i_s, rpm) in DATASHEET.items():
        m = motor(name)
        assert m.gear_ratio == ratio
        assert m.stall_torque == tau_s
        assert m.no_load_speed == pytest.approx(rpm * 2 * math.pi / 60)
        assert "ROBOTIS e-Manual" in m.source and name in m.source
        # Stall: the model draws exactly the datasheet current and V·I at zero speed.
        assert m.current(tau_s) == pytest.approx(i_s)
        assert m.electrical_power(tau_s, 0.0) == pytest.approx(12.0 * i_s)
        # Efficiency from the torque-speed line is a physical efficiency.
        assert 0 < m.gearbox_efficiency <= 1
        assert m.gearbox_efficiency == pytest.approx(tau_s * rpm * RPM / (12.0 * i_s))


def test_odri_actuator_hand_values() -> None:
    """Solo-12's module: 2.5 N·m at 12 A through 9 : 1; copper loss (3/2) R_s i² with
    R_s = 0.23255 Ω; 300 rpm/V at 24 V through 9 : 1."""
    m = motor("odri-4004")
    assert m.current(2.5) == pytest.approx(12.0)
    assert m.joule_power(2.5) == pytest.approx(1.5 * 0.23255 * 12.0**2)
    assert m.joule_coefficient == pytest.approx(1.5 * 0.23255 / (2.5 / 12) ** 2)
    assert m.no_load_speed == pytest.approx(800 * 2 * math.pi / 60)
    assert "open_robot_actuator_hardware" in m.source and "assumed" in m.source


def test_ax18a_hand_values() -> None:
    m = motor(DEFAULT_MOTOR)
    # R = 12 V / 2.2 A, k_t G = 1.8 / 2.2 N·m/A, c = R / (k_t G)² = 12·2.2 / 1.8² W/(N·m)².
    assert m.resistance == pytest.approx(12 / 2.2)
    assert m.torque_constant * m.gear_ratio == pytest.approx(1.8 / 2.2)
    assert m.joule_coefficient == pytest.approx(12 * 2.2 / 1.8**2)
    assert m.gearbox_efficiency == pytest.approx(1.8 * 97 * 2 * math.pi / 60 / (12 * 2.2))
    assert not m.regeneration


def test_default_motor_is_the_robot_joint_limit() -> None:
    from hexaleg.robot.model import load_robot

    robot = load_robot()
    m = motor(DEFAULT_MOTOR)
    idx = [robot.model.joints[robot.model.getJointId(n)].idx_v for n in robot.joint_names]
    np.testing.assert_allclose(robot.model.effortLimit[idx], m.stall_torque)
    np.testing.assert_allclose(robot.model.velocityLimit[idx], m.no_load_speed, rtol=1e-6)


def test_lookup_is_case_insensitive_and_unknown_lists_names() -> None:
    assert motor("ax-18a") is CATALOGUE["AX-18A"]
    with pytest.raises(UnknownNameError) as e:
        motor("AX-99")
    for name in CATALOGUE:
        assert name in str(e.value)


def test_ideal_gearbox_power_is_mechanical_plus_joule() -> None:
    rng = np.random.default_rng(0)
    tau, qdot = rng.normal(size=(50, 18)), rng.normal(size=(50, 18)) * 5
    m = ideal()
    np.testing.assert_allclose(m.electrical_power(tau, qdot),
                               tau * qdot + m.joule_coefficient * tau**2, rtol=1e-12)
    np.testing.assert_allclose(m.joule_power(tau), m.resistance * m.current(tau) ** 2)


def test_gearbox_efficiency_motoring_and_backdriving() -> None:
    m = ideal(eta=0.5)
    c = m.joule_coefficient
    # Motoring: the motor supplies twice the joint power; back-driven: it receives half.
    assert m.electrical_power(2.0, 3.0) == pytest.approx(6.0 / 0.5 + c * 4)
    assert m.electrical_power(2.0, -3.0) == pytest.approx(-6.0 * 0.5 + c * 4)
    assert m.electrical_power(-2.0, 3.0) == pytest.approx(-6.0 * 0.5 + c * 4)
    assert m.gearbox_input_power(0.0, 3.0) == 0.0


def test_power_bounds_second_law() -> None:
    rng = np.random.default_rng(1)
    tau, qdot = rng.normal(size=(200, 6)), rng.normal(size=(200, 6)) * 10
    for eta in (1.0, 0.7, 0.3):
        m = ideal(eta)
        with_regen = m.electrical_power(tau, qdot, regeneration=True)
        without = m.electrical_power(tau, qdot, regeneration=False)
        # Electrical input never falls below the mechanical output (no free energy) ...
        assert np.all(with_regen >= tau * qdot - 1e-12)
        # ... and without regeneration the drawn power is non-negative and ≥ with regeneration.
        assert np.all(without >= 0) and np.all(without >= with_regen)
        np.testing.assert_array_equal(without, np.maximum(with_regen, 0))


@pytest.mark.parametrize("regeneration", [True, False])
@pytest.mark.parametrize("eta", [1.0, 0.6])
def test_electrical_power_is_convex_in_torque(eta: float, regeneration: bool) -> None:
    m = ideal(eta)
    rng = np.random.default_rng(2)
    qdot = rng.normal(size=1000) * 5
    a, b = rng.normal(size=1000) * 2, rng.normal(size=1000) * 2
    lam = rng.uniform(size=1000)
    lhs = m.electrical_power(lam * a + (1 - lam) * b, qdot, regeneration)
    rhs = (lam * m.electrical_power(a, qdot, regeneration)
           + (1 - lam) * m.electrical_power(b, qdot, regeneration))
    assert np.all(lhs <= rhs + 1e-12)


def test_default_regeneration_flag() -> None:
    assert ideal(regeneration=False).electrical_power(1.0, -100.0) == 0.0
    assert ideal(regeneration=True).electrical_power(1.0, -100.0) < 0.0


@pytest.mark.parametrize("field, value", [
    ("gear_ratio", 0.0), ("gear_ratio", -3.0), ("torque_constant", 0.0),
    ("resistance", 0.0), ("resistance", -1.0), ("resistance", float("nan")),
    ("stall_torque", 0.0), ("no_load_speed", -1.0), ("voltage", float("inf")),
    ("gearbox_efficiency", 0.0), ("gearbox_efficiency", 1.2), ("gearbox_efficiency", -0.5),
    ("regeneration", 1), ("name", ""), ("source", "  "),
])
def test_bad_parameters_are_named(field: str, value: object) -> None:
    with pytest.raises(InvalidParameterError) as e:
        dataclasses.replace(motor("AX-18A"), **{field: value})
    assert f"Motor.{field}" in str(e.value) and "allowed" in str(e.value)


def test_inconsistent_datasheet_is_refused() -> None:
    # XC430-W150 figures (e-Manual: 1.6 N·m at 1.4 A, 106 rpm at 12 V) imply η > 1.
    with pytest.raises(InvalidParameterError, match="gearbox_efficiency"):
        from_datasheet("XC430-W150", gear_ratio=159.59, stall_torque=1.6, stall_current=1.4,
                       no_load_speed_rpm=106.0, voltage=12.0, source="ROBOTIS e-Manual")


def test_bad_arrays() -> None:
    m = motor()
    with pytest.raises(InvalidParameterError, match=r"tau.*index \(1, 0\)"):
        m.electrical_power([[1.0], [float("nan")]], [[0.0], [0.0]])
    with pytest.raises(InvalidParameterError, match="qdot"):
        m.electrical_power(np.zeros((3, 2)), np.zeros((3, 1)))
    with pytest.raises(HexalegError):
        m.current([1.0, float("inf")])


def test_motor_from_mapping() -> None:
    m = motor_from_mapping({"base": "AX-18A", "resistance": 3.0, "regeneration": True})
    assert m.resistance == 3.0 and m.regeneration and m.gear_ratio == 254.0
    assert "resistance" in m.source
    assert m.joule_coefficient == pytest.approx(3.0 * (2.2 / 1.8) ** 2)
    full = {f.name: getattr(m, f.name) for f in dataclasses.fields(Motor)}
    assert motor_from_mapping(full) == m
    with pytest.raises(UnknownNameError, match="resistance"):
        motor_from_mapping({"base": "AX-18A", "resistence": 3.0})
    with pytest.raises(ConfigError, match="missing keys"):
        motor_from_mapping({"name": "x", "gear_ratio": 100.0})
    with pytest.raises(ConfigError, match="resistance"):
        motor_from_mapping({"base": "AX-18A", "resistance": "3 ohm"})
    with pytest.raises(InvalidParameterError, match="gearbox_efficiency"):
        motor_from_mapping({"base": "AX-18A", "gearbox_efficiency": 1.5})


def test_catalogue_table_lists_every_motor_and_its_datasheet() -> None:
    text = catalogue_table()
    for name, m in CATALOGUE.items():
        row = next(line for line in text.splitlines() if line.startswith(name + " "))
        assert f"{m.joule_coefficient:.3f}" in row and f"{m.gearbox_efficiency:.3f}" in row
        assert f"{name}: {m.source}" in text
    assert "AX-12A" not in catalogue_table({"AX-18A": motor("AX-18A")})
