"""The balance controller's rate: how much faster the base answers its wrench than the model it
is sized for, and the period that keeps the sampled loop stable (G1's end-to-end run is in
test_balance.py)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from conftest import held_loop_radius

from hexaleg.scenario.scenario import Scenario
from hexaleg.simulation import balance, control_rate

BIPED6 = str(Path(__file__).parents[1] / "data" / "biped6.toml")


def test_the_base_answers_a_wrench_r_times_faster_than_the_model_it_is_sized_for():
    """``loop_ratio``: the base's acceleration under the controller's wrench (Pinocchio's ABA
    with the joints free, gravity and velocity off: a formulation without ``M⁻¹``) along the
    slowest model direction is r times what the model (m, I_c) assumes; on the biped on soles
    the 100-Hz loop is within the limit, so its controller keeps 100 Hz."""
    import pinocchio as pin

    prepared = Scenario.from_tables(BIPED6, {"gait": {"samples": 100}}).prepare()
    robot, q = prepared.robot, prepared.motion.q[0]
    r = control_rate.loop_ratio(robot, q)
    model = robot.model.copy()
    model.gravity.linear[:] = 0.0
    data = model.createData()
    pin.ccrba(model, data, q, np.zeros(model.nv))
    rot = pin.Quaternion(q[6], *q[3:6]).toRotationMatrix()
    inertia = rot.T @ np.asarray(data.Ig.inertia) @ rot
    seen = []
    for rows, scale in ((slice(0, 3), robot.mass * np.eye(3)), (slice(3, 6), inertia)):
        for axis in np.eye(3):
            tau = np.zeros(model.nv)
            tau[rows] = scale @ axis  # the model's wrench for a unit acceleration
            accel = pin.aba(model, data, q, np.zeros(model.nv), tau)[rows]
            seen.append(accel @ axis)
    assert r == pytest.approx(5.03, abs=0.01)  # angular (5.02 at the default 1000 samples)
    assert max(seen) <= r * (1 + 1e-9) and max(seen) > 0.9 * r, (seen, r)
    gains = balance.size_gains(robot, prepared.motion)
    assert gains.period == control_rate.CONTROL_PERIOD
    assert held_loop_radius(r, gains, gains.period) < 1.0
