"""The energy cost: the project's exact power, a smoothing within its stated bound, and the
cost's derivatives against finite differences."""

from __future__ import annotations

import numpy as np
import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError

crocoddyl = pytest.importorskip("crocoddyl")

from hexaleg.optimal.energy import EnergyCost, JointPower  # noqa: E402


@pytest.fixture(scope="module")
def motor():
    return hexaleg.Scenario.load("hexaleg").actuator


def test_exact_power_is_the_motors(motor):
    power = JointPower.of(motor, 4, 1e-3)
    rng = np.random.default_rng(0)
    u, w = rng.normal(size=(50, 4)), rng.normal(size=(50, 4)) * 3
    np.testing.assert_allclose(power.exact(u, w), motor.electrical_power(u, w), rtol=1e-12)


@pytest.mark.parametrize("eps", [1e-1, 1e-3])
def test_smoothing_is_above_the_exact_power_by_at_most_its_bound(motor, eps):
    power = JointPower.of(motor, 3, eps)
    rng = np.random.default_rng(1)
    u, w = rng.normal(size=(400, 3)), rng.normal(size=(400, 3)) * 3
    gap = power.smoothed(u, w)[0] - power.exact(u, w)
    assert gap.min() >= -1e-12
    assert gap.max() <= 2 * eps * np.log(2) + 1e-12
    assert gap.max() >= 0.3 * eps  # the bound is of the right size, not vacuous


def test_smoothed_derivatives_match_finite_differences(motor):
    power = JointPower.of(motor, 5, 1e-2)
    rng = np.random.default_rng(2)
    u, w, h = rng.normal(size=5) * 0.3, rng.normal(size=5), 1e-6
    _, (gu, gv), (huu, hvv, huv) = power.smoothed(u, w)
    f = lambda a, b: power.smoothed(a, b)[0]  # noqa: E731
    g = lambda a, b: power.smoothed(a, b)[1]  # noqa: E731
    np.testing.assert_allclose(gu, (f(u + h, w) - f(u - h, w)) / (2 * h), rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(gv, (f(u, w + h) - f(u, w - h)) / (2 * h), rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(huu, (g(u + h, w)[0] - g(u - h, w)[0]) / (2 * h), rtol=1e-5,
                               atol=1e-7)
    np.testing.assert_allclose(hvv, (g(u, w + h)[1] - g(u, w - h)[1]) / (2 * h), rtol=1e-5,
                               atol=1e-7)
    np.testing.assert_allclose(huv, (g(u, w + h)[0] - g(u, w - h)[0]) / (2 * h), rtol=1e-5,
                               atol=1e-7)


def test_regeneration_takes_negative_power_back(motor):
    import dataclasses
    power = JointPower.of(dataclasses.replace(motor, regeneration=True), 1, 1e-3)
    u, w = np.array([0.1]), np.array([-5.0])  # back-driven: power returns
    assert power.exact(u, w)[0] < 0
    assert power.smoothed(u, w)[0][0] == pytest.approx(power.exact(u, w)[0], abs=2e-3)


def test_the_cost_sums_the_joints_and_its_derivatives_are_its_slopes(robot, motor):
    state = crocoddyl.StateMultibody(robot.model)
    cost = EnergyCost(state, JointPower.of(motor, robot.nj, 1e-2))
    data = cost.createData(crocoddyl.DataCollectorAbstract())
    rng = np.random.default_rng(3)
    x = np.concatenate([pin_neutral(robot), rng.normal(size=robot.model.nv)])
    u = rng.normal(size=robot.nj) * 0.3
    cost.calc(data, x, u)
    assert data.cost == pytest.approx(np.sum(cost.power.smoothed(u, x[robot.model.nq + 6:])[0]))
    cost.calcDiff(data, x, u)
    h = 1e-6
    lx = np.zeros(state.ndx)
    for i in range(state.ndx):
        dx = np.zeros(state.ndx)
        dx[i] = h
        cost.calc(data, state.integrate(x, dx), u)
        up = data.cost
        cost.calc(data, state.integrate(x, -dx), u)
        lx[i] = (up - data.cost) / (2 * h)
    np.testing.assert_allclose(data.Lx, lx, atol=1e-7)
    assert np.abs(lx[:robot.model.nv + 6]).max() == 0.0  # positions and base speeds: no power


def pin_neutral(robot):
    import pinocchio as pin
    return pin.neutral(robot.model)


def test_bad_constants_are_named():
    with pytest.raises(InvalidParameterError, match="efficiency"):
        JointPower(np.ones(2), np.array([0.5, 1.5]), np.zeros(2, bool), 1e-3)
    with pytest.raises(InvalidParameterError, match="smoothing"):
        JointPower(np.ones(2), np.array([0.5, 0.5]), np.zeros(2, bool), 0.0)
