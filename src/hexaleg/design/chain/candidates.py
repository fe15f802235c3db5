"""One family's answer: its optimal springs, the parts to buy, and what they save net of their mass.

For a family, :func:`design_family` finds the global optimum of the magnitudes with the geometry
searched (:func:`hexaleg.design.search.optimal.optimal_springs`, one design per joint class); for a
mirrored or per-joint grouping it keeps each class's geometry and re-solves the magnitudes of
the finer groups (one convex program: never worse than the class design, which it contains).
Each spring element becomes a torsion spring (:mod:`hexaleg.design.springs.parts`); the springs'
mass, carried at their joints (:func:`hexaleg.robot.payload.with_point_masses`), costs energy,
so the saving is also given net of it: the gait with the springs on the heavier robot against
the baseline of the robot as it is (a logged motion kept as logged, :func:`carried`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from hexaleg.design.chain.config import METRICS, DesignParams
from hexaleg.design.chain.groups import class_of
from hexaleg.design.evaluator import Scenario, metric_row
from hexaleg.design.families import CONTAINS, Geometry
from hexaleg.design.search.geometry import Mapper
from hexaleg.design.search.optimal import OptimalSprings, optimal_springs
from hexaleg.design.springs.parts import (
    PartOptions,
    SpringPart,
    arbor_for,
    spring_masses,
    spring_parts,
)
from hexaleg.dynamics.energy import saving
from hexaleg.dynamics.prepare import Prepared, prepare
from hexaleg.errors import HexalegError
from hexaleg.motion.legged import tripod_gait
from hexaleg.motion.params import GaitParams
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.mirror import mirror
from hexaleg.robot.payload import with_point_masses
from hexaleg.robot.springs import SpringSet


@dataclass(frozen=True, eq=False)
class Candidate:
    """One family's optimal design on the sprung groups and what it buys.

    Attributes:
        family: The spring family.
        optimum: Its optimal springs (:class:`~hexaleg.design.search.optimal.OptimalSprings`).
        parts: The torsion springs to buy, one per element and group.
        row: Every metric with the springs, its baseline and saving
            (:func:`~hexaleg.design.evaluator.metric_row`).
        spring_mass: Mass of all the springs, kg.
        net: Metric (:data:`~hexaleg.design.chain.config.METRICS`) → saving with the
            springs' mass carried.
        marginal: Group → saving of the ranking metric lost without that group's springs
            (fraction of the baseline).
        notes: What the user should know (constant-torque springs, springs that do not fit).
        max_torque: The spring torque bound it was designed with, N·m, or None.
        dropped: Group → its own marginal saving, for the groups of the classes left unfitted
            because the class's worth was below ``[design] min_group_saving``
            (:func:`parsimonious`).
        searched: The family's optimum on every sprung class as its geometry search found it
            (before finer groups and the parsimony): where a family that contains this one
            starts its search (:data:`~hexaleg.design.families.CONTAINS`).
    """

    family: str
    optimum: OptimalSprings
    parts: tuple[SpringPart, ...]
    row: dict[str, Any]
    spring_mass: float
    net: dict[str, float]
    marginal: dict[str, float]
    notes: tuple[str, ...]
    max_torque: float | None = None
    dropped: Mapping[str, float] = field(default_factory=dict)
    searched: OptimalSprings | None = None

    @property
    def label(self) -> str:
        """The family, and its torque bound when it has one."""
        bound = f", spring torque ≤ {self.max_torque:.4g} N·m" if self.max_torque else ""
        return self.family + bound

    @property
    def buildable(self) -> bool:
        """Every part has a torsion spring that fits and holds up."""
        return all(p.spring is not None for p in self.parts)


def _optimum(prepared: Prepared, groups: Mapping[str, tuple[str, ...]],
             class_groups: Mapping[str, tuple[str, ...]], family: str, params: DesignParams,
             start: Sequence[Mapping[str, Geometry]] = (),
             geometry: Mapping[str, Geometry] | None = None,
             contained: Mapping[str, OptimalSprings] | None = None,
             map_fn: Mapper | None = None) -> tuple[OptimalSprings, OptimalSprings]:
    """The family's optimum on the class groups (at ``geometry`` when given, else searched from
    ``start`` and the optima of the families it contains, ``contained``: family → optimum on the
    same class groups; designed here where one is missing), and the design on ``groups``: for
    finer groups, their magnitudes at the class geometry; ``map_fn`` spreads the search's solves
    (:func:`~hexaleg.design.search.optimal.optimal_springs`)."""
    bound = params.deflection_bound
    kw: dict[str, Any] = {"max_torque": params.max_torque, "max_deflection": bound,
                          "metric": params.metric,
                          "mirrored": mirror(prepared.robot).mirrored if params.mirror else ()}
    if geometry is not None:
        best = optimal_springs(prepared, dict(class_groups), family, "joule",
                               geometry=dict(geometry), **kw)
    else:
        inner = [(contained or {}).get(f) for f in CONTAINS.get(family, ())]
        usable = all(c is not None and c.groups == dict(class_groups) for c in inner)
        best = optimal_springs(prepared, dict(class_groups), family, "joule",
                               start=list(start) or None,
                               contained=inner if usable else None, map_fn=map_fn, **kw)
    if dict(groups) == dict(class_groups):
        return best, best
    owner = {j: c for c, js in class_groups.items() for j in js}
    geometry = {g: best.geometry[owner[js[0]]] for g, js in groups.items()}
    return best, optimal_springs(prepared, dict(groups), family, "joule", geometry=geometry,
                                 **kw)


def arbors(run: Scenario, groups: Mapping[str, Sequence[str]]) -> dict[str, float]:
    """Group → the arbor its springs wind on, m (:func:`~hexaleg.design.springs.parts.arbor_for`:
    the description's, the servo's output hub, else the stated rule from the link width)."""
    robot, desc, motor = run.model, run.description, run.actuator
    return {g: arbor_for(robot, desc, motor, class_of(robot, tuple(js)))[0]
            for g, js in groups.items()}


def carried(run: Scenario, gait: GaitParams, masses: Mapping[str, float],
            logged: Motion | None = None) -> Prepared:
    """The nominal gait of the robot carrying ``masses`` (joint → kg) at its joints: the gait
    re-made on the heavier robot, or a logged motion (``--motion``) as it was logged (a log is
    the motion the robot walked: the mass is added to the robot, the motion unchanged).

    Raises:
        HexalegError: the gait or its forces cannot be made with the mass added; the message
            names the gait and the springs' mass, and what was refused.
    """
    heavy = with_point_masses(run.model, masses, note="springs' mass at their joints")
    which = (f"the logged motion {logged.info.get('log', '')}" if logged is not None else
             f"the nominal gait (period {gait.period:g} s, stride {gait.stride:g} m, "
             f"{gait.samples} samples)")
    try:
        motion = logged if logged is not None else tripod_gait(heavy, gait)
        return prepare(heavy, motion, motor=run.actuator, contact=run.contact)
    except HexalegError as e:
        grams = ", ".join(f"{j} {1e3 * m:.1f} g" for j, m in masses.items())
        raise HexalegError(
            f"the saving net of the springs' mass needs {which} on the robot carrying the "
            f"springs ({1e3 * sum(masses.values()):.1f} g: {grams}), and it cannot be made: "
            f"{type(e).__name__}: {e}") from e


def candidate(optimum: OptimalSprings, prepared: Prepared, run: Scenario, gait: GaitParams,
              outer: Mapping[str, float], params: DesignParams) -> Candidate:
    """Parts, savings net of the springs' mass and each group's share, of one optimum."""
    options = PartOptions(materials=params.materials, safety_factor=params.safety_factor,
                          arbor_diameter=params.arbor_diameter, leg_length=params.leg_length,
                          life_cycles=params.life_cycles)
    parts = spring_parts(optimum, prepared, outer, options,
                         arbor=None if params.arbor_diameter > 0 else arbors(run, optimum.groups))
    a = optimum.analysis
    row = metric_row(a.metrics, a.baseline)
    masses = spring_masses(parts)
    # a run of a given motion (a log, an optimal motion) carries it unchanged, whatever made it
    logged = prepared.motion if run.recorded is not None else None
    heavy = carried(run, gait, masses, logged).evaluate(optimum.springs,
                                                         "joule").metrics["total"]
    net = {m: saving(float(heavy[m]), float(a.baseline["total"][m])) for m in METRICS}
    marginal = {}
    for g, joints in optimum.groups.items():
        rest = SpringSet({j: s for j, s in optimum.springs.items() if j not in joints})
        without = prepared.evaluate(rest, "joule").metrics["total"][params.metric]
        marginal[g] = row[f"saving.{params.metric}"] - saving(
            float(without), float(a.baseline["total"][params.metric]))
    notes = list(optimum.notes)
    for p in parts:
        if p.problem:
            notes.append(f"group {p.group} ({p.side}, {p.role}): {p.problem}")
    return Candidate(family=optimum.family, optimum=optimum, parts=parts, row=row,
                     spring_mass=sum(masses.values()), net=net, marginal=marginal,
                     notes=tuple(notes), max_torque=params.max_torque)


def design_family(prepared: Prepared, run: Scenario, gait: GaitParams,
                  groups: Mapping[str, tuple[str, ...]],
                  class_groups: Mapping[str, tuple[str, ...]], family: str,
                  params: DesignParams, outer: Mapping[str, float],
                  start: Sequence[Mapping[str, Geometry]] = (),
                  geometry: Mapping[str, Geometry] | None = None,
                  contained: Mapping[str, OptimalSprings] | None = None,
                  map_fn: Mapper | None = None) -> Candidate:
    """One family's :class:`Candidate` (module docstring).

    Args:
        prepared: The nominal gait, prepared.
        run: Robot, actuator, contact (for the gait carrying the springs' mass).
        gait: The nominal gait's parameters.
        groups: The design groups (:func:`hexaleg.design.chain.groups.design_groups`).
        class_groups: The same joints by class (where the geometry is searched).
        family: The spring family.
        params: The ``[design]`` table.
        outer: Group → largest outer diameter of its springs, m.
        start: Class geometries to start the geometry search from.
        geometry: Class → geometry to design the magnitudes at instead of searching it.
        contained: Family → the class-level optimum (:attr:`Candidate.searched`) of the families
            this one contains, to start its search from.
        map_fn: How the geometry search solves candidates side by side (e.g.
            :func:`hexaleg.parallel.forked.fork_map`; the same result); default here.

    Raises:
        HexalegError: as :func:`~hexaleg.design.search.optimal.optimal_springs` (constraints that no
            design meets name themselves there).
    """
    searched, optimum = _optimum(prepared, groups, class_groups, family, params, start,
                                 geometry, contained, map_fn)
    return dataclasses.replace(candidate(optimum, prepared, run, gait, outer, params),
                               searched=searched)


def parsimonious(prepared: Prepared, run: Scenario, gait: GaitParams,
                 groups: Mapping[str, tuple[str, ...]],
                 class_groups: Mapping[str, tuple[str, ...]], family: str,
                 params: DesignParams, outer: Mapping[str, float],
                 start: Sequence[Mapping[str, Geometry]] = (),
                 geometry: Mapping[str, Geometry] | None = None,
                 contained: Mapping[str, OptimalSprings] | None = None,
                 map_fn: Mapper | None = None) -> Candidate:
    """:func:`design_family` without the joint classes that do not pay for their parts.

    A class's worth (:func:`class_worth`: the ranking metric's saving lost without all its
    springs, the others kept) below ``params.min_group_saving`` means parts to buy, mount and
    maintain for less than that share of the baseline: the weakest such class is left unsprung
    and the family designed again on the rest (the magnitudes re-optimised: the other classes
    may take over some of its work), until every class clears the bar or one class is left. The
    bar is on the class whatever the grouping, so like is compared with like: per joint, a
    tibia's spring is a sixth of its class's worth, and a bar on each group would drop a class
    the class design keeps (a refinement that loses). The rest keep their searched geometry and
    get their magnitudes again (one convex program: the global optimum of the magnitudes for
    that geometry); the geometry is not searched again (that would double the design's time
    for a change under the bar). The dropped groups and their own shares are in
    :attr:`Candidate.dropped`, the classes' worth in the notes; the design is never one with a
    class under the bar unless it is the last one (then the candidate's own saving says whether
    it pays at all).

    Args: as :func:`design_family`.
    """
    def usable(starts: Sequence[Mapping[str, Geometry]]) -> list[dict[str, Geometry]]:
        """The starts restricted to the classes designed (those missing one are left out)."""
        return [{k: s[k] for k in class_groups} for s in starts
                if all(k in s for k in class_groups)]

    dropped: dict[str, float] = {}
    notes: list[str] = []
    start = usable(start)
    c = design_family(prepared, run, gait, groups, class_groups, family, params, outer, start,
                      None if geometry is None else {k: geometry[k] for k in class_groups},
                      contained, map_fn)
    searched = c.searched
    while len(class_groups) > 1:
        worth = class_worth(c, prepared, class_groups, params.metric)
        weak = {k: v for k, v in worth.items() if v < params.min_group_saving}
        if not weak:
            break
        cls = min(weak, key=lambda k: weak[k])
        members = [g for g, js in groups.items() if js[0] in class_groups[cls]]
        dropped.update({g: float(c.marginal[g]) for g in members})
        notes.append(f"class {cls} not fitted ({', '.join(members)}): its springs would add "
                     f"{100 * worth[cls]:+.2f} % of {params.metric} (under the "
                     f"{100 * params.min_group_saving:g} point bar, [design] min_group_saving)")
        class_groups = {k: v for k, v in class_groups.items() if k != cls}
        groups = {g: js for g, js in groups.items() if g not in dropped}
        kept = class_geometry(c.optimum, class_groups)
        c = design_family(prepared, run, gait, groups, class_groups, family, params, outer,
                          geometry=kept)
    if dropped:
        c = dataclasses.replace(c, dropped=dropped, notes=(*c.notes, *notes))
    return dataclasses.replace(c, searched=searched)


def class_worth(c: Candidate, prepared: Prepared, class_groups: Mapping[str, tuple[str, ...]],
                metric: str) -> dict[str, float]:
    """Class → the saving of ``metric`` lost without all of the class's springs in ``c``, the
    others kept (a fraction of the baseline; the class's :attr:`Candidate.marginal` when it is
    one group)."""
    base = float(c.optimum.analysis.baseline["total"][metric])
    out = {}
    for cls, joints in class_groups.items():
        rest = SpringSet({j: s for j, s in c.optimum.springs.items() if j not in joints})
        without = float(prepared.evaluate(rest, "joule").metrics["total"][metric])
        out[cls] = c.row[f"saving.{metric}"] - saving(without, base)
    return out


def class_geometry(optimum: OptimalSprings, class_groups: Mapping[str, tuple[str, ...]]
                    ) -> dict[str, Geometry]:
    """Class → the geometry of ``optimum`` for the classes in ``class_groups`` (finer groups
    share their class's; a class ``optimum`` does not spring is left out)."""
    out: dict[str, Geometry] = {}
    for g, js in optimum.groups.items():
        owner = next((k for k, cj in class_groups.items() if js[0] in cj), None)
        if owner is not None:
            out.setdefault(owner, optimum.geometry[g])
    return out
