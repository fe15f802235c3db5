"""``hexaleg design``: which springs to fit, where, what to buy, and how they hold up.

:func:`build_design` runs, for the robot and its gait (:class:`~hexaleg.studies.design.config.
DesignConfig`):

1. every allowed family's globally optimal springs on the sprung classes
   (:mod:`hexaleg.studies.design.candidates`: the magnitudes the global optimum of one convex
   program, the geometry searched), each with its torsion springs and its saving net of their
   mass, ranked by the net saving of the ranking metric (default ``electrical``, the energy the
   servos draw); the best buildable one is recommended;
2. the Pareto front of the recommended family: the optimum with the spring torque bounded to
   fractions of the recommended design's peak (a constrained optimum may find a geometry the
   unconstrained search missed: the recommended design is then searched again from it, so it
   never saves less than a point of its own front);
3. robustness maps of the recommended design frozen (:mod:`hexaleg.design.robustness_map`):
   period × stride and payload × μ, and their worst case;
4. the robust design: the recommended geometry's magnitudes for the box of conditions
   (:func:`hexaleg.design.robust.robust_springs`: its corners and the nominal gait, one convex
   program), with its own parts;
5. the proof: the recommended springs on the nominal gait simulated forward in MuJoCo, with and
   without them, under each controller a servo robot runs
   (:func:`hexaleg.simulation.sensitivity.controller_check`: feedforward + PD and position
   only), the simulated saving beside the predicted one. Gross savings on both sides: the
   simulated robot does not carry the springs' mass either.

The result is a frozen :class:`DesignResult`; :mod:`hexaleg.studies.design.data` turns it into
``design.json``, :mod:`hexaleg.studies.design.write` writes the files.
"""

from __future__ import annotations

import dataclasses
import itertools
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.design.evaluator import RunSpec
from hexaleg.design.families import Geometry
from hexaleg.design.robust import RobustSprings, robust_springs
from hexaleg.design.robustness import Condition, condition_prepared, condition_savings
from hexaleg.design.robustness_map import RobustnessMap, robustness_map
from hexaleg.design.spring_parts import spring_outer_diameter
from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import (
    HexalegError,
    InfeasibleForcesError,
    InvalidParameterError,
    TorqueLimitError,
)
from hexaleg.motion.params import GaitParams
from hexaleg.simulation.sensitivity import controller_check
from hexaleg.studies.design.candidates import Candidate, candidate, design_family
from hexaleg.studies.design.config import METRICS, DesignConfig
from hexaleg.studies.design.groups import class_of, design_groups, sprung_classes

MIN_SAVING = 1e-4
"""A recommendation must save more than this fraction of the ranking metric (0.01 %); below it,
the limits leave nothing worth fitting and ``hexaleg design`` says which to change."""


@dataclass(frozen=True, eq=False)
class RobustResult:
    """The robust design and both designs over the box of conditions.

    Attributes:
        conditions: The nominal gait and the box's corners.
        design: The robust program's result (savings per condition in its metric).
        candidate: The robust magnitudes as a design on the nominal gait, with its parts.
        savings: Metric (:data:`~hexaleg.studies.design.config.METRICS`) →
            ``{"robust": (n,), "nominal": (n,)}`` savings per condition.
    """

    conditions: tuple[Condition, ...]
    design: RobustSprings
    candidate: Candidate
    savings: dict[str, dict[str, np.ndarray]]

    def worst(self, metric: str, design: str = "robust") -> float:
        """The worst saving of ``design`` (robust or nominal) over the conditions."""
        return float(np.min(self.savings[metric][design]))


@dataclass(frozen=True, eq=False)
class DesignResult:
    """Everything ``hexaleg design`` found (module docstring).

    Attributes:
        config: The configuration. robot: Its name. title: Its title. mass: kg.
        actuator: The actuator's name. gait: The nominal gait.
        baseline: Metric totals of the nominal gait without springs (J or N·m).
        candidates: One per family, ranked (best first). recommended: The recommendation: the
            best buildable design of the families and the Pareto points.
        outer: Group → (largest spring outer diameter, m; where it comes from).
        pareto: The recommended family's optimum with the spring torque bounded to fractions of
            the unbounded design's peak (fraction, the candidate), ascending; the last point,
            fraction 1, is the unbounded design itself.
        maps: The robustness maps. worst: Metric → (worst saving over the maps, its
            condition's label).
        robust: The robust design, or None when the box is the nominal gait alone.
        simulation: The recommendation simulated, one row per controller
            (:func:`~hexaleg.simulation.sensitivity.controller_check`); empty when the
            simulation could not run (a note says why).
        timings: Step → wall time, s. notes: What the user should know.
    """

    config: DesignConfig
    robot: str
    title: str
    mass: float
    actuator: str
    gait: GaitParams
    baseline: dict[str, float]
    candidates: tuple[Candidate, ...]
    recommended: Candidate
    outer: dict[str, tuple[float, str]]
    pareto: tuple[tuple[float, Candidate], ...]
    maps: tuple[RobustnessMap, ...]
    worst: dict[str, tuple[float, str]]
    robust: RobustResult | None
    simulation: tuple[dict[str, Any], ...]
    timings: dict[str, float]
    notes: tuple[str, ...]

    @property
    def pays(self) -> bool:
        """Whether the recommended springs save energy net of their own mass."""
        return bool(self.recommended.net[self.config.design.metric] > 0)

    def summary(self) -> str:
        """One line: the recommendation and its saving."""
        r, m = self.recommended, self.config.design.metric
        head = "fit" if self.pays else "no spring pays for its mass here; the best,"
        line = (f"{head} {r.label} springs on {', '.join(r.optimum.groups)}: {m} saving "
                f"{100 * r.row[f'saving.{m}']:+.2f} % ({100 * r.net[m]:+.2f} % net "
                f"of {1e3 * r.spring_mass:.1f} g of springs); worst case over the maps "
                f"{100 * self.worst[m][0]:+.2f} % at {self.worst[m][1]}")
        simulated = [f"{row['label']} {100 * row['simulated']:+.2f} %"
                     if row["simulated"] is not None else f"{row['label']}: {row['verdict']}"
                     for row in self.simulation]
        if simulated:
            line += (f"; simulated electrical saving {', '.join(simulated)} (predicted "
                     f"{100 * self.simulation[0]['predicted']:+.2f} %)")
        return line


def _rank(c: Candidate, metric: str) -> float:
    value = c.net[metric]
    return float(value) if np.isfinite(value) else -np.inf


def _class_geometry(c: Candidate, class_groups: dict[str, tuple[str, ...]]
                    ) -> dict[str, Geometry]:
    """Class → the geometry of ``c`` (finer groups share their class's)."""
    out: dict[str, Geometry] = {}
    for g, js in c.optimum.groups.items():
        owner = next(k for k, cj in class_groups.items() if js[0] in cj)
        out.setdefault(owner, c.optimum.geometry[g])
    return out


def _corners(cfg: DesignConfig) -> tuple[Condition, ...]:
    d = cfg.design
    boxes = [sorted(set(b)) for b in (d.robust_period, d.robust_stride, d.robust_payload,
                                      d.robust_mu)]
    out = [Condition()]
    for p, s, w, mu in itertools.product(*boxes):
        c = Condition(period=p, stride=s, payload=w, mu=mu)
        if c not in out:
            out.append(c)
    return tuple(out)


def _robust(cfg: DesignConfig, run: RunSpec, gait: GaitParams, prepared: Prepared,
            rec: Candidate, outer: dict[str, float]) -> RobustResult | None:
    """The robust design over the box's corners and the nominal gait (module docstring)."""
    conditions = _corners(cfg)
    if len(conditions) == 1:
        return None
    preps = [condition_prepared(run, gait, c) for c in conditions]
    for c, p in zip(conditions, preps, strict=True):
        try:
            p.baseline("joule")
        except (InfeasibleForcesError, TorqueLimitError) as e:
            raise InvalidParameterError(
                "design robust box corner", c.label(),
                f"corners where the robot has admissible forces without springs ({e}); narrow "
                "the robust_* ranges") from e
    d = cfg.design
    design = robust_springs(rec.optimum, prepared, preps, d.robust_mode, d.metric,
                            max_torque=d.max_torque, max_deflection=d.deflection_bound)
    analysis = prepared.evaluate(design.springs, "joule")
    value = float(analysis.metrics["total"]["joule"])
    optimum = dataclasses.replace(
        rec.optimum, magnitudes=design.magnitudes, springs=design.springs, analysis=analysis,
        value=value, saving=float(design.saving[0]), notes=(), solver=design.solver)
    rows = {name: [condition_savings(p, s, "joule") for p in preps]
            for name, s in (("robust", design.springs), ("nominal", rec.optimum.springs))}
    savings = {m: {name: np.array([r[f"saving.{m}"] if r["status"] == "ok" else -np.inf
                                   for r in rs]) for name, rs in rows.items()}
               for m in METRICS}
    return RobustResult(conditions=conditions, design=design,
                        candidate=candidate(optimum, prepared, run, gait, outer, cfg.design),
                        savings=savings)


def build_design(config: DesignConfig | None = None,
                 progress: Callable[[str], None] | None = None) -> DesignResult:
    """Compute the design answer (module docstring).

    Args:
        config: The configuration (default: the built-in robot, its gait, the defaults).
        progress: Called with one status line per step.

    Returns:
        The result.

    Raises:
        InvalidParameterError: limits under which no spring saves anything (names them and
            what to change), a map range whose gait is unreachable, a robust box with corners
            where the robot has no admissible forces, an outer diameter no wire fits.
        UnknownNameError: an unknown robot, class, family, material or motor.
    """
    cfg = config or DesignConfig()
    d = cfg.design
    say = progress or (lambda _msg: None)
    timings: dict[str, float] = {}
    t0 = last = time.perf_counter()

    def step(name: str, msg: str) -> None:
        nonlocal last
        now = time.perf_counter()
        timings[name] = now - last
        last = now
        say(f"{msg} ({now - t0:.1f} s)")

    run = d.run(cfg.robot, cfg.contact)
    robot, desc, gait = run.load(), run.description(), cfg.nominal_gait
    prepared = condition_prepared(run, gait, Condition())
    baseline = {k: float(v) for k, v in prepared.baseline("joule")["total"].items()}
    classes = sprung_classes(robot, d.classes)
    class_groups = design_groups(robot, classes, "class")
    groups = design_groups(robot, classes, d.grouping)
    outer_src = {}
    for g, js in groups.items():
        kind = class_of(robot, js)
        outer_src[g] = ((float(d.max_outer_diameter[kind]), "[design] max_outer_diameter")
                        if kind in d.max_outer_diameter else spring_outer_diameter(desc, robot,
                                                                                   kind))
    outer = {g: v for g, (v, _) in outer_src.items()}
    step("prepare", f"{robot.name}: gait of {gait.samples} samples prepared")
    cands = []
    for fam in d.families:
        cands.append(design_family(prepared, run, gait, groups, class_groups, fam, d, outer))
        step(f"family {fam}", f"{fam}: {d.metric} saving "
             f"{100 * cands[-1].row[f'saving.{d.metric}']:+.2f} %")
    ranked = sorted(cands, key=lambda c: -_rank(c, d.metric))
    rec = next((c for c in ranked if c.buildable), ranked[0])
    peak = float(np.abs(rec.optimum.analysis.tau_spring).max())
    pareto = []
    for f in sorted(d.pareto_fractions):
        bounded = dataclasses.replace(d, max_torque=min(f * peak, d.max_torque or np.inf))
        pareto.append((f, design_family(prepared, run, gait, groups, class_groups, rec.family,
                                        bounded, outer, [_class_geometry(rec, class_groups)])))
    best_point = max((c for _, c in pareto), key=lambda c: c.optimum.saving, default=None)
    if best_point is not None and best_point.optimum.saving > rec.optimum.saving:
        # a bounded optimum beat the unbounded one in the program's own objective: the geometry
        # search missed it, so search again from both
        again = design_family(prepared, run, gait, groups, class_groups, rec.family, d, outer,
                              [_class_geometry(c, class_groups) for c in (rec, best_point)])
        if again.optimum.saving > rec.optimum.saving:
            cands = [again if c is rec else c for c in cands]
            ranked = sorted(cands, key=lambda c: -_rank(c, d.metric))
    # the recommendation: the best buildable design evaluated, Pareto points included (a
    # smaller spring may save more of the ranking metric than the Joule-optimal one)
    unbounded = next(c for c in ranked if c.family == rec.family)
    pareto.append((1.0, unbounded))
    pool = sorted([*ranked, *(c for _, c in pareto)], key=lambda c: -_rank(c, d.metric))
    rec = next((c for c in pool if c.buildable), pool[0])
    step("pareto", f"Pareto front of {rec.family} ({len(pareto)} points)")
    if not rec.row[f"saving.{d.metric}"] > MIN_SAVING:
        raise InvalidParameterError(
            "design limits", {"max_torque": d.max_torque, "max_deflection": d.max_deflection,
                              "classes": classes, "families": d.families},
            f"limits under which some spring saves {d.metric}: none of the families saves any; "
            "raise max_torque or max_deflection, or allow more classes or families")
    maps = (robustness_map(run, gait, rec.optimum.springs,
                           {"period": d.map_period, "stride": d.map_stride}),
            robustness_map(run, gait, rec.optimum.springs,
                           {"payload": d.map_payload, "mu": d.map_mu}))
    worst = {}
    for m in METRICS:
        s, c = min((mp.worst(m) for mp in maps),
                   key=lambda sc: np.inf if np.isnan(sc[0]) else sc[0])
        worst[m] = (s, c.label() if c is not None else "—")
    step("maps", f"robustness maps: worst {d.metric} saving {100 * worst[d.metric][0]:+.2f} %")
    robust = _robust(cfg, run, gait, prepared, rec, outer)
    step("robust", "robust design over the box of conditions")
    simulation, unsimulated = _simulate(prepared, rec)
    step("simulate", "the recommendation simulated in MuJoCo under both controllers")
    pays = [] if rec.net[d.metric] > 0 else [
        f"no design saves {d.metric} energy net of its springs' mass: the best saves "
        f"{100 * rec.row[f'saving.{d.metric}']:+.2f} % but {100 * rec.net[d.metric]:+.2f} % "
        "net — fitting springs does not pay on this robot and gait"]
    notes = [*pays, *unsimulated, *robot.notes, *rec.notes,
             "gait slope and the other gait patterns are not conditions of the maps yet: the "
             "gait generator walks level tripod-type gaits only",
             f"designed at {gait.samples} samples per cycle (Joule-optimal forces); ranked by "
             f"the {d.metric} saving net of the springs' mass"]
    return DesignResult(
        config=cfg, robot=robot.name, title=desc.title, mass=robot.mass,
        actuator=run.actuator().name, gait=gait, baseline=baseline, candidates=tuple(ranked),
        recommended=rec, outer=outer_src, pareto=tuple(pareto), maps=maps, worst=worst,
        robust=robust, simulation=simulation, timings=timings, notes=tuple(notes))


def _simulate(prepared: Prepared, rec: Candidate) -> tuple[tuple[dict[str, Any], ...], list[str]]:
    """The recommendation's controller check, or no rows and a note saying why it could not
    run."""
    try:
        return tuple(controller_check(prepared, rec.optimum.springs, "joule")), []
    except HexalegError as e:
        return (), [f"the recommendation could not be simulated: {type(e).__name__}: {e}"]


__all__ = ["DesignResult", "RobustResult", "build_design"]
