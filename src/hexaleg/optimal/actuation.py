"""The springs inside the dynamics: a Crocoddyl actuation model whose joint torque is the motor's
torque plus the springs'.

A sprung joint's torque is ``τ = u + τ_s(q, q̇)`` with ``u`` the motor's torque (the control) and
``τ_s`` the spring's (:mod:`hexaleg.robot.springs`), so the motor supplies ``u = τ − τ_s`` — the
relation the project's energy model charges (``docs/energy.md``). On the floating base
``τ = [0₆; u + τ_s]``. Crocoddyl's actuation interface (Mastalli et al., ICRA 2020, §IV-B; the
``ActuationModelAbstract`` documentation: ``tau = a(x, u)`` with ``dtau_dx``, ``dtau_du``) takes
the derivatives

* ``∂τ/∂u = S = [0₆ₓₙ; Iₙ]`` (the selection matrix of the floating base),
* ``∂τ_j/∂q_j = K_j(q_j) = Σ_b x_b φ_b'(q_j)``: the spring's tangent stiffness, from its basis
  terms (:mod:`hexaleg.robot.springs.terms`: a ramp ``above``/``below`` has slope −1 past its
  angle, ``linear`` −1, a step or ``constant`` 0 — a preload's jump has no derivative, and DDP sees
  none),
* ``∂τ_j/∂q̇_j``: the spring's damping, ``τ_s(q, 1) − τ_s(q, 0)`` exactly since every law is
  affine in q̇ (:class:`~hexaleg.robot.springs.DeadZoneSpring` damps when engaged; the term
  families have none).

A free flyer's configuration tangent is its velocity index, so a revolute joint's column in
``dtau_dx`` is its ``idx_v`` (positions) and ``nv + idx_v`` (velocities).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.errors import InvalidParameterError
from hexaleg.optimal.backend import crocoddyl_module
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet
from hexaleg.robot.springs.spring_set import Spring

crocoddyl = crocoddyl_module()
_ActuationModelAbstract: Any = crocoddyl.ActuationModelAbstract
"""Crocoddyl's base class (typed Any: Crocoddyl ships no type information)."""

_SLOPE = {"above": -1.0, "below": -1.0, "linear": -1.0, "step_above": 0.0, "step_below": 0.0,
          "constant": 0.0}
"""dφ/dq of each term kind where it is differentiable (see the module docstring)."""


def stiffness(spring: Spring, angle: float) -> float:
    """Tangent stiffness ``dτ_s/dq`` of ``spring`` at ``angle``, N·m/rad (≤ 0 for a restoring
    spring): ``Σ_b x_b φ_b'(q)`` over its terms (:mod:`hexaleg.robot.springs.terms`); a ramp
    counts on its engaged side only (strictly past its angle)."""
    k = 0.0
    for term, x in zip(spring.terms(), spring.magnitudes(), strict=True):
        d = angle - term.angle
        engaged = {"above": d > 0.0, "below": d < 0.0}.get(term.kind, True)
        k += float(x) * _SLOPE[term.kind] * engaged
    return k


@dataclass(frozen=True)
class _Sprung:
    """One sprung joint: its column among the actuated joints, q and v indices, its law."""

    column: int
    iq: int
    iv: int
    spring: Spring


def sprung_joints(robot: Robot, springs: SpringSet) -> tuple[_Sprung, ...]:
    """The sprung joints of ``robot`` in :meth:`SpringSet.columns` order.

    Raises:
        UnknownNameError: a sprung joint is not a joint of the robot.
        InvalidParameterError: a sprung joint is continuous (two configuration numbers): the
            optimal-control problem takes revolute joints only.
    """
    out = []
    for name, column in springs.columns(robot).items():
        joint = robot.model.joints[robot.model.getJointId(name)]
        if joint.nq != 1:
            raise InvalidParameterError(f"spring on {name}", f"a joint with nq = {joint.nq}",
                                        "a revolute joint (nq = 1) in the optimal-control problem")
        out.append(_Sprung(column, joint.idx_q, joint.idx_v, springs[name]))
    return tuple(out)


class SpringActuation(_ActuationModelAbstract):
    """Floating-base actuation with springs: ``τ = [0₆; u + τ_s(q, q̇)]`` (module docstring).

    Args:
        state: Crocoddyl's multibody state of ``robot.model`` (free flyer first).
        robot: The robot (its joints' indices).
        springs: The springs; an empty set gives Crocoddyl's ``ActuationModelFloatingBase``.
    """

    def __init__(self, state: Any, robot: Robot, springs: SpringSet
                 ) -> None:
        nv = state.nv
        crocoddyl.ActuationModelAbstract.__init__(self, state, nv - 6)
        self.sprung = sprung_joints(robot, springs)
        self._nv = nv

    def spring_torques(self, x: np.ndarray) -> np.ndarray:
        """``τ_s`` of every actuated joint at state ``x`` (nq + nv,), shape (nv − 6,), N·m."""
        nq = self.state.nq
        out = np.zeros(self._nv - 6)
        for s in self.sprung:
            q, v = np.array([x[s.iq]]), np.array([x[nq + s.iv]])
            out[s.column] = float(s.spring.torque(q, v)[0])
        return out

    def calc(self, data: Any, x: np.ndarray,
             u: np.ndarray | None = None) -> None:
        """``data.tau = [0₆; u + τ_s(x)]`` (``u`` None: Crocoddyl's terminal node, u = 0)."""
        tau = np.zeros(self._nv)
        tau[6:] = self.spring_torques(x) + (0.0 if u is None else u)
        data.tau[:] = tau

    def calcDiff(self, data: Any, x: np.ndarray,
                 u: np.ndarray | None = None) -> None:
        """``dtau_du = S``; ``dtau_dx`` the springs' stiffness and damping (module docstring)."""
        nv = self._nv
        dx = np.zeros((nv, 2 * nv))
        for s in self.sprung:
            q = x[s.iq]
            dx[6 + s.column, s.iv] = stiffness(s.spring, q)
            one, zero = np.array([1.0]), np.array([0.0])
            qa = np.array([q])
            dx[6 + s.column, nv + s.iv] = float(s.spring.torque(qa, one)[0]
                                                - s.spring.torque(qa, zero)[0])
        data.dtau_dx[:, :] = dx
        du = np.zeros((nv, nv - 6))
        du[6:, :] = np.eye(nv - 6)
        data.dtau_du[:, :] = du

    def commands(self, data: Any, x: np.ndarray,
                 tau: np.ndarray) -> None:
        """The motor torques for joint torques ``tau`` (nv,): ``u = τ[6:] − τ_s(x)``."""
        data.u[:] = np.asarray(tau)[6:] - self.spring_torques(x)

    def torqueTransform(self, data: Any,
                        x: np.ndarray, u: np.ndarray) -> None:
        """``∂u/∂τ`` of :meth:`commands`: the identity on the joints (Crocoddyl's interface)."""
        m = np.zeros((self._nv - 6, self._nv))
        m[:, 6:] = np.eye(self._nv - 6)
        data.Mtau[:, :] = m
