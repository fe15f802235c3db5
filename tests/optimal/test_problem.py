"""The optimal-control problem: the gait's contact timing at every knot, the springs in its
actuation, the motor's limits as the control box, the periodic terminal state; bad input named."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError, UnknownNameError

pytest.importorskip("crocoddyl")

from hexaleg.optimal.problem import OptimalParams, build_problem


@pytest.fixture(scope="module")
def run():
    return hexaleg.Scenario.load("hexaleg")


@pytest.fixture(scope="module")
def built(run):
    return build_problem(run.model, run.motion(), run.actuator, hexaleg.SpringSet(),
                         OptimalParams(nodes=20))


def test_knots_follow_the_gaits_contact_timing(run, built):
    motion = run.motion()
    assert built.problem.T == 20
    assert built.dt == pytest.approx(motion.period / 20)
    legs = [leg.name for leg in run.model.legs]
    for k, model in enumerate(built.problem.runningModels):
        sample = round(k * built.dt / motion.dt)
        down = sorted(model.differential.contacts.active_set)
        assert down == sorted(n for n, s in zip(legs, motion.stance[sample], strict=True) if s)
        assert len(down) == 3  # the tripod


def test_the_motors_stall_torque_is_the_control_box(run, built):
    model = built.problem.runningModels[0]
    np.testing.assert_allclose(model.u_ub, run.actuator.stall_torque)
    np.testing.assert_allclose(model.u_lb, -run.actuator.stall_torque)


def test_the_terminal_state_is_the_first_moved_by_a_stride(built):
    x0, xn = built.x_warm[0], built.x_warm[-1]
    np.testing.assert_allclose(xn[:3] - x0[:3], [built.distance, 0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(xn[3:], x0[3:], atol=1e-12)
    assert "periodic" in built.problem.terminalModel.differential.costs.costs.todict()


def test_the_springs_are_in_the_dynamics(run):
    springs = hexaleg.SpringSet({"LF_femur": hexaleg.LinearSpring(0.5, reference=0.3)})
    b = build_problem(run.model, run.motion(), run.actuator, springs, OptimalParams(nodes=10))
    x = b.x_warm[0]
    model = b.problem.runningModels[0]
    data = model.createData()
    model.calc(data, x, np.zeros(run.model.nj))
    column = run.model.joint_names.index("LF_femur")
    expected = springs.torques(run.model, x[None, :run.model.model.nq])[0, column]
    assert data.differential.multibody.actuation.tau[6 + column] == pytest.approx(expected)
    assert expected != 0.0


def test_bad_input_is_named(run):
    with pytest.raises(InvalidParameterError, match="nodes"):
        OptimalParams(nodes=3)
    with pytest.raises(InvalidParameterError, match="friction_use"):
        OptimalParams(friction_use=1.5)
    with pytest.raises(InvalidParameterError, match="closing"):
        OptimalParams(closing=-1)
    with pytest.raises(InvalidParameterError, match="gap"):
        OptimalParams(gap=0.0)
    motion = run.motion()
    with pytest.raises(InvalidParameterError, match="fixed_base"):
        build_problem(run.model, dataclasses.replace(motion, fixed_base=True), run.actuator,
                      hexaleg.SpringSet())
    airborne = dataclasses.replace(motion, stance=np.zeros_like(motion.stance))
    with pytest.raises(InvalidParameterError, match="no foot down at knot 0"):
        build_problem(run.model, airborne, run.actuator, hexaleg.SpringSet())


def test_a_stance_foot_off_its_foothold_is_back_on_it_at_the_next_knot(run, built):
    """The contacts' dead-beat Baumgarte gains (``contact_gains``): the whole robot moved 1 mm
    off its footholds comes back onto them in one knot, to a few per cent of the offset (second
    order in the knot's change of the contact Jacobian). Velocity damping alone would leave the
    feet 1 mm off: a planned stance foot would drift, and the servos fight the ground for it."""
    import pinocchio as pin

    robot = run.model
    nq = robot.model.nq
    k = 3
    model = built.problem.runningModels[k]
    data = model.createData()
    x = built.x_warm[k].copy()
    x[:3] += [1e-3, -1e-3, 1e-3]
    model.calc(data, x, model.quasiStatic(data, x))
    pin.framesForwardKinematics(robot.model, robot.data, data.xnext[:nq])
    down = built.stance[k]
    assert down.sum() == 3
    for j in np.flatnonzero(down):
        foot = robot.data.oMf[robot.legs[j].foot_frame_id].translation
        assert np.linalg.norm(foot - built.footholds[k, j]) < 0.05 * np.sqrt(3) * 1e-3


def test_the_gains_are_dead_beat_for_the_knot():
    from hexaleg.optimal.problem import contact_gains

    dt = 0.025
    kp, kd = contact_gains(dt)
    e, v = 1e-3, 0.02  # the foot's error and speed along one axis
    v1 = v + dt * (-kp * e - kd * v)
    assert e + dt * v1 == pytest.approx(0.0, abs=1e-18)
    with pytest.raises(InvalidParameterError, match="dt"):
        contact_gains(0.0)


@pytest.mark.parametrize("integrator, order", [("rk2", 2), ("rk3", 3), ("rk4", 4)])
def test_the_runge_kutta_gains_are_dead_beat_for_their_knot(integrator, order):
    """The error ODE ``ë = −k_p e − k_d ė`` stepped by the explicit Runge–Kutta of the knot's
    order (its step matrix ``Σ_{i ≤ p} (dt A)ⁱ/i!``) lands on zero from any error and speed.
    The Euler gains under RK4 leave 94 % of a 1 mm error (spectral radius 0.61)."""
    import math

    from hexaleg.optimal.problem import contact_gains

    dt = 0.025
    kp, kd = contact_gains(dt, integrator)
    a = dt * np.array([[0.0, 1.0], [-kp, -kd]])
    step = sum(np.linalg.matrix_power(a, i) / math.factorial(i) for i in range(order + 1))
    np.testing.assert_allclose(step @ [1e-3, 0.02 * dt], 0.0, atol=1e-15)
    with pytest.raises(UnknownNameError, match="integrator"):
        contact_gains(dt, "rk5")


def test_a_runge_kutta_knot_holds_its_stance_feet_on_their_footholds(run):
    """``integrator="rk4"``: every running knot Crocoddyl's RK4 with its dead-beat gains (the
    terminal knot Euler's of zero step); the whole robot moved 1 mm off its footholds is back on
    them at the next knot, to a few per cent, as with Euler's knot. With the gains
    ``k_p = 1/dt², k_d = 1/dt`` an RK4 knot leaves them 1.15 mm off (of 1.73 mm)."""
    import crocoddyl
    import pinocchio as pin

    from hexaleg.optimal.problem import contact_gains

    robot = run.model
    nq = robot.model.nq
    b = build_problem(robot, run.motion(), run.actuator, hexaleg.SpringSet(),
                      OptimalParams(nodes=20, integrator="rk4"))
    assert all(isinstance(m, crocoddyl.IntegratedActionModelRK)
               for m in b.problem.runningModels)
    assert isinstance(b.problem.terminalModel, crocoddyl.IntegratedActionModelEuler)
    k = 3
    model = b.problem.runningModels[k]
    for item in model.differential.contacts.contacts.todict().values():
        np.testing.assert_allclose(item.contact.gains, contact_gains(b.dt, "rk4"))
    data = model.createData()
    x = b.x_warm[k].copy()
    x[:3] += [1e-3, -1e-3, 1e-3]
    model.calc(data, x, model.quasiStatic(data, x))
    pin.framesForwardKinematics(robot.model, robot.data, data.xnext[:nq])
    for j in np.flatnonzero(b.stance[k]):
        foot = robot.data.oMf[robot.legs[j].foot_frame_id].translation
        assert np.linalg.norm(foot - b.footholds[k, j]) < 0.05 * np.sqrt(3) * 1e-3
    with pytest.raises(UnknownNameError, match="integrator"):
        OptimalParams(integrator="implicit")


def test_a_runge_kutta_knots_forces_are_its_first_stages(run):
    """The solve reads a Runge–Kutta knot's contact forces from its first stage (the dynamics
    at the knot's own state), not its last, and none for a swing foot."""
    from hexaleg.optimal.solve import _forces

    robot = run.model
    b = build_problem(robot, run.motion(), run.actuator, hexaleg.SpringSet(),
                      OptimalParams(nodes=20, integrator="rk4"))
    xs = list(b.x_warm)
    b.problem.calc(xs, list(b.problem.quasiStatic(xs[:-1])))
    forces = _forces(robot, b)
    for k, data in enumerate(b.problem.runningDatas):
        first = data.differential[0].multibody.contacts.contacts.todict()
        last = data.differential[3].multibody.contacts.contacts.todict()
        for j, leg in enumerate(robot.legs):
            if b.stance[k, j]:
                np.testing.assert_array_equal(forces[k, j], first[leg.name].f.linear)
                assert np.abs(forces[k, j] - last[leg.name].f.linear).max() > 1e-6
            else:
                assert not forces[k, j].any()


def test_a_swing_foot_below_the_ground_is_penalised(run, built):
    """The clearance barrier of a swing knot is zero with the foot above the ground and grows
    as the square of its depth below it (the whole robot lowered until the swing foot is 1 mm,
    then 2 mm under); a stance foot has none."""
    import pinocchio as pin

    from hexaleg.optimal.bounds import ground_heights

    robot = run.model
    nq = robot.model.nq
    ground = ground_heights(built.stance, built.footholds, built.displacement)
    k = int(np.flatnonzero((~built.stance).any(axis=1))[0])
    j = int(np.flatnonzero(~built.stance[k])[0])
    name = f"{robot.legs[j].name}_clearance"
    model = built.problem.runningModels[k]
    data = model.createData()

    def cost(x):
        model.calc(data, x, np.zeros(model.nu))
        return data.differential.costs.costs[name].cost

    x = built.x_warm[k].copy()
    pin.framesForwardKinematics(robot.model, robot.data, x[:nq])
    height = robot.data.oMf[robot.legs[j].foot_frame_id].translation[2] - ground[k, j]
    assert height > 0 and cost(x) == 0.0
    x[2] -= height + 1e-3
    below = cost(x)
    assert below == pytest.approx(0.5 * 1e-6, rel=1e-6)  # ½ depth², weighed in the sum
    x[2] -= 1e-3
    assert cost(x) == pytest.approx(4 * below, rel=1e-6)
    assert all(f"{leg.name}_clearance" not in built.problem.runningModels[k].differential
               .costs.costs.todict() for leg, down in zip(robot.legs, built.stance[k],
                                                          strict=True) if down)


def test_a_knot_at_full_stretch_is_penalised():
    """Solo-12's knee straightened at a knot (its foot at full stretch) is in the limits'
    barrier; the warm start's knee, well bent, is not. Catches a problem without the margin:
    the URDF's knee limits (±10 rad) allow a straight knee."""
    run = hexaleg.Scenario.load("solo12")
    built = build_problem(run.model, run.motion(), run.actuator, hexaleg.SpringSet(),
                          OptimalParams(nodes=20))
    model = built.problem.runningModels[0]
    data = model.createData()

    def cost(x):
        model.calc(data, x, np.zeros(model.nu))
        return data.differential.costs.costs["limits"].cost

    x = built.x_warm[0].copy()
    assert cost(x) == 0.0
    for leg in run.model.legs:
        x[leg.q_index[-1]] = 0.0
    assert cost(x) > 0.0
