"""The sections of the report page as JSON-ready dicts, one function per section.

Every number is a quantity ``{"value", "unit"}`` (:mod:`hexaleg.quantities`),
taken from the analyses, not recomputed: the energies are
:func:`hexaleg.dynamics.energy.metrics` (work eq. 20, cost of transport eq. 23, the motor model
of :mod:`hexaleg.robot.motor`) with the springs and in the baseline (no springs); k_M is eq. 19
(:func:`hexaleg.design.rules.k_M`); the friction usage ``|f_t| / (μ f_n)`` is the load of the
Coulomb friction cone that the force program (:mod:`hexaleg.dynamics.contact`) keeps ≤ 1.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from hexaleg.design import rules as design
from hexaleg.design.springs.law_json import spring_entry
from hexaleg.design.studies.curves import StiffnessCurve
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.energy import metric_unit
from hexaleg.dynamics.prepare import Analysis
from hexaleg.motion.params import GaitParams
from hexaleg.motion.trajectory import Motion
from hexaleg.quantities import comparison, quantity
from hexaleg.report.config import SpringDesign
from hexaleg.robot.actuator import EVERY_JOINT, Actuator
from hexaleg.robot.model import Robot
from hexaleg.robot.payload import Payload
from hexaleg.robot.sanity import Finding
from hexaleg.robot.springs import SpringSet

ENERGY_TABLE_KEYS: tuple[str, ...] = ("positive_work", "joule", "electrical")
"""Metrics of the per-joint energy table."""
ENGAGED = 1e-9
"""A spring counts as pushing on its joint where its torque exceeds this fraction of its peak
(its torque is exactly zero in a dead zone or before contact; the fraction keeps rounding out)."""


def notes_section(notes: tuple[str, ...], motion: Motion,
                  findings: Sequence[Finding] = ()) -> list[str]:
    """The configuration's caveats, the sanity checks' findings on the robot, the gait and its
    torques (:mod:`hexaleg.robot.sanity`), and the body sway of a gait balanced on two feet or
    one."""
    out = list(notes) + [f"check {f.message}" for f in findings]
    sway = motion.info.get("balance", {})
    if sway.get("mode") == "sway":
        out.append(f"two-foot gait: the body sways ±{1e3 * sway['amplitude']:.2f} mm so that the "
                   "two stance feet can carry it (no moment about the support line; "
                   f"{sway['iterations']} iterations, residual {sway['residual']:.1e} m g h)")
    if sway.get("mode") == "zmp":
        out.append(f"one-foot gait: the body sways ±{1e3 * sway['sway'][0]:.2f} mm (base x), "
                   f"±{1e3 * sway['sway'][1]:.2f} mm (base y) and turns "
                   f"±{math.degrees(sway['turn']):.2f}° so that the zero-moment point is on the "
                   "stance foot (a ZMP walking pattern; "
                   f"{sway['iterations']} iterations, residual {sway['residual']:.1e} m g h)")
    return out


def robot_section(robot: Robot) -> dict[str, Any]:
    """Name, mass, joints, legs and joint classes."""
    return {"name": robot.name, "mass": quantity(robot.mass, "kg"), "joints": robot.nj,
            "legs": list(robot.leg_names), "joint_names": list(robot.joint_names),
            "joint_classes": {k: list(v) for k, v in robot.joint_classes.items()}}


def gait_section(motion: Motion, g: GaitParams) -> dict[str, Any]:
    """The gait's parameters and what its sampling measured (stride, speed, static margin; the
    legs' timing, heading and ground; the body shift of a statically stable gait)."""
    info = motion.info
    if "stride_length" not in info:  # a logged motion: what its cycle measures
        return _logged_gait(motion, g)
    timed = g.pattern is not None or g.phases is not None  # else the groups as given
    groups = info.get("groups", g.groups) if timed else g.groups
    ground = info.get("ground", {"slope": 0.0, "cross_slope": 0.0, "attitude": g.attitude})
    balance = info.get("balance", {})
    return {"period": quantity(motion.period, "s"), "duty_factor": quantity(g.duty_factor, "1"),
            "stride_length": quantity(info["stride_length"], "m"),
            "speed": quantity(info["speed"], "m/s"), "step_height": quantity(g.step_height, "m"),
            "body_height": quantity(info["body_height"], "m"),
            "foot_radius": quantity(info["foot_radius"], "m"),
            "yaw_rate": quantity(g.yaw_rate, "rad/s"),
            "samples": motion.n_samples, "groups": [list(x) for x in groups],
            "pattern": g.pattern, "heading": quantity(g.heading, "rad"),
            "slope": quantity(ground["slope"], "rad"),
            "cross_slope": quantity(ground["cross_slope"], "rad"),
            "attitude": ground["attitude"],
            "min_stance_feet": int(info["min_stance_feet"]),
            "static_margin": (quantity(info["static_margin"], "m")
                              if info["static_margin"] is not None else None),
            "shift": ({"target": quantity(balance["target"], "m"),
                       "amplitude": quantity(balance["amplitude"], "m")}
                      if balance.get("mode") == "shift" else None)}


def _logged_gait(motion: Motion, g: GaitParams) -> dict[str, Any]:
    """A logged motion's gait section: its cycle's measured figures (stride = distance per
    cycle, speed = stride / period, duty factor = the mean stance fraction, step height = the
    highest foot lift, body height = the base's mean height, foot radius = the feet's mean
    horizontal distance from the base); what a log does not define (yaw rate, static margin,
    pattern) as the generated gait's or none, and the log's source."""
    stance, feet, q = motion.stance, motion.feet, motion.q
    lift = feet[..., 2] - feet[..., 2].min(axis=0)
    radius = np.linalg.norm(feet[..., :2] - q[:, None, :2], axis=-1)
    return {"period": quantity(motion.period, "s"),
            "duty_factor": quantity(float(stance.mean()), "1"),
            "stride_length": quantity(motion.distance, "m"),
            "speed": quantity(motion.distance / motion.period, "m/s"),
            "step_height": quantity(float(lift.max()), "m"),
            "body_height": quantity(float(q[:, 2].mean()), "m"),
            "foot_radius": quantity(float(radius.mean()), "m"),
            "yaw_rate": quantity(0.0, "rad/s"), "samples": motion.n_samples,
            "groups": [list(x) for x in g.groups], "pattern": None,
            "heading": quantity(0.0, "rad"), "slope": quantity(0.0, "rad"),
            "cross_slope": quantity(0.0, "rad"), "attitude": g.attitude,
            "min_stance_feet": int(stance.sum(axis=1).min()), "static_margin": None,
            "shift": None, "logged": str(motion.info.get("log", motion.info.get("source", "")))}


def payload_section(payload: Payload | None, robot: Robot) -> dict[str, Any] | None:
    """The payload on the base (mass, centre of mass in the base frame, inertia about it as 9
    values row by row) and the robot's total mass with it; None without a payload."""
    if payload is None:
        return None
    return {"mass": quantity(payload.mass, "kg"), "com": quantity(list(payload.com), "m"),
            "inertia": quantity([list(r) for r in payload.inertia], "kg·m²"),
            "total_mass": quantity(robot.mass, "kg")}


def motor_section(motor: Actuator) -> dict[str, Any]:
    """The servo of every joint; for a :class:`~hexaleg.robot.motor_set.MotorSet` also
    ``classes``, one entry per joint class with its motor's figures."""
    if tuple(motor.models) != (EVERY_JOINT,):
        classes = [{"joint_class": c, "name": m.name, **_motor_figures(m)}
                   for c, m in motor.models.items()]
        return {"name": motor.name, "classes": classes, "source": motor.source,
                "notes": motor.notes}
    return {"name": motor.name, **_motor_figures(motor), "source": motor.source,
            "notes": motor.notes}


def _motor_figures(motor: Actuator) -> dict[str, Any]:
    return {"joule_coefficient": quantity(motor.joule_coefficient, "W/(N·m)²"),
            "stall_torque": quantity(motor.stall_torque, "N·m"),
            "gearbox_efficiency": quantity(motor.gearbox_efficiency, "1"),
            "regeneration": motor.regeneration}


def contact_section(contact: ContactParams) -> dict[str, Any]:
    """The contact settings of the force program."""
    return {"mu": quantity(contact.mu, "1"), "cone": contact.cone,
            "min_normal_force": quantity(contact.min_normal_force, "N"),
            "torque_limits": contact.torque_limits}


def springs_section(robot: Robot, a: Analysis, design: str) -> dict[str, Any]:
    """The springs the page analyses, of any family: per joint its law as ``design.json`` writes
    it (family and parameters in SI, :func:`hexaleg.design.springs.law_json.spring_entry`), the
    share of the cycle it pushes on its joint and its peak torque.

    Args:
        robot: The robot.
        a: The analysis with these springs.
        design: Where they come from: ``"answer"`` (the answer the page leads with) or the
            ``[springs] design`` (``"paper"``, ``"centred"``, ``"baseline"``, ``"explicit"``).
    """
    cols = a.springs.columns(robot)
    rows = {}
    for name, spring in a.springs.items():
        entry = spring_entry(name, spring)
        tau = np.abs(a.tau_spring[:, cols[name]])
        rows[name] = {"family": entry["family"], "parameters": entry["parameters"],
                      "engaged_fraction": quantity(float((tau > ENGAGED * tau.max()).mean())
                                                   if tau.max() > 0 else 0.0, "1"),
                      "peak_torque": quantity(float(tau.max()), "N·m")}
    return {"design": design, "joints": rows}


def reference_section(robot: Robot, motion: Motion, a: Analysis,
                      springs: SpringDesign | SpringSet) -> dict[str, Any]:
    """The reference design (the paper's dead-zone springs carried over, or the configured
    ones) on this gait: its name, the total energies with it and without springs, and each
    spring's k against k_M (eq. 19), dead zone, α, convention and the share of the cycle it is
    engaged."""
    cols = a.springs.columns(robot)
    rows = {}
    for name, s in a.springs.dead_zones("the report's reference springs").items():
        k_m = design.k_M(robot, motion, name, alpha=s.transmission)
        angle = a.q[:, cols[name]]
        rows[name] = {
            "stiffness": quantity(s.stiffness, "N·m/rad"), "k_M": quantity(k_m, "N·m/rad"),
            "stiffness_over_k_M": quantity(s.stiffness / k_m, "1"),
            "neutral": quantity(s.neutral, "rad"), "theta_minus": quantity(s.th_minus, "rad"),
            "theta_plus": quantity(s.th_plus, "rad"), "alpha": quantity(s.alpha, "1"),
            "convention": s.convention,
            "engaged_fraction": quantity(float(s.engaged(angle).mean()), "1")}
    return {"design": springs.design if isinstance(springs, SpringDesign) else "explicit",
            "joints": rows, "energy": energy_section(robot, a)["totals"]}


def joints_section(robot: Robot, a: Analysis, baseline: Analysis) -> dict[str, Any]:
    """Per joint: angle range, peak motor, spring torque and power (with springs and in the
    baseline), peak spring energy."""
    out = {}
    for j, name in enumerate(robot.joint_names):
        out[name] = {
            "angle_min": quantity(a.q[:, j].min(), "rad"),
            "angle_max": quantity(a.q[:, j].max(), "rad"),
            "peak_motor_torque": quantity(np.abs(a.tau_motor[:, j]).max(), "N·m"),
            "peak_motor_torque_baseline": quantity(np.abs(baseline.tau_motor[:, j]).max(), "N·m"),
            "peak_spring_torque": quantity(np.abs(a.tau_spring[:, j]).max(), "N·m"),
            "peak_power": quantity(np.abs(a.power[:, j]).max(), "W"),
            "peak_power_baseline": quantity(np.abs(baseline.power[:, j]).max(), "W"),
            "peak_spring_energy": quantity(a.spring_energy[:, j].max(), "J"),
        }
    return out


def forces_section(robot: Robot, motion: Motion, a: Analysis,
                   usage: np.ndarray) -> dict[str, Any]:
    """Per leg the stance fraction, normal forces and friction usage; the weight and peaks.

    Args:
        robot: The robot.
        motion: The gait (stance flags).
        a: The analysis with the springs.
        usage: Its friction usage ``|f_t| / (μ f_n)``, shape (T, n_legs), 1.
    """
    stance = motion.stance.astype(bool)
    normal = np.array([0.0, 0.0, 1.0]) if motion.normal is None else motion.normal
    f_n = a.forces @ normal  # normal components: along the ground's normal on a slope
    legs = {}
    for i, leg in enumerate(robot.leg_names):
        fn = f_n[:, i]
        legs[leg] = {"stance_fraction": quantity(stance[:, i].mean(), "1"),
                     "peak_normal_force": quantity(fn.max(), "N"),
                     "mean_normal_force_in_stance": quantity(fn[stance[:, i]].mean()
                                                             if stance[:, i].any() else 0.0, "N"),
                     "peak_friction_usage": quantity(usage[:, i].max(), "1")}
    gravity = float(np.linalg.norm(robot.model.gravity.linear))
    return {"legs": legs, "peak_friction_usage": quantity(usage.max(), "1"),
            "weight": quantity(robot.mass * gravity, "N"),
            "peak_total_normal_force": quantity(f_n.sum(1).max(), "N"),
            "resolved_samples": int(a.resolved.sum())}


def energy_section(robot: Robot, a: Analysis) -> dict[str, Any]:
    """Total and per-joint metrics with the springs and in the baseline, savings in %."""
    met, base, sav = a.metrics, a.baseline, a.savings
    totals = {k: comparison(met["total"][k], base["total"][k], sav["total"][k], metric_unit(k))
              for k in sav["total"]}
    per_joint = {k: {name: comparison(met["joint"][k][j], base["joint"][k][j],
                                      sav["joint"][k][j], metric_unit(k))
                     for j, name in enumerate(robot.joint_names)} for k in sav["joint"]}
    net = {"with_springs": quantity(met["total"]["net_work"], "J"),
           "baseline": quantity(base["total"]["net_work"], "J")}
    return {"totals": totals, "net_work": net, "joints": per_joint,
            "table_keys": list(ENERGY_TABLE_KEYS)}


def cost_of_transport_section(motion: Motion, a: Analysis) -> dict[str, Any]:
    """Cost of transport E / (m g d) (eq. 23) per energy; none for a gait that does not
    travel."""
    met, base, sav = a.metrics, a.baseline, a.savings
    cot = ({k: comparison(met["cost_of_transport"][k], base["cost_of_transport"][k],
                          sav["cost_of_transport"][k], "1")
            for k in met["cost_of_transport"]} if "cost_of_transport" in met else {})
    return {"distance": quantity(motion.distance, "m"), "metrics": cot}


def curve_section(spec: str, curve: StiffnessCurve) -> dict[str, Any]:
    """The stiffness curve: every point, the baseline, the best feasible point per metric
    against the mean k_M (eq. 19), and the infeasible points with their errors."""
    k_M_mean = float(np.mean(list(curve.k_M.values())))
    metrics = {}
    for m in curve.totals:
        best = curve.best(m)
        unit = metric_unit(m)
        metrics[m] = {
            "values": quantity(curve.totals[m], unit),
            "baseline": quantity(curve.baseline[m], unit),
            "saving": quantity(100 * curve.savings(m), "%"),
            "best": None if best is None else {
                "stiffness": quantity(curve.stiffness[best], "N·m/rad"),
                "stiffness_over_k_M": quantity(curve.stiffness[best] / k_M_mean, "1"),
                "value": quantity(curve.totals[m][best], unit),
                "saving": quantity(100 * curve.savings(m)[best], "%")}}
    return {
        "spec": spec, "joints": list(curve.joints),
        "stiffness": quantity(curve.stiffness, "N·m/rad"), "k_M": quantity(k_M_mean, "N·m/rad"),
        "k_M_per_joint": {j: quantity(k, "N·m/rad") for j, k in curve.k_M.items()},
        "metrics": metrics,
        "infeasible": [{"stiffness": quantity(k, "N·m/rad"), "error": e}
                       for k, e in zip(curve.stiffness, curve.errors, strict=True) if e]}
