"""Metrics of spring designs on one gait: ``prepare`` once, one force solve per design.

The paper chooses one stiffness for one joint (k_M by eq. 19, k_E by minimising the energy of
eq. 21) and leaves "the appropriate elastic joint assembly position and the optimal stiffness" as
future work. The design layer answers that for a gait and a motor: which joints should carry a
dead-zone spring (eq. 8, :class:`hexaleg.robot.springs.DeadZoneSpring`), with which contact angles
and which stiffness. This module evaluates one design; :mod:`hexaleg.design.studies.optimise`,
:mod:`hexaleg.design.studies.placement` and :mod:`hexaleg.design.robust.conditions` search and study
designs,
:mod:`hexaleg.sweep` runs grids of them.

Groups and designs
------------------
A *group* is a joint class (``"femur"``: the same design on all six femurs — left/right
symmetric), one joint, or any list of joints. A design gives, in SI (see
:data:`SPRING_PARAMETERS`):

* ``k`` (N·m/rad) and optionally ``k_minus`` (k⁻, default k);
* the dead zone: ``theta_k`` (±θ_k, rad, > 0), or ``dead_zone`` (θ_k as a fraction of each
  joint's half range of motion in the gait, in (0, 1)), or ``theta_minus`` < ``theta_plus`` (rad);
* ``offset`` (rad): the spring's neutral relative to the *centre of each joint's range of motion
  in the gait* (default 0: a "centred" design, the symmetric dead zone about the motion that the
  paper assumes, eq. 8 and eq. 25).

Evaluation
----------
Designs on one gait share one :func:`hexaleg.dynamics.prepare.prepare`. Workers never receive
Pinocchio objects: a task carries the run, a picklable :class:`~hexaleg.scenario.scenario.
Scenario` (robot name, actuator, force objective, contact settings, gait), and each process
loads the robot once and keeps an :class:`Evaluator` per run in a small cache
(:func:`evaluator`). A design then costs one force
solve (:meth:`hexaleg.dynamics.prepare.Prepared.solve`) and the energy metrics; the spring torques
come from the spring's torque basis (linear in k⁺ and k⁻), cached per dead-zone geometry.

Metric and objective
--------------------
Forces are distributed by the core's default objective ``"joule"`` (the convex quadratic program
with the fast exact path). Designs are ranked by :data:`DEFAULT_METRIC` = ``"electrical"``, the
energy the servos draw over a cycle (Joule loss plus mechanical work through the gearbox, no
regeneration unless the motor model allows it) — what the battery pays, i.e. the paper's energy
criterion (eq. 20–24) with a motor model. Any key of ``Analysis.metrics["total"]``
(:data:`METRICS`) may be chosen instead.
"""

from __future__ import annotations

import math
from collections import OrderedDict
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from hexaleg.checks import typed
from hexaleg.dynamics.contact import check_objective
from hexaleg.dynamics.energy import ENERGY_KEYS, NO_SAVING_KEYS, TORQUE_KEYS, savings
from hexaleg.dynamics.inertia import joint_range
from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import (
    InfeasibleForcesError,
    InvalidParameterError,
    TorqueLimitError,
)
from hexaleg.motion.params import GaitParams
from hexaleg.robot.springs import DeadZoneSpring, SpringSet
from hexaleg.scenario.scenario import Scenario, clear_robots

METRICS: tuple[str, ...] = (*ENERGY_KEYS, "electrical_bus", *TORQUE_KEYS)
"""Keys of ``Analysis.metrics["total"]`` a design study records and may optimise (J or N·m)."""
SAVING_METRICS: tuple[str, ...] = tuple(m for m in METRICS if m not in NO_SAVING_KEYS)
"""Metrics with a saving column (``saving.<key>``; the signed net work has none)."""
DEFAULT_METRIC = "electrical"
"""Metric ranked and optimised by default (energy drawn by the servos per cycle, J)."""

SPRING_PARAMETERS: tuple[str, ...] = ("k", "k_minus", "theta_k", "dead_zone", "theta_minus",
                                      "theta_plus", "offset")
"""Design parameters of a spring group, SI: N·m/rad, N·m/rad, rad, 1, rad, rad, rad."""
CACHE_SIZE = 4
"""Gaits whose :class:`Evaluator` a process keeps."""

Design = Mapping[str, Mapping[str, float]]
"""Spring design: group name → parameter → value (SI, :data:`SPRING_PARAMETERS`)."""


# --------------------------------------------------------------------------- per-process cache


_EVALUATORS: OrderedDict[tuple, Evaluator] = OrderedDict()


def clear_cache() -> None:
    """Forget the robots and evaluators this process has built (e.g. after editing a URDF, or
    to time a sweep from a cold start)."""
    clear_robots()
    _EVALUATORS.clear()


@typed
def evaluator(run: Scenario) -> Evaluator:
    """The :class:`Evaluator` of a run, built once per process and kept in a small cache (keyed
    by :meth:`Scenario.key <hexaleg.scenario.scenario.Scenario.key>`).

    Args:
        run: The run: robot, actuator, objective, contact and gait (or a log's cycle).
    """
    key = run.key()
    if key in _EVALUATORS:
        _EVALUATORS.move_to_end(key)
        return _EVALUATORS[key]
    ev = Evaluator.for_scenario(run)
    _EVALUATORS[key] = ev
    while len(_EVALUATORS) > CACHE_SIZE:
        _EVALUATORS.popitem(last=False)
    return ev


# --------------------------------------------------------------------------- the evaluator


class Evaluator:
    """Metrics of spring designs on one prepared motion: one force solve per design.

    Everything that does not depend on the springs is in ``prepared`` (computed once); a design
    costs its spring torques (from a cached torque basis, linear in the magnitudes) and one
    :meth:`~hexaleg.dynamics.prepare.Prepared.solve`. Sweeps, the optimiser, placement,
    robustness and the report's stiffness curve all evaluate through it.

    Args:
        prepared: The motion, prepared (:func:`hexaleg.dynamics.prepare.prepare`).
        objective: Force-distribution objective (:data:`hexaleg.dynamics.contact.OBJECTIVES`).
        gait: The gait parameters the motion was made from, if it is a gait (recorded by sweeps).

    Attributes:
        robot: The robot. motion: The motion. prepared: Its
            :class:`~hexaleg.dynamics.prepare.Prepared`. baseline: Metrics without springs.
        centre: Joint → centre of its range of motion in the gait, rad.
        half_range: Joint → half its range of motion in the gait, rad.
        evaluations: Designs evaluated so far (for tests and benchmarks).
    """

    def __init__(self, prepared: Prepared, objective: str = "joule",
                 gait: GaitParams | None = None) -> None:
        self.objective = check_objective(objective)
        self.gait = gait
        self.prepared = prepared
        self.robot, self.motion = prepared.robot, prepared.motion
        self.baseline = self.prepared.baseline(objective)
        ranges = {j: joint_range(self.robot, self.motion, j) for j in self.robot.joint_names}
        self.centre = {j: (lo + hi) / 2 for j, (lo, hi) in ranges.items()}
        self.half_range = {j: (hi - lo) / 2 for j, (lo, hi) in ranges.items()}
        self.evaluations = 0
        self._basis: OrderedDict[tuple, tuple[np.ndarray, np.ndarray]] = OrderedDict()

    @classmethod
    def for_scenario(cls, run: Scenario) -> Evaluator:
        """The evaluator of a run (its motion prepared once, :meth:`Scenario.prepare
        <hexaleg.scenario.scenario.Scenario.prepare>`)."""
        return cls(run.prepare(), run.objective, run.gait if run.recorded is None else None)

    def spring(self, joint: str, params: Mapping[str, float]) -> DeadZoneSpring:
        """The spring of design ``params`` on ``joint``, with its absolute neutral angle (SI).

        Raises:
            InvalidParameterError: an out-of-range parameter (from
                :class:`~hexaleg.robot.springs.DeadZoneSpring`).
        """
        theta_k = params.get("theta_k")
        if "dead_zone" in params:
            if not self.half_range[joint] > 0:
                raise InvalidParameterError(
                    f"dead_zone of the spring on {joint}", params["dead_zone"],
                    "a joint that moves in the gait: this one does not, so a dead zone that is a "
                    "fraction of its motion has no width; give theta_k in rad or spring "
                    "another joint")
            theta_k = params["dead_zone"] * self.half_range[joint]
        return DeadZoneSpring(stiffness=params["k"], theta_k=theta_k,
                              theta_minus=params.get("theta_minus"),
                              theta_plus=params.get("theta_plus"),
                              stiffness_minus=params.get("k_minus"),
                              neutral=self.centre[joint] + params.get("offset", 0.0))

    def springs(self, groups: Mapping[str, Sequence[str]], design: Design) -> SpringSet:
        """The springs of ``design`` on every joint of its groups (absolute neutrals, SI)."""
        return SpringSet({j: self.spring(j, params) for g, params in design.items()
                          for j in groups[g]})

    def _unit_torques(self, joints: Sequence[str], params: Mapping[str, float]
                      ) -> tuple[np.ndarray, np.ndarray]:
        """Torques (T, nj) per unit k⁺ and per unit k⁻ of a group's dead-zone geometry."""
        geometry = tuple(sorted((k, v) for k, v in params.items() if k not in ("k", "k_minus")))
        key = (tuple(joints), geometry)
        if key not in self._basis:
            geo = dict(geometry)
            q, v = self.motion.q, self.motion.v
            plus = SpringSet({j: self.spring(j, {**geo, "k": 1.0, "k_minus": 0.0})
                              for j in joints}).torques(self.robot, q, v)
            minus = SpringSet({j: self.spring(j, {**geo, "k": 0.0, "k_minus": 1.0})
                               for j in joints}).torques(self.robot, q, v)
            self._basis[key] = (plus, minus)
            while len(self._basis) > 64:
                self._basis.popitem(last=False)
        self._basis.move_to_end(key)
        return self._basis[key]

    def spring_torques(self, groups: Mapping[str, Sequence[str]], design: Design) -> np.ndarray:
        """Spring torques of ``design`` along the gait, shape (T, nj), N·m.

        Equal to ``self.springs(groups, design).torques(robot, q, v)``, through the spring's
        torque basis (linear in k⁺ and k⁻ for a fixed dead zone), cached per dead zone.
        """
        tau = np.zeros_like(self.prepared.q)
        for g, params in design.items():
            self.springs({g: groups[g]}, {g: params})  # validates the design
            plus, minus = self._unit_torques(groups[g], params)
            k = params["k"]
            k_minus = params.get("k_minus", k)
            tau += k * plus + k_minus * minus
        return tau

    def metrics(self, groups: Mapping[str, Sequence[str]], design: Design) -> dict[str, Any]:
        """Energy metrics of the gait with ``design``, as :func:`hexaleg.dynamics.energy.metrics`.

        Raises:
            InfeasibleForcesError, TorqueLimitError: no admissible forces or torques.
        """
        return self.torque_metrics(self.spring_torques(groups, design))

    def torque_metrics(self, tau_spring: np.ndarray) -> dict[str, Any]:
        """Energy metrics of the motion with spring torques ``tau_spring`` (T, nj), N·m.

        Raises:
            InfeasibleForcesError, TorqueLimitError: no admissible forces or torques.
        """
        self.evaluations += 1
        _, tau_m, _ = self.prepared.solve(tau_spring, self.objective)
        return self.prepared.metrics(tau_m)

    def value(self, groups: Mapping[str, Sequence[str]], design: Design,
              metric: str = DEFAULT_METRIC) -> float:
        """One metric total of ``design`` (J or N·m); +inf when no forces or torques exist."""
        try:
            return float(self.metrics(groups, design)["total"][metric])
        except (InfeasibleForcesError, TorqueLimitError):
            return math.inf

    def row(self, groups: Mapping[str, Sequence[str]], design: Design) -> dict[str, Any]:
        """Every metric total, its baseline and its saving for ``design``, plus a status
        (:func:`metric_row`; a design with no admissible forces or torques has the error)."""
        try:
            return metric_row(self.metrics(groups, design), self.baseline)
        except (InfeasibleForcesError, TorqueLimitError) as e:
            return metric_row(None, self.baseline, e)


def metric_row(metrics: Mapping[str, Any] | None, baseline: Mapping[str, Any],
               error: Exception | None = None) -> dict[str, Any]:
    """A table row of the metric totals with springs, their baselines and savings.

    Args:
        metrics: :func:`hexaleg.dynamics.energy.metrics` with the springs; None with ``error``.
        baseline: The same without springs.
        error: Why there are no metrics (no admissible forces or torques).

    Returns:
        ``{<metric>: …, "baseline.<metric>": …, "saving.<metric>": …, "status": "ok"}`` for
        :data:`METRICS`; with ``error``, NaN metrics and savings (the baselines stay) and the
        error's type and message as the status.
    """
    m: Mapping[str, Any]
    s: Mapping[str, Any]
    if metrics is None:
        m = {"total": dict.fromkeys(METRICS, math.nan)}
        s = {"total": dict.fromkeys(SAVING_METRICS, math.nan)}
        status = f"{type(error).__name__}: {error}"
    else:
        m, s, status = metrics, savings(metrics, baseline), "ok"
    out: dict[str, Any] = {key: m["total"][key] for key in METRICS}
    out.update({f"baseline.{key}": baseline["total"][key] for key in METRICS})
    out.update({f"saving.{key}": s["total"][key] for key in SAVING_METRICS})
    out["status"] = status
    return out
