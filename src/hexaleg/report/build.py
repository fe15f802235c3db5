"""The gait energy report (``hexaleg report``): one gait, analysed with springs and without.

The report leads with the answer — which springs to fit and what they save
(:mod:`hexaleg.report.answer`: a given or found ``design.json`` of ``hexaleg design``,
else the design's quick core) — and analyses those springs on its gait; the paper's design
carried over to the robot is the reference, one section below (a ``[springs]`` table replaces
both: the page then analyses the configured springs). :func:`build_report` runs the pipeline —
robot (with the configured payload, :class:`hexaleg.robot.payload.Payload`) → gait
(:func:`hexaleg.motion.legged.gait`) → :func:`hexaleg.dynamics.prepare.prepare` once →
:meth:`~hexaleg.dynamics.prepare.Prepared.evaluate` with the answer's springs, the reference's,
in the baseline (no springs) and at every point of the reference's stiffness curve
(:mod:`hexaleg.design.studies.curves`); for a robot with ``stand`` and ``sphere`` poses also the
stand → sphere transformation (:mod:`hexaleg.report.transform`) — and collects every number in a
JSON-ready dict whose quantities carry their unit (``{"value": …, "unit": "J"}``), one section of
the page each (:mod:`hexaleg.report.sections`).
:func:`hexaleg.commands.report.write.write_report` writes it as ``report.html``, ``report.json``
and the plots.

Sources of the models: the answer's springs are :mod:`hexaleg.design`'s families; the reference
springs are the paper's dead-zone springs (eq. 7–8, 14) placed by :mod:`hexaleg.design.rules`
(centred dead zone, θ_k/A of Section 4.2, k_M of eq. 19); the energies
are :func:`hexaleg.dynamics.energy.metrics` (work eq. 20, cost of transport eq. 23, the motor model
of :mod:`hexaleg.robot.motor`); the friction usage ``|f_t| / (μ f_n)`` is the load of the Coulomb
friction cone that the force program (:mod:`hexaleg.dynamics.contact`) keeps ≤ 1; the paper's
single-joint numbers come from :func:`hexaleg.paper.reproduce.reproduce`
(:mod:`hexaleg.report.paper_section`).
"""

from __future__ import annotations

import importlib.metadata
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from hexaleg.checks import typed
from hexaleg.design import rules as design
from hexaleg.design.studies.curves import StiffnessCurve, curve_springs, stiffness_curve
from hexaleg.dynamics import contact
from hexaleg.dynamics.draw import WholeDraw, whole_draw
from hexaleg.dynamics.plausibility import check_baseline, measured_beside
from hexaleg.dynamics.prepare import Analysis, Prepared, prepare
from hexaleg.dynamics.sanity import torque_findings
from hexaleg.dynamics.without_constants import WithoutConstants, without_constants
from hexaleg.motion.legged import gait
from hexaleg.motion.sanity import motion_findings
from hexaleg.motion.trajectory import Motion
from hexaleg.quantities import file_data
from hexaleg.report import sections
from hexaleg.report.answer import answer_line, answer_section
from hexaleg.report.config import ReportConfig, ReportParams
from hexaleg.report.design_section import design_section
from hexaleg.report.paper_section import paper_reference
from hexaleg.report.transform import transform_section
from hexaleg.robot.model import Robot, load_robot
from hexaleg.robot.sanity import Finding, robot_findings
from hexaleg.robot.springs import SpringSet
from hexaleg.scenario.run_warnings import gait_defaults, run_warnings


@dataclass(frozen=True, eq=False)
class Report:
    """A computed report: the analyses it was made from and its JSON content.

    Attributes:
        config: The configuration.
        robot: The robot.
        motion: The gait.
        analysis: The gait with the springs the page analyses (the answer's, or the configured
            ``[springs]``; the reference's when there is no answer).
        baseline: The gait without springs (same objective).
        curve: The reference springs' stiffness curve.
        usage: Friction usage of ``analysis``'s forces, shape (T, n_legs), 1.
        data: Every number of the report with its unit (the content of ``report.json``).
        files: Files written by :func:`hexaleg.commands.report.write.write_report` (empty from
            :func:`build_report`).
    """

    config: ReportConfig
    robot: Robot
    motion: Motion
    analysis: Analysis
    baseline: Analysis
    curve: StiffnessCurve
    usage: np.ndarray
    data: dict[str, Any]
    files: tuple[Path, ...] = ()

    def summary(self) -> str:
        """The lines the command prints: first, for joints with a generic actuator, the motor
        choice asked for with what holds without its constants
        (:mod:`hexaleg.dynamics.without_constants`); the reference springs' electrical energy
        per cycle with and without them and their saving; the whole draw; last, the answer
        (:func:`~hexaleg.report.answer.answer_line`: where it comes from, which springs, the
        saving)."""
        e = self.data["reference"]["energy"]["electrical"]
        design = self.data["reference"]["design"]
        reference = ("the paper's design (the reference)" if design == "paper"
                     else f"the configured springs ({design})")
        draw = self.data.get("whole_draw")
        whole = "" if draw is None else (
            f"\nthe robot's whole draw, without springs: {_watts(draw['total_baseline'])} "
            f"(motors {_watts(draw['motors_baseline'])}, servos at rest "
            + _watts(draw["idle_power"], "not published for " + ", ".join(draw["idle_missing"]))
            + ("" if not draw["idle_family"] else
               f" ({', '.join(draw['idle_family'])}: its family's standby current, range "
               f"{draw['idle_range']['low']['value']:.3g}–"
               f"{draw['idle_range']['high']['value']:.4g} W)")
            + ", "
            "electronics "
            f"{_watts(draw['electronics_power'], 'not given: [robot] electronics_power')}"
            f"){', a lower bound' if draw['is_bound'] else ''}"
            f"{', an estimate on assumed actuator constants' if draw['assumed'] else ''}")
        plausible = self.data.get("plausibility")
        if plausible is not None and not plausible["plausible"]:
            whole += f"\nWARNING baseline energy {plausible['message']}"
        for m in self.data.get("measured_robots") or []:
            whole += f"\nmeasured: {m['line']}"
        generic = self.data.get("without_constants")
        first = "" if generic is None else generic["line"] + "\n" + generic["band_line"] + "\n"
        return (first
                + f"{reference}: electrical energy per cycle {e['with_springs']['value']:.4g} J "
                f"with its springs, {e['baseline']['value']:.4g} J without (saving "
                f"{e['saving']['value']:+.2f} %){whole}\n"
                + answer_line(self.data["design"]))


def _report_curve(prepared: Prepared, springs: SpringSet, rp: ReportParams, objective: str,
                  step: Callable[[str], None]) -> StiffnessCurve:
    """The stiffness curve of ``rp.curve_joints`` over ``[stiffness_min, stiffness_max]``
    (default maximum: 10 × the mean k_M of eq. 19 over the curve's joints)."""
    robot, motion = prepared.robot, prepared.motion
    base = curve_springs(robot, motion, springs, rp.curve_joints)
    joints = robot.joints(rp.curve_joints)
    k_hi = rp.stiffness_max
    if k_hi is None:
        zones = base.dead_zones("the report's stiffness curve")
        k_hi = 10 * float(np.mean([design.k_M(robot, motion, j, alpha=zones[j].transmission)
                                   for j in joints]))
    ks = np.linspace(rp.stiffness_min, k_hi, rp.stiffness_points)
    return stiffness_curve(prepared, base, rp.curve_joints, ks, rp.curve_metrics, objective, step)


def _findings(robot: Robot, motion: Motion, a: Analysis) -> list[Finding]:
    """What the sanity checks find in the robot, the gait and its motor torques (joint speeds
    over their limits aside: the run's warnings say them, :mod:`hexaleg.scenario.run_warnings`)."""
    return [*robot_findings(robot),
            *(f for f in motion_findings(robot, motion) if f.check != "joint_speed"),
            *torque_findings(robot, a.tau_motor, motion.t)]


def _report_data(cfg: ReportConfig, robot: Robot, motion: Motion, a: Analysis,
                 baseline: Analysis, curve: StiffnessCurve, usage: np.ndarray,
                 draw: WholeDraw | None) -> dict[str, Any]:
    """The page's sections, in the page's order (the content of ``report.json`` without the
    transformation, the paper's joint and the file list)."""
    return {
        "title": cfg.report.title,
        "hexaleg_version": importlib.metadata.version("hexaleg"),
        "warnings": list(run_warnings(robot, motion, cfg.motor, desc=cfg.robot_description,
                                      gait=cfg.gait if cfg.motion is None else None)),
        "gait_defaults": gait_defaults(cfg.robot_description,
                                       cfg.gait if cfg.motion is None else None),
        "notes": sections.notes_section(cfg.notes, motion, _findings(robot, motion, a)),
        "robot": sections.robot_section(robot),
        "payload": sections.payload_section(cfg.payload, robot),
        "gait": sections.gait_section(motion, cfg.gait),
        "motor": sections.motor_section(cfg.motor),
        "contact": sections.contact_section(cfg.contact),
        "objective": cfg.report.objective,
        "joints": sections.joints_section(robot, a, baseline),
        "forces": sections.forces_section(robot, motion, a, usage),
        "energy": sections.energy_section(robot, a),
        "cost_of_transport": sections.cost_of_transport_section(motion, a),
        "whole_draw": None if draw is None else draw.as_dict(),
        "plausibility": None if (p := check_baseline(a.baseline, robot.mass, cfg.motor)) is None
        else p.as_dict(),
        "without_constants": None if (w := without_constants(baseline)) is None
        else w.as_dict(),
        "measured_robots": _measured(cfg, robot, draw, w),
        "stiffness_curve": sections.curve_section(cfg.report.curve_joints, curve),
    }


def _measured(cfg: ReportConfig, robot: Robot, draw: WholeDraw | None,
              generic: WithoutConstants | None) -> list[dict[str, Any]]:
    """Published whole-robot power and cost of transport beside this run's predicted draw
    without springs and its sourced band, in watts and as costs of transport at the run's speed
    (:func:`hexaleg.dynamics.plausibility.measured_beside`); empty for a motion that is not one
    periodic cycle."""
    if draw is None:
        return []
    band = None
    if generic is not None and (b := generic.band_dict()) is not None and b["power"]:
        band = (b["power"]["low"]["value"], b["power"]["high"]["value"])
    return measured_beside(cfg.robot, robot.mass, draw.total_baseline, band,
                           draw.speed if draw.speed > 0 else None)


def _watts(q: dict[str, Any] | None, unknown: str = "unknown") -> str:
    """A ``{value, unit}`` power in words, or what is missing."""
    return unknown if q is None else f"{q['value']:.3g} W"


def answer_draw(answer: dict[str, Any], draw: WholeDraw) -> dict[str, Any] | None:
    """The answer's saving on the whole draw: its electrical saving (on this report's gait
    when it has one, else the design's) in watts over the baseline's whole draw — the standby
    and electronics draw does not depend on the springs (:mod:`hexaleg.dynamics.draw`). None
    when the answer's metric is not the electrical energy."""
    if answer["metric"] != "electrical":
        return None
    on = answer.get("report_gait") or answer
    share = draw.motors_baseline / draw.total_baseline if draw.total_baseline > 0 else 0.0
    return {"saving": {"value": on["saving"]["value"] * share, "unit": "%"},
            "motor_share": {"value": share, "unit": "1"}, "complete": draw.complete,
            "is_bound": draw.is_bound,
            "line": draw.line()}


def _draw(cfg: ReportConfig, robot: Robot, motion: Motion, a: Analysis) -> WholeDraw | None:
    """The whole draw of the configured springs' gait (:mod:`hexaleg.dynamics.draw`); None for
    a motion that is not one periodic cycle."""
    if not motion.periodic or motion.period is None:
        return None
    desc = cfg.robot_description
    return whole_draw(a.metrics["total"]["electrical"], a.baseline["total"]["electrical"],
                      motion.period, motion.distance, cfg.motor, robot.nj,
                      electronics=None if desc is None else desc.electronics_power,
                      battery_wh=None if desc is None else desc.battery_wh)


@typed
def build_report(config: ReportConfig | None = None, *, robot: Robot | None = None,
                 progress: Callable[[str], None] | None = None) -> Report:
    """Compute the report: gait, the answer, its springs' analysis and the baseline, the
    reference design and its stiffness curve, the paper's joint.

    Args:
        config: The configuration (default :class:`ReportConfig`: built-in robot, default tripod
            gait, default motor, the answer's springs with the paper-style femur springs as the
            reference).
        robot: The robot (default :func:`hexaleg.robot.model.load_robot`).
        progress: Called with one status line per step (e.g. print to stderr).

    Returns:
        The report (``files`` empty).

    Raises:
        ConfigError: ``[report] design`` is not a readable ``design.json`` (before any work).
        HexalegError: from the gait, the springs or the analysis (unreachable foot targets,
            unknown joints, infeasible forces at the configured springs, …).
    """
    cfg = config or ReportConfig()
    say = progress or (lambda _msg: None)
    t0 = time.perf_counter()

    def step(msg: str) -> None:
        say(f"{msg} ({time.perf_counter() - t0:.1f} s)")

    robot = robot or load_robot()
    design_section(cfg.report.design, robot)  # a bad design.json fails before any work
    if cfg.payload is not None:  # carried on the base through dynamics, forces and design
        robot = cfg.payload.attach(robot)
    step(f"robot {robot.name}: {robot.nj} joints, {robot.mass:.3f} kg")
    motion = cfg.motion if cfg.motion is not None else gait(robot, cfg.gait)
    step(f"gait: {motion.n_samples} samples over {motion.period:g} s"
         + (" (logged)" if cfg.motion is not None else ""))
    prepared = prepare(robot, motion, motor=cfg.motor, contact=cfg.contact)
    step("dynamics prepared (RNEA, Jacobians, force program)")
    answer, answer_springs, passed = answer_section(cfg, robot, prepared)
    if answer is not None:
        step(f"answer: {answer['label']} springs ({answer['origin']}), "
             f"{answer['metric']} saving {answer['saving']['value']:+.2f} %")
    objective = cfg.report.objective
    reference_springs = cfg.spring_set(robot, motion)
    reference = prepared.evaluate(reference_springs, objective)
    leads = cfg.springs is None and answer_springs is not None
    analysis = prepared.evaluate(answer_springs, objective) if leads else reference
    baseline = prepared.evaluate(None, objective)
    step(f"analysed with the {'answer' if leads else 'configured'}'s {len(analysis.springs)} "
         f"springs{', with the reference' if leads else ''} and without")
    curve = _report_curve(prepared, reference_springs, cfg.report, objective, step)
    usage = contact.friction_usage(analysis.forces, motion.stance.astype(bool), cfg.contact.mu,
                                   motion.normal)
    draw = _draw(cfg, robot, motion, analysis)
    data = file_data(_report_data(cfg, robot, motion, analysis, baseline, curve, usage, draw))
    data["reference"] = file_data(sections.reference_section(
        robot, motion, reference, cfg.reference(robot)))
    data["springs"] = file_data(sections.springs_section(
        robot, analysis, "answer" if leads else data["reference"]["design"]))
    data["design"] = answer
    if answer is not None and draw is not None:
        answer["whole_draw"] = answer_draw(answer, draw)
    data["notes"] += passed
    residual = prepared.residual.line() if prepared.residual is not None else None
    if residual is not None:  # a logged motion the contacts could not carry exactly
        data["notes"].append(residual)
    data["transform"] = transform_section(robot, cfg, analysis.springs, objective)
    if data["transform"] is not None:
        step("stand → sphere transformation analysed")
    step("the paper's single joint reproduced (its sinusoid, eq. 25)")
    data["paper"] = paper_reference(cfg.report.paper_samples)
    step("numbers collected")
    return Report(config=cfg, robot=robot, motion=motion, analysis=analysis, baseline=baseline,
                  curve=curve, usage=usage, data=data)
