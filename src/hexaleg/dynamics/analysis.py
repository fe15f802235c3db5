"""What :meth:`Prepared.evaluate <hexaleg.dynamics.prepare.Prepared.evaluate>` returns: the
:class:`Analysis` of one motion with one choice of springs — foot forces, motor and spring
torques, powers, stored energy and the energy metrics against the baseline."""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.dynamics.contact import ContactParams
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.actuator import Actuator
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet


@dataclass(frozen=True, eq=False)
class Analysis:
    """Forces, torques, powers and energy metrics of one motion with one choice of springs.

    Joint columns follow the Pinocchio model's joint order (``robot.joint_names``); legs follow
    ``robot.legs`` (LF LM LH RF RM RH for the hexapod). "Baseline" is the one name for the same
    motion analysed without springs, here and in every module that compares against it.

    Attributes:
        robot: The robot.
        motion: The motion analysed.
        springs: The springs (joint name → spring).
        motor: The servo model of every joint, or one per joint (a MotorSet).
        objective: The force-distribution objective (:data:`hexaleg.dynamics.contact.OBJECTIVES`).
        contact: Contact settings.
        t: Sample times, shape (T,), s.
        q: Joint angles, shape (T, nj), rad.
        qdot: Joint velocities, shape (T, nj), rad/s.
        residual: For a logged motion (:func:`hexaleg.load_motion`), the base wrench its
            contacts could not produce where the forces were solved for the nearest one
            (:mod:`hexaleg.dynamics.nearest`); None for a generated motion.
        forces: World-frame ground reaction forces on the feet, shape (T, n_legs, 3), N (zero for
            swing feet).
        tau_motor: Motor torques, shape (T, nj), N·m.
        tau_spring: Spring torques on the joints, shape (T, nj), N·m.
        resolved: Samples whose forces needed the exact conic solve (an inequality binds), (T,).
        metrics: :func:`hexaleg.dynamics.energy.metrics` of ``tau_motor`` (per joint and total, SI).
        baseline: The same metrics for the same motion with no springs (the baseline).
        savings: :func:`hexaleg.dynamics.energy.savings` of ``metrics`` against ``baseline``
            (fraction of the baseline value saved, :func:`hexaleg.dynamics.energy.saving`;
            positive = the springs save).
    """

    robot: Robot
    motion: Motion
    springs: SpringSet
    motor: Actuator
    objective: str
    contact: ContactParams
    t: np.ndarray
    q: np.ndarray
    qdot: np.ndarray
    forces: np.ndarray
    tau_motor: np.ndarray
    tau_spring: np.ndarray
    resolved: np.ndarray
    metrics: dict[str, Any]
    baseline: dict[str, Any]
    savings: dict[str, Any]

    @property
    def tau_total(self) -> np.ndarray:
        """Joint torque carried by motor and spring together, shape (T, nj), N·m."""
        return self.tau_motor + self.tau_spring

    @property
    def power(self) -> np.ndarray:
        """Motor mechanical power ``τ_motor q̇``, shape (T, nj), W."""
        return self.tau_motor * self.qdot

    @functools.cached_property
    def spring_energy(self) -> np.ndarray:
        """Energy stored in the springs, shape (T, nj), J (computed when first asked for: a
        sweep never needs it)."""
        if not len(self.springs):
            return np.zeros_like(self.q)
        return self.springs.energies(self.robot, self.motion.q)
