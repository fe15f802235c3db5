"""The spring design as a chain of stages over one run: :class:`DesignChain`.

Modelled on pvlib's ``ModelChain``: the orchestrator lives in the library, each stage is a
method that can be called on its own (it runs the stages it needs first, once), and
:meth:`DesignChain.run` runs a subset and returns one :class:`~hexaleg.design.chain.result.
DesignResult`. The stages, in order (:data:`STAGES`; the work of each is in
:mod:`hexaleg.design.chain.stages`):

1. ``candidates``: the nominal gait prepared once (:meth:`DesignChain.nominal`), every allowed
   family's globally optimal springs (the magnitudes the global optimum of one convex program,
   the geometry searched), groups whose marginal saving is under ``[design] min_group_saving``
   left unfitted, each with its torsion springs and its saving net of their mass;
2. ``pareto``: the front family's optimum with the spring torque bounded to fractions of its
   peak; the front family is the one whose optimum simulates best under the servo (net of its
   springs' mass, the worse controller's: the ranking's figure), or, without the ranking, the
   best predicted buildable one;
3. ``ranking``: every family optimum and Pareto point simulated forward in MuJoCo under the
   servo the robot runs (``[design] controller``, :mod:`hexaleg.design.chain.ranking`; by
   default under both controllers, each design judged by the worse); the recommendation is the
   best *simulated* buildable design net of its springs' mass (without this stage: the best
   predicted one);
4. ``tolerance``: the recommendation designed for its worst saving over the stops' mounting
   error within ``[design] stop_tolerance``
   (:func:`hexaleg.design.search.tolerance.tolerant_springs`);
5. ``envelope``: each part's stress over its joints' whole range, poses and a turn, the hard
   stop where it would yield, and its fatigue safety at ``[design] life_cycles``;
6. ``fold``: the fold into the sphere and back with the recommendation and without
   (:mod:`hexaleg.design.fold`): energy, torque, the walking after which the springs pay for a
   fold, the ``[mission]`` saving; a robot without both poses has none;
7. ``maps``: the recommendation frozen over period × stride, payload × μ and slope × gait
   pattern, their worst case;
8. ``robust``: the recommended geometry's magnitudes for a box of conditions, with its parts
   (neither 7 nor 8 is one of the spring rules: ``[design] robustness = false`` leaves both
   out, as ``hexaleg codesign`` does on the gait it chose);
9. ``proof``: the recommendation simulated under each controller a servo robot runs
   (:func:`hexaleg.simulation.sensitivity.controller_check`).

Where no design saves energy net of its springs' mass the result says so (``pays`` false and
"no springs pay" in the summary), never a recommendation that costs energy.

A new spring family is one module in :mod:`hexaleg.robot.springs` (its law) and one entry in
:data:`hexaleg.design.families.FAMILIES` (its design rows); the chain runs it as it runs the
others.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any

from hexaleg.design.chain.candidates import Candidate
from hexaleg.design.chain.checkpoint import StageFiles, run_key
from hexaleg.design.chain.config import DesignParams, design_params, design_run
from hexaleg.design.chain.config import mission as mission_of
from hexaleg.design.chain.failure import STAGE_KEYS, StageFailure
from hexaleg.design.chain.ranking import Simulated, best_simulated, simulate_candidates, under
from hexaleg.design.chain.result import MIN_SAVING, DesignResult
from hexaleg.design.chain.robust_stage import RobustResult, robust_design
from hexaleg.design.chain.stages import (
    LOGGED_SKIP,
    UNMAPPED,
    Nominal,
    envelope_and_fatigue,
    family_candidates,
    nominal,
    pareto_front,
    per_joint_evidence,
    rank,
    robustness_maps,
    stop_tolerance,
)
from hexaleg.design.fold import Fold, Mission, fold
from hexaleg.design.robust.maps import RobustnessMap
from hexaleg.design.search.tolerance import TolerantSprings
from hexaleg.design.springs.envelope import PartEnvelope
from hexaleg.design.springs.fatigue import FatigueCheck
from hexaleg.design.springs.parts import SpringPart
from hexaleg.dynamics.draw import WholeDraw, whole_draw
from hexaleg.dynamics.plausibility import check_baseline
from hexaleg.dynamics.without_constants import WithoutConstants, without_constants
from hexaleg.errors import HexalegError, InvalidParameterError, UnknownNameError
from hexaleg.robot.mirror import mirror
from hexaleg.robot.springs import SpringSet
from hexaleg.scenario.scenario import Scenario
from hexaleg.simulation.controllers import controllers_of
from hexaleg.simulation.sensitivity import controller_check

STAGES: tuple[str, ...] = ("candidates", "pareto", "ranking", "tolerance", "envelope", "fold",
                           "maps", "robust", "proof")
"""The stages of :class:`DesignChain`, in order (module docstring)."""


class DesignChain:
    """The spring design of one run, stage by stage (module docstring).

    Each stage method computes its stage once (and the stages it needs before it) and returns
    it; :meth:`run` returns the :class:`~hexaleg.design.chain.result.DesignResult`.

    Args:
        scenario: The run (:class:`~hexaleg.scenario.scenario.Scenario`: its ``[design]`` table
            the design's settings, its ``[mission]`` the fold's); default: the built-in robot,
            its gait, the defaults.
        progress: Called with one status line per stage.
        design: The design's settings in place of the scenario's ``[design]`` table.
        controller: The servo the robot runs over ``[design] controller`` (``--controller``).
        mission: The mission in place of the scenario's ``[mission]`` table.
        files: A folder where each finished stage is kept as it goes, and read back from
            when the same run was killed or failed there before
            (:class:`~hexaleg.design.chain.checkpoint.StageFiles`); None: nothing kept.

    Attributes:
        scenario: The run the design works on (:func:`~hexaleg.design.chain.config.design_run`: at
            ``[design] samples``, Joule-optimal forces). design: The ``[design]`` settings.
        mission: The ``[mission]`` table. files: The kept stages, or None.
        failed: The stage after the candidates that failed in :meth:`run`, or None.

    Example:
        ``DesignChain(scenario).run(stages=("candidates",))`` is the family optima alone, the
        recommendation the best predicted buildable one (the report's quick answer).
    """

    def __init__(self, scenario: Scenario | None = None,
                 progress: Callable[[str], None] | None = None, *,
                 design: DesignParams | None = None, controller: str | None = None,
                 mission: Mission | None = None, files: str | Path | None = None) -> None:
        if scenario is not None and not isinstance(scenario, Scenario):
            raise InvalidParameterError("scenario", type(scenario).__name__,
                                        "a hexaleg.Scenario (Scenario.load(robot, config))")
        scenario = scenario or Scenario.load()
        self.design = design_params(scenario, controller, design=design)
        self.scenario = design_run(scenario, self.design)
        self.mission = mission if mission is not None else mission_of(scenario)
        self._say = progress or (lambda _msg: None)
        self._done: dict[str, Any] = {}
        self._wanted: tuple[str, ...] = STAGES  # what run() asked for; a stage alone: all
        self.files = None if files is None else StageFiles(
            files, run_key(scenario, self.design, self.mission))
        self.failed: StageFailure | None = None
        self.timings: dict[str, float] = {}
        self._said: list[tuple[str, str]] = []  # (timing name, line) of each step, in order
        self._t0 = self._last = time.perf_counter()

    def _step(self, name: str, msg: str) -> None:
        now = time.perf_counter()
        self.timings[name] = now - self._last
        self._last = now
        self._said.append((name, msg))
        self._say(f"{msg} ({now - self._t0:.1f} s)")

    def _shared(self) -> dict[str, object]:
        """The objects a kept stage refers to: this run's robot (by its content) and the
        prepared nominal gait (by name) (:mod:`hexaleg.design.chain.checkpoint`)."""
        nom = self.nominal()
        return {"robot": nom.robot, "nominal": nom, "prepared": nom.prepared, "run": nom.run,
                "scenario": self.scenario, "design": self.design}

    def _once(self, name: str, compute: Callable[[], Any]) -> Any:
        if name in self._done:
            return self._done[name]
        files = self.files if name in STAGES else None
        kept = None if files is None else files.load(name, self._shared())
        if kept is not None:  # this run's stage, kept by its earlier process
            value, timings, said = kept
            self.timings.update(timings)
            for _, line in said:
                self._say(f"{line} (kept from the earlier run)")
            self._last = time.perf_counter()
        else:
            first, before = len(self._said), dict(self.timings)
            value = compute()
            if files is not None:
                said = self._said[first:]
                files.save(name, (value, {k: v for k, v in self.timings.items()
                                          if before.get(k) != v}, said), self._shared())
        self._done[name] = value
        return value

    def nominal(self) -> Nominal:
        """The nominal gait prepared once, the sprung classes, the groups, the fit limits."""
        def compute() -> Nominal:
            nom = nominal(self.scenario, self.design)
            self._step("prepare", f"{nom.robot.name}: gait of {nom.gait.samples} samples "
                       "prepared")
            return nom
        return self._once("nominal", compute)

    def candidates(self) -> tuple[Candidate, ...]:
        """Every allowed family's candidate, ranked by predicted net saving (best first)."""
        return self._candidates()[0]

    def _candidates(self) -> tuple[tuple[Candidate, ...], tuple[str, ...]]:
        """The candidates and the notes of the families whose program failed."""
        def compute() -> tuple[tuple[Candidate, ...], tuple[str, ...]]:
            cands, left_out = family_candidates(self.nominal(), self._step)
            return tuple(cands), tuple(left_out)
        return self._once("candidates", compute)

    def pareto(self) -> tuple[tuple[float, Candidate], ...]:
        """The front family's optimum with its spring torque bounded, ascending; the last point
        (fraction 1) is the unbounded design itself. The front family is the one whose optimum
        the ranking would recommend among the family optima (:meth:`_optima`: the best
        simulated net saving under the worse controller, the figure the recommendation is
        chosen by); without the ranking stage, or where no buildable optimum walked, the best
        predicted buildable one. (By the prediction alone the front's family flipped between
        two families whose predicted net savings were close on a motion moved by a hair:
        docs/optimal.md, "Starts above the search box".)"""
        def compute() -> tuple[tuple[float, Candidate], ...]:
            ranked = self.candidates()
            walked = best_simulated(self._optima()) if "ranking" in self._wanted else None
            family = (walked.candidate if walked is not None else
                      next((c for c in ranked if c.buildable), ranked[0]))
            front = pareto_front(self.nominal(), family)
            self._step("pareto", f"Pareto front of {front[-1][1].family} ({len(front)} points)")
            return tuple(front)
        return self._once("pareto", compute)

    def _optima(self) -> tuple[Simulated, ...]:
        """The family optima simulated under the design's servo (the ranking's first rows, in
        its order: :func:`~hexaleg.design.chain.ranking.simulate_candidates`)."""
        def compute() -> tuple[Simulated, ...]:
            d = self.design
            pool = sorted(self.candidates(), key=lambda c: -rank(c, d.metric))
            return tuple(simulate_candidates(self.nominal().prepared, pool, d.controller,
                                             d.metric))
        return self._once("optima", compute)

    def ranking(self) -> tuple[tuple[Simulated, ...], Candidate, tuple[str, ...]]:
        """The family optima and Pareto points simulated under the design's servo, the
        recommendation (the best simulated buildable design; when none walked, the best
        predicted one) and the notes of the ranking."""
        def compute() -> tuple[tuple[Simulated, ...], Candidate, tuple[str, ...]]:
            d = self.design
            points = [c for _, c in self.pareto()[:-1]]
            pool = sorted([*self.candidates(), *points], key=lambda c: -rank(c, d.metric))
            each = {(id(r.candidate), r.controller): r for r in (
                *self._optima(), *simulate_candidates(self.nominal().prepared, points,
                                                      d.controller, d.metric))}
            rows = [each[(id(c), k)] for k in controllers_of(d.controller)
                    for c in pool]  # as simulate_candidates orders them: controller, pool
            notes = [f"{r.candidate.label}: simulated under the {r.controller} servo it saves "
                     + (f"{100 * r.simulated:+.2f} % against {100 * r.predicted:+.2f} % "
                        "predicted — under half the prediction" if r.simulated is not None
                        else f"nothing: {r.verdict}")
                     for r in rows if r.flagged and r.predicted > 0]
            best = best_simulated(rows)
            if best is not None:
                rec = best.candidate
            else:
                rec = next((c for c in pool if c.buildable), pool[0])
                notes.append(f"no buildable design walked under {under(d.controller)}: the "
                             "recommendation is the best predicted one")
            self._step("ranking", f"{len({id(r.candidate) for r in rows})} designs simulated "
                       f"under {under(d.controller)}: recommended {rec.label}")
            return tuple(rows), rec, tuple(notes)
        return self._once("ranking", compute)

    def _ranked(self) -> Candidate:
        """The recommendation before the stop tolerance: the ranking's when it ran (or runs),
        else the best predicted buildable family optimum."""
        if "ranking" in self._wanted:
            return self.ranking()[1]
        ranked = self.candidates()
        return next((c for c in ranked if c.buildable), ranked[0])

    def tolerance(self) -> tuple[Candidate, TolerantSprings | None]:
        """The recommendation designed for its stops' mounting error, and the comparison with
        its tolerance-blind self (None without a tolerance or angles)."""
        rec, tol, _ = self._tolerance()
        return rec, tol

    def _tolerance(self) -> tuple[Candidate, TolerantSprings | None, tuple[str, ...]]:
        """:meth:`tolerance` and why the stop-tolerance design failed, if it did."""
        def compute() -> tuple[Candidate, TolerantSprings | None, tuple[str, ...]]:
            d = self.design
            untolerant: tuple[str, ...] = ()
            try:
                rec, tol = stop_tolerance(self.nominal(), self._ranked())
            except HexalegError as err:  # a stage's failure does not end the design
                rec, tol = self._ranked(), None
                untolerant = (
                    f"the design for the stops' mounting error (±"
                    f"{math.degrees(d.stop_tolerance):g}°) failed ({err}): the tolerance-blind "
                    "design is recommended, its saving with stops mounted off not checked",)
                self._step("tolerance", "the stop-tolerance design failed: the tolerance-blind "
                           "design is kept (a note says why)")
            if tol is not None:
                self._step("tolerance", f"stops within ±{math.degrees(d.stop_tolerance):g}°: "
                           f"worst {d.metric} saving {100 * tol.worst['tolerant']:+.2f} % "
                           f"(tolerance-blind design {100 * tol.worst['blind']:+.2f} %)")
            return rec, tol, untolerant
        return self._once("tolerance", compute)

    def recommended(self) -> Candidate:
        """The recommendation: after the stop tolerance when it runs in this chain."""
        return self.tolerance()[0] if "tolerance" in self._wanted else self._ranked()

    def envelope(self) -> tuple[tuple[PartEnvelope, ...],
                                tuple[tuple[SpringPart, FatigueCheck], ...], tuple[str, ...]]:
        """Each bought part over its whole envelope with its hard stop, its fatigue check, and
        notes."""
        def compute() -> tuple[tuple[PartEnvelope, ...],
                               tuple[tuple[SpringPart, FatigueCheck], ...], tuple[str, ...]]:
            env, fatigue, notes = envelope_and_fatigue(self.nominal(), self.recommended())
            self._step("envelope", f"{len(env)} parts checked over their whole envelope and "
                       f"for fatigue at {self.design.life_cycles:,.0f} cycles")
            return env, fatigue, tuple(notes)
        return self._once("envelope", compute)

    def fold(self) -> Fold | None:
        """The fold into the sphere and back with the recommendation and without; None for a
        robot without a stand and a sphere pose, or a logged motion that does not travel."""
        def compute() -> Fold | None:
            nom, rec = self.nominal(), self.recommended()
            a = rec.optimum.analysis
            distance = nom.prepared.motion.distance
            if distance <= 0:
                return None
            walking = (float(a.metrics["total"]["electrical"]) / distance,
                       float(a.baseline["total"]["electrical"]) / distance)
            result = fold(nom.robot, nom.prepared.motor, nom.prepared.contact,
                          rec.optimum.springs, walking, self.mission.metres_per_fold)
            self._step("fold", "no fold: the robot has no stand and sphere poses"
                       if result is None else result.line())
            return result
        return self._once("fold", compute)

    def maps(self) -> tuple[tuple[RobustnessMap, ...], dict[str, tuple[float, str]]]:
        """The recommendation over the robustness maps, and each metric's worst case."""
        def compute() -> tuple[tuple[RobustnessMap, ...], dict[str, tuple[float, str]]]:
            nom, d = self.nominal(), self.design
            maps, worst = robustness_maps(nom, self.recommended())
            self._step("maps", f"robustness maps: worst {d.metric} saving "
                       f"{100 * worst[d.metric][0]:+.2f} %" if maps else
                       "robustness maps and robust design left out: "
                       + ("a logged motion" if nom.motion is not None
                          else "[design] robustness = false"))
            return maps, worst
        return self._once("maps", compute)

    def robust(self) -> RobustResult | None:
        """The robust design over the box of conditions, or None (:meth:`robust_notes` say
        what was left out and why)."""
        return self._robust()[0]

    def robust_notes(self) -> tuple[str, ...]:
        """The robust stage's notes: corners left out (the keys that set them), or why there
        is no robust design."""
        return self._robust()[1]

    def _robust(self) -> tuple[RobustResult | None, tuple[str, ...]]:
        def compute() -> tuple[RobustResult | None, tuple[str, ...]]:
            robust, notes = robust_design(self.nominal(), self.recommended())
            dropped = sum(n.startswith("robust box corner") for n in notes)
            self._step("robust", ("robust design over the box of conditions" if robust
                                  is not None else "no robust design")
                       + (f" ({dropped} corners left out)" if dropped else ""))
            return robust, notes
        return self._once("robust", compute)

    def proof(self) -> tuple[tuple[dict[str, Any], ...], tuple[str, ...]]:
        """The recommendation simulated under each controller, or no rows and a note saying why
        it could not run."""
        def compute() -> tuple[tuple[dict[str, Any], ...], tuple[str, ...]]:
            try:
                rows = tuple(controller_check(self.nominal().prepared,
                                              self.recommended().optimum.springs, "joule"))
                out: tuple[tuple[dict[str, Any], ...], tuple[str, ...]] = rows, ()
            except HexalegError as e:
                out = (), (f"the recommendation could not be simulated: {type(e).__name__}: "
                           f"{e}",)
            self._step("simulate", "the recommendation simulated in MuJoCo under both "
                       "controllers")
            return out
        return self._once("proof", compute)

    def run(self, stages: Iterable[str] = STAGES) -> DesignResult:
        """Run ``stages`` (:data:`STAGES`, in their order; each runs the ones it needs) and
        return the result; a stage left out leaves its fields empty (None, no rows).

        Raises:
            UnknownNameError: a stage not in :data:`STAGES`.
            InvalidParameterError: an outer diameter no wire fits.
            UnknownNameError: an unknown robot, class, family, material or motor.

        A stage after the candidates that fails (a :class:`~hexaleg.errors.HexalegError`) ends
        the stages after it, not the design: the result holds the stages before it and
        :attr:`failed` (:class:`~hexaleg.design.chain.failure.StageFailure`) names it and the
        keys that set it.
        """
        wanted = tuple(stages)
        for s in wanted:
            if s not in STAGES:
                raise UnknownNameError("design stage", s, STAGES)
        self._wanted = tuple(s for s in STAGES if s in wanted or s == "candidates")
        for i, s in enumerate(self._wanted):
            if s == "candidates":  # the design itself: its failure ends the run
                self.candidates()
                continue
            try:
                getattr(self, s)()
            except HexalegError as e:  # the stages before it stand
                left = self._wanted[i + 1:]
                self.failed = StageFailure(stage=s, error=f"{type(e).__name__}: {e}",
                                           keys=STAGE_KEYS[s], left_out=left)
                self._wanted = self._wanted[:i]
                self._say(self.failed.line())
                break
        return self._result()

    def _result(self) -> DesignResult:
        """The result of the stages this chain ran, with its notes."""
        nom, d, w = self.nominal(), self.design, self._wanted
        rec = self.recommended()
        rows, _, ranking_notes = self.ranking() if "ranking" in w else ((), rec, ())
        tol = self.tolerance()[1] if "tolerance" in w else None
        env, fatigue, envelope_notes = self.envelope() if "envelope" in w else ((), (), ())
        maps, worst = self.maps() if "maps" in w else ((), {})
        robust, robust_notes = self._robust() if "robust" in w else (None, ())
        simulation, unsimulated = self.proof() if "proof" in w else ((), ())
        folded = self.fold() if "fold" in w else None
        stalled = [] if robust is None or not robust.design.solver.get("stopped") else [
            f"robust design: its bundle method's {robust.design.solver['stopped']} (predicted "
            f"decrease left {robust.design.solver['gap']:.3g} of the baseline's energy)"]
        pays = [] if rec.net[d.metric] > MIN_SAVING else [
            f"no springs pay: the best design saves {100 * rec.row[f'saving.{d.metric}']:+.2f} "
            f"% of {d.metric} and {100 * rec.net[d.metric]:+.2f} % net of its springs' mass — "
            "fitting springs does not pay on this robot and gait"]
        mirrored = mirror(nom.robot)
        plausible = check_baseline(nom.prepared.baseline("joule"), nom.robot.mass,
                                   nom.run.actuator)
        flagged = () if plausible is None else (f"baseline energy {plausible.message}",)
        logged = ([LOGGED_SKIP] if nom.motion is not None
                  else [] if d.robustness else [UNMAPPED])
        ranked = (f"ranked by the {d.metric} saving net of the springs' mass, simulated under "
                  f"{under(d.controller)}" if "ranking" in w else
                  f"ranked by the predicted {d.metric} saving net of the springs' mass (not "
                  "simulated)")
        residual = nom.prepared.residual.line() if nom.prepared.residual is not None else None
        evidence = per_joint_evidence(nom, rec) if "ranking" in w else None
        untolerant = self._tolerance()[2] if "tolerance" in w else ()
        failed = (self.failed.line(),) if self.failed is not None else ()
        notes = [*failed, *flagged, *((evidence,) if evidence else ()), *self._candidates()[1],
                 *untolerant, *pays, *logged,
                 *((residual,) if residual else ()), *ranking_notes,
                 *envelope_notes, *robust_notes, *stalled, *unsimulated, *nom.notes,
                 *nom.robot.notes,
                 *rec.notes,
                 (mirrored.summary() + ("; each gets its group's spring mirrored" if d.mirror
                                        and mirrored.mirrored else "")), *mirrored.notes,
                 f"designed at {nom.gait.samples} samples per cycle (Joule-optimal forces); "
                 + ranked]
        return DesignResult(
            run=nom.run, design=d, mission=self.mission, robot=nom.robot.name, title=nom.desc.title,
            mass=nom.robot.mass, actuator=nom.run.actuator.name, gait=nom.gait,
            baseline=nom.baseline, candidates=self.candidates(), recommended=rec,
            outer=nom.outer, pareto=self.pareto() if "pareto" in w else (), maps=maps,
            worst=worst, robust=robust, ranking=rows, tolerance=tol, envelope=env,
            fatigue=fatigue, simulation=simulation, timings=dict(self.timings),
            notes=tuple(notes), plausibility=plausible, motion=nom.motion, stages=w,
            whole_draw=_whole_draw(nom, rec), fold=folded, sourced=_sourced(nom, rec),
            failed=self.failed)


def _sourced(nom: Nominal, rec: Candidate
             ) -> tuple[WithoutConstants, WithoutConstants] | None:
    """Without the springs and with the recommendation: the figures of the joints that have no
    named motor, their sourced band among them
    (:func:`hexaleg.dynamics.without_constants.without_constants`); None when every joint's
    motor is named."""
    with_springs = without_constants(rec.optimum.analysis)
    if with_springs is None:
        return None
    baseline = without_constants(nom.prepared.evaluate(SpringSet(), "joule"))
    return None if baseline is None else (baseline, with_springs)


def _whole_draw(nom: Nominal, rec: Candidate) -> WholeDraw | None:
    """The recommendation's whole draw (:mod:`hexaleg.dynamics.draw`) on the nominal gait: its
    predicted electrical saving on the motors' baseline energy; None for a motion that is not
    one periodic cycle."""
    motion = nom.prepared.motion
    if not motion.periodic or motion.period is None:
        return None
    base = nom.baseline["electrical"]
    return whole_draw(base * (1.0 - rec.row["saving.electrical"]), base, motion.period,
                      motion.distance, nom.run.actuator, nom.robot.nj,
                      electronics=nom.desc.electronics_power, battery_wh=nom.desc.battery_wh)


__all__ = ["STAGES", "DesignChain"]
