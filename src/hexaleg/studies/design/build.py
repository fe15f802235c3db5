"""``hexaleg design``: which springs to fit, where, what to buy, and how they hold up.

:func:`build_design` runs the stages of :mod:`hexaleg.studies.design.stages` for the robot and
its gait (:class:`~hexaleg.studies.design.config.DesignConfig`):

1. ``nominal``: the gait prepared once, the sprung classes, the design groups, the fit limits;
2. ``candidates``: every allowed family's globally optimal springs (the magnitudes the global
   optimum of one convex program, the geometry searched), groups whose marginal saving is under
   ``[design] min_group_saving`` left unfitted, each with its torsion springs and its saving net
   of their mass;
3. ``pareto``: the best family's optimum with the spring torque bounded to fractions of its peak;
4. ``ranking``: every family optimum and Pareto point simulated forward in MuJoCo under the
   servo the robot runs (``[design] controller``, :mod:`hexaleg.studies.design.ranking`); the
   recommendation is the best *simulated* buildable design net of its springs' mass, and one
   whose simulated saving is under half its prediction is flagged;
   then ``tolerance``: the recommendation designed for its worst saving over the stops' mounting
   error within ``[design] stop_tolerance`` (:func:`hexaleg.design.tolerance.tolerant_springs`),
   and ``envelope``: each part's stress over its joints' whole range, poses and a turn, the hard
   stop where it would yield, and its fatigue safety at ``[design] life_cycles``;
5. ``maps``: the recommendation frozen over period × stride, payload × μ and slope × gait
   pattern (a condition the robot cannot walk is a cell with its reason), their worst case;
6. ``robust``: the recommended geometry's magnitudes for a box of conditions, with its parts
   (neither 5 nor 6 is one of the spring rules: ``[design] robustness = false`` leaves both
   out, as ``hexaleg codesign`` does on the gait it chose);
7. ``proof``: the recommendation simulated under each controller a servo robot runs
   (:func:`hexaleg.simulation.sensitivity.controller_check`), the simulated saving beside the
   predicted one.

Where no design saves energy net of its springs' mass the result says so (``pays`` false and
"no springs pay" in the summary), never a recommendation that costs energy. The result is a
frozen :class:`DesignResult`; :mod:`hexaleg.studies.design.data` turns it into ``design.json``,
:mod:`hexaleg.studies.design.write` writes the files.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from hexaleg.checks import typed
from hexaleg.design.envelope import PartEnvelope
from hexaleg.design.fatigue import FatigueCheck
from hexaleg.design.robustness_map import RobustnessMap
from hexaleg.design.spring_parts import SpringPart
from hexaleg.design.tolerance import TolerantSprings
from hexaleg.dynamics.plausibility import Plausibility, check_cost_of_transport, uses_generic
from hexaleg.errors import HexalegError
from hexaleg.motion.params import GaitParams
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.mirror import mirror
from hexaleg.simulation.sensitivity import controller_check
from hexaleg.studies.design.candidates import Candidate
from hexaleg.studies.design.config import DesignConfig
from hexaleg.studies.design.ranking import Simulated, best_simulated, simulate_candidates
from hexaleg.studies.design.stages import (
    LOGGED_SKIP,
    UNMAPPED,
    Nominal,
    RobustResult,
    envelope_and_fatigue,
    family_candidates,
    nominal,
    pareto_front,
    rank,
    robust_design,
    robustness_maps,
    stop_tolerance,
)

MIN_SAVING = 1e-4
"""A recommendation must save more than this fraction of the ranking metric (0.01 %) net of its
springs' mass to pay; below it the design says that no springs pay."""


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
        ranking: Every ranked design simulated under ``[design] controller``
            (:mod:`~hexaleg.studies.design.ranking`), in the order ranked.
        tolerance: The recommendation against its tolerance-blind self over the stops'
            mounting error (:class:`~hexaleg.design.tolerance.TolerantSprings`), or None.
        envelope: Each bought part over its whole envelope, and the hard stop it needs.
        fatigue: Each bought part and its fatigue check at ``[design] life_cycles``.
        simulation: The recommendation simulated, one row per controller
            (:func:`~hexaleg.simulation.sensitivity.controller_check`); empty when the
            simulation could not run (a note says why).
        timings: Step → wall time, s. notes: What the user should know.
        plausibility: The baseline's electrical cost of transport against the plausible band
            for the robot's mass (:func:`~hexaleg.dynamics.plausibility.check_cost_of_transport`),
            or None when the gait does not travel.
        motion: The logged motion designed on (``--motion``), None on a generated gait.
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
    ranking: tuple[Simulated, ...]
    tolerance: TolerantSprings | None
    envelope: tuple[PartEnvelope, ...]
    fatigue: tuple[tuple[SpringPart, FatigueCheck], ...]
    simulation: tuple[dict[str, Any], ...]
    timings: dict[str, float]
    notes: tuple[str, ...]
    plausibility: Plausibility | None = None
    motion: Motion | None = None

    @property
    def pays(self) -> bool:
        """Whether the recommended springs save energy net of their own mass."""
        return bool(self.recommended.net[self.config.design.metric] > MIN_SAVING)

    def summary(self) -> str:
        """One line: the recommendation and its saving."""
        r, m = self.recommended, self.config.design.metric
        head = "fit" if self.pays else "no springs pay here; the best would be"
        line = (f"{head} {r.label} springs on {', '.join(r.optimum.groups)}: {m} saving "
                f"{100 * r.row[f'saving.{m}']:+.2f} % ({100 * r.net[m]:+.2f} % net "
                f"of {1e3 * r.spring_mass:.1f} g of springs); " + (
                    f"worst case over the maps {100 * self.worst[m][0]:+.2f} % at "
                    f"{self.worst[m][1]}" if self.maps else "no robustness maps ("
                    + ("logged motion" if self.config.motion is not None else "left out") + ")"))
        simulated = [f"{row['label']} {100 * row['simulated']:+.2f} %"
                     if row["simulated"] is not None else f"{row['label']}: {row['verdict']}"
                     for row in self.simulation]
        if simulated:
            line += (f"; simulated electrical saving {', '.join(simulated)} (predicted "
                     f"{100 * self.simulation[0]['predicted']:+.2f} %)")
        if self.plausibility is not None and not self.plausibility.plausible:
            line += f"; WARNING baseline energy {self.plausibility.message}"
        return line


@typed
def build_design(config: DesignConfig | None = None,
                 progress: Callable[[str], None] | None = None) -> DesignResult:
    """Compute the design answer (module docstring): the stages in order, each timed.

    Args:
        config: The configuration (default: the built-in robot, its gait, the defaults).
        progress: Called with one status line per stage.

    Raises:
        InvalidParameterError: a robust box with corners
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

    nom = nominal(cfg)
    step("prepare", f"{nom.robot.name}: gait of {nom.gait.samples} samples prepared")
    ranked = family_candidates(nom, step)
    pareto = pareto_front(nom, next((c for c in ranked if c.buildable), ranked[0]))
    step("pareto", f"Pareto front of {pareto[-1][1].family} ({len(pareto)} points)")
    pool = sorted([*ranked, *(c for _, c in pareto[:-1])], key=lambda c: -rank(c, d.metric))
    rows, rec, notes = _ranking(nom, pool)
    step("ranking", f"{len(rows)} designs simulated under the {d.controller} servo: "
         f"recommended {rec.label}")
    rec, tolerance = stop_tolerance(nom, rec)
    if tolerance is not None:
        step("tolerance", f"stops within ±{math.degrees(d.stop_tolerance):g}°: worst {d.metric} "
             f"saving {100 * tolerance.worst['tolerant']:+.2f} % (tolerance-blind design "
             f"{100 * tolerance.worst['blind']:+.2f} %)")
    envelope, fatigue, envelope_notes = envelope_and_fatigue(nom, rec)
    step("envelope", f"{len(envelope)} parts checked over their whole envelope and for fatigue "
         f"at {d.life_cycles:.3g} cycles")
    maps, worst = robustness_maps(nom, rec)
    step("maps", f"robustness maps: worst {d.metric} saving {100 * worst[d.metric][0]:+.2f} %"
         if maps else "robustness maps and robust design left out: "
         + ("a logged motion" if nom.motion is not None else "[design] robustness = false"))
    robust = robust_design(nom, rec)
    stalled = [] if robust is None or not robust.design.solver.get("stopped") else [
        f"robust design: its bundle method's {robust.design.solver['stopped']} (predicted "
        f"decrease left {robust.design.solver['gap']:.3g} of the baseline's energy)"]
    step("robust", "robust design over the box of conditions" if robust is not None
         else "no robust design")
    simulation, unsimulated = _proof(nom, rec)
    step("simulate", "the recommendation simulated in MuJoCo under both controllers")
    pays = [] if rec.net[d.metric] > MIN_SAVING else [
        f"no springs pay: the best design saves {100 * rec.row[f'saving.{d.metric}']:+.2f} % "
        f"of {d.metric} and {100 * rec.net[d.metric]:+.2f} % net of its springs' mass — fitting "
        "springs does not pay on this robot and gait"]
    mirrored = mirror(nom.robot)
    plausible = _plausibility(nom)
    flagged = () if plausible is None else (f"baseline energy {plausible.message}",)
    logged = ([LOGGED_SKIP] if nom.motion is not None
              else [] if d.robustness else [UNMAPPED])
    notes = [*flagged, *pays, *logged, *notes, *envelope_notes, *stalled, *unsimulated,
             *nom.robot.notes,
             *rec.notes,
             (mirrored.summary() + ("; each gets its group's spring mirrored" if d.mirror
                                    and mirrored.mirrored else "")), *mirrored.notes,
             f"designed at {nom.gait.samples} samples per cycle (Joule-optimal forces); ranked "
             f"by the {d.metric} saving net of the springs' mass, simulated under the "
             f"{d.controller} servo"]
    return DesignResult(
        config=cfg, robot=nom.robot.name, title=nom.desc.title, mass=nom.robot.mass,
        actuator=nom.run.actuator().name, gait=nom.gait, baseline=nom.baseline,
        candidates=tuple(ranked), recommended=rec, outer=nom.outer, pareto=tuple(pareto),
        maps=maps, worst=worst, robust=robust, ranking=tuple(rows), tolerance=tolerance,
        envelope=envelope, fatigue=fatigue, simulation=simulation,
        timings=timings, notes=tuple(notes), plausibility=plausible, motion=nom.motion)


def _plausibility(nom: Nominal) -> Plausibility | None:
    """The nominal gait's electrical cost of transport without springs against the plausible
    band for the robot's mass (None for a gait in place)."""
    cot = nom.prepared.baseline("joule").get("cost_of_transport", {}).get("electrical")
    if cot is None:
        return None
    return check_cost_of_transport(cot, nom.robot.mass, generic=uses_generic(nom.run.actuator()))


def _ranking(nom: Nominal, pool: list[Candidate]
             ) -> tuple[list[Simulated], Candidate, list[str]]:
    """The pool simulated under the design's controller and the recommendation: the best
    simulated buildable design, or — when none walked — the best predicted one, with a note."""
    d = nom.config.design
    rows = simulate_candidates(nom.prepared, pool, d.controller, d.metric)
    best = best_simulated(rows)
    notes = [f"{r.candidate.label}: simulated under the {r.controller} servo it saves "
             + (f"{100 * r.simulated:+.2f} % against {100 * r.predicted:+.2f} % predicted — "
                "under half the prediction" if r.simulated is not None
                else f"nothing: {r.verdict}")
             for r in rows if r.flagged and r.predicted > 0]
    if best is not None:
        return rows, best.candidate, notes
    rec = next((c for c in pool if c.buildable), pool[0])
    return rows, rec, [*notes, f"no buildable design walked under the {d.controller} servo: "
                       "the recommendation is the best predicted one"]


def _proof(nom: Nominal, rec: Candidate) -> tuple[tuple[dict[str, Any], ...], list[str]]:
    """The recommendation's controller check, or no rows and a note saying why it could not
    run."""
    try:
        return tuple(controller_check(nom.prepared, rec.optimum.springs, "joule")), []
    except HexalegError as e:
        return (), [f"the recommendation could not be simulated: {type(e).__name__}: {e}"]


__all__ = ["DesignResult", "RobustResult", "build_design"]
