"""Tests of the pages' angle format (hexaleg.outputs.angles)."""

from __future__ import annotations

import math

import pytest

from hexaleg.outputs.angles import format_degrees


def test_degrees_never_read_minus_zero():
    assert format_degrees(-1e-9) == "+0.0°"
    assert format_degrees({"value": math.radians(-12.79), "unit": "rad"}) == "-12.8°"
    with pytest.raises(ValueError, match="not an angle in rad"):
        format_degrees({"value": 1.0, "unit": "deg"})


def test_an_unsigned_angle_has_no_sign_and_a_missing_one_reads_a_dash():
    assert format_degrees(math.radians(31.34), signed=False) == "31.3°"
    assert format_degrees(None) == "—" and format_degrees({"value": None, "unit": "rad"}) == "—"
