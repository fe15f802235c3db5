"""The one actuator interface: what the dynamics, the energy metrics, the simulation and the
pages ask of whatever drives the joints.

An :class:`Actuator` turns the output (joint) torque τ and speed q̇ into a current and an
electrical power, states its Joule coefficient, its idle draw, its limits and its source, and
says which single actuator model drives each joint. Every figure is either one value for every
joint or an array of shape (n,), one per joint in the model's column order
(``robot.joint_names``), so that it broadcasts against torques of shape (..., n); callers
broadcast with ``np.broadcast_to(value, (n,))``.

The implementations:

* :class:`hexaleg.robot.motor.Motor` — one geared DC model (Verstraten et al., IEEE RA-L 1(1),
  2016) on every joint. The catalogue servos (:func:`hexaleg.robot.motor.from_datasheet`), the
  brushless quasi-direct-drive modules (:mod:`hexaleg.robot.brushless`), the published A1 energy
  model, the generic actuator from URDF limits (:func:`hexaleg.robot.motor.generic_actuator`)
  and an identified actuator (:func:`hexaleg.robot.identify.identify_actuator`) are all
  :class:`~hexaleg.robot.motor.Motor` instances: they differ in how their constants are
  obtained (their constructors), not in the model, so they share its methods.
* :class:`hexaleg.robot.motor_set.MotorSet` — a different actuator per joint class: a mapping
  joint class → actuator that answers each question by asking each joint's own actuator
  (values then (n,) arrays).

A new actuator *model* (one whose current or power is not the geared DC model's) is a new class
satisfying this protocol; ``docs/architecture.md`` ("A new actuator model") says which files it
touches.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike

from hexaleg.robot.standby import Idle

EVERY_JOINT = "every joint"
"""The label of the one model of an actuator that drives every joint the same
(:attr:`Actuator.models`)."""


@runtime_checkable
class Actuator(Protocol):
    """What drives the joints (module docstring): torque and speed → current and power, the
    Joule coefficient, the idle draw, the limits, the source, and the model of each joint.

    Figures typed ``float | np.ndarray`` are one value for every joint or shape (n,), one per
    joint in column order.
    """

    @property
    def name(self) -> str:
        """The model name (a set: each model with its joint classes), for pages and errors."""
        ...

    @property
    def source(self) -> str:
        """Where the constants come from (a datasheet, a paper, a fit, the URDF's limits)."""
        ...

    @property
    def notes(self) -> str:
        """What was derived or assumed rather than read off the source; may be empty. A generic
        actuator's open with :data:`hexaleg.robot.motor.GENERIC_MARK`."""
        ...

    @property
    def joule_coefficient(self) -> float | np.ndarray:
        """``c = R / (k_t G)²``, W/(N·m)²: the Joule loss per squared output torque, the
        weight of the force program's objective; a float or shape (n,)."""
        ...

    @property
    def stall_torque(self) -> float | np.ndarray:
        """The peak output torque, N·m (the analysis' torque limits, the servos' saturation);
        a float or shape (n,)."""
        ...

    @property
    def no_load_speed(self) -> float | np.ndarray:
        """The no-load output speed, rad/s (the servos' damping ``τ_s / ω_0``); a float or shape
        (n,)."""
        ...

    @property
    def gearbox_efficiency(self) -> float | np.ndarray:
        """The constant transmission efficiency η in (0, 1], applied by the direction of power
        flow; a float or shape (n,)."""
        ...

    @property
    def regeneration(self) -> bool | np.ndarray:
        """Whether negative electrical power returns to the supply; a bool or shape (n,)."""
        ...

    @property
    def voltage(self) -> float | np.ndarray:
        """The supply voltage of the figures, V; a float or shape (n,)."""
        ...

    @property
    def models(self) -> Mapping[str, Actuator]:
        """Each single actuator model and what it drives: joint class → its model for a set,
        ``{EVERY_JOINT: self}`` for one model on every joint. Its values are single models
        (their figures floats)."""
        ...

    def joint_labels(self, n_joints: int) -> tuple[str, ...]:
        """The key in :attr:`models` of each of ``n_joints`` joints, in column order.

        Raises:
            InvalidParameterError: a set built for another number of joints.
        """
        ...

    def idle_power(self, n_joints: int) -> Idle:
        """What the actuators of ``n_joints`` joints draw at rest, powered and holding no load
        (their electronics): ``Σ_j I_standby,j V_j``, W, with its range and each figure's source
        (:class:`hexaleg.robot.standby.Idle`; a figure no source gives is named missing).

        Raises:
            InvalidParameterError: a set built for another number of joints.
        """
        ...

    def current(self, tau: ArrayLike) -> np.ndarray:
        """The winding (q-axis) current for output torques ``tau`` (shape (..., n), N·m), A,
        the shape of ``tau``."""
        ...

    def joule_power(self, tau: ArrayLike) -> np.ndarray:
        """The Joule (I²R) loss ``c τ²`` for output torques ``tau`` (shape (..., n), N·m), W,
        the shape of ``tau``."""
        ...

    def electrical_power(self, tau: ArrayLike, qdot: ArrayLike,
                         regeneration: bool | None = None) -> np.ndarray:
        """The electrical power drawn for output torques ``tau`` (shape (..., n), N·m) at joint
        speeds ``qdot`` (the shape of ``tau``, rad/s), W, the shape of ``tau``; negative power
        flows back only with ``regeneration`` (``None``: the actuator's own
        :attr:`regeneration`)."""
        ...


def joint_models(actuator: Actuator, n_joints: int) -> tuple[Actuator, ...]:
    """The single model driving each of ``n_joints`` joints, in column order
    (:meth:`Actuator.joint_labels` looked up in :attr:`Actuator.models`)."""
    models = actuator.models
    return tuple(models[label] for label in actuator.joint_labels(n_joints))


__all__ = ["EVERY_JOINT", "Actuator", "joint_models"]
