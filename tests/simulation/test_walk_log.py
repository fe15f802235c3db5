"""The simulated walk log: its sensors as stated and its energy the steady walk's."""

from __future__ import annotations

import math

import numpy as np
import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.recorded.read import read_log
from hexaleg.simulation.run import simulate
from hexaleg.simulation.walk_log import DYNAMIXEL_TICK, Sensors, walk_log


@pytest.fixture(scope="module")
def gait(robot):
    return hexaleg.gait(robot)


@pytest.fixture(scope="module")
def exact(robot, gait):
    return walk_log(robot, gait, settle=0.5, cycles=4, evaluate=2,
                    sensors=Sensors(tick=0.0, joint_noise=0.0, base_noise=0.0, imu_noise=0.0))


def test_the_steady_walk_after_a_drop_uses_the_energy_of_the_simulated_gait(robot, gait,
                                                                             exact):
    """A periodic steady state forgets its start: the drop and the settle change the last
    cycles' energy by less than a part in 10³ from the simulation started on the plan."""
    planned = simulate(robot, gait, None).baseline.metrics["electrical"]
    assert exact.electrical == pytest.approx(planned, rel=1e-3)
    assert exact.walk_from == pytest.approx(0.5, abs=1e-3)
    assert exact.evaluated_from == pytest.approx(2.5, abs=1e-3)
    for fraction in exact.touch.values():  # the handover: longer than the plan's 0.5
        assert 0.5 <= fraction <= 0.65


def test_the_sensors_add_the_stated_noise(robot, gait, exact):
    noisy = walk_log(robot, gait, settle=0.5, cycles=4, evaluate=2,
                     sensors=Sensors(base_noise=1e-3, imu_noise=math.radians(1.0)))
    joints = np.stack([noisy.columns[j] for j in robot.joint_names], axis=1)
    assert np.allclose(joints / DYNAMIXEL_TICK, np.round(joints / DYNAMIXEL_TICK), atol=1e-9)
    true = np.stack([exact.columns[j] for j in robot.joint_names], axis=1)
    assert 0.2 * DYNAMIXEL_TICK < np.std(joints - true) < 0.6 * DYNAMIXEL_TICK
    base = np.stack([noisy.columns[c] - exact.columns[c] for c in ("base_x", "base_y",
                                                                    "base_z")], axis=1)
    assert np.std(base) == pytest.approx(1e-3, rel=0.1)
    qn = np.stack([noisy.columns[c] for c in ("base_qx", "base_qy", "base_qz", "base_qw")], 1)
    qe = np.stack([exact.columns[c] for c in ("base_qx", "base_qy", "base_qz", "base_qw")], 1)
    assert np.allclose(np.linalg.norm(qn, axis=1), 1.0, atol=1e-12)
    angle = 2 * np.arccos(np.clip(np.abs(np.sum(qn * qe, axis=1)), 0.0, 1.0))
    # the angle of a rotation by a Gaussian axis-angle vector of σ per axis: Maxwell, mean
    # 2 σ √(2/π)
    assert np.mean(angle) == pytest.approx(2 * math.radians(1.0) * math.sqrt(2 / math.pi),
                                           rel=0.1)


def test_the_log_reads_back_in_degrees_and_parts(robot, exact, tmp_path):
    path = exact.write(tmp_path / "walk.csv", ("joints", "imu"), degrees=True)
    header = path.read_text(encoding="utf-8").splitlines()[0]
    assert "base_x" not in header and f"{robot.joint_names[0]} [deg]" in header
    log = read_log(robot, path)
    np.testing.assert_allclose(log.matrix(list(robot.joint_names)),
                               np.stack([exact.columns[j] for j in robot.joint_names], 1),
                               rtol=1e-8, atol=1e-9)
    switches = read_log(robot, exact.write(tmp_path / "c.csv", ("joints", "contacts")))
    for leg, touch in exact.touch.items():  # the switches over the evaluated cycles
        column = switches.matrix([f"contact_{leg}"])[:, 0]
        assert set(np.unique(column)) == {0.0, 1.0}
        t = switches.t
        evaluated = (t >= exact.evaluated_from) & (t < t[-1] + 1e-9)
        assert column[evaluated].mean() == pytest.approx(touch, abs=0.02)
    with pytest.raises(InvalidParameterError, match="parts"):
        exact.write(tmp_path / "x.csv", ("base",))
    with pytest.raises(InvalidParameterError, match="lidar"):
        exact.write(tmp_path / "x.csv", ("joints", "lidar"))
