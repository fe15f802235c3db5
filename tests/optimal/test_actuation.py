"""The spring actuation: its torque is the motor's plus the springs', its derivatives are the
finite differences of its torque, and its commands invert it."""

from __future__ import annotations

import numpy as np
import pytest

import hexaleg
from hexaleg.errors import UnknownNameError

crocoddyl = pytest.importorskip("crocoddyl")

from hexaleg.optimal.actuation import SpringActuation, sprung_joints, stiffness  # noqa: E402

SPRINGS = hexaleg.SpringSet({
    "LF_femur": hexaleg.DeadZoneSpring(0.4, theta_minus=-0.2, theta_plus=0.1, k2=0.05,
                                       damping=0.02),
    "RM_tibia": hexaleg.OneSidedSpring(0.3, contact=0.2, side="below"),
    "LH_coxa": hexaleg.LinearSpring(0.25, reference=0.1, torque_at_reference=0.03),
})


def _state(robot, rng):
    q = robot.poses["standing"].copy() if "standing" in robot.poses else \
        np.array(next(iter(robot.poses.values())))
    q[7:] += rng.uniform(-0.5, 0.5, robot.nj)
    v = rng.uniform(-1.0, 1.0, robot.model.nv)
    return np.concatenate([q, v])


def test_torque_is_the_motors_plus_the_springs(robot):
    state = crocoddyl.StateMultibody(robot.model)
    act = SpringActuation(state, sprung_joints(robot, SPRINGS))
    data = act.createData()
    rng = np.random.default_rng(1)
    x, u = _state(robot, rng), rng.normal(size=robot.nj)
    act.calc(data, x, u)
    nq = robot.model.nq
    expected = SPRINGS.torques(robot, x[None, :nq], x[None, nq:])[0] + u
    np.testing.assert_allclose(data.tau[:6], 0.0)
    np.testing.assert_allclose(data.tau[6:], expected, atol=1e-12)
    assert np.count_nonzero(expected - u) == 3  # the three springs act at this state
    act.commands(data, x, data.tau)
    np.testing.assert_allclose(data.u, u, atol=1e-12)


@pytest.mark.parametrize("seed", [2, 3, 4])
def test_derivatives_match_finite_differences(robot, seed):
    """∂τ/∂x (the springs' stiffness and damping) and ∂τ/∂u against central differences of
    :meth:`calc` on the state manifold (the free flyer's tangent by Pinocchio's integrate)."""
    state = crocoddyl.StateMultibody(robot.model)
    act = SpringActuation(state, sprung_joints(robot, SPRINGS))
    data = act.createData()
    rng = np.random.default_rng(seed)
    x, u = _state(robot, rng), rng.normal(size=robot.nj)
    act.calcDiff(data, x, u)
    jx, ju = data.dtau_dx.copy(), data.dtau_du.copy()
    assert np.count_nonzero(jx) >= 3  # the springs' stiffness and the damping enter
    h = 1e-7
    fd = np.zeros_like(jx)
    for i in range(state.ndx):
        dx = np.zeros(state.ndx)
        dx[i] = h
        plus, minus = state.integrate(x, dx), state.integrate(x, -dx)
        act.calc(data, plus, u)
        tp = data.tau.copy()
        act.calc(data, minus, u)
        fd[:, i] = (tp - data.tau) / (2 * h)
    np.testing.assert_allclose(jx, fd, atol=1e-6)
    fdu = np.zeros_like(ju)
    for i in range(robot.nj):
        du = np.zeros(robot.nj)
        du[i] = h
        act.calc(data, x, u + du)
        tp = data.tau.copy()
        act.calc(data, x, u - du)
        fdu[:, i] = (tp - data.tau) / (2 * h)
    np.testing.assert_allclose(ju, fdu, atol=1e-6)


def test_stiffness_is_the_slope_of_each_law():
    """Analytic cases: a dead zone is stiff only past its contact angles (k₂ everywhere), a
    linear spring everywhere, a preload's step has no slope."""
    dz = hexaleg.DeadZoneSpring(0.4, theta_minus=-0.2, theta_plus=0.1, k2=0.05)
    assert stiffness(dz, 0.0) == pytest.approx(-0.05)
    assert stiffness(dz, 0.3) == pytest.approx(-0.45)
    assert stiffness(dz, -0.3) == pytest.approx(-0.45)
    assert stiffness(hexaleg.LinearSpring(0.25), 7.0) == pytest.approx(-0.25)
    pre = hexaleg.OneSidedSpring(0.3, contact=0.2, preload=0.1)
    assert stiffness(pre, 0.1) == 0.0
    assert stiffness(pre, 0.3) == pytest.approx(-0.3)


def test_a_spring_on_an_unknown_joint_is_named(robot):
    state = crocoddyl.StateMultibody(robot.model)
    with pytest.raises(UnknownNameError, match="XX_femur"):
        SpringActuation(state, sprung_joints(robot, hexaleg.SpringSet(
            {"XX_femur": hexaleg.LinearSpring(1.0)})))
