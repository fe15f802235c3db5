"""The configuration of ``hexaleg design``: the ``[design]`` table and the whole TOML document.

A design runs on a :class:`~hexaleg.scenario.scenario.Scenario` (the robot, ``[gait]``,
``[contact]``, ``[motor]``, read once by the scenario) with the ``[design]`` table
(:class:`DesignParams`, checked here by :func:`design_params`) and the ``[mission]`` table
(:func:`mission`). The actuator has one home, ``[motor]`` (a catalogue ``base`` with overrides,
read as every command reads it); without it the robot's own. ``[design] motor`` (a catalogue
name) is deprecated: it still works, with a warning saying where it went, and is refused beside
``[motor]``. Every key of ``[design]`` is a field of :class:`DesignParams`.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from hexaleg.checks import integer, is_real, named_arguments, real
from hexaleg.config import from_mapping
from hexaleg.design.evaluator import DEFAULT_METRIC
from hexaleg.design.families import FAMILIES, family
from hexaleg.design.fold import Mission
from hexaleg.design.robust.box import MODES
from hexaleg.design.springs.materials import MATERIALS, material
from hexaleg.design.springs.torsion_spring import SAFETY_FACTOR
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.motion.limits import MIN_SAMPLES
from hexaleg.motion.patterns import PATTERNS
from hexaleg.robot.catalogue import motor as motor_by_name
from hexaleg.scenario.scenario import Scenario
from hexaleg.simulation.controllers import BOTH, SERVOS

TABLES: tuple[str, ...] = ("gait", "contact", "design", "mission")
"""Tables ``hexaleg design`` reads; a config file may hold the other commands' too
(:data:`hexaleg.scenario.scenario.TABLES`), each checked by its owner."""
MAX_SAFETY_FACTOR = 10.0
"""The largest ``[design] safety_factor``: a static torsion spring is designed at 1.2–2 on its
yield strength (Shigley's *Mechanical Engineering Design* §10-12); at 100 the design bought 1.7 kg
of springs for a 1.4-kg robot (issue #58)."""
GROUPINGS: tuple[str, ...] = ("class", "mirrored", "joint")
"""One spring design per joint class (all legs), per left/right pair of legs, or per joint."""
METRICS: tuple[str, ...] = ("electrical", "joule")
"""Metrics the designs may be ranked by: those every step records — the saving net of the
springs' mass, the robustness maps (:data:`hexaleg.design.robust.maps.METRICS`) and the robust
program (:data:`hexaleg.design.robust.box.METRICS`)."""


def _floats(name: str, values: Any, low: float, low_open: bool, what: str) -> tuple[float, ...]:
    if isinstance(values, (str, bytes)) or not isinstance(values, (list, tuple)) or not values:
        raise InvalidParameterError(f"design.{name}", values, f"a non-empty list of {what}")
    return tuple(real(f"design.{name}", v, low=low, low_open=low_open,
                      allowed=f"{what} ({'>' if low_open else '>='} {low:g})") for v in values)


@named_arguments
@dataclass(frozen=True)
class DesignParams:
    """The ``[design]`` table (SI; factors relative to the nominal gait).

    Attributes:
        families: Spring families to design (:data:`~hexaleg.design.families.FAMILIES`).
        classes: Joint classes that may carry springs; empty: every class of the robot.
        grouping: One of :data:`GROUPINGS` (mirrored and per-joint designs keep the class
            optimum's geometry and re-solve the magnitudes: one convex program each).
        max_torque: Largest spring torque over the gait, N·m, or None.
        max_deflection: Largest wind-up of a spring from its free position, rad (default π: half
            a turn), or ``"none"`` for no bound (then a design may need a constant-torque
            spring, which is flagged).
        metric: The metric the designs are ranked by, one of :data:`METRICS` (default the
            energy the servos draw).
        motor: Deprecated (a catalogue servo on every joint): the actuator's home is the file's
            ``[motor]`` table (:attr:`Scenario.actuator
            <hexaleg.scenario.scenario.Scenario.actuator>`).
        samples: Samples per gait cycle of the design and the maps.
        materials: Wire materials (:data:`~hexaleg.design.springs.materials.MATERIALS`).
        safety_factor: Design factor on the wire's bending yield strength, ≥ 1.
        arbor_diameter: The pin a spring winds onto, m, ≥ 0.
        leg_length: Length of each spring leg, m, or None (one mean coil diameter).
        max_outer_diameter: Joint class → largest spring outer diameter, m (over the robot
            description's, else the width of the links).
        map_period: Period factors of the period × stride map.
        map_stride: Stride factors of the period × stride map.
        map_payload: Payloads (fractions of the robot's mass) of the payload × μ map.
        map_mu: Friction coefficients of the payload × μ map.
        map_slope: Ground slopes of the slope × pattern map, rad, positive uphill along the
            walking direction, each in (−π/2, π/2) (default −15°, −7.5°, 0, 7.5°, 15°).
        map_pattern: Gait patterns of the slope × pattern map
            (:data:`~hexaleg.motion.patterns.PATTERNS`, each at its own duty factor); None
            (default): the nominal gait's and every other the robot's legs can walk
            (:func:`~hexaleg.design.robust.maps.robot_patterns`: tripod, ripple, wave on the
            hexapod; trot, crawl, pace on a quadruped).
        robust_period: ``[low, high]`` period factors of the robust design's box.
        robust_stride: ``[low, high]`` stride factors of the box.
        robust_payload: ``[low, high]`` payload fractions of the box.
        robust_mu: ``[low, high]`` friction coefficients of the box.
        robust_mode: ``"worst"`` (maximise the worst saving over the box's corners and the
            nominal gait) or ``"mean"``.
        pareto_fractions: ``max_torque`` of the Pareto points as fractions (0, 1) of the
            recommended design's peak spring torque.
        controller: The servo the robot runs (:data:`~hexaleg.simulation.controllers.SERVOS`):
            ``"feedforward"`` or ``"position"``, every ranked design simulated under it and the
            recommendation the best simulated one; ``"both"`` (default, a robot that may run
            either), every design simulated under each and ranked by the worse.
        min_group_saving: A joint class whose springs' worth (the ranking metric's saving lost
            without them all) is below this fraction of the baseline (default 0.01: one point)
            is not fitted, whatever the grouping.
        stop_tolerance: How far a workshop may mount a spring's stop from its drawing, rad
            (default 1°); the design is chosen for its worst saving within it. 0: no tolerance.
        life_cycles: The load cycles each spring must survive (fatigue), ≥ 1 (default 10⁷).
        mirror: Share one physical design across a mirror: joints that count their angle the
            other way round from their twin (:func:`hexaleg.robot.mirror.mirror`, from the
            joint axes) get their group's spring mirrored (default true).
        robustness: Compute the robustness maps and the robust design over the box of
            conditions (default true). Neither is one of the spring rules — they show and design
            for conditions other than the nominal gait — so ``hexaleg codesign``, which applies
            the rules to the gait it chose, leaves them out (false).

    Raises:
        UnknownNameError: an unknown family, grouping, metric, material or motor.
        InvalidParameterError: a value out of range.
    """

    families: tuple[str, ...] = ("linear", "one_sided", "preloaded", "dead_zone")
    classes: tuple[str, ...] = ()
    grouping: str = "class"
    max_torque: float | None = None
    max_deflection: float | str | None = math.pi
    metric: str = DEFAULT_METRIC
    motor: str | None = None
    samples: int = 200
    materials: tuple[str, ...] = tuple(MATERIALS)
    safety_factor: float = SAFETY_FACTOR
    arbor_diameter: float = 0.0
    leg_length: float | None = None
    max_outer_diameter: Mapping[str, float] = field(default_factory=dict)
    map_period: tuple[float, ...] = (0.5, 0.71, 1.0, 1.41, 2.0)
    map_stride: tuple[float, ...] = (0.5, 0.75, 1.0, 1.25, 1.5)
    map_payload: tuple[float, ...] = (0.0, 0.1, 0.2, 0.3, 0.4, 0.5)
    map_mu: tuple[float, ...] = (0.3, 0.45, 0.6, 0.8, 1.0)
    map_slope: tuple[float, ...] = tuple(math.radians(a) for a in (-15.0, -7.5, 0.0, 7.5, 15.0))
    map_pattern: tuple[str, ...] | None = None
    robust_period: tuple[float, ...] = (0.75, 1.5)
    robust_stride: tuple[float, ...] = (0.75, 1.25)
    robust_payload: tuple[float, ...] = (0.0, 0.25)
    robust_mu: tuple[float, ...] = (0.5, 1.0)
    robust_mode: str = "worst"
    pareto_fractions: tuple[float, ...] = (0.25, 0.5, 0.75)
    controller: str = BOTH
    min_group_saving: float = 0.01
    stop_tolerance: float = math.pi / 180
    life_cycles: float = 1e7
    mirror: bool = True
    robustness: bool = True

    def __post_init__(self) -> None:
        set_ = lambda name, value: object.__setattr__(self, name, value)  # noqa: E731
        if isinstance(self.families, str) or not self.families:
            raise InvalidParameterError("design.families", self.families,
                                        f"a non-empty list of {', '.join(FAMILIES)}")
        for name in self.families:
            family(name)
        set_("families", tuple(self.families))
        set_("classes", tuple(self.classes))
        if self.grouping not in GROUPINGS:
            raise UnknownNameError("design.grouping", self.grouping, GROUPINGS)
        if self.max_deflection == "none":
            set_("max_deflection", None)
        for name, unit, off in (("max_torque", "N·m", "leave it out"),
                                ("max_deflection", "rad", '"none" for no bound')):
            if getattr(self, name) is not None:  # as a float: an int bound is a bound too
                set_(name, real(f"design.{name}", getattr(self, name), low=0.0, low_open=True,
                                allowed=f"a finite value > 0 ({unit}), or {off}"))
        if self.metric not in METRICS:
            raise UnknownNameError("design.metric", self.metric, METRICS)
        if self.motor is not None:
            motor_by_name(self.motor)  # UnknownNameError listing the catalogue
            warnings.warn(f"[design] motor = {self.motor!r} is deprecated: the actuator's one "
                          f"home is [motor] (write [motor] base = {self.motor!r})",
                          DeprecationWarning, stacklevel=2)
        integer("design.samples", self.samples, low=MIN_SAMPLES)
        if isinstance(self.materials, str) or not self.materials:
            raise InvalidParameterError("design.materials", self.materials,
                                        f"a non-empty list of {', '.join(MATERIALS)}")
        for name in self.materials:
            material(name)
        set_("materials", tuple(self.materials))
        real("design.safety_factor", self.safety_factor, low=1.0, high=MAX_SAFETY_FACTOR,
             allowed=f"1 to {MAX_SAFETY_FACTOR:g} (static torsion springs are designed at "
                     "1.2 to 2, Shigley §10-12)")
        real("design.arbor_diameter", self.arbor_diameter, low=0.0, allowed=">= 0 m")
        if self.leg_length is not None:
            real("design.leg_length", self.leg_length, low=0.0, allowed=">= 0 m, or leave it out")
        if not isinstance(self.max_outer_diameter, Mapping) or not all(
                isinstance(k, str) and is_real(v) and v > 0
                for k, v in self.max_outer_diameter.items()):
            raise InvalidParameterError("design.max_outer_diameter", self.max_outer_diameter,
                                        "a table of joint class = diameter > 0 (m)")
        for name, what, low, low_open in (
                ("map_period", "factors", 0.0, True), ("map_stride", "factors", 0.0, True),
                ("map_payload", "fractions of the robot's mass", 0.0, False),
                ("map_mu", "friction coefficients", 0.0, True),
                ("robust_period", "factors", 0.0, True), ("robust_stride", "factors", 0.0, True),
                ("robust_payload", "fractions of the robot's mass", 0.0, False),
                ("robust_mu", "friction coefficients", 0.0, True)):
            set_(name, _floats(name, getattr(self, name), low, low_open, what))
        slopes = self.map_slope
        if isinstance(slopes, (str, bytes)) or not isinstance(slopes, (list, tuple)) or not slopes:
            raise InvalidParameterError("design.map_slope", slopes, "a non-empty list of angles "
                                        "in (−π/2, π/2) rad, positive uphill")
        set_("map_slope", tuple(real("design.map_slope", a, low=-math.pi / 2, high=math.pi / 2,
                                     low_open=True, high_open=True,
                                     allowed="angles in (−π/2, π/2) rad, positive uphill")
                                for a in slopes))
        if self.map_pattern is not None:
            if isinstance(self.map_pattern, str) or not self.map_pattern:
                raise InvalidParameterError("design.map_pattern", self.map_pattern,
                                            f"a non-empty list of {', '.join(PATTERNS)}, or "
                                            "leave it out for the robot's own")
            for name in self.map_pattern:
                if name not in PATTERNS:
                    raise UnknownNameError("design.map_pattern", name, PATTERNS)
            set_("map_pattern", tuple(self.map_pattern))
        for name in ("robust_period", "robust_stride", "robust_payload", "robust_mu"):
            box = getattr(self, name)
            if len(box) != 2 or box[0] > box[1]:
                raise InvalidParameterError(f"design.{name}", list(box), "[low, high], low <= high")
        if self.robust_mode not in MODES:
            raise UnknownNameError("design.robust_mode", self.robust_mode, MODES)
        set_("pareto_fractions", tuple(real("design.pareto_fractions", f, low=0.0, high=1.0,
                                            low_open=True, high_open=True,
                                            allowed="fractions in (0, 1)")
                                       for f in self.pareto_fractions))
        if self.controller not in SERVOS:
            raise UnknownNameError("design.controller", self.controller, SERVOS)
        set_("min_group_saving", real("design.min_group_saving", self.min_group_saving, low=0.0,
                                      high=1.0, allowed="a fraction in [0, 1] of the baseline"))
        set_("stop_tolerance", real("design.stop_tolerance", self.stop_tolerance, low=0.0,
                                    high=math.radians(10.0),
                                    allowed="an angle in [0, 0.1745] rad (0 to 10°)"))
        set_("life_cycles", real("design.life_cycles", self.life_cycles, low=1.0, high=1e12,
                                 allowed="a number of cycles in [1, 1e12]"))

    @property
    def deflection_bound(self) -> float | None:
        """:attr:`max_deflection` as a number, or None for no bound."""
        return self.max_deflection if isinstance(self.max_deflection, float) else None


def _one_home(design: DesignParams, motor: Any, where: str) -> None:
    """Refuse the actuator in two homes: a ``[motor]`` table beside the deprecated ``[design]
    motor``."""
    if motor and design.motor is not None:
        raise ConfigError(f"{where}: [design] motor = {design.motor!r} beside a [motor] table: "
                          "the actuator has one home, [motor]; remove [design] motor")


def design_params(scenario: Scenario, controller: str | None = None, *,
                  design: DesignParams | None = None) -> DesignParams:
    """The design's settings for a run: the file's ``[design]`` table (checked here, its
    owner) or ``design``, with ``controller`` (``--controller``) over its ``controller``.

    Raises:
        ConfigError, UnknownNameError, InvalidParameterError: a bad ``[design]`` value;
            ``[design] samples`` with a log (named); ``[design] motor`` beside ``[motor]``.
    """
    s = scenario
    table = s.table("design")
    if s.log is not None and "samples" in table:
        raise InvalidParameterError(
            f"{s.where} [design] samples", table["samples"],
            f"no samples with --motion {s.log}: the logged cycle keeps its own samples; "
            "remove the key or the --motion option")
    if design is None:
        design = from_mapping(DesignParams, table, f"{s.where} [design]")
    _one_home(design, s.table("motor"), s.where)
    if controller:
        design = dataclasses.replace(design, controller=controller)
    return design


def design_run(scenario: Scenario, design: DesignParams) -> Scenario:
    """The run a design works on: ``scenario`` at ``[design] samples`` with Joule-optimal
    forces, and the deprecated ``[design] motor`` on every joint where it is given (the file's
    ``[motor]`` beside it is refused by :func:`design_params`)."""
    run = scenario.with_samples(design.samples).replace(objective="joule")
    return run if design.motor is None else run.replace(actuator=motor_by_name(design.motor))


def mission(scenario: Scenario) -> Mission:
    """The run's ``[mission]`` table (:class:`~hexaleg.design.fold.Mission`)."""
    return from_mapping(Mission, scenario.table("mission"), f"{scenario.where} [mission]")
