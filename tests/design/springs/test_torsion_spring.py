"""Tests of the buyable helical torsion spring (hexaleg.design.springs.torsion_spring,
spring_materials).

The worked example is Shigley's Example 10-8 (Budynas & Nisbett, *Shigley's Mechanical
Engineering Design*, 9th/10th ed., §10-12): a stock spring of 0.072 in music wire, 4¼ body
turns, straight 1 in legs, OD 19/32 in, over a 0.400 in pin. Each step is fed the book's printed
inputs (as the book chains its rounded numbers) and must print the book's digits.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from hexaleg.design.springs import torsion_spring as ts
from hexaleg.design.springs.materials import MATERIALS, Material
from hexaleg.errors import InvalidParameterError, SpringDesignError, UnknownNameError
from hexaleg.units import MM

IN = 25.4e-3
KPSI = 6.894757e6
LBF_IN = 4.4482216152605 * IN
E_BOOK = 28.5e6 * 6894.757  # Table 10-5, music wire 0.064–0.125 in


def _book(x: float, digits: int) -> float:
    """``x`` to ``digits`` significant digits, rounded."""
    return float(f"{x:.{digits}g}")


def _cut(x: float, decimals: int) -> float:
    """``x`` cut to ``decimals`` decimals: the book prints its deflections in turns cut, not
    rounded (0.25857 → 0.2585, 0.23597 → 0.2359)."""
    return math.floor(x * 10**decimals) / 10**decimals


def test_shigley_example_10_8_to_the_books_digits():
    d, D_book = 0.072 * IN, 0.5218 * IN
    # (a) S_ut = A/d^m with Table 10-4's A = 201 kpsi·in^m, m = 0.145; S_y = 0.78 S_ut (10-57)
    wire = Material("book", "music wire", ((6.5 * MM, 201 * KPSI * IN**0.145, 0.145),),
                    0.1 * MM, ((math.inf, E_BOOK),), 0.78, 7800.0)
    assert _book(float(wire.tensile_strength(d)) / KPSI, 4) == 294.4
    assert _book(float(wire.yield_strength(d)) / KPSI, 4) == 229.6
    assert (19 / 32 * IN - d) / IN == pytest.approx(0.52175)  # printed 0.5218
    C = D_book / d
    assert round(C, 3) == 7.247
    assert round(float(ts.inner_fibre_factor(7.247)), 3) == 1.115
    # M_y = π d³ S_y / (32 K_i): the inverse of Eq. 10-44 at σ = S_y
    m_y = math.pi * d**3 * 229.6 * KPSI / (32 * 1.115)
    assert round(m_y / LBF_IN, 3) == 7.546
    sigma = float(ts.bending_stress(7.546 * LBF_IN, d, D_book)) / KPSI  # back to S_y
    assert sigma == pytest.approx(229.6, rel=5e-4)
    na = float(ts.active_turns(4.25, D_book, IN, IN))
    assert round(na, 3) == 4.657
    theta = float(ts.deflection_turns(7.546 * LBF_IN, d, D_book, 4.657, E_BOOK))
    assert _cut(theta, 4) == 0.2585  # 0.25857
    assert round(theta * 360, 1) == 93.1
    k_turn = float(ts.rate(d, D_book, 4.657, E_BOOK)) * 2 * math.pi
    assert k_turn / LBF_IN == pytest.approx(29.19, abs=0.015)  # 7.546 / 0.2585
    # (b) the body's deflection, the wound coil and the pin clearance
    theta_c = float(ts.deflection_turns(7.546 * LBF_IN, d, D_book, 4.25, E_BOOK))
    assert _cut(theta_c, 4) == 0.2359  # 0.23597
    D_wound = float(ts.wound_diameter(D_book, 4.25, 0.2359))
    assert round(D_wound / IN, 4) == 0.4944
    assert round((0.4944 * IN - d - 0.400 * IN) / IN, 4) == 0.0224


def _strain_energy(M: float, d: float, D: float, body_turns: float, legs: tuple[float, float],
                   E: float, n: int = 20001) -> float:
    """∫ M(s)² / (2 E I) ds along the wire, by the trapezoidal rule: the body carries M over
    π D N_b, each leg (a cantilever loaded at its end) M s / l over its length."""
    EI = E * math.pi * d**4 / 64
    u = M**2 * math.pi * D * body_turns / (2 * EI)
    for length in legs:
        s = np.linspace(0.0, length, n)
        u += float(np.trapezoid((M * s / length) ** 2, s)) / (2 * EI)
    return u


def test_rate_equals_castiglianos_derivative_of_the_strain_energy():
    """θ = dU/dM (Castigliano) by central differences of the wire's bending energy equals the
    beam-theory deflection 2π·10.19 M D N_a/(d⁴E) with the legs' N_e = (l₁+l₂)/(3πD); the
    design rate uses Wahl's 10.8 instead, a fixed ratio."""
    d, D, nb, legs, E = 1.0e-3, 8.0e-3, 5.25, (6.0e-3, 11.0e-3), 200e9
    M, h = 0.12, 1e-5
    theta = (_strain_energy(M + h, d, D, nb, legs, E)
             - _strain_energy(M - h, d, D, nb, legs, E)) / (2 * h)
    na = float(ts.active_turns(nb, D, *legs))
    beam = 2 * math.pi * float(ts.deflection_turns(M, d, D, na, E, constant=ts.BEAM))
    assert theta == pytest.approx(beam, rel=1e-7)
    k = float(ts.rate(d, D, na, E))
    assert k * beam == pytest.approx(M * ts.BEAM / ts.WAHL, rel=1e-12)
    # the spring's own energy ½ k θ² has torque k θ: finite differences of it
    th, dh = 0.7, 1e-6
    assert (0.5 * k * (th + dh) ** 2 - 0.5 * k * (th - dh) ** 2) / (2 * dh) == \
        pytest.approx(k * th, rel=1e-8)


def test_monotonic_in_every_dimension():
    d, D, na, E = 1e-3, 8e-3, 6.0, 200e9
    k = float(ts.rate(d, D, na, E))
    assert float(ts.rate(1.1 * d, D, na, E)) > k
    assert float(ts.rate(d, 1.1 * D, na, E)) < k
    assert float(ts.rate(d, D, 1.1 * na, E)) < k
    assert float(ts.active_turns(5, D, 2e-3, 2e-3)) < float(ts.active_turns(5, D, 4e-3, 4e-3))
    C = np.linspace(2.0, 20.0, 50)
    assert np.all(np.diff(ts.inner_fibre_factor(C)) < 0) and np.all(ts.inner_fibre_factor(C) > 1)
    assert float(ts.bending_stress(0.2, d, D)) < float(ts.bending_stress(0.3, d, D))
    assert float(ts.bending_stress(0.2, 1.2 * d, D)) < float(ts.bending_stress(0.2, d, D))
    assert np.all(np.diff(ts.wound_diameter(D, 5.0, np.linspace(0, 1, 9))) < 0)
    for mat in MATERIALS.values():
        wires = mat.wire_diameters()
        assert np.all(np.diff(mat.tensile_strength(wires)) < 0)


def test_designed_spring_meets_every_limit_and_the_rate():
    req = ts.TorsionRequirement(rate=0.0212, max_torque=0.09, preload_torque=0.058,
                                max_outer_diameter=0.02, arbor_diameter=4e-3)
    s = ts.design_torsion_spring(req)
    assert s.outer_diameter <= req.max_outer_diameter
    assert ts.C_MIN <= s.index <= ts.C_MAX
    assert s.stress * req.safety_factor <= s.yield_strength
    assert s.wound_inner_diameter >= req.arbor_diameter
    assert abs(s.rate / req.rate - 1) <= ts.D_STEP / s.mean_diameter + 1e-12
    assert s.preload_angle == pytest.approx(0.058 / s.rate)
    assert s.max_torque == pytest.approx(0.09, rel=ts.D_STEP / s.mean_diameter + 1e-12)
    assert s.max_deflection == pytest.approx(s.max_torque / s.rate)
    wire = MATERIALS[s.material]
    volume = math.pi / 4 * s.wire_diameter**2 * (math.pi * s.mean_diameter * s.body_turns
                                                 + 2 * s.leg_length)
    assert s.mass == pytest.approx(wire.density * volume)
    table = s.table()
    assert table["rate_nmm_per_deg"]["unit"] == "N·mm/deg"
    assert table["rate_nmm_per_deg"]["value"] == pytest.approx(s.rate * 1e3 * math.pi / 180)
    # a stiffer, stronger requirement never gives a lighter spring
    heavier = ts.design_torsion_spring(ts.TorsionRequirement(rate=0.0424, max_torque=0.18,
                                                             preload_torque=0.116))
    assert heavier.mass > s.mass


def test_no_spring_fits_names_the_limit_and_the_nearest():
    req = ts.TorsionRequirement(rate=0.0212, max_torque=0.09, preload_torque=0.058,
                                max_outer_diameter=0.004)
    with pytest.raises(SpringDesignError, match="max_outer_diameter") as info:
        ts.design_torsion_spring(req)
    nearest = info.value.nearest
    assert isinstance(nearest, ts.TorsionSpring)
    assert nearest.outer_diameter > req.max_outer_diameter
    assert f"{nearest.outer_diameter / MM:.2f} mm" in str(info.value)
    relaxed = ts.design_torsion_spring(ts.TorsionRequirement(
        rate=0.0212, max_torque=0.09, preload_torque=0.058,
        max_outer_diameter=nearest.outer_diameter))
    assert relaxed.outer_diameter <= nearest.outer_diameter


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"rate": 0.0, "max_torque": 0.1}, "constant-torque"),
    ({"rate": 0.1, "max_torque": 0.1, "max_outer_diameter": 0.3e-3}, "thinnest preferred wire"),
    ({"rate": 0.1, "max_torque": 0.1, "preload_torque": 0.2}, "preload_torque"),
    ({"rate": 0.1, "max_torque": 0.1, "safety_factor": 0.5}, ">= 1"),
])
def test_bad_requirements_are_named(kwargs, match):
    with pytest.raises(InvalidParameterError, match=match):
        ts.TorsionRequirement(**kwargs)


def test_unknown_material_lists_the_materials():
    with pytest.raises(UnknownNameError, match="music_wire, stainless_302"):
        ts.TorsionRequirement(rate=0.1, max_torque=0.1, materials=("bronze",))


def test_the_wound_coil_clears_its_arbor_by_the_margin():
    """D' − d ≥ arbor (1 + margin) (§10-12's clearance, Associated Spring's about 10 %): a
    design that only just cleared the bare arbor is refused with the margin."""
    base = dict(rate=0.0212, max_torque=0.09, preload_torque=0.058, max_outer_diameter=0.02)
    bare = ts.design_torsion_spring(ts.TorsionRequirement(**base, arbor_diameter=4e-3,
                                                          arbor_margin=0.0))
    assert ts.TorsionRequirement(**base).arbor_margin == ts.ARBOR_MARGIN == 0.10
    # an arbor the bare design just clears: with the 10 % margin that spring no longer fits
    tight = bare.wound_inner_diameter / 1.05
    s = ts.design_torsion_spring(ts.TorsionRequirement(**base, arbor_diameter=tight))
    assert s.wound_inner_diameter >= 1.1 * tight * (1 - 1e-12)
    assert s.table()["arbor_margin"] == {"value": 0.1, "unit": "1"}
    with pytest.raises(SpringDesignError):  # no coil inside 20 mm clears 18 mm by 10 %
        ts.design_torsion_spring(ts.TorsionRequirement(**base, arbor_diameter=18e-3))
    for bad in (-0.1, 1.5, math.nan):
        with pytest.raises(InvalidParameterError):
            ts.TorsionRequirement(**base, arbor_margin=bad)
