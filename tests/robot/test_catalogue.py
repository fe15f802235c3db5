"""Tests of hexaleg.robot.catalogue: every servo reproduces its datasheet figures through the model,
sources and notes, lookup, TOML overrides, the table, and docs/energy.md's copy of it."""

from __future__ import annotations

import dataclasses
import math
import re
from pathlib import Path

import numpy as np
import pytest

from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.robot.catalogue import (
    CATALOGUE,
    DEFAULT_MOTOR,
    KGF_CM,
    OUTPUT_HUBS,
    catalogue_table,
    motor,
    motor_from_mapping,
)
from hexaleg.robot.motor import Motor

RPM = 2 * math.pi / 60
EMANUAL = "https://emanual.robotis.com/docs/en/dxl/"

# The manufacturers' figures, typed in from the pages: URL, gear ratio, stall torque N·m, stall
# current A, no-load speed rad/s, all at 12 V.
DATASHEET = {
    "AX-12A": (EMANUAL + "ax/ax-12a/", 254.0, 1.5, 1.5, 59 * RPM),
    "AX-18A": (EMANUAL + "ax/ax-18a/", 254.0, 1.8, 2.2, 97 * RPM),
    "MX-28": (EMANUAL + "mx/mx-28-2/", 193.0, 2.5, 1.4, 55 * RPM),
    "XM540-W150": (EMANUAL + "x/xm540-w150/", 152.3, 7.3, 4.4, 53 * RPM),
    "XM540-W270": (EMANUAL + "x/xm540-w270/", 272.5, 10.6, 4.4, 30 * RPM),
    "XL430-W250": (EMANUAL + "x/xl430-w250/", 258.5, 1.5, 1.4, 61 * RPM),
    "XM430-W350": (EMANUAL + "x/xm430-w350/", 353.5, 4.1, 2.3, 46 * RPM),
    "MX-64": (EMANUAL + "mx/mx-64/", 200.0, 6.0, 4.1, 63 * RPM),
    "MX-106": (EMANUAL + "mx/mx-106/", 225.0, 8.4, 5.2, 45 * RPM),
    # Feetech: 30 kg·cm (kgf·cm, g_n = 9.80665 m/s²), 2.7 A, 0.222 s per 60°.
    "STS3215-C018": ("https://www.feetechrc.com/525603.html", 345.0, 30 * 9.80665e-2, 2.7,
                     (math.pi / 3) / 0.222),
}
VOLTAGE = 12.0

# TowerPro's figures: kgf·cm, s per 60°, stall current A, voltage V.
TOWERPRO = {"MG996R": (11.0, 0.14, 2.5, 6.0), "SG90": (1.8, 0.1, 0.65, 4.8)}


@pytest.mark.parametrize("name", TOWERPRO)
def test_towerpro_servo_reproduces_its_datasheet(name: str) -> None:
    """11 kgf·cm = 1.0787 N·m; 0.14 s/60° = (π/3)/0.14 rad/s; the model stalls at V/R with the
    datasheet's torque and runs free at the datasheet's speed; the source names the figures."""
    kgf_cm, s60, i_s, volts = TOWERPRO[name]
    m = motor(name)
    tau_s, omega_0 = kgf_cm * 9.80665e-2, (math.pi / 3) / s60
    kt_g, eta = m.torque_constant * m.gear_ratio, m.gearbox_efficiency
    assert m.voltage == volts and m.gear_ratio == 1.0
    assert (volts / m.resistance) * kt_g == pytest.approx(tau_s, rel=1e-12)
    assert volts / (kt_g / eta) == pytest.approx(omega_0, rel=1e-12)
    assert m.current(tau_s) == pytest.approx(i_s, rel=1e-12)
    assert 0.4 < eta < 0.9  # within the span of the ROBOTIS and Feetech entries
    assert "TowerPro" in m.source and f"{kgf_cm:g} kgf·cm" in m.source
    assert f"{s60:g} s/60°" in m.source and "G = 1" in m.notes


def test_catalogue_holds_the_datasheet_servos_and_the_odri_module() -> None:
    assert set(CATALOGUE) == (set(DATASHEET) | {"ODRI-4004", "DSS-M15S", "A1-Yang2021"}
                              | set(TOWERPRO) | {"ODRI-4004-RAL2020", "MiniCheetah-hip",
                                                 "MiniCheetah-hip-Katz", "MiniCheetah-knee",
                                                 "Cheetah3-hip", "Cheetah3-knee"})
    assert KGF_CM == pytest.approx(9.80665 / 100)


def test_dss_m15s_reproduces_dfrobots_figures() -> None:
    """DFRobot wiki (SKU SER0044), 6 V: 11.5 kg·cm locking torque = 1.1278 N·m, stall current
    1.4 A, 0.18 s/60° = 55.56 rpm, gear ratio 310 : 1. Hand values: k_t G = 1.1278 / 1.4 =
    0.806 N·m/A, R = 6 / 1.4 = 4.29 Ω, η = 1.1278 · 5.818 / (6 · 1.4) = 0.781, c = 6.61 W/(N·m)²;
    the 7 V figures (12 kg·cm, 1.76 A, 0.16 s/60°) would give η = 0.625."""
    m = motor("dss-m15s")
    assert m.gear_ratio == 310.0 and m.voltage == 6.0 and not m.regeneration
    assert m.stall_torque == pytest.approx(1.1278, abs=1e-4)
    assert m.no_load_speed / RPM == pytest.approx(55.56, abs=5e-3)
    assert m.current(m.stall_torque) == pytest.approx(1.4, rel=1e-12)
    assert (6.0 / m.resistance) * m.torque_constant * m.gear_ratio == pytest.approx(
        m.stall_torque, rel=1e-12)  # stalled at V / R the model gives the datasheet torque
    assert m.torque_constant * m.gear_ratio == pytest.approx(0.806, abs=5e-4)
    assert m.resistance == pytest.approx(4.286, abs=5e-4)
    assert m.gearbox_efficiency == pytest.approx(0.781, abs=5e-4)
    assert m.joule_coefficient == pytest.approx(6.605, abs=5e-4)
    for figure in ("SER0044", "0.18 sec/60 degrees", "11.5 kg·cm", "1.4 A", "310:1", "6 V"):
        assert figure in m.source, figure
    assert "= 0.625" in m.notes and "no winding resistance" in m.notes
    hub = OUTPUT_HUBS["DSS-M15S"]
    assert hub.diameter == pytest.approx(5.8e-3) and "25T/5.80" in hub.source


@pytest.mark.parametrize("name", DATASHEET)
def test_servo_reproduces_its_datasheet_through_the_model(name: str) -> None:
    """At the rated voltage the model's stall torque and no-load speed are the datasheet's: with
    the rotor held the whole voltage drives I_s = V / R, whose torque is k_t G I_s; unloaded, the
    back-EMF (k_t G / η) ω_0 equals V. The stall current and power are the datasheet's too."""
    _, ratio, tau_s, i_s, omega_0 = DATASHEET[name]
    m = motor(name)
    kt_g, eta = m.torque_constant * m.gear_ratio, m.gearbox_efficiency
    assert m.voltage == VOLTAGE and m.gear_ratio == ratio
    assert (VOLTAGE / m.resistance) * kt_g == pytest.approx(tau_s, rel=1e-12)
    assert VOLTAGE / (kt_g / eta) == pytest.approx(omega_0, rel=1e-12)
    assert m.stall_torque == pytest.approx(tau_s, rel=1e-12)
    assert m.no_load_speed == pytest.approx(omega_0, rel=1e-12)
    assert m.current(tau_s) == pytest.approx(i_s, rel=1e-12)
    assert m.electrical_power(tau_s, 0.0) == pytest.approx(VOLTAGE * i_s, rel=1e-12)
    assert 0 < eta <= 1 and not m.regeneration


@pytest.mark.parametrize("name", DATASHEET)
def test_every_servo_names_its_page_and_figures_and_what_was_derived(name: str) -> None:
    url, ratio, tau_s, i_s, _ = DATASHEET[name]
    m = motor(name)
    assert url in m.source and "12 V" in m.source and f"{i_s:g} A" in m.source
    if name.startswith("STS"):
        assert "30 kg·cm" in m.source and "0.222 s/60°" in m.source and "Feetech" in m.source
    else:
        assert m.source.startswith(f"ROBOTIS e-Manual, {name} specifications")
        assert f"{ratio:g} : 1" in m.source and f"{tau_s:g} N·m" in m.source
    assert "no winding resistance" in m.notes
    assert f"R = V / I_s = {VOLTAGE / i_s:.2f} Ω" in m.notes
    assert f"k_t G = τ_s / I_s = {tau_s / i_s:.3f} N·m/A" in m.notes


def test_new_servos_hand_values() -> None:
    """XM430-W350 against the published cross-check (servos.md, Rhoban BAM at 12 V: k_t ≈ 1.78
    N·m/A at the output, R ≈ 5.2 Ω with the driver); STS3215: 30 kgf·cm = 2.942 N·m, 45.05 rpm."""
    xm = motor("XM430-W350")
    assert xm.torque_constant * xm.gear_ratio == pytest.approx(1.78, abs=0.005)
    assert xm.resistance == pytest.approx(5.2, abs=0.05)
    sts = motor("sts3215-c018")
    assert sts.stall_torque == pytest.approx(2.942, abs=5e-4)
    assert sts.no_load_speed / RPM == pytest.approx(45.05, abs=0.005)
    assert sts.gearbox_efficiency == pytest.approx(2.942 * 4.717 / (12 * 2.7), abs=1e-3)
    assert "7.4 V" in sts.notes and "345" in sts.notes
    xl = motor("XL430-W250")
    assert "11.1 V" in xl.notes  # the recommended voltage is named, the 12 V figures used


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
    assert motor(" mx-64 ") is CATALOGUE["MX-64"]
    with pytest.raises(UnknownNameError) as e:
        motor("AX-99")
    for name in CATALOGUE:
        assert name in str(e.value)


def test_motor_from_mapping() -> None:
    m = motor_from_mapping({"base": "AX-18A", "resistance": 3.0, "regeneration": True})
    assert m.resistance == 3.0 and m.regeneration and m.gear_ratio == 254.0
    assert "resistance" in m.source
    assert "Overridden in [motor]: regeneration, resistance" in m.notes
    assert m.joule_coefficient == pytest.approx(3.0 * (2.2 / 1.8) ** 2)
    full = {f.name: getattr(m, f.name) for f in dataclasses.fields(Motor)}
    assert motor_from_mapping(full) == m
    # Without a base every field is required but notes, which defaults to "".
    del full["notes"]
    assert motor_from_mapping(full).notes == ""
    assert motor_from_mapping({"base": "MX-64"}) == motor("MX-64")
    noted = motor_from_mapping({"base": "AX-18A", "voltage": 11.1, "notes": "bench, 3S"})
    assert noted.notes == "bench, 3S" and "voltage" in noted.source
    with pytest.raises(UnknownNameError, match="resistance"):
        motor_from_mapping({"base": "AX-18A", "resistence": 3.0})
    with pytest.raises(ConfigError, match="missing keys") as e:
        motor_from_mapping({"name": "x", "gear_ratio": 100.0})
    assert "notes" not in str(e.value).split("(or")[0]
    with pytest.raises(ConfigError, match="resistance"):
        motor_from_mapping({"base": "AX-18A", "resistance": "3 ohm"})
    with pytest.raises(ConfigError, match="notes"):
        motor_from_mapping({"base": "AX-18A", "notes": 3})
    with pytest.raises(InvalidParameterError, match="gearbox_efficiency"):
        motor_from_mapping({"base": "AX-18A", "gearbox_efficiency": 1.5})


def test_catalogue_table_lists_every_motor_its_datasheet_and_notes() -> None:
    text = catalogue_table()
    for name, m in CATALOGUE.items():
        row = next(line for line in text.splitlines() if line.startswith(name + " "))
        assert f"{m.joule_coefficient:.3f}" in row and f"{m.gearbox_efficiency:.3f}" in row
        assert f"{name}: {m.source}" in text
        assert f"{name} notes: {m.notes}" in text
    assert "AX-12A" not in catalogue_table({"AX-18A": motor("AX-18A")})
    bare = dataclasses.replace(motor("AX-18A"), notes="")
    assert "notes" not in catalogue_table({"AX-18A": bare})


def _docs_catalogue_rows() -> dict[str, list[str]]:
    """docs/energy.md's catalogue table: motor name → its cells."""
    page = (Path(__file__).resolve().parents[2] / "docs" / "energy.md").read_text()
    lines = page.split("### Catalogue", 1)[1].splitlines()
    start = next(i for i, line in enumerate(lines) if line.startswith("| motor |"))
    rows = {}
    for line in lines[start + 2:]:
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        rows[cells[0].replace("**", "").split()[0]] = cells[1:]
    return rows


def test_docs_catalogue_table_matches_the_catalogue() -> None:
    """Every entry is in docs/energy.md with the constants the code derives (as rounded there)."""
    rows = _docs_catalogue_rows()
    assert list(rows) == list(CATALOGUE)
    for name, m in CATALOGUE.items():
        g, kt_g, r, eta, c, tau_s, rpm = (float(re.sub(r"[*]", "", x)) for x in rows[name])
        assert g == m.gear_ratio, name
        assert kt_g == round(m.torque_constant * m.gear_ratio, 3), name
        assert r == round(m.resistance, 2), name
        assert eta == round(m.gearbox_efficiency, 3), name
        assert c == round(m.joule_coefficient, 3), name
        assert tau_s == pytest.approx(m.stall_torque, abs=5e-3), name
        assert rpm == round(m.no_load_speed / RPM), name


def test_every_catalogue_servo_states_its_output_hub_or_why_not():
    from hexaleg.robot.catalogue import output_hub

    assert set(OUTPUT_HUBS) == set(CATALOGUE)
    for name, hub in OUTPUT_HUBS.items():
        assert hub.source, name
        assert hub.diameter is None or 0 < hub.diameter < 0.05, name
        if hub.diameter is None:
            assert "not sourced" in hub.source, name
    assert output_hub("ax-18a") is OUTPUT_HUBS["AX-18A"]
    with pytest.raises(UnknownNameError):
        output_hub("HS-311")
