"""Tests of hexaleg.robot.brushless: the ODRI module of Solo-12 from its documented figures, and
the reasons the registry's other brushless actuators are not in the catalogue."""

from __future__ import annotations

import math

import pytest

from hexaleg.robot.catalogue import CATALOGUE, motor


def test_brushless_module_holds_odri_and_names_the_unsourced_registry_actuators() -> None:
    """odri_actuator lives in hexaleg.robot.brushless and is re-exported by the catalogue; that
    module says, for every registry robot left with a generic actuator, why its real one is not
    in the catalogue."""
    from hexaleg.robot import brushless, catalogue
    from hexaleg.robot.registry import DESCRIPTIONS

    assert catalogue.odri_actuator is brushless.odri_actuator
    assert CATALOGUE["ODRI-4004"] == brushless.odri_actuator()
    doc = brushless.__doc__ or ""
    generic = [name for name, d in DESCRIPTIONS.items() if d.motor is None]
    assert sorted(generic) == ["anymal", "anymal_c", "go2"]
    for name in (*generic, "a1"):  # a1: its model is in the catalogue, its motor still not
        assert f"``{name}``" in doc, name
    for actuator in ("A1 joint motor", "GO-M8010-6", "ANYdrive"):
        assert actuator in doc, actuator


def test_odri_actuator_hand_values() -> None:
    """Solo-12's module: 2.5 N·m at 12 A through 9 : 1; copper loss (3/2) R_s i² with
    R_s = 0.23255 Ω; 300 rpm/V at 24 V through 9 : 1."""
    m = motor("odri-4004")
    assert m.current(2.5) == pytest.approx(12.0)
    assert m.joule_power(2.5) == pytest.approx(1.5 * 0.23255 * 12.0**2)
    assert m.joule_coefficient == pytest.approx(1.5 * 0.23255 / (2.5 / 12) ** 2)
    assert m.no_load_speed == pytest.approx(800 * 2 * math.pi / 60)
    assert "open_robot_actuator_hardware" in m.source and "assumed" in m.source
    assert "Assumed" in m.notes and "24 V" in m.notes and "0.9" in m.notes
