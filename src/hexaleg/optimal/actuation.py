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
class SprungJoint:
    """One sprung joint: its column among the actuated joints, q and v indices, its law."""

    column: int
    iq: int
    iv: int
    spring: Spring


def sprung_joints(robot: Robot, springs: SpringSet) -> tuple[SprungJoint, ...]:
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
        out.append(SprungJoint(column, joint.idx_q, joint.idx_v, springs[name]))
    return tuple(out)


class SpringActuation(_ActuationModelAbstract):
    """Actuation with springs: ``τ = [0_b; u + τ_s(q, q̇)]`` (module docstring), ``b`` the
    unactuated base's velocity dimensions (6 for a free flyer, 0 for a fixed base).

    Args:
        state: Crocoddyl's multibody state (the base's joint first).
        sprung: The sprung joints (:func:`sprung_joints`); none gives Crocoddyl's
            ``ActuationModelFloatingBase`` (``base`` 6) or ``ActuationModelFull`` (``base`` 0).
        base: ``b``.
    """

    def __init__(self, state: Any, sprung: tuple[SprungJoint, ...], base: int = 6) -> None:
        nv = state.nv
        crocoddyl.ActuationModelAbstract.__init__(self, state, nv - base)
        self.sprung = sprung
        self._nv = nv
        self._base = base

    def spring_torques(self, x: np.ndarray) -> np.ndarray:
        """``τ_s`` of every actuated joint at state ``x`` (nq + nv,), shape (nv − b,), N·m."""
        nq = self.state.nq
        out = np.zeros(self._nv - self._base)
        for s in self.sprung:
            q, v = np.array([x[s.iq]]), np.array([x[nq + s.iv]])
            out[s.column] = float(s.spring.torque(q, v)[0])
        return out

    def calc(self, data: Any, x: np.ndarray,
             u: np.ndarray | None = None) -> None:
        """``data.tau = [0₆; u + τ_s(x)]`` (``u`` None: Crocoddyl's terminal node, u = 0)."""
        tau = np.zeros(self._nv)
        tau[self._base:] = self.spring_torques(x) + (0.0 if u is None else u)
        data.tau[...] = np.reshape(tau, np.shape(data.tau))

    def calcDiff(self, data: Any, x: np.ndarray,
                 u: np.ndarray | None = None) -> None:
        """``dtau_du = S``; ``dtau_dx`` the springs' stiffness and damping (module docstring)."""
        nv, b = self._nv, self._base
        dx = np.zeros((nv, 2 * nv))
        for s in self.sprung:
            q = x[s.iq]
            dx[b + s.column, s.iv] = stiffness(s.spring, q)
            one, zero = np.array([1.0]), np.array([0.0])
            qa = np.array([q])
            dx[b + s.column, nv + s.iv] = float(s.spring.torque(qa, one)[0]
                                                - s.spring.torque(qa, zero)[0])
        data.dtau_dx[...] = np.reshape(dx, np.shape(data.dtau_dx))
        du = np.zeros((nv, nv - b))
        du[b:, :] = np.eye(nv - b)
        data.dtau_du[...] = np.reshape(du, np.shape(data.dtau_du))

    def commands(self, data: Any, x: np.ndarray,
                 tau: np.ndarray) -> None:
        """The motor torques for joint torques ``tau`` (nv,): ``u = τ[6:] − τ_s(x)``."""
        u = np.asarray(tau)[self._base:] - self.spring_torques(x)
        data.u[...] = np.reshape(u, np.shape(data.u))

    def torqueTransform(self, data: Any,
                        x: np.ndarray, u: np.ndarray) -> None:
        """``∂u/∂τ`` of :meth:`commands`: the identity on the joints (Crocoddyl's interface)."""
        b = self._base
        m = np.zeros((self._nv - b, self._nv))
        m[:, b:] = np.eye(self._nv - b)
        data.Mtau[...] = np.reshape(m, np.shape(data.Mtau))
