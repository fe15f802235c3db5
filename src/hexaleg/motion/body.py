"""The body of a periodic gait: its constant-twist motion, the balancing sway, the base frame.

The base moves with a constant twist (local linear velocity ``[speed, 0, 0]``, angular velocity
``[0, 0, yaw_rate]``) at a constant height, starting at the origin with zero yaw, plus an
optional horizontal sway ``d(t) e`` (:class:`hexaleg.motion.balance.Sway`). World foot targets
are taken into the base frame with the exact rotating-frame derivatives (see
:func:`in_base_frame`), as :func:`hexaleg.motion.kinematics.leg_ik` needs them.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import pinocchio as pin

from hexaleg.motion.balance import Sway
from hexaleg.robot.model import Robot


class Body(NamedTuple):
    """The base's motion at N sample times (world position, yaw; LOCAL velocities).

    Attributes:
        base: Base position, shape (N, 3), m.
        yaw: Yaw, shape (N,), rad.
        rot: Base orientation R(yaw), shape (N, 3, 3).
        v: Linear velocity in the base frame, shape (3,) or (N, 3), m/s.
        w: Angular velocity in the base frame, shape (3,), rad/s.
        a: Linear acceleration in the base frame, shape (3,) or (N, 3), m/s².
    """

    base: np.ndarray
    yaw: np.ndarray
    rot: np.ndarray
    v: np.ndarray
    w: np.ndarray
    a: np.ndarray


def reference_pose(robot: Robot) -> np.ndarray:
    """The ``stand`` pose (or the neutral configuration), base at the origin, shape (nq,)."""
    q = robot.pose("stand") if "stand" in robot.poses else pin.neutral(robot.model)
    q[:7] = pin.neutral(robot.model)[:7]
    return q


def body_pose(t: np.ndarray, speed: float, yaw_rate: float, height: float
              ) -> tuple[np.ndarray, np.ndarray]:
    """Base position (N, 3) m and yaw (N,) rad of the constant-twist body motion at times t."""
    yaw = yaw_rate * t
    if yaw_rate == 0.0:
        x, y = speed * t, np.zeros_like(t)
    else:
        x, y = speed / yaw_rate * np.sin(yaw), speed / yaw_rate * (1.0 - np.cos(yaw))
    return np.stack([x, y, np.full_like(t, height)], axis=-1), yaw


def rotz(yaw: np.ndarray) -> np.ndarray:
    """Rotation matrices about z by ``yaw`` (any shape), shape ``(*yaw.shape, 3, 3)``."""
    c, s = np.cos(yaw), np.sin(yaw)
    rot = np.zeros((*np.shape(yaw), 3, 3))
    rot[..., 0, 0], rot[..., 0, 1], rot[..., 1, 0], rot[..., 1, 1] = c, -s, s, c
    rot[..., 2, 2] = 1.0
    return rot


def body_motion(t: np.ndarray, speed: float, yaw_rate: float, height: float,
                sway: Sway | None) -> Body:
    """The constant-twist body at times ``t`` (N,), with the sway ``d(t) e`` on top if given.

    The sway adds ``R e d`` to the position, ``e ḋ + ω ẑ × e d`` to the LOCAL linear velocity
    and makes the acceleration ``e d̈ + ω ẑ × e ḋ`` (exact derivatives of the trigonometric
    polynomial d).
    """
    base, yaw = body_pose(t, speed, yaw_rate, height)
    rot = rotz(yaw)
    v_local = np.array([speed, 0.0, 0.0])
    w_local = np.array([0.0, 0.0, yaw_rate])
    a_local = np.zeros(3)
    if sway is not None:
        d, dd, ddd = sway(t)
        e, e_perp = sway.direction, np.cross(w_local, sway.direction)
        base = base + np.einsum("nij,j->ni", rot, e) * d[:, None]
        v_local = v_local + e * dd[:, None] + e_perp * d[:, None]
        a_local = e * ddd[:, None] + e_perp * dd[:, None]
    return Body(base, yaw, rot, v_local, w_local, a_local)


def base_state(robot: Robot, body: Body) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """q (N, nq), v (N, nv), a (N, nv) with the base rows of ``body`` and the leg joints at the
    reference pose (:func:`reference_pose`), their velocities and accelerations zero."""
    n = len(body.yaw)
    q = np.tile(reference_pose(robot), (n, 1))
    q[:, :3] = body.base
    q[:, 5], q[:, 6] = np.sin(body.yaw / 2), np.cos(body.yaw / 2)
    v = np.zeros((n, robot.model.nv))
    v[:, :3], v[:, 3:6] = body.v, body.w
    a = np.zeros((n, robot.model.nv))
    a[:, :3] = body.a
    return q, v, a


def in_base_frame(body: Body, p_w: np.ndarray, pd_w: np.ndarray, pdd_w: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """World foot targets p, ṗ, p̈ (N, 3) in the moving base frame, with exact derivatives.

    ``p_b = Rᵀ (p − base)``, ``ṗ_b = −ω × p_b + Rᵀ ṗ − v`` and
    ``p̈_b = −ω × ṗ_b − ω × Rᵀ ṗ + Rᵀ p̈ − v̇`` (v, ω, v̇ the LOCAL base velocities).
    """
    rot, w_local = body.rot, body.w
    rel = np.einsum("nji,nj->ni", rot, p_w - body.base)
    rt_pd = np.einsum("nji,nj->ni", rot, pd_w)
    rel_d = -np.cross(w_local, rel) + rt_pd - body.v
    rel_dd = -np.cross(w_local, rel_d) - np.cross(w_local, rt_pd) \
        + np.einsum("nji,nj->ni", rot, pdd_w) - body.a
    return rel, rel_d, rel_dd
