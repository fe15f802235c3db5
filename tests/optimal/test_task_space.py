"""An optimal cycle rebuilt in task space: through the knots, its stance feet on their footholds
at every instant, its velocities and accelerations the derivatives of its configurations.

The default gait thinned to 40 knots stands in for the solver's cycle (no Crocoddyl needed): a
cycle whose knots are exact, so what the rebuild adds between them is what is tested. The
solver's own cycle rebuilt and simulated is in ``test_solve.py``."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError
from hexaleg.optimal.task_space import task_space_motion

PER_KNOT = 8


@pytest.fixture(scope="module")
def knots(walk):
    thin = slice(None, None, 25)
    return hexaleg.Motion(t=walk.t[thin], q=walk.q[thin], v=walk.v[thin], a=walk.a[thin],
                          stance=walk.stance[thin], feet=walk.feet[thin], period=walk.period,
                          distance=walk.distance, info=dict(walk.info))


@pytest.fixture(scope="module")
def footholds(knots):
    return np.where(knots.stance[..., None], knots.feet, 0.0)


@pytest.fixture(scope="module")
def rebuilt(robot, knots, footholds):
    return task_space_motion(robot, knots, footholds, per_knot=PER_KNOT)


def _feet(robot, q, v):
    """World position and LOCAL_WORLD_ALIGNED linear velocity of every foot, (n_legs, 3) each."""
    pin.forwardKinematics(robot.model, robot.data, q, v)
    pin.updateFramePlacements(robot.model, robot.data)
    world = pin.LOCAL_WORLD_ALIGNED
    return (np.array([robot.data.oMf[leg.foot_frame_id].translation for leg in robot.legs]),
            np.array([pin.getFrameVelocity(robot.model, robot.data, leg.foot_frame_id,
                                           world).linear for leg in robot.legs]))


def test_the_rebuilt_cycle_passes_through_the_knots(knots, rebuilt):
    assert rebuilt.n_samples == PER_KNOT * knots.n_samples
    assert rebuilt.period == knots.period and rebuilt.distance == knots.distance
    np.testing.assert_allclose(rebuilt.q[::PER_KNOT], knots.q, atol=1e-9)
    np.testing.assert_array_equal(rebuilt.stance[::PER_KNOT], knots.stance)
    assert "integrator" not in rebuilt.info  # a continuous motion, not semi-implicit knots


def test_the_stance_feet_hold_their_footholds_between_the_knots(robot, knots, rebuilt):
    """Every sample's stance feet on their footholds and at rest."""
    worst_position = worst_speed = 0.0
    for k in range(rebuilt.n_samples):
        p, v = _feet(robot, rebuilt.q[k], rebuilt.v[k])
        down = rebuilt.stance[k]
        np.testing.assert_allclose(p, rebuilt.feet[k], atol=1e-12)
        worst_position = max(worst_position, float(np.abs(p - knots.feet[k // PER_KNOT])[
            down].max(initial=0.0)))
        worst_speed = max(worst_speed, float(np.abs(v[down]).max(initial=0.0)))
    assert worst_position <= 1e-12 and worst_speed <= 1e-9


def test_the_velocities_and_accelerations_are_the_derivatives(robot, rebuilt):
    """Central differences of the configurations give the velocities, of the velocities the
    accelerations (away from the knots, where a foot's lift-off or touch-down may change the
    acceleration)."""
    h, n = rebuilt.dt, rebuilt.n_samples
    inner = np.arange(1, n - 1)
    dq = np.array([pin.difference(robot.model, rebuilt.q[i - 1], rebuilt.q[i + 1]) / (2 * h)
                   for i in inner])
    scale = np.abs(rebuilt.v).max()
    assert np.abs(dq - rebuilt.v[inner]).max() <= 2e-3 * scale
    smooth = inner[(inner % PER_KNOT != 0) & ((inner + 1) % PER_KNOT != 0)
                   & ((inner - 1) % PER_KNOT != 0)]
    dv = (rebuilt.v[smooth + 1] - rebuilt.v[smooth - 1]) / (2 * h)
    assert np.abs(dv - rebuilt.a[smooth]).max() <= 2e-2 * np.abs(rebuilt.a).max()


def test_bad_footholds_and_turning_cycles_are_refused(robot, knots, footholds):
    with pytest.raises(InvalidParameterError, match=r"footholds\.shape"):
        task_space_motion(robot, knots, footholds[:-1])
    info = dict(knots.info)
    turn = np.eye(4)
    turn[:3, :3] = pin.exp3(np.array([0.0, 0.0, 0.1]))
    info["cycle"] = turn.tolist()
    turning = hexaleg.Motion(t=knots.t, q=knots.q, v=knots.v, a=knots.a, stance=knots.stance,
                             feet=knots.feet, period=knots.period, distance=knots.distance,
                             info=info)
    with pytest.raises(InvalidParameterError, match="straight stride"):
        task_space_motion(robot, turning, footholds)


@pytest.mark.slow
def test_the_solvers_cycle_rebuilt_walks_for_what_hexaleg_predicts():
    """A short cycle with springs and six feet down at times (the default gait at duty factor
    0.8, its linear springs, 20 knots, 60 iterations; 13 s of CPU): played as its knots'
    joint angles it falls short of its distance under feedforward servos (87 %, 32.7 J/m of
    what it covered, where the solver booked 10.6 J/m) — between the knots the stance feet
    leave their footholds and the legs push against each other —; rebuilt in task space it
    walks for 20.3 J/m, predicted 21.3 by hexaleg's pipeline (the solver's 20 knots let its
    stance feet slide 24 mm/s: the plan's own figure is not the held cycle's)."""
    pytest.importorskip("crocoddyl")
    from dataclasses import replace

    from hexaleg.design.codesign.alternation import predicted_per_metre
    from hexaleg.design.codesign.build import default_gait
    from hexaleg.design.codesign.servo import simulated_per_metre
    from hexaleg.optimal.problem import OptimalParams, build_problem
    from hexaleg.optimal.solve import solve

    run = hexaleg.Scenario.load("hexaleg")
    robot = run.model
    params = replace(default_gait(robot, "hexaleg", 0.06, None, 100), duty_factor=0.8)
    motion = hexaleg.gait(robot, params)
    prepared = hexaleg.prepare(robot, motion, motor=run.actuator, contact=run.contact)
    springs = hexaleg.optimal_springs(prepared, list(robot.joint_classes), family="linear",
                                      metric="electrical").springs
    result = solve(robot, build_problem(robot, motion, run.actuator, springs,
                                        OptimalParams(nodes=20, iterations=60, stop=5e-5)))
    played = result.task_space
    predicted, why = predicted_per_metre(robot, played, run.actuator, springs, run.contact)
    assert why == "" and predicted is not None
    simulated, verdict = simulated_per_metre(robot, played, run.actuator, springs,
                                             "feedforward", run.contact)
    assert verdict == "walks" and simulated is not None
    assert simulated == pytest.approx(predicted, rel=0.06)  # 20.30 against 21.35 measured
    knots, why = simulated_per_metre(robot, result.motion, run.actuator, springs, "feedforward",
                                     run.contact)
    # measured: short (87 % of the planned distance), 32.7 J/m of the distance it covered
    assert knots is None and why.startswith("short"), (knots, why)


@pytest.mark.slow  # the humanoid's gait: ~5 s of CPU
def test_a_joint_on_no_leg_follows_its_knots():
    """The test humanoid's arm joints (on no leg) swung by a sinusoid in the knots: the rebuilt
    cycle passes through them with the sinusoid's speed between them (a periodic spline)."""
    run = hexaleg.Scenario.load(str(Path(__file__).resolve().parents[1] / "data"
                                    / "humanoid.toml"))
    robot, walk = run.model, run.motion()
    thin = slice(None, None, 25)
    on_legs = {int(i) for leg in robot.legs for i in np.atleast_1d(
        np.arange(robot.model.nv)[leg.v_index])}
    arm = next(j for j in list(robot.model.joints)[2:] if j.idx_v not in on_legs)
    q = walk.q[thin].copy()
    t = walk.t[thin]
    omega = 2 * np.pi / walk.period
    q[:, arm.idx_q] += 0.2 * np.sin(omega * t)
    knots = hexaleg.Motion(t=t, q=q, v=walk.v[thin], a=walk.a[thin], stance=walk.stance[thin],
                           feet=walk.feet[thin], period=walk.period, distance=walk.distance,
                           info=dict(walk.info))
    rebuilt = task_space_motion(robot, knots, np.where(knots.stance[..., None], knots.feet, 0.0),
                                per_knot=4)
    np.testing.assert_allclose(rebuilt.q[::4], knots.q, atol=1e-9)
    speed = 0.2 * omega * np.cos(omega * rebuilt.t)
    assert np.abs(rebuilt.v[:, arm.idx_v] - speed).max() <= 0.01 * 0.2 * omega
