"""The body of a periodic gait: its constant-twist motion, the balancing sway, the base frame.

The base moves with a constant twist (local linear velocity ``speed · h`` along the robot's
heading h, :attr:`hexaleg.robot.model.Robot.heading`, default ``[1, 0, 0]``; angular velocity
``[0, 0, yaw_rate]``) at a constant height, starting at the origin with zero yaw, plus an
optional horizontal sway ``d(t) e`` (:class:`hexaleg.motion.balance.Sway`) and yaw turn ψ(t)
(:class:`hexaleg.motion.balance.Turn`, the walking pattern of one-foot gaits). The legs' mid-stance
footholds in the base frame are :func:`nominal_footholds`. World foot targets
are taken into the base frame with the exact rotating-frame derivatives (see
:func:`in_base_frame`), as :func:`hexaleg.motion.kinematics.leg_ik` needs them.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
import pinocchio as pin

from hexaleg.motion.balance import Sway, Turn
from hexaleg.motion.ground import Ground, ground_plane, level_footholds
from hexaleg.motion.params import GaitParams
from hexaleg.robot.fields import horizontal_axis
from hexaleg.robot.model import Robot

FORWARD = np.array([1.0, 0.0, 0.0])
"""The default heading: the base's x axis."""


class Body(NamedTuple):
    """The base's motion at N sample times (world position, yaw; LOCAL velocities).

    Attributes:
        base: Base position, shape (N, 3), m.
        yaw: Yaw, shape (N,), rad (about the ground's normal on a slope).
        rot: Base orientation, shape (N, 3, 3): R(yaw) on level ground, ``R_g Rz(yaw) C`` on a
            slope (:mod:`hexaleg.motion.ground`).
        v: Linear velocity in the base frame, shape (3,) or (N, 3), m/s.
        w: Angular velocity in the base frame, shape (3,) or (N, 3), rad/s.
        a: Linear acceleration in the base frame, shape (3,) or (N, 3), m/s².
        ground: The inclined ground, or None on level ground.
        alpha: Angular acceleration in the base frame, shape (N, 3), rad/s², with a yaw turn;
            None: zero (the constant twist).
    """

    base: np.ndarray
    yaw: np.ndarray
    rot: np.ndarray
    v: np.ndarray
    w: np.ndarray
    a: np.ndarray
    ground: Ground | None = None
    alpha: np.ndarray | None = None


def reference_pose(robot: Robot) -> np.ndarray:
    """The ``stand`` pose (or the neutral configuration), base at the origin, shape (nq,)."""
    q = robot.pose("stand") if "stand" in robot.poses else pin.neutral(robot.model)
    q[:7] = pin.neutral(robot.model)[:7]
    return q


def heading(robot: Robot) -> np.ndarray:
    """The robot's heading (:attr:`Robot.heading`) as a horizontal unit vector, shape (3,).

    Checked here too (:func:`hexaleg.robot.fields.horizontal_axis`), since the attribute can be
    reassigned after loading.

    Raises:
        InvalidParameterError: not a finite, non-zero horizontal 3-vector.
    """
    h = horizontal_axis("heading", getattr(robot, "heading", FORWARD))
    if h[0] == 1.0 and h[1] == 0.0:
        return FORWARD.copy()
    return np.array([h[0], h[1], 0.0]) / np.hypot(h[0], h[1])


def walk_direction(robot: Robot, gait: GaitParams) -> np.ndarray:
    """The walking direction in the base frame, shape (3,): the robot's heading
    (:func:`heading`) turned by ``gait.heading`` about z (exactly the heading when that is 0)."""
    h = heading(robot)
    if gait.heading == 0.0:
        return h
    c, s = math.cos(gait.heading), math.sin(gait.heading)
    return np.array([c * h[0] - s * h[1], s * h[0] + c * h[1], 0.0])


def gait_ground(robot: Robot, gait: GaitParams) -> Ground | None:
    """The gait's inclined ground (:func:`hexaleg.motion.ground.ground_plane` along
    :func:`walk_direction`), or None on level ground."""
    return ground_plane(gait.slope, gait.cross_slope, gait.attitude, walk_direction(robot, gait))


def body_height(robot: Robot, gait: GaitParams) -> float:
    """``gait.body_height``, or the depth of the ``stand`` pose's feet below the base, m."""
    if gait.body_height is not None:
        return gait.body_height
    return -float(robot.foot_positions(reference_pose(robot))[:, 2].mean())


def nominal_footholds(robot: Robot, gait: GaitParams) -> np.ndarray:
    """Mid-stance foot positions in the base frame, shape (n_legs, 3), m.

    Horizontally the footholds of the robot's ``stand`` pose (scaled to ``foot_radius`` from the
    base z axis when given); vertically ``−body_height`` (default the stand pose's mean foot
    depth), so the feet are on the ground z = 0 when the base is at ``body_height``. A level
    body on a slope (``attitude = "level"``) puts each foot on the plane below its horizontal
    place (:func:`hexaleg.motion.ground.level_footholds`).

    Args:
        robot: The robot.
        gait: Gait parameters.

    Returns:
        Footholds in the base frame, legs in ``robot.legs`` order.
    """
    feet = robot.foot_positions(reference_pose(robot))
    height = -float(feet[:, 2].mean()) if gait.body_height is None else gait.body_height
    if gait.foot_radius is not None:
        radial = np.linalg.norm(feet[:, :2], axis=1, keepdims=True)
        feet[:, :2] *= gait.foot_radius / radial
    feet[:, 2] = -height
    ground = gait_ground(robot, gait)
    if ground is not None and ground.attitude == "level":
        return level_footholds(ground, feet, height)
    return feet


def body_pose(t: np.ndarray, speed: float, yaw_rate: float, height: float,
              direction: np.ndarray | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Base position (N, 3) m and yaw (N,) rad of the constant-twist body motion at times t.

    The local linear velocity ``speed · h`` (h = ``direction``, a horizontal unit vector in the
    base frame, default ``[1, 0, 0]``) and angular velocity ``[0, 0, yaw_rate]`` integrate to a
    line or a circular arc along h (rigid-body motion with a constant twist, Lynch & Park,
    *Modern Robotics*, 2017, §3.3.3: for h = x̂, ``x = v/ω sin ωt``, ``y = v/ω (1 − cos ωt)``;
    for another h the same path rotated about z by the angle of h).
    """
    yaw = yaw_rate * t
    if yaw_rate == 0.0:
        x, y = speed * t, np.zeros_like(t)
    else:
        x, y = speed / yaw_rate * np.sin(yaw), speed / yaw_rate * (1.0 - np.cos(yaw))
    if direction is not None and not (direction[0] == 1.0 and direction[1] == 0.0):
        c, s = float(direction[0]), float(direction[1])
        x, y = c * x - s * y, s * x + c * y
    return np.stack([x, y, np.full_like(t, height)], axis=-1), yaw


def rotz(yaw: np.ndarray) -> np.ndarray:
    """Rotation matrices about z by ``yaw`` (any shape), shape ``(*yaw.shape, 3, 3)``."""
    c, s = np.cos(yaw), np.sin(yaw)
    rot = np.zeros((*np.shape(yaw), 3, 3))
    rot[..., 0, 0], rot[..., 0, 1], rot[..., 1, 0], rot[..., 1, 1] = c, -s, s, c
    rot[..., 2, 2] = 1.0
    return rot


def body_motion(t: np.ndarray, speed: float, yaw_rate: float, height: float,
                sway: Sway | Sequence[Sway] | None, direction: np.ndarray | None = None,
                ground: Ground | None = None) -> Body:
    """The constant-twist body at times ``t`` (N,), with the sways ``d(t) e`` on top if given.

    The body travels along ``direction`` (the walking direction h, base frame; default
    ``[1, 0, 0]``): LOCAL linear velocity ``speed · h`` (:func:`body_pose`). Each sway adds
    ``R e d`` to the position, ``e ḋ + ω × e d`` to the LOCAL linear velocity and
    ``e d̈ + ω × e ḋ + ω̇ × e d`` to the acceleration (ω the LOCAL angular velocity; exact
    derivatives of the trigonometric polynomial d). On a slope (``ground``,
    :mod:`hexaleg.motion.ground`) the same motion happens in the ground frame at ``height`` from
    the plane along its normal: the world pose is ``R_g`` times the ground-frame pose with the
    base attitude ``Rz(ψ) C``, and the LOCAL velocities become ``Cᵀ (speed h)`` and
    ``Cᵀ (0, 0, ω)``.

    A :class:`~hexaleg.motion.balance.Turn` ψ(t) among the sways turns the base about its
    vertical (the ground's normal) on the same path: the yaw becomes ``yaw_rate t + ψ``, so
    ``ω = Cᵀ ẑ (yaw_rate + ψ̇)``, ``ω̇ = Cᵀ ẑ ψ̈``, and the path's LOCAL velocity
    ``Cᵀ Rz(−ψ) (speed h)`` gains the derivative ``−ψ̇ Cᵀ (ẑ × Rz(−ψ) speed h)`` (rotating
    frames: Lynch & Park, *Modern Robotics*, 2017, §3.3.2).
    """
    base, yaw = body_pose(t, speed, yaw_rate, height, direction)
    v_path = np.array([speed, 0.0, 0.0]) if direction is None else speed * direction
    sways = [] if sway is None else [sway] if isinstance(sway, Sway) else list(sway)
    turns = [one for one in sways if isinstance(one, Turn)]
    shifts = [one for one in sways if not isinstance(one, Turn)]
    tilt = np.eye(3) if ground is None else ground.tilt
    alpha: np.ndarray | None = None
    if turns:
        psi, psi_d, psi_dd = turns[0](t)
        yaw = yaw + psi
        turned = np.einsum("nji,j->ni", rotz(psi), v_path)  # Rz(−ψ) speed h
        v_local = turned @ tilt
        a_local = -psi_d[:, None] * (np.cross([0.0, 0.0, 1.0], turned) @ tilt)
        w_local = np.outer(yaw_rate + psi_d, tilt[2])
        alpha = np.outer(psi_dd, tilt[2])
    else:
        v_local, a_local, w_local = v_path, np.zeros(3), np.array([0.0, 0.0, yaw_rate])
        if ground is not None:
            v_local, w_local = ground.tilt.T @ v_local, ground.tilt.T @ w_local
    rot = rotz(yaw)
    if ground is not None:
        base = base @ ground.rotation.T
        rot = ground.rotation @ rot @ ground.tilt
    for one in shifts:
        d, dd, ddd = one(t)
        e, e_perp = one.direction, np.cross(w_local, one.direction)
        base = base + np.einsum("nij,j->ni", rot, e) * d[:, None]
        v_local = v_local + e * dd[:, None] + e_perp * d[:, None]
        a_local = a_local + e * ddd[:, None] + e_perp * dd[:, None]
        if alpha is not None:
            a_local = a_local + np.cross(alpha, e) * d[:, None]
    return Body(base, yaw, rot, v_local, w_local, a_local, ground, alpha)


def base_state(robot: Robot, body: Body) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """q (N, nq), v (N, nv), a (N, nv) with the base rows of ``body`` and the leg joints at the
    reference pose (:func:`reference_pose`), their velocities and accelerations zero."""
    n = len(body.yaw)
    q = np.tile(reference_pose(robot), (n, 1))
    q[:, :3] = body.base
    if body.ground is None:
        q[:, 5], q[:, 6] = np.sin(body.yaw / 2), np.cos(body.yaw / 2)
    else:
        q[:, 3:7] = body.ground.quaternions(body.yaw)
    v = np.zeros((n, robot.model.nv))
    v[:, :3], v[:, 3:6] = body.v, body.w
    a = np.zeros((n, robot.model.nv))
    a[:, :3] = body.a
    if body.alpha is not None:
        a[:, 3:6] = body.alpha
    return q, v, a


def swing_other_joints(robot: Robot, period: float, t: np.ndarray, q: np.ndarray,
                       v: np.ndarray, a: np.ndarray) -> None:
    """Set the joints on no leg that :attr:`Robot.moves <hexaleg.robot.loaded.Robot.moves>`
    names swinging about their stand angle, in place: ``q = q₀ + A sin(ω t + φ)``,
    ``q̇ = A ω cos(ω t + φ)``, ``q̈ = −A ω² sin(ω t + φ)``, ω = 2π / ``period`` (one swing a gait
    cycle, so the motion stays periodic). ``q`` (N, nq), ``v`` and ``a`` (N, nv) hold the
    others at the stand (:func:`base_state`); ``t`` (N,) s."""
    model = robot.model
    omega = 2.0 * np.pi / period
    for joint, (amplitude, phase) in robot.moves.items():
        j = model.joints[model.getJointId(joint)]
        angle = omega * np.asarray(t, dtype=float) + phase
        q[:, j.idx_q] += amplitude * np.sin(angle)
        v[:, j.idx_v] = amplitude * omega * np.cos(angle)
        a[:, j.idx_v] = -amplitude * omega ** 2 * np.sin(angle)


def in_base_frame(body: Body, p_w: np.ndarray, pd_w: np.ndarray, pdd_w: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """World foot targets p, ṗ, p̈ (N, 3) in the moving base frame, with exact derivatives.

    ``p_b = Rᵀ (p − base)``, ``ṗ_b = −ω × p_b + Rᵀ ṗ − v`` and
    ``p̈_b = −ω̇ × p_b − ω × ṗ_b − ω × Rᵀ ṗ + Rᵀ p̈ − v̇`` (v, ω, v̇, ω̇ the LOCAL base
    velocities and accelerations; ω̇ = 0 but with a yaw turn).
    """
    rot, w_local = body.rot, body.w
    rel = np.einsum("nji,nj->ni", rot, p_w - body.base)
    rt_pd = np.einsum("nji,nj->ni", rot, pd_w)
    rel_d = -np.cross(w_local, rel) + rt_pd - body.v
    rel_dd = -np.cross(w_local, rel_d) - np.cross(w_local, rt_pd) \
        + np.einsum("nji,nj->ni", rot, pdd_w) - body.a
    if body.alpha is not None:
        rel_dd = rel_dd - np.cross(body.alpha, rel)
    return rel, rel_d, rel_dd
