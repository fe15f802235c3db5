"""Stepping a model: MuJoCo's rollout and the Python loop agree; divergence and step bounds are
verdicts and errors, never NaN or a hang."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.robot.springs import DeadZoneSpring
from hexaleg.simulation import stepping
from hexaleg.simulation.controllers import controls, reference
from hexaleg.simulation.model import build_model


def test_a_diverging_run_stops_without_nan(prepared):
    """Contacts made 10⁴ times stiffer after the timestep check: MuJoCo's bad acceleration or the
    fall check ends the run; the trajectory holds finite values only."""
    robot, motion = prepared.robot, prepared.motion
    sim = build_model(robot, motion, prepared.motor)
    sim.model.pair_solref[:] *= 1e4
    t = np.arange(400) * sim.timestep
    ref = reference(motion, prepared.evaluate(None).tau_motor, t)
    traj = stepping.run(sim, controls(sim.servo, ref, sim.kp, sim.kd),
                        *sim.joints.to_mujoco(motion.q[0], motion.v[0]), 0.09)
    assert traj.verdict in ("diverged", "fell") and "t =" in traj.message
    assert traj.n < 400 and np.all(np.isfinite(traj.qpos)) and np.all(np.isfinite(traj.servo))


def test_python_stepping_equals_mujoco_rollout(prepared):
    """The per-step Python loop (used for non-native springs) and MuJoCo's rollout give the same
    run when the Python force is zero."""
    robot, motion = prepared.robot, prepared.motion
    sim = build_model(robot, motion, prepared.motor)
    loop = dataclasses.replace(sim, springs=dataclasses.replace(
        sim.springs, python=((0, DeadZoneSpring(stiffness=1.0, theta_k=1e6, damping=1.0)),)))
    # a damper whose dead zone (±1e6 rad) no joint leaves: the Python loop with a zero force
    t = np.arange(300) * sim.timestep
    ctrl = controls(sim.servo, reference(motion, prepared.evaluate(None).tau_motor, t),
                    sim.kp, sim.kd)
    start = sim.joints.to_mujoco(motion.q[0], motion.v[0])
    a, b = stepping.run(sim, ctrl, *start, 0.09), stepping.run(loop, ctrl, *start, 0.09)
    for field in ("qpos", "qvel", "servo", "feet"):
        assert np.allclose(getattr(a, field), getattr(b, field), rtol=0, atol=1e-12), field


def test_a_closed_loop_that_changes_nothing_is_the_open_loop_run_bitwise(prepared):
    """The closed loop's chunks (the state set back, the constraint warm start carried over),
    under a feedback that returns zero, step exactly the open-loop run — through MuJoCo's
    rollout and through the Python loop of non-native springs; a feedback's change is applied
    to its chunk's rows and recorded in the controls."""
    robot, motion = prepared.robot, prepared.motion
    sim = build_model(robot, motion, prepared.motor)
    loop = dataclasses.replace(sim, springs=dataclasses.replace(
        sim.springs, python=((0, DeadZoneSpring(stiffness=1.0, theta_k=1e6, damping=1.0)),)))
    t = np.arange(1000) * sim.timestep
    ctrl = controls(sim.servo, reference(motion, prepared.evaluate(None).tau_motor, t),
                    sim.kp, sim.kd)
    start = sim.joints.to_mujoco(motion.q[0], motion.v[0])
    for model in (sim, loop):
        a = stepping.run(model, ctrl.copy(), *start, 0.09)
        b = stepping.run(model, ctrl.copy(), *start, 0.09, lambda *x: np.zeros(robot.nj), 7)
        for field in ("qpos", "qvel", "servo", "feet", "controls"):
            assert np.array_equal(getattr(a, field), getattr(b, field)), field
    times = []

    def nudge(t, qpos, qvel, feet):
        times.append(t)
        return np.full(robot.nj, 1e-3)

    c = stepping.run(sim, ctrl.copy(), *start, 0.09, nudge, 7)
    assert np.allclose(times, np.arange(0, 1000, 7) * sim.timestep, rtol=0, atol=1e-15)
    assert np.allclose(c.controls - ctrl, 1e-3, rtol=0, atol=1e-15)


def test_an_open_loop_run_in_chunks_is_the_one_call_rollout_bitwise(prepared):
    """The open-loop run steps in chunks of :data:`stepping.CHUNK` (the state set back, the
    warm start carried over): to the bit what one call of MuJoCo's rollout steps."""
    import mujoco
    import mujoco.rollout

    robot, motion = prepared.robot, prepared.motion
    sim = build_model(robot, motion, prepared.motor)
    n = round(2.4 * stepping.CHUNK / sim.timestep)  # three chunks, the last one short
    ctrl = controls(sim.servo, reference(motion, prepared.evaluate(None).tau_motor,
                                         np.arange(n) * sim.timestep), sim.kp, sim.kd)
    start = sim.joints.to_mujoco(motion.q[0], motion.v[0])
    traj = stepping.run(sim, ctrl, *start, 0.09)
    m = sim.model
    data = mujoco.MjData(m)
    data.qpos[:], data.qvel[:] = start
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    state0 = np.zeros(mujoco.mj_stateSize(m, spec))
    mujoco.mj_getState(m, data, state0, spec)
    state, sensors = mujoco.rollout.rollout(m, data, state0[None], ctrl[None])
    qpos = np.concatenate([state0[None, 1:1 + m.nq], state[0, :-1, 1:1 + m.nq]])
    assert traj.n == n and np.array_equal(traj.qpos, qpos)
    assert np.array_equal(traj.servo, sensors[0, :, :robot.nj])


def test_an_open_loop_run_stops_stepping_once_it_fell(prepared, monkeypatch):
    """A robot whose controls are reckoned with 1/200 of its servos' gain falls: its run stops
    within a chunk of the fall instead of stepping the fallen robot to the end (the rows after
    it were cut anyway)."""
    robot, motion = prepared.robot, prepared.motion
    sim = build_model(robot, motion, prepared.motor)
    loop = dataclasses.replace(sim, springs=dataclasses.replace(
        sim.springs, python=((0, DeadZoneSpring(stiffness=1.0, theta_k=1e6, damping=1.0)),)))
    stepped = []
    inner = stepping._python_loop
    monkeypatch.setattr(stepping, "_python_loop",
                        lambda s, d, c: stepped.append(len(c)) or inner(s, d, c))
    n = round(4 * motion.period / sim.timestep)
    ctrl = controls(sim.servo, reference(motion, prepared.evaluate(None).tau_motor,
                                         np.arange(n) * sim.timestep), sim.kp / 200, sim.kd)
    traj = stepping.run(loop, ctrl, *sim.joints.to_mujoco(motion.q[0], motion.v[0]),
                        float(np.mean(motion.q[:, 2])))
    assert traj.verdict == "fell" and traj.n < n
    chunk = round(stepping.CHUNK / sim.timestep)
    assert traj.n <= sum(stepped) <= traj.n + chunk < n


def test_too_many_steps_is_an_error_not_a_hang(prepared):
    sim = build_model(prepared.robot, prepared.motion, prepared.motor)
    with pytest.raises(InvalidParameterError, match="simulation steps"):
        stepping.run(sim, np.broadcast_to(np.zeros(1), (stepping.MAX_STEPS + 1, 1)),
                     np.zeros(1), np.zeros(1), 0.09)


def test_tilt_of_a_rolled_and_pitched_base():
    import pinocchio as pin

    quat = pin.Quaternion(pin.utils.rpyToMatrix(0.2, -0.1, 1.0)).coeffs()  # x y z w
    qpos = np.zeros((1, 7))
    qpos[0, 3], qpos[0, 4:7] = quat[3], quat[:3]
    roll, pitch = stepping.tilt(qpos)
    assert roll[0] == pytest.approx(0.2) and pitch[0] == pytest.approx(-0.1)


def test_rows_are_the_state_before_each_step_and_its_sensors(prepared):
    """Row k holds the state at t_k and what MuJoCo computed from it (foot sites, servo force):
    the torque recorded with a speed is the one applied over that step."""
    import mujoco

    robot, motion = prepared.robot, prepared.motion
    sim = build_model(robot, motion, prepared.motor)
    t = np.arange(50) * sim.timestep
    ctrl = controls(sim.servo, reference(motion, prepared.evaluate(None).tau_motor, t),
                    sim.kp, sim.kd)
    start = sim.joints.to_mujoco(motion.q[0], motion.v[0])
    traj = stepping.run(sim, ctrl, *start, 0.09)
    assert np.array_equal(traj.qpos[0], start[0]) and np.array_equal(traj.t, t)
    data = mujoco.MjData(sim.model)
    for k in (0, 17, 49):
        data.qpos[:], data.qvel[:], data.ctrl[:18] = traj.qpos[k], traj.qvel[k], ctrl[k]
        mujoco.mj_forward(sim.model, data)
        assert np.allclose(traj.feet[k], [data.site(f"{leg}_foot").xpos
                                          for leg in robot.leg_names], atol=1e-12)
        assert np.allclose(traj.servo[k], data.actuator_force[:18], atol=1e-12)


def _run_against_a_variant(prepared, change, cycles: float):
    """The gait's model and a copy of it changed by ``change(model)``, each run open loop for
    ``cycles`` of the gait from the planned start: (model, run, variant's run)."""
    import copy

    motion = prepared.motion
    sim = build_model(prepared.robot, motion, prepared.motor)
    variant = dataclasses.replace(sim, model=copy.deepcopy(sim.model))
    change(variant.model)
    t = np.arange(round(cycles * motion.period / sim.timestep)) * sim.timestep
    ctrl = controls(sim.servo, reference(motion, prepared.evaluate(None).tau_motor, t),
                    sim.kp, sim.kd)
    start = sim.joints.to_mujoco(motion.q[0], motion.v[0])
    a, b = stepping.run(sim, ctrl, *start, 0.09), stepping.run(variant, ctrl, *start, 0.09)
    assert a.verdict == b.verdict == "ran"
    return sim, a, b


def test_the_pgs_solver_gives_the_energies_of_mujocos_newton_solver(prepared):
    """The model's projected Gauss–Seidel and MuJoCo's default Newton solver solve the same
    contact program: over a cycle of the gait (two tripod handovers) the motor energy and the
    trajectory agree to the solvers' tolerance."""
    import mujoco

    from hexaleg.dynamics.energy import metrics

    def newton(model):
        assert model.opt.solver == mujoco.mjtSolver.mjSOL_PGS
        model.opt.solver = mujoco.mjtSolver.mjSOL_NEWTON

    sim, a, b = _run_against_a_variant(prepared, newton, 1.0)
    dq = [sim.joints.joints_mj(r.qvel, velocity=True) for r in (a, b)]
    energy = [metrics(r.tau_motor, w, sim.timestep, prepared.motor)["total"]["electrical"]
              for r, w in zip((a, b), dq, strict=True)]
    assert abs(energy[0] - energy[1]) < 1e-5 * energy[1]
    assert np.abs(a.qpos - b.qpos).max() < 1e-6


def test_switching_off_island_discovery_leaves_the_states_bitwise_equal(prepared):
    """A walking robot's contacts couple through its base into one constraint island, so MuJoCo's
    island search (switched off by the model, for speed) changes nothing: half a cycle of the
    gait with it switched back on gives the same states to the last bit."""
    import mujoco

    if not hasattr(mujoco.mjtDisableBit, "mjDSBL_ISLAND"):
        pytest.skip("this MuJoCo has no island discovery")
    island = int(mujoco.mjtDisableBit.mjDSBL_ISLAND)

    def search(model):
        assert model.opt.disableflags & island
        model.opt.disableflags &= ~island

    _, a, b = _run_against_a_variant(prepared, search, 0.5)
    np.testing.assert_array_equal(a.qpos, b.qpos)
    np.testing.assert_array_equal(a.servo, b.servo)


def test_the_closed_loops_scalar_fall_check_is_the_runs(prepared):
    """The closed loop asks at each update, in scalars, whether the base fell (stepping._down);
    it must judge a state as the run's verdict does (stepping._fallen): random bases, tilted
    and upright, high and low, a non-finite one."""
    rng = np.random.default_rng(7)
    height = 0.09
    for i in range(3000):
        q = np.zeros(prepared.robot.model.nq)
        q[2] = rng.uniform(0.0, 2 * height)
        q[3:7] = rng.normal(size=4) if i % 2 else np.r_[1.0, 0.6 * rng.normal(size=3)]
        q[3:7] *= rng.uniform(0.5, 2.0)  # not normalised: both normalise
        assert stepping._down(q, height) == bool(stepping._fallen(q[None], height)[0]), q[:7]
    q[2] = np.nan
    assert stepping._down(q, height) and stepping._fallen(q[None], height)[0]
