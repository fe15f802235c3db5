"""MuJoCo's stage timers are off while a run steps and back after; the steps are the same to
the bit; a timer the user set keeps running."""

from __future__ import annotations

import sys

import mujoco
import numpy as np
import pytest

from hexaleg.simulation import stepping, timers
from hexaleg.simulation.controllers import controls, reference
from hexaleg.simulation.model import build_model

STEP = int(mujoco.mjtTimer.mjTIMER_STEP)


@pytest.fixture(scope="module")
def sim(prepared):
    return build_model(prepared.robot, prepared.motion, prepared.motor)


def _timed(sim, steps: int = 5) -> float:
    """Seconds MuJoCo's step timer counts over ``steps`` fresh steps of ``sim``."""
    data = mujoco.MjData(sim.model)
    mujoco.mj_resetData(sim.model, data)
    data.timer[STEP].duration = 0.0
    for _ in range(steps):
        mujoco.mj_step(sim.model, data)
    return float(data.timer[STEP].duration)


def test_the_clock_is_found_where_the_bindings_loaded_mujoco():
    """The wheels this project runs (Linux) lay MuJoCo's library out as :data:`timers.LIBRARIES`
    says: found, so the speed-up is not silently lost."""
    if sys.platform.startswith("linux"):
        assert timers.clock_pointer() is not None


def test_steps_untimed_are_not_timed_and_the_timers_come_back(sim):
    """Inside :func:`timers.untimed` MuJoCo's step timer counts nothing; after it, and after
    nested blocks and an exception inside one, it counts again."""
    if timers.clock_pointer() is None:
        pytest.skip("MuJoCo's library not found: timers stay on")
    assert _timed(sim) > 0
    with timers.untimed():
        assert _timed(sim) == 0.0
        with timers.untimed():
            assert _timed(sim) == 0.0
        assert _timed(sim) == 0.0  # an inner block's end leaves the outer one untimed
    assert _timed(sim) > 0
    with pytest.raises(RuntimeError), timers.untimed():
        raise RuntimeError("a run interrupted")
    assert _timed(sim) > 0


def test_a_users_timer_keeps_running(sim):
    """A timer set from Python (``mujoco.set_mjcb_time``) is the user's: left running."""
    calls = []

    def clock() -> float:
        calls.append(1)
        return float(len(calls))

    mujoco.set_mjcb_time(clock)
    try:
        with timers.untimed():
            _timed(sim, 1)
    finally:
        mujoco.set_mjcb_time(None)
    assert calls
    assert mujoco.get_mjcb_time() is None


def test_a_run_untimed_is_the_timed_run_to_the_bit(sim, prepared):
    """The timers write only ``mjData.timer``: 400 steps of the default gait under
    :func:`stepping.run` (untimed) and MuJoCo's step in a Python loop with the timers on give
    the same states and sensors, bit for bit."""
    motion = prepared.motion
    t = np.arange(400) * sim.timestep
    ctrl = controls(sim.servo, reference(motion, prepared.evaluate(None).tau_motor, t),
                    sim.kp, sim.kd)
    qpos0, qvel0 = sim.joints.to_mujoco(motion.q[0], motion.v[0])
    run = stepping.run(sim, ctrl, qpos0, qvel0, 0.09)
    m = sim.model
    data = mujoco.MjData(m)
    data.qpos[:], data.qvel[:] = qpos0, qvel0
    qpos, sensors = np.empty((len(t), m.nq)), np.empty((len(t), m.nsensordata))
    for k in range(len(t)):
        qpos[k] = data.qpos
        data.ctrl[:] = ctrl[k]
        mujoco.mj_step(m, data)
        sensors[k] = data.sensordata
    assert data.timer[STEP].duration > 0  # this loop was timed
    forces, feet = sim.sensor_slices()
    assert run.n == len(t)
    assert np.array_equal(run.qpos, qpos)
    assert np.array_equal(run.servo, sensors[:, forces])
    assert np.array_equal(run.feet.reshape(len(t), -1), sensors[:, feet])
