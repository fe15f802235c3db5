"""A standing pose from where the feet are: foot positions and a body height, solved per leg.

Users know how high their robot stands and roughly where its feet go; they rarely know the joint
angles. :func:`stand_from_feet` places each foot at ``(x, y, −body_height)`` in the base frame
(``x, y`` given, or the foot's at the zero configuration) and solves the leg's joints by damped
least squares on the foot position (Levenberg–Marquardt; Nakamura & Hanafusa, "Inverse
kinematics solutions with singularity robustness", 1986; Buss, "Introduction to inverse
kinematics with Jacobian transpose, pseudoinverse and damped least squares methods", 2004),
from several bent-knee starts: the solution kept is within the URDF joint limits and farthest
from a singular (stretched) leg, i.e. with the largest smallest singular value of the foot
Jacobian.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import numpy as np
import pinocchio as pin

from hexaleg.errors import InvalidParameterError

if TYPE_CHECKING:
    from hexaleg.robot.model import Leg, Robot

TOLERANCE = 1e-9
"""m: a foot this close to its target is placed."""
ITERATIONS = 200
DAMPING = 1e-6
BENDS = (0.0, 0.4, -0.4, 0.8, -0.8)
"""rad: start angles of each leg's second joint; the joints after it bend twice as far, in turn
back and forth (a zig-zag: a knee, then an ankle bent the other way)."""


def stand_from_feet(robot: Robot, body_height: float,
                    feet: Mapping[str, Sequence[float]] | None = None) -> np.ndarray:
    """The standing configuration with the feet at ``(x, y, −body_height)`` in the base frame.

    Args:
        robot: The robot (its legs and joint limits).
        body_height: Height of the base origin above the feet, m, > 0.
        feet: Leg → ``[x, y]`` (m, base frame); legs not given keep their foot's ``x, y`` at the
            zero configuration.

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
    q = pin.neutral(model)
    zero_feet = robot.foot_positions(q)
    for k, leg in enumerate(robot.legs):
        xy = given.get(leg.name, zero_feet[k, :2])
        q[leg.q_index] = _solve(robot, leg, np.array([xy[0], xy[1], -body_height]))
    return q


def _solve(robot: Robot, leg: Leg, target: np.ndarray) -> np.ndarray:
    model = robot.model
    data = model.createData()
    lo, hi = model.lowerPositionLimit[leg.q_index], model.upperPositionLimit[leg.q_index]
    best, best_sigma, closest = None, -1.0, np.inf
    for bend in BENDS:
        q = pin.neutral(model)
        if len(leg.q_index) >= 2:
            q[leg.q_index[1]] = bend
        for i, k in enumerate(leg.q_index[2:]):
            q[k] = -2.0 * bend * (-1.0) ** i
        err = np.inf
        for _ in range(ITERATIONS):
            pin.framesForwardKinematics(model, data, q)
            e = target - data.oMf[leg.foot_frame_id].translation
            err = float(np.linalg.norm(e))
            if err < TOLERANCE:
                break
            jac = pin.computeFrameJacobian(model, data, q, leg.foot_frame_id,
                                           pin.LOCAL_WORLD_ALIGNED)[:3, leg.v_index]
            step = jac.T @ np.linalg.solve(jac @ jac.T + DAMPING * np.eye(3), e)
            q[leg.q_index] += step * min(1.0, 0.3 / max(float(np.linalg.norm(step)), 1e-300))
        closest = min(closest, err)
        angles = q[leg.q_index]
        if err >= TOLERANCE or np.any(angles < lo - 1e-9) or np.any(angles > hi + 1e-9):
            continue
        jac = pin.computeFrameJacobian(model, data, q, leg.foot_frame_id,
                                       pin.LOCAL_WORLD_ALIGNED)[:3, leg.v_index]
        sigma = float(np.linalg.svd(jac, compute_uv=False)[-1])
        if sigma > best_sigma:
            best, best_sigma = angles.copy(), sigma
    if best is None:
        pin.framesForwardKinematics(model, data, pin.neutral(model))
        hip = data.oMi[leg.joint_ids[0]].translation
        reach = float(np.linalg.norm(data.oMf[leg.foot_frame_id].translation - hip))
        raise InvalidParameterError(
            f"stand foot of leg {leg.name}", [round(float(v), 4) for v in target],
            f"a point the leg reaches within its joint limits (it stops {closest:.3g} m from "
            f"it; the foot is {reach:.3g} m from the first joint when stretched): lower "
            "body_height or bring the foot closer to the hip")
    return best
