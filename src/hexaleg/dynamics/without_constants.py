"""What a run with generic actuators can say without the motor constants it does not have.

A joint whose actuator is generic (:func:`hexaleg.robot.motor.generic_actuator`: built from the
URDF's effort and velocity limits, every other constant assumed) gets an electrical energy that
rests on those assumptions — off by ×0.8–×1.6 for the gearbox efficiency alone, and by far more
when the limits are placeholders or a driver's current limit (issue #40: 3–10× on brushless
quadrupeds). :func:`without_constants` gives, for the generic joints of an analysis (the gait
without springs), what holds whatever the motor:

* the **positive mechanical work** ``∫ max(0, τ q̇) dt`` — the least any motor must convert
  (paper eq. 20);
* the **squared-torque integral** ``∫ τ² dt`` — the Joule loss is ``c`` times it for a motor of
  Joule coefficient ``c = R / (k_t G)²``, the one constant the user must supply
  (:mod:`hexaleg.robot.motor`);
* the **electrical energy with the catalogue's motors of that torque class** — each catalogue
  actuator whose stall torque is within :data:`TORQUE_CLASS` of the class's URDF effort limit,
  run on the same torques and speeds (:func:`hexaleg.dynamics.energy.metrics`): a range from
  real datasheets, or none when the catalogue has no actuator of that class;

beside the figure the generic actuator states. Sources: the energy metrics of
:mod:`hexaleg.dynamics.energy`; the catalogue of :mod:`hexaleg.robot.catalogue`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.dynamics import energy
from hexaleg.dynamics.prepare import Analysis
from hexaleg.quantities import quantity
from hexaleg.robot.catalogue import CATALOGUE
from hexaleg.robot.motor import GENERIC_MARK
from hexaleg.robot.motor_set import MotorSet

TORQUE_CLASS = (0.5, 2.0)
"""A catalogue actuator is of a joint's torque class when its stall torque is within these
factors of the joint's URDF effort limit."""


@dataclass(frozen=True)
class WithoutConstants:
    """The motor-independent figures of a run's generic joints (module docstring), per cycle.

    Attributes:
        joints: The joints with a generic actuator.
        positive_work: Their positive mechanical work, J.
        torque_squared: Their ``∫ Σ τ² dt``, N²·m²·s.
        stated: Their electrical energy with the generic actuator's assumed constants, J.
        catalogue: Catalogue actuator of their torque class → their electrical energy with it,
            J (empty when the catalogue has none of that class).
        effort: The largest URDF effort limit of these joints, N·m (the torque class's centre).
    """

    joints: tuple[str, ...]
    positive_work: float
    torque_squared: float
    stated: float
    catalogue: dict[str, float]
    effort: float

    def line(self) -> str:
        """The figures in one line, the motor choice asked for first."""
        lo, hi = TORQUE_CLASS
        values = sorted(self.catalogue.values())
        span = (f"{values[0]:.4g} J" if len(values) == 1 or values[0] == values[-1]
                else f"{values[0]:.4g}–{values[-1]:.4g} J") if values else ""
        cat = (f"electrical with the catalogue's actuators of their torque class ({lo:g}–{hi:g}"
               f" × {self.effort:.3g} N·m, their largest URDF effort) {span} "
               f"({', '.join(self.catalogue)})" if self.catalogue else
               f"the catalogue has no actuator of their torque class ({lo:g}–{hi:g} × "
               f"{self.effort:.3g} N·m, their largest URDF effort)")
        return (f"name the motor of {len(self.joints)} joints first: no motor is named for them, "
                f"so their electrical energy ({self.stated:.4g} J per cycle) rests on assumed "
                f"constants. Without constants, per cycle: positive mechanical work "
                f"{self.positive_work:.4g} J (the least any motor converts); Joule loss = c × "
                f"{self.torque_squared:.4g} N²·m²·s, c = R/(k_t G)² of the motor you choose; "
                f"{cat}")

    def as_dict(self) -> dict[str, Any]:
        """The figures for a command's JSON, ``{value, unit}`` each."""
        return {"joints": list(self.joints),
                "positive_work": quantity(self.positive_work, "J"),
                "torque_squared": quantity(self.torque_squared, "N²·m²·s"),
                "stated_electrical": quantity(self.stated, "J"),
                "catalogue_electrical": {k: quantity(v, "J") for k, v in self.catalogue.items()},
                "torque_class": {"effort": quantity(self.effort, "N·m"),
                                 "factors": list(TORQUE_CLASS)},
                "line": self.line()}


def _generic_joints(analysis: Analysis) -> list[str]:
    motor = analysis.motor
    names = analysis.robot.joint_names
    if isinstance(motor, MotorSet):
        return [j for j, kind in zip(motor.joint_names, motor.joint_classes, strict=True)
                if dict(motor.by_class)[kind].notes.startswith(GENERIC_MARK)]
    return list(names) if motor.notes.startswith(GENERIC_MARK) else []


def without_constants(analysis: Analysis) -> WithoutConstants | None:
    """The motor-independent figures of ``analysis``'s generic joints (module docstring); None
    when no joint's actuator is generic.

    Args:
        analysis: An analysis of the gait (its motor torques and speeds; the report passes the
            one without springs).
    """
    joints = _generic_joints(analysis)
    if not joints:
        return None
    robot, motion = analysis.robot, analysis.motion
    cols = [robot.column(j) for j in joints]
    per_joint = analysis.metrics["joint"]
    c = np.broadcast_to(analysis.motor.joule_coefficient, (robot.nj,))
    tau, qdot = analysis.tau_motor[:, cols], analysis.qdot[:, cols]
    dt = float(motion.t[1] - motion.t[0])
    effort = float(np.max(robot.model.effortLimit[[6 + k for k in cols]]))
    lo, hi = TORQUE_CLASS
    catalogue = {name: float(energy.metrics(tau, qdot, dt, m, periodic=motion.periodic)[
        "total"]["electrical"]) for name, m in sorted(CATALOGUE.items())
        if lo * effort <= m.stall_torque <= hi * effort}
    return WithoutConstants(
        joints=tuple(joints), positive_work=float(per_joint["positive_work"][cols].sum()),
        torque_squared=float((per_joint["joule"][cols] / c[cols]).sum()),
        stated=float(per_joint["electrical"][cols].sum()), catalogue=catalogue, effort=effort)


__all__ = ["TORQUE_CLASS", "WithoutConstants", "without_constants"]
