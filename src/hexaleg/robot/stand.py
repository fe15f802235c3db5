"""A standing pose from where the feet are: foot positions and a body height, solved per leg.

Users know how high their robot stands and roughly where its feet go; they rarely know the joint
angles. :func:`stand_from_feet` places each foot at ``(x, y, −body_height)`` in the base frame
(``x, y`` given, or the foot's at the zero configuration) and solves the leg's joints by damped
least squares on the foot position (Levenberg–Marquardt; Nakamura & Hanafusa, "Inverse
kinematics solutions with singularity robustness", 1986; Buss, "Introduction to inverse
kinematics with Jacobian transpose, pseudoinverse and damped least squares methods", 2004),
from several bent-knee starts: the solution kept is within the URDF joint limits and farthest
from a singular (stretched) leg, i.e. with the largest smallest singular value of the foot
Jacobian. Those starts suit a yaw–pitch–knee leg; when none of them ends within the limits (a
hip that turns pitch–roll–yaw, a knee whose range excludes 0), the solver starts again from
points inside the limits with each step projected into them (box-constrained damped least
squares, Kanzow, Yamashita & Fukushima, "Levenberg–Marquardt methods with strong local
convergence properties for solving nonlinear equations with convex constraints", J. Comput.
Appl. Math. 172, 2004). A foot reached only outside the limits is refused as such, naming the
joint and the limit; a foot no start reaches is refused as out of reach.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
import pinocchio as pin

from hexaleg.errors import InvalidParameterError, UnknownNameError

if TYPE_CHECKING:
    from hexaleg.robot.model import Leg, Robot

TOLERANCE = 1e-9
"""m: a foot this close to its target is placed."""
ITERATIONS = 200
DAMPING = 1e-6
BENDS = (0.0, 0.4, -0.4, 0.8, -0.8)
"""rad: start angles of each leg's second joint; the joints after it bend twice as far, in turn
back and forth (a zig-zag: a knee, then an ankle bent the other way)."""
NULL_GAIN = 0.2
"""Share of the way to the preferred pose a projected step moves the leg's self-motion."""
INTERIOR_STARTS = 16
"""Starts inside the joint limits tried when no bent-knee start gives a pose within them
(:func:`interior_starts`): a hip that turns pitch–roll–yaw, a knee whose range excludes 0."""


def hold_other_joints(robot: Robot, q: np.ndarray, given: Mapping[str, float], *,
                      legs_too: bool = False) -> np.ndarray:
    """``q`` with the joints of ``given`` at their angles and every joint on no leg
    (:attr:`~hexaleg.robot.model.Robot.other_joints`) not given at its value in ``q`` clipped
    into its URDF limits: an arm or a torso holds a pose it can take.

    Args:
        robot: The robot.
        q: The configuration, shape (nq,) (not changed).
        given: Joint → angle, rad (or m), for joints on no leg (any joint with ``legs_too``).
        legs_too: Whether ``given`` may name leg joints (a stand given joint by joint).

    Returns:
        The configuration, shape (nq,).

    Raises:
        UnknownNameError: ``given`` names no actuated joint (lists them), or a leg joint
            without ``legs_too`` (lists the joints on no leg: the legs' pose is solved).
    """
    from hexaleg.errors import UnknownNameError

    model = robot.model
    out = np.array(q, dtype=float)
    others = robot.other_joints
    for joint, value in given.items():
        robot.column(joint)  # an unknown joint raises, listing the joints
        if not legs_too and joint not in others:
            raise UnknownNameError("stand.joints entry (a joint on no leg; the legs' joints are "
                                   "solved from body_height)", joint, others)
        out[model.joints[model.getJointId(joint)].idx_q] = value
    for joint in others:
        if joint in given:
            continue
        iq = model.joints[model.getJointId(joint)].idx_q
        out[iq] = np.clip(out[iq], model.lowerPositionLimit[iq], model.upperPositionLimit[iq])
    return out


def stand_from_feet(robot: Robot, body_height: float,
                    feet: Mapping[str, Sequence[float]] | None = None,
                    q: np.ndarray | None = None) -> np.ndarray:
    """The standing configuration with the feet at ``(x, y, −body_height)`` in the base frame.

    Args:
        robot: The robot (its legs and joint limits).
        body_height: Height of the base origin above the feet, m, > 0.
        feet: Leg → ``[x, y]`` (m, base frame); legs not given keep their foot's ``x, y`` at the
            zero configuration.
        q: The configuration of the joints on no leg, shape (nq,) (its leg joints are solved);
            default Pinocchio's neutral one.

    Returns:
        The configuration, shape (nq,), base at the origin.

    Raises:
        InvalidParameterError: a bad height or foot position, an unknown leg, or a foot no joint
            angles within the limits can reach (names the leg, the target and the leg's reach).
    """
    if not (np.isfinite(body_height) and body_height > 0):
        raise InvalidParameterError("stand.body_height", body_height, "a height > 0 (m)")
    given = {name: np.asarray(xy, dtype=float) for name, xy in (feet or {}).items()}
    for name, xy in given.items():
        robot.leg(name)  # an unknown leg raises, listing the legs
        if xy.shape != (2,) or not np.all(np.isfinite(xy)):
            raise InvalidParameterError(f"stand.feet.{name}", xy, "[x, y] (m, finite)")
    model = robot.model
    q = pin.neutral(model) if q is None else np.array(q, dtype=float)
    zero = q.copy()
    for leg in robot.legs:
        zero[leg.q_index] = pin.neutral(model)[leg.q_index]
    zero_feet = robot.foot_positions(zero)
    for k, leg in enumerate(robot.legs):
        xy = given.get(leg.name, zero_feet[k, :2])
        q[leg.q_index] = _solve(robot, leg, np.array([xy[0], xy[1], -body_height]), q)
    return q


def _newton(robot: Robot, data: pin.Data, leg: Leg, target: np.ndarray, q: np.ndarray,
            box: tuple[np.ndarray, np.ndarray] | None = None, pull: bool = False) -> float:
    """Damped least squares on the foot position from ``q`` (changed in place), each step at
    most 0.3 rad; with ``box``, projected into the joint limits (a box-constrained
    Levenberg–Marquardt step, its iterates feasible), and with ``pull`` each step also moves
    the leg's self-motion towards the zero configuration clipped into the box (the null-space
    term ``(I − J⁺J) (q_pref − q)``, Siciliano et al., *Robotics*, 2009, §3.5.1: a redundant
    leg — a humanoid's six joints — untwists where it can); the foot's distance to
    ``target``, m."""
    model = robot.model
    err = np.inf
    for _ in range(ITERATIONS):
        pin.framesForwardKinematics(model, data, q)
        e = target - data.oMf[leg.foot_frame_id].translation
        err = float(np.linalg.norm(e))
        if err < TOLERANCE and not pull:
            break
        jac = pin.computeFrameJacobian(model, data, q, leg.foot_frame_id,
                                       pin.LOCAL_WORLD_ALIGNED)[:3, leg.v_index]
        if pull and box is not None:
            pinv = jac.T @ np.linalg.inv(jac @ jac.T + DAMPING * np.eye(3))
            untwist = NULL_GAIN * (np.eye(len(leg.q_index)) - pinv @ jac) @ (
                np.clip(0.0, *box) - q[leg.q_index])
            if err < TOLERANCE and float(np.linalg.norm(untwist)) < TOLERANCE:
                break
            step = pinv @ e + untwist
        else:
            step = jac.T @ np.linalg.solve(jac @ jac.T + DAMPING * np.eye(3), e)
        q[leg.q_index] += step * min(1.0, 0.3 / max(float(np.linalg.norm(step)), 1e-300))
        if box is not None:
            q[leg.q_index] = np.clip(q[leg.q_index], *box)
    return err


def interior_starts(lo: np.ndarray, hi: np.ndarray, count: int = INTERIOR_STARTS) -> np.ndarray:
    """Start points inside the joint limits, shape (count, n): the middle of the box, the two
    zig-zags at a quarter and three quarters of each range (a knee bent one way, the next joint
    the other), then points drawn uniformly from the box's inner 80 % (seeded: the same starts
    on every machine). A joint without a finite limit is sampled on [−π, π]."""
    lo = np.where(np.isfinite(lo) & (lo > -1e10), lo, -np.pi)
    hi = np.where(np.isfinite(hi) & (hi < 1e10), hi, np.pi)
    n = len(lo)
    sign = (-1.0) ** np.arange(n)
    fractions = [np.full(n, 0.5), 0.5 + 0.25 * sign, 0.5 - 0.25 * sign]
    rng = np.random.default_rng(0)
    fractions += list(0.1 + 0.8 * rng.random((max(count - 3, 0), n)))
    return lo + np.array(fractions[:count]) * (hi - lo)


def _beyond(angles: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """How far each joint is outside its limits, rad (≤ 0 inside)."""
    return np.maximum(lo - angles, angles - hi)


def _solve(robot: Robot, leg: Leg, target: np.ndarray, rest: np.ndarray) -> np.ndarray:
    """The leg's joints that put its foot on ``target`` within the joint limits: from the
    bent-knee starts (:data:`BENDS`), else from points inside the limits with each step
    projected into them (:func:`interior_starts`); of the solutions within the limits, the one
    farthest from a singular leg."""
    model = robot.model
    data = model.createData()
    lo, hi = model.lowerPositionLimit[leg.q_index], model.upperPositionLimit[leg.q_index]
    best, best_sigma, closest = None, -np.inf, np.inf
    outside: np.ndarray | None = None  # angles reaching it outside the limits, least beyond
    near: tuple[float, np.ndarray] | None = None  # the closest start kept within the limits
    starts: list[tuple[np.ndarray, bool]] = []
    for bend in BENDS:
        q = rest.copy()
        if len(leg.q_index) >= 2:
            q[leg.q_index[1]] = bend
        for i, k in enumerate(leg.q_index[2:]):
            q[k] = -2.0 * bend * (-1.0) ** i
        starts.append((q, False))
    for point in interior_starts(lo, hi):
        q = rest.copy()
        q[leg.q_index] = point
        starts.append((q, True))
    for q, projected in starts:
        if projected and best is not None:
            break  # the bent-knee starts found a pose within the limits: keep theirs
        err = _newton(robot, data, leg, target, q, (lo, hi) if projected else None)
        if projected and err < TOLERANCE and len(lo) > 3:  # untwist a redundant leg
            untwisted = q.copy()
            _newton(robot, data, leg, target, untwisted, (lo, hi), pull=True)
            if _newton(robot, data, leg, target, untwisted, (lo, hi)) < TOLERANCE:
                q = untwisted  # the untwisted pose, put back on the target exactly
        closest = min(closest, err)
        angles = q[leg.q_index].copy()
        if projected and (near is None or err < near[0]):
            near = (err, angles)
        if err >= TOLERANCE:
            continue
        beyond = _beyond(angles, lo, hi)
        if beyond.max() > 1e-9:
            if outside is None or beyond.max() < _beyond(outside, lo, hi).max():
                outside = angles
            continue
        pin.framesForwardKinematics(model, data, q)
        jac = pin.computeFrameJacobian(model, data, q, leg.foot_frame_id,
                                       pin.LOCAL_WORLD_ALIGNED)[:3, leg.v_index]
        sigma = float(np.linalg.svd(jac, compute_uv=False)[-1])
        if projected:  # of the poses inside the limits, the least twisted
            sigma = -float(np.linalg.norm(angles - np.clip(0.0, lo, hi)))
        if sigma > best_sigma:
            best, best_sigma = angles, sigma
    if best is not None:
        return best
    where = f"stand foot of leg {leg.name}"
    at = [round(float(v), 4) for v in target]
    held = ""
    if near is not None:
        pinned = [i for i in range(len(lo)) if min(abs(near[1][i] - lo[i]),
                                                     abs(near[1][i] - hi[i])) < 1e-9]
        if pinned:
            held = (f"; within the limits it stops {near[0]:.3g} m from it, held by "
                    + ", ".join(f"joint {leg.joint_names[i]} at its "
                                f"{'lower' if abs(near[1][i] - lo[i]) < 1e-9 else 'upper'} "
                                f"limit {near[1][i]:+.4g} rad" for i in pinned))
    if outside is not None:
        i = int(np.argmax(_beyond(outside, lo, hi)))
        side, limit = ("lower", lo[i]) if outside[i] < lo[i] else ("upper", hi[i])
        fixed = [name for name, a, b in zip(leg.joint_names, lo, hi, strict=True) if a == b]
        advice = (f"{', '.join(fixed)} {'has' if len(fixed) == 1 else 'have'} no range "
                  "(lower = upper: a URDF <limit> without lower and upper reads as 0), so no "
                  "body_height bends this leg: give "
                  f"{'it its' if len(fixed) == 1 else 'them their'} <limit lower=… upper=…> in "
                  "the URDF" if fixed else
                  "change body_height or the feet, or the URDF <limit> if it is wrong")
        raise InvalidParameterError(
            where, at,
            f"a point the leg reaches within its joint limits — outside the limits: the leg "
            f"reaches it only with joint {leg.joint_names[i]} at {outside[i]:+.4g} rad, beyond "
            f"its {side} limit {limit:+.4g} rad{held} ({len(starts)} starts, "
            f"{len(starts) - len(BENDS)} of them inside the limits): {advice}")
    pin.framesForwardKinematics(model, data, rest)
    hip = data.oMi[leg.joint_ids[0]].translation
    reach = float(np.linalg.norm(data.oMf[leg.foot_frame_id].translation - hip))
    distance = float(np.linalg.norm(target - hip))
    advice = ("lower body_height or bring the foot closer to the hip" if distance > reach else
              "the leg does not fold that short: raise body_height or move the foot away from "
              "the hip")
    raise InvalidParameterError(
        where, at,
        f"a point the leg reaches within its joint limits (out of reach: it stops "
        f"{closest:.3g} m from it, {distance:.3g} m from the first joint; the foot is "
        f"{reach:.3g} m from the first joint when stretched{held}): {advice}")


def checked_moves(name: str, robot: Robot, stand: np.ndarray, moves: Mapping[str, Any]
                  ) -> dict[str, tuple[float, float]]:
    """``moves`` against the loaded robot: each joint one on no leg
    (:attr:`~hexaleg.robot.loaded.Robot.other_joints`), its swing about the stand within its
    URDF limits.

    Raises:
        UnknownNameError: a joint on a leg or not in the robot (lists the joints on no leg).
        InvalidParameterError: a swing that leaves the joint's limits (names them).
    """
    model = robot.model
    for joint, (amplitude, _) in moves.items():
        if joint not in robot.other_joints:
            raise UnknownNameError(f"joint in {name}'s moves (one on no leg)", joint,
                                   robot.other_joints)
        idx = model.joints[model.getJointId(joint)].idx_q
        lo, hi, at = model.lowerPositionLimit[idx], model.upperPositionLimit[idx], stand[idx]
        if at - amplitude < lo or at + amplitude > hi:
            raise InvalidParameterError(
                f"{name}: moves.{joint}.amplitude", amplitude,
                f"a swing within the joint's limits [{lo:.4g}, {hi:.4g}] rad about its stand "
                f"angle {at:.4g} rad (at most {min(at - lo, hi - at):.4g})")
    return dict(moves)

