"""Tests of hexaleg.units: paper units ↔ SI."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hexaleg import units


def test_stiffness_conversion_by_hand():
    # 1 N·mm/deg = 1e-3 N·m per (π/180) rad = 0.18/π N·m/rad.
    assert units.nmm_per_deg_to_nm_per_rad(1.0) == pytest.approx(0.18 / math.pi, rel=1e-15)
    # Table 4: 400 N·mm/deg = 22.918 N·m/rad.
    assert units.nmm_per_deg_to_nm_per_rad(400.0) == pytest.approx(22.91831181, rel=1e-9)


@pytest.mark.parametrize(("fwd", "back", "x"), [
    (units.deg_to_rad, units.rad_to_deg, 7.32),
    (units.mm_to_m, units.m_to_mm, 47.141),
    (units.kgmm2_to_kgm2, units.kgm2_to_kgmm2, 107.059),
    (units.nmm_per_deg_to_nm_per_rad, units.nm_per_rad_to_nmm_per_deg, 713.547),
    (units.nmms_per_deg_to_nms_per_rad, units.nms_per_rad_to_nmms_per_deg, 1.0),
    (units.nmm_to_nm, units.nm_to_nmm, 12.5),
])
def test_round_trips(fwd, back, x):
    assert back(fwd(x)) == pytest.approx(x, rel=1e-14)
    arr = np.array([x, 2 * x])
    assert np.allclose(back(fwd(arr)), arr, rtol=1e-14)


def test_scales():
    assert units.kgmm2_to_kgm2(1.0) == pytest.approx(1e-6)
    assert units.deg_to_rad(180.0) == pytest.approx(math.pi)
    assert isinstance(units.mm_to_m(1.0), float)


def test_ascii_spelling_of_the_printed_symbols():
    import codecs

    codecs.register_error("test-ascii", units.ascii_spelling)
    text = "k_t·G = 1.5 N·m/rad, θ ≥ 10°, m/s², 0.5 µm → ∀"
    assert text.encode("ascii", "test-ascii").decode() == (
        "k_t*G = 1.5 N*m/rad, theta >= 10 deg, m/s^2, 0.5 um -> \\u2200")
    assert all(v.isascii() for v in units.ASCII_SPELLINGS.values())
    with pytest.raises(UnicodeDecodeError):
        b"\xff".decode("ascii", "test-ascii")
