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


MANY = hexaleg.SpringSet({
    **SPRINGS,
    "LM_femur": hexaleg.DeadZoneSpring(0.3, theta_k=0.15, neutral=0.2, alpha=1.3,
                                       convention="eq14"),
    "RF_tibia": hexaleg.OneSidedSpring(0.2, contact=-0.1, side="above", preload=0.05),
    "RH_femur": hexaleg.PreloadedSpring(0.5, 0.04, theta_k=0.05),
    "LF_coxa": hexaleg.LinearSpring(0.07514952938680902, reference=0.013408641197613785,
                                    torque_at_reference=-1.4215499839611968e-18),
    "RM_femur": hexaleg.LinearSpring(3.418777983426041e-13, reference=0.5463761917680798,
                                     torque_at_reference=-0.042832338802230405),
})


def _one_by_one(spring, q, v):
    """A law's torque, stiffness and damping at one joint, as the actuation took them joint by
    joint before its laws were grouped: the law's own methods on one-element arrays, the
    stiffness summed term by term."""
    qa, one = np.array([q]), np.array([1.0])
    k = 0.0
    for term, x in zip(spring.terms(), spring.magnitudes(), strict=True):
        d = q - term.angle
        engaged = {"above": d > 0.0, "below": d < 0.0}.get(term.kind, True)
        k += float(x) * {"above": -1.0, "below": -1.0, "linear": -1.0}.get(term.kind,
                                                                           0.0) * engaged
    return (float(spring.torque(qa, np.array([v]))[0]), k,
            float(spring.torque(qa, one)[0] - spring.torque(qa, 0 * one)[0]))


@pytest.mark.parametrize("seed", [5, 6, 7])
def test_the_grouped_laws_are_each_laws_own_numbers_to_the_bit(robot, seed):
    """The actuation evaluates the laws a group at a time (:class:`LawGroup`); its torques,
    stiffnesses and damping are exactly (not approximately) each law's own on its joint — a dead
    zone taken by its joint-side terms (``a k⁺`` as one magnitude: it rounds otherwise, and
    has no damping) fails here."""
    state = crocoddyl.StateMultibody(robot.model)
    act = SpringActuation(state, sprung_joints(robot, MANY))
    data = act.createData()
    rng = np.random.default_rng(seed)
    nq, nv = robot.model.nq, robot.model.nv
    for _ in range(50):
        x = _state(robot, rng)
        tau = act.spring_torques(x)
        act.calcDiff(data, x, np.zeros(robot.nj))
        for s in act.sprung:
            torque, k, damping = _one_by_one(s.spring, x[s.iq], x[nq + s.iv])
            assert tau[s.column] == torque
            assert data.dtau_dx[6 + s.column, s.iv] == k
            assert data.dtau_dx[6 + s.column, nv + s.iv] == damping
    assert 1 < len(act.groups) < len(act.sprung)  # groups of several laws and sizes


def test_a_non_finite_state_is_named(robot):
    state = crocoddyl.StateMultibody(robot.model)
    act = SpringActuation(state, sprung_joints(robot, SPRINGS))
    x = _state(robot, np.random.default_rng(8))
    x[act.sprung[0].iq] = np.nan
    with pytest.raises(hexaleg.errors.InvalidParameterError, match="q"):
        act.spring_torques(x)


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
