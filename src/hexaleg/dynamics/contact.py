"""The force program of the stance feet: contact settings, objectives and the stance system.

The motion fixes ``b = M(q) a + h(q, v)`` (RNEA) at every sample, but not how the stance feet share
the load: with 3 feet there are 9 force components against the 6 base equations. For each sample
hexaleg picks the world-frame foot forces ``f`` (3 per stance foot) that solve::

    minimise   E(τ)                                   (the motor-energy objective below)
    subject to J_baseᵀ f = b_base                     (6 base rows: Newton–Euler of the robot)
               τ = b_joint − J_jointᵀ f − τ_spring    (joint rows: the motor torques)
               ‖(f_x, f_y)‖ ≤ μ f_z                    (Coulomb friction cone; or the inscribed
                                                        pyramid |f_x|, |f_y| ≤ μ f_z / √2)
               f_z ≥ f_min                            (unilateral contact, minimum normal force)
               |τ| ≤ τ_max                             (optional motor torque limits)

The samples are independent (the objective is a sum over time), so the program separates into one
small problem per sample. Objectives, all convex in ``f`` because ``τ`` is affine in ``f``:

- ``"joule"`` (default): Joule losses Σ_j c_j τ_j², ``c_j = R/(k_t G)²`` of joint j's motor. It is
  what a servo robot mostly spends (Seok et al., IEEE/ASME T-Mech 2013: 76 % of the MIT Cheetah's
  energy is motor heat), it is strictly convex (a unique answer) and it admits the exact fast path.
- ``"torque_squared"``: Σ_j τ_j² (identical forces to ``"joule"`` when every joint has the same
  motor).
- ``"electrical"``: electrical energy without regeneration
  Σ_j max(0, max(τ_j q̇_j / η, η τ_j q̇_j) + c_j τ_j²) + ε Σ_j τ_j² — the servo model of
  :meth:`hexaleg.robot.motor.Motor.electrical_power` (gearbox efficiency η by power-flow direction,
  Verstraten et al., RA-L 1(1) 2016; "positive electrical work" of Yesilevskiy & Remy, J.
  Mechanisms Robotics 10(3) 031008); the max is flat while a joint regenerates, so the same small
  regulariser ε makes the answer unique.
- ``"positive_work"``: positive mechanical work Σ_j max(0, τ_j q̇_j) + ε Σ_j τ_j²; the small
  regulariser ε makes the answer unique (same source).

This module holds the definitions both solvers share: :mod:`hexaleg.dynamics.solver` (the fast
exact path) and :mod:`hexaleg.dynamics.reference` (cvxpy, the reference of the tests).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hexaleg.checks import named_arguments, positive, real
from hexaleg.errors import InfeasibleForcesError, InvalidParameterError

OBJECTIVES: tuple[str, ...] = ("joule", "torque_squared", "electrical", "positive_work")
"""Names of the motor-energy objectives, default first."""
QUADRATIC_OBJECTIVES: tuple[str, ...] = ("joule", "torque_squared")
"""The objectives quadratic in τ, which admit the exact fast path
(:class:`hexaleg.dynamics.solver.QuadraticGains`)."""
CONES: tuple[str, ...] = ("soc", "pyramid")
"""Friction models: the exact second-order cone, or the inscribed (inner) linear pyramid."""


@named_arguments
@dataclass(frozen=True)
class ContactParams:
    """Contact and force-distribution settings.

    Attributes:
        mu: Coulomb friction coefficient, > 0 (default 0.6: rubber foot on a hard floor, assumed).
        cone: ``"soc"`` (exact cone) or ``"pyramid"`` (inscribed pyramid, an inner approximation).
        min_normal_force: Smallest normal force of a stance foot, N, ≥ 0.
        torque_limits: Constrain |τ_motor| to each joint's motor stall torque (the actuator
            the analysis uses: a catalogue motor, or a generic actuator built from the
            URDF effort limits).
        regularization: ε of the ``"positive_work"`` objective, W/(N·m)², > 0.
    """

    mu: float = 0.6
    cone: str = "soc"
    min_normal_force: float = 0.0
    torque_limits: bool = True
    regularization: float = 1e-4

    def __post_init__(self) -> None:
        # A bool is not a friction coefficient (mu=True is refused, not read as 1).
        positive("ContactParams.mu", self.mu)
        real("ContactParams.min_normal_force", self.min_normal_force, low=0.0,
             allowed="a finite number >= 0 N")
        positive("ContactParams.regularization", self.regularization)
        if not isinstance(self.torque_limits, bool):
            raise InvalidParameterError("ContactParams.torque_limits", self.torque_limits,
                                        "True or False")
        if self.cone not in CONES:
            raise InvalidParameterError("ContactParams.cone", self.cone, " or ".join(CONES))


def check_objective(objective: str) -> str:
    """Return ``objective`` if it is one of :data:`OBJECTIVES`.

    Raises:
        InvalidParameterError: otherwise; the message lists the objectives.
    """
    if objective not in OBJECTIVES:
        raise InvalidParameterError("objective", objective, "one of " + ", ".join(OBJECTIVES))
    return objective


@dataclass(frozen=True, eq=False)
class StanceSystem:
    """The spring-independent linear algebra of one motion, for the force program.

    Force vectors are padded to all legs: ``f`` has shape (T, 3 n_legs) with leg ``i``'s world
    force at ``f[:, 3i:3i+3]``; swing legs' columns of ``A`` and ``D`` are zero and their forces are
    zero.

    Attributes:
        stance: Stance mask, shape (T, n_legs), bool.
        A: Base rows ``J_baseᵀ``, shape (T, 6, 3 n_legs).
        D: Joint rows ``J_jointᵀ``, shape (T, nj, 3 n_legs).
        b_base: Base rows of ``M a + h``, shape (T, 6).
        b_joint: Joint rows of ``M a + h``, shape (T, nj), N·m.
        qdot: Joint velocities, shape (T, nj), rad/s.
        tau_max: Motor torque limits, shape (nj,), N·m.
        t: Sample times, shape (T,), s (for error messages).
        leg_names: Leg names, for error messages.
        joint_names: Joint names, for error messages.
        efficiency: Gearbox efficiency η of each joint's motor, shape (nj,) or a scalar for
            all, in (0, 1] (``"electrical"`` objective).
        frame: The contact frame on an inclined ground (:func:`contact_frame`), shape (3, 3),
            or None on level ground. When given, the force columns of ``A`` and ``D`` act on
            each foot's force in this frame (``f_world = frame @ f``, normal along its z), so the
            program's cones about z are the cones about the ground's normal; every solver's
            forces are in this frame and :meth:`to_world` takes them back.
    """

    stance: np.ndarray
    A: np.ndarray
    D: np.ndarray
    b_base: np.ndarray
    b_joint: np.ndarray
    qdot: np.ndarray
    tau_max: np.ndarray
    t: np.ndarray
    leg_names: tuple[str, ...]
    joint_names: tuple[str, ...]
    efficiency: float | np.ndarray = 1.0
    frame: np.ndarray | None = None

    @property
    def n_samples(self) -> int:
        return int(self.stance.shape[0])

    def to_world(self, f: np.ndarray) -> np.ndarray:
        """Forces ``f`` (T, 3 n_legs) of the program in the world frame, same shape, N."""
        if self.frame is None:
            return f
        return (f.reshape(*f.shape[:-1], -1, 3) @ self.frame.T).reshape(f.shape)

    def torques(self, f: np.ndarray, tau_spring: np.ndarray,
                rows: np.ndarray | slice = slice(None)) -> np.ndarray:
        """Motor torques ``b_joint − D f − τ_spring`` of samples ``rows``, for their forces ``f``
        (T', 3 n_legs) and spring torques (T', nj); shape (T', nj), N·m."""
        return self.b_joint[rows] - (self.D[rows] @ f[..., None])[..., 0] - tau_spring


def violations(system: StanceSystem, f: np.ndarray, tau: np.ndarray, contact: ContactParams,
               tol: float = 1e-9) -> np.ndarray:
    """Which samples' forces/torques break an inequality of the program, shape (T,), bool.

    Args:
        system: The motion's stance system.
        f: Forces, shape (T, 3 n_legs), N.
        tau: Motor torques, shape (T, nj), N·m.
        contact: Contact settings (friction cone, minimum normal force, torque limits).
        tol: Slack allowed on every inequality, N or N·m.
    """
    T, n_legs = system.stance.shape
    f3 = f.reshape(T, n_legs, 3)
    fz = f3[..., 2]
    st = system.stance
    bad = np.any(st & (fz < contact.min_normal_force - tol), axis=1)
    if contact.cone == "soc":
        slack = contact.mu * fz - np.hypot(f3[..., 0], f3[..., 1])
    else:
        slack = contact.mu / math.sqrt(2) * fz - np.maximum(np.abs(f3[..., 0]), np.abs(f3[..., 1]))
    bad |= np.any(st & (slack < -tol), axis=1)
    if contact.torque_limits:
        bad |= np.any(np.abs(tau) > system.tau_max + tol, axis=1)
    return bad


def contact_frame(normal: np.ndarray) -> np.ndarray:
    """The contact frame of a ground with unit normal ``normal`` (3,): the rotation that turns
    ẑ onto it about ``ẑ × n`` (Rodrigues' formula, ``R = I + [k]× + [k]×² (1 − c) / s²`` with
    ``k = ẑ × n``, s = |k|, c = n_z; Murray, Li & Sastry, *A Mathematical Introduction to Robotic
    Manipulation*, 1994, eq. 2.14); its columns are two tangents and the normal, (3, 3)."""
    n = np.asarray(normal, dtype=float)
    k = np.array([-n[1], n[0], 0.0])
    s2, c = float(k @ k), float(n[2])
    if s2 < 1e-30:
        return np.eye(3)
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + kx + kx @ kx * ((1.0 - c) / s2)


def check_ground_friction(normal: np.ndarray | None, contact: ContactParams) -> None:
    """Refuse a ground steeper than friction allows, before any force program runs.

    Over a cycle of a periodic motion the contact forces average to ``−m g`` (the CoM's
    momentum is periodic: Newton's second law integrated over the cycle). Its component along
    the ground is ``m g sin γ`` and across it ``m g cos γ`` (γ the ground's inclination), and
    feet inside their cones (``|f_t| ≤ μ f_n``) sum to at most ``μ Σ f_n`` tangentially, so a
    periodic gait on that ground needs ``μ ≥ tan γ`` — at every instant on average.

    Args:
        normal: The ground's unit normal (world), or None (level ground: nothing to check).
        contact: The contact settings (μ).

    Raises:
        InfeasibleForcesError: ``tan γ > μ``; names γ, tan γ, μ and what to change.
    """
    if normal is None:
        return
    n_z = float(normal[2])
    tan = math.sqrt(max(0.0, 1.0 - n_z * n_z)) / n_z
    if tan > contact.mu:
        raise InfeasibleForcesError(
            f"the ground is inclined by γ = {math.degrees(math.acos(n_z)):.3g}° and the "
            f"friction allows at most atan μ = {math.degrees(math.atan(contact.mu)):.3g}°: "
            f"tan γ = {tan:.4g} > μ = {contact.mu:g}. Over a cycle the feet must push the "
            "weight, whose component along the ground needs μ ≥ tan γ; raise ContactParams.mu "
            f"([contact] mu) to ≥ {tan:.4g} or walk a gentler slope (GaitParams.slope, "
            "cross_slope)")


def friction_usage(forces: np.ndarray, stance: np.ndarray, mu: float,
                   normal: np.ndarray | None = None) -> np.ndarray:
    """Load of the Coulomb friction cone ``|f_t| / (μ f_n)`` of every foot, the cone about the
    ground's normal n: ``f_n = f · n``, ``f_t = f − f_n n``.

    Args:
        forces: World-frame foot forces, shape (T, n_legs, 3), N.
        stance: Stance flags, shape (T, n_legs), bool.
        mu: Friction coefficient, > 0.
        normal: The ground's unit normal, shape (3,); None: level ground, ``[0, 0, 1]``.

    Returns:
        Shape (T, n_legs), 1: 0 for swing feet and for stance feet without normal force, 1 on
        the cone's surface (the foot is about to slip).
    """
    if normal is not None:
        forces = forces @ contact_frame(normal)  # each foot's force in the contact frame
    fn = forces[..., 2]
    ft = np.hypot(forces[..., 0], forces[..., 1])
    out = np.zeros(fn.shape)
    np.divide(ft, mu * fn, out=out, where=stance & (fn > 0))
    return out
