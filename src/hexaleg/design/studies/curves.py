"""Stiffness curves: the gait's total metrics against the stiffness of one joint class's springs.

:func:`curve_springs` completes a spring set so that every joint of the class has a spring (the
paper's centred dead-zone design, θ_k/A = 0.426 and α = 1.05 of Section 4.2, eq. 14 convention,
from :mod:`hexaleg.design.rules`); :func:`stiffness_curve` then sets the same stiffness k on all
of them at each point and evaluates the gait (one :func:`hexaleg.dynamics.prepare.prepare`, many
:meth:`~hexaleg.dynamics.prepare.Prepared.evaluate`). The metrics are those of
:func:`hexaleg.dynamics.energy.metrics` (work eq. 20, the motor model of
:mod:`hexaleg.robot.motor`); k_M is the torque-optimal stiffness of eq. 19.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from hexaleg.design import rules as design
from hexaleg.design.evaluator import Evaluator
from hexaleg.dynamics import energy
from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import InfeasibleForcesError, TorqueLimitError, UnknownNameError
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet

CURVE_METRICS: tuple[str, ...] = (*(k for k in energy.ENERGY_KEYS
                                    if k not in energy.NO_SAVING_KEYS),
                                  "electrical_bus", *energy.TORQUE_KEYS)
"""Total metrics a stiffness curve can show (keys of ``metrics["total"]``)."""


@dataclass(frozen=True)
class StiffnessCurve:
    """Total metrics of the gait against the stiffness of one joint class's springs.

    Every joint of the class gets the same stiffness k; dead zones, α and convention are kept.

    Attributes:
        joints: The joints whose stiffness varies.
        stiffness: k, shape (K,), N·m/rad.
        totals: Metric → total over the cycle at each k, shape (K,), J or N·m; NaN where the
            forces were infeasible (see ``errors``).
        baseline: Metric → the same total without any springs (J or N·m).
        errors: Per point, None or the message of the infeasibility / torque-limit error.
        k_M: Per joint, the eq. 19 stiffness for that joint's spring convention, N·m/rad.
    """

    joints: tuple[str, ...]
    stiffness: np.ndarray
    totals: dict[str, np.ndarray]
    baseline: dict[str, float]
    errors: tuple[str | None, ...]
    k_M: dict[str, float]

    @property
    def feasible(self) -> np.ndarray:
        """Points whose forces were feasible, shape (K,), bool."""
        return np.array([e is None for e in self.errors])

    def savings(self, metric: str) -> np.ndarray:
        """Fraction of ``metric`` saved against the baseline at each k, shape (K,), 1
        (:func:`hexaleg.dynamics.energy.saving`; NaN where infeasible)."""
        return np.asarray(energy.saving(self.totals[metric], self.baseline[metric]), dtype=float)

    def best(self, metric: str) -> int | None:
        """Index of the feasible point with the smallest ``metric``; None if none is feasible."""
        ok = self.feasible
        if not ok.any():
            return None
        return int(np.flatnonzero(ok)[np.argmin(self.totals[metric][ok])])


def curve_springs(robot: Robot, motion: Motion, springs: SpringSet, spec: str) -> SpringSet:
    """The springs a stiffness curve varies: ``springs`` plus, on every joint of ``spec`` that has
    none, the paper's centred design (θ_k/A = 0.426, α = 1.05, eq. 14; stiffness set later)."""
    out = dict(springs)
    for j in robot.joints(spec):
        if j not in out:
            out[j] = design.centred_spring(robot, motion, j, 0.0, alpha=design.PAPER_ALPHA,
                                           convention="eq14")
    return SpringSet(out)


def stiffness_curve(prepared: Prepared, springs: SpringSet, spec: str, stiffness: np.ndarray,
                    metrics: tuple[str, ...], objective: str = "joule",
                    progress: Callable[[str], None] | None = None) -> StiffnessCurve:
    """Evaluate the gait with the springs of ``spec`` at each stiffness through the design
    layer's :class:`~hexaleg.design.evaluator.Evaluator` (one ``prepare``, one force solve a k).

    A dead-zone spring's torque is affine in its stiffness k (eq. 8: k⁺ and a k⁻ that follows
    it multiply the compression; damping and the secondary spring do not depend on k), so the
    springs' torques along the gait are ``τ(k) = τ(0) + k (τ(1) − τ(0))``, evaluated once.

    Args:
        prepared: :func:`hexaleg.dynamics.prepare.prepare` of the gait.
        springs: The springs (from :func:`curve_springs`: every joint of ``spec`` has one).
        spec: Joint class or joint whose stiffness varies.
        stiffness: k, shape (K,), N·m/rad, each ≥ 0.
        metrics: Total metrics to record (:data:`CURVE_METRICS`).
        objective: Force-distribution objective.
        progress: Called with a status line every 10 points.

    Returns:
        The curve.

    Raises:
        UnknownNameError: ``spec`` or a metric is unknown, or a joint of ``spec`` has no spring.
    """
    robot, motion = prepared.robot, prepared.motion
    joints = robot.joints(spec)
    for m in metrics:
        if m not in CURVE_METRICS:
            raise UnknownNameError("curve metric", m, CURVE_METRICS)
    ks = np.asarray(stiffness, dtype=float)
    ev = Evaluator(prepared, objective)
    zones = SpringSet(springs).dead_zones("a stiffness curve")
    tau0, tau1 = (SpringSet({**springs, **{j: zones[j].with_stiffness(k) for j in joints}})
                  .torques(robot, motion.q, motion.v) for k in (0.0, 1.0))
    totals = {m: np.empty(ks.size) for m in metrics}
    errors: list[str | None] = []
    for i, k in enumerate(ks):
        try:
            total = ev.torque_metrics(tau0 + k * (tau1 - tau0))["total"]
        except (InfeasibleForcesError, TorqueLimitError) as e:  # recorded, not hidden
            errors.append(str(e))
            for m in metrics:
                totals[m][i] = np.nan
        else:
            errors.append(None)
            for m in metrics:
                totals[m][i] = total[m]
        if progress and ((i + 1) % 10 == 0 or i + 1 == ks.size):
            progress(f"stiffness curve {i + 1}/{ks.size}")
    k_m = {j: design.k_M(robot, motion, j, alpha=zones[j].transmission) for j in joints}
    return StiffnessCurve(joints=joints, stiffness=ks, totals=totals,
                          baseline={m: ev.baseline["total"][m] for m in metrics},
                          errors=tuple(errors), k_M=k_m)
