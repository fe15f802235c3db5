"""Tests of hexaleg.robot.motor: the power model's physics, convexity, the actuator built from URDF
limits, errors. The catalogue's entries are tested in test_catalogue.py."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import hexaleg.robot.catalogue as catalogue
import hexaleg.robot.motor as motor_module
from hexaleg.errors import HexalegError, InvalidParameterError
from hexaleg.robot.catalogue import motor
from hexaleg.robot.motor import (
    GENERIC_EFFICIENCY_RANGE,
    GENERIC_GEARBOX_EFFICIENCY,
    GENERIC_VOLTAGE,
    Motor,
    from_datasheet,
    generic_actuator,
    generic_energy_range,
)


def ideal(eta: float = 1.0, regeneration: bool = True) -> Motor:
    return dataclasses.replace(motor("AX-18A"), gearbox_efficiency=eta, regeneration=regeneration)


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
    ("regeneration", 1), ("name", ""), ("source", "  "), ("notes", 3), ("notes", None),
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


def test_notes_default_to_empty_and_existing_calls_still_work() -> None:
    """``notes`` is the one field with a default: positional and keyword construction as before."""
    fields = [f for f in dataclasses.fields(Motor) if f.name != "notes"]
    m = Motor(*(getattr(motor("AX-18A"), f.name) for f in fields))
    assert m.notes == "" and m.joule_coefficient == motor("AX-18A").joule_coefficient


def test_from_datasheet_states_what_it_derived() -> None:
    """Hand values: 2 N·m at 1 A and 12 V, 50 rpm → k_t G = 2 N·m/A, R = 12 Ω,
    η = 2 N·m · 50 rpm / (12 V · 1 A) = 0.873."""
    m = from_datasheet("X", gear_ratio=100.0, stall_torque=2.0, stall_current=1.0,
                       no_load_speed_rpm=50.0, voltage=12.0, source="sheet", notes="Variant B.")
    assert m.torque_constant * m.gear_ratio == pytest.approx(2.0)
    assert m.resistance == pytest.approx(12.0)
    assert m.gearbox_efficiency == pytest.approx(2.0 * 50 * 2 * math.pi / 60 / 12.0)
    assert m.notes.startswith("Variant B. Derived")
    for text in ("k_t G = τ_s / I_s = 2.000 N·m/A", "R = V / I_s = 12.00 Ω", "η = "):
        assert text in m.notes

    with pytest.raises(AttributeError, match="no_such_name"):
        motor_module.no_such_name  # noqa: B018


# An actuator from URDF limits: the stall torque is the effort limit and the no-load speed the
# velocity limit, through the model's own DC-motor relations (checked below from R, k_t G and η,
# not from the fields that merely store them).
URDF_LIMITS = [(1.8, 97 * 2 * math.pi / 60), (2.5, 83.8), (33.5, 21.0), (80.0, 7.5)]


@pytest.mark.parametrize("effort, velocity", URDF_LIMITS)
def test_generic_actuator_reproduces_the_urdf_limits(effort: float, velocity: float) -> None:
    m = generic_actuator(effort, velocity)
    v, kt_g, eta = m.voltage, m.torque_constant * m.gear_ratio, m.gearbox_efficiency
    assert m.stall_torque == effort and m.no_load_speed == velocity
    # Stall: the full voltage across R drives I_s = V / R, which gives the effort limit ...
    assert (v / m.resistance) * kt_g == pytest.approx(effort, rel=1e-12)
    assert m.current(effort) == pytest.approx(v / m.resistance, rel=1e-12)
    assert m.electrical_power(effort, 0.0) == pytest.approx(v * v / m.resistance, rel=1e-12)
    # ... no load: the back-EMF k_e G ω_0 = (k_t G / η) ω_0 equals V at the velocity limit.
    assert v / (kt_g / eta) == pytest.approx(velocity, rel=1e-12)
    # η is the one from_datasheet would derive from these stall and no-load figures.
    assert effort * velocity / (v * v / m.resistance) == pytest.approx(eta, rel=1e-12)


def test_generic_actuator_hand_values_and_assumptions() -> None:
    """2.5 N·m, 84 rad/s, V = 24 V, η = 0.7: k_t G = 0.7 · 24 / 84 = 0.2 N·m/A, I_s = 12.5 A,
    R = 1.92 Ω, c = 84 / (0.7 · 2.5) = 48 W/(N·m)²."""
    assert (GENERIC_VOLTAGE, GENERIC_GEARBOX_EFFICIENCY) == (24.0, 0.7)
    m = generic_actuator(2.5, 84.0, name="solo-knee")
    assert m.name == "solo-knee" and not m.regeneration
    assert m.torque_constant * m.gear_ratio == pytest.approx(0.2)
    assert m.current(2.5) == pytest.approx(12.5)
    assert m.resistance == pytest.approx(1.92)
    assert m.joule_coefficient == pytest.approx(48.0)
    assert "URDF" in m.source and "2.5 N·m" in m.source and "84 rad/s" in m.source
    for text in ("stall torque", "no-load speed", "24 V", "η = 0.7", "G = 1", "no regeneration",
                 "Verstraten", "12.5 A", "1.92 Ω", "48 W/(N·m)²"):
        assert text in m.notes, text


def test_generic_joule_coefficient_does_not_depend_on_the_assumed_voltage(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """c = ω_0 / (η τ_s): the reference voltage scales current and R only."""
    base = generic_actuator(3.0, 10.0)
    monkeypatch.setattr(motor_module, "GENERIC_VOLTAGE", 48.0)
    other = generic_actuator(3.0, 10.0)
    assert other.voltage == 48.0 and other.resistance == pytest.approx(4 * base.resistance)
    assert other.joule_coefficient == pytest.approx(base.joule_coefficient, rel=1e-12)
    tau, qdot = np.linspace(-3, 3, 13), np.linspace(10, -10, 13)
    np.testing.assert_allclose(other.electrical_power(tau, qdot), base.electrical_power(tau, qdot))


@pytest.mark.parametrize("effort, velocity, bad", [
    (0.0, 5.0, "effort"), (-1.0, 5.0, "effort"), (float("nan"), 5.0, "effort"),
    (float("inf"), 5.0, "effort"), ("2", 5.0, "effort"), (True, 5.0, "effort"),
    (None, 5.0, "effort"), (2.0, 0.0, "velocity"), (2.0, -3.0, "velocity"),
    (2.0, float("inf"), "velocity"), (2.0, float("nan"), "velocity"),
])
def test_generic_actuator_refuses_bad_limits(effort: object, velocity: object, bad: str) -> None:
    with pytest.raises(InvalidParameterError) as e:
        generic_actuator(effort, velocity, name="LF_knee")  # type: ignore[arg-type]
    text = str(e.value)
    assert f"LF_knee: URDF {bad} limit" in text and "allowed: a finite number > 0" in text
    assert repr(effort if bad == "effort" else velocity) in text


def test_generic_actuator_needs_a_name() -> None:
    with pytest.raises(InvalidParameterError, match=r"Motor\.name"):
        generic_actuator(1.0, 1.0, name=" ")


def test_the_generic_efficiency_sits_among_the_catalogue_servos() -> None:
    """GENERIC_GEARBOX_EFFICIENCY's docstring: the servos' datasheet-derived η span 0.43–0.86,
    median about 0.63 (the brushless entries' η is assumed or from a paper's gearbox figure,
    and the A1 model has none: not derived from stall figures);
    GENERIC_EFFICIENCY_RANGE is
    that span, and generic_energy_range the factors 0.7/0.86 and 0.7/0.43 it implies."""
    etas = [m.gearbox_efficiency for m in catalogue.CATALOGUE.values()
            if m.name not in ("ODRI-4004", "ODRI-4004-RAL2020", "A1-Yang2021")
            and not m.name.startswith(("MiniCheetah", "Cheetah3"))]
    assert (min(etas), max(etas)) == (pytest.approx(0.43, abs=5e-3), pytest.approx(0.86, abs=5e-3))
    assert float(np.median(etas)) == pytest.approx(0.63, abs=5e-3)
    assert GENERIC_EFFICIENCY_RANGE == (round(min(etas), 2), round(max(etas), 2))
    assert generic_energy_range() == (pytest.approx(0.7 / 0.86), pytest.approx(0.7 / 0.43))
    notes = generic_actuator(33.5, 21.0).notes
    assert "×0.81–×1.63" in notes and "hexaleg motors" in notes
    assert min(etas) < GENERIC_GEARBOX_EFFICIENCY < max(etas)
