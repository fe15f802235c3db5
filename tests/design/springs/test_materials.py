"""Tests of hexaleg.design.springs.materials: Shigley's Table 10-4 strengths, Table 10-5 moduli,
Eq. 10-57 bending yield, preferred diameters."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.design.springs.materials import MATERIALS, PREFERRED_WIRE_DIAMETERS, material
from hexaleg.errors import InvalidParameterError, UnknownNameError


def test_material_tables():
    mw, ss = material("music_wire"), material("stainless_302")
    assert float(mw.tensile_strength(1e-3)) == pytest.approx(2211e6)
    assert float(ss.tensile_strength(3e-3)) == pytest.approx(2065e6 / 3**0.263)
    assert float(ss.yield_strength(1e-3)) == pytest.approx(0.61 * 1867e6)
    assert float(mw.young_modulus(0.5e-3)) == 203.4e9 and float(mw.young_modulus(2e-3)) == 196.5e9
    assert mw.wire_diameters()[0] == pytest.approx(0.1e-3)
    assert ss.wire_diameters()[0] == pytest.approx(0.3e-3)
    with pytest.raises(InvalidParameterError, match=r"0\.3 … 10 mm"):
        ss.tensile_strength(0.2e-3)
    with pytest.raises(UnknownNameError, match="music_wire"):
        material("piano_wire")


def test_strength_falls_with_diameter_and_the_preferred_sizes_ascend():
    assert np.all(np.diff(PREFERRED_WIRE_DIAMETERS) > 0)
    for mat in MATERIALS.values():
        wires = mat.wire_diameters()
        assert np.all(np.diff(mat.tensile_strength(wires)) < 0)
        assert 7700 < mat.density < 7850
