"""The motor's electrical power as a Crocoddyl cost, smoothed where DDP needs derivatives.

The project's model (:mod:`hexaleg.robot.motor`, ``docs/energy.md``; Verstraten et al., IEEE
RA-L 1(1), 2016) of a joint with motor torque ``u`` and speed ``q̇``, mechanical power
``P = u q̇``::

    P_e = max(P/η, η P) + c u²           (gearbox by the direction of power flow, Joule loss)
    drawn = max(0, P_e)                   without regeneration; P_e with it

Both maxima have kinks where DDP's second-order model breaks, so the cost takes the softplus
``s_ε(z) = ε log(1 + e^{z/ε})`` for ``max(z, 0)`` (Boyd & Vandenberghe, *Convex Optimization*,
§3.1.5 — the log-sum-exp bound ``max(z, 0) ≤ s_ε(z) ≤ max(z, 0) + ε log 2``):

    max(P/η, η P) ≈ η P + s_ε((1/η − η) P),     drawn ≈ s_ε(P_e)

so each joint's smoothed power is above its exact power by at most ``2 ε log 2`` (W) and
converges to it as ε → 0. Results are always reported with the exact model
(:meth:`hexaleg.robot.motor.Motor.electrical_power`); ε only shapes the search. Crocoddyl's Euler
integrator multiplies a running cost by the time step, so the cost in W integrates to J.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.checks import positive
from hexaleg.errors import InvalidParameterError
from hexaleg.optimal.backend import crocoddyl_module

crocoddyl = crocoddyl_module()
_CostModelAbstract: Any = crocoddyl.CostModelAbstract
"""Crocoddyl's base class (typed Any: Crocoddyl ships no type information)."""


def _softplus(z: np.ndarray, eps: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``s_ε(z)``, its first and second derivatives (overflow-safe)."""
    r = z / eps
    value = eps * np.logaddexp(0.0, r)
    sig = 0.5 * (1.0 + np.tanh(0.5 * r))  # the logistic function, without overflow
    return value, sig, sig * (1.0 - sig) / eps


@dataclass(frozen=True)
class JointPower:
    """The joints' motor constants: ``c`` (W/(N·m)²), ``η`` and regeneration, each (n,).

    Attributes:
        joule: Joule coefficient ``c = R/(k_t G)²`` of each joint, W/(N·m)².
        efficiency: Gearbox efficiency η of each joint, in (0, 1].
        regeneration: Whether each joint's negative power returns to the supply.
        smoothing: ε of the softplus, W (module docstring).
    """

    joule: np.ndarray
    efficiency: np.ndarray
    regeneration: np.ndarray
    smoothing: float

    def __post_init__(self) -> None:
        positive("smoothing", self.smoothing)
        eta = np.asarray(self.efficiency)
        if eta.ndim != 1 or np.any(~(eta > 0.0)) or np.any(eta > 1.0):
            raise InvalidParameterError("gearbox efficiency", eta, "values in (0, 1]")
        if np.shape(self.joule) != eta.shape or np.any(~(np.asarray(self.joule) >= 0.0)):
            raise InvalidParameterError("Joule coefficient", self.joule,
                                        f"{eta.size} values ≥ 0")

    @classmethod
    def of(cls, actuator: Any, n: int, smoothing: float) -> JointPower:
        """The constants of a :class:`~hexaleg.robot.motor.Motor` (every joint) or a
        :class:`~hexaleg.robot.motor_set.MotorSet` (per joint), for ``n`` joints."""
        def per_joint(value: Any) -> np.ndarray:
            return np.broadcast_to(np.asarray(value, dtype=float), (n,)).copy()
        return cls(per_joint(actuator.joule_coefficient), per_joint(actuator.gearbox_efficiency),
                   per_joint(actuator.regeneration).astype(bool), smoothing)

    def exact(self, u: np.ndarray, qdot: np.ndarray) -> np.ndarray:
        """The project's exact power per joint (module docstring), shape of ``u``, W."""
        p = u * qdot
        pe = np.maximum(p / self.efficiency, p * self.efficiency) + self.joule * u**2
        return np.where(self.regeneration, pe, np.maximum(pe, 0.0))

    def smoothed(self, u: np.ndarray, qdot: np.ndarray
                 ) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray],
                            tuple[np.ndarray, np.ndarray, np.ndarray]]:
        """The smoothed power per joint, its gradient ``(∂/∂u, ∂/∂q̇)`` and Hessian
        ``(∂²/∂u², ∂²/∂q̇², ∂²/∂u∂q̇)``, each shape (n,), by the chain rule through the two
        softplus (module docstring)."""
        eta, c = self.efficiency, self.joule
        k = 1.0 / eta - eta
        p = u * qdot
        s, s1, s2 = _softplus(k * p, self.smoothing)
        m, m1, m2 = eta * p + s, eta + k * s1, k * k * s2  # max(P/η, ηP) and d/dP, d²/dP²
        e = m + c * u**2
        eu, ev = m1 * qdot + 2.0 * c * u, m1 * u
        euu, evv, euv = m2 * qdot**2 + 2.0 * c, m2 * u**2, m2 * p + m1
        d, d1, d2 = _softplus(e, self.smoothing)
        regen = self.regeneration
        d, d1, d2 = np.where(regen, e, d), np.where(regen, 1.0, d1), np.where(regen, 0.0, d2)
        return (d, (d1 * eu, d1 * ev),
                (d2 * eu**2 + d1 * euu, d2 * ev**2 + d1 * evv, d2 * eu * ev + d1 * euv))


class EnergyCost(_CostModelAbstract):
    """Σ_j smoothed electrical power of joint j, W, with ``u`` the motor torques and ``q̇`` the
    joint speeds of the state (``x[nq + b:]``, ``b`` the unactuated base's velocity dimensions).

    Args:
        state: Crocoddyl's multibody state (the base's joint first).
        power: The joints' motor constants.
        base: ``b``: 6 for a free flyer, 0 for a fixed base.
    """

    def __init__(self, state: Any, power: JointPower, base: int = 6) -> None:
        n = state.nv - base
        crocoddyl.CostModelAbstract.__init__(self, state, crocoddyl.ActivationModelQuad(n), n)
        self.power = power
        self.base = base

    def calc(self, data: Any, x: np.ndarray,
             u: np.ndarray | None = None) -> None:
        """``data.cost``: the smoothed power, W (0 at a terminal node, which has no control)."""
        if u is None:
            data.cost = 0.0
            return
        qdot = x[self.state.nq + self.base:]
        value, _, _ = self.power.smoothed(np.asarray(u), qdot)
        data.cost = float(np.sum(value))

    def calcDiff(self, data: Any, x: np.ndarray,
                 u: np.ndarray | None = None) -> None:
        """``Lx, Lu, Lxx, Luu, Lxu``: the smoothed power's exact gradient and Hessian."""
        if u is None:
            return
        nq, nv, b = self.state.nq, self.state.nv, self.base
        _, (gu, gv), (huu, hvv, huv) = self.power.smoothed(np.asarray(u), x[nq + b:])
        n = nv - b
        lx = np.zeros(2 * nv)
        lx[nv + b:] = gv
        lxx = np.zeros((2 * nv, 2 * nv))
        lxx[nv + b:, nv + b:] = np.diag(hvv)
        lxu = np.zeros((2 * nv, n))
        lxu[nv + b:, :] = np.diag(huv)
        data.Lx[...] = np.reshape(lx, np.shape(data.Lx))
        data.Lu[...] = np.reshape(gu, np.shape(data.Lu))
        data.Lxx[...] = np.reshape(lxx, np.shape(data.Lxx))
        data.Luu[...] = np.reshape(np.diag(huu), np.shape(data.Luu))
        data.Lxu[...] = np.reshape(lxu, np.shape(data.Lxu))
