"""The dynamics residual of a trajectory: Newton–Euler by Pinocchio against its torques and
contact forces, independent of the solver that made it.

For each knot ``k`` of a trajectory integrated by Crocoddyl's Euler scheme
(``v_{k+1} = v_k + a_k dt``, ``q_{k+1} = q_k ⊕ v_{k+1} dt``; Crocoddyl's
``IntegratedActionModelEuler``) the acceleration is ``a_k = (v_{k+1} − v_k)/dt`` and the
equations of motion (Featherstone, *Rigid Body Dynamics Algorithms*, §5.3, RNEA with external
forces) must hold::

    RNEA(q_k, v_k, a_k, f_ext) = [0₆; u_k + τ_s(q_k, v_k)]

with ``f_ext`` each stance foot's force ``λ`` (world axes) applied at its foot frame's origin —
the world wrench ``(λ, p × λ)`` carried into the foot's parent joint frame. The residual is the
difference, N·m (N on the base's linear rows); the base rows say whether the feet carry the robot,
the joint rows whether the motors and springs make the motion.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from hexaleg.errors import InvalidParameterError
from hexaleg.robot.model import Robot


def dynamics_residual(robot: Robot, q: np.ndarray, v: np.ndarray, dt: float,
                      joint_torques: np.ndarray, forces: np.ndarray) -> np.ndarray:
    """Newton–Euler residual of every knot (module docstring).

    Args:
        robot: The robot (free flyer).
        q: Configurations at the knots, (N + 1, nq).
        v: Velocities at the knots, (N + 1, nv).
        dt: Knot spacing, s.
        joint_torques: Motor plus spring torque of every actuated joint, (N, nj), N·m.
        forces: Each leg's foot force in world axes, (N, n_legs, 3), N (zero in swing).

    Returns:
        The residual, (N, nv).
    """
    model, data = robot.model, robot.data
    n = len(joint_torques)
    if q.shape != (n + 1, model.nq) or v.shape != (n + 1, model.nv):
        raise InvalidParameterError("trajectory shapes", (q.shape, v.shape),
                                    f"({n + 1}, {model.nq}) and ({n + 1}, {model.nv})")
    if forces.shape != (n, len(robot.legs), 3):
        raise InvalidParameterError("forces.shape", forces.shape, f"({n}, {len(robot.legs)}, 3)")
    out = np.zeros((n, model.nv))
    for k in range(n):
        a = (v[k + 1] - v[k]) / dt
        pin.framesForwardKinematics(model, data, q[k])
        fext = [pin.Force.Zero() for _ in range(model.njoints)]
        for j, leg in enumerate(robot.legs):
            frame = model.frames[leg.foot_frame_id]
            p = data.oMf[leg.foot_frame_id].translation
            world = pin.Force(forces[k, j], np.cross(p, forces[k, j]))
            fext[frame.parentJoint] += data.oMi[frame.parentJoint].actInv(world)
        tau = pin.rnea(model, data, q[k], v[k], a, fext)
        out[k] = tau - np.concatenate([np.zeros(model.nv - robot.nj), joint_torques[k]])
    return out
