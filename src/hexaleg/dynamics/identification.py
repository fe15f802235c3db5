"""A robot's actuators identified from the measurements of its own log (``hexaleg motors
--identify LOG``).

A motion loaded from a log (:func:`hexaleg.load_motion`) carries the log's actuator columns —
``current_<joint>`` (A), ``torque_<joint>`` (output torque, N·m), ``power_<joint>`` (electrical
power, W) — in ``motion.info["measured"]``, cycle-averaged as the joints are. For each actuator
model of the run (one motor for every joint, or one per joint class of a
:class:`~hexaleg.robot.motor_set.MotorSet`), :func:`identify_motion` fits the joints that have
the measurements together (:func:`hexaleg.robot.identify.identify_actuator`, the model of
:mod:`hexaleg.robot.motor`). The output torque is the logged one where every such joint has a
``torque_`` column; else the analysis' motor torque of the same motion
(:meth:`hexaleg.dynamics.prepare.Prepared.evaluate`: inverse dynamics, and the foot forces that
minimise the Joule loss, an assumption about how the real robot shares its load that the result
states). The speed is the motion's joint velocity.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import prepare
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.actuator import Actuator
from hexaleg.robot.identify import Identification, identify_actuator
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet

FITTED: tuple[str, ...] = ("current", "power")
"""The measurements that identify an actuator (a torque column only replaces the analysis')."""


@dataclass(frozen=True)
class ActuatorFit:
    """One actuator model identified on the joints it drives.

    Attributes:
        joints: The joints fitted (those with the measurements).
        torque: ``"logged"`` (the log's ``torque_`` columns) or ``"analysis"`` (the analysis'
            motor torque of the motion, Joule-optimal foot forces).
        identification: The fit (:class:`~hexaleg.robot.identify.Identification`).
    """

    joints: tuple[str, ...]
    torque: str
    identification: Identification

    def lines(self) -> list[str]:
        """The fit in words: each constant with its residual, one line a fit."""
        ident = self.identification
        shown = ", ".join(self.joints[:3]) + (", …" if len(self.joints) > 3 else "")
        head = (f"{ident.motor.name} on {len(self.joints)} joints ({shown}), torques from the "
                + ("log" if self.torque == "logged" else
                   "analysis (Joule-optimal foot forces: log torque_<joint> columns to fit on "
                   "the robot's own)"))
        out = [head]
        if ident.current is not None:
            f = ident.current
            out.append(f"  k_t G = {f.constants['output_torque_constant']:.4g} N·m/A from the "
                       f"currents: residual {f.residual_rms:.3g} A RMS "
                       f"({100 * f.relative_residual:.1f} % of the currents'), {f.samples} samples")
        if ident.power is not None:
            f = ident.power
            out.append(f"  η = {f.constants['gearbox_efficiency']:.4g}, c = "
                       f"{f.constants['joule_coefficient']:.4g} W/(N·m)² from the powers: "
                       f"residual {f.residual_rms:.3g} W RMS ({100 * f.relative_residual:.1f} % "
                       f"of the powers'), {f.samples} samples")
        m = ident.motor
        out.append(f"  so R = {m.resistance:.4g} Ω (k_t {m.torque_constant:.4g} N·m/A at G "
                   f"{m.gear_ratio:g}); {m.notes}")
        return out


def _groups(robot: Robot, motor: Actuator) -> list[tuple[str, Actuator, tuple[str, ...]]]:
    """(label, model, joints) per actuator model of the run (its
    :attr:`~hexaleg.robot.actuator.Actuator.models`, each with the joints it drives)."""
    labels = np.array(motor.joint_labels(robot.nj))
    names = np.array(robot.joint_names)
    return [(label, m, tuple(names[labels == label])) for label, m in motor.models.items()]


def identify_motion(robot: Robot, motion: Motion, motor: Actuator, *,
                    contact: ContactParams | None = None, springs: SpringSet | None = None
                    ) -> dict[str, ActuatorFit]:
    """The run's actuators fitted to the log's measurements (module docstring).

    Args:
        robot: The robot of the log.
        motion: A motion loaded from its log (:func:`hexaleg.load_motion`).
        motor: The actuators as known before (the fit's starting point and what it keeps).
        contact: Contact settings of the analysis (when its torques are used).
        springs: Springs the logged robot carried (their torque is not the motors'), or None.

    Returns:
        Per actuator model (``"every joint"``, or a joint class) that has measurements, its fit.

    Raises:
        InvalidParameterError: a motion without ``current_<joint>`` or ``power_<joint>``
            measurements (not loaded from a log, or a log without them); as
            :func:`~hexaleg.robot.identify.identify_actuator` (too few samples, wrong signs).
        HexalegError: from the analysis when its torques are needed.
    """
    if not isinstance(motion, Motion):
        raise InvalidParameterError("motion", type(motion).__name__,
                                    "a Motion loaded from a log (hexaleg.load_motion)")
    measured: Mapping[str, Any] = motion.info.get("measured") or {}
    if not any(k.startswith(f"{kind}_") for k in measured for kind in FITTED):
        raise InvalidParameterError(
            "motion", f"{motion.info.get('log', 'a motion')} without current or power columns",
            "a log with current_<joint> (A) or power_<joint> (W) columns for the joints of one "
            "actuator, and optionally torque_<joint> (N·m) (docs/motion.md)")
    analysis = None
    out: dict[str, ActuatorFit] = {}
    for label, base, joints in _groups(robot, motor):
        kinds = [k for k in FITTED if any(f"{k}_{j}" in measured for j in joints)]
        used = tuple(j for j in joints if kinds and all(f"{k}_{j}" in measured for k in kinds))
        if not used:
            continue
        cols = [robot.column(j) for j in used]
        if all(f"torque_{j}" in measured for j in used):
            tau, source = np.stack([measured[f"torque_{j}"] for j in used], axis=1), "logged"
        else:
            if analysis is None:
                analysis = prepare(robot, motion, motor=motor,
                                   contact=contact or ContactParams()).evaluate(springs, "joule")
            tau, source = analysis.tau_motor[:, cols], "analysis"
        signal = {k: np.stack([measured[f"{k}_{j}"] for j in used], axis=1) for k in kinds}
        out[label] = ActuatorFit(used, source, identify_actuator(
            base, tau, motion.v[:, 6:][:, cols], current=signal.get("current"),
            power=signal.get("power")))
    return out


__all__ = ["FITTED", "ActuatorFit", "identify_motion"]
