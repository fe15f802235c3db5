"""Fatigue of a helical torsion spring: the Gerber safety factor at a stated life, and its life.

Budynas & Nisbett, *Shigley's Mechanical Engineering Design* (9th/10th ed.), §10-12 "Helical
Torsion Springs", "Fatigue Strength", SI throughout. A torsion spring's wire works in bending,
so the Sines (torsion) model does not apply; the book uses the Gerber criterion with S_ut:

1. **Stresses** at the inner fibre, Eq. (10-44) with K_i of Eq. (10-43), for the moment's
   amplitude ``M_a = (M_max − M_min)/2`` and mean ``M_m = (M_max + M_min)/2``:
   ``σ_a = K_i 32 M_a/(π d³)``, ``σ_m = K_i 32 M_m/(π d³)`` (the book's example does this).
2. **Repeated (zero-to-max) bending strength** S_r at the life N (:func:`repeated_strength`):

   * 10⁵ and 10⁶ cycles: **Table 10-10** (Associated Spring), ``S_r = p S_ut`` with p of the
     material's column (:data:`~hexaleg.design.springs.materials.FATIGUE_COLUMNS`);
   * 10⁷ cycles and more (:data:`ZIMMERLI_LIFE`, infinite life): **Zimmerli's** torsional data
     (:data:`~hexaleg.design.springs.materials.ZIMMERLI`), as the book uses them for compression
     springs: the Gerber line in shear through (S_sm, S_sa) with ``S_su = 0.67 S_ut``
     (Eq. 10-30) gives the fully reversed ``S_se = S_sa/(1 − (S_sm/S_su)²)`` (Eq. 10-42), the
     repeated torsional strength S_sr is that line's amplitude on the load line r = 1 times 2
     (Table 6-7, Gerber), and in bending ``S_r = S_sr/0.577`` (distortion energy, §10-12);
   * between those lives: **our S–N model**, stated because no table gives them: S_r is
     interpolated linearly in log S against log N (a Basquin line through the neighbouring
     points). Below 10⁵ cycles nothing is sourced: refused.

3. **Endurance** from the repeated strength on the Gerber parabola (§10-12):
   ``S_e = (S_r/2) / (1 − (S_r/(2 S_ut))²)``.
4. **Safety factor** ``n_f = S_a/σ_a`` with the Gerber amplitude on the load line
   ``r = σ_a/σ_m`` (Table 6-7): ``S_a = r² S_ut²/(2 S_e) (−1 + √(1 + (2 S_e/(r S_ut))²))``
   (``S_a = S_e`` without a mean stress).
5. **Life**: the N where ``n_f(N) = 1`` on that S–N model (bisection in log N); infinite when
   n_f ≥ 1 at 10⁷ (Zimmerli's is an infinite-life strength), "below 10⁵" when n_f < 1 already
   there.

Worked check: the book's example of a torsion spring in fatigue — the music-wire spring of
Example 10-8 loaded from M_min = 1 to M_max = 5 lbf·in, Table 10-10 at 10⁶ cycles, unpeened
(Example 10-9 of the 9th/10th editions) — is reproduced in the tests (its digits worked along
the book's chain; the page itself was not at hand to compare with).

:func:`cycles_per_year` turns a gait period into cycles a year for a stated duty: the spring
winds and unwinds once per step of its leg, i.e. once per gait period.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import Any

from hexaleg.checks import real
from hexaleg.design.springs.materials import (
    FATIGUE_COLUMNS,
    ZIMMERLI,
    ZIMMERLI_MAX_WIRE,
    Material,
    material,
)
from hexaleg.design.springs.torsion_spring import TorsionSpring, bending_stress
from hexaleg.errors import InvalidParameterError
from hexaleg.quantities import quantity
from hexaleg.units import MM

TABLE_LIVES = (1e5, 1e6)
"""Lives of Table 10-10, cycles."""
ZIMMERLI_LIFE = 1e7
"""Cycles taken as infinite life, where Zimmerli's endurance data apply (Associated Spring's
and the book's usual 10⁷)."""
LIFE = ZIMMERLI_LIFE
"""Default required life, cycles."""
SHEAR_ULTIMATE = 0.67
"""``S_su = 0.67 S_ut`` (Shigley Eq. 10-30)."""
DISTORTION_ENERGY = 0.577
"""Torsional to bending strength ratio of the distortion-energy theory, 1/√3 as the book
rounds it (§10-12: ``S_r = S_sr / 0.577``)."""
HOURS_PER_DAY = 1.0
"""Default duty: one hour of walking a day (assumed; 24 for walking continuously)."""
DAYS_PER_YEAR = 365.0


def gerber_amplitude(ratio: float, S_e: float, S_ut: float) -> float:
    """Gerber strength amplitude on the load line ``r = σ_a/σ_m`` (Shigley Table 6-7):
    ``S_a = r² S_ut²/(2 S_e) (−1 + √(1 + (2 S_e/(r S_ut))²))``, Pa; ``S_e`` for r → ∞."""
    if math.isinf(ratio):
        return S_e
    x = 2 * S_e / (ratio * S_ut)
    # −1 + √(1 + x²) written as x² / (1 + √(1 + x²)): no cancellation for small x
    return ratio**2 * S_ut**2 / (2 * S_e) * x**2 / (1 + math.sqrt(1 + x**2))


def gerber_endurance(S_r: float, S_ut: float) -> float:
    """Fully reversed endurance from the repeated strength on the Gerber parabola (Shigley
    §10-12): ``S_e = (S_r/2) / (1 − (S_r/(2 S_ut))²)``, Pa."""
    return (S_r / 2) / (1 - (S_r / (2 * S_ut)) ** 2)


def zimmerli_repeated_strength(S_ut: float, peened: bool = False) -> float:
    """Repeated bending strength for infinite life from Zimmerli's torsional data, Pa (module
    docstring, step 2): ``S_se = S_sa/(1 − (S_sm/S_su)²)`` (Eq. 10-42, ``S_su = 0.67 S_ut``,
    Eq. 10-30), ``S_sr = 2 S_a(r = 1)`` (Table 6-7 in shear), ``S_r = S_sr/0.577``."""
    s_sa, s_sm = ZIMMERLI[peened]
    s_su = SHEAR_ULTIMATE * S_ut
    s_se = s_sa / (1 - (s_sm / s_su) ** 2)
    return 2 * gerber_amplitude(1.0, s_se, s_su) / DISTORTION_ENERGY


def _points(mat: Material, S_ut: float, peened: bool) -> list[tuple[float, float]]:
    table = FATIGUE_COLUMNS[mat.fatigue_column][peened]
    return [(n, table[n] * S_ut) for n in TABLE_LIVES] + [
        (ZIMMERLI_LIFE, zimmerli_repeated_strength(S_ut, peened))]


def repeated_strength(mat: Material | str, d: float, cycles: float, peened: bool = False
                      ) -> float:
    """Repeated (zero-to-max) bending strength ``S_r`` of a torsion spring of wire ``d`` (m)
    at ``cycles`` (≥ 10⁵; ≥ 10⁷ is infinite life), Pa (module docstring, step 2).

    Raises:
        InvalidParameterError: cycles below 10⁵ (nothing sourced there), a wire outside the
            material's Table 10-4 range, or for ≥ 10⁷ cycles a wire of 10 mm or more
            (Zimmerli's data are for wire under 10 mm).
    """
    mat = material(mat) if isinstance(mat, str) else mat
    cycles = real("life cycles", cycles, low=TABLE_LIVES[0],
                  allowed=f">= {TABLE_LIVES[0]:.0e} cycles (Shigley Table 10-10's shortest "
                          "life; nothing shorter is sourced)") if not math.isinf(cycles) \
        else cycles
    if cycles > TABLE_LIVES[-1] and d >= ZIMMERLI_MAX_WIRE:
        raise InvalidParameterError("wire diameter", d, f"< {ZIMMERLI_MAX_WIRE / MM:g} mm for "
                                    "lives beyond 10⁶ cycles (Zimmerli's data); [design] "
                                    "life_cycles <= 1e6 checks it on Shigley's Table 10-10")
    S_ut = float(mat.tensile_strength(d))
    points = _points(mat, S_ut, peened)
    if cycles >= ZIMMERLI_LIFE:
        return points[-1][1]
    for (n0, s0), (n1, s1) in itertools.pairwise(points):
        if cycles <= n1:
            t = math.log(cycles / n0) / math.log(n1 / n0)
            return float(s0 * (s1 / s0) ** t)
    raise AssertionError("unreachable")  # pragma: no cover


def wire_limit(life: float) -> float | None:
    """The wire a spring for ``life`` cycles must be thinner than, m: Zimmerli's data, which
    every life beyond 10⁶ cycles uses (module docstring, step 2), are for wire under
    :data:`~hexaleg.design.springs.materials.ZIMMERLI_MAX_WIRE`; None (any preferred wire) up to
    10⁶ cycles, where Table 10-10 covers the materials' whole range."""
    return ZIMMERLI_MAX_WIRE if life > TABLE_LIVES[-1] else None


def gerber_safety(sigma_a: float, sigma_m: float, S_e: float, S_ut: float) -> float:
    """Gerber fatigue safety factor ``n_f = S_a/σ_a`` on the load line (Table 6-7); inf
    without an alternating stress."""
    if sigma_a <= 0:
        return math.inf
    ratio = math.inf if sigma_m <= 0 else sigma_a / sigma_m
    return gerber_amplitude(ratio, S_e, S_ut) / sigma_a


@dataclass(frozen=True)
class FatigueCheck:
    """A torsion spring's fatigue check (module docstring), SI.

    Attributes:
        material: Material key. peened: Shot-peened wire. wire_diameter, mean_diameter: m.
        moment_min, moment_max: The cycle's moments, N·m.
        stress_alternating, stress_mean: σ_a, σ_m at the inner fibre, Pa.
        tensile_strength: S_ut, Pa. repeated_strength: S_r at the required life, Pa.
        endurance_strength: S_e at the required life, Pa.
        required_life: Cycles asked for. safety_factor: n_f at that life.
        life: Cycles the spring has (n_f = 1 there); inf: infinite life (n_f ≥ 1 at 10⁷).
        life_note: How ``life`` reads ("" when exact; "below 1e5 cycles, the shortest sourced
            life" when n_f < 1 already there — then ``life`` is 1e5, an upper bound).
    """

    material: str
    peened: bool
    wire_diameter: float
    mean_diameter: float
    moment_min: float
    moment_max: float
    stress_alternating: float
    stress_mean: float
    tensile_strength: float
    repeated_strength: float
    endurance_strength: float
    required_life: float
    safety_factor: float
    life: float
    life_note: str = ""

    @property
    def meets(self) -> bool:
        """Whether it lasts the required life (n_f ≥ 1)."""
        return self.safety_factor >= 1.0

    def table(self) -> dict[str, Any]:
        """Every number as ``{value, unit}`` (:func:`hexaleg.quantities.quantity`: an infinite
        life stays infinite, written ``null`` with a note in a JSON file)."""
        q = quantity

        return {"material": self.material, "peened": self.peened,
                "criterion": "Gerber (Shigley §10-12, Table 6-7)",
                "moment_min": q(self.moment_min, "N·m"), "moment_max": q(self.moment_max, "N·m"),
                "stress_alternating": q(self.stress_alternating, "Pa"),
                "stress_mean": q(self.stress_mean, "Pa"),
                "tensile_strength": q(self.tensile_strength, "Pa"),
                "repeated_strength": q(self.repeated_strength, "Pa"),
                "endurance_strength": q(self.endurance_strength, "Pa"),
                "required_life": q(self.required_life, "cycles"),
                "safety_factor": q(self.safety_factor, "1"), "life": q(self.life, "cycles"),
                "life_note": self.life_note, "meets": self.meets}


def fatigue_check(mat: Material | str, d: float, D: float, m_min: float, m_max: float, *,
                  life: float = LIFE, peened: bool = False) -> FatigueCheck:
    """The fatigue check of a torsion spring of wire ``d`` and mean diameter ``D`` (m) cycled
    between ``m_min`` and ``m_max`` (N·m, winding it up) for ``life`` cycles (module docstring).

    Raises:
        InvalidParameterError: ``0 ≤ m_min ≤ m_max``, ``m_max > 0`` broken (a torsion spring is
            loaded in the sense that winds it), D ≤ d, or a life or wire
            :func:`repeated_strength` refuses.
        UnknownNameError: an unknown material name.
    """
    mat = material(mat) if isinstance(mat, str) else mat
    d = real("wire diameter", d, low=0.0, low_open=True, allowed="> 0 m")
    D = real("mean diameter", D, low=d, low_open=True, allowed=f"> the wire diameter {d:g} m")
    m_max = real("moment_max", m_max, low=0.0, low_open=True, allowed="> 0 N·m")
    m_min = real("moment_min", m_min, low=0.0, high=m_max,
                 allowed=f"0 … moment_max = {m_max:g} N·m (a torsion spring is loaded in the "
                         "sense that winds it up)")
    if not (isinstance(life, (int, float)) and math.isinf(life) and life > 0):
        life = real("life", life, low=TABLE_LIVES[0],
                    allowed=f">= {TABLE_LIVES[0]:.0e} cycles (Shigley Table 10-10's shortest "
                            "life), or inf")
    S_ut = float(mat.tensile_strength(d))
    sa = float(bending_stress((m_max - m_min) / 2, d, D))
    sm = float(bending_stress((m_max + m_min) / 2, d, D))

    def n_f(cycles: float) -> float:
        return gerber_safety(sa, sm, gerber_endurance(repeated_strength(
            mat, d, cycles, peened), S_ut), S_ut)

    S_r = repeated_strength(mat, d, life, peened)
    note = ""
    # wire Zimmerli's data leave out is sourced up to Table 10-10's longest life
    top = ZIMMERLI_LIFE if d < ZIMMERLI_MAX_WIRE else TABLE_LIVES[-1]
    if n_f(top) >= 1:
        has = math.inf if top == ZIMMERLI_LIFE else top
        if top != ZIMMERLI_LIFE:
            note = (f"at least {top:.0e} cycles, the longest sourced life for wire of "
                    f"{ZIMMERLI_MAX_WIRE / MM:g} mm or more (a lower bound)")
    elif n_f(TABLE_LIVES[0]) < 1:
        has, note = TABLE_LIVES[0], (f"below {TABLE_LIVES[0]:.0e} cycles, the shortest "
                                     "sourced life (an upper bound)")
    else:  # n_f falls with N: bisect log N between 1e5 and the longest sourced life
        lo, hi = math.log(TABLE_LIVES[0]), math.log(top)
        for _ in range(60):
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if n_f(math.exp(mid)) >= 1 else (lo, mid)
        has = math.exp(lo)
    return FatigueCheck(
        material=mat.name, peened=peened, wire_diameter=d, mean_diameter=D, moment_min=m_min,
        moment_max=m_max, stress_alternating=sa, stress_mean=sm, tensile_strength=S_ut,
        repeated_strength=S_r, endurance_strength=gerber_endurance(S_r, S_ut),
        required_life=life, safety_factor=n_f(life), life=has, life_note=note)


def spring_fatigue(spring: TorsionSpring, *, life: float = LIFE, peened: bool = False,
                   m_min: float | None = None, m_max: float | None = None) -> FatigueCheck:
    """:func:`fatigue_check` of a designed spring cycled from its preload torque (where it rests
    on its stop, or the near end of the motion) to its ``max_torque`` — once per step over the
    gait it was designed on — unless ``m_min``/``m_max`` (N·m) say otherwise."""
    low = spring.rate * spring.preload_angle if m_min is None else m_min
    high = spring.max_torque if m_max is None else m_max
    return fatigue_check(spring.material, spring.wire_diameter, spring.mean_diameter, low, high,
                         life=life, peened=peened)


def cycles_per_year(period: float, hours_per_day: float = HOURS_PER_DAY) -> float:
    """Load cycles a year of a spring that cycles once per gait ``period`` (s) while the robot
    walks ``hours_per_day`` (default :data:`HOURS_PER_DAY`; 24 is walking continuously):
    ``hours × 3600 × 365 / period``.

    Raises:
        InvalidParameterError: period ≤ 0 or hours outside (0, 24].
    """
    period = real("period", period, low=0.0, low_open=True, allowed="> 0 s")
    hours = real("hours_per_day", hours_per_day, low=0.0, high=24.0, low_open=True,
                 allowed="0 < hours <= 24")
    return hours * 3600.0 * DAYS_PER_YEAR / period
