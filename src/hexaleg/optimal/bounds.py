"""The optimal-control problem's bounds at each knot (:mod:`~hexaleg.optimal.problem` puts them
under quadratic barriers): each leg's knee held off its full stretch by a reach margin
(:func:`knee_bounds`, the law of cosines of the leg's two links), and the ground under each
swing foot (:func:`ground_heights`, the lower of the footholds it leaves and lands on). Plain
kinematics of the warm start and its footholds: no Crocoddyl."""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from hexaleg.errors import InvalidParameterError
from hexaleg.robot.model import Robot


def ground_heights(stance: np.ndarray, footholds: np.ndarray,
                   displacement: np.ndarray) -> np.ndarray:
    """The ground's height under each swing foot at each knot, (N, n_legs), m (NaN at a stance
    knot): the lower of the footholds it lifted off and lands on (the cycle's displacement
    applied to one in another cycle), so a swing foot between two footholds of one height stays
    above that plane. A leg that never stands has no ground: NaN."""
    n, legs = stance.shape
    out = np.full((n, legs), np.nan)
    for j in range(legs):
        if not stance[:, j].any():
            continue
        for k in np.flatnonzero(~stance[:, j]):
            ends = []
            for step in (-1, 1):
                s = k
                while not stance[s % n, j]:
                    s += step
                p = np.append(footholds[s % n, j], 1.0)
                wraps = s // n
                shift = np.linalg.matrix_power(displacement, abs(wraps))
                ends.append((shift if wraps >= 0 else np.linalg.inv(shift))[:3] @ p)
            out[k, j] = min(e[2] for e in ends)
    return out


def knee_bounds(robot: Robot, qs: np.ndarray, margin: float) -> tuple[np.ndarray, np.ndarray]:
    """Bounds on the configuration that keep each leg's end ``margin`` short of its full
    stretch, (N, nq) lower and upper (the model's position limits, a knee's narrowed).

    A leg's knee is the last of its joints that can stretch it: revolute about the unit axis
    ``a`` through its origin ``o``, with the joint before it (origin ``h``, the hip) and the
    leg's end past it (``f``: the foot for the last joint; for a joint before it, the next
    joint's origin) both off that axis. The end is a point no later joint moves (a joint's
    origin is fixed on the link before it), so the distance ``d`` from ``h`` to ``f`` depends
    on the knee angle ``θ`` alone (a joint rotates about an axis through its own origin, so the
    joints before the knee keep every distance to ``h``). A leg that ends in a knee holds its
    foot; one that ends in ankle joints about axes through one point (tests/data/biped6.toml's
    pitch and roll: neither can move that point off the hip) holds its ankle, the foot past it
    turned by the ankle. With ``u = o − h`` and ``w = f − o`` each split into a part along
    ``a`` (``u_a``, ``w_a``) and across it (lengths ``r_u``, ``r_w``), the law of cosines gives

        d(θ)² = (u_a + w_a)² + r_u² + r_w² + 2 r_u r_w cos(θ − θ*),

    ``θ*`` the angle that lines the across parts up: the leg stretched, ``d`` its reach
    ``d* = √((u_a + w_a)² + (r_u + r_w)²)`` (Craig, *Introduction to Robotics*, 3rd ed., §4.2,
    the two-link arm's workspace). ``d ≤ d* − margin`` holds where ``|θ − θ*| ≥ δ``,
    ``cos δ = ((d* − margin)² − (u_a + w_a)² − r_u² − r_w²) / (2 r_u r_w)``: at each knot the
    knee is kept at least ``δ`` off ``θ*`` on the side the warm start ``qs`` bends it to (a
    front and a hind knee may bend opposite ways). A leg none of whose joints can stretch it
    (each with its hip or end on its axis): no bound.

    Args:
        robot: The robot; every leg of two joints or more, revolute from its knee on (one
            coordinate each).
        qs: The warm start's configurations at the knots, (N, nq).
        margin: How far short of its reach each leg's end is held, m, ≥ 0.

    Raises:
        InvalidParameterError: a leg of one joint, or a joint after its knee (or the knee)
            that is not revolute.
    """
    model, data = robot.model, robot.data
    lower = np.tile(model.lowerPositionLimit, (len(qs), 1))
    upper = np.tile(model.upperPositionLimit, (len(qs), 1))
    pin.computeJointJacobians(model, data, qs[0])
    pin.framesForwardKinematics(model, data, qs[0])
    for leg in robot.legs:
        ids = leg.joint_ids
        if len(ids) < 2:
            raise InvalidParameterError(f"leg {leg.name}'s joints", leg.joint_names,
                                        "two joints or more, revolute from the knee on")
        end = data.oMf[leg.foot_frame_id].translation  # the last joint's end: the foot
        for b in range(len(ids) - 1, 0, -1):  # from the last joint back, to the knee
            knee = ids[b]
            motion = pin.getJointJacobian(model, data, knee, pin.LOCAL)[:, leg.v_index[b]]
            if model.joints[knee].nq != 1 or np.linalg.norm(motion[:3]) > 1e-12:
                raise InvalidParameterError(f"leg {leg.name}'s joints", leg.joint_names,
                                            "two joints or more, revolute from the knee on")
            axis = motion[3:] / np.linalg.norm(motion[3:])  # in the knee's frame
            u = -data.oMi[knee].actInv(data.oMi[ids[b - 1]].translation)
            w = data.oMi[knee].actInv(end)
            u_t, w_t = u - (u @ axis) * axis, w - (w @ axis) * axis
            r_u, r_w = float(np.linalg.norm(u_t)), float(np.linalg.norm(w_t))
            if r_u * r_w >= 1e-12:
                break
            end = data.oMi[knee].translation.copy()  # the joint before: its end is this origin
        else:
            continue
        along = float((u + w) @ axis)
        i = int(leg.q_index[b])
        stretched = float(qs[0, i]) + float(np.arctan2(axis @ np.cross(w_t, u_t), w_t @ u_t))
        reach = float(np.hypot(along, r_u + r_w))
        cos_delta = ((reach - margin) ** 2 - along**2 - r_u**2 - r_w**2) / (2.0 * r_u * r_w)
        delta = float(np.arccos(np.clip(cos_delta, -1.0, 1.0)))
        off = np.angle(np.exp(1j * (qs[:, i] - stretched)))  # θ − θ*, wrapped to (−π, π]
        lower[off >= 0.0, i] = np.maximum(lower[off >= 0.0, i], stretched + delta)
        upper[off < 0.0, i] = np.minimum(upper[off < 0.0, i], stretched - delta)
    return lower, upper

__all__ = ["ground_heights", "knee_bounds"]
