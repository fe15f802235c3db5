"""A landing leg's position-servo effort as a Crocoddyl cost (issue #56: the optimal motion under
position servos).

A position servo (:mod:`hexaleg.simulation.controllers`, ``"position"``) gives its joint the
motor torque ``τ = kp e − D q̇`` — no feedforward — so to give the plan's motor torque ``u`` at
speed ``q̇`` it must lag its reference by ``e = (u + D q̇)/kp``. A swing leg that lags as its
foot meets the ground lands off its planned foothold, and the stance then holds that offset:
the stance legs push against each other and the position servos pay for it (measured in
``analysis/bench_optimal_servo.py``). The cost

    ℓ(x, u) = ½ Σ_{j ∈ leg} (u_j + D_j q̇_j)²          (N·m)², times its weight in W/(N·m)²

on the leg's joints at its last swing knots asks the plan to bring the foot down with the
effort a position servo gives at its reference; ``D = τ_s/ω₀`` is the motor's back-EMF damping
(the ideal DC motor's torque–speed line, Verstraten et al., IEEE RA-L 1(1), 2016; the
controllers' ``D``). The residual is linear in ``(x, u)``, so the gradient and Hessian below are
exact.

The cost does not help every motion under position servos: on Solo-12's trot without springs
the weighted plan is the same plan and its simulated figure, fragile with the timestep,
doubles (``analysis/bench_logs/bench_optimal_landing.log``). So ``hexaleg codesign --motion
optimal`` solves each optimal row without and with it and keeps the answer walking cheaper under
the worse servo (:mod:`hexaleg.design.codesign.optimal_rows`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from hexaleg.checks import positive
from hexaleg.errors import InvalidParameterError
from hexaleg.optimal.backend import crocoddyl_module

crocoddyl = crocoddyl_module()
_CostModelAbstract: Any = crocoddyl.CostModelAbstract
"""Crocoddyl's base class (typed Any: Crocoddyl ships no type information)."""


def back_emf_damping(actuator: Any, n: int) -> np.ndarray:
    """``D = τ_s/ω₀`` of each of ``n`` joints, N·m·s/rad, shape (n,): the motor's stall torque
    over its no-load speed (a :class:`~hexaleg.robot.motor.Motor` or a per-joint set)."""
    stall = np.broadcast_to(np.asarray(actuator.stall_torque, dtype=float), (n,))
    speed = np.broadcast_to(np.asarray(actuator.no_load_speed, dtype=float), (n,))
    return np.array([positive("stall torque", s) / positive("no-load speed", w)
                     for s, w in zip(stall, speed, strict=True)])


class ServoEffortCost(_CostModelAbstract):
    """``½ Σ_{j ∈ columns} (u_j + D_j q̇_j)²`` (module docstring), ``u`` the motor torques and
    ``q̇`` the joint speeds of the state (``x[nq + b:]``, ``b`` the base's velocity
    dimensions).

    Args:
        state: Crocoddyl's multibody state (the base's joint first).
        columns: The joints the cost is on, indices among the actuated joints, shape (m,).
        damping: ``D`` of every actuated joint, N·m·s/rad, shape (n,).
        base: ``b``: 6 for a free flyer, 0 for a fixed base.

    Raises:
        InvalidParameterError: ``damping`` not one value ≥ 0 per actuated joint, or a column
            outside them.
    """

    def __init__(self, state: Any, columns: Any, damping: np.ndarray, base: int = 6) -> None:
        n = state.nv - base
        damping = np.asarray(damping, dtype=float)
        if damping.shape != (n,) or np.any(~(damping >= 0.0)):
            raise InvalidParameterError("damping", damping, f"{n} values ≥ 0 (N·m·s/rad)")
        cols = np.asarray(columns, dtype=int)
        if cols.ndim != 1 or np.any(cols < 0) or np.any(cols >= n):
            raise InvalidParameterError("columns", cols, f"indices in [0, {n})")
        crocoddyl.CostModelAbstract.__init__(self, state, crocoddyl.ActivationModelQuad(n), n)
        self.mask = np.zeros(n)
        self.mask[cols] = 1.0
        self.damping = damping
        self.base = base

    def _effort(self, x: np.ndarray, u: np.ndarray) -> np.ndarray:
        """``u + D q̇`` on the cost's joints, zero elsewhere, shape (n,), N·m."""
        qdot = np.asarray(x)[self.state.nq + self.base:]
        return self.mask * (np.asarray(u) + self.damping * qdot)

    def calc(self, data: Any, x: np.ndarray, u: np.ndarray | None = None) -> None:
        """``data.cost``: the half squared effort, (N·m)² (0 at a terminal node)."""
        if u is None:
            data.cost = 0.0
            return
        r = self._effort(x, u)
        data.cost = 0.5 * float(r @ r)

    def calcDiff(self, data: Any, x: np.ndarray, u: np.ndarray | None = None) -> None:
        """``Lx, Lu, Lxx, Luu, Lxu``: the exact gradient and Hessian of the quadratic."""
        if u is None:
            return
        nv, b = self.state.nv, self.base
        r = self._effort(x, u)
        md = self.mask * self.damping
        lx = np.zeros(2 * nv)
        lx[nv + b:] = md * r
        lxx = np.zeros((2 * nv, 2 * nv))
        lxx[nv + b:, nv + b:] = np.diag(md * self.damping)
        lxu = np.zeros((2 * nv, nv - b))
        lxu[nv + b:, :] = np.diag(md)
        data.Lx[...] = np.reshape(lx, np.shape(data.Lx))
        data.Lu[...] = np.reshape(r, np.shape(data.Lu))
        data.Lxx[...] = np.reshape(lxx, np.shape(data.Lxx))
        data.Luu[...] = np.reshape(np.diag(self.mask), np.shape(data.Luu))
        data.Lxu[...] = np.reshape(lxu, np.shape(data.Lxu))


__all__ = ["ServoEffortCost", "back_emf_damping"]
