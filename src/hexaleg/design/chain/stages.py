"""The stages of ``hexaleg design``, each a function with its inputs and outputs.

:class:`~hexaleg.design.chain.chain.DesignChain` runs them in order (as pvlib's ModelChain
runs its models): :func:`nominal` (the gait prepared once, the groups and the fit limits),
:func:`family_candidates` (every family's optimum, groups that do not pay left out),
:func:`pareto_front` (the best family under spring-torque bounds), :func:`stop_tolerance` (the
recommendation designed for its stops' mounting error),
:func:`robustness_maps` (the recommendation under changed conditions). The design for a box of
conditions is :mod:`hexaleg.design.chain.robust_stage`; the ranking by simulation is
:mod:`hexaleg.design.chain.ranking`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TypeVar

import numpy as np

from hexaleg.checks import one_of
from hexaleg.design.chain.candidates import (
    Candidate,
    candidate,
    class_geometry,
    parsimonious,
)
from hexaleg.design.chain.config import METRICS, DesignParams
from hexaleg.design.chain.groups import (
    class_of,
    design_groups,
    split_by_motion,
    sprung_classes,
)
from hexaleg.design.families import Geometry, containment_waves
from hexaleg.design.robust.conditions import condition_prepared
from hexaleg.design.robust.maps import RobustnessMap, robot_patterns, robustness_map
from hexaleg.design.search.optimal import OptimalSprings
from hexaleg.design.search.tolerance import TolerantSprings, tolerant_springs
from hexaleg.design.springs.envelope import PartEnvelope, parts_envelope
from hexaleg.design.springs.fatigue import FatigueCheck, spring_fatigue
from hexaleg.design.springs.parts import SpringPart, spring_outer_diameter
from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import (
    HexalegError,
    InfeasibleForcesError,
    InvalidParameterError,
)
from hexaleg.motion.legged import tripod_gait
from hexaleg.motion.params import GaitParams
from hexaleg.motion.trajectory import Motion
from hexaleg.parallel.forked import fork_map, robot_objects
from hexaleg.robot.description import RobotDescription
from hexaleg.robot.mirror import mirror
from hexaleg.robot.model import Robot
from hexaleg.scenario.condition import Condition
from hexaleg.scenario.scenario import Scenario

T = TypeVar("T")
R = TypeVar("R")


@dataclass(frozen=True, eq=False)
class Nominal:
    """What every stage shares: the robot, its nominal gait prepared once, the groups.

    Attributes:
        design: The ``[design]`` table. run: The run (robot, actuator, contact, the nominal
            gait at ``[design] samples``). robot: The robot. desc: Its description. gait: The
            nominal gait (a log's: its period and samples). prepared: It, prepared.
        baseline: Metric totals without springs (J or N·m).
        classes: The sprung joint classes. class_groups: Class → joints (where geometries are
            searched). groups: The design groups (``[design] grouping``).
        outer: Group → (largest spring outer diameter, m; where it comes from).
        motion: The logged motion (``--motion``) the design is made on, or None for the
            generated gait (then ``gait`` only gives its period and samples).
        notes: What the grouping decided (a class split by its motion,
            :func:`~hexaleg.design.chain.groups.split_by_motion`).
    """

    design: DesignParams
    run: Scenario
    robot: Robot
    desc: RobotDescription
    gait: GaitParams
    prepared: Prepared
    baseline: dict[str, float]
    classes: tuple[str, ...]
    class_groups: dict[str, tuple[str, ...]]
    groups: dict[str, tuple[str, ...]]
    outer: dict[str, tuple[float, str]]
    motion: Motion | None = None
    notes: tuple[str, ...] = ()

    @property
    def outer_diameters(self) -> dict[str, float]:
        """Group → largest spring outer diameter, m."""
        return {g: v for g, (v, _) in self.outer.items()}

    def family(self, family: str, params: DesignParams | None = None,
               start: Sequence[dict[str, Geometry]] = (), like: Candidate | None = None,
               geometry: dict[str, Geometry] | None = None,
               contained: Mapping[str, OptimalSprings] | None = None) -> Candidate:
        """One family's parsimonious candidate (:func:`~hexaleg.design.chain.candidates.
        parsimonious`) with the ``[design]`` table, or ``params`` in its place; on the groups of
        ``like`` only when given (its classes: the others were left unfitted); at ``geometry``
        (class → geometry) when given, else searched (from ``contained``: family → the
        class-level optimum of a family it contains), its solves spread over the cores
        (:meth:`fork_map`: the same result)."""
        d = self.design if params is None else params
        groups, classes = self.groups, self.class_groups
        if like is not None:
            groups = {g: js for g, js in groups.items() if g in like.optimum.groups}
            kept = {j for js in groups.values() for j in js}
            classes = {k: js for k, js in classes.items() if js[0] in kept}
        return parsimonious(self.prepared, self.run, self.gait, groups, classes, family, d,
                            self.outer_diameters, start, geometry, contained, self.fork_map)

    def fork_map(self, fn: Callable[[T], R], items: Sequence[T],
                 done: Callable[[int, R], None] | None = None) -> list[R]:
        """``[fn(x) for x in items]`` over one forked process per core, the results referring to
        this robot by reference (:func:`~hexaleg.parallel.forked.fork_map`)."""
        return fork_map(fn, items, shared=robot_objects(self.robot), done=done)


LOGGED_SKIP = ("the robustness maps and the robust design are left out: they re-make the gait "
               "from its parameters (period, stride, pattern) and a logged motion (--motion) has "
               "none to vary; the candidates, ranking, stop tolerance and envelope are on the "
               "logged cycle")
"""The note of a design on a logged motion."""
UNMAPPED = ("the robustness maps and the robust design are left out ([design] robustness = "
            "false): neither is one of the spring rules, both are about conditions other than "
            "the nominal gait")
"""The note of a design without them (``[design] robustness`` false)."""


def nominal(run: Scenario, d: DesignParams) -> Nominal:
    """The nominal gait of ``run`` prepared (or the logged motion's cycle), the sprung classes,
    the design groups and their fit limits (``d``: the ``[design]`` table)."""
    robot, desc, gait = run.model, run.description, run.gait
    for kind in d.max_outer_diameter:  # a typo would be ignored and the springs come out larger
        one_of("[design] max_outer_diameter joint class", kind, robot.joint_kinds)
    motion = run.recorded
    if motion is not None:  # the log's cycle, as the run read it
        gait = dataclasses.replace(gait, samples=motion.n_samples, period=motion.period)
        prepared = run.prepare()
    else:
        prepared = condition_prepared(run, Condition())
    baseline = {k: float(v) for k, v in prepared.baseline("joule")["total"].items()}
    classes = sprung_classes(robot, d.classes)
    signs = mirror(robot).signs if d.mirror else None
    q = prepared.motion.q[:, 7:]
    angles = {j: (float(q[:, c].min()), float(q[:, c].max()))
              for j, c in ((j, robot.column(j)) for j in robot.joint_names)}
    class_groups, split = split_by_motion(robot, design_groups(robot, classes, "class"), angles,
                                          signs)
    groups = (class_groups if d.grouping == "class" else
              design_groups(robot, classes, d.grouping))
    outer = {}
    for g, js in groups.items():
        kind = class_of(robot, js)
        outer[g] = ((float(d.max_outer_diameter[kind]), "[design] max_outer_diameter")
                    if kind in d.max_outer_diameter else spring_outer_diameter(desc, robot, kind))
        if d.arbor_diameter >= outer[g][0]:  # a coil winds around the arbor, inside the limit
            raise InvalidParameterError(
                "[design] arbor_diameter", d.arbor_diameter,
                f"< {1e3 * outer[g][0]:.3g} mm, the largest spring outer diameter of {g} "
                f"({outer[g][1]}): a spring's coil winds around its arbor (0 for the rule of "
                "docs/design.md)")
    return Nominal(d, run, robot, desc, gait, prepared, baseline, tuple(classes),
                   class_groups, groups, outer, motion, tuple(split))


def rank(c: Candidate, metric: str) -> float:
    """The predicted saving of ``metric`` net of the springs' mass (−∞ when not finite)."""
    value = c.net[metric]
    return float(value) if np.isfinite(value) else -np.inf


def family_candidates(nom: Nominal, progress: Callable[[str, str], None]
                      ) -> tuple[list[Candidate], list[str]]:
    """Every allowed family's candidate, ranked by predicted net saving (best first), and a note
    for each family whose program failed (skipped: the design goes on with the others).

    The families are convex programs with their own geometry searches, so they run in
    parallel, one process per core (:func:`~hexaleg.parallel.forked.fork_map`: the workers
    inherit the prepared gait, each returns its candidate with the robot by reference), the
    same computations as one after the other (tested bit for bit). A family that contains
    others (:data:`~hexaleg.design.families.CONTAINS`) runs after them and starts its search
    from their optima, so its optimum is never below theirs.

    Args:
        nom: The nominal stage.
        progress: Called with (step name, message) as each family ends.

    Raises:
        HexalegError: every family failed (the first family's own error).
    """
    d = nom.design
    found: dict[str, Candidate] = {}
    failed: dict[str, str] = {}

    def done(i: int, c: Candidate | str) -> None:
        fam = d.families[i]
        if isinstance(c, str):
            failed[fam] = c
            progress(f"family {fam}", f"{fam}: left out, its program failed: {c}")
            return
        found[fam] = c
        progress(f"family {fam}", f"{fam}: family optimum, {d.metric} saving "
                 f"{100 * c.row[f'saving.{d.metric}']:+.2f} %")

    for wave in containment_waves(d.families):
        contained = {f: c.searched for f, c in found.items() if c.searched is not None}

        def one(fam: str, contained: dict[str, OptimalSprings] = contained) -> Candidate | str:
            try:
                return nom.family(fam, contained=contained)
            except HexalegError as err:  # this family only: the others go on
                return f"{type(err).__name__}: {err}"

        def finished(i: int, c: Candidate | str, wave: list[str] = wave) -> None:
            done(d.families.index(wave[i]), c)

        nom.fork_map(one, wave, done=finished)
    if not found:  # the first family again, here: its own error, raised (the workers' are
        nom.family(d.families[0])  # messages only)
        raise InfeasibleForcesError(f"every spring family's program failed: "
                                    f"{failed[d.families[0]]}")
    cands = [found[fam] for fam in d.families if fam in found]
    notes = [f"spring family {fam} left out: its program failed on this gait ({why}); the "
             "design compares the other families" for fam, why in failed.items()]
    return sorted(cands, key=lambda c: -rank(c, d.metric)), notes


PER_JOINT_EVIDENCE = 0.02
"""Net saving (a fraction of the baseline) by which per-joint springs must beat the design by
joint class for the answer to say so (issue #55: +38.91 % per joint against +32.34 % by class
on a 13-kg quadruped, unsaid)."""


def per_joint_evidence(nom: Nominal, rec: Candidate) -> str | None:
    """What ``[design] grouping = "joint"`` would design against ``rec``, designed by joint
    class: the same family at the class geometry the search found, the magnitudes per joint
    (one convex program containing the class design), the classes that do not pay left
    unfitted as the class design does (:func:`~hexaleg.design.chain.candidates.parsimonious`).
    A note with both net savings when per joint is ahead by more than
    :data:`PER_JOINT_EVIDENCE`, else None (also for another grouping, or when the per-joint
    program fails: the class design stands)."""
    d = nom.design
    searched = rec.searched if rec.searched is not None else rec.optimum
    classes = {g: js for g, js in nom.class_groups.items() if g in searched.geometry}
    if d.grouping != "class" or not rec.buildable or not classes:
        return None
    groups = {j: (j,) for js in classes.values() for j in js}
    if len(groups) == len(classes):
        return None
    outer = {j: nom.outer_diameters[g] for g, js in classes.items() for j in js}
    params = dataclasses.replace(d, max_torque=rec.max_torque)
    try:
        fine = parsimonious(nom.prepared, nom.run, nom.gait, groups, classes, rec.family, params,
                            outer, geometry={g: searched.geometry[g] for g in classes})
    except HexalegError:
        return None
    gain = float(fine.net[d.metric] - rec.net[d.metric])
    if not gain > PER_JOINT_EVIDENCE:
        return None
    return (f"per-joint springs would save {100 * fine.net[d.metric]:+.2f} % of {d.metric} net "
            f"of their mass ({1e3 * fine.spring_mass:.1f} g) against "
            f"{100 * rec.net[d.metric]:+.2f} % for the design by joint class "
            f"({100 * gain:+.2f} points; {rec.family} at the class geometry, each joint's "
            "magnitudes its own): [design] grouping = \"joint\" designs them")


def pareto_front(nom: Nominal, rec: Candidate) -> list[tuple[float, Candidate]]:
    """``rec``'s geometry with its spring torque bounded to fractions of its peak: at each bound
    the magnitudes are the global optimum of the ranking metric for that geometry (one convex
    program each; the magnitudes optimise the metric the design ranks by, so no bounded point
    beats the unbounded one on its own geometry).

    Returns:
        ``[(fraction, candidate)]`` ascending, the last ``rec`` itself (fraction 1).
    """
    d = nom.design
    peak = float(np.abs(rec.optimum.analysis.tau_spring).max())
    geometry = class_geometry(rec.optimum, nom.class_groups)
    pareto = []
    for f in sorted(d.pareto_fractions):
        if peak <= 0:
            break
        bounded = dataclasses.replace(d, max_torque=min(f * peak, d.max_torque or np.inf))
        pareto.append((f, nom.family(rec.family, bounded, like=rec, geometry=geometry)))
    return [*pareto, (1.0, rec)]


def stop_tolerance(nom: Nominal, rec: Candidate) -> tuple[Candidate, TolerantSprings | None]:
    """``rec`` designed for the stops a workshop mounts within ``[design] stop_tolerance``
    (:func:`hexaleg.design.search.tolerance.tolerant_springs`: the worst saving over the mounting
    errors maximised), with its parts, when that keeps more than the tolerance-blind design's
    worst; else ``rec``. The comparison (both designs' nominal and worst savings and curves)
    either way; None without a tolerance or for a family without angles."""
    d = nom.design
    if d.stop_tolerance == 0 or not rec.optimum.geometry or not any(
            rec.optimum.geometry.values()):
        return rec, None
    t = tolerant_springs(nom.prepared, rec.optimum, d.stop_tolerance, d.metric,
                         max_torque=rec.max_torque, max_deflection=d.deflection_bound,
                         map_fn=nom.fork_map)
    if t.chosen == "blind":
        return rec, t
    return dataclasses.replace(candidate(t.optimum, nom.prepared, nom.run, nom.gait,
                                         nom.outer_diameters, d), dropped=rec.dropped,
                               max_torque=rec.max_torque), t


TURN_RATE = 0.2
"""rad/s: the turn whose joint ranges the envelope adds (the nominal gait turning, a gentle turn
of about 11° a second)."""


def envelope_and_fatigue(nom: Nominal, rec: Candidate
                         ) -> tuple[tuple[PartEnvelope, ...], tuple[tuple[SpringPart, FatigueCheck],
                                                                      ...], list[str]]:
    """Each bought part's stress over everything its joints may see
    (:func:`hexaleg.design.springs.envelope.parts_envelope`: URDF limits, stand and sphere poses,
    the gait, a turn at :data:`TURN_RATE`) with the hard stop it needs where it would yield, and its
    fatigue safety at ``[design] life_cycles``
    (:func:`hexaleg.design.springs.fatigue.spring_fatigue`); notes for a turn the robot cannot
    make."""
    d = nom.design
    parts = [p for p in rec.parts if p.spring is not None]
    joints = sorted({j for p in parts for j in p.joints}, key=nom.robot.column)
    extra, notes = [], []
    if nom.motion is not None:
        notes.append(f"the envelope leaves out a turn at {TURN_RATE:g} rad/s: a logged motion "
                     "(--motion) has no gait to turn")
    else:
        try:
            turn = tripod_gait(nom.robot, dataclasses.replace(nom.gait, yaw_rate=TURN_RATE))
            q = {j: turn.q[:, nom.robot.column(j)] for j in joints}
            extra.append((f"turning {TURN_RATE:g} rad/s",
                          {j: (float(v.min()), float(v.max())) for j, v in q.items()}))
        except HexalegError as e:
            notes.append(f"the envelope leaves out a turn at {TURN_RATE:g} rad/s: {e}")
    env = parts_envelope(parts, nom.prepared, extra=extra, design_factor=d.safety_factor,
                         mirrored=rec.optimum.mirrored)
    assert all(p.spring is not None for p in parts)
    fatigue = tuple((p, spring_fatigue(p.spring, life=d.life_cycles))  # type: ignore[arg-type]
                    for p in parts)
    return env, fatigue, notes


def robustness_maps(nom: Nominal, rec: Candidate
                    ) -> tuple[tuple[RobustnessMap, ...], dict[str, tuple[float, str]]]:
    """The recommendation frozen over period × stride, payload × μ and slope × pattern (the
    ground's slope along the walking direction; the patterns of ``[design] map_pattern``, by
    default the nominal gait's and every other the robot's legs walk,
    :func:`~hexaleg.design.robust.maps.robot_patterns`), and each metric's worst case
    (saving, its condition's label) over all three; none on a logged motion (NaN worst cases,
    :data:`LOGGED_SKIP`), nor without ``[design] robustness`` (:data:`UNMAPPED`)."""
    d = nom.design
    if nom.motion is not None or not d.robustness:  # LOGGED_SKIP, UNMAPPED
        why = "logged motion" if nom.motion is not None else "[design] robustness = false"
        return (), {m: (float("nan"), f"not mapped ({why})") for m in METRICS}
    springs = rec.optimum.springs
    patterns = d.map_pattern or robot_patterns(nom.robot, nom.gait)
    axes: list[dict[str, Sequence[float] | Sequence[str]]] = [
        {"period": d.map_period, "stride": d.map_stride},
        {"payload": d.map_payload, "mu": d.map_mu}]
    if patterns:  # a robot whose leg names do not say side and place has no named pattern
        axes.append({"slope": d.map_slope, "pattern": patterns})
    maps = tuple(robustness_map(nom.run, springs, a, mapper=nom.fork_map,
                                nominal=nom.prepared.motion) for a in axes)
    worst = {}
    for m in METRICS:
        s, c = min((mp.worst(m) for mp in maps),
                   key=lambda sc: np.inf if np.isnan(sc[0]) else sc[0])
        worst[m] = (s, c.label() if c is not None else "—")
    return maps, worst


__all__ = [
    "LOGGED_SKIP",
    "UNMAPPED",
    "Nominal",
    "envelope_and_fatigue",
    "family_candidates",
    "nominal",
    "pareto_front",
    "rank",
    "robustness_maps",
    "stop_tolerance",
]
