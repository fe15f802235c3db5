"""The optimal-control problem: the gait's contact timing at every knot, the springs in its
actuation, the motor's limits as the control box, the periodic terminal state; bad input named."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError

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


def test_the_ground_under_a_swing_foot_is_the_lower_of_its_two_footholds():
    """One leg, six knots: down at 0–1 and 5, in swing at 2–4; the cycle climbs 30 mm (a
    slope's stride), so the foothold it lands on at knot 5 … and the one of the next cycle's
    knot 0 are 30 mm higher than this cycle's."""
    from hexaleg.optimal.problem import ground_heights

    stance = np.array([[True], [True], [False], [False], [False], [True]])
    footholds = np.zeros((6, 1, 3))
    footholds[[0, 1], 0] = [0.0, 0.0, 0.10]
    footholds[5, 0] = [0.2, 0.0, 0.12]
    displacement = np.eye(4)
    displacement[:3, 3] = [0.3, 0.0, 0.03]
    ground = ground_heights(stance, footholds, displacement)
    np.testing.assert_allclose(ground[2:5, 0], 0.10)
    assert np.isnan(ground[[0, 1, 5], 0]).all()
    # the swing that runs past the cycle's end lands on the next cycle's foothold
    stance = np.array([[True], [True], [True], [True], [False], [False]])
    footholds[:4, 0] = [0.0, 0.0, 0.10]
    ground = ground_heights(stance, footholds, displacement)
    np.testing.assert_allclose(ground[4:, 0], 0.10)  # min(0.10, 0.13)
    displacement[2, 3] = -0.03  # downhill: the next cycle's foothold is the lower
    np.testing.assert_allclose(ground_heights(stance, footholds, displacement)[4:, 0], 0.07)


def test_a_swing_foot_below_the_ground_is_penalised(run, built):
    """The clearance barrier of a swing knot is zero with the foot above the ground and grows
    as the square of its depth below it (the whole robot lowered until the swing foot is 1 mm,
    then 2 mm under); a stance foot has none."""
    import pinocchio as pin

    from hexaleg.optimal.problem import ground_heights

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


def _hip_to_foot(robot, leg, q):
    """Distance from the joint before the leg's knee to its foot at ``q``, m."""
    import pinocchio as pin

    pin.framesForwardKinematics(robot.model, robot.data, q)
    return float(np.linalg.norm(robot.data.oMf[leg.foot_frame_id].translation
                                - robot.data.oMi[leg.joint_ids[-2]].translation))


@pytest.mark.parametrize("name", ["hexaleg", "solo12"])
def test_the_knee_bound_holds_the_foot_the_margin_short_of_full_stretch(name):
    """At the bound the hip-to-foot distance is the leg's reach less the margin, the reach
    being the largest distance over a sweep of the knee (Solo-12's front and hind knees bend
    opposite ways: each is bounded on its own side). Catches a bound on the wrong side of the
    stretched angle, a margin taken as an angle, or a stretched angle that is not the reach's."""
    from hexaleg.optimal.problem import knee_bounds

    run = hexaleg.Scenario.load(name)
    robot, q = run.model, run.motion().q[:1]
    lower, upper = knee_bounds(robot, q, 3e-3)
    for leg in robot.legs:
        i = leg.q_index[-1]
        sweep = np.linspace(-np.pi, np.pi, 20001)
        reach = max(_hip_to_foot(robot, leg, np.concatenate([q[0, :i], [t], q[0, i + 1:]]))
                    for t in sweep)
        bent_up = lower[0, i] > robot.model.lowerPositionLimit[i]
        bound = lower[0, i] if bent_up else upper[0, i]
        assert (q[0, i] >= bound) if bent_up else (q[0, i] <= bound)  # the warm start's side
        at = q[0].copy()
        at[i] = bound
        assert _hip_to_foot(robot, leg, at) == pytest.approx(reach - 3e-3, abs=1e-6)
        assert lower[0, i] == robot.model.lowerPositionLimit[i] or \
            upper[0, i] == robot.model.upperPositionLimit[i]  # one side bounded


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
