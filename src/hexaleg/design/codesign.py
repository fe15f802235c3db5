"""Springs as decision variables: the globally optimal magnitudes in one convex program.

:func:`optimal_springs` designs one spring per group of joints (a joint class, a mirrored pair,
one joint) for a prepared gait. For a fixed geometry (:mod:`hexaleg.design.families`) the
magnitudes come from one convex program over the whole cycle (:mod:`hexaleg.design.program`):
the global optimum for that geometry. The geometry — a few angles per group — is given, or
searched: a grid per group (rounds over the groups), then bounded Nelder–Mead over all angles
(:func:`scipy.optimize.minimize`), each step one convex solve. The linear family has no geometry,
so its answer is global outright.

Every design constraint is linear in the magnitudes: magnitudes ≥ 0 where the family needs it;
``max_torque`` (|τ_s| ≤ τ_max over the gait; the laws are non-increasing in q, so the extremes of
each joint's motion are the binding samples); ``max_deflection`` (each spring element's
deflection from its free position ≤ Δ_max: a linear spring's |τ₀ − k (q − q_r)| ≤ k Δ_max, a
spring engaged past a contact angle ``k·compression + preload ≤ k Δ_max``, Shigley's torsion
spring: deflection = moment / rate); one design shared by a group's joints.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, cast

import numpy as np

from hexaleg.checks import real
from hexaleg.design import families
from hexaleg.design.families import FAMILIES, Family, Geometry
from hexaleg.design.program import DesignProblem, DesignSolution, solve_design
from hexaleg.design.search import search_geometry
from hexaleg.design.spring_table import magnitudes_table
from hexaleg.dynamics.contact import QUADRATIC_OBJECTIVES, check_objective
from hexaleg.dynamics.energy import saving
from hexaleg.dynamics.prepare import Analysis, Prepared
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.robot.springs import Spring, SpringSet, Term, basis

OBJECTIVE_METRIC = {"joule": "joule", "torque_squared": "rms_torque", "electrical": "electrical",
                    "positive_work": "positive_work"}
"""The metric of ``Analysis.metrics["total"]`` each objective is judged by."""
GRID = 7
"""Grid points per angle of the geometry search's start."""
ZERO_STIFFNESS = 1e-9
"""k below this (N·m/rad) with a nonzero constant torque reads as a constant-torque spring."""

ENGAGED = 1e-9
"""A term acts over the gait where its basis exceeds this somewhere (rad of compression, or the
unit step); below it the term is fixed at 0 instead of left to round-off."""

Groups = Mapping[str, Sequence[str] | str] | Sequence[str]


@dataclass(frozen=True)
class OptimalSprings:
    """The optimal springs of :func:`optimal_springs`.

    Attributes:
        family: The spring family. objective: The force program's objective.
        groups: Group name → its joints (one shared design each).
        geometry: Group → its geometry (rad from each joint's centre of motion; ``side``).
        magnitudes: Group → magnitude name → value, SI (N·m/rad, N·m).
        springs: Every sprung joint's spring (accepted by ``Prepared.evaluate``).
        analysis: ``prepared.evaluate(springs, objective)``.
        metric: The metric of the objective (:data:`OBJECTIVE_METRIC`). value: Its value with the
            springs. baseline: Without. saving: ``(baseline − value) / |baseline|``.
        notes: What the user should know (a constant-torque spring, a spring that never engages).
        solver: How it was solved (path, Clarabel solves, explicit samples, geometry evaluations).
    """

    family: str
    objective: str
    groups: dict[str, tuple[str, ...]]
    geometry: dict[str, dict[str, float | str]]
    magnitudes: dict[str, dict[str, float]]
    springs: SpringSet
    analysis: Analysis
    metric: str
    value: float
    baseline: float
    saving: float
    notes: tuple[str, ...] = ()
    solver: dict[str, Any] = field(default_factory=dict)

    def table(self) -> dict[str, dict[str, Any]]:
        """Per group: geometry and magnitudes as ``{value, unit}``, in SI and the paper's units
        (N·mm/deg, N·mm, deg)."""
        return {g: magnitudes_table(self.geometry[g], self.magnitudes[g]) for g in self.groups}


def resolve_groups(prepared: Prepared, groups: Groups) -> dict[str, tuple[str, ...]]:
    """Group name → joints, from ``{name: [joints] or a joint spec}`` or a list of joint specs.

    Raises:
        InvalidParameterError: no group, an empty group, a joint in two groups.
        UnknownNameError: an unknown joint or class (lists them).
    """
    robot = prepared.robot
    if isinstance(groups, str) or not isinstance(groups, (Mapping, Sequence)):
        raise InvalidParameterError("groups", groups, "{name: [joints]} or a list of joint "
                                    "classes/joints")
    items = groups.items() if isinstance(groups, Mapping) else ((g, g) for g in groups)
    out: dict[str, tuple[str, ...]] = {}
    owner: dict[str, str] = {}
    for name, spec in items:
        joints = tuple(robot.joints(spec)) if isinstance(spec, str) else tuple(spec)
        if not joints:
            raise InvalidParameterError(f"group {name}", list(joints), "at least one joint")
        for j in joints:
            robot.column(j)  # UnknownNameError listing the joints
            if j in owner:
                raise InvalidParameterError(f"joint {j}", f"in groups {owner[j]} and {name}",
                                            "each joint in one group")
            owner[j] = name
        out[str(name)] = joints
    if not out:
        raise InvalidParameterError("groups", groups, "at least one group")
    return out


@dataclass(frozen=True, eq=False)
class _Setup:
    """What does not change while the geometry is searched."""

    prepared: Prepared
    objective: str
    fam: Family
    groups: dict[str, tuple[str, ...]]
    centre: dict[str, float]
    q_min: dict[str, float]
    q_max: dict[str, float]
    max_torque: float | None
    max_deflection: float | None

    def check_geometry(self, geometry: Mapping[str, Geometry]
                       ) -> dict[str, dict[str, float | str]]:
        """Every group's geometry checked by its family; no geometry for an unknown group.

        Raises:
            UnknownNameError: a group that does not exist (lists the groups), or a geometry
                parameter the family does not have.
            InvalidParameterError: a group without its angles, angles out of order.
        """
        unknown = [g for g in geometry if g not in self.groups]
        if unknown:
            raise UnknownNameError("geometry group", unknown[0], tuple(self.groups))
        missing = [g for g in self.groups if g not in geometry and self.fam.angles]
        if missing:
            raise InvalidParameterError(f"geometry of group {missing[0]}", None,
                                        f"the angles {', '.join(self.fam.angles)} (rad)")
        return {g: self.fam.check(geometry.get(g, {}), f"geometry[{g}]") for g in self.groups}

    def half_range(self, group: str) -> float:
        return max((self.q_max[j] - self.q_min[j]) / 2 for j in self.groups[group])

    def problem(self, geometry: Mapping[str, Geometry]) -> DesignProblem:
        """The design program of ``geometry`` (group → geometry)."""
        p, fam = self.prepared, self.fam
        nm = len(fam.magnitudes)
        joints = [j for js in self.groups.values() for j in js]
        cols = np.array([p.robot.column(j) for j in joints])
        B = np.zeros((p.motion.n_samples, len(joints), nm * len(self.groups)))
        rows: list[np.ndarray] = []
        h: list[float] = []
        labels: list[str] = []
        i = 0
        for g_index, (g, js) in enumerate(self.groups.items()):
            sl = slice(g_index * nm, (g_index + 1) * nm)
            engaged = np.zeros(nm, dtype=bool)
            for j in js:
                terms = fam.terms(geometry[g], self.centre[j])
                B[:, i, sl] = basis(terms, p.q[:, p.robot.column(j)])
                engaged |= np.any(np.abs(B[:, i, sl]) > ENGAGED, axis=0)
                for row, rhs, label in self._rows(terms, j):
                    full = np.zeros(B.shape[2])
                    full[sl] = row
                    rows.append(full)
                    h.append(rhs)
                    labels.append(label)
                i += 1
            for m in np.flatnonzero(~engaged):  # a term that never acts over the gait: x = 0
                full = np.zeros(B.shape[2])
                full[g_index * nm + m] = 1.0
                rows.append(full)
                h.append(0.0)
                labels.append("never engaged")
        G = np.array(rows) if rows else np.zeros((0, B.shape[2]))
        return DesignProblem(p, self.objective, cols, B, np.tile(fam.nonnegative(), len(
            self.groups)), G, np.array(h), tuple(labels))

    def _rows(self, terms: tuple[Term, ...], joint: str) -> list[tuple[np.ndarray, float, str]]:
        """Design rows ``row · x_group ≤ rhs`` on one joint (module docstring)."""
        out = []
        lo, hi = self.q_min[joint], self.q_max[joint]
        if self.max_torque is not None:
            out.append((basis(terms, lo), self.max_torque, "max_torque"))
            out.append((-basis(terms, hi), self.max_torque, "max_torque"))
        if self.max_deflection is not None:
            d = self.max_deflection
            for e in self.fam.elements:
                if e.linear:  # |τ₀ − k (q − q_r)| ≤ k Δ at both ends of the motion
                    for q in (lo, hi):
                        r = terms[e.stiffness].angle
                        for s in (1.0, -1.0):
                            row = np.zeros(len(terms))
                            row[e.stiffness] = -s * (q - r) - d
                            row[cast(int, e.preload)] = s  # the linear law's constant
                            out.append((row, 0.0, "max_deflection"))
                    continue
                term = terms[e.stiffness]
                q = hi if term.kind == "above" else lo
                row = np.zeros(len(terms))
                row[e.stiffness] = abs(float(term.torque(np.array(q)))) - d
                if e.preload is not None:
                    row[e.preload] = abs(float(terms[e.preload].torque(np.array(q))))
                out.append((row, 0.0, "max_deflection"))
        return out

    def solve(self, geometry: Mapping[str, Geometry]) -> DesignSolution:
        problem = self.problem(geometry)
        if self.objective in QUADRATIC_OBJECTIVES:
            return solve_design(problem)
        from hexaleg.design.program_reference import solve_design_reference

        return solve_design_reference(problem)


def optimal_springs(prepared: Prepared, groups: Groups, family: str = "linear",
                    objective: str = "joule", *, max_torque: float | None = None,
                    max_deflection: float | None = None,
                    geometry: Mapping[str, Geometry] | None = None,
                    start: Mapping[str, Geometry] | Sequence[Mapping[str, Geometry]] | None = None
                    ) -> OptimalSprings:
    """The optimal springs of one family on the groups' joints for a prepared gait.

    Args:
        prepared: :func:`hexaleg.prepare` of the robot's gait (motor, contact settings).
        groups: ``{name: [joints] or a joint class}`` (one shared design per group: a class, a
            mirrored pair, one joint), or a list of joint classes / joints.
        family: One of :data:`hexaleg.design.families.FAMILIES`.
        objective: The force program's objective (:data:`hexaleg.dynamics.contact.OBJECTIVES`),
            summed over the cycle; judged by :data:`OBJECTIVE_METRIC`.
        max_torque: Largest spring torque over the gait, N·m, > 0; None for no bound.
        max_deflection: Largest deflection of each spring from its free position, rad, > 0;
            None for no bound (then a linear spring may come out as a constant-torque spring).
        geometry: Group → geometry (rad from each joint's centre of motion; see
            :mod:`hexaleg.design.families`); None searches it (the linear family has none).
        start: Group → geometry to start the search from (every group; e.g. each group's
            optimum alone), or a list of such: the result is never worse than any of them. Not
            with ``geometry``.

    Returns:
        The optimal springs, their analysis and saving; the magnitudes are the global optimum
        for the returned geometry.

    Raises:
        InvalidParameterError: an empty group, a joint in two groups, Δ_max or τ_max not > 0, a
            geometry for a group that does not exist or out of order.
        UnknownNameError: an unknown family, objective, joint or geometry parameter.
        InfeasibleForcesError, TorqueLimitError: the gait has no admissible forces even without
            springs (the baseline), or the program has no solution.
    """
    setup = _setup(prepared, groups, family, objective, max_torque, max_deflection)
    baseline = float(prepared.baseline(objective)["total"][OBJECTIVE_METRIC[objective]])
    if geometry is not None:
        if start is not None:
            raise InvalidParameterError("start", start, "None when the geometry is given")
        chosen = setup.check_geometry(geometry)
        solution, evaluations = setup.solve(chosen), 1
    else:
        starts = [] if start is None or not setup.fam.angles else (
            [start] if isinstance(start, Mapping) else list(start))
        chosen, solution, evaluations = search_geometry(
            setup, [setup.check_geometry(s) for s in starts])
    return _result(setup, chosen, solution, evaluations, baseline)


def _setup(prepared: Prepared, groups: Groups, family: str, objective: str,
           max_torque: float | None, max_deflection: float | None) -> _Setup:
    """The checked inputs of :func:`optimal_springs` and each joint's range of motion."""
    fam = families.family(family)
    check_objective(objective)
    if max_torque is not None:
        max_torque = real("max_torque", max_torque, low=0.0, low_open=True,
                          allowed="a finite torque > 0 (N·m), or None")
    if max_deflection is not None:
        max_deflection = real("max_deflection", max_deflection, low=0.0, low_open=True,
                              allowed="a finite angle > 0 (rad), or None")
    resolved = resolve_groups(prepared, groups)
    joints = [j for js in resolved.values() for j in js]
    qs = {j: prepared.q[:, prepared.robot.column(j)] for j in joints}
    return _Setup(prepared, objective, fam, resolved, centre=motion_centres(prepared, joints),
                  q_min={j: float(q.min()) for j, q in qs.items()},
                  q_max={j: float(q.max()) for j, q in qs.items()},
                  max_torque=max_torque, max_deflection=max_deflection)


def design_problem(prepared: Prepared, groups: Groups, family: str,
                   geometry: Mapping[str, Geometry], objective: str = "joule", *,
                   max_torque: float | None = None, max_deflection: float | None = None
                   ) -> DesignProblem:
    """The design program :func:`optimal_springs` solves for a given geometry (arguments as
    there), for benchmarks and comparisons of the solvers
    (:func:`hexaleg.design.program.solve_design`,
    :func:`hexaleg.design.program_reference.solve_design_reference`)."""
    setup = _setup(prepared, groups, family, objective, max_torque, max_deflection)
    return setup.problem(setup.check_geometry(geometry))


def motion_centres(prepared: Prepared, joints: Sequence[str]) -> dict[str, float]:
    """Joint → the centre of its range of motion in the gait, rad (the origin of a design's
    angles)."""
    q = {j: prepared.q[:, prepared.robot.column(j)] for j in joints}
    return {j: float(v.min() + v.max()) / 2 for j, v in q.items()}


def frozen_problem(prepared: Prepared, optimum: OptimalSprings, centres: Mapping[str, float], *,
                   max_torque: float | None = None, max_deflection: float | None = None
                   ) -> DesignProblem:
    """The design program of ``optimum``'s family and geometry on another gait (a changed
    condition), its angles frozen at the nominal ``centres`` (absolute, as built), the
    magnitudes free; the design rows at this gait's ranges of motion. A term that never acts in
    this gait is left free here (its "never engaged" row dropped): another condition may need
    it.

    Args:
        prepared: The condition's prepared gait.
        optimum: The nominal optimum (family, groups, geometry, objective).
        centres: Joint → nominal centre of motion, rad (:func:`motion_centres`).
        max_torque: As :func:`optimal_springs`, at this gait.
        max_deflection: As :func:`optimal_springs`, at this gait.
    """
    setup = _setup(prepared, optimum.groups, optimum.family, optimum.objective, max_torque,
                   max_deflection)
    setup = dataclasses.replace(setup, centre={j: float(centres[j]) for j in setup.centre})
    p = setup.problem(setup.check_geometry(optimum.geometry))
    keep = np.array([label != "never engaged" for label in p.labels], dtype=bool)
    return dataclasses.replace(p, G=p.G[keep] if p.G.size else p.G, h=p.h[keep],
                               labels=tuple(lb for lb, k in zip(p.labels, keep, strict=True)
                                            if k))


def group_springs(fam: Family, groups: Mapping[str, Sequence[str]],
                  geometry: Mapping[str, Geometry], centres: Mapping[str, float], x: np.ndarray
                  ) -> tuple[dict[str, dict[str, float]], dict[str, Spring]]:
    """Group → magnitude name → value, and joint → spring law, of the stacked magnitudes ``x``
    (groups in order, each :attr:`Family.magnitudes`; angles from ``centres``, rad)."""
    nm = len(fam.magnitudes)
    magnitudes, springs = {}, {}
    for i, (g, js) in enumerate(groups.items()):
        xg = x[i * nm:(i + 1) * nm]
        magnitudes[g] = dict(zip(fam.magnitudes, (float(v) for v in xg), strict=True))
        for j in js:
            springs[j] = fam.spring(geometry[g], centres[j], xg)
    return magnitudes, springs


def _result(setup: _Setup, geometry: dict[str, dict[str, float | str]],
            solution: DesignSolution, evaluations: int, baseline: float) -> OptimalSprings:
    fam, prepared = setup.fam, setup.prepared
    nonneg = np.tile(fam.nonnegative(), len(setup.groups))
    x = np.where(nonneg, np.maximum(solution.x, 0.0), solution.x)
    magnitudes, springs = group_springs(fam, setup.groups, geometry, setup.centre, x)
    notes = []
    for g, m in magnitudes.items():
        if fam.name == "linear" and m["k"] < ZERO_STIFFNESS and abs(m["torque_at_reference"]) > 0:
            notes.append(f"group {g}: k = 0 with a constant torque of "
                         f"{m['torque_at_reference']:+.4g} N·m — a constant-torque spring; give "
                         "max_deflection to bound how far a real spring may wind")
    analysis = prepared.evaluate(springs, setup.objective)
    metric = OBJECTIVE_METRIC[setup.objective]
    value = float(analysis.metrics["total"][metric])
    return OptimalSprings(
        family=fam.name, objective=setup.objective, groups=dict(setup.groups),
        geometry=geometry, magnitudes=magnitudes, springs=SpringSet(springs), analysis=analysis,
        metric=metric, value=value, baseline=baseline, saving=saving(value, baseline),
        notes=tuple(notes),
        solver={"path": ("active set" if setup.objective in QUADRATIC_OBJECTIVES
                         else "cvxpy stacked program"),
                "program_value": solution.value, "clarabel_solves": solution.rounds,
                "explicit_samples": int(solution.explicit.size),
                "geometry_evaluations": evaluations})


__all__ = ["FAMILIES", "OBJECTIVE_METRIC", "OptimalSprings", "design_problem", "frozen_problem",
           "group_springs", "motion_centres", "optimal_springs", "resolve_groups"]
