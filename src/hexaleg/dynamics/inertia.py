"""Kinematic and inertial facts of a robot on a motion: each joint's range and apparent inertia.

The apparent inertia of a joint is the diagonal entry ``M[v, v]`` of the joint-space mass matrix
(Pinocchio CRBA) at the motion's mean posture: with the base and the other joints held, the
moment of inertia about the joint axis of everything distal to it — the paper's ``m l² + I``
(eq. 5). It is eq. 24's I (:meth:`hexaleg.dynamics.prepare.Prepared.inertia`) and eq. 19's J
(:func:`hexaleg.design.rules.k_M`).
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot


def joint_range(robot: Robot, motion: Motion, joint: str) -> tuple[float, float]:
    """Smallest and largest angle of ``joint`` over ``motion``, rad.

    Raises:
        UnknownNameError: ``joint`` is not an actuated joint (lists them).
    """
    col = robot.column(joint)
    q = motion.q[:, 7 + col]
    return float(q.min()), float(q.max())


def apparent_inertias(robot: Robot, motion: Motion) -> np.ndarray:
    """Inertia ``M[v, v]`` seen by every actuated joint at the motion's mean joint angles, kg·m²,
    shape (nj,) in ``robot.joint_names`` order (one CRBA).

    With the base and the other joints held, this is the moment of inertia about the joint axis
    of everything distal to the joint — the paper's ``m l² + I`` (eq. 5).
    """
    q = motion.q[0].copy()  # the joint block of M does not depend on the base placement
    q[7:] = motion.q[:, 7:].mean(axis=0)
    M = pin.crba(robot.model, robot.data, q)
    return np.diag(M)[6:].copy()


def apparent_inertia(robot: Robot, motion: Motion, joint: str) -> float:
    """:func:`apparent_inertias` of one joint, kg·m².

    Raises:
        UnknownNameError: ``joint`` is not an actuated joint (lists them).
    """
    return float(apparent_inertias(robot, motion)[robot.column(joint)])
