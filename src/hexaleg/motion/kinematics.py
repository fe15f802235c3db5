"""Leg inverse kinematics: foot position, velocity and acceleration → joint angles and derivatives.

Two solvers, both working in the base frame (the base's pose does not enter a leg's kinematics):

* :func:`analytic_leg_ik` — closed form for hexaleg-type legs (coxa about the body z axis, femur
  and tibia about parallel horizontal axes, see :mod:`hexaleg.robot.builder`), vectorised over
  time. The knee branch is fixed: tibia angle ≤ 0 (knee above the foot, as in the ``stand`` and
  ``sphere`` poses), so the branch never switches along a trajectory.
* :func:`~hexaleg.motion.leg_ik.newton_leg_ik` — any leg of two joints or more: Newton
  iterations on the leg's chain read from Pinocchio, every sample at once, then ``q̇ = J⁻¹ ṗ``
  and ``q̈ = J⁻¹ (p̈ − J̇ q̇)`` (a two-joint leg's in least squares; a leg of four or more with
  the augmented Jacobian of its stated secondary objective,
  :class:`~hexaleg.motion.leg_chain.LegChain`).

Derivatives are exact (chain rule on the closed form, or the Jacobian relations above), never
finite differences. :func:`leg_ik` picks the analytic solver when the leg's geometry matches it
(checked against Pinocchio forward kinematics) and Newton otherwise.

Source: standard serial-chain kinematics (Siciliano et al., *Robotics: Modelling, Planning and
Control*, 2009, §2.12 inverse kinematics, §3.1–3.2 the geometric Jacobian and its derivative);
the paper studies one joint and has no leg IK.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from hexaleg.errors import RobotModelError, UnreachableTargetError
from hexaleg.motion.leg_chain import leg_chain
from hexaleg.motion.leg_ik import newton_leg_ik
from hexaleg.robot.model import Leg, Robot

FK_CHECK_TOL = 1e-12
"""Tolerance, m, of the check that the analytic model reproduces Pinocchio's forward kinematics."""


@dataclass(frozen=True)
class LegGeometry:
    """Geometry of a hexaleg-type leg, in the base frame, SI.

    The coxa joint sits at ``hip`` with its x axis yawed by ``yaw`` about the base z axis and turns
    about z; the femur joint is ``coxa`` m further along the coxa's x axis; femur and tibia turn
    about the leg's −y axis (positive angles lift) and have lengths ``femur`` and ``tibia``; the
    foot is at the tibia tip.

    Attributes:
        hip: Coxa joint position in the base frame, shape (3,), m.
        yaw: Hip yaw about the base z axis, rad.
        coxa: Coxa length (coxa axis → femur axis), m.
        femur: Femur length, m.
        tibia: Tibia length (knee → foot), m.
    """

    hip: tuple[float, float, float]
    yaw: float
    coxa: float
    femur: float
    tibia: float

    def __post_init__(self) -> None:
        for name in ("coxa", "femur", "tibia"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0.0):
                raise RobotModelError(f"leg geometry: {name} length {value!r} must be finite "
                                      "and ≥ 0")
        if self.femur <= 0.0 or self.tibia <= 0.0:
            raise RobotModelError(f"leg geometry: femur {self.femur} m and tibia {self.tibia} m "
                                  "must be > 0")

    @property
    def reach(self) -> tuple[float, float]:
        """Smallest and largest distance of the foot from the femur axis, m."""
        return abs(self.femur - self.tibia), self.femur + self.tibia

    def forward(self, q: np.ndarray) -> np.ndarray:
        """Foot position in the base frame.

        Args:
            q: Joint angles (coxa, femur, tibia), shape (..., 3), rad.

        Returns:
            Foot positions, shape (..., 3), m.
        """
        q = np.asarray(q, dtype=float)
        q1, q2, q3 = q[..., 0], q[..., 1], q[..., 2]
        rho = self.coxa + self.femur * np.cos(q2) + self.tibia * np.cos(q2 + q3)
        z = self.femur * np.sin(q2) + self.tibia * np.sin(q2 + q3)
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        x_h, y_h = rho * np.cos(q1), rho * np.sin(q1)
        return np.stack([self.hip[0] + c * x_h - s * y_h, self.hip[1] + s * x_h + c * y_h,
                         self.hip[2] + z], axis=-1)

    def jacobian(self, q: np.ndarray) -> np.ndarray:
        """Derivative of :meth:`forward` with respect to the joint angles.

        Args:
            q: Joint angles, shape (..., 3), rad.

        Returns:
            ∂p/∂q, shape (..., 3, 3), m/rad (rows x y z of the base frame, columns the joints).
        """
        q = np.asarray(q, dtype=float)
        q1, q2, q23 = q[..., 0], q[..., 1], q[..., 1] + q[..., 2]
        rho = self.coxa + self.femur * np.cos(q2) + self.tibia * np.cos(q23)
        d_rho = np.stack([np.zeros_like(q1), -self.femur * np.sin(q2) - self.tibia * np.sin(q23),
                          -self.tibia * np.sin(q23)], axis=-1)
        d_z = np.stack([np.zeros_like(q1), self.femur * np.cos(q2) + self.tibia * np.cos(q23),
                        self.tibia * np.cos(q23)], axis=-1)
        c1, s1 = np.cos(q1)[..., None], np.sin(q1)[..., None]
        j_hip = np.stack([c1 * d_rho, s1 * d_rho, d_z], axis=-2)
        j_hip[..., 0, 0] = -rho * np.sin(q1)
        j_hip[..., 1, 0] = rho * np.cos(q1)
        c, s = math.cos(self.yaw), math.sin(self.yaw)
        rot = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        return np.einsum("ij,...jk->...ik", rot, j_hip)


def _joint_axis(model: pin.Model, jid: int) -> np.ndarray:
    """Rotation axis of 1-DoF joint ``jid`` in its own frame, shape (3,)."""
    data = model.createData()
    q = pin.neutral(model)
    pin.computeJointJacobians(model, data, q)
    jac = pin.getJointJacobian(model, data, jid, pin.LOCAL)
    return np.array(jac[3:, model.joints[jid].idx_v])


def analytic_geometry(robot: Robot, leg: Leg) -> LegGeometry | None:
    """The :class:`LegGeometry` of ``leg`` if it is a hexaleg-type leg, else None.

    The leg qualifies when it has three joints, the first hanging from the base and turning about
    the base z axis, the femur and tibia joints turning about −y with their frames translated
    along x only, and the foot frame on the tibia's x axis; the result is then checked against
    Pinocchio's forward kinematics at random configurations (to ``FK_CHECK_TOL``).

    Args:
        robot: The robot.
        leg: One of ``robot.legs``.

    Returns:
        The geometry, or None when the closed form does not apply.
    """
    model = robot.model
    if len(leg.joint_ids) != 3:
        return None
    j1, j2, j3 = leg.joint_ids
    foot = model.frames[leg.foot_frame_id]
    if model.parents[j1] != 1 or model.parents[j2] != j1 or model.parents[j3] != j2 \
            or foot.parentJoint != j3:
        return None
    axes = [_joint_axis(model, j) for j in (j1, j2, j3)]
    want = [np.array([0.0, 0.0, 1.0]), np.array([0.0, -1.0, 0.0]), np.array([0.0, -1.0, 0.0])]
    if any(not np.allclose(a, w, atol=1e-12) for a, w in zip(axes, want, strict=True)):
        return None
    m1 = model.jointPlacements[j1]
    if not np.allclose(m1.rotation[2], [0.0, 0.0, 1.0], atol=1e-12):
        return None
    for placement in (model.jointPlacements[j2], model.jointPlacements[j3], foot.placement):
        if not (np.allclose(placement.rotation, np.eye(3), atol=1e-12)
                and np.allclose(placement.translation[1:], 0.0, atol=1e-12)):
            return None
    try:
        geom = LegGeometry(hip=tuple(float(x) for x in m1.translation),  # type: ignore[arg-type]
                           yaw=math.atan2(m1.rotation[1, 0], m1.rotation[0, 0]),
                           coxa=float(model.jointPlacements[j2].translation[0]),
                           femur=float(model.jointPlacements[j3].translation[0]),
                           tibia=float(foot.placement.translation[0]))
    except RobotModelError:
        return None
    rng = np.random.default_rng(0)
    data = model.createData()
    q = pin.neutral(model)
    for _ in range(5):
        q_leg = rng.uniform(-1.5, 1.5, 3)
        q[leg.q_index] = q_leg
        pin.framesForwardKinematics(model, data, q)
        if np.linalg.norm(data.oMf[leg.foot_frame_id].translation - geom.forward(q_leg)) \
                > FK_CHECK_TOL:
            return None
    return geom


def _check_limits(robot: Robot, leg: Leg, q: np.ndarray, t: np.ndarray, p: np.ndarray) -> None:
    """Raise UnreachableTargetError at the first sample where a joint leaves its limits."""
    lo = robot.model.lowerPositionLimit[leg.q_index]
    hi = robot.model.upperPositionLimit[leg.q_index]
    bad = (q < lo) | (q > hi)
    if bad.any():
        k, j = (int(i) for i in np.argwhere(bad)[0])
        raise UnreachableTargetError(
            f"leg {leg.name} at t = {t[k]:.6g} s: joint {leg.joint_names[j]} would be "
            f"{math.degrees(q[k, j]):.2f}° (= {q[k, j]:.4f} rad), outside its limits "
            f"[{math.degrees(lo[j]):.1f}°, {math.degrees(hi[j]):.1f}°]",
            **_where(leg.name, t, k, np.atleast_2d(p)[k]))


def _where(leg: str, t: np.ndarray, k: int, p: np.ndarray, dist: float | None = None) -> dict:
    """The data fields of an :class:`UnreachableTargetError` at sample k."""
    return {"leg": leg, "t": float(t[k]), "index": k, "target": tuple(float(x) for x in p),
            "distance": None if dist is None else float(dist)}


def analytic_leg_ik(geom: LegGeometry, p: np.ndarray, pd: np.ndarray, pdd: np.ndarray, *,
                    leg_name: str = "leg", t: np.ndarray | None = None
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Closed-form inverse kinematics of a hexaleg-type leg, with exact derivatives.

    The coxa angle is the polar angle of the foot about the coxa axis; the femur and tibia solve
    the planar two-link problem in the leg plane (law of cosines) on the branch tibia angle ≤ 0.
    Velocities and accelerations follow by the chain rule: polar coordinates for the coxa, and
    ``[ṙ, ż] = J₂ [q̇₂, q̇₃]``, ``[r̈, z̈] = J₂ [q̈₂, q̈₃] + J̇₂ [q̇₂, q̇₃]`` in the leg plane.

    Args:
        geom: The leg's geometry.
        p: Foot positions in the base frame, shape (T, 3), m.
        pd: Their time derivatives in the base frame, shape (T, 3), m/s.
        pdd: Their second time derivatives in the base frame, shape (T, 3), m/s².
        leg_name: Leg name for error messages.
        t: Sample times for error messages, shape (T,), s; default the sample indices.

    Returns:
        Joint angles (T, 3) rad, velocities (T, 3) rad/s and accelerations (T, 3) rad/s², joints
        in the order coxa, femur, tibia.

    Raises:
        UnreachableTargetError: a target is farther from (or closer to) the femur axis than the
            leg reaches, or on the coxa axis; the message names the leg, the time and the
            distance out of reach.
    """
    p, pd, pdd = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (p, pd, pdd))
    t = np.arange(len(p), dtype=float) if t is None else np.asarray(t, dtype=float)
    c, s = math.cos(geom.yaw), math.sin(geom.yaw)
    rot_t = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])  # base → hip frame
    x, y, z = (rot_t @ (p - np.asarray(geom.hip)).T)
    xd, yd, zd = rot_t @ pd.T
    xdd, ydd, zdd = rot_t @ pdd.T

    rad2 = x * x + y * y
    rad = np.sqrt(rad2)
    lo, hi = geom.reach
    r = rad - geom.coxa
    dist = np.hypot(r, z)
    out = np.maximum(dist - hi, lo - dist)
    bad = (out > 0) | (rad <= geom.coxa * 1e-9 + 1e-12)
    if bad.any():
        k = int(np.argmax(bad))
        where = (f"leg {leg_name} at t = {t[k]:.6g} s: foot target "
                 f"{np.round(p[k], 6).tolist()} m (base frame)")
        if out[k] <= 0:
            raise UnreachableTargetError(f"{where} is on the coxa axis, where the coxa angle is "
                                         "undefined; targets must lie outward of it",
                                         **_where(leg_name, t, k, p[k]))
        raise UnreachableTargetError(
            f"{where} is {out[k]:.6g} m out of reach (distance {dist[k]:.6g} m from the femur "
            f"axis; the leg reaches {lo:.6g}–{hi:.6g} m)", **_where(leg_name, t, k, p[k], out[k]))

    l1, l2 = geom.femur, geom.tibia
    cos3 = np.clip((dist**2 - l1**2 - l2**2) / (2.0 * l1 * l2), -1.0, 1.0)
    q3 = -np.arccos(cos3)
    s3 = np.sin(q3)
    q2 = np.arctan2(z, r) - np.arctan2(l2 * s3, l1 + l2 * cos3)
    q1 = np.arctan2(y, x)

    # Coxa: polar angle and the radial distance, with exact derivatives.
    w = x * yd - y * xd
    u = x * xd + y * yd
    q1d = w / rad2
    q1dd = (x * ydd - y * xdd) / rad2 - 2.0 * w * u / rad2**2
    rd = u / rad
    rdd = (xd**2 + yd**2 + x * xdd + y * ydd) / rad - u**2 / rad**3

    # Femur and tibia: planar two-link Jacobian J₂ (det = l1 l2 sin q3).
    q23 = q2 + q3
    s2, c2, s23, c23 = np.sin(q2), np.cos(q2), np.sin(q23), np.cos(q23)
    j = np.empty((len(p), 2, 2))
    j[:, 0, 0] = -l1 * s2 - l2 * s23
    j[:, 0, 1] = -l2 * s23
    j[:, 1, 0] = l1 * c2 + l2 * c23
    j[:, 1, 1] = l2 * c23
    qd23 = np.linalg.solve(j, np.stack([rd, zd], axis=-1)[..., None])[..., 0]
    w2, w23 = qd23[:, 0], qd23[:, 0] + qd23[:, 1]
    bias = np.stack([-l1 * c2 * w2**2 - l2 * c23 * w23**2, -l1 * s2 * w2**2 - l2 * s23 * w23**2],
                    axis=-1)
    qdd23 = np.linalg.solve(j, (np.stack([rdd, zdd], axis=-1) - bias)[..., None])[..., 0]

    q = np.stack([q1, q2, q3], axis=-1)
    qd = np.column_stack([q1d, qd23])
    qdd = np.column_stack([q1dd, qdd23])
    return q, qd, qdd


def leg_ik(robot: Robot, leg: Leg, p: np.ndarray, pd: np.ndarray, pdd: np.ndarray, *,
           t: np.ndarray | None = None,
           turn: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray, str]:
    """Inverse kinematics of one leg over a trajectory: analytic when possible, else Newton.

    Joint limits of the robot model are checked on the result.

    Args:
        robot: The robot.
        leg: One of ``robot.legs``.
        p: Foot positions in the base frame, shape (T, 3), m.
        pd: Their time derivatives in the base frame, shape (T, 3), m/s.
        pdd: Their second time derivatives in the base frame, shape (T, 3), m/s².
        t: Sample times for error messages, shape (T,), s.
        turn: A sole leg's foot turn in the base frame with its rates (θ, θ̇, θ̈), each (T, 3),
            rad (:func:`~hexaleg.motion.leg_ik.newton_leg_ik`); None: held at the stand's.

    Returns:
        Joint angles (T, n) rad, velocities (T, n) rad/s, accelerations (T, n) rad/s², in the
        order of ``leg.joint_names`` (n of them), and the solver used (``"analytic"`` or
        ``"newton"``). A sole leg's self-motion is its foot's orientation: it is not shifted
        to keep the joints within their limits (the limits are checked).

    Raises:
        UnreachableTargetError: a target is out of reach or needs a joint beyond its limits; the
            message names the leg and the time.
        RobotModelError: the leg has fewer than two joints, or is not one chain of 1-DoF joints
            (:func:`~hexaleg.motion.leg_chain.leg_chain`).
    """
    t = np.arange(len(np.atleast_2d(p)), dtype=float) if t is None else np.asarray(t, float)
    geom = analytic_geometry(robot, leg)
    if geom is not None:
        q, qd, qdd = analytic_leg_ik(geom, p, pd, pdd, leg_name=leg.name, t=t)
        solver = "analytic"
    else:
        q, qd, qdd = newton_leg_ik(robot, leg, p, pd, pdd, t=t, turn=turn)
        solver = "newton"
        if len(leg.joint_names) > 3 and leg.name not in robot.soles and \
                _outside(robot, leg, q).any():
            q, qd, qdd = _within_limits(robot, leg, p, pd, pdd, t, q, qd, qdd)
    _check_limits(robot, leg, q, t, p)
    return q, qd, qdd, solver


REDUNDANT_SHIFTS: tuple[float, ...] = (1.0, 1.25, 1.5, 2.0, 3.0)
"""How far a redundant leg's self-motion is set off the stand's (:func:`_within_limits`), in
multiples of the shift that brings the joints leaving their limits back to them to first order,
tried in this order: the least that keeps every joint within its limits is kept."""
MAX_SHIFT = math.pi / 2
"""The largest self-motion shift tried, rad (a quarter turn: beyond it the leg is another pose,
not the stand's set off)."""


def _outside(robot: Robot, leg: Leg, q: np.ndarray) -> np.ndarray:
    """By how much each sample's joints leave their limits (rad; 0 within), shape (T, n)."""
    lo = robot.model.lowerPositionLimit[leg.q_index]
    hi = robot.model.upperPositionLimit[leg.q_index]
    return np.maximum(lo - q, 0.0) + np.maximum(q - hi, 0.0)


def _within_limits(robot: Robot, leg: Leg, p: np.ndarray, pd: np.ndarray, pdd: np.ndarray,
                   t: np.ndarray, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A redundant leg's motion with its self-motion set off the stand's so that every joint
    stays within its limits, or the motion as it was when no shift of
    :data:`REDUNDANT_SHIFTS` does (then :func:`_check_limits` names the joint).

    The leg's secondary objective holds ``N₀ᵀ (q − q_stand)`` at a constant (:func:`~hexaleg.
    motion.leg_ik.newton_leg_ik`'s ``shift``) over the whole cycle, so the motion stays one
    smooth periodic solution with exact rates; the constant points along ``N₀ᵀ d``, ``d`` the
    joints' way back inside their limits at their worst sample (a joint past its lower limit
    +1, past its upper −1), at the least multiple (:data:`REDUNDANT_SHIFTS`, up to
    :data:`MAX_SHIFT`) of the first-order shift back to the limits that keeps every sample
    within. The stand
    solver chooses a stand within the limits the same way (issue #55: Centauro's swing took
    ``hip_pitch_1`` 0.1° past its limit though its 5-joint leg had two spare directions)."""
    reference = robot.pose("stand") if "stand" in robot.poses else pin.neutral(robot.model)
    reference[:7] = pin.neutral(robot.model)[:7]
    redundant = leg_chain(robot, leg, reference).redundant
    lo = robot.model.lowerPositionLimit[leg.q_index]
    worst = _outside(robot, leg, q).max(axis=0)
    k = np.argmax(_outside(robot, leg, q), axis=0)
    d = np.where(worst > 0, np.where(q[k, np.arange(q.shape[1])] < lo, 1.0, -1.0), 0.0)
    direction = redundant.T @ d
    if not redundant.shape[1] or np.linalg.norm(direction) < 1e-9:
        return q, qd, qdd
    direction = direction / np.linalg.norm(direction)
    moves = np.abs(redundant @ direction)  # each joint's move a radian of shift, to first order
    bad = worst > 0
    if (moves[bad] < 1e-9).any():
        return q, qd, qdd
    needed = float(np.max(worst[bad] / moves[bad]))
    for size in (needed * f for f in REDUNDANT_SHIFTS if needed * f <= MAX_SHIFT):
        try:
            moved = newton_leg_ik(robot, leg, p, pd, pdd, t=t, shift=size * direction)
        except UnreachableTargetError:
            continue
        if not _outside(robot, leg, moved[0]).any():
            return moved
    return q, qd, qdd
