"""Is a cost of transport plausible for a legged machine of this mass? One check, one rule.

A result built on assumed actuator constants (a generic actuator from URDF limits,
:func:`hexaleg.robot.motor.generic_actuator`) or a defective model can be off by orders of
magnitude without any error. :func:`check_cost_of_transport` compares the dimensionless cost of
transport ``E / (m g d)`` (paper eq. 23; Gabrielli & von Kármán, "What price speed?", Mechanical
Engineering 72, 1950; Tucker, "The energetic cost of moving about", American Scientist 63(4),
1975) against a band around the animal line of the same mass:

* **Reference** (:func:`animal_cost_of_transport`): the minimum (incremental) metabolic cost of
  transport of running animals and birds from 7 g to 250 kg, ``10.7 M^-0.316`` J/(kg·m)
  (Taylor, Heglund & Maloiy, "Energetics and mechanics of terrestrial locomotion. I", J. Exp.
  Biol. 97, 1982, eq. for ``E_metab / M_b`` against speed: slope ``10.7 M_b^-0.316``), divided
  by ``g`` to be dimensionless — Tucker's line for walking and running animals.
* **Low bound** :data:`LOW_FACTOR` × reference: the most efficient legged machines reach the
  animal line and no further — the Cornell biped 0.2 against a human's 0.2 (Collins, Ruina,
  Tedrake & Wisse, "Efficient bipedal robots based on passive-dynamic walkers", Science 307,
  2005), Cornell Ranger 0.19 at 9.9 kg, 0.36 × its line (Bhounsule et al., IJRR 33(10), 2014).
  A motor-only model (no electronics, ideal contacts) may sit below them by a small factor;
  below a quarter of the line the energy is almost certainly missing a term (an actuator too
  strong for its limits, a mass too small).
* **High bound** :data:`HIGH_FACTOR` × reference: ASIMO's ratio to its line, 3.2 at 52 kg
  (Collins, Ruina, Tedrake & Wisse 2005), 10.3 ×: the least efficient electric legged robot of
  the surveys, so no electric robot is known above it. MIT Cheetah sits at 0.51 at 33 kg, 1.4 ×
  (Seok et al., "Design principles for energy-efficient legged locomotion and implementation on
  the MIT Cheetah robot", IEEE/ASME T-Mech 20(3), 2015); BigDog's 15 (hydraulic, engine-driven;
  quoted by Seok et al.) is outside the electric servo model here. (Before issue #40 the bound
  was twice ASIMO's ratio, and a generic actuator 19.8 × the line passed it.)
* **Published robots** (:data:`PUBLISHED`): the verdict also lists the published costs of
  transport of legged robots within a factor of two of the mass, with the ratio of the checked
  value to each, for context (not a flag: their speeds and what they count differ).

* **Measured robots** (:data:`MEASURED`, :func:`measured_beside`): published whole-robot
  power and cost-of-transport figures, set beside a run's predicted draw and cost of transport
  (and its sourced band, when its actuators are generic) where the run's robot is the measured
  one (or of its family), or the measured robot is of its mass class (within a factor of two):
  ANYmal B under 280 W at full speed (Hutter et al. 2016; no speed, so no cost of transport), a
  15.65-kg quadruped's 23.4 W for locomotion at 0.4 m/s (Arm et al. 2025; its cost of
  transport 23.4 / (15.65 g 0.4) = 0.381 is computed here from those three figures) and
  ANYmal's full cost of transport 1.27 (Bjelonic, Tischhauser & Hutter 2025, as its abstract
  gives it; which ANYmal is not said there). Context, not a flag: speeds and what each counts
  differ, and both are said.

The bounds are a rule to flag, not a law: a result outside them is reported as implausible with
the numbers (``flag`` ``"low"`` or ``"high"``), never refused.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from hexaleg.checks import positive, real
from hexaleg.robot.actuator import Actuator
from hexaleg.robot.motor import GENERIC_MARK
from hexaleg.units import G

TAYLOR_COEFFICIENT = 10.7
"""Minimum metabolic cost of transport of running animals at 1 kg, J/(kg·m) (Taylor, Heglund &
Maloiy 1982)."""
TAYLOR_EXPONENT = -0.316
"""Its mass exponent (Taylor, Heglund & Maloiy 1982)."""
LOW_FACTOR = 0.25
"""Below this fraction of the animal line a cost of transport is flagged ``"low"`` (module
docstring: the best legged machines reach 0.36 × their line)."""
ASIMO_COST_OF_TRANSPORT = 3.2
"""ASIMO's cost of transport (Collins, Ruina, Tedrake & Wisse, Science 307, 2005)."""
ASIMO_MASS = 52.0
"""ASIMO's mass, kg (Collins et al. 2005)."""


@dataclass(frozen=True)
class PublishedRobot:
    """A legged robot's published cost of transport.

    Attributes:
        name: The robot. mass: Its mass, kg. cost_of_transport: The published value, 1.
        counts: What the value counts (e.g. the whole robot's electrical draw).
        source: The publication.
    """

    name: str
    mass: float
    cost_of_transport: float
    counts: str
    source: str


PUBLISHED: tuple[PublishedRobot, ...] = (
    PublishedRobot("Cornell Ranger", 9.9, 0.19, "whole robot, electrical",
                   "Bhounsule et al., IJRR 33(10), 2014"),
    PublishedRobot("Cornell biped", 13.0, 0.2, "whole robot, electrical",
                   "Collins, Ruina, Tedrake & Wisse, Science 307, 2005"),
    PublishedRobot("MIT Cheetah", 33.0, 0.51, "whole robot, electrical, at 6 m/s",
                   "Seok et al., IEEE/ASME T-Mech 20(3), 2015"),
    PublishedRobot("ASIMO", ASIMO_MASS, ASIMO_COST_OF_TRANSPORT, "whole robot, electrical",
                   "Collins, Ruina, Tedrake & Wisse, Science 307, 2005"),
)
"""Published costs of transport of electric legged robots (module docstring)."""


@dataclass(frozen=True)
class MeasuredPower:
    """A legged robot's published whole-robot power or cost of transport.

    Attributes:
        name: The robot as the source names it.
        robots: hexaleg registry names of that robot (empty: only its mass class matches).
        mass: Its mass, kg; None: not in the source.
        power: The published power, W; None: the source gives a cost of transport only.
        speed: The speed it was measured at, m/s; None: not stated.
        upper: Whether the power is an upper limit ("less than") rather than a value.
        counts: What it counts, in words.
        source: The publication, with the quote.
        cost_of_transport: The published cost of transport, 1; None: not published (then
            :attr:`computed_cost_of_transport` gives it where power, mass and speed are known).
        matches: How a run of one of :attr:`robots` matches it, in words.
    """

    name: str
    robots: tuple[str, ...]
    mass: float | None
    power: float | None
    speed: float | None
    upper: bool
    counts: str
    source: str
    cost_of_transport: float | None = None
    matches: str = "the same robot"

    @property
    def computed_cost_of_transport(self) -> float | None:
        """``P / (m g v)`` from the published power, mass and speed (eq. 23 per unit time), or
        None where one of them is not published or the power is an upper limit."""
        if self.power is None or self.mass is None or self.speed is None or self.upper:
            return None
        return self.power / (self.mass * G * self.speed)


MEASURED: tuple[MeasuredPower, ...] = (
    MeasuredPower("ANYmal (B)", ("anymal",), None, 280.0, None, True,
                  "the whole robot, 'full-speed running' (the speed is not in the abstract)",
                  "Hutter et al., 'ANYmal - a highly mobile and dynamic quadrupedal robot', "
                  "IROS 2016, abstract: 'even full-speed running requires less than 280 W, "
                  "resulting in an autonomy of more than 2 h'"),
    MeasuredPower("a 15.65-kg quadruped (platform not named in the abstract)", (), 15.65, 23.4,
                  0.4, False, "power for locomotion in Earth gravity",
                  "Arm, Fischer, Church, Fuhrer, Kolvenbach & Hutter 2025, arXiv:2509.10128: "
                  "'power consumption for locomotion of 23.4 W in Earth gravity on a 15.65 kg "
                  "robot at 0.4 m/s'"),
    MeasuredPower("ANYmal (which one is not named in the abstract)", ("anymal", "anymal_c"),
                  None, None, None, False, "the full cost of transport, whole robot, with the "
                  "paper's learned policy (speed not in the abstract)",
                  "Bjelonic, Tischhauser & Hutter 2025, 'Towards bridging the gap: systematic "
                  "sim-to-real transfer for diverse legged robots', arXiv:2509.06342, abstract: "
                  "'achieving a 32% reduction in the full Cost of Transport of ANYmal (1.27)'",
                  cost_of_transport=1.27,
                  matches="its family: the abstract does not say which ANYmal"),
)
"""Published whole-robot power and cost of transport of electric quadrupeds
(shared/reference/motor-sources.md, items 1 and 2)."""


def measured_beside(robot: str | None, mass: float, predicted: float,
                    band: tuple[float, float] | None = None,
                    speed: float | None = None) -> list[dict[str, Any]]:
    """The measured robots that match a run, each beside its prediction.

    Args:
        robot: The run's registry name (None: a description file, matched by mass only).
        mass: The run's robot mass, kg, > 0.
        predicted: The run's predicted mean draw without springs, W, ≥ 0.
        band: The sourced band's (low, high) mean power, W, or None.
        speed: The run's mean speed, m/s, > 0, for its cost of transport ``P / (m g v)``;
            None: a motion in place (no cost of transport).

    Returns:
        One dict per match: the figure (power and cost of transport, each None where the source
        gives none; a cost of transport computed from the quoted power, mass and speed says so),
        what it counts, its source, why it matches ("the same robot", its family or "its mass
        class"), the prediction and band beside it (W, and as costs of transport), and whether
        the band's low end (else the prediction) is at most the figure where the figure is an
        upper limit.
    """
    positive("mass", mass)
    real("predicted power", predicted, low=0.0, allowed="a finite number ≥ 0")
    per = None if speed is None else 1.0 / (mass * G * positive("speed", speed))
    out = []
    for m in MEASURED:
        if robot is not None and robot in m.robots:
            why = m.matches
        elif m.mass is not None and 0.5 <= m.mass / mass <= 2.0:
            why = f"its mass class: {m.mass:g} kg against {mass:.3g} kg, within 2 ×"
        else:
            continue
        low = predicted if band is None else band[0]
        cot = m.cost_of_transport if m.cost_of_transport is not None else (
            m.computed_cost_of_transport)
        how = (None if cot is None else "published" if m.cost_of_transport is not None else
               "computed here from the quoted power, mass and speed, P / (m g v)")
        figure = ("" if m.power is None else
                  f"{'under ' if m.upper else ''}{m.power:g} W, ") + (
            "" if cot is None else f"cost of transport {cot:.3g} ({how}), ")
        out.append({
            "robot": m.name, "matches": why,
            "power": None if m.power is None else {"value": m.power, "unit": "W"},
            "upper_limit": m.upper,
            "speed": None if m.speed is None else {"value": m.speed, "unit": "m/s"},
            "cost_of_transport": None if cot is None else {"value": cot, "unit": "1"},
            "cost_of_transport_is": how,
            "counts": m.counts, "source": m.source,
            "predicted": {"value": predicted, "unit": "W"},
            "predicted_cost_of_transport": None if per is None else {
                "value": predicted * per, "unit": "1"},
            "band": None if band is None else {"low": {"value": band[0], "unit": "W"},
                                               "high": {"value": band[1], "unit": "W"}},
            "band_cost_of_transport": None if band is None or per is None else {
                "low": {"value": band[0] * per, "unit": "1"},
                "high": {"value": band[1] * per, "unit": "1"}},
            "consistent": (low <= m.power) if m.upper and m.power is not None else None,
            "line": (f"{m.name}, {why}: {figure}{m.counts}"
                     + (f" at {m.speed:g} m/s" if m.speed is not None else "")
                     + f"; predicted {predicted:.4g} W"
                     + ("" if per is None else f", cost of transport {predicted * per:.3g}")
                     + ("" if band is None else f", sourced band {band[0]:.4g}–{band[1]:.4g} W"
                        + ("" if per is None else
                           f" (cost of transport {band[0] * per:.3g}–{band[1] * per:.3g})")))})
    return out


def animal_cost_of_transport(mass: float) -> float:
    """The animal line: ``10.7 M^-0.316 / g`` (Taylor, Heglund & Maloiy 1982), dimensionless.

    Args:
        mass: Body mass M, kg, > 0.

    Returns:
        The minimum cost of transport of a running animal of that mass (1).
    """
    return TAYLOR_COEFFICIENT * positive("mass", mass) ** TAYLOR_EXPONENT / G


HIGH_FACTOR = ASIMO_COST_OF_TRANSPORT / animal_cost_of_transport(ASIMO_MASS)
"""Above this multiple of the animal line a cost of transport is flagged ``"high"``: ASIMO's
ratio, 10.3 (module docstring)."""


def comparable(mass: float) -> tuple[PublishedRobot, ...]:
    """The published robots within a factor of two of ``mass`` (:data:`PUBLISHED`)."""
    return tuple(r for r in PUBLISHED if 0.5 <= r.mass / mass <= 2.0)


def plausible_range(mass: float) -> tuple[float, float]:
    """``(low, high)`` cost of transport of a legged machine of ``mass`` kg (module docstring)."""
    ref = animal_cost_of_transport(mass)
    return LOW_FACTOR * ref, HIGH_FACTOR * ref


def uses_generic(motor: Actuator) -> bool:
    """Whether any joint's actuator is a :func:`~hexaleg.robot.motor.generic_actuator` (its notes
    open with the generic actuator's statement of assumptions)."""
    return any(m.notes.startswith(GENERIC_MARK) for m in motor.models.values())


@dataclass(frozen=True)
class Plausibility:
    """The verdict of :func:`check_cost_of_transport`.

    Attributes:
        cost_of_transport: The checked value E / (m g d), 1.
        mass: The robot's mass, kg.
        reference: The animal line at that mass, 1.
        low: The low bound, 1. high: The high bound, 1.
        flag: ``None`` inside the band, ``"low"`` or ``"high"`` outside.
        message: One sentence with the numbers and, when flagged, what to check.
    """

    cost_of_transport: float
    mass: float
    reference: float
    low: float
    high: float
    flag: str | None
    message: str

    @property
    def plausible(self) -> bool:
        """Whether the value is inside the band."""
        return self.flag is None

    def as_dict(self) -> dict[str, Any]:
        """JSON form: the numbers as ``{value, unit}`` quantities, the flag and the message."""
        def one(x: float) -> dict[str, Any]:
            return {"value": x, "unit": "1"}

        return {"cost_of_transport": one(self.cost_of_transport),
                "mass": {"value": self.mass, "unit": "kg"}, "animal_line": one(self.reference),
                "low": one(self.low), "high": one(self.high), "plausible": self.plausible,
                "flag": self.flag, "message": self.message,
                "rule": f"[{LOW_FACTOR:g}, {HIGH_FACTOR:.3g}] x 10.7 M^-0.316 / g (Taylor, "
                        "Heglund & Maloiy 1982; the high bound is ASIMO's ratio; "
                        "hexaleg.dynamics.plausibility)",
                "published": [{"robot": r.name, "mass": {"value": r.mass, "unit": "kg"},
                               "cost_of_transport": one(r.cost_of_transport),
                               "ratio": one(self.cost_of_transport / r.cost_of_transport),
                               "counts": r.counts, "source": r.source}
                              for r in comparable(self.mass)]}


def check_cost_of_transport(cost: float, mass: float, *, what: str = "electrical energy",
                            generic: bool = False) -> Plausibility:
    """Compare a cost of transport with the plausible band for a legged machine of ``mass``.

    Args:
        cost: The cost of transport E / (m g d), finite, ≥ 0.
        mass: Robot mass, kg, > 0.
        what: The energy it is made of, for the message.
        generic: Whether the actuators are generic (assumed from URDF limits): the message then
            names that as the first thing to replace.

    Returns:
        The verdict, flagged outside ``[LOW_FACTOR, HIGH_FACTOR] × animal line``.

    Raises:
        InvalidParameterError: ``cost`` negative or not finite, ``mass`` not > 0.
    """
    cot = real("cost of transport", cost, low=0.0, allowed="a finite number ≥ 0")
    ref = animal_cost_of_transport(mass)
    low, high = LOW_FACTOR * ref, HIGH_FACTOR * ref
    head = (f"cost of transport {cot:.3g} ({what}) at {mass:.3g} kg, "
            f"{cot / ref:.2g} × the animal line {ref:.3g}")
    fix = ("the actuators are generic (from URDF limits): give the robot catalogue motors "
           "(hexaleg motors) or identified constants ([motor] base = …) — "
           if generic else "")
    if cot < low:
        flag: str | None = "low"
        msg = (f"implausibly low: {head}, below {low:.3g} ({LOW_FACTOR:g} × the line, where no "
               f"legged machine has gone); check {fix}the masses and the actuators' constants")
    elif cot > high:
        flag = "high"
        msg = (f"implausibly high: {head}, above {high:.3g} ({HIGH_FACTOR:.3g} × the line: "
               f"ASIMO's ratio, the least efficient electric legged robot published); check "
               f"{fix}the actuators' constants and the gait's speed")
    else:
        flag, msg = None, (f"plausible: {head}, within [{low:.3g}, {high:.3g}]"
                           + (" (generic actuators: the value is an estimate)" if generic else ""))
    return Plausibility(cot, float(mass), ref, low, high, flag, msg)


def check_baseline(baseline: dict[str, Any], mass: float, motor: Actuator
                   ) -> Plausibility | None:
    """The baseline's electrical cost of transport (``metrics["cost_of_transport"]
    ["electrical"]`` of :func:`hexaleg.dynamics.energy.metrics`) checked by
    :func:`check_cost_of_transport`, the message naming a generic ``motor``; None for a motion
    in place (no cost of transport). The one check of ``report`` and ``design``."""
    cot = baseline.get("cost_of_transport", {}).get("electrical")
    if cot is None:
        return None
    return check_cost_of_transport(cot, mass, generic=uses_generic(motor))


__all__ = ["HIGH_FACTOR", "LOW_FACTOR", "MEASURED", "PUBLISHED", "MeasuredPower",
           "Plausibility", "PublishedRobot", "animal_cost_of_transport", "check_baseline",
           "check_cost_of_transport", "comparable", "measured_beside", "plausible_range",
           "uses_generic"]
