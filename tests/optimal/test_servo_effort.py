"""The landing leg's position-servo effort: its value ``½ Σ (u + D q̇)²`` on the leg's joints
only, its derivatives against finite differences, the knots it is on, and the problem unchanged
when it is off."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError

crocoddyl = pytest.importorskip("crocoddyl")

from hexaleg.optimal.problem import OptimalParams, _landing_knots, build_problem  # noqa: E402
from hexaleg.optimal.servo_effort import ServoEffortCost, back_emf_damping  # noqa: E402


@pytest.fixture(scope="module")
def run():
    return hexaleg.Scenario.load("hexaleg")


def _cost_and_state(run, columns):
    robot = run.model
    state = crocoddyl.StateMultibody(robot.model)
    cost = ServoEffortCost(state, columns, back_emf_damping(run.actuator, robot.nj))
    return cost, state, cost.createData(crocoddyl.DataCollectorAbstract())


def test_damping_is_stall_torque_over_no_load_speed(run):
    d = back_emf_damping(run.actuator, 18)
    assert d.shape == (18,)
    np.testing.assert_allclose(d, run.actuator.stall_torque / run.actuator.no_load_speed)


def test_the_cost_is_the_legs_servo_effort_only(run):
    """Catches a cost on every joint, or one that leaves out the back-EMF term D q̇ (the lag a
    position servo needs to move its joint at all)."""
    robot = run.model
    cols = robot.legs[0].columns
    cost, _, data = _cost_and_state(run, cols)
    rng = np.random.default_rng(0)
    x = np.concatenate([pin.neutral(robot.model), rng.normal(size=robot.model.nv)])
    u = rng.normal(size=robot.nj) * 0.3
    cost.calc(data, x, u)
    qdot = x[robot.model.nq + 6:]
    d = back_emf_damping(run.actuator, robot.nj)
    assert data.cost == pytest.approx(0.5 * np.sum((u[cols] + d[cols] * qdot[cols]) ** 2),
                                      rel=1e-12)
    others = np.setdiff1d(np.arange(robot.nj), cols)
    u2 = u.copy()
    u2[others] += 1.0  # another leg's torque changes nothing
    cost.calc(data, x, u2)
    assert data.cost == pytest.approx(0.5 * np.sum((u[cols] + d[cols] * qdot[cols]) ** 2),
                                      rel=1e-12)
    cost.calc(data, x, None)
    assert data.cost == 0.0


def test_its_derivatives_are_its_slopes(run):
    """Catches a wrong gradient or Hessian (the solver would then descend the wrong way)."""
    robot = run.model
    cost, state, data = _cost_and_state(run, robot.legs[2].columns)
    rng = np.random.default_rng(1)
    x = np.concatenate([pin.neutral(robot.model), rng.normal(size=robot.model.nv)])
    u = rng.normal(size=robot.nj) * 0.3
    cost.calcDiff(data, x, u)
    lx, lu = np.array(data.Lx), np.array(data.Lu)
    lxx, luu, lxu = np.array(data.Lxx), np.array(data.Luu), np.array(data.Lxu)
    h = 1e-6
    fx, fu = np.zeros(state.ndx), np.zeros(robot.nj)
    gxx, gxu = np.zeros((state.ndx, state.ndx)), np.zeros((state.ndx, robot.nj))
    guu = np.zeros((robot.nj, robot.nj))
    for i in range(state.ndx):
        dx = np.zeros(state.ndx)
        dx[i] = h
        values = []
        for sign in (1, -1):
            cost.calc(data, state.integrate(x, sign * dx), u)
            values.append(data.cost)
            cost.calcDiff(data, state.integrate(x, sign * dx), u)
            gxx[:, i] += sign * np.array(data.Lx) / (2 * h)
        fx[i] = (values[0] - values[1]) / (2 * h)
    for i in range(robot.nj):
        du = np.zeros(robot.nj)
        du[i] = h
        values = []
        for sign in (1, -1):
            cost.calc(data, x, u + sign * du)
            values.append(data.cost)
            cost.calcDiff(data, x, u + sign * du)
            guu[:, i] += sign * np.array(data.Lu) / (2 * h)
            gxu[:, i] += sign * np.array(data.Lx) / (2 * h)
        fu[i] = (values[0] - values[1]) / (2 * h)
    np.testing.assert_allclose(lx, fx, atol=1e-7)
    np.testing.assert_allclose(lu, fu, atol=1e-7)
    np.testing.assert_allclose(lxx, gxx, atol=1e-6)
    np.testing.assert_allclose(luu, guu, atol=1e-6)
    np.testing.assert_allclose(lxu, gxu, atol=1e-6)


def test_bad_input_is_named(run):
    robot = run.model
    state = crocoddyl.StateMultibody(robot.model)
    with pytest.raises(InvalidParameterError, match="damping"):
        ServoEffortCost(state, [0], np.ones(3))
    with pytest.raises(InvalidParameterError, match="columns"):
        ServoEffortCost(state, [robot.nj], np.ones(robot.nj))
    with pytest.raises(InvalidParameterError, match="servo_landing_weight"):
        OptimalParams(servo_landing_weight=-1.0)
    with pytest.raises(InvalidParameterError, match="servo_landing_knots"):
        OptimalParams(servo_landing_knots=0)


def test_the_landing_knots_are_the_last_swing_knots_before_a_touch_down():
    """Catches the knots after a lift-off, or a touch-down across the cycle's end missed."""
    stance = np.array([[1, 0], [0, 0], [0, 1], [0, 1], [1, 1], [1, 0]], dtype=bool)
    np.testing.assert_array_equal(_landing_knots(stance, 1),
                                  [[0, 0], [0, 1], [0, 0], [1, 0], [0, 0], [0, 0]])
    np.testing.assert_array_equal(_landing_knots(stance, 2),
                                  [[0, 1], [0, 1], [1, 0], [1, 0], [0, 0], [0, 0]])


def test_the_problem_has_the_cost_only_where_a_leg_lands_and_only_when_on(run):
    """Catches a default that changes the command's problem, or the cost on a stance leg."""
    motion = run.motion()
    off = build_problem(run.model, motion, run.actuator, hexaleg.SpringSet(),
                        OptimalParams(nodes=20))
    on = build_problem(run.model, motion, run.actuator, hexaleg.SpringSet(),
                       OptimalParams(nodes=20, servo_landing_weight=30.0))
    landing = _landing_knots(on.stance, 1)
    for k, (a, b) in enumerate(zip(off.problem.runningModels, on.problem.runningModels,
                                   strict=True)):
        names_off = set(a.differential.costs.costs.todict())
        names_on = set(b.differential.costs.costs.todict())
        assert not any(n.endswith("_servo_landing") for n in names_off)
        expected = {f"{leg.name}_servo_landing" for j, leg in enumerate(run.model.legs)
                    if landing[k, j]}
        assert names_on - names_off == expected
        for name in expected:
            assert b.differential.costs.costs[name].weight == 30.0
    assert landing.sum() == 6  # each leg lands once a cycle
