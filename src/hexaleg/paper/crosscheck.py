"""Cross-check of the paper's rigid joint torque (eq. 13) with Pinocchio's RNEA on the robot model.

The robot's femur link carries the Table 6 lever, so the whole-robot model reduced to one femur
joint must reproduce :meth:`hexaleg.paper.joint.PaperJoint.baseline_torque` exactly.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
from numpy.typing import ArrayLike

from hexaleg.paper.joint import POSTURES, PaperJoint
from hexaleg.robot.model import load_robot


def pinocchio_femur_torque(t: ArrayLike, joint: PaperJoint | None = None, leg: str = "LF",
                           gravity: bool = True) -> np.ndarray:
    """Rigid femur torque from Pinocchio's RNEA on the robot model reduced to one femur joint.

    Every other joint and the free-flyer base are locked at the ``zero`` pose
    (``pin.buildReducedModel``); the links beyond the femur (tibia, foot) are given zero inertia,
    so the moving body is the femur link alone (Table 6 mass, CoM and inertia). Gravity points
    along the femur link's +x axis at θ = 0 for ``posture="hanging"`` (the lever hangs, eq. 6:
    potential −m g l cos θ) and along −x for ``"upright"``.

    Args:
        t: Times, s, shape (T,).
        joint: Trajectory and gravity (default :class:`PaperJoint`); its m, l, I are not used —
            the robot model's are.
        leg: Which leg's femur.
        gravity: Include gravity.

    Returns:
        Joint torque, N·m, shape (T,), the same quantity as :meth:`PaperJoint.baseline_torque`.
    """
    j = joint or PaperJoint()
    robot = load_robot()
    name = f"{robot.leg(leg).name}_femur"
    model = pin.Model(robot.model)
    femur = model.getJointId(name)
    for jid in range(1, model.njoints):
        if _descends(model, jid, femur):
            model.inertias[jid] = pin.Inertia.Zero()
    lock = [jid for jid in range(1, model.njoints) if jid != femur]
    reduced = pin.buildReducedModel(model, lock, robot.pose("zero"))
    data = reduced.createData()
    pin.forwardKinematics(reduced, data, np.zeros(1))
    x_axis = data.oMi[1].rotation[:, 0]
    s = POSTURES[j.posture]
    reduced.gravity.linear = s * j.gravity * x_axis if gravity else np.zeros(3)
    th, thd, thdd = j.trajectory(t)
    return np.array([pin.rnea(reduced, data, np.array([a]), np.array([b]), np.array([c]))[0]
                     for a, b, c in zip(np.ravel(th), np.ravel(thd), np.ravel(thdd),
                                        strict=True)])


def _descends(model: pin.Model, jid: int, ancestor: int) -> bool:
    """Whether joint ``jid`` of ``model`` lies beyond (is a descendant of) joint ``ancestor``."""
    while jid > 0:
        jid = model.parents[jid]
        if jid == ancestor:
            return True
    return False
