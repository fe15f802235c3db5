"""The servos a legged robot really runs: torque feedforward + PD, or a position-only PD.

A servo is a geared DC motor driven by a voltage; with stall torque τ_s and no-load speed ω₀ the
torque it delivers is ``τ = u − D q̇``, with ``u`` the voltage expressed as a torque
(``u = K V / R``, limited to ``|u| ≤ τ_s`` by the supply) and ``D = τ_s/ω₀ = K²/R`` the back-EMF
damping — the ideal DC motor's torque–speed line (e.g. Verstraten et al., IEEE RA-L 1(1), 2016,
the model of :mod:`hexaleg.robot.motor`). The saturation of ``u`` is the actuator's torque–speed
envelope ``−τ_s − D q̇ ≤ τ ≤ τ_s − D q̇``. Two controllers command ``u``:

* ``"feedforward"``: ``u = τ_ff + kp (q_ref − q) + kd (q̇_ref − q̇) + D q̇`` — the analysis'
  motor torque τ_ff (:attr:`hexaleg.dynamics.prepare.Analysis.tau_motor`) plus joint PD, the
  back-EMF compensated (a current-controlled driver); unsaturated the joint gets
  ``τ = τ_ff + kp e + kd ė``;
* ``"position"``: ``u = kp (q_ref − q) + (D − kd) q̇`` — the voltage-mode P servo of most hobby
  hexapods (Dynamixel AX, hobby PWM servos): no feedforward, and with the default ``kd = D`` the
  only damping is the motor's own back-EMF, ``τ = kp e − D q̇``.

Gains from the servo model: ``kp = τ_s / θ_c`` with ``θ_c`` the compliance angle at which the
servo gives full torque — ROBOTIS AX-12/AX-18 e-manual, "Compliance Slope": default 32 steps of
0.29° (= 9.3°, :data:`COMPLIANCE`); the torque ramps from 0 to the torque limit over the slope —
and ``kd = D = τ_s/ω₀``. ``kp_scale``/``kd_scale`` scale them (sensitivity studies). τ_s, ω₀ (and
so the gains) may differ per joint: a motor whose ``stall_torque``/``no_load_speed`` are (nj,)
arrays broadcasts.

In MuJoCo each servo is a ``general`` actuator on its joint with force
``u = kp·ctrl − kp q + (D − kd) q̇`` clamped to ``±τ_s`` (``forcerange``), and the joint has
damping D: the control ``ctrl = q_ref + (τ_ff + kd q̇_ref)/kp`` (feedforward) or ``q_ref``
(position) is a function of time only, so whole runs are open-loop control sequences.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from hexaleg.checks import one_of, positive
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.trajectory import Motion
from hexaleg.simulation.mjcf import fmt

CONTROLLERS: tuple[str, ...] = ("feedforward", "position")
"""The controllers (module docstring), default first."""
BOTH = "both"
"""The servo of a robot that may run either controller: a design is judged under each, by the
worse (``[design] controller``, ``[codesign] controller``)."""
SERVOS: tuple[str, ...] = (BOTH, *CONTROLLERS)
"""What a design may be ranked under: :data:`BOTH` (the default) or one controller."""


def controllers_of(servo: str) -> tuple[str, ...]:
    """The controllers a design is simulated under for ``servo`` (one of :data:`SERVOS`): both
    for :data:`BOTH`, else the one named.

    Raises:
        UnknownNameError: not one of :data:`SERVOS` (lists them).
    """
    return CONTROLLERS if one_of("controller", servo, SERVOS) == BOTH else (servo,)
COMPLIANCE = float(np.deg2rad(32 * 0.29))
"""rad: joint error at which a servo gives its stall torque — the AX-12/AX-18 default compliance
slope of 32 steps × 0.29°."""


class ServoMotor(Protocol):
    """What the controllers need of a motor: a :class:`~hexaleg.robot.motor.Motor` or a set of
    per-joint motors (values then (nj,) arrays)."""

    @property
    def stall_torque(self) -> float | np.ndarray: ...

    @property
    def no_load_speed(self) -> float | np.ndarray: ...


@dataclass(frozen=True)
class Servo:
    """A servo's controller and gains (module docstring).

    Attributes:
        controller: One of :data:`CONTROLLERS`.
        compliance: θ_c, rad, > 0: the error at which the servo reaches its stall torque.
        kp_scale: Factor on kp = τ_s/θ_c, > 0.
        kd_scale: Factor on kd = τ_s/ω₀, > 0.

    Raises:
        UnknownNameError: an unknown controller (lists them).
        InvalidParameterError: a gain, scale or compliance ≤ 0.
    """

    controller: str = "feedforward"
    compliance: float = COMPLIANCE
    kp_scale: float = 1.0
    kd_scale: float = 1.0

    def __post_init__(self) -> None:
        one_of("controller", self.controller, CONTROLLERS)
        positive("compliance (rad)", self.compliance)
        positive("kp_scale", self.kp_scale)
        positive("kd_scale", self.kd_scale)

    def gains(self, motor: ServoMotor, nj: int) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                         np.ndarray]:
        """``(kp, kd, D, τ_s)`` per joint, each shape (nj,): N·m/rad, N·m·s/rad, N·m·s/rad, N·m.

        Raises:
            InvalidParameterError: a motor whose stall torque or no-load speed is not > 0 or
                not one value per joint.
        """
        try:
            stall = np.broadcast_to(np.asarray(motor.stall_torque, dtype=float), (nj,)).copy()
            speed = np.broadcast_to(np.asarray(motor.no_load_speed, dtype=float), (nj,)).copy()
        except ValueError:
            raise InvalidParameterError("motor stall_torque/no_load_speed",
                                        np.shape(motor.stall_torque),
                                        f"one value or {nj} (one per joint)") from None
        if not (np.all(stall > 0) and np.all(speed > 0)):
            raise InvalidParameterError("motor stall_torque/no_load_speed",
                                        (stall.tolist(), speed.tolist()), "> 0")
        damping = stall / speed
        return stall / self.compliance * self.kp_scale, damping * self.kd_scale, damping, stall


def servo_xml(joints: tuple[str, ...], kp: np.ndarray, kd: np.ndarray, damping: np.ndarray,
              stall: np.ndarray) -> str:
    """The servo actuators, one ``<general>`` per joint in ``joints`` order (module docstring).

    Args:
        joints: Joint names, nj.
        kp: Position gains, (nj,), N·m/rad.
        kd: Velocity gains, (nj,), N·m·s/rad.
        damping: Back-EMF damping D, (nj,), N·m·s/rad (the joint's own damping).
        stall: Stall torques τ_s, (nj,), N·m.
    """
    return "\n".join(
        f'<general name="{j}_servo" joint="{j}" gainprm="{fmt(kp[i])}" biastype="affine" '
        f'biasprm="{fmt([0.0, -kp[i], damping[i] - kd[i]])}" ctrllimited="false" '
        f'forcelimited="true" forcerange="{fmt([-stall[i], stall[i]])}"/>'
        for i, j in enumerate(joints))


@dataclass(frozen=True)
class Reference:
    """The planned joint motion and feedforward torque at the simulation's instants.

    Attributes:
        q: Joint angles, shape (n, nj), rad.
        qdot: Joint velocities, shape (n, nj), rad/s.
        tau: Feedforward motor torques, shape (n, nj), N·m.
    """

    q: np.ndarray
    qdot: np.ndarray
    tau: np.ndarray


def reference(motion: Motion, tau_motor: np.ndarray, t: np.ndarray) -> Reference:
    """The periodic motion's joints at times ``t``: cubic Hermite interpolation of the sampled
    angles with their exact velocities as slopes (Hermite's ``h00 … h11`` basis), its derivative
    as the velocity, and the analysis' torques interpolated linearly.

    Args:
        motion: A periodic motion (its samples one period, endpoint excluded).
        tau_motor: Motor torques of the motion's samples, shape (T, nj), N·m.
        t: Times, shape (n,), s (any: the motion repeats).

    Raises:
        InvalidParameterError: the motion is not periodic.
    """
    if not motion.periodic:
        raise InvalidParameterError("motion.periodic", False, "a periodic motion (a gait)")
    h, n = motion.dt, motion.n_samples
    x = np.asarray(t, dtype=float) / h
    k0 = np.floor(x).astype(int)
    s = (x - k0)[:, None]
    k0 %= n
    k1 = (k0 + 1) % n
    q, v = motion.q[:, 7:], motion.v[:, 6:]
    if q.shape[1] != v.shape[1]:
        raise InvalidParameterError("motion", "continuous joints", "revolute or prismatic joints")
    h00, h10, h01, h11 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s, -2 * s**3 + 3 * s**2, \
        s**3 - s**2
    d00, d10, d01, d11 = 6 * s**2 - 6 * s, 3 * s**2 - 4 * s + 1, -6 * s**2 + 6 * s, 3 * s**2 - 2 * s
    qr = h00 * q[k0] + h10 * h * v[k0] + h01 * q[k1] + h11 * h * v[k1]
    vr = (d00 * q[k0] + d10 * h * v[k0] + d01 * q[k1] + d11 * h * v[k1]) / h
    tau = np.asarray(tau_motor, dtype=float)
    return Reference(qr, vr, (1 - s) * tau[k0] + s * tau[k1])


def controls(servo: Servo, ref: Reference, kp: np.ndarray, kd: np.ndarray,
             torques: bool = False) -> np.ndarray:
    """The servo actuators' controls at the reference's instants, shape (n, nj):
    ``q_ref + (τ_ff + kd q̇_ref)/kp`` (feedforward) or ``q_ref`` (position); with ``torques``
    a position servo's reference holds the plan's torque too, ``q_ref + τ_ff/kp`` — the static
    compensation of a compliant joint (Tomei, "A simple PD controller for robots with elastic
    joints", IEEE Trans. Automatic Control 36(10), 1991: the set point ``q* + K⁻¹ g(q*)``, here
    ``K = kp`` and the load the plan's motor torque), which a host computing the servos'
    positions sends at every servo update as it sends the angles
    (:mod:`hexaleg.simulation.balance`, "Deflection"). Its back-EMF lag ``D q̇/kp`` is left:
    the position servo's own tracking error."""
    if servo.controller == "position":
        return ref.q + ref.tau / kp if torques else ref.q.copy()
    return ref.q + (ref.tau + kd * ref.qdot) / kp
