"""The floating base of a log: its pose as logged or from leg odometry, and its velocities.

**Leg odometry** (without a logged base position): the stance feet are held still. Between two
samples the base's pose change is the rigid transform that best maps the feet in stance at both,
seen from the base, onto where they were in the world — the least-squares rotation by SVD (Arun,
Huang & Blostein, *IEEE PAMI* 9(5), 1987; Kabsch) with three or more such feet, the
least-squares translation alone with fewer. What the transform cannot explain is the feet's
slip, reported as an rms speed, m/s. The first pose stands the first sample's stance feet on
z = 0, level when three or more are down (yaw 0).

**Velocities**: the pose as position and Z-Y-X Euler angles (yaw unwrapped), each smoothed and
differentiated (:mod:`~hexaleg.motion.recorded.smooth`); Pinocchio's free-flyer velocity is the
LOCAL twist ``v = Rᵀ ṗ``, ``ω = Rᵀ ω_w`` with ``ω_w = ψ̇ e_z + θ̇ e₂ + φ̇ e₃`` (e₂ = R_z e_y,
e₃ = R_z R_y e_x), and ``a`` its time derivative: ``v̇ = Rᵀ p̈ − ω × v``, ``ω̇ = Rᵀ ω̇_w``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Odometry:
    """The base from the stance feet.

    Attributes:
        position: World base positions, shape (T + 1, 3), m (the last: after one more step,
            sample 0 of the next cycle for a periodic motion).
        rotation: World base orientations, shape (T + 1, 3, 3).
        slip: Rms speed of the stance feet the fit leaves, per step, shape (T,), m/s.
    """

    position: np.ndarray
    rotation: np.ndarray
    slip: np.ndarray


def rotation_from_quaternion(quat: np.ndarray) -> np.ndarray:
    """Rotation matrices (T, 3, 3) of unit quaternions (T, 4), x y z w."""
    x, y, z, w = np.moveaxis(np.asarray(quat, dtype=float), -1, 0)
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
    ], -2)


def euler_from_rotation(rot: np.ndarray) -> np.ndarray:
    """Z-Y-X Euler angles (roll φ, pitch θ, yaw ψ) of rotations (T, 3, 3), yaw unwrapped."""
    roll = np.arctan2(rot[:, 2, 1], rot[:, 2, 2])
    pitch = -np.arcsin(np.clip(rot[:, 2, 0], -1.0, 1.0))
    yaw = np.unwrap(np.arctan2(rot[:, 1, 0], rot[:, 0, 0]))
    return np.stack([roll, pitch, yaw], axis=1)


def quaternion_from_euler(rpy: np.ndarray) -> np.ndarray:
    """Unit quaternions (T, 4), x y z w, of Z-Y-X Euler angles (T, 3) (roll, pitch, yaw)."""
    h = 0.5 * np.asarray(rpy, dtype=float)
    cr, sr, cp, sp, cy, sy = (np.cos(h[:, 0]), np.sin(h[:, 0]), np.cos(h[:, 1]),
                              np.sin(h[:, 1]), np.cos(h[:, 2]), np.sin(h[:, 2]))
    return np.stack([sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
                     cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy], axis=1)


def rotation_from_euler(rpy: np.ndarray) -> np.ndarray:
    """Rotations (T, 3, 3) of Z-Y-X Euler angles (T, 3)."""
    return rotation_from_quaternion(quaternion_from_euler(rpy))


def twist(rpy: np.ndarray, drpy: np.ndarray, ddrpy: np.ndarray, dp: np.ndarray,
          ddp: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pinocchio's free-flyer velocity and acceleration (T, 6) each, LOCAL (module docstring),
    from Euler angles (T, 3) and the world position's derivatives (T, 3), with theirs."""
    _roll, pitch, yaw = rpy.T
    d_roll, d_pitch, d_yaw = drpy.T
    cy, sy, cp, sp = np.cos(yaw), np.sin(yaw), np.cos(pitch), np.sin(pitch)
    zero = np.zeros_like(yaw)
    e1 = np.stack([zero, zero, zero + 1.0], 1)
    e2 = np.stack([-sy, cy, zero], 1)
    e3 = np.stack([cy * cp, sy * cp, -sp], 1)
    de2 = d_yaw[:, None] * np.stack([-cy, -sy, zero], 1)
    de3 = (d_yaw[:, None] * np.stack([-sy * cp, cy * cp, zero], 1)
           + d_pitch[:, None] * np.stack([-cy * sp, -sy * sp, -cp], 1))
    w_world = d_yaw[:, None] * e1 + d_pitch[:, None] * e2 + d_roll[:, None] * e3
    dw_world = (ddrpy[:, 2:3] * e1 + ddrpy[:, 1:2] * e2 + d_pitch[:, None] * de2
                + ddrpy[:, 0:1] * e3 + d_roll[:, None] * de3)
    rot = rotation_from_euler(rpy)
    rt = np.transpose(rot, (0, 2, 1))
    v_lin = np.einsum("tij,tj->ti", rt, dp)
    w = np.einsum("tij,tj->ti", rt, w_world)
    a_lin = np.einsum("tij,tj->ti", rt, ddp) - np.cross(w, v_lin)
    dw = np.einsum("tij,tj->ti", rt, dw_world)
    return np.concatenate([v_lin, w], 1), np.concatenate([a_lin, dw], 1)


def _fit(world: np.ndarray, body: np.ndarray, rotate: bool, rot: np.ndarray
         ) -> tuple[np.ndarray, np.ndarray]:
    """The pose (R, p) minimising Σ |R b_i + p − w_i|² (Arun et al. 1987); R = ``rot`` kept
    when ``rotate`` is False."""
    cw, cb = world.mean(axis=0), body.mean(axis=0)
    if rotate:
        u, _, vt = np.linalg.svd((body - cb).T @ (world - cw))
        d = np.sign(np.linalg.det(vt.T @ u.T))
        rot = vt.T @ np.diag([1.0, 1.0, d]) @ u.T
    return rot, cw - rot @ cb


def _initial_pose(feet: np.ndarray, down: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Level the first sample's stance feet (a plane through ≥ 3 of them) onto z = 0: the
    smallest rotation taking the plane's normal n to e_z (Rodrigues' formula), yaw 0."""
    pts = feet[down] if down.any() else feet
    rot = np.eye(3)
    if len(pts) >= 3:
        normal = np.linalg.svd(pts - pts.mean(axis=0))[2][2]
        normal = normal if normal[2] > 0 else -normal  # the ground's normal, base frame
        axis = np.cross(normal, [0.0, 0.0, 1.0])
        s, c = float(np.linalg.norm(axis)), float(normal[2])
        if s > 1e-12:
            k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]],
                          [-axis[1], axis[0], 0]])
            rot = np.eye(3) + k + k @ k * ((1 - c) / s**2)
    return rot, -(pts @ rot.T).mean(axis=0)


def leg_odometry(feet: np.ndarray, stance: np.ndarray, dt: float, *, periodic: bool,
                 rotation: np.ndarray | None = None) -> Odometry:
    """The base's poses from the feet in the base frame held still in stance (module docstring).

    Args:
        feet: Foot positions in the base frame, shape (T, n_legs, 3), m.
        stance: Stance flags, shape (T, n_legs).
        dt: Sample spacing, s.
        periodic: Whether sample T is sample 0 again (one more step closes the cycle).
        rotation: The base's orientations from an IMU, shape (T, 3, 3), world; then only the
            translation is fitted.

    Returns:
        Poses at T + 1 samples (the last repeats the cycle's start, or extrapolates one step)
        and the slip per step. A step without a foot in stance at both ends keeps the base
        moving as in the step before.
    """
    n = feet.shape[0]
    rot = np.empty((n + 1, 3, 3))
    pos = np.empty((n + 1, 3))
    slip = np.zeros(n)
    rot[0], pos[0] = _initial_pose(feet[0], stance[0])
    if rotation is not None:
        rot[:n] = rotation
        rot[n] = rotation[0] if periodic else rotation[-1]
        pos[0] = -(feet[0, stance[0]] @ rot[0].T).mean(axis=0) if stance[0].any() else 0.0
    for k in range(n):
        nxt = (k + 1) % n if periodic else min(k + 1, n - 1)
        both = stance[k] & stance[nxt]
        if not both.any() or (not periodic and k == n - 1):
            prev = max(k - 1, 0)
            if rotation is None:
                rot[k + 1] = rot[k] @ rot[prev].T @ rot[k]
            pos[k + 1] = pos[k] + (pos[k] - pos[prev])
            continue
        world = feet[k, both] @ rot[k].T + pos[k]
        fixed = rot[k] if rotation is None else rot[k + 1]
        rotate = rotation is None and int(both.sum()) >= 3
        rot[k + 1], pos[k + 1] = _fit(world, feet[nxt, both], rotate, fixed)
        residual = feet[nxt, both] @ rot[k + 1].T + pos[k + 1] - world
        slip[k] = float(np.sqrt((residual**2).sum(axis=1).mean())) / dt
    return Odometry(position=pos, rotation=rot, slip=slip)
