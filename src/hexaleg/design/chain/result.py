"""The design chain's result and ``design.json``, its one writer.

:class:`DesignResult` is what :class:`~hexaleg.design.chain.chain.DesignChain` found;
:meth:`DesignResult.to_json` writes ``design.json``: every number as ``{"value": …, "unit": …}``
(savings in %, SI otherwise; a missing or non-finite number is ``null``, its path listed in
``non_finite``), and each recommended spring as ``{"family", "joint", "parameters"}``
(:mod:`hexaleg.design.springs.law_json`), which :func:`hexaleg.design.chain.design_file.load_design`
— the one reader — and so ``hexaleg simulate --springs`` and ``hexaleg report --design`` read
back. ``simulation`` holds the recommendation's forward simulation, one row per controller, as
``hexaleg simulate --sensitivity`` writes its rows
(:func:`hexaleg.simulation.sensitivity.sensitivity_row`), under the servo the robot runs and the
worse first; ``proof`` says whether they back the answer, and if not why. The records of the
chain's single products in it — a candidate design, a ranked design's simulation, a robustness
map, the robust design — are :mod:`hexaleg.design.chain.records`'.
"""

from __future__ import annotations

import importlib.metadata
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.design.chain.candidates import Candidate
from hexaleg.design.chain.config import DesignParams
from hexaleg.design.chain.design_file import gait_parameters
from hexaleg.design.chain.failure import StageFailure
from hexaleg.design.chain.ranking import Simulated
from hexaleg.design.chain.records import candidate_data, map_data, ranking_data, robust_data
from hexaleg.design.chain.robust_stage import RobustResult
from hexaleg.design.evaluator import SAVING_METRICS
from hexaleg.design.families import family
from hexaleg.design.fold import Fold, Mission
from hexaleg.design.robust.maps import RobustnessMap
from hexaleg.design.search.tolerance import TolerantSprings
from hexaleg.design.springs.envelope import STRESS, PartEnvelope
from hexaleg.design.springs.fatigue import FatigueCheck, cycles_per_year
from hexaleg.design.springs.mounting import mountings
from hexaleg.design.springs.parts import SpringPart
from hexaleg.dynamics.contact import friction_usage
from hexaleg.dynamics.draw import WholeDraw
from hexaleg.dynamics.energy import metric_unit
from hexaleg.dynamics.plausibility import Plausibility
from hexaleg.dynamics.prepare import Analysis
from hexaleg.dynamics.without_constants import WithoutConstants
from hexaleg.motion.params import GaitParams
from hexaleg.motion.trajectory import Motion
from hexaleg.quantities import file_data, json_text, quantity
from hexaleg.scenario.scenario import Scenario
from hexaleg.simulation.controllers import controllers_of
from hexaleg.simulation.result import verdict_meanings
from hexaleg.simulation.sensitivity import sensitivity_row

MIN_SAVING = 1e-4
"""A recommendation must save more than this fraction of the ranking metric (0.01 %) net of its
springs' mass to pay; below it the design says that no springs pay."""


@dataclass(frozen=True, eq=False)
class DesignResult:
    """Everything the design chain found (:class:`~hexaleg.design.chain.chain.DesignChain`).

    Attributes:
        run: The run designed on (:class:`~hexaleg.scenario.scenario.Scenario`). design: The
            ``[design]`` settings. mission: The ``[mission]`` table. robot: Its name. title:
            Its title. mass: kg.
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
        ranking: Every ranked design simulated under each controller of ``[design]
            controller`` (:mod:`hexaleg.design.chain.ranking`): the designs in the order
            ranked, a controller's rows after another's.
        tolerance: The recommendation against its tolerance-blind self over the stops'
            mounting error (:class:`~hexaleg.design.search.tolerance.TolerantSprings`), or None.
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
        stages: The stages of the chain that ran (:data:`hexaleg.design.chain.chain.STAGES`);
            the fields of a stage left out are empty (None, no rows).
        whole_draw: The recommendation's whole draw on the nominal gait — motors, servos at
            rest, electronics (:mod:`hexaleg.dynamics.draw`) — or None for a motion that is
            not one periodic cycle.
        fold: The fold into the sphere and back with the recommendation and without
            (:mod:`hexaleg.design.fold`), or None (no such poses, or the stage left out).
        sourced: The joints with no named motor, without springs and with the recommendation
            (:mod:`hexaleg.dynamics.without_constants`: their sourced band), or None when every
            motor is named.
        failed: The stage after the candidates that failed (the stages after it not run), or
            None (:class:`~hexaleg.design.chain.failure.StageFailure`).
    """

    run: Scenario
    design: DesignParams
    mission: Mission
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
    stages: tuple[str, ...] = ()
    whole_draw: WholeDraw | None = None
    fold: Fold | None = None
    sourced: tuple[WithoutConstants, WithoutConstants] | None = None
    failed: StageFailure | None = None

    def to_dict(self, **extra: Any) -> dict[str, Any]:
        """What ``design.json`` holds (:func:`design_data`), with ``extra`` keys of the command
        that writes it (its run's warnings, its files), as the file holds it
        (:func:`hexaleg.quantities.file_data`: a number that is not finite null, its path in
        ``non_finite``)."""
        return file_data({**design_data(self), **extra})

    def to_json(self, **extra: Any) -> str:
        """``design.json``: :meth:`to_dict` through :func:`hexaleg.config.json_text` (every
        number ``{value, unit}``, a non-finite one ``null`` with its path in ``non_finite``:
        never ``Infinity``). :func:`hexaleg.design.chain.design_file.load_design` reads it
        back."""
        return json_text(self.to_dict(**extra))

    @property
    def pays(self) -> bool:
        """Whether the recommended springs save energy net of their own mass."""
        return bool(self.recommended.net[self.design.metric] > MIN_SAVING)

    def simulated(self) -> list[dict[str, Any]]:
        """The recommendation's simulation rows under the servo the robot runs (``[design]
        controller``: both controllers by default), the worse first: a run that did not walk,
        then the lower simulated saving."""
        runs = controllers_of(self.design.controller)
        rows = [row for row in self.simulation if row.get("controller") in runs]
        return sorted(rows, key=lambda row: (row["simulated"] is not None,
                                             row["simulated"] or 0.0))

    @property
    def unproven(self) -> str:
        """Why no simulation backs the recommendation under the servo the robot runs, or ""
        when one does: the recommendation and the robot without springs both walk
        (:func:`hexaleg.simulation.measures.verdict`) under each controller of ``[design]
        controller``, and the simulated saving is positive under each."""
        runs = controllers_of(self.design.controller)
        rows = self.simulated()
        if not rows:
            return ("not simulated" + (f" under {' and '.join(runs)}"
                                       if self.simulation else "")
                    + ("" if "proof" in self.stages else " (the proof stage did not run)"))
        for row in rows:
            if row["simulated"] is None:
                why = f": {row['why']}" if row.get("why") else ""
                return f"under {row['label']} the runs did not walk ({row['verdict']}{why})"
            if row["simulated"] <= 0:
                return (f"under {row['label']} the simulated saving is "
                        f"{100 * row['simulated']:+.2f} %")
        return ""

    def summary(self) -> str:
        """One line: the recommendation and its saving; "unproven" and why where no simulation
        under the servo the robot runs backs it (:attr:`unproven`)."""
        r, m = self.recommended, self.design.metric
        why = self.unproven
        head = ("no springs pay here; the best would be" if not self.pays else
                f"unproven ({why}): the analysis would fit" if why else "fit")
        line = (f"{head} {r.label} springs on {', '.join(r.optimum.groups)}: {m} saving "
                f"{100 * r.row[f'saving.{m}']:+.2f} % ({100 * r.net[m]:+.2f} % net "
                f"of {1e3 * r.spring_mass:.1f} g of springs); " + (
                    f"worst case over the maps {100 * self.worst[m][0]:+.2f} % at "
                    f"{self.worst[m][1]}" if self.maps else "no robustness maps ("
                    + ("logged motion" if self.run.log is not None else "left out") + ")"))
        stops = [f"{e.group} ({e.side}) at {math.degrees(e.stop.angle_from_centre):+.1f}° from "
                 "its centre of motion (" + (
                     f"S_y/σ {e.safety_factor:.2f} without" if e.stop.limit == STRESS else
                     f"its coil {1e3 * e.wound_inner_diameter:.2f} mm over its "
                     f"{1e3 * e.arbor_diameter:.2f}-mm arbor without") + ")"
                 for e in self.envelope if e.stop is not None]
        unsafe = [f"{e.group} ({e.side}): {e.problem}" for e in self.envelope
                  if e.stop is None and not e.meets]
        if stops:
            line += "; hard stops needed: " + ", ".join(stops)
        if unsafe:
            line += "; NOT SAFE over the joint's envelope: " + ", ".join(unsafe)
        simulated = [f"{row['label']} {100 * row['simulated']:+.2f} %"
                     if row["simulated"] is not None else f"{row['label']}: {row['verdict']}"
                     for row in self.simulated()]
        if simulated:
            line += (f"; simulated electrical saving {', '.join(simulated)} (predicted "
                     f"{100 * self.simulation[0]['predicted']:+.2f} %)")
        if self.plausibility is not None and not self.plausibility.plausible:
            line += f"; WARNING baseline energy {self.plausibility.message}"
        return line


def tolerance_data(r: DesignResult) -> dict[str, Any]:
    """The recommendation and its tolerance-blind self over the stops' mounting error: nominal
    and worst saving within the tolerance (worst case over a stated set of shifts and the dense
    common-shift curve, :mod:`hexaleg.design.search.tolerance`), the curve saving vs common
    shift."""
    t = r.tolerance
    assert t is not None
    return {"tolerance": quantity(t.tolerance, "rad"), "metric": t.metric,
            "criterion": "worst case over the mounting errors within ± the tolerance",
            "chosen": t.chosen, "search": t.optimum.solver.get("search"),
            "shifts": quantity(t.shifts, "rad"),
            **{name: {"nominal_saving": quantity(100 * t.nominal[name], "%"),
                      "worst_saving": quantity(100 * t.worst[name], "%"),
                      "curve": quantity(100 * t.curve[name], "%")}
               for name in ("tolerant", "blind")}}


def gait_data(r: DesignResult) -> dict[str, Any]:
    """``gait``: the nominal gait's period, stride, duty factor, samples and ``parameters``
    (what ``hexaleg simulate --springs`` re-makes it from); on a logged motion (``--motion``)
    the cycle's figures and ``motion`` — the log's path, ``--cycle`` and quality figures — in
    place of the parameters, which a log does not have."""
    g = r.gait
    if r.run.log is None:
        return {"period": quantity(g.period, "s"), "stride": quantity(g.stride, "m"),
                "duty_factor": quantity(g.duty_factor, "1"), "samples": g.samples,
                "parameters": gait_parameters(g)}
    from hexaleg.scenario.logged import quality_data

    logged = r.motion
    return {"period": quantity(g.period, "s"),
            "stride": None if logged is None else quantity(logged.distance, "m"),
            "duty_factor": (None if logged is None
                            else quantity(float(logged.stance.mean()), "1")),
            "samples": g.samples,
            "motion": {"source": "log", "path": r.run.log, "cycle": r.run.cycle,
                       "quality": None if logged is None else quality_data(logged)}}


def planned_friction_use(a: Analysis) -> float:
    """The largest share of its friction cone a stance foot's planned force uses over the
    cycle, ``max |f_t| / (μ f_n)`` (:func:`hexaleg.dynamics.contact.friction_usage`; 1: about to
    slip), at the analysis' μ."""
    usage = friction_usage(a.forces, a.motion.stance.astype(bool), a.contact.mu, a.motion.normal)
    return float(usage.max()) if usage.size else 0.0


def mounting_data(r: DesignResult) -> list[dict[str, Any]]:
    """``mounting``: each recommended spring on each of its joints, every angle from the joint's
    zero and from its centre of motion, with the hard stop its envelope needs
    (:func:`hexaleg.design.springs.mounting.mountings`): the angles the page draws."""
    c = r.recommended
    a = c.optimum.analysis
    joints = {j for p in c.parts for j in p.joints}
    return [m.table() for m in mountings(c.parts, a.q, {j: a.robot.column(j) for j in joints},
                                         envelope=r.envelope, mirrored=c.optimum.mirrored)]


def design_data(r: DesignResult) -> dict[str, Any]:
    """The content of ``design.json`` (module docstring)."""
    d = r.design
    return {
        "title": f"{r.title}: the spring design",
        "pays": r.pays,
        "hexaleg_version": importlib.metadata.version("hexaleg"),
        "robot": {"name": r.robot, "title": r.title, "mass": quantity(r.mass, "kg")},
        "actuator": r.actuator,
        "gait": gait_data(r),
        "settings": {
            "families": list(d.families), "classes": list(r.recommended.optimum.groups),
            "grouping": d.grouping, "metric": d.metric, "force_objective": "joule",
            "max_torque": None if d.max_torque is None else quantity(d.max_torque, "N·m"),
            "max_deflection": (None if d.deflection_bound is None
                               else quantity(d.deflection_bound, "rad")),
            "materials": list(d.materials), "safety_factor": quantity(d.safety_factor, "1"),
            "arbor_diameter": quantity(d.arbor_diameter, "m"),
            "stop_tolerance": quantity(d.stop_tolerance, "rad"),
            "life_cycles": quantity(d.life_cycles, "cycles"),
            "contact_mu": quantity(r.run.contact.mu, "1"), "controller": d.controller,
            "min_group_saving": quantity(100 * d.min_group_saving, "%")},
        "baseline": {m: quantity(r.baseline[m], metric_unit(m)) for m in SAVING_METRICS},
        "plausibility": None if r.plausibility is None else r.plausibility.as_dict(),
        "whole_draw": None if r.whole_draw is None else r.whole_draw.as_dict(),
        "sourced": sourced_data(r),
        "friction_use": quantity(planned_friction_use(r.recommended.optimum.analysis), "1"),
        "recommended": candidate_data(r.recommended, r.outer),
        "mounting": mounting_data(r),
        "candidates": [candidate_data(c, r.outer) for c in r.candidates],
        "pareto": [{"fraction": quantity(f, "1"), **candidate_data(c, r.outer)}
                   for f, c in r.pareto],
        "maps": [map_data(m) for m in r.maps],
        "worst": {k: {"saving": quantity(100 * s, "%"), "condition": c}
                  for k, (s, c) in r.worst.items()},
        "robust": None if r.robust is None else robust_data(r.robust, r.outer),
        "ranking": [ranking_data(row) for row in r.ranking],
        "stop_tolerance": None if r.tolerance is None else tolerance_data(r),
        "envelope": [e.table() for e in r.envelope],
        "fold": None if r.fold is None else r.fold.table(),
        "fatigue": [{"group": p.group, "side": p.side, "role": p.role, **f.table(),
                     "cycles_per_year": {
                         "one_hour_a_day": quantity(cycles_per_year(r.gait.period, 1.0),
                                                    "cycles"),
                         "continuous": quantity(cycles_per_year(r.gait.period, 24.0), "cycles")}}
                    for p, f in r.fatigue],
        "simulation": [sensitivity_row(row) for row in r.simulated()],
        "proof": proof_data(r),
        "story": story_data(r),
        "timings": {k: quantity(v, "s") for k, v in r.timings.items()},
        "notes": list(r.notes),
        "stages": list(r.stages),
        "failed": None if r.failed is None else r.failed.table(),
    }


QUICK_FAMILY = "linear"
"""The family of ``hexaleg report``'s quick answer (:mod:`hexaleg.report.answer`): its global
optimum is one convex program (about a second), no geometry to search."""


def story_data(r: DesignResult) -> list[dict[str, Any]]:
    """``story``: the figures a user meets for this gait, each with what it is and why it
    differs from the springs to buy — the quick answer, each family's optimum, the springs to
    buy, net of their mass, at worst with the stops off, beyond the tolerance, simulated under
    the worse servo, over the maps and over the robust box (issue #57: five "best springs" for
    one gait, and nowhere said why they differ). Savings of the ranking metric, in %."""
    m, rec = r.design.metric, r.recommended
    out: list[dict[str, Any]] = []

    def row(figure: str, value: float | None, why: str) -> None:
        out.append({"figure": figure,
                    "saving": None if value is None else quantity(100 * value, "%"),
                    "why": why})

    quick = next((c for c in r.candidates if c.family == QUICK_FAMILY), None)
    if quick is not None:
        row("hexaleg report's quick answer", quick.row[f"saving.{m}"],
            f"the {QUICK_FAMILY} family's global optimum: no stop angles to search, one convex "
            "program, so the report can give it in a second; not simulated")
    for c in r.candidates:
        row(f"the {c.family} family's optimum", c.row[f"saving.{m}"],
            ("its stops at their exact angles; " if family(c.family).angles else "")
            + ("the family of the springs to buy, before the stop tolerance"
               if c.family == rec.family else
               "ranked below the springs to buy by its simulated saving net of its springs' "
               "mass (the families' table)"))
    row("the springs to buy", rec.row[f"saving.{m}"],
        "the family ranked best by its simulated saving net of the springs' mass"
        + (", designed for stops a workshop mounts within ±"
           f"{math.degrees(r.tolerance.tolerance):g}°: it gives up part of the exact-stop "
           "optimum for its worst case" if r.tolerance is not None
           and r.tolerance.chosen == "tolerant" else ""))
    row("the springs to buy, net of their mass", rec.net[m],
        f"{1e3 * rec.spring_mass:.1f} g of springs carried on every step")
    t = r.tolerance
    if t is not None:
        row(f"at worst with every stop within ±{math.degrees(t.tolerance):g}°",
            t.worst[t.chosen], "the lowest over the stated mounting errors")
        outside = np.abs(t.shifts) > t.tolerance * (1 + 1e-9)
        if outside.any():
            k = int(np.flatnonzero(outside)[np.argmin(t.curve[t.chosen][outside])])
            row(f"a common stop shift of {math.degrees(t.shifts[k]):+.1f}°, outside the "
                "tolerance", t.curve[t.chosen][k],
                "the stops mounted further off than designed for: the saving falls fast "
                "beyond the tolerance")
    sims = r.simulated()
    if sims:
        worse = sims[0]
        row(f"simulated in MuJoCo, {worse['label']} (the worse servo)", worse["simulated"],
            "the springs in a forward simulation with real contacts and that servo's "
            "tracking" + ("" if worse["simulated"] is not None
                          else f": the runs did not walk ({worse['verdict']})"))
    if r.maps and m in r.worst:
        row(f"over the robustness maps, at worst ({r.worst[m][1]})", r.worst[m][0],
            "the same springs on another gait, load or floor than the one designed for")
    if r.robust is not None:
        row("the robust design over its box, at worst", r.robust.worst(m),
            "other magnitudes, chosen for the worst corner of the box, not the springs to "
            "buy")
    return out


def sourced_data(r: DesignResult) -> dict[str, Any] | None:
    """``sourced``: where joints have no named motor, their figures without springs and with the
    recommendation (:meth:`~hexaleg.dynamics.without_constants.WithoutConstants.as_dict`) and
    the saving with each sourced actuator of their class, ``1 − E_springs / E_baseline`` on
    those joints, as a band (low, high, which actuators); None when every motor is named."""
    if r.sourced is None:
        return None
    base, rec = r.sourced
    savings = {k: 1.0 - rec.band[k] / v for k, v in base.band.items()
               if k in rec.band and v > 0}
    band = None
    if savings:
        low = min(savings, key=savings.__getitem__)
        high = max(savings, key=savings.__getitem__)
        band = {"low": quantity(100 * savings[low], "%"), "low_actuator": low,
                "high": quantity(100 * savings[high], "%"), "high_actuator": high,
                "by_actuator": {k: quantity(100 * v, "%") for k, v in savings.items()},
                "joints": list(base.joints),
                "note": ("the saving on the joints without a named motor with the scaling "
                         "law's actuators of their effort (no sourced actuator of their class); "
                         "a band on assumed constants" if base.from_law else
                         "the saving on the joints without a named motor with each sourced "
                         "actuator geared to their effort; a band on sourced constants")}
    return {"baseline": base.as_dict(), "with_springs": rec.as_dict(), "saving_band": band}


def proof_data(r: DesignResult) -> dict[str, Any]:
    """``proof``: whether a simulation under the servo the robot runs backs the answer
    (:attr:`DesignResult.unproven`), the controllers it needs, and what each run's verdict
    means (:func:`hexaleg.simulation.measures.verdict_meanings`)."""
    why = r.unproven
    return {"proven": not why, "why": why or None,
            "controllers": list(controllers_of(r.design.controller)),
            "verdicts": verdict_meanings()}


__all__ = ["MIN_SAVING", "QUICK_FAMILY", "DesignResult", "design_data", "gait_data",
           "mounting_data", "proof_data", "sourced_data", "story_data", "tolerance_data"]
