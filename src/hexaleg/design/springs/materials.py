"""Spring wire you can buy: materials, their strength and moduli, preferred wire diameters.

Sources (Budynas & Nisbett, *Shigley's Mechanical Engineering Design*, 9th–11th ed., ch. 10;
the tables and equations keep their numbers across these editions):

* minimum tensile strength ``S_ut = A / d^m`` (Eq. 10-14) with A and m of **Table 10-4**
  (SI columns, MPa·mm^m): music wire ASTM A228 A = 2211, m = 0.145 (d 0.10–6.5 mm); stainless
  302, ASTM A313: A = 1867, m = 0.146 (0.3–2.5 mm), A = 2065, m = 0.263 (2.5–5 mm), A = 2911,
  m = 0.478 (5–10 mm);
* Young's modulus E of **Table 10-5**: music wire 203.4 GPa (d ≤ 0.032 in), 200.0 (≤ 0.063 in),
  196.5 (≤ 0.125 in), 193.0 GPa above; stainless 302 193 GPa (28.0 Mpsi) — a torsion spring
  works in bending, so E sets its rate;
* the yield strength in bending of a helical torsion spring, **Eq. 10-57** (from Associated
  Spring): ``S_y = 0.78 S_ut`` for music wire and cold-drawn carbon steel, ``0.87 S_ut`` for
  hardened and tempered carbon and low-alloy steel, ``0.61 S_ut`` for austenitic stainless steel
  and non-ferrous alloys — the allowable bending stress for static service;
* density from the specific weight of **Table A-5**: carbon steel 76.5 kN/m³, stainless 18-8
  76.0 kN/m³ (÷ g₀ = 9.80665 m/s²);
* preferred wire diameters: the first-choice metric preferred sizes of **Table A-17**
  (0.10 … 10 mm), within each material's range of Table 10-4;
* fatigue (used by :mod:`hexaleg.design.springs.fatigue`): **Table 10-10** (courtesy of Associated
  Spring), the maximum recommended bending stress (K_B corrected) of helical torsion springs in
  cyclic applications as a percentage of S_ut — ASTM A228 and type 302 stainless: 53 % at 10⁵
  and 50 % at 10⁶ cycles not shot-peened, 62 % and 60 % shot-peened; ASTM A230 and A232: 55/53 %
  and 64/62 % — each material names its column (:attr:`Material.fatigue_column`); and
  **Zimmerli's** endurance data for spring steel wire under 10 mm (§10-9: size, material and
  tensile strength have no effect on them, infinite life only), in torsion: unpeened
  S_sa = 241 MPa, S_sm = 379 MPa (35 and 55 kpsi); peened S_sa = 398 MPa, S_sm = 534 MPa
  (57.5 and 77.5 kpsi) (:data:`ZIMMERLI`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from hexaleg.checks import one_of
from hexaleg.errors import InvalidParameterError
from hexaleg.units import MM

IN = 25.4e-3
"""One inch in metres (Table 10-5 states diameter ranges in inches)."""
STANDARD_GRAVITY = 9.80665
"""g₀, m/s², to turn Table A-5's specific weights into densities."""

PREFERRED_WIRE_DIAMETERS: tuple[float, ...] = tuple(MM * v for v in (
    0.10, 0.12, 0.16, 0.20, 0.25, 0.30, 0.40, 0.50, 0.60, 0.70, 0.80, 0.90, 1.0, 1.1, 1.2, 1.4,
    1.5, 1.6, 1.8, 2.0, 2.2, 2.5, 2.8, 3.0, 3.5, 4.0, 4.5, 5.0, 5.5, 6.0, 6.5, 7.0, 8.0, 9.0,
    10.0))
"""Shigley Table A-17, first-choice metric preferred sizes from 0.10 to 10 mm, m."""

FATIGUE_COLUMNS: dict[str, dict[bool, dict[float, float]]] = {
    "A228/302": {False: {1e5: 0.53, 1e6: 0.50}, True: {1e5: 0.62, 1e6: 0.60}},
    "A230/A232": {False: {1e5: 0.55, 1e6: 0.53}, True: {1e5: 0.64, 1e6: 0.62}},
}
"""Shigley Table 10-10 (Associated Spring): column → shot-peened? → cycles → the maximum
recommended repeated bending stress of a helical torsion spring as a fraction of S_ut ("no
surging, springs in the as-stress-relieved condition"; peening "not always possible")."""
ZIMMERLI: dict[bool, tuple[float, float]] = {False: (241e6, 379e6), True: (398e6, 534e6)}
"""Zimmerli's torsional endurance strengths of spring wire under 10 mm, shot-peened? →
(S_sa, S_sm), Pa (Shigley §10-9, infinite life)."""
ZIMMERLI_MAX_WIRE = 10.0 * MM
"""Zimmerli's data hold for wire under 10 mm (Shigley §10-9), m."""


@dataclass(frozen=True)
class Material:
    """A spring wire material (module docstring for the sources).

    Attributes:
        name: Key in :data:`MATERIALS`.
        title: Human-readable name and standard.
        strength: ``(d_max, A, m)`` rows of Table 10-4 in ascending d_max: for
            ``d ≤ d_max`` (m), ``S_ut = A / d^m`` with A in Pa·m^m.
        d_min: Smallest diameter Table 10-4 covers, m.
        modulus: ``(d_max, E)`` rows of Table 10-5 in ascending d_max (m, Pa); the last row
            covers every larger wire.
        yield_ratio: ``S_y / S_ut`` in bending (Eq. 10-57).
        density: kg/m³ (Table A-5).
        fatigue_column: The column of Table 10-10 (:data:`FATIGUE_COLUMNS`) the material's
            fatigue strengths are read from.
    """

    name: str
    title: str
    strength: tuple[tuple[float, float, float], ...]
    d_min: float
    modulus: tuple[tuple[float, float], ...]
    yield_ratio: float
    density: float
    fatigue_column: str = "A228/302"

    def __post_init__(self) -> None:
        if self.fatigue_column not in FATIGUE_COLUMNS:
            raise InvalidParameterError(f"{self.name} fatigue_column", self.fatigue_column,
                                        f"one of {', '.join(FATIGUE_COLUMNS)} (Table 10-10)")

    @property
    def d_max(self) -> float:
        """Largest diameter Table 10-4 covers, m."""
        return self.strength[-1][0]

    def covers(self, d: ArrayLike) -> np.ndarray:
        """Whether Table 10-4 covers wire diameter ``d`` (m), shape of ``d``."""
        d = np.asarray(d, dtype=float)
        return (d >= self.d_min * (1 - 1e-9)) & (d <= self.d_max * (1 + 1e-9))

    def tensile_strength(self, d: ArrayLike) -> np.ndarray:
        """Minimum tensile strength ``S_ut = A / d^m`` (Shigley Eq. 10-14, Table 10-4), Pa.

        Args:
            d: Wire diameters, m, any shape, within :meth:`covers`.

        Raises:
            InvalidParameterError: a diameter outside the table's range for this material.
        """
        d = np.asarray(d, dtype=float)
        if not np.all(self.covers(d)):
            bad = float(np.ravel(d)[np.flatnonzero(~np.ravel(self.covers(d)))[0]])
            raise InvalidParameterError(f"{self.name} wire diameter", bad,
                                        f"{self.d_min / MM:g} … {self.d_max / MM:g} mm "
                                        "(Shigley Table 10-4)")
        out = np.empty_like(d)
        done = np.zeros(d.shape, dtype=bool)
        for d_max, a, m in self.strength:
            rows = ~done & (d <= d_max * (1 + 1e-9))
            out[rows] = a / d[rows] ** m
            done |= rows
        return out

    def yield_strength(self, d: ArrayLike) -> np.ndarray:
        """Bending yield strength ``S_y = r S_ut`` (Shigley Eq. 10-57), Pa."""
        return self.yield_ratio * self.tensile_strength(d)

    def young_modulus(self, d: ArrayLike) -> np.ndarray:
        """Young's modulus by wire diameter (Shigley Table 10-5), Pa, shape of ``d``."""
        d = np.asarray(d, dtype=float)
        out = np.full(d.shape, self.modulus[-1][1])
        for d_max, e in reversed(self.modulus[:-1]):
            out[d <= d_max * (1 + 1e-9)] = e
        return out

    def wire_diameters(self) -> np.ndarray:
        """The preferred diameters (:data:`PREFERRED_WIRE_DIAMETERS`) this material comes in,
        m, ascending."""
        d = np.array(PREFERRED_WIRE_DIAMETERS)
        return d[self.covers(d)]


def _a(mpa_mm_m: float, m: float) -> float:
    """Table 10-4's A in MPa·mm^m → Pa·m^m (``S = A / d^m`` with d in m)."""
    return mpa_mm_m * 1e6 * MM**m


MATERIALS: dict[str, Material] = {
    "music_wire": Material(
        "music_wire", "music wire, ASTM A228",
        strength=((6.5 * MM, _a(2211.0, 0.145), 0.145),), d_min=0.10 * MM,
        modulus=((0.032 * IN, 203.4e9), (0.063 * IN, 200.0e9), (0.125 * IN, 196.5e9),
                 (np.inf, 193.0e9)),
        yield_ratio=0.78, density=76.5e3 / STANDARD_GRAVITY, fatigue_column="A228/302"),
    "stainless_302": Material(
        "stainless_302", "stainless steel 302, ASTM A313",
        strength=((2.5 * MM, _a(1867.0, 0.146), 0.146), (5.0 * MM, _a(2065.0, 0.263), 0.263),
                  (10.0 * MM, _a(2911.0, 0.478), 0.478)), d_min=0.3 * MM,
        modulus=((np.inf, 193.0e9),), yield_ratio=0.61, density=76.0e3 / STANDARD_GRAVITY,
        fatigue_column="A228/302"),
}
"""The wire materials hexaleg designs torsion springs in (module docstring)."""


def material(name: str) -> Material:
    """The material called ``name``.

    Raises:
        UnknownNameError: not one of :data:`MATERIALS` (lists them).
    """
    return MATERIALS[one_of("spring material", name, MATERIALS)]
