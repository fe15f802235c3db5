"""Whole-robot inverse dynamics, springs, foot forces and motor energy: ``prepare`` → ``evaluate``.

For every sample of a :class:`~hexaleg.motion.trajectory.Motion`, Pinocchio's RNEA gives
``b = M(q) a + C(q, v) v + g(q)`` and the stance feet's Jacobians ``J_i`` (3 × nv, world-aligned).
With world foot forces ``f_i``, spring torques ``τ_s`` and motor torques ``τ_m`` the equations of
motion split into the base rows and the joint rows::

    b_base  = Σ_i J_base,iᵀ f_i                          (6 rows: the whole robot's Newton–Euler)
    τ_m     = b_joint − Σ_i J_joint,iᵀ f_i − τ_s          (18 rows)

Everything that does not depend on the springs — RNEA, Jacobians, the stance system and the
quadratic program's gains — is computed once by :func:`prepare`; :meth:`Prepared.evaluate` then
only evaluates the spring torques and re-solves the forces (:mod:`hexaleg.dynamics.solver`), into
an :class:`~hexaleg.dynamics.analysis.Analysis`. A motion with ``fixed_base=True`` (the paper's
single joint) has no contacts: the fixture carries the base rows and ``τ_m = b_joint − τ_s``.
The same holds at the ``Motion.supported`` samples of any motion (the body resting on the ground
while the legs fold): the support supplies ``b_base``, so the base rows there read 0 = 0, no foot
carries load and ``τ_m = b_joint − τ_s``.

On an inclined ground (``Motion.normal``) the stance system's force columns are turned into the
contact frame (:func:`hexaleg.dynamics.contact.contact_frame`: z along the ground's normal), so
the same force program puts the friction cones about the normal; the forces come back to the
world frame in :meth:`Prepared.solve` (``StanceSystem.to_world``).
"""

from __future__ import annotations

import dataclasses
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg.checks import typed
from hexaleg.dynamics import energy
from hexaleg.dynamics.analysis import Analysis
from hexaleg.dynamics.batched import WarmStart
from hexaleg.dynamics.contact import (
    ContactParams,
    StanceSystem,
    check_ground_friction,
    check_objective,
    contact_frame,
)
from hexaleg.dynamics.inertia import apparent_inertias
from hexaleg.dynamics.nearest import WrenchResidual, nearest_wrench
from hexaleg.dynamics.solver import QuadraticGains, quadratic_gains, solve_fast
from hexaleg.errors import HexalegWarning, InvalidParameterError, TorqueLimitError
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.actuator import Actuator
from hexaleg.robot.catalogue import motor as motor_by_name
from hexaleg.robot.model import Robot
from hexaleg.robot.motor_set import MotorSet
from hexaleg.robot.springs import Spring, SpringSet
from hexaleg.units import G

SpringsLike = SpringSet | Mapping[str, Spring] | None
SPRING_TORQUE_BOUND = 1000.0
"""A spring may push at most this many times its joint's stall torque along the motion: more is a
value in the wrong unit (a stiffness of 1e300 N·m/rad ended as a contact-force error)."""


def _as_motor(motor: Actuator | str | None, robot: Robot) -> Actuator:
    if motor is None:
        return motor_by_name()
    if isinstance(motor, str):
        return motor_by_name(motor)
    if not isinstance(motor, Actuator):
        raise InvalidParameterError("motor", motor, "a hexaleg.Motor, a MotorSet or a catalogue "
                                    "name")
    if isinstance(motor, MotorSet) and motor.joint_names != robot.joint_names:
        # a set is built for named joints: the same count in another order is another robot's
        raise InvalidParameterError("motor joints", motor.joint_names,
                                    f"the joints of {robot.name}, {robot.joint_names}")
    motor.joint_labels(robot.nj)  # an actuator built for another number of joints: named
    return motor


def _as_springs(springs: SpringsLike) -> SpringSet:
    if springs is None:
        return SpringSet()
    return springs if isinstance(springs, SpringSet) else SpringSet(springs)


@dataclass(eq=False)
class Prepared:
    """The spring-independent part of the analysis of one motion (see :func:`prepare`).

    :meth:`baseline` caches the metrics of the motion without springs — "baseline" is the one
    name for that analysis, which :meth:`evaluate` compares every spring design against.

    Attributes:
        robot: The robot.
        motion: The motion.
        motor: The servo model of every joint, or one per joint (a MotorSet).
        contact: Contact settings.
        rnea: ``M a + h`` at every sample, shape (T, nv).
        jacobians: Foot Jacobians (world-aligned, linear part), shape (T, n_legs, 3, nv).
        system: The force program's linear algebra (:class:`hexaleg.dynamics.contact.StanceSystem`).
        q: Joint angles, shape (T, nj), rad.
        qdot: Joint velocities, shape (T, nj), rad/s.
        residual: For a logged motion (:func:`hexaleg.load_motion`), the base wrench its
            contacts could not produce where the forces were solved for the nearest one
            (:mod:`hexaleg.dynamics.nearest`); None for a generated motion.
    """

    robot: Robot
    motion: Motion
    motor: Actuator
    contact: ContactParams
    rnea: np.ndarray
    jacobians: np.ndarray
    system: StanceSystem
    q: np.ndarray
    qdot: np.ndarray
    residual: WrenchResidual | None = None
    _gains: dict[str, QuadraticGains] = field(default_factory=dict, repr=False)
    _warm: dict[str, WarmStart] = field(default_factory=dict, repr=False)
    _warm_baseline: dict[str, WarmStart] = field(default_factory=dict, repr=False)
    _baseline: dict[str, dict[str, Any]] = field(default_factory=dict, repr=False)
    _inertia: np.ndarray | None = field(default=None, repr=False)

    def weights(self, objective: str) -> np.ndarray:
        """Per-joint weights of the objective: Joule coefficients, or ones for Σ τ²; (nj,)."""
        if objective == "torque_squared":
            return np.ones(self.robot.nj)
        return np.full(self.robot.nj, self.motor.joule_coefficient)

    def gains(self, objective: str) -> QuadraticGains:
        """The quadratic program's gains for ``objective``, computed once and cached."""
        if objective not in self._gains:
            self._gains[objective] = quadratic_gains(self.system, self.weights(objective))
        return self._gains[objective]

    def spring_torques(self, springs: SpringsLike) -> np.ndarray:
        """Spring torques on the joints along the motion, shape (T, nj), N·m."""
        s = _as_springs(springs)
        if not len(s):
            return np.zeros_like(self.q)
        return s.torques(self.robot, self.motion.q, self.motion.v)

    def _check_spring_torques(self, springs: SpringSet, tau_spring: np.ndarray) -> None:
        """Refuse springs whose torque along the motion is not finite or over
        :data:`SPRING_TORQUE_BOUND` times the joint's stall torque, naming the joint and its
        spring (a stiffness in the wrong unit ends here, not as a contact-force error)."""
        if not len(springs):
            return
        stall = np.broadcast_to(np.asarray(getattr(self.motor, "stall_torque", np.inf),
                                           dtype=float), (tau_spring.shape[1],))
        peak = np.max(np.abs(np.nan_to_num(tau_spring, nan=np.inf)), axis=0)
        bad = np.flatnonzero(~(peak <= SPRING_TORQUE_BOUND * stall))
        if bad.size:
            j = int(bad[np.argmax(peak[bad] / stall[bad])])
            name = self.robot.joint_names[j]
            raise InvalidParameterError(
                f"springs[{name!r}]", springs[name] if name in springs else None,
                f"a spring whose torque along the motion stays finite and within "
                f"{SPRING_TORQUE_BOUND:g} × the joint's stall torque ({stall[j]:.3g} N·m); it "
                f"reaches {peak[j]:.3g} N·m — a stiffness or torque in the wrong unit?")

    def solve(self, tau_spring: np.ndarray, objective: str = "joule"
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Foot forces and motor torques for given spring torques (the sweep's inner step).

        Args:
            tau_spring: Spring torques, shape (T, nj), N·m.
            objective: Force-distribution objective.

        Returns:
            ``(forces (T, n_legs, 3) N, tau_motor (T, nj) N·m, resolved (T,) bool)``.
        """
        check_objective(objective)
        T, n_legs = self.system.stance.shape
        if self.motion.fixed_base:
            tau = self.system.b_joint - tau_spring
            if self.contact.torque_limits:
                over = np.abs(tau) > self.system.tau_max
                if over.any():
                    k, j = np.argwhere(over)[0]
                    raise TorqueLimitError(
                        f"motor torque limit exceeded at t = {self.motion.t[k]:.4f} s: joint "
                        f"{self.robot.joint_names[j]} needs τ = {tau[k, j]:+.4f} N·m "
                        f"(limit ±{self.system.tau_max[j]:.4f} N·m). {self._limit_hint()}")
            return np.zeros((T, n_legs, 3)), tau, np.zeros(T, dtype=bool)
        try:
            f, tau, resolved = solve_fast(self.system, tau_spring, objective,
                                          self.weights(objective), self.contact,
                                          warm=self._warm.setdefault(objective, WarmStart()))
        except TorqueLimitError as exc:
            raise TorqueLimitError(f"{exc}. {self._limit_hint()}") from None
        return self.system.to_world(f).reshape(T, n_legs, 3), tau, resolved

    def _limit_hint(self) -> str:
        """Where the torque limits come from and what to change, for TorqueLimitError."""
        return (f"The limits are the stall torques of the motor {self.motor.name}; fit a "
                "stronger one (motor = \"…\" in the robot description, a catalogue name of "
                "`hexaleg motors`), ask less of it (a longer period, a shorter stride_length, "
                "springs), or analyse without limits (ContactParams(torque_limits=False), "
                "[contact] torque_limits = false)")

    def metrics(self, tau_motor: np.ndarray) -> dict[str, Any]:
        """:func:`hexaleg.dynamics.energy.metrics` of motor torques ``tau_motor`` (T, nj) on this
        motion (cost of transport when it travels; end samples weighted for a non-periodic
        motion)."""
        distance = self.motion.distance if self.motion.distance > 0 else None
        return energy.metrics(tau_motor, self.qdot, self.motion.dt, self.motor,
                              mass=self.robot.mass if distance else None, distance=distance,
                              joint_names=self.robot.joint_names,
                              periodic=self.motion.periodic, inertia=self.inertia)

    @property
    def inertia(self) -> np.ndarray:
        """Moment of inertia about each joint's axis of everything distal to it, at the motion's
        mean posture (:func:`hexaleg.dynamics.inertia.apparent_inertias`), shape (nj,), kg·m² —
        eq. 24's I for the ε of :meth:`metrics`."""
        if self._inertia is None:
            self._inertia = apparent_inertias(self.robot, self.motion)
        return self._inertia

    def baseline(self, objective: str = "joule") -> dict[str, Any]:
        """Metrics of the motion with no springs (the baseline), computed once per objective and
        cached."""
        if objective not in self._baseline:
            _, tau, _ = self.solve(np.zeros_like(self.q), objective)
            self._baseline[objective] = self.metrics(tau)
            if objective in self._warm:
                self._warm_baseline[objective] = self._warm[objective].copy()
        return self._baseline[objective]

    def reset_warm_start(self, objective: str = "joule") -> None:
        """Start the next solve of ``objective`` from the active sets of the baseline (or cold,
        before the baseline is computed) instead of the last solve's.

        A solve starts from the last one's active sets (the warm start of a sweep,
        :class:`~hexaleg.dynamics.batched.WarmStart`): the forces agree to rounding whatever
        the start, but not always to the last bit. A sweep resets at the start of every chunk
        of points, so that a chunk's rows are the same bits in any process and any order.
        """
        if objective in self._warm_baseline:
            self._warm[objective] = self._warm_baseline[objective].copy()
        else:
            self._warm.pop(objective, None)

    def evaluate(self, springs: SpringsLike = None, objective: str = "joule") -> Analysis:
        """Analyse the motion with ``springs``.

        Args:
            springs: Joint name → spring (SI), a :class:`~hexaleg.robot.springs.SpringSet`, or None.
            objective: Force-distribution objective, one of
                :data:`hexaleg.dynamics.contact.OBJECTIVES`.

        Returns:
            The analysis.

        Raises:
            UnknownNameError: a spring on a joint the robot does not have (lists the joints).
            InvalidParameterError: unknown objective.
            InfeasibleForcesError: no contact forces at some sample (names time and feet).
            TorqueLimitError: a motor torque limit cannot be met (names joint, time, torque).
        """
        check_objective(objective)
        s = _as_springs(springs)
        tau_s = self.spring_torques(s)
        self._check_spring_torques(s, tau_s)
        forces, tau_m, resolved = self.solve(tau_s, objective)
        metrics = self.metrics(tau_m)
        baseline = self.baseline(objective)
        return Analysis(robot=self.robot, motion=self.motion, springs=s, motor=self.motor,
                        objective=objective, contact=self.contact, t=self.motion.t, q=self.q,
                        qdot=self.qdot, forces=forces, tau_motor=tau_m, tau_spring=tau_s,
                        resolved=resolved,
                        metrics=metrics, baseline=baseline,
                        savings=energy.savings(metrics, baseline))


@typed
def prepare(robot: Robot, motion: Motion, *, motor: Actuator | str | None = None,
            contact: ContactParams | None = None) -> Prepared:
    """Compute everything about ``motion`` that does not depend on the springs.

    Args:
        robot: The robot the motion was made for.
        motion: The motion (q, v, a in Pinocchio conventions; stance flags).
        motor: The servo of every joint: a :class:`~hexaleg.robot.motor.Motor`, a catalogue name,
            a :class:`~hexaleg.robot.motor_set.MotorSet` (one motor per joint) or None for
            :data:`hexaleg.robot.catalogue.DEFAULT_MOTOR`.
        contact: Contact settings (friction, cone, minimum normal force, torque limits — each
            joint's limit is its motor's stall torque).

    Returns:
        The prepared analysis; call :meth:`Prepared.evaluate` with springs.

    Raises:
        InvalidParameterError: the motion does not fit the robot.
        InfeasibleForcesError: a periodic motion on a ground steeper than the friction allows,
            ``tan γ > μ`` (:func:`hexaleg.dynamics.contact.check_ground_friction`).
    """
    model, data = robot.model, robot.data
    T = motion.n_samples
    if motion.q.shape[1] != model.nq or motion.v.shape[1] != model.nv:
        raise InvalidParameterError("motion", f"q {motion.q.shape}, v {motion.v.shape}",
                                    f"q (T, {model.nq}) and v (T, {model.nv}) for {robot.name}")
    n_legs = len(robot.legs)
    if motion.stance.shape != (T, n_legs):
        raise InvalidParameterError("motion.stance", motion.stance.shape, f"(T, {n_legs})")
    rnea = np.empty((T, model.nv))
    jac = np.zeros((T, n_legs, 3, model.nv))
    frames = [leg.foot_frame_id for leg in robot.legs]
    lwa = pin.ReferenceFrame.LOCAL_WORLD_ALIGNED
    for k in range(T):
        rnea[k] = pin.rnea(model, data, motion.q[k], motion.v[k], motion.a[k])
        if motion.supported[k] or not motion.stance[k].any():
            continue
        pin.computeJointJacobians(model, data, motion.q[k])
        pin.updateFramePlacements(model, data)
        for i, fid in enumerate(frames):
            if motion.stance[k, i]:
                jac[k, i] = pin.getFrameJacobian(model, data, fid, lwa)[:3]
    # Padded stance system: column block 3i:3i+3 is leg i; swing legs' blocks are zero.
    contact = contact or ContactParams()
    frame = None
    if motion.normal is not None:  # forces in the contact frame: cones about the ground normal
        if motion.periodic:
            check_ground_friction(motion.normal, contact)
        frame = contact_frame(motion.normal)
        jt = np.einsum("tlkv,kj->tvlj", jac, frame).reshape(T, model.nv, 3 * n_legs)
    else:
        jt = np.transpose(jac, (0, 3, 1, 2)).reshape(T, model.nv, 3 * n_legs)  # (T, nv, 3 n_legs)
    motor = _as_motor(motor, robot)
    # Each joint's servo stall torque limits it (the URDF's effort limits are those of the robot's
    # nominal servo, which the user may be replacing; a generic actuator is built from them).
    tau_max = np.broadcast_to(np.asarray(motor.stall_torque, dtype=float), (robot.nj,)).copy()
    system = StanceSystem(stance=motion.stance.astype(bool), A=jt[:, :6], D=jt[:, 6:],
                          b_base=np.where(motion.supported[:, None], 0.0, rnea[:, :6]),
                          b_joint=rnea[:, 6:], qdot=motion.v[:, 6:],
                          tau_max=tau_max, t=motion.t, leg_names=robot.leg_names,
                          joint_names=robot.joint_names,
                          efficiency=np.broadcast_to(motor.gearbox_efficiency, (robot.nj,)).copy(),
                          frame=frame)
    residual = None
    if motion.info.get("source") == "load_motion":  # a measurement: the nearest wrench
        b_base, residual = nearest_wrench(system.A, system.b_base, system.stance, contact.mu,
                                          contact.min_normal_force, robot.mass * G,
                                          motion.t)
        system = dataclasses.replace(system, b_base=b_base)
        line = residual.line()
        if line is not None:
            warnings.warn(f"{motion.info.get('log', 'motion log')}: {line}", HexalegWarning,
                          stacklevel=2)
    return Prepared(robot=robot, motion=motion, motor=motor, contact=contact,
                    rnea=rnea, jacobians=jac, system=system, q=motion.q[:, 7:],
                    qdot=motion.v[:, 6:], residual=residual)


@typed
def analyze(robot: Robot, motion: Motion, springs: SpringsLike = None, *,
            motor: Actuator | str | None = None, objective: str = "joule",
            contact: ContactParams | None = None) -> Analysis:
    """Analyse ``motion`` with ``springs``: ``prepare(robot, motion, …).evaluate(springs, …)``.

    Args:
        robot: The robot.
        motion: The motion.
        springs: Joint name → spring, e.g.
            ``{"LF_femur": hexaleg.DeadZoneSpring(stiffness=2.0, theta_k=0.13)}`` (SI), or None.
        motor: Servo of every joint (Motor, MotorSet, catalogue name, or None for the
            default).
        objective: Force-distribution objective (:data:`hexaleg.dynamics.contact.OBJECTIVES`;
            default ``"joule"``).
        contact: Contact settings.

    Returns:
        The analysis: forces (T, n_legs, 3), tau_motor / tau_spring / power (T, nj), metrics.
    """
    check_objective(objective)
    return prepare(robot, motion, motor=motor, contact=contact).evaluate(springs, objective)
