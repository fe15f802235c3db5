"""A single sprung joint: Crocoddyl's optimum with the spring actuation and the energy cost
against a dense direct transcription of the same problem solved by scipy's SLSQP.

The problem: a pendulum (one revolute joint, its mass below the axis) with a linear spring swings
from rest at 0 to rest at 0.8 rad in 0.4 s; the running cost is the motor's smoothed electrical
power (:mod:`hexaleg.optimal.energy`; a Joule coefficient large enough that the optimum is
unique — with a small one the problem has many local optima, bang-bang-like, and two local
solvers need not meet), the terminal cost ``½ W ‖x_N − x*‖²``; both solvers see
the same Euler discretisation (``v⁺ = v + a dt``, ``q⁺ = q + v⁺ dt``). The transcription's
variables are every state and control (3N), its dynamics N·2 equality constraints, with the
acceleration by Pinocchio's ABA — nothing of Crocoddyl. Both are local methods on a smooth,
small problem: they must find the same optimum.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest
from scipy.optimize import minimize

import hexaleg

crocoddyl = pytest.importorskip("crocoddyl")

from hexaleg.optimal.actuation import SpringActuation, SprungJoint  # noqa: E402
from hexaleg.optimal.energy import EnergyCost, JointPower  # noqa: E402

N, DT, W = 20, 0.02, 1e3
TARGET = np.array([0.8, 0.0])
SPRING = hexaleg.LinearSpring(0.6, reference=0.5)
POWER = JointPower(np.array([20.0]), np.array([0.7]), np.array([False]), 0.05)


def _pendulum() -> pin.Model:
    model = pin.Model()
    joint = model.addJoint(0, pin.JointModelRY(), pin.SE3.Identity(), "hinge")
    model.appendBodyToJoint(joint, pin.Inertia(0.3, np.array([0.0, 0.0, -0.1]),
                                               np.diag([1e-4, 1e-4, 1e-4])), pin.SE3.Identity())
    return model


def _crocoddyl(model):
    state = crocoddyl.StateMultibody(model)
    actuation = SpringActuation(state, (SprungJoint(0, 0, 0, SPRING),), base=0)
    running = crocoddyl.CostModelSum(state, 1)
    running.addCost("energy", EnergyCost(state, POWER, base=0), 1.0)
    terminal = crocoddyl.CostModelSum(state, 1)
    terminal.addCost("target", crocoddyl.CostModelResidual(
        state, crocoddyl.ResidualModelState(state, TARGET, 1)), W)
    dam = crocoddyl.DifferentialActionModelFreeFwdDynamics(state, actuation, running)
    dam_t = crocoddyl.DifferentialActionModelFreeFwdDynamics(state, actuation, terminal)
    problem = crocoddyl.ShootingProblem(np.zeros(2),
                                        [crocoddyl.IntegratedActionModelEuler(dam, DT)] * N,
                                        crocoddyl.IntegratedActionModelEuler(dam_t, 0.0))
    solver = crocoddyl.SolverFDDP(problem)
    solver.th_stop = 1e-12
    solver.solve([np.zeros(2)] * (N + 1), [np.zeros(1)] * N, 500, False)
    return solver


def _transcription(model):
    data = model.createData()

    def step(x, u):
        q, v = x
        tau = u + SPRING.torque(np.array([q]))[0]
        a = pin.aba(model, data, np.array([q]), np.array([v]), np.array([tau]))[0]
        v1 = v + a * DT
        return np.array([q + v1 * DT, v1])

    def split(z):
        return np.vstack([np.zeros(2), z[:2 * N].reshape(N, 2)]), z[2 * N:]

    def cost(z):
        x, u = split(z)
        running = POWER.smoothed(u, x[:-1, 1])[0].sum() * DT
        return running + 0.5 * W * np.sum((x[-1] - TARGET) ** 2)

    def defects(z):
        x, u = split(z)
        return np.concatenate([x[k + 1] - step(x[k], u[k]) for k in range(N)])

    guess = np.concatenate([np.linspace([0.0, 0.0], TARGET, N + 1)[1:].ravel(), np.zeros(N)])
    out = minimize(cost, guess, method="SLSQP", constraints={"type": "eq", "fun": defects},
                   options={"maxiter": 1000, "ftol": 1e-12})
    assert out.success, out.message
    assert np.abs(defects(out.x)).max() < 1e-8
    return out.fun, split(out.x)[1]


@pytest.mark.slow
def test_the_optimum_is_the_direct_transcriptions():
    model = _pendulum()
    solver = _crocoddyl(model)
    assert solver.stop < 1e-9 and solver.ffeas < 1e-10
    cost, u = _transcription(model)
    assert solver.cost == pytest.approx(cost, rel=1e-4)
    np.testing.assert_allclose(np.array(solver.us)[:, 0], u, atol=2e-3 * np.abs(u).max())
    final = np.array(solver.xs)[-1]
    assert np.abs(final - TARGET).max() < 0.05  # it gets there


def test_the_spring_changes_the_optimum():
    """Without the spring's torque in the actuation the same problem costs something else: the
    comparison above sees the spring, not only the pendulum."""
    model = _pendulum()
    with_spring = _crocoddyl(model).cost
    state = crocoddyl.StateMultibody(model)
    bare = SpringActuation(state, (), base=0)
    running = crocoddyl.CostModelSum(state, 1)
    running.addCost("energy", EnergyCost(state, POWER, base=0), 1.0)
    terminal = crocoddyl.CostModelSum(state, 1)
    terminal.addCost("target", crocoddyl.CostModelResidual(
        state, crocoddyl.ResidualModelState(state, TARGET, 1)), W)
    problem = crocoddyl.ShootingProblem(
        np.zeros(2), [crocoddyl.IntegratedActionModelEuler(
            crocoddyl.DifferentialActionModelFreeFwdDynamics(state, bare, running), DT)] * N,
        crocoddyl.IntegratedActionModelEuler(
            crocoddyl.DifferentialActionModelFreeFwdDynamics(state, bare, terminal), 0.0))
    solver = crocoddyl.SolverFDDP(problem)
    solver.solve([np.zeros(2)] * (N + 1), [np.zeros(1)] * N, 500, False)
    assert abs(solver.cost - with_spring) > 0.05 * with_spring
