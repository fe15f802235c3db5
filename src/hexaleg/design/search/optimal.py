"""Springs as decision variables: the globally optimal magnitudes in one convex program.

:func:`optimal_springs` designs one spring per group of joints (a joint class, a mirrored pair,
one joint) for a prepared gait. For a fixed geometry (:mod:`hexaleg.design.families`) the
magnitudes come from one convex program over the whole cycle (:mod:`hexaleg.design.search.program`):
the global optimum for that geometry. The geometry — a few angles per group — is given, or
searched (:mod:`hexaleg.design.search.geometry`: each angle scanned over every place it can change
the design, coordinate descent over the groups to a fixed point; deterministic), each step one
convex solve. The linear family has no geometry, so its answer is global outright. A family
that contains others (:data:`~hexaleg.design.families.CONTAINS`: preloaded contains one_sided,
dead_zone and linear) starts from their optima, so it is never below them.

Every design constraint is linear in the magnitudes: magnitudes ≥ 0 where the family needs it;
``max_torque`` (|τ_s| ≤ τ_max over the gait; the laws are non-increasing in q, so the extremes of
each joint's motion are the binding samples); ``max_deflection`` (each spring element's
deflection from its free position ≤ Δ_max: a linear spring's |τ₀ − k (q − q_r)| ≤ k Δ_max, a
spring engaged past a contact angle ``k·compression + preload ≤ k Δ_max``, Shigley's torsion
spring: deflection = moment / rate); one design shared by a group's joints.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from hexaleg.checks import typed
from hexaleg.design.families import (
    CONTAINS,
    FAMILIES,
    ZERO_MAGNITUDE,
    Family,
    Geometry,
    embed,
)
from hexaleg.design.search.geometry import Mapper, off_angles, search_geometry
from hexaleg.design.search.program import DesignProblem, DesignSolution
from hexaleg.design.search.setup import (
    ENGAGED,
    METRICS,
    DesignSetup,
    Groups,
    design_setup,
    motion_centres,
    resolve_groups,
)
from hexaleg.design.springs.table import magnitudes_table
from hexaleg.dynamics.contact import QUADRATIC_OBJECTIVES
from hexaleg.dynamics.energy import saving
from hexaleg.dynamics.prepare import Analysis, Prepared
from hexaleg.errors import HexalegError, InvalidParameterError
from hexaleg.robot.springs import Spring, SpringSet

OBJECTIVE_METRIC = {"joule": "joule", "torque_squared": "rms_torque", "electrical": "electrical",
                    "positive_work": "positive_work"}
"""The metric of ``Analysis.metrics["total"]`` each objective is judged by."""



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
        mirrored: Joints whose spring is the group's design mirrored (they count their angle
            the other way round; geometry and magnitudes are the group's as designed).
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
    mirrored: frozenset[str] = frozenset()

    def table(self) -> dict[str, dict[str, Any]]:
        """Per group: geometry and magnitudes as ``{value, unit}``, in SI and the paper's units
        (N·mm/deg, N·mm, deg); an angle past which nothing acts has none
        (:func:`~hexaleg.design.springs.table.magnitudes_table`)."""
        return {g: magnitudes_table(self.geometry[g], self.magnitudes[g], self.family)
                for g in self.groups}


@typed
def optimal_springs(prepared: Prepared, groups: Groups, family: str = "linear",
                    objective: str = "joule", *, max_torque: float | None = None,
                    max_deflection: float | None = None,
                    geometry: Mapping[str, Geometry] | None = None,
                    start: Mapping[str, Geometry] | Sequence[Mapping[str, Geometry]] | None = None,
                    metric: str | None = None, mirrored: Iterable[str] = (),
                    contained: Sequence[OptimalSprings | None] | None = None,
                    map_fn: Mapper | None = None) -> OptimalSprings:
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
        mirrored: Joints that count their angle the other way round from their group's design
            (:func:`hexaleg.robot.mirror.mirror`): each gets the group's spring mirrored, so one
            physical design serves both sides of a mirror.
        contained: The optima of the families this one contains (same arguments; None where
            one has none), to start from; None: designed here.
        metric: What the magnitudes (and the geometry search) minimise. None (default): the
            force program's own objective, the joint program over (x, forces) above. With a
            metric the geometry is the Joule program's search, then the best in the metric of
            its optimum, the starts and the contained families' optima: never worse in the
            metric than any of them. (A coordinate descent in the metric within 4 levels of
            the Joule optimum gained at most 0.005 points on the default robot, for 4× the
            family's time.)
            ``"electrical"`` or ``"joule"`` (one of :data:`hexaleg.design.search.setup.METRICS`,
            with objective ``"joule"``): that metric per cycle of the Joule-optimal forces — the
            convention of ``Prepared.evaluate(springs, "joule")`` that ``hexaleg design`` ranks
            by — through the condensed program (:mod:`hexaleg.design.search.condensed`): exact, and
            the global optimum for the geometry, when no sample's friction, normal-force or
            torque-limit inequality binds at the optimum (checked at every sample); a sample
            that binds gets explicit forces minimising the metric there (that module's
            docstring). x = 0, the baseline, is always feasible, so the program never costs
            energy; should the exact evaluation still cost some (binding samples), the result
            is no springs (x = 0), with a note.
        map_fn: How the geometry searches solve candidates side by side
            (:func:`~hexaleg.design.search.geometry.search_geometry`; e.g.
            :func:`hexaleg.parallel.forked.fork_map`): the same result, sooner; default one
            after another here.

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
    mirrored = tuple(mirrored)  # read again for the contained families
    setup = design_setup(prepared, groups, family, objective, max_torque, max_deflection,
                         metric, mirrored=mirrored)
    baseline = float(prepared.baseline(objective)["total"][metric or OBJECTIVE_METRIC[objective]])
    if geometry is not None:
        if start is not None:
            raise InvalidParameterError("start", start, "None when the geometry is given")
        chosen = setup.check_geometry(geometry)
        return springs_result(setup, chosen, setup.solve(chosen), 1, baseline)
    starts = [] if start is None or not setup.fam.angles else (
        [start] if isinstance(start, Mapping) else list(start))
    checked = [setup.check_geometry(s) for s in starts]
    if contained is None:
        contained = [_inner(prepared, groups, inner, objective, max_torque, max_deflection,
                            metric, mirrored, map_fn) for inner in CONTAINS.get(family, ())]
    inner_starts = [_embedded(setup, c) for c in contained if c is not None]
    if not setup.condensed:  # its comparison solves are the exact program
        found = search_geometry(setup, [*checked, *inner_starts], map_fn=map_fn)
        chosen, solution, searches = found.geometry, found.solution, [found]
    else:  # the Joule program's search, then the best in the metric of it and the starts
        nominal = dataclasses.replace(setup, metric=None, shifts=())
        first = search_geometry(nominal, [*checked, *inner_starts], map_fn=map_fn)
        found = search_geometry(setup, [first.geometry, *checked, *inner_starts],
                                max_sweeps=0)
        chosen, solution, searches = found.geometry, setup.solve(found.geometry), [first, found]
    result = springs_result(setup, chosen, solution,
                            sum(f.evaluations for f in searches) + 1, baseline)
    search = {"stages": [f.to_dict() for f in searches],
              "contains": [c.family for c in contained if c is not None]}
    return dataclasses.replace(result, solver={**result.solver, "search": search})


def _inner(prepared: Prepared, groups: Groups, family: str, objective: str,
           max_torque: float | None, max_deflection: float | None, metric: str | None,
           mirrored: Iterable[str], map_fn: Mapper | None) -> OptimalSprings | None:
    """A contained family's optimum (a start of the containing family's search), or None where
    it has none (its program infeasible, a constraint no design of it meets)."""
    try:
        return optimal_springs(prepared, groups, family, objective, max_torque=max_torque,
                               max_deflection=max_deflection, metric=metric, mirrored=mirrored,
                               map_fn=map_fn)
    except HexalegError:
        return None


def _embedded(setup: DesignSetup, inner: OptimalSprings) -> dict[str, dict[str, float | str]]:
    """``inner``'s design as a geometry of ``setup``'s family (:func:`embed`), checked."""
    return setup.check_geometry({g: embed(setup.fam.name, inner.family, inner.geometry[g],
                                          inner.magnitudes[g], off_angles(setup, g))
                                 for g in setup.groups})


def design_problem(prepared: Prepared, groups: Groups, family: str,
                   geometry: Mapping[str, Geometry], objective: str = "joule", *,
                   max_torque: float | None = None, max_deflection: float | None = None
                   ) -> DesignProblem:
    """The design program :func:`optimal_springs` solves for a given geometry (arguments as
    there), for benchmarks and comparisons of the solvers
    (:func:`hexaleg.design.search.program.solve_design`,
    :func:`hexaleg.design.search.program_reference.solve_design_reference`)."""
    setup = design_setup(prepared, groups, family, objective, max_torque, max_deflection)
    return setup.problem(setup.check_geometry(geometry))


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
    setup = design_setup(prepared, optimum.groups, optimum.family, optimum.objective, max_torque,
                   max_deflection, mirrored=optimum.mirrored)
    setup = dataclasses.replace(setup, centre={j: float(centres[j]) for j in setup.centre})
    p = setup.problem(setup.check_geometry(optimum.geometry))
    keep = np.array([label != "never engaged" for label in p.labels], dtype=bool)
    return dataclasses.replace(p, G=p.G[keep] if p.G.size else p.G, h=p.h[keep],
                               labels=tuple(lb for lb, k in zip(p.labels, keep, strict=True)
                                            if k))


def group_springs(fam: Family, groups: Mapping[str, Sequence[str]],
                  geometry: Mapping[str, Geometry], centres: Mapping[str, float], x: np.ndarray,
                  mirrored: frozenset[str] = frozenset()
                  ) -> tuple[dict[str, dict[str, float]], dict[str, Spring]]:
    """Group → magnitude name → value, and joint → spring law, of the stacked magnitudes ``x``
    (groups in order, each :attr:`Family.magnitudes`; angles from ``centres``, rad); a joint of
    ``mirrored`` gets its group's spring mirrored (:meth:`Family.mirror`)."""
    nm = len(fam.magnitudes)
    magnitudes, springs = {}, {}
    for i, (g, js) in enumerate(groups.items()):
        xg = x[i * nm:(i + 1) * nm]
        magnitudes[g] = dict(zip(fam.magnitudes, (float(v) for v in xg), strict=True))
        for j in js:
            if j in mirrored:
                mirrored_geometry, mirrored_x = fam.mirror(geometry[g], xg)
                springs[j] = fam.spring(mirrored_geometry, centres[j], mirrored_x)
            else:
                springs[j] = fam.spring(geometry[g], centres[j], xg)
    return magnitudes, springs


def springs_result(setup: DesignSetup, geometry: dict[str, dict[str, float | str]],
                   solution: DesignSolution, evaluations: int, baseline: float
                   ) -> OptimalSprings:
    """The :class:`OptimalSprings` of a solved geometry: the springs, their exact evaluation
    (``prepared.evaluate(springs, objective)``), notes and how it was solved."""
    fam, prepared = setup.fam, setup.prepared
    nonneg = np.tile(fam.nonnegative(), len(setup.groups))
    x = np.where(nonneg, np.maximum(solution.x, 0.0), solution.x)
    problem = setup.problem(geometry)  # a term that never acts over the gait is exactly 0 (a
    for row, label in zip(problem.G, problem.labels, strict=True):  # solver leaves ~1e-12)
        if label == "never engaged":
            x[np.flatnonzero(row)] = 0.0
    magnitudes, springs = group_springs(fam, setup.groups, geometry, setup.centre, x,
                                        setup.mirrored)
    notes = []
    for g, m in magnitudes.items():
        if (fam.name == "linear" and m["k"] <= ZERO_MAGNITUDE
                and abs(m["torque_at_reference"]) > ZERO_MAGNITUDE):
            notes.append(f"group {g}: k = 0 with a constant torque of "
                         f"{m['torque_at_reference']:+.4g} N·m — a constant-torque spring; "
                         "bound how far a real spring may wind with max_deflection (hexaleg "
                         "design: [design] max_deflection)")
    analysis = prepared.evaluate(springs, setup.objective)
    metric = setup.metric or OBJECTIVE_METRIC[setup.objective]
    value = float(analysis.metrics["total"][metric])
    if setup.metric is not None and value > baseline:  # never a design that costs energy
        notes.append(f"no magnitudes of {fam.name} springs save {metric} energy here (the "
                     f"program's best costs {100 * -saving(value, baseline):.3g} %): no springs")
        x = np.zeros_like(x)
        magnitudes, springs = group_springs(fam, setup.groups, geometry, setup.centre, x,
                                        setup.mirrored)
        analysis = prepared.evaluate(springs, setup.objective)
        value = float(analysis.metrics["total"][metric])
    return OptimalSprings(
        family=fam.name, objective=setup.objective, groups=dict(setup.groups),
        geometry=geometry, magnitudes=magnitudes, springs=SpringSet(springs), analysis=analysis,
        metric=metric, value=value, baseline=baseline, saving=saving(value, baseline),
        notes=tuple(notes), mirrored=setup.mirrored,
        solver={"path": ("condensed program" if setup.condensed else "active set"
                         if setup.objective in QUADRATIC_OBJECTIVES else "cvxpy stacked program"),
                "program_value": solution.value, "clarabel_solves": solution.rounds,
                "explicit_samples": int(solution.explicit.size),
                "geometry_evaluations": evaluations})


__all__ = ["ENGAGED", "FAMILIES", "METRICS", "OBJECTIVE_METRIC", "DesignSetup", "Groups",
           "OptimalSprings", "design_problem", "frozen_problem", "group_springs",
           "motion_centres", "optimal_springs", "resolve_groups", "springs_result"]
