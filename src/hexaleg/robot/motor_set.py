"""A robot whose joint classes carry different actuators: a mapping joint class → actuator that
is itself an :class:`~hexaleg.robot.actuator.Actuator`.

Hexapod builders often fit a stronger servo where the load is (an XM430 on the femur, an XL430 on
the coxa and tibia). A :class:`MotorSet` maps each joint class to the single actuator model of its
joints and answers what the dynamics and the energy metrics ask of an actuator — Joule
coefficients, stall torques, gearbox efficiencies, currents, electrical power — as per-joint
arrays, by asking each joint's own actuator about that joint's column (for a
:class:`~hexaleg.robot.motor.Motor`, the geared-DC model of Verstraten et al., IEEE RA-L 2016, see
:mod:`hexaleg.robot.motor`). Everywhere an :class:`~hexaleg.robot.actuator.Actuator` is taken, a
:class:`MotorSet` may stand in for a single model.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.robot.actuator import EVERY_JOINT, Actuator, joint_models
from hexaleg.robot.model import Robot
from hexaleg.robot.motor import Motor, as_torque_speed, generic_actuator
from hexaleg.robot.standby import Idle, combined


def _single(actuator: object) -> bool:
    """Whether ``actuator`` is one actuator model (an :class:`Actuator` whose
    :attr:`~Actuator.models` is itself on every joint), as a set's values must be."""
    return (isinstance(actuator, Actuator) and not isinstance(actuator, Mapping)
            and tuple(actuator.models) == (EVERY_JOINT,))


@dataclass(frozen=True)
class MotorSet(Mapping[str, Actuator]):
    """The actuator of every joint, grouped by joint class: a mapping joint class → its
    actuator (in the order of :attr:`by_class`) and itself an
    :class:`~hexaleg.robot.actuator.Actuator` whose figures are (n,) arrays.

    Attributes:
        joint_names: The robot's joints in the model's column order, n names.
        joint_classes: The class of each joint (``"coxa"``, ``"femur"`` …), n names.
        by_class: Joint class → its actuator, as ``(class, actuator)`` pairs; every class of
            :attr:`joint_classes` exactly once, each actuator a single model (a
            :class:`~hexaleg.robot.motor.Motor`, not another set).
    """

    joint_names: tuple[str, ...]
    joint_classes: tuple[str, ...]
    by_class: tuple[tuple[str, Actuator], ...]

    def __post_init__(self) -> None:
        object.__setattr__(self, "joint_names", tuple(self.joint_names))
        object.__setattr__(self, "joint_classes", tuple(self.joint_classes))
        object.__setattr__(self, "by_class", tuple((str(c), m) for c, m in self.by_class))
        if len(self.joint_names) != len(self.joint_classes) or not self.joint_names:
            raise InvalidParameterError("MotorSet.joint_classes", self.joint_classes,
                                        f"one class per joint, {len(self.joint_names)} names")
        named = [c for c, _ in self.by_class]
        for c, m in self.by_class:
            if not _single(m):
                raise InvalidParameterError(f"MotorSet motor of {c}", m,
                                            "a hexaleg.Motor (one actuator model)")
        if sorted(named) != sorted(set(self.joint_classes)):
            raise InvalidParameterError("MotorSet classes", named, "each joint class of "
                                        f"{sorted(set(self.joint_classes))} exactly once")

    @classmethod
    def per_class(cls, joint_classes: Mapping[str, tuple[str, ...]], joint_names: tuple[str, ...],
                  motors: Mapping[str, Actuator]) -> MotorSet:
        """The motor set of a robot from its joint classes and one actuator per class.

        Args:
            joint_classes: Class → its joints (:attr:`hexaleg.robot.model.Robot.joint_classes`).
            joint_names: The robot's joints in column order.
            motors: Class → actuator, every class of ``joint_classes``.

        Returns:
            The set, in the order of ``joint_classes``.
        """
        of = {joint: kind for kind, joints in joint_classes.items() for joint in joints}
        missing = [j for j in joint_names if j not in of]
        if missing:
            raise InvalidParameterError("MotorSet joints", missing, "every joint in one class "
                                        f"of {sorted(joint_classes)}")
        return cls(joint_names, tuple(of[j] for j in joint_names),
                   tuple((kind, motors[kind]) for kind in joint_classes if kind in motors))

    # the mapping joint class → actuator
    def __getitem__(self, kind: str) -> Actuator:
        for c, m in self.by_class:
            if c == kind:
                return m
        raise KeyError(kind)

    def __iter__(self) -> Iterator[str]:
        return (c for c, _ in self.by_class)

    def __len__(self) -> int:
        return len(self.by_class)

    # the Actuator protocol
    @property
    def models(self) -> Mapping[str, Actuator]:
        """The set itself: joint class → its actuator."""
        return self

    def joint_labels(self, n_joints: int) -> tuple[str, ...]:
        """The class of each joint (:attr:`joint_classes`).

        Raises:
            InvalidParameterError: ``n_joints`` is not the set's number of joints.
        """
        if n_joints != len(self.joint_names):
            raise InvalidParameterError("motor joints", f"{len(self.joint_names)} joints",
                                        f"the robot's {n_joints}")
        return self.joint_classes

    def idle_power(self, n_joints: int) -> Idle:
        """The standby draw of each joint's actuator (its own ``idle_power`` of one joint),
        summed in column order (:func:`hexaleg.robot.standby.combined`).

        Raises:
            InvalidParameterError: ``n_joints`` is not the set's number of joints.
        """
        return combined(m.idle_power(1) for m in joint_models(self, n_joints))

    @property
    def motors(self) -> tuple[Actuator, ...]:
        """The actuator of each joint, n entries."""
        return tuple(self[c] for c in self.joint_classes)

    def _per_joint(self, attribute: str) -> np.ndarray:
        return np.array([getattr(m, attribute) for m in self.motors], dtype=float)

    @property
    def name(self) -> str:
        """``"XM430-W350 (femur) · XL430-W250 (coxa, tibia)"``: each motor and its classes."""
        classes: list[tuple[Actuator, list[str]]] = []
        for c, m in self.by_class:
            for model, cs in classes:
                if model == m:
                    cs.append(c)
                    break
            else:
                classes.append((m, [c]))
        return " · ".join(f"{m.name} ({', '.join(cs)})" for m, cs in classes)

    @property
    def joule_coefficient(self) -> np.ndarray:
        """``c = R / (k_t G)²`` of each joint's motor, shape (n,), W/(N·m)²."""
        return self._per_joint("joule_coefficient")

    @property
    def stall_torque(self) -> np.ndarray:
        """Stall torque of each joint's motor, shape (n,), N·m (the analysis' torque limits)."""
        return self._per_joint("stall_torque")

    @property
    def no_load_speed(self) -> np.ndarray:
        """No-load speed of each joint's motor, shape (n,), rad/s."""
        return self._per_joint("no_load_speed")

    @property
    def gearbox_efficiency(self) -> np.ndarray:
        """Gearbox efficiency η of each joint's motor, shape (n,)."""
        return self._per_joint("gearbox_efficiency")

    @property
    def voltage(self) -> np.ndarray:
        """Supply voltage of each joint's motor's figures, shape (n,), V."""
        return self._per_joint("voltage")

    @property
    def regeneration(self) -> np.ndarray:
        """Whether each joint's motor returns negative power to the supply, shape (n,), bool."""
        return np.array([m.regeneration for m in self.motors])

    def _columns(self, method: Callable[[Actuator], Callable[..., np.ndarray]],
                 *arrays: np.ndarray) -> np.ndarray:
        """Apply each class's actuator method to its joints' columns (last axis, n)."""
        n = len(self.joint_names)
        if arrays[0].ndim == 0 or arrays[0].shape[-1] != n:
            raise InvalidParameterError("tau", f"array of shape {arrays[0].shape}",
                                        f"a last axis of {n} joints, {self.joint_names}")
        out = np.empty(arrays[0].shape)
        kinds = np.array(self.joint_classes)
        for kind, motor in self.by_class:
            cols = kinds == kind
            out[..., cols] = method(motor)(*(a[..., cols] for a in arrays))
        return out

    def current(self, tau: ArrayLike) -> np.ndarray:
        """Winding current, each joint's actuator's ``current``; ``tau`` (..., n) N·m → A."""
        t, _ = as_torque_speed(tau, np.zeros(np.shape(tau)))
        return self._columns(lambda m: m.current, t)

    def joule_power(self, tau: ArrayLike) -> np.ndarray:
        """Joule loss, each joint's actuator's ``joule_power``; ``tau`` (..., n) N·m → W."""
        t, _ = as_torque_speed(tau, np.zeros(np.shape(tau)))
        return self._columns(lambda m: m.joule_power, t)

    def electrical_power(self, tau: ArrayLike, qdot: ArrayLike,
                         regeneration: bool | None = None) -> np.ndarray:
        """Electrical power per joint (each joint's actuator's ``electrical_power``).

        Args:
            tau: Joint torques, shape (..., n), N·m.
            qdot: Joint speeds, the shape of ``tau``, rad/s.
            regeneration: Whether negative power returns to the supply on every joint; ``None``
                uses each actuator's own ``regeneration``.

        Returns:
            Electrical power, the shape of ``tau``, W.
        """
        t, w = as_torque_speed(tau, qdot)
        return self._columns(
            lambda m: lambda a, b: m.electrical_power(a, b, regeneration=regeneration), t, w)

    @property
    def source(self) -> str:
        """Each motor's source, by class."""
        return " · ".join(f"{c}: {m.source}" for c, m in self.by_class)

    @property
    def notes(self) -> str:
        """Each motor's notes, by class (empty when none has notes)."""
        return " · ".join(f"{c}: {m.notes}" for c, m in self.by_class if m.notes)


def motor_classes(robot: Robot) -> dict[str, tuple[str, ...]]:
    """Every actuated joint of ``robot`` in one motor class: the leg joint classes
    (:attr:`~hexaleg.robot.model.Robot.joint_classes`), then each joint on no leg (an arm's, a
    torso's: :attr:`~hexaleg.robot.model.Robot.other_joints`) as a class of its own, named after
    the joint — its actuator is built from its own URDF limits."""
    return {**robot.joint_classes, **{j: (j,) for j in robot.other_joints}}


def class_motors(robot: Robot, named: Mapping[str, Motor], generic: str) -> Actuator:
    """The motor of every joint class of ``robot``: ``named`` ones, and for the others a generic
    actuator from the largest URDF effort and velocity limits of the class's joints
    (:func:`hexaleg.robot.motor.generic_actuator`, its assumptions in its notes). A joint on no
    leg is a class of its own (:func:`motor_classes`): its holding torque is drawn by an
    actuator sized from its own limits, not a leg's.

    Args:
        robot: The loaded robot (its joint classes and URDF limits).
        named: Joint class (or joint on no leg) → motor, for the classes that have one.
        generic: The name of the generic actuators.

    Returns:
        The one :class:`Motor` when every class gets the same, else the :class:`MotorSet`.

    Raises:
        UnknownNameError: ``named`` has a class the robot does not have.
        InvalidParameterError: a class without a motor whose URDF joints have no effort or
            velocity limit.
    """
    classes = motor_classes(robot)
    for kind in named:
        if kind not in classes:
            raise UnknownNameError(f"{robot.name}: motor joint class", kind, classes)
    motors: dict[str, Motor] = {}
    for kind, joints in classes.items():
        if kind in named:
            motors[kind] = named[kind]
            continue
        cols = [6 + robot.column(j) for j in joints]
        limits = {"effort": float(robot.model.effortLimit[cols].max()),
                  "velocity": float(robot.model.velocityLimit[cols].max())}
        for what, value in limits.items():
            if not (math.isfinite(value) and value > 0):
                raise InvalidParameterError(
                    f"{robot.name}: URDF {what} limit of joint class {kind!r} "
                    f"({', '.join(joints)})", value,
                    f"a finite number > 0 (the actuator's peak {what}; a limit of 0 or none "
                    "gives nothing to build a motor from): give these joints <limit "
                    f"{what}=\"…\"> in the URDF, or the class a catalogue motor (the "
                    f"description's motor = {{{kind} = \"…\"}}, hexaleg motors lists them)")
        motors[kind] = generic_actuator(limits["effort"], limits["velocity"], name=generic)
    if len(set(motors.values())) == 1:
        return next(iter(motors.values()))
    return MotorSet.per_class(classes, robot.joint_names, motors)
