"""Feet with soles: a flat rectangle under each foot frame, laid flat on the ground in the stand.

A point foot (hexaleg's default) touches the ground at one point and transmits a force only; a
biped balances on it only dynamically. A humanoid stands on soles: the ground's force on a foot
is spread over a flat rectangle, so it carries a moment too — the centre of pressure can move
anywhere in the sole (Vukobratović & Borovac, "Zero-moment point — thirty five years of its
life", Int. J. Humanoid Robotics 1(1), 2004: the ZMP is the centre of pressure and stays in the
support polygon; Caron, Pham & Nakamura, "Stability of surface contacts for humanoid robots:
closed-form formulae of the contact wrench cone for rectangular support areas", ICRA 2015: the
contact wrench of a rectangle is exactly the sum of four point forces at its corners, each in
its friction cone).

A description declares ``sole = [length, width]`` (m): every foot is then the rectangle of that
size centred on its foot frame, the length along the frame's x axis, the width along its y, the
sole in its x–y plane. The foot frame is the sole's centre (a URDF frame on the underside of the
foot link). The stand lays each sole flat (:func:`flat_stand`): the foot frame's axes parallel to
the base's, which needs a leg that can turn its foot about every axis (six joints: hip yaw, roll
and pitch, knee, ankle pitch and roll), and the gait keeps the soles flat
(:class:`hexaleg.motion.leg_chain.LegChain`).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg.errors import InvalidParameterError, RobotModelError

FLAT_TOL = 1e-12
"""rad and m: how far from flat and from its place a foot of :func:`flat_stand` may end."""
FLAT_MAX_ITER = 50
"""Newton iterations :func:`flat_stand` takes at most per leg."""


@dataclass(frozen=True)
class Sole:
    """A flat rectangular sole centred on a foot frame (module docstring).

    Attributes:
        length: Along the foot frame's x axis, m, > 0.
        width: Along its y axis, m, > 0.
    """

    length: float
    width: float

    def corners(self) -> np.ndarray:
        """The sole's corners in the foot frame, shape (4, 3), m: front left, front right,
        back left, back right (``(±l/2, ±w/2, 0)``)."""
        a, b = self.length / 2, self.width / 2
        return np.array([[a, b, 0.0], [a, -b, 0.0], [-a, b, 0.0], [-a, -b, 0.0]])


def sole_of(name: str, value: Any) -> Sole:
    """A description's ``sole = [length, width]`` (m) as a :class:`Sole`.

    Raises:
        InvalidParameterError: not two finite lengths > 0 (names the robot and the value).
    """
    try:
        length, width = (float(v) for v in value)
    except (TypeError, ValueError):
        raise InvalidParameterError(f"{name}: sole", value,
                                    "[length, width], two lengths in m") from None
    if not (np.isfinite(length) and np.isfinite(width) and length > 0 and width > 0):
        raise InvalidParameterError(f"{name}: sole", value,
                                    "[length, width], each a finite length > 0 m")
    return Sole(length, width)


def flat_stand(robot: Any, stand: np.ndarray, legs: Sequence[str]) -> np.ndarray:
    """The stand with each named leg's sole laid flat: its foot frame's axes parallel to the
    base's and its origin where the stand put it — Newton's method on the foot's pose
    ``[p − p₀; log(R)]`` with its 6 × n frame Jacobian (world-aligned; Siciliano et al.,
    *Robotics*, 2009, §3.7, inverse kinematics with the orientation error as a rotation
    vector), least squares for a leg of other than six joints.

    Args:
        robot: The loaded robot (:class:`~hexaleg.robot.loaded.Robot`), base at the origin.
        stand: The stand pose, shape (nq,).
        legs: Names of the legs with soles.

    Returns:
        The pose, shape (nq,).

    Raises:
        RobotModelError: a leg that cannot lay its sole flat at its foot's place (names the
            leg, how far from flat it stays and what a sole needs), or one whose flat stand
            leaves a joint's URDF limits (names the joint).
    """
    model, q = robot.model, np.array(stand, dtype=float)
    data = model.createData()
    for leg in robot.legs:
        if leg.name not in legs:
            continue
        pin.framesForwardKinematics(model, data, q)
        target = data.oMf[leg.foot_frame_id].translation.copy()
        error = np.inf
        for _ in range(FLAT_MAX_ITER):
            pin.computeJointJacobians(model, data, q)
            pin.framesForwardKinematics(model, data, q)
            frame = data.oMf[leg.foot_frame_id]
            e = np.r_[target - frame.translation, -pin.log3(frame.rotation)]
            error = float(np.abs(e).max())
            if error <= FLAT_TOL:
                break
            jac = pin.getFrameJacobian(model, data, leg.foot_frame_id,
                                       pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)[:, leg.v_index]
            step = np.linalg.lstsq(jac, e, rcond=None)[0]
            q[leg.q_index] += step * min(1.0, 0.3 / max(float(np.abs(step).max()), 1e-300))
        if error > FLAT_TOL:
            raise RobotModelError(
                f"{robot.name}: leg {leg.name} cannot lay its sole flat where the stand puts "
                f"its foot ({error:.3g} rad or m from it, {len(leg.joint_names)} joints); a "
                "sole needs a leg that turns its foot about every axis (six joints: hip yaw, "
                "roll and pitch, knee, ankle pitch and roll)")
        lower, upper = model.lowerPositionLimit, model.upperPositionLimit
        for name, i in zip(leg.joint_names, leg.q_index, strict=True):
            if not lower[i] <= q[i] <= upper[i]:
                raise RobotModelError(
                    f"{robot.name}: leg {leg.name}'s flat sole needs {name} at {q[i]:.4g} rad, "
                    f"outside its URDF limits [{lower[i]:.4g}, {upper[i]:.4g}] rad; give a stand "
                    "whose foot the leg reaches flat (stand = {body_height = …})")
    return q
