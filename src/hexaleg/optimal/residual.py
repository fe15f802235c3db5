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

A Runge–Kutta knot (``OptimalParams.integrator`` ``"rk2"`` … ``"rk4"``, Crocoddyl's
``IntegratedActionModelRK``) steps its state through stages whose accelerations differ, so
``(v_{k+1} − v_k)/dt`` is their weighted mean and no acceleration the dynamics hold at any one
state (0.07 to 0.24 N·m on the default robot's RK4 optimum, docs/optimal.md "The knots'
integrator"). Its check is two parts: :func:`rnea_residual` at each knot's state with the
acceleration and contact forces its differential model computes there (its first stage, the
dynamics at the knot itself) — :data:`KNOT_ACCELERATION` — and the knots' defect stepped by the
same integrator (:func:`~hexaleg.optimal.solve.knot_defect`). Euler's check is
:data:`EULER_STEP`, both parts in one: its acceleration is the step's.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from hexaleg.errors import InvalidParameterError
from hexaleg.robot.model import Robot

EULER_STEP = "euler_step"
"""The name of :func:`dynamics_residual`'s check: RNEA at ``a_k = (v_{k+1} − v_k)/dt``, the
semi-implicit Euler knot's own acceleration (module docstring)."""

KNOT_ACCELERATION = "knot_acceleration"
"""The name of the Runge–Kutta knots' check: RNEA at each knot's state with the acceleration its
differential model computes there (:func:`rnea_residual`; module docstring)."""


def dynamics_residual(robot: Robot, q: np.ndarray, v: np.ndarray, dt: float,
                      joint_torques: np.ndarray, forces: np.ndarray) -> np.ndarray:
    """Newton–Euler residual of every knot of an Euler trajectory (:data:`EULER_STEP`, module
    docstring): :func:`rnea_residual` at ``a_k = (v_{k+1} − v_k)/dt``.

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
    model = robot.model
    n = len(joint_torques)
    if q.shape != (n + 1, model.nq) or v.shape != (n + 1, model.nv):
        raise InvalidParameterError("trajectory shapes", (q.shape, v.shape),
                                    f"({n + 1}, {model.nq}) and ({n + 1}, {model.nv})")
    return rnea_residual(robot, q[:-1], v[:-1], np.diff(v, axis=0) / dt, joint_torques,
                         forces)


def rnea_residual(robot: Robot, q: np.ndarray, v: np.ndarray, a: np.ndarray,
                  joint_torques: np.ndarray, forces: np.ndarray) -> np.ndarray:
    """Newton–Euler residual ``RNEA(q_k, v_k, a_k, f_ext) − [0₆; τ_k]`` of every knot at the
    accelerations given (module docstring; Featherstone, §5.3): a Runge–Kutta knot's check
    (:data:`KNOT_ACCELERATION`) with ``a_k`` its differential model's at the knot.

    Args:
        robot: The robot (free flyer).
        q: Configurations at the knots, (N, nq).
        v: Velocities at the knots, (N, nv).
        a: Accelerations at the knots, (N, nv).
        joint_torques: Motor plus spring torque of every actuated joint, (N, nj), N·m.
        forces: Each leg's foot force in world axes, (N, n_legs, 3), N (zero in swing).

    Returns:
        The residual, (N, nv).
    """
    model, data = robot.model, robot.data
    n = len(joint_torques)
    if q.shape != (n, model.nq) or v.shape != (n, model.nv) or a.shape != (n, model.nv):
        raise InvalidParameterError("knot shapes", (q.shape, v.shape, a.shape),
                                    f"({n}, {model.nq}), ({n}, {model.nv}) and ({n}, {model.nv})")
    if forces.shape != (n, len(robot.legs), 3):
        raise InvalidParameterError("forces.shape", forces.shape, f"({n}, {len(robot.legs)}, 3)")
    out = np.zeros((n, model.nv))
    for k in range(n):
        pin.framesForwardKinematics(model, data, q[k])
        fext = [pin.Force.Zero() for _ in range(model.njoints)]
        for j, leg in enumerate(robot.legs):
            frame = model.frames[leg.foot_frame_id]
            p = data.oMf[leg.foot_frame_id].translation
            world = pin.Force(forces[k, j], np.cross(p, forces[k, j]))
            fext[frame.parentJoint] += data.oMi[frame.parentJoint].actInv(world)
        tau = pin.rnea(model, data, q[k], v[k], a[k], fext)
        out[k] = tau - np.concatenate([np.zeros(model.nv - robot.nj), joint_torques[k]])
    return out
