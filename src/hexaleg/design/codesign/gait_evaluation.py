"""One candidate gait of the gait + spring co-design: its energy per metre with and without its
best springs, and every constraint of :class:`Constraints` measured on it.

A gait at a required speed ``v`` is :class:`~hexaleg.motion.params.GaitParams` with five free
parameters (:data:`PARAMETERS`: body height, foot radius, step height, duty factor, period; the
stride is ``v · period``). :func:`evaluate_gait` makes it (:func:`hexaleg.motion.legged.gait`),
prepares it (:func:`hexaleg.dynamics.prepare.prepare`) and, when springs are asked for, solves
the inner spring program (:func:`hexaleg.design.search.optimal.optimal_springs`, a family's
magnitudes the global optimum of one convex program minimising the electrical energy). The objective
is the servos' electrical energy per cycle over the distance per cycle, ``E / (v T)`` J/m; the cost
of transport is ``E / (m g d)`` (Gabrielli & von Kármán, "What price speed?", Mech. Eng. 72, 1950).

A gait that cannot be made or has no admissible forces (a foot out of reach, a joint out of its
limits, no forces inside the friction cones and torque limits) is a :class:`GaitPoint` with its
error, never an exception, so the outer search can penalise it
(:mod:`hexaleg.design.codesign.gait_search`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import numpy as np

from hexaleg.checks import nonnegative, real
from hexaleg.design.search.optimal import Groups, optimal_springs
from hexaleg.dynamics.contact import ContactParams, friction_usage
from hexaleg.dynamics.energy import G
from hexaleg.dynamics.prepare import Prepared, prepare
from hexaleg.errors import HexalegError, InvalidParameterError
from hexaleg.motion.legged import gait
from hexaleg.motion.params import GaitParams
from hexaleg.motion.sanity import speed_ratio
from hexaleg.motion.support import static_margins
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet

PARAMETERS: tuple[str, ...] = ("body_height", "foot_radius", "step_height", "duty_factor",
                               "period")
"""The gait parameters the co-design chooses (the stride follows from the speed)."""
UNITS = {"body_height": "m", "foot_radius": "m", "step_height": "m", "duty_factor": "1",
         "period": "s"}
"""Unit of each of :data:`PARAMETERS`."""
METRIC = "electrical"
"""What is minimised: the energy the servos draw (no regeneration), J per cycle."""


@dataclass(frozen=True)
class Constraints:
    """What a co-designed gait must respect; each a setting with its default.

    Attributes:
        min_static_margin: Smallest static margin over the cycle, m (McGhee & Frank, Math.
            Biosci. 3, 1968: the CoM's ground projection inside the stance feet's polygon);
            None (default): the robot's default gait's own at the same speed.
        speed_fraction: Peak joint speed at most this fraction of the URDF velocity limit
            (the actuator's, AX-18A datasheet for hexaleg), default 1.
        torque_limits: Motor torques within each servo's stall torque (inside the force
            program, :class:`~hexaleg.dynamics.contact.ContactParams`), default True.
        mu: Friction coefficient of the floor, default 0.6 (the analysis' assumed rubber on
            a hard floor).
        friction_margin: The planned foot forces use at most this fraction of the friction
            cone, ``|f_t| ≤ friction_margin · μ f_n``, in (0, 1], default 0.7: the gait
            search and its inner spring program plan with ``friction_margin · μ``
            (:meth:`planning_contact`), so a gait whose energy leans on the cone's edge is not
            chosen (issue #41: at 0.90 of the cone the co-designed gait's feet slipped in
            simulation, and on a grippier floor its springs saved half as much). The full
            spring rules on the chosen gait design at the floor's μ (at the narrowed cone the
            preloaded family's condensed program failed numerically there), and their
            design.json states the friction their forces plan to use.
        min_foot_clearance: Lowest swing apex of a foot above the ground, m (the step height's
            lower bound), default 0.015 (assumed: half the default gait's 0.03 m step).
        min_body_clearance: Lowest point of the body's (base link's) geometry above the ground
            over the cycle, m, default 0.02 (assumed); robots whose base geometry is a mesh use
            the base origin's height.

    Joint position limits and reach are always enforced: the gait generator refuses a foot out
    of reach or a joint out of its URDF limits.
    """

    min_static_margin: float | None = None
    speed_fraction: float = 1.0
    torque_limits: bool = True
    mu: float = 0.6
    friction_margin: float = 0.7
    min_foot_clearance: float = 0.015
    min_body_clearance: float = 0.02

    def __post_init__(self) -> None:
        if self.min_static_margin is not None:
            nonnegative("constraints.min_static_margin", self.min_static_margin)
        real("constraints.speed_fraction", self.speed_fraction, low=0.0, high=1.0,
             low_open=True, allowed="a fraction in (0, 1] of the URDF velocity limit")
        if not isinstance(self.torque_limits, bool):
            raise InvalidParameterError("constraints.torque_limits", self.torque_limits,
                                        "True or False")
        real("constraints.mu", self.mu, low=0.0, low_open=True, allowed="a friction "
             "coefficient > 0")
        real("constraints.friction_margin", self.friction_margin, low=0.0, high=1.0,
             low_open=True, allowed="a fraction in (0, 1] of the friction cone")
        real("constraints.min_foot_clearance", self.min_foot_clearance, low=0.0,
             low_open=True, allowed="a height > 0 m")
        nonnegative("constraints.min_body_clearance", self.min_body_clearance)

    def contact(self) -> ContactParams:
        """The floor: friction ``mu``, the torque limits (what a simulation walks on)."""
        return ContactParams(mu=self.mu, torque_limits=self.torque_limits)

    def planning_contact(self) -> ContactParams:
        """The force programs' settings: the cone narrowed to ``friction_margin · mu``."""
        return ContactParams(mu=self.friction_margin * self.mu, torque_limits=self.torque_limits)


@dataclass(frozen=True)
class GaitPoint:
    """One evaluated gait.

    Attributes:
        params: The gait. distance: Distance per cycle, m.
        baseline: Electrical energy per cycle without springs, J (nan: see ``error``).
        sprung: With the inner program's springs, J (= ``baseline`` when none were asked).
        springs: Those springs (empty without).
        measures: Constraint name → (value, bound, unit, "min" or "max").
        error: Why the gait has no numbers, or None.
    """

    params: GaitParams
    distance: float
    baseline: float = math.nan
    sprung: float = math.nan
    springs: SpringSet = field(default_factory=SpringSet)
    measures: dict[str, tuple[float, float, str, str]] = field(default_factory=dict)
    error: str | None = None

    @property
    def per_metre(self) -> float:
        """Electrical energy per metre without springs, J/m."""
        return self.baseline / self.distance

    @property
    def per_metre_springs(self) -> float:
        """Electrical energy per metre with the springs, J/m."""
        return self.sprung / self.distance

    def violation(self) -> float:
        """Sum of the constraints' relative violations (0 when all hold; each
        ``(bound − value)/|bound|`` for a minimum, ``(value − bound)/|bound|`` for a maximum)."""
        total = 0.0
        for value, bound, _unit, kind in self.measures.values():
            excess = bound - value if kind == "min" else value - bound
            total += max(0.0, excess) / max(abs(bound), 1e-9)
        return total

    @property
    def feasible(self) -> bool:
        """Whether the gait was made, has forces, and meets every constraint."""
        return self.error is None and self.violation() <= 1e-9


def with_values(base: GaitParams, speed: float, values: Mapping[str, float]) -> GaitParams:
    """``base`` with the co-design's parameters set and the stride ``speed · period``."""
    unknown = set(values) - set(PARAMETERS)
    if unknown:
        raise InvalidParameterError("co-design parameter", sorted(unknown),
                                    ", ".join(PARAMETERS))
    return replace(base, speed=float(speed),
                   **{k: float(v) for k, v in values.items()})  # type: ignore[arg-type]


def body_clearance(robot: Robot, motion: Motion) -> float:
    """Lowest height of the base link's geometry over the motion, m (the collision shapes;
    exact for boxes, spheres and cylinders, :func:`hexaleg.robot.geometry.lowest_points`); the
    base origin's lowest height where the base has no such shape (a mesh)."""
    model, objects = robot.model, robot.collision_model.geometryObjects
    ignore = sorted({model.frames[o.parentFrame].name for o in objects if o.parentJoint != 1})
    try:
        if all(o.parentJoint != 1 for o in objects):  # joint 1: the free flyer, the base
            return float(motion.q[:, 2].min())
        z, _ = robot.lowest_points(motion.q, "collision", ignore)
        return float(z.min())
    except HexalegError:
        return float(motion.q[:, 2].min())


def measure(robot: Robot, motion: Motion, prepared: Prepared, tau_motor: np.ndarray,
            forces: np.ndarray, constraints: Constraints, min_margin: float
            ) -> dict[str, tuple[float, float, str, str]]:
    """Every constraint of :class:`Constraints` on one analysed gait: name → (value, bound,
    unit, ``"min"``/``"max"``). Joint speeds against the URDF velocity limits, motor torques
    against the stall torques (``τ_stall``), the friction cone's usage ``|f_t| / (μ f_n)`` of
    the floor's μ against ``friction_margin`` (:func:`hexaleg.dynamics.contact.friction_usage`),
    the static margin, the swing apex and
    the body's clearance. The static margin is over the samples on three or more feet (a trot's
    two-foot samples are balanced dynamically by the body's sway) and absent when there are
    none."""
    ratio = speed_ratio(robot, motion.v)[0]
    stall = np.broadcast_to(np.asarray(prepared.motor.stall_torque, dtype=float), (robot.nj,))
    torque = float((np.abs(tau_motor).max(axis=0) / stall).max())
    usage = friction_usage(forces, prepared.motion.stance, constraints.mu)
    margins = static_margins(robot, motion.q, motion.feet, motion.stance)
    margins = margins[np.isfinite(margins)]  # −inf: under three feet, balanced by the sway
    apex = float(motion.feet[..., 2].max())
    out = {"joint_speed": (ratio, constraints.speed_fraction, "1", "max"),
           "foot_clearance": (apex, constraints.min_foot_clearance, "m", "min"),
           "body_clearance": (body_clearance(robot, motion), constraints.min_body_clearance,
                              "m", "min"),
           "friction": (float(np.max(usage)) if np.size(usage) else 0.0,
                        constraints.friction_margin + 1e-6, "1", "max")}
    if margins.size:
        out["static_margin"] = (float(margins.min()), min_margin, "m", "min")
    if constraints.torque_limits:
        out["torque"] = (torque, 1.0 + 1e-6, "1", "max")
    return out


def evaluate_gait(robot: Robot, params: GaitParams, *, groups: Groups | None,
                  family: str, constraints: Constraints, min_margin: float,
                  motor: object = None) -> GaitPoint:
    """Make, prepare and analyse one gait; with ``groups`` also its optimal springs of
    ``family`` (the inner program, electrical metric, deflection ≤ π). Never raises a hexaleg
    error: a gait that fails carries it in ``error``."""
    point = GaitPoint(params=params, distance=params.stride)
    try:
        motion = gait(robot, params)
        prepared = prepare(robot, motion, motor=motor,  # type: ignore[arg-type]
                           contact=constraints.planning_contact())
        if groups:
            best = optimal_springs(prepared, groups, family, "joule", metric=METRIC,
                                   max_deflection=math.pi)
            analysis, springs = best.analysis, best.springs
        else:
            analysis, springs = prepared.evaluate({}, "joule"), SpringSet()
        base = float(analysis.baseline["total"][METRIC])
        sprung = float(analysis.metrics["total"][METRIC])
        measures = measure(robot, motion, prepared, analysis.tau_motor, analysis.forces,
                           constraints, min_margin)
    except HexalegError as err:
        return replace(point, error=f"{type(err).__name__}: {err}")
    return replace(point, baseline=base, sprung=sprung, springs=springs, measures=measures)


def cost_of_transport(energy_per_metre: float, mass: float) -> float:
    """``E / (m g d)`` from the energy per metre ``E / d`` (J/m) and the mass (kg), 1."""
    return energy_per_metre / (mass * G)


__all__ = ["METRIC", "PARAMETERS", "UNITS", "Constraints", "GaitPoint", "body_clearance",
           "cost_of_transport", "evaluate_gait", "measure", "with_values"]
