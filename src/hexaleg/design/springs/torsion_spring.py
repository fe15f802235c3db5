"""A helical torsion spring you can buy: round wire, designed by the textbook equations.

Equations of Budynas & Nisbett, *Shigley's Mechanical Engineering Design* (9th–11th ed.),
§10-12 "Helical Torsion Springs" (equation numbers of the 9th/10th editions), SI throughout:

* spring index ``C = D / d`` (D mean coil diameter, d wire diameter); bending-stress correction
  at the inner fibre, Eq. (10-43): ``K_i = (4C² − C − 1) / (4C (C − 1))``, and the bending
  stress, Eq. (10-44): ``σ = K_i 32 M / (π d³)``;
* active turns with the straight legs' contribution: ``N_a = N_b + (l₁ + l₂) / (3π D)``
  (each leg a cantilever, its bending energy that of a length l/3 of coil);
* deflection in turns ``θ' = 10.2 M D N_a / (d⁴ E)`` from beam theory (64 / 2π = 10.19), raised
  to ``θ' = 10.8 M D N_a / (d⁴ E)`` for the friction between coils (Wahl's tests), so the rate
  is ``k' = d⁴ E / (10.8 D N_a)`` N·m/turn and ``k = k' / 2π`` N·m/rad;
* coil diameter under wind-up ``D' = N_b D / (N_b + θ'_c)``, with ``θ'_c`` the body's deflection
  in turns (N_a → N_b above); the clearance over an arbor D_p, ``Δ = D' − d − D_p`` (§10-12),
  must be ≥ :data:`ARBOR_MARGIN` D_p (Associated Spring's stock springs: "suggested mandrel
  sizes allow about 10 % clearance"; Shigley gives Δ, not a percentage);
* allowable bending stress for static service: the bending yield strength ``S_y`` of
  Eq. (10-57) (:mod:`hexaleg.design.springs.materials`), divided by a design factor;
* body turns ``N_b = integer + β / 360°``: β is the angle between the legs in the free spring.

Worked check: Shigley's Example 10-8 (a 0.072 in music wire stock spring, 4¼ body turns, 1 in
legs, over a 0.400 in pin) is reproduced to the book's digits in the tests. The close-wound body
length ``d (N_b + 1 + θ'_c)`` is the spring makers' formula (e.g. Associated Spring's handbook).

:func:`design_torsion_spring` picks, for a required rate, torque and preload, the lightest spring
(within :data:`MASS_TIE`, the shortest) over the materials, the preferred wire diameters and body
turns on a quarter-turn grid, the mean diameter solved from the rate equation (rounded to
:data:`D_STEP`), within ``C_MIN ≤ C ≤ C_MAX`` (Shigley §10-8's recommended range), the outer
diameter limit, the stress limit and the arbor. No spring: :class:`~hexaleg.errors.
SpringDesignError` naming the binding limit and the nearest spring.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from hexaleg.checks import real, typed
from hexaleg.design.springs.materials import MATERIALS, PREFERRED_WIRE_DIAMETERS, material
from hexaleg.errors import InvalidParameterError, SpringDesignError
from hexaleg.quantities import quantity
from hexaleg.units import MM, nm_per_rad_to_nmm_per_deg, rad_to_deg

WAHL = 10.8
"""Deflection constant with the friction between coils (Shigley §10-12, after Wahl), 1."""
BEAM = 64.0 / (2.0 * math.pi)
"""Deflection constant of pure beam theory, 64/2π = 10.19 (Shigley's 10.2)."""
C_MIN, C_MAX = 4.0, 12.0
"""Recommended spring index range (Shigley §10-8, design for static service)."""
N_B_MIN, N_B_MAX = 2.0, 40.0
"""Body turns considered (assumed: fewer than 2 turns do not make a stable coil)."""
TURN_STEP = 0.25
"""Body turns grid, turns: β in steps of 90° between the legs of the free spring."""
D_STEP = 0.01 * MM
"""Mean coil diameter resolution, m (a drawing dimension to 0.01 mm)."""
ARBOR_MARGIN = 0.10
"""Default clearance of the wound coil over its arbor, a fraction of the arbor (module doc)."""
SAFETY_FACTOR = 1.2
"""Default static design factor on S_y (Shigley §10-8 uses n_s ≥ 1.2 for static service)."""
MASS_TIE = 0.05
"""Springs within this fraction of the lightest one's mass count as equally light; the one with
the shortest body is chosen (it fits the joint's axial space best)."""
LEG_RATIO = 1.0
"""Default length of each straight leg in mean coil diameters (assumed: short torsion ends)."""


def inner_fibre_factor(C: ArrayLike) -> np.ndarray:
    """Bending-stress correction at the inner fibre ``K_i = (4C² − C − 1)/(4C(C − 1))``
    (Shigley Eq. 10-43), shape of ``C`` (> 1)."""
    C = np.asarray(C, dtype=float)
    return (4 * C**2 - C - 1) / (4 * C * (C - 1))


def bending_stress(M: ArrayLike, d: ArrayLike, D: ArrayLike) -> np.ndarray:
    """Bending stress at the inner fibre ``σ = K_i 32 M / (π d³)`` (Shigley Eq. 10-44), Pa.

    Args:
        M: Moment on the spring, N·m.
        d: Wire diameter, m.
        D: Mean coil diameter, m (broadcast together).
    """
    d = np.asarray(d, dtype=float)
    return inner_fibre_factor(np.asarray(D) / d) * 32 * np.asarray(M) / (math.pi * d**3)


def active_turns(body_turns: ArrayLike, D: ArrayLike, leg_1: ArrayLike, leg_2: ArrayLike
                 ) -> np.ndarray:
    """``N_a = N_b + (l₁ + l₂) / (3π D)`` (Shigley §10-12: straight legs as cantilevers).

    Args:
        body_turns: N_b, turns.
        D: Mean coil diameter, m.
        leg_1: Length of one leg, m.
        leg_2: Length of the other, m.
    """
    return np.asarray(body_turns) + (np.asarray(leg_1) + np.asarray(leg_2)) / (
        3 * math.pi * np.asarray(D))


def deflection_turns(M: ArrayLike, d: ArrayLike, D: ArrayLike, turns: ArrayLike, E: ArrayLike,
                     constant: float = WAHL) -> np.ndarray:
    """Angular deflection ``θ' = c M D N / (d⁴ E)`` in turns (Shigley §10-12; c = 10.8 with coil
    friction, :data:`BEAM` for beam theory; N = N_a for the whole spring, N_b for the body)."""
    return constant * np.asarray(M) * np.asarray(D) * np.asarray(turns) / (
        np.asarray(d) ** 4 * np.asarray(E))


def rate(d: ArrayLike, D: ArrayLike, active: ArrayLike, E: ArrayLike,
         constant: float = WAHL) -> np.ndarray:
    """Spring rate ``k = d⁴ E / (c D N_a) / 2π`` in N·m/rad (Shigley §10-12: k' per turn over
    2π; c = 10.8 with coil friction)."""
    return np.asarray(d) ** 4 * np.asarray(E) / (
        constant * np.asarray(D) * np.asarray(active)) / (2 * math.pi)


def wound_diameter(D: ArrayLike, body_turns: ArrayLike, body_deflection: ArrayLike
                   ) -> np.ndarray:
    """Mean coil diameter wound up by ``θ'_c`` turns ``D' = N_b D / (N_b + θ'_c)`` (Shigley
    §10-12), m."""
    nb = np.asarray(body_turns)
    return nb * np.asarray(D) / (nb + np.asarray(body_deflection))


@dataclass(frozen=True)
class TorsionRequirement:
    """What one spring must do, from the spring design (SI).

    Attributes:
        rate: Required rate, N·m/rad, > 0 (k → 0 is a constant-torque spring, not this part).
        max_torque: Torque at the far end of the joint's motion, N·m, ≥ ``preload_torque``.
        preload_torque: Torque where the spring engages (the contact angle; 0 for a spring
            free there), N·m, ≥ 0.
        max_outer_diameter: Largest outer coil diameter that fits the joint, m, > 0.
        arbor_diameter: Diameter of the pin the coil winds onto, m, ≥ 0 (0: none).
        arbor_margin: Wound inside diameter ≥ ``arbor_diameter (1 + margin)``; ≥ 0.
        materials: Wire materials to choose from (:data:`~hexaleg.design.springs.materials.
            MATERIALS`).
        safety_factor: Design factor on the bending yield strength, ≥ 1.
        leg_length: Length of each straight leg, m; None: :data:`LEG_RATIO` mean diameters.
        max_wire_diameter: Wire must be thinner than this, m (the wire the fatigue data at the
            required life cover: :func:`hexaleg.design.springs.fatigue.wire_limit`); None: any
            preferred wire.

    Raises:
        InvalidParameterError: a value out of range (a zero rate names the constant-torque
            spring it would need; a max_outer_diameter no wire fits names the smallest).
        UnknownNameError: an unknown material (lists them).
    """

    rate: float
    max_torque: float
    preload_torque: float = 0.0
    max_outer_diameter: float = 0.02
    arbor_diameter: float = 0.0
    materials: tuple[str, ...] = tuple(MATERIALS)
    safety_factor: float = SAFETY_FACTOR
    leg_length: float | None = None
    arbor_margin: float = ARBOR_MARGIN
    max_wire_diameter: float | None = None

    def __post_init__(self) -> None:
        real("rate", self.rate, low=0.0, low_open=True,
             allowed="> 0 N·m/rad: a spring with k → 0 holds a constant torque and needs a "
                     "constant-torque (spiral or constant-force) spring, not a helical torsion "
                     "spring")
        real("preload_torque", self.preload_torque, low=0.0, allowed=">= 0 N·m")
        real("max_torque", self.max_torque, low=max(self.preload_torque, 0.0), low_open=True,
             allowed=f"> preload_torque = {self.preload_torque:g} N·m")
        d_min = min(PREFERRED_WIRE_DIAMETERS)
        smallest = (C_MIN + 1) * d_min
        real("max_outer_diameter", self.max_outer_diameter, low=smallest,
             allowed=f">= {smallest / MM:g} mm: the thinnest preferred wire ({d_min / MM:g} mm) "
                     f"wound at the smallest spring index C = {C_MIN:g}")
        real("arbor_diameter", self.arbor_diameter, low=0.0, allowed=">= 0 m")
        real("arbor_margin", self.arbor_margin, low=0.0, high=1.0, allowed="0 … 1 (0.1: 10 %)")
        real("safety_factor", self.safety_factor, low=1.0, allowed=">= 1")
        if self.leg_length is not None:
            real("leg_length", self.leg_length, low=0.0, allowed="None or >= 0 m")
        if self.max_wire_diameter is not None:
            real("max_wire_diameter", self.max_wire_diameter, low=0.0, low_open=True,
                 allowed="None or > 0 m")
        if isinstance(self.materials, str) or not self.materials:
            raise InvalidParameterError("materials", self.materials,
                                        f"a non-empty list of {', '.join(MATERIALS)}")
        object.__setattr__(self, "materials", tuple(self.materials))
        for name in self.materials:
            material(name)

    @property
    def deflection(self) -> float:
        """Deflection from the free position at ``max_torque``, rad."""
        return self.max_torque / self.rate


@dataclass(frozen=True)
class TorsionSpring:
    """A helical torsion spring (round wire), its fit and its check (module docstring), SI.

    Attributes:
        material: Key of the wire material. wire_diameter: d, m. mean_diameter: D, m.
        body_turns: N_b. active_turns: N_a (legs included). leg_length: Each leg, m.
        rate: N·m/rad (10.8 constant). free_leg_angle: β of ``N_b = n + β/360°``, rad.
        preload_angle: Wind-up where it engages (preload torque / rate), rad.
        max_deflection: Wind-up at the far end of the motion, rad.
        max_torque: Torque there, N·m. stress: σ at ``max_torque`` (inner fibre), Pa.
        yield_strength: S_y in bending, Pa. safety_factor: S_y / σ. design_factor: Required.
        wound_outer_diameter: Outer diameter at ``max_deflection``, m.
        wound_inner_diameter: Inner diameter there, m. arbor_diameter: m.
        body_length: Close-wound body length at ``max_deflection``, m. mass: kg.
        requirement: What it was designed for.
    """

    material: str
    wire_diameter: float
    mean_diameter: float
    body_turns: float
    active_turns: float
    leg_length: float
    rate: float
    free_leg_angle: float
    preload_angle: float
    max_deflection: float
    max_torque: float
    stress: float
    yield_strength: float
    safety_factor: float
    design_factor: float
    wound_outer_diameter: float
    wound_inner_diameter: float
    arbor_diameter: float
    body_length: float
    mass: float
    requirement: TorsionRequirement

    @property
    def outer_diameter(self) -> float:
        """Free outer diameter D + d, m."""
        return self.mean_diameter + self.wire_diameter

    @property
    def index(self) -> float:
        """Spring index C = D / d."""
        return self.mean_diameter / self.wire_diameter

    def table(self) -> dict[str, Any]:
        """Every number as ``{value, unit}`` (SI, the rate also in N·mm/deg, angles also in deg).
        """
        q = quantity

        return {
            "material": MATERIALS[self.material].title,
            "wire_diameter": q(self.wire_diameter, "m"),
            "mean_diameter": q(self.mean_diameter, "m"),
            "outer_diameter": q(self.outer_diameter, "m"),
            "spring_index": q(self.index, "1"),
            "body_turns": q(self.body_turns, "1"), "active_turns": q(self.active_turns, "1"),
            "leg_length": q(self.leg_length, "m"),
            "rate": q(self.rate, "N·m/rad"),
            "rate_nmm_per_deg": q(nm_per_rad_to_nmm_per_deg(self.rate), "N·mm/deg"),
            "required_rate": q(self.requirement.rate, "N·m/rad"),
            "free_leg_angle": q(rad_to_deg(self.free_leg_angle), "deg"),
            "preload_angle": q(rad_to_deg(self.preload_angle), "deg"),
            "max_deflection": q(rad_to_deg(self.max_deflection), "deg"),
            "max_torque": q(self.max_torque, "N·m"),
            "stress": q(self.stress, "Pa"), "yield_strength": q(self.yield_strength, "Pa"),
            "safety_factor": q(self.safety_factor, "1"),
            "design_factor": q(self.design_factor, "1"),
            "wound_outer_diameter": q(self.wound_outer_diameter, "m"),
            "wound_inner_diameter": q(self.wound_inner_diameter, "m"),
            "arbor_diameter": q(self.arbor_diameter, "m"),
            "arbor_margin": q(self.requirement.arbor_margin, "1"),
            "max_outer_diameter": q(self.requirement.max_outer_diameter, "m"),
            "body_length": q(self.body_length, "m"), "mass": q(self.mass, "kg"),
        }

    def summary(self) -> str:
        """One line: material, d, D, OD, turns, rate, stress against S_y, mass."""
        return (f"{self.material} d {self.wire_diameter / MM:.2f} mm, "
                f"D {self.mean_diameter / MM:.2f} mm (OD {self.outer_diameter / MM:.2f} mm), "
                f"{self.body_turns:g} body turns, "
                f"rate {nm_per_rad_to_nmm_per_deg(self.rate):.4g} N·mm/deg, "
                f"preload {rad_to_deg(self.preload_angle):.0f}°, "
                f"σ {self.stress / 1e6:.0f}/{self.yield_strength / 1e6:.0f} MPa, "
                f"{1e3 * self.mass:.2f} g")


def _candidates(req: TorsionRequirement) -> dict[str, np.ndarray]:
    """Every (material, wire, body turns) with D from the rate equation; flat arrays."""
    rows: dict[str, list[np.ndarray]] = {}
    nb_grid = np.arange(N_B_MIN, N_B_MAX + TURN_STEP / 2, TURN_STEP)
    k_turn = req.rate * 2 * math.pi
    for m_index, name in enumerate(req.materials):
        mat = material(name)
        d = mat.wire_diameters()
        if not d.size:
            continue
        dd, nb = (a.ravel() for a in np.meshgrid(d, nb_grid, indexing="ij"))
        E = mat.young_modulus(dd)
        x = dd**4 * E / (WAHL * k_turn)  # = D · N_a
        if req.leg_length is None:
            D = x / (nb + 2 * LEG_RATIO / (3 * math.pi))
        else:
            D = (x - 2 * req.leg_length / (3 * math.pi)) / nb
        D = np.maximum(np.round(D / D_STEP) * D_STEP, D_STEP)
        leg = LEG_RATIO * D if req.leg_length is None else np.full_like(D, req.leg_length)
        na = active_turns(nb, D, leg, leg)
        k = rate(dd, D, na, E)
        # the design's stroke (max − preload torque)/rate at the required rate; installed so
        # that it gives the preload torque where it engages
        m_max = req.preload_torque + k * (req.max_torque - req.preload_torque) / req.rate
        theta_c = deflection_turns(m_max, dd, D, nb, E)
        Dw = wound_diameter(D, nb, theta_c)
        for key, value in (("material", np.full(dd.shape, m_index)), ("d", dd), ("D", D),
                           ("nb", nb), ("na", na), ("leg", leg), ("E", E), ("k", k),
                           ("m_max", m_max), ("theta_c", theta_c), ("Dw", Dw),
                           ("sy", mat.yield_strength(dd)),
                           ("stress", np.where(D > 1.5 * dd, bending_stress(
                               m_max, dd, np.maximum(D, 1.5 * dd)), np.inf)),
                           ("mass", mat.density * math.pi / 4 * dd**2
                            * (math.pi * D * nb + 2 * leg))):
            rows.setdefault(key, []).append(value)
    return {k: np.concatenate(v) for k, v in rows.items()}


def _ratios(c: dict[str, np.ndarray], req: TorsionRequirement) -> dict[str, np.ndarray]:
    """Each limit's use, ≤ 1 where met (names are the requirement's fields or the index)."""
    C = c["D"] / c["d"]
    inner = c["Dw"] - c["d"]
    wire = (np.zeros_like(c["d"]) if req.max_wire_diameter is None else
            np.where(c["d"] < req.max_wire_diameter, 0.0, np.inf))
    return {"max_outer_diameter": (c["D"] + c["d"]) / req.max_outer_diameter,
            "max_wire_diameter": wire,
            "max_torque": c["stress"] * req.safety_factor / c["sy"],
            "spring_index_min": C_MIN / C, "spring_index_max": C / C_MAX,
            "arbor_diameter": np.where(inner > 0, req.arbor_diameter * (1 + req.arbor_margin)
                                       / np.maximum(inner, 1e-12), np.inf)}


def _spring(c: dict[str, np.ndarray], i: int, req: TorsionRequirement) -> TorsionSpring:
    d, D, nb = float(c["d"][i]), float(c["D"][i]), float(c["nb"][i])
    k, m_max = float(c["k"][i]), float(c["m_max"][i])
    stress, sy = float(c["stress"][i]), float(c["sy"][i])
    return TorsionSpring(
        material=req.materials[int(c["material"][i])], wire_diameter=d, mean_diameter=D,
        body_turns=nb, active_turns=float(c["na"][i]), leg_length=float(c["leg"][i]), rate=k,
        free_leg_angle=2 * math.pi * (nb - math.floor(nb)),
        preload_angle=req.preload_torque / k, max_deflection=m_max / k, max_torque=m_max,
        stress=stress, yield_strength=sy, safety_factor=sy / stress,
        design_factor=req.safety_factor,
        wound_outer_diameter=float(c["Dw"][i]) + d, wound_inner_diameter=float(c["Dw"][i]) - d,
        arbor_diameter=req.arbor_diameter,
        body_length=d * (nb + 1 + float(c["theta_c"][i])), mass=float(c["mass"][i]),
        requirement=req)


@typed
def design_torsion_spring(req: TorsionRequirement) -> TorsionSpring:
    """The lightest helical torsion spring that meets ``req`` (module docstring).

    Args:
        req: The rate, torques, outer diameter limit, arbor, materials, design factor.

    Returns:
        The spring; its rate equals ``req.rate`` within the rounding of the mean diameter to
        :data:`D_STEP` (relative error ≤ D_STEP / D).

    Raises:
        SpringDesignError: no spring meets every limit; names the limit the nearest spring
            breaks, by how much, and carries that spring (``nearest``: the smallest outer
            diameter meeting every other limit, else the spring breaking its limits least).
    """
    c = _candidates(req)
    ratios = _ratios(c, req)
    worst = np.max(np.vstack(list(ratios.values())), axis=0)
    ok = worst <= 1 + 1e-12
    if ok.any():  # the lightest; of those within MASS_TIE of it, the shortest body
        light = ok & (c["mass"] <= (1 + MASS_TIE) * c["mass"][ok].min())
        length = c["d"] * (c["nb"] + 1 + c["theta_c"])
        i = int(np.flatnonzero(light)[np.argmin(length[light])])
        return _spring(c, i, req)
    others = np.max(np.vstack([v for k, v in ratios.items() if k != "max_outer_diameter"]),
                    axis=0)
    fits = others <= 1 + 1e-12
    if fits.any():  # the nearest: the smallest outer diameter meeting every other limit
        i = int(np.flatnonzero(fits)[np.argmin(ratios["max_outer_diameter"][fits])])
    else:  # nothing holds up in any diameter: the spring that breaks its limits least
        i = int(np.argmin(worst))
    nearest = _spring(c, i, req)
    binding = max(ratios, key=lambda n: ratios[n][i])
    what = {
        "max_outer_diameter": (req.max_outer_diameter, f">= {nearest.outer_diameter / MM:.2f} mm "
                                                       f"(m: {nearest.outer_diameter:.5f})"),
        "max_torque": (req.max_torque, f"<= {req.max_torque / ratios['max_torque'][i]:.4g} N·m "
                                       "in the wire that fits (or a larger max_outer_diameter)"),
        "spring_index_min": (nearest.index, f">= {C_MIN:g}: the rate needs a coil too tight for "
                                            "the wire; lower the rate or allow a thinner wire"),
        "spring_index_max": (nearest.index, f"<= {C_MAX:g}: the rate needs a coil too wide"),
        "arbor_diameter": (req.arbor_diameter, f"<= {nearest.wound_inner_diameter / MM:.2f} mm / "
                                               f"{1 + req.arbor_margin:g} (the clearance)"),
        "max_wire_diameter": (nearest.wire_diameter, f"< {(req.max_wire_diameter or 0) / MM:g} "
                              "mm, the wire the fatigue data at the required life cover "
                              "(Zimmerli's, for lives beyond 10⁶ cycles): [design] life_cycles "
                              "<= 1e6 checks thicker wire on Shigley's Table 10-10"),
    }[binding]
    thicker = ""
    if req.max_wire_diameter is not None and binding != "max_wire_diameter":
        free = np.max(np.vstack([v for k, v in ratios.items() if k != "max_wire_diameter"]),
                      axis=0) <= 1 + 1e-12
        if free.any():
            thicker = (f"; wire of {req.max_wire_diameter / MM:g} mm or more would carry it, "
                       "but the fatigue data beyond 10⁶ cycles (Zimmerli's) cover wire under "
                       "it: [design] life_cycles <= 1e6 allows it (Shigley's Table 10-10)")
    raise SpringDesignError(
        binding, what[0],
        f"{what[1]}; no {' or '.join(req.materials)} torsion spring of rate "
        f"{req.rate:.4g} N·m/rad carrying {req.max_torque:.4g} N·m fits{thicker}; nearest: "
        f"{nearest.summary()}", nearest=nearest)
