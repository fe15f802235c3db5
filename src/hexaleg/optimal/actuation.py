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

from hexaleg.checks import finite_array
from hexaleg.errors import InvalidParameterError
from hexaleg.optimal.backend import crocoddyl_module
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import DeadZoneSpring, SpringSet
from hexaleg.robot.springs.dead_zone import zone_basis, zone_torque
from hexaleg.robot.springs.spring_set import Spring
from hexaleg.robot.springs.terms import basis_torque

crocoddyl = crocoddyl_module()
_ActuationModelAbstract: Any = crocoddyl.ActuationModelAbstract
"""Crocoddyl's base class (typed Any: Crocoddyl ships no type information)."""

_SLOPE = {"above": -1.0, "below": -1.0, "linear": -1.0, "step_above": 0.0, "step_below": 0.0,
          "constant": 0.0}
"""dφ/dq of each term kind where it is differentiable (see the module docstring)."""


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


class LawGroup:
    """The sprung joints of one kind of law with one number of terms, evaluated together.

    The torques are the laws' own formulas, called with the group's parameters as arrays (one
    entry a joint): a term's φ is :func:`~hexaleg.robot.springs.terms.basis_torque`, as
    :meth:`~hexaleg.robot.springs.terms.Term.torque` takes it, a dead zone's torque
    :func:`~hexaleg.robot.springs.dead_zone.zone_basis` and
    :func:`~hexaleg.robot.springs.dead_zone.zone_torque`, as
    :meth:`~hexaleg.robot.springs.DeadZoneSpring.torque` takes them: the numbers are the same
    to the bit (tested), the Python calls one per group instead of a dozen per joint. The dot of
    a term law is NumPy's ``matmul`` of each joint's row, as the law's ``basis @ magnitudes``
    (:meth:`~hexaleg.robot.springs.law.TermSpring.elastic_torque`) takes it (a sum in another
    order, or fused multiply-adds, may round otherwise).

    Args:
        joints: The group's sprung joints (one law class, one number of terms), m of them.
    """

    def __init__(self, joints: tuple[SprungJoint, ...]) -> None:
        self.columns = np.array([j.column for j in joints], dtype=int)
        self.iq = np.array([j.iq for j in joints], dtype=int)
        self.iv = np.array([j.iv for j in joints], dtype=int)
        terms = [j.spring.terms() for j in joints]
        kinds = np.array([[t.kind for t in row] for row in terms])
        self.kinds = {kind: kinds == kind for kind in np.unique(kinds)}
        """Where each term kind sits, (m, n_terms) bool each."""
        self.angles = np.array([[t.angle for t in row] for row in terms])
        self.magnitudes = np.array([np.asarray(j.spring.magnitudes(), float) for j in joints])
        self.slopes = self.magnitudes * np.vectorize(_SLOPE.__getitem__, otypes=[float])(kinds)
        """``x_b φ_b'``, (m, n_terms) (:func:`stiffness`)."""
        springs = [j.spring for j in joints]
        self.zone = all(isinstance(s, DeadZoneSpring) for s in springs)
        if self.zone:
            zones = [s for s in springs if isinstance(s, DeadZoneSpring)]
            self.neutral = np.array([s.neutral for s in zones])
            self.plus = np.array([s.th_plus for s in zones])
            self.minus = np.array([s.th_minus for s in zones])
            self.transmission = np.array([s.transmission for s in zones])
            self.k_plus = np.array([s.stiffness for s in zones])
            self.k_minus = np.array([s.k_minus for s in zones])
            self.k2 = np.array([s.k2 for s in zones])
            self.damping = np.array([s.damping for s in zones])

    def torques(self, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        """The springs' torques at their joints' angles ``q`` and speeds ``v`` (m,), N·m."""
        if self.zone:  # DeadZoneSpring.torque: its torque_basis, then its coefficients
            return zone_torque(zone_basis(q - self.neutral, v, self.minus, self.plus,
                                          self.transmission),
                               self.k_plus, self.k_minus, self.k2, self.damping)
        d = q[:, None] - self.angles  # Term.torque of every term, then basis @ magnitudes
        phi = np.ones_like(d)
        for kind, where in self.kinds.items():
            phi[where] = basis_torque(kind, d[where])
        return np.matmul(phi[:, None, :], self.magnitudes[:, :, None])[:, 0, 0]

    def stiffness(self, q: np.ndarray) -> np.ndarray:
        """``dτ_s/dq = Σ_b x_b φ_b'(q)`` at the joints' angles ``q`` (m,), N·m/rad (module
        docstring), summed term by term in each law's order from 0; a ramp counts strictly past
        its angle."""
        d = q[:, None] - self.angles
        engaged = np.ones_like(d, dtype=bool)
        if "above" in self.kinds:
            engaged[self.kinds["above"]] = d[self.kinds["above"]] > 0.0
        if "below" in self.kinds:
            engaged[self.kinds["below"]] = d[self.kinds["below"]] < 0.0
        k = np.zeros(len(q))
        for b in range(d.shape[1]):
            k = k + self.slopes[:, b] * engaged[:, b]
        return k


def law_groups(sprung: tuple[SprungJoint, ...]) -> tuple[LawGroup, ...]:
    """``sprung`` grouped by law class and number of terms (:class:`LawGroup`), in order of
    first appearance."""
    keys: dict[tuple[bool, int], list[SprungJoint]] = {}
    for j in sprung:
        keys.setdefault((isinstance(j.spring, DeadZoneSpring), len(j.spring.terms())),
                        []).append(j)
    return tuple(LawGroup(tuple(group)) for group in keys.values())


def stiffness(spring: Spring, angle: float) -> float:
    """Tangent stiffness ``dτ_s/dq`` of ``spring`` at ``angle``, N·m/rad (≤ 0 for a restoring
    spring): ``Σ_b x_b φ_b'(q)`` over its terms (:mod:`hexaleg.robot.springs.terms`); a ramp
    counts on its engaged side only (strictly past its angle)."""
    group = LawGroup((SprungJoint(0, 0, 0, spring),))
    return float(group.stiffness(np.array([float(angle)]))[0])


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
        self.groups = law_groups(sprung)
        self._nv = nv
        self._base = base
        self._du = np.zeros((nv, nv - base))
        self._du[base:, :] = np.eye(nv - base)

    def _angles(self, group: LawGroup, x: np.ndarray,
                check: bool = True) -> tuple[np.ndarray, np.ndarray]:
        """The group's joint angles and speeds in state ``x``, each (m,).

        Raises:
            InvalidParameterError: a value is not finite (as the laws' own checks say), when
                ``check``; the solver's own calls (:meth:`calc`, :meth:`calcDiff`) do not check.
        """
        q, v = x[group.iq], x[self.state.nq + group.iv]
        if check and not (np.isfinite(q).all() and np.isfinite(v).all()):
            finite_array("q", q)
            finite_array("v", v)
        return q, v

    def spring_torques(self, x: np.ndarray, check: bool = True) -> np.ndarray:
        """``τ_s`` of every actuated joint at state ``x`` (nq + nv,), shape (nv − b,), N·m;
        ``check`` as :meth:`_angles`."""
        out = np.zeros(self._nv - self._base)
        for group in self.groups:
            out[group.columns] = group.torques(*self._angles(group, x, check))
        return out

    def calc(self, data: Any, x: np.ndarray,
             u: np.ndarray | None = None) -> None:
        """``data.tau = [0₆; u + τ_s(x)]`` (``u`` None: Crocoddyl's terminal node, u = 0).

        A non-finite ``x`` (a line search's trial step rolled out beyond the finite numbers)
        gives non-finite torques, not an error: Crocoddyl's forward pass then finds its cost
        non-finite and its line search tries the next, shorter step (``SolverDDP::solve``
        catches the forward pass's error); a Python error raised here would end the solve
        instead."""
        tau = np.zeros(self._nv)
        tau[self._base:] = self.spring_torques(x, check=False) + (0.0 if u is None else u)
        data.tau[...] = np.reshape(tau, np.shape(data.tau))

    def calcDiff(self, data: Any, x: np.ndarray,
                 u: np.ndarray | None = None) -> None:
        """``dtau_du = S``; ``dtau_dx`` the springs' stiffness and damping (module docstring):
        the damping as ``τ_s(q, 1) − τ_s(q, 0)``."""
        nv, b = self._nv, self._base
        dx = np.zeros((nv, 2 * nv))
        for group in self.groups:
            q, _ = self._angles(group, x, check=False)
            rows = b + group.columns
            dx[rows, group.iv] = group.stiffness(q)
            dx[rows, nv + group.iv] = (group.torques(q, np.ones_like(q))
                                       - group.torques(q, np.zeros_like(q)))
        data.dtau_dx[...] = np.reshape(dx, np.shape(data.dtau_dx))
        data.dtau_du[...] = np.reshape(self._du, np.shape(data.dtau_du))

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
