"""A leg's inverse kinematics by Newton's method on its serial chain, every sample at once.

The chain (:class:`~hexaleg.motion.leg_chain.LegChain`, read from Pinocchio by
:func:`~hexaleg.motion.leg_chain.leg_chain`) gives the foot's position, Jacobian and bias
acceleration for a stack of configurations; :func:`newton_leg_ik` solves a leg of two joints (in
least squares: its foot moves in a plane), three, or four and more (with the chain's stated
secondary objective, the augmented Jacobian) and returns exact rates from the Jacobian relations.

Source: Newton's method on the forward kinematics and the inverse differential kinematics
``q̇ = J⁻¹ ṗ``, ``q̈ = J⁻¹ (p̈ − J̇ q̇)`` (Siciliano et al., *Robotics: Modelling, Planning and
Control*, 2009, §2.12 and §3.5).
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pinocchio as pin

from hexaleg.checks import finite_array
from hexaleg.errors import UnreachableTargetError
from hexaleg.motion.leg_chain import LegChain, leg_chain
from hexaleg.robot.model import Leg, Robot

NEWTON_TOL = 1e-13
"""Foot position residual, m, at which the Newton solver stops."""
NEWTON_MAX_ITER = 50
"""Newton iterations allowed per sample before the target is declared unreachable."""
PLANE_TOL = 1e-6
"""How far off a two-joint leg's plane a foot target may lie, m (a gait for such a leg puts its
feet in that plane; more is a target the leg cannot reach)."""
NEWTON_JUMP = 0.1
"""Largest joint change, rad (or m), between consecutive samples solved all at once from the
same start that :func:`newton_leg_ik` accepts as one continuous branch; a larger one is solved
again sample by sample from its predecessor."""
NEWTON_REJOIN = 1e-9
"""Largest joint difference, rad (or m), between a sample solved again from its predecessor and
its all-at-once solution at which :func:`newton_leg_ik` takes the two for one (the same branch:
both converged to :data:`NEWTON_TOL`) and keeps the all-at-once solutions that follow."""


def newton_leg_ik(robot: Robot, leg: Leg, p: np.ndarray, pd: np.ndarray, pdd: np.ndarray, *,
                  q0: np.ndarray | None = None, t: np.ndarray | None = None,
                  shift: np.ndarray | None = None,
                  turn: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Inverse kinematics of a leg of two or more joints by Newton's method on its forward
    kinematics.

    The leg is read from Pinocchio as a fixed chain (:func:`~hexaleg.motion.leg_chain.leg_chain`,
    the other joints at the ``stand`` pose) and Newton runs on every sample at once from ``q0``.
    The branch is the one ``q0`` selects: the result is kept when every sample converged and
    consecutive samples differ by under :data:`NEWTON_JUMP` (a continuous path from the first
    sample, so each sample is the solution Newton reaches from its predecessor); otherwise the
    samples from the first failure on are solved one after another, each from the previous
    solution, until one lands on its all-at-once solution (within :data:`NEWTON_REJOIN`: the
    path is back on the batch's branch, whose following samples are kept up to the next
    failure). A jump that only coarse sampling makes costs one sample's solve. Then
    ``q̇ = J⁻¹ ṗ`` and ``q̈ = J⁻¹ (p̈ − J̇ q̇)``, with ``J`` the foot's translation Jacobian and
    ``J̇ q̇`` its acceleration at zero joint acceleration.

    A leg of n ≥ 4 joints is redundant; it keeps the secondary objective of :class:`LegChain`,
    ``N₀ᵀ (q − q_stand) = 0`` (its redundant directions at the stand pose hold their stand values:
    to first order, the configuration nearest the stand that puts the foot on the target).
    Newton then solves the square system ``F(q) = [p(q) − p*; N₀ᵀ (q − q_stand)] = 0`` with the
    augmented Jacobian ``Ĵ = [J; N₀ᵀ]`` (n × n), from ``q0`` projected on the objective's plane
    (the rows are linear, so every Newton step keeps them), and ``q̇ = Ĵ⁻¹ [ṗ; 0]``,
    ``q̈ = Ĵ⁻¹ [p̈ − J̇ q̇; 0]`` (the rows are constant: no bias term): the exact time derivatives
    of the position solution.
    Args:
        robot: The robot.
        leg: One of ``robot.legs``, with two joints or more
            (:data:`~hexaleg.motion.leg_chain.MIN_JOINTS`).
        p: Foot positions in the base frame, shape (T, 3), m.
        pd: Their time derivatives, shape (T, 3), m/s.
        pdd: Their second time derivatives, shape (T, 3), m/s².
        q0: Initial guess of the leg's joint angles, shape (n,), rad; default the ``stand`` pose
            (or Pinocchio's neutral configuration when the robot has none).
        t: Sample times for error messages, shape (T,), s; default the sample indices.
        shift: A redundant leg's secondary objective held at ``N₀ᵀ (q − q_stand) = shift``
            instead of 0, shape (n − 3,), rad (its self-motion set off the stand's by a
            constant, the same over the cycle: :func:`~hexaleg.motion.kinematics.leg_ik` uses
            it to keep a swing within the joint limits); default 0.
        turn: A sole leg's foot orientation: the rotation vector θ from its stand orientation
            (base frame, rad) with its first and second time derivatives, each shape (T, 3) —
            a foot flat on the ground under a body that yaws by ψ turns by θ = (0, 0, −ψ) in
            the base frame. Newton then starts where the objective's rows hold
            ``N₀ᵀ (q − q_stand) = S⁻¹ Uᵀ θ`` (:attr:`~hexaleg.motion.leg_chain.LegChain.turn_rows`)
            and solves the foot's whole pose, ``R = exp([θ]) R_stand`` (:func:`_newton_pose`),
            with ``q̇ = J₆⁻¹ [ṗ; θ̇]`` and ``q̈ = J₆⁻¹ [p̈ − J̇ q̇; θ̈ − J̇_ω q̇]`` (θ about the
            base's fixed vertical, so θ̇ is the foot's angular velocity); default: the stand's
            orientation held (θ = 0).

    Returns:
        Joint angles (T, n) rad, velocities (T, n) rad/s, accelerations (T, n) rad/s², in the
        order of ``leg.joint_names`` (a two-joint leg's in least squares: exact for targets in
        its plane; a redundant leg's with its secondary objective met).

    Raises:
        RobotModelError: the leg does not have two or more 1-DoF joints in one chain, or a
            redundant leg is stretched at the stand pose (:func:`leg_chain`).
        UnreachableTargetError: Newton does not reach a target (or the Jacobian — the augmented
            one of a redundant leg — is singular there), or a two-joint leg's target lies off
            its plane; the message names the leg, the time and the distance.
    """
    model = robot.model
    p, pd, pdd = (np.atleast_2d(np.asarray(x, dtype=float)) for x in (p, pd, pdd))
    for name, x in (("p", p), ("pd", pd), ("pdd", pdd)):
        finite_array(f"leg {leg.name} foot target {name}", x)
    t = np.arange(len(p), dtype=float) if t is None else np.asarray(t, dtype=float)
    reference = robot.pose("stand") if "stand" in robot.poses else pin.neutral(model)
    reference[:7] = pin.neutral(model)[:7]
    chain = leg_chain(robot, leg, reference)
    if shift is not None and chain.redundant.shape[1]:
        chain = dataclasses.replace(chain, reference=chain.reference
                                    + chain.redundant @ np.asarray(shift, dtype=float))
    start = chain.reference if q0 is None else np.asarray(q0, dtype=float)
    start = start + chain.redundant @ (chain.redundant.T @ (chain.reference - start))
    held = np.zeros((3, len(p), chain.redundant.shape[1]))  # the rows' targets and rates
    reference, starts = np.tile(chain.reference, (len(p), 1)), np.tile(start, (len(p), 1))
    if turn is not None and chain.sole:  # the rows' targets move: per-sample references
        held = np.array([np.asarray(x, dtype=float) @ chain.turn_rows.T for x in turn])
        reference = reference + held[0] @ chain.redundant.T
        starts = starts + held[0] @ chain.redundant.T
    pose = chain.sole  # six joints (leg_chain checks): Newton on the foot's whole pose
    if pose:
        theta = np.zeros((3, len(p), 3)) if turn is None else \
            np.array([np.asarray(x, dtype=float) for x in turn])
        targets = np.array([pin.exp3(x) for x in theta[0]]) \
            @ chain.rotation(chain.reference[None])[0]

    def solve(k: slice, start: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        if pose:
            return _newton_pose(chain, p[k], targets[k], start)
        return _newton(chain, p[k], start, reference[k])

    q, err, off = solve(slice(None), starts)
    k = _suspect(q, err, 0)
    while k < len(p):
        batch = q[k].copy()
        q[k:k + 1], err[k:k + 1], off[k:k + 1] = solve(slice(k, k + 1),
                                                        starts[:1] if k == 0 else q[k - 1:k])
        if err[k] > NEWTON_TOL:
            break
        rejoined = np.abs(q[k] - batch).max() <= NEWTON_REJOIN
        k = _suspect(q, err, k + 1) if rejoined else k + 1
    if pose:
        _, _, aug = chain.pose_jacobian(q)
    else:
        _, jac = chain.position_jacobian(q)
        aug = chain.augmented(jac)
    singular = np.linalg.cond(aug) > 1e8
    failed = (err > NEWTON_TOL) | singular | (off > PLANE_TOL)
    if failed.any():
        k = int(np.argmax(failed))
        where = (f"leg {leg.name} at t = {t[k]:.6g} s: foot target "
                 f"{np.round(p[k], 6).tolist()} m (base frame)")
        if err[k] <= NEWTON_TOL and not singular[k]:
            raise UnreachableTargetError(
                f"{where} is {off[k]:.3g} m off the plane its {chain.angular.shape[0]} joints "
                "move the foot in (at most "
                f"{PLANE_TOL:g} m): a gait for a two-joint leg keeps each foot in its plane — "
                "no sideways shift or step (a bound, a pronk or a trot, whose sway runs in the "
                "legs' planes; not a crawl, whose body shifts sideways over its three feet)",
                leg=leg.name, t=float(t[k]), index=k, target=tuple(float(x) for x in p[k]),
                distance=float(off[k]))
        raise UnreachableTargetError(
            f"{where} is out of reach: Newton stopped {err[k]:.6g} m from it"
            + (" (or rad from its sole's flat orientation)" if pose else "")
            + (" at a singular configuration" if err[k] <= NEWTON_TOL else ""),
            leg=leg.name, t=float(t[k]), index=k, target=tuple(float(x) for x in p[k]),
            distance=float(err[k]))
    if pose:  # the foot's angular velocity is θ̇: θ turns about the base's fixed vertical
        qd = _least_squares(aug, np.concatenate([pd, theta[1]], axis=1))
        qdd = _least_squares(aug, np.concatenate([pdd - chain.bias(q, qd),
                                                  theta[2] - chain.angular_bias(q, qd)], axis=1))
        return q, qd, qdd
    qd = _least_squares(aug, np.concatenate([pd, held[1]], axis=1))
    qdd = _least_squares(aug, np.concatenate([pdd - chain.bias(q, qd), held[2]], axis=1))
    return q, qd, qdd


def _suspect(q: np.ndarray, err: np.ndarray, start: int) -> int:
    """The first sample from ``start`` on that Newton did not solve (``err`` above
    :data:`NEWTON_TOL`) or that differs from its predecessor by :data:`NEWTON_JUMP` or more,
    ``len(q)`` if none: the samples :func:`newton_leg_ik` solves again from their predecessor.

    Args:
        q: Joint values, shape (T, n). err: Their Newton errors, shape (T,). start: The first
            sample to look at.
    """
    jumps = np.r_[False, np.abs(np.diff(q, axis=0)).max(axis=1) >= NEWTON_JUMP]
    bad = np.flatnonzero((err[start:] > NEWTON_TOL) | jumps[start:])
    return start + int(bad[0]) if bad.size else len(q)


def _least_squares(jac: np.ndarray, e: np.ndarray) -> np.ndarray:
    """Per sample, the joint change that moves the foot nearest ``e``: ``J⁻¹ e`` for a square
    Jacobian (least squares where it is singular), ``J⁺ e`` for a two-joint leg's (T, 3, 2); with
    a redundant leg's augmented Jacobian ``Ĵ`` (:meth:`LegChain.augmented`), the change that
    also moves the secondary objective's rows by the rest of ``e``.

    Args:
        jac: Jacobians, shape (T, m, n): ``J`` (m = 3) or ``Ĵ`` (m = n ≥ 4). e: Foot
            displacements, shape (T, 3) (with the objective's rows, shape (T, m)).

    Returns:
        Joint changes, shape (T, n).
    """
    if jac.shape[1] == jac.shape[2]:
        try:
            return np.linalg.solve(jac, e[..., None])[..., 0]
        except np.linalg.LinAlgError:  # a singular Jacobian: the least-squares step
            pass
    return (np.linalg.pinv(jac) @ e[..., None])[..., 0]


def _log3(rot: np.ndarray) -> np.ndarray:
    """The rotation vectors of rotations ``rot`` (T, 3, 3), shape (T, 3), rad: the angle
    ``atan2(sin θ, cos θ)`` times the unit axis of the skew part ``(R − Rᵀ)/2 = sin θ [a]×``
    (Rodrigues; Murray, Li & Sastry, *A Mathematical Introduction to Robotic Manipulation*,
    1994, §2.2.2), the limit ``θ / sin θ → 1`` taken below 1e-8 rad (angles below π)."""
    vee = (rot - np.swapaxes(rot, 1, 2))[:, [2, 0, 1], [1, 2, 0]] / 2
    sine = np.linalg.norm(vee, axis=1)
    angle = np.arctan2(sine, (np.trace(rot, axis1=1, axis2=2) - 1) / 2)
    ratio = np.where(sine > 1e-8, angle / np.maximum(sine, 1e-300), 1.0)
    return vee * ratio[:, None]


def _newton_pose(chain: LegChain, p: np.ndarray, rotations: np.ndarray, q: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Newton's method on a six-joint sole leg's whole foot pose, every sample at once: the
    step solves ``[J; J_ω] Δq = [p* − p; log(R* Rᵀ)]`` (the orientation error as a rotation
    vector in the base frame; Siciliano et al., *Robotics*, 2009, §3.7; at most 0.5 rad a
    step), until position and orientation are each within :data:`NEWTON_TOL` (m, rad) or
    :data:`NEWTON_MAX_ITER` steps. Exact for any six-joint leg, where the linear rows of
    :class:`~hexaleg.motion.leg_chain.LegChain` hold the orientation exactly only for a hip
    that turns yaw, roll, pitch.

    Args:
        chain: The leg. p: Foot targets, shape (T, 3), m. rotations: Foot orientations,
            shape (T, 3, 3). q: Starting joint values, shape (T, 6).

    Returns:
        The joint values reached, shape (T, 6); their pose error, shape (T,) (the larger of
        the position's, m, and the orientation's, rad); and zeros (nothing is off a plane).
    """
    q = q.copy()
    err = np.full(len(p), np.inf)
    todo = np.arange(len(p))
    for it in range(NEWTON_MAX_ITER + 1):
        at, rot, jac = chain.pose_jacobian(q[todo])
        e = np.concatenate([p[todo] - at,
                            _log3(rotations[todo] @ np.swapaxes(rot, 1, 2))], axis=1)
        err[todo] = np.maximum(np.linalg.norm(e[:, :3], axis=1),
                               np.linalg.norm(e[:, 3:], axis=1))
        keep = err[todo] > NEWTON_TOL
        todo = todo[keep]
        if not todo.size or it == NEWTON_MAX_ITER:
            break
        step = _least_squares(jac[keep], e[keep])
        norm = np.linalg.norm(step, axis=1, keepdims=True)
        q[todo] += step * np.minimum(1.0, 0.5 / np.maximum(norm, 1e-300))
    return q, err, np.zeros(len(p))


def _newton(chain: LegChain, p: np.ndarray, q: np.ndarray, reference: np.ndarray | None = None
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Damped Newton steps (at most 0.5 rad or m a step; least squares where the Jacobian is
    singular or not square) on every sample at once until each is within :data:`NEWTON_TOL` of
    its target — of its target's projection on what the joints can reach, for a two-joint leg —
    or :data:`NEWTON_MAX_ITER` steps. A redundant leg steps with its augmented Jacobian on
    ``[p* − p; −N₀ᵀ (q − q_stand)]`` (:meth:`LegChain.task`): from a start on the secondary
    objective's plane its rows stay met to rounding, every step included.

    Args:
        chain: The leg. p: Targets, shape (T, 3), m. q: Starting joint values, shape (T, n).
        reference: Per sample, the reference the objective's rows hold, shape (T, n); default
            the chain's.

    Returns:
        The joint values reached, shape (T, n); their distance to the targets within reach,
        shape (T,), m; and what is out of reach (off a two-joint leg's plane), shape (T,), m.
    """
    q = q.copy()
    err = np.full(len(p), np.inf)
    off = np.zeros(len(p))
    todo = np.arange(len(p))
    for it in range(NEWTON_MAX_ITER + 1):
        at, jac = chain.position_jacobian(q[todo])
        e = p[todo] - at
        step = _least_squares(chain.augmented(jac), chain.task(
            q[todo], e, None if reference is None else reference[todo]))
        if jac.shape[2] >= 3:
            err[todo] = np.linalg.norm(e, axis=1)
        else:  # the part of e the joints move the foot along; the rest is off the leg's plane
            reach = np.einsum("tij,tj->ti", jac, step)
            err[todo] = np.linalg.norm(reach, axis=1)
            off[todo] = np.linalg.norm(e - reach, axis=1)
        keep = err[todo] > NEWTON_TOL
        todo, step = todo[keep], step[keep]
        if not todo.size or it == NEWTON_MAX_ITER:
            break
        norm = np.linalg.norm(step, axis=1, keepdims=True)
        q[todo] += step * np.minimum(1.0, 0.5 / np.maximum(norm, 1e-300))
    return q, err, off
