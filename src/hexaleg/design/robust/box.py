"""The robust spring design: one set of magnitudes for a box of conditions, in one convex program.

A spring is bought once and the conditions change (:mod:`hexaleg.design.robust.conditions`). For the
nominal optimum's family and geometry — frozen, absolute angles as built — the magnitudes x
that do best over conditions c = 1…n solve one convex program: the design program
(:mod:`hexaleg.design.search.program`) of every condition stacked, x shared, each condition its own
forces at every sample, its own friction cones, normal forces and torque limits, the design
rows (``max_torque``, ``max_deflection``) at every condition's range of motion, and

* ``mode = "worst"``: minimise ``max_c E_c(x) / E_c(0)`` — maximise the worst saving;
* ``mode = "mean"``: minimise ``Σ_c E_c(x) / E_c(0) / n`` — maximise the mean saving.

``E_c`` is the condition's energy per cycle in the chosen metric, ``E_c(0)`` its baseline; the
forces minimise the Joule loss (the force objective ``"joule"``), as in every evaluation. Where
no inequality of a sample binds its forces and motor torques are affine in x
(``f = f₀ − K B x``, ``τ = τ₀ + G B x``, :class:`hexaleg.dynamics.solver.QuadraticGains`), and
both metrics are convex in τ — the Joule loss ``Σ w c τ²`` and the electrical energy
``Σ w max(0, c τ² + max(q̇τ/η, q̇τη))`` (:meth:`hexaleg.robot.motor.Motor.electrical_power`) —
hence convex in x; the max and the mean of convex functions are convex, so the optimum is global
for the geometry. Solved as :func:`~hexaleg.design.search.program.solve_design` does: every sample
starts condensed; samples whose condensed forces break an inequality get explicit forces and
their constraints, until none does (cvxpy, Clarabel). For the Joule metric that is the exact
joint program over (x, f); for the electrical one it is exact when no sample binds (then every
sample's forces are the Joule-optimal ones the evaluation uses; a sample that binds gets forces
of its own in the program — the savings reported are from the exact evaluation either way).
In mode ``"worst"`` the stacked program holds, from the bundle method's optimum, only the
conditions that can set the worst case — those with explicit samples and those near the worst —
and takes in any other its solution leaves above its worst
(:func:`~hexaleg.design.search.condensed.explicit_program`: a relaxation whose optimum meets the
left-out conditions, so the whole box's optimum): Solo-12's box of 17 conditions is solved as a
program of 8, in half the CPU time, its savings the same to 6e-8.

The nominal design is feasible for this program whenever its magnitudes meet the design rows at
every condition (always without ``max_torque`` / ``max_deflection``), so the robust design's worst
(or mean) saving over the conditions is then never below the nominal design's (tested).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from hexaleg.checks import typed
from hexaleg.design.families import family
from hexaleg.design.search.bundle import MODES, minimise
from hexaleg.design.search.condensed import TOLERANCE, Condensed, explicit_program, preferred
from hexaleg.design.search.optimal import (
    ENGAGED,
    OptimalSprings,
    frozen_problem,
    group_springs,
    motion_centres,
)
from hexaleg.dynamics.energy import saving
from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import InfeasibleForcesError, InvalidParameterError, TorqueLimitError
from hexaleg.robot.springs import SpringSet

METRICS: tuple[str, ...] = ("joule", "electrical")
"""The savings the robust program can maximise."""
__all__ = ["METRICS", "MODES", "TOLERANCE", "RobustSprings", "robust_springs"]


@dataclass(frozen=True, eq=False)
class RobustSprings:
    """The robust design of :func:`robust_springs` and how it and the nominal fare.

    Attributes:
        family: The spring family. mode: ``"worst"`` or ``"mean"``. metric: The saving
            maximised (:data:`METRICS`).
        groups: Group → joints. geometry: The nominal geometry (rad from the nominal centres).
        magnitudes: Group → magnitude name → value, SI.
        springs: The robust springs (absolute angles), for ``Prepared.evaluate`` of any
            condition.
        value: The metric per cycle of each condition with the robust springs, shape (n,), J.
        baseline: Without springs, shape (n,), J.
        saving: Robust design's saving per condition, shape (n,).
        nominal_saving: The nominal design's, shape (n,).
        nominal_feasible: Whether the nominal magnitudes meet the design rows at every
            condition (then ``worst ≥ nominal_worst`` in "worst" mode).
        solver: Rounds, explicit samples per condition, the program's value.
    """

    family: str
    mode: str
    metric: str
    groups: dict[str, tuple[str, ...]]
    geometry: dict[str, dict[str, float | str]]
    magnitudes: dict[str, dict[str, float]]
    springs: SpringSet
    value: np.ndarray
    baseline: np.ndarray
    saving: np.ndarray
    nominal_saving: np.ndarray
    nominal_feasible: bool
    solver: dict[str, Any] = field(default_factory=dict)

    @property
    def worst(self) -> float:
        """The robust design's worst saving over the conditions."""
        return float(np.min(self.saving))

    @property
    def nominal_worst(self) -> float:
        """The nominal design's worst saving over the same conditions."""
        return float(np.min(self.nominal_saving))


@typed
def robust_springs(optimum: OptimalSprings, nominal: Prepared, conditions: Sequence[Prepared],
                   mode: str = "worst", metric: str = "joule", *,
                   max_torque: float | None = None, max_deflection: float | None = None,
                   prefer: int | None = None) -> RobustSprings:
    """The magnitudes that maximise the worst (or mean) saving over ``conditions``.

    Args:
        optimum: The nominal optimum (objective ``"joule"``): family, groups, geometry.
        nominal: The prepared gait it was designed on (its centres of motion freeze the angles).
        conditions: Each condition's prepared gait (:func:`hexaleg.design.robust.conditions.
            condition_prepared`); include the nominal one to keep it in the box.
        mode: One of :data:`MODES`.
        metric: One of :data:`METRICS`: the saving maximised (forces minimise the Joule loss
            either way).
        max_torque: Largest spring torque at every condition, N·m, or None.
        max_deflection: Largest deflection from the free position at every condition, rad, or
            None.
        prefer: In mode ``"worst"``: the condition (index into ``conditions``, the nominal
            gait's) whose saving decides between magnitudes of equal worst — the worst case's
            minimiser is not unique where conditions that do not set it leave directions free
            (:func:`hexaleg.design.search.condensed.preferred`); None: wherever the bundle method
            stops in that set.

    Returns:
        The robust design and both designs' savings per condition.

    Raises:
        InvalidParameterError: an unknown mode or metric, no conditions, an objective other
            than joule.
        InfeasibleForcesError: the stacked program has no solution (a condition without
            admissible forces, or design rows no magnitudes meet).
    """
    if mode not in MODES:
        raise InvalidParameterError("mode", mode, " or ".join(MODES))
    if metric not in METRICS:
        raise InvalidParameterError("metric", metric, " or ".join(METRICS))
    if not conditions:
        raise InvalidParameterError("conditions", [], "at least one prepared condition")
    if optimum.objective != "joule":
        raise InvalidParameterError("optimum.objective", optimum.objective,
                                    "joule (the robust program is in Joule energy)")
    centres = motion_centres(nominal, [j for js in optimum.groups.values() for j in js])
    data = [Condensed(frozen_problem(p, optimum, centres, max_torque=max_torque,
                                      max_deflection=max_deflection), metric)
            for p in conditions]
    fam = family(optimum.family)
    nx = data[0].problem.nx
    x0 = np.concatenate([[optimum.magnitudes[g][m] for m in fam.magnitudes]
                         for g in optimum.groups])
    engaged = np.zeros(nx, dtype=bool)
    for d in data:
        engaged |= np.any(np.abs(d.problem.B) > ENGAGED, axis=(0, 1))
    G = np.vstack([d.problem.G for d in data if d.problem.G.size] or [np.zeros((0, nx))])
    h = np.concatenate([d.problem.h for d in data if d.problem.G.size] or [np.zeros(0)])
    nonneg = data[0].problem.nonnegative
    result = minimise([d.oracle for d in data], x0, mode, G=G, h=h, nonneg=nonneg,
                      fixed=~engaged)
    xv = np.where(nonneg, np.maximum(result.x, 0.0), result.x)
    solver: dict[str, Any] = {"path": "proximal bundle, every sample condensed",
                              "iterations": result.iterations,
                              "serious_steps": result.serious_steps, "gap": result.gap,
                              "stopped": result.stopped,
                              "program_value": float(result.values.max() if mode == "worst"
                                                     else result.values.mean())}
    if mode == "worst" and prefer is not None and len(data) > 1:
        xv, solver["preferred"] = preferred(data, prefer, xv, G, h, nonneg, ~engaged)
    if any([d.update(xv) for d in data]):  # some sample binds: explicit forces there
        xv, explicit = explicit_program(data, mode, nonneg, engaged, G, h, start=xv)
        for stale in ("gap", "stopped"):  # the bundle's, not the explicit program's
            solver.pop(stale)
        solver.update(explicit)
    solver["explicit_samples"] = [int((~d.condensed).sum()) for d in data]
    return _result(optimum, mode, metric, data, xv, x0, centres, solver)


def _result(optimum: OptimalSprings, mode: str, metric: str, data: list[Condensed],
            x: np.ndarray,
            x0: np.ndarray, centres: dict[str, float], solver: dict[str, Any]
            ) -> RobustSprings:
    magnitudes, springs = group_springs(family(optimum.family), optimum.groups,
                                        optimum.geometry, centres, x, optimum.mirrored)
    robust = SpringSet(springs)
    value, base, nominal_saving = [], [], []
    feasible = True
    for d in data:
        p = d.problem.prepared
        b = float(p.baseline("joule")["total"][metric])
        value.append(float(p.evaluate(robust, "joule").metrics["total"][metric]))
        base.append(b)
        try:
            nominal_value = float(p.evaluate(optimum.springs, "joule").metrics["total"][metric])
        except (InfeasibleForcesError, TorqueLimitError):  # no forces: the worst there is
            nominal_value = np.inf
        nominal_saving.append(saving(nominal_value, b))
        if d.problem.G.size and np.any(d.problem.G @ x0 > d.problem.h + 1e-9):
            feasible = False
    v, bs = np.array(value), np.array(base)
    return RobustSprings(family=optimum.family, mode=mode, metric=metric,
                         groups=dict(optimum.groups),
                         geometry=optimum.geometry, magnitudes=magnitudes, springs=robust,
                         value=v, baseline=bs, saving=saving(v, bs),
                         nominal_saving=np.array(nominal_saving), nominal_feasible=feasible,
                         solver=solver)
