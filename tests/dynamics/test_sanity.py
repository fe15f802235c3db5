"""Tests of hexaleg.dynamics.sanity: joint torques over the URDF effort limits are flagged per
joint at the peak, a joint without a limit is reported rather than skipped silently, and the
registry robots' default gaits stay within their limits."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import analyze
from hexaleg.dynamics.sanity import torque_findings
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.legged import tripod_gait
from hexaleg.motion.scaling import robot_gait
from hexaleg.robot.registry import DESCRIPTIONS, description, load

SAMPLES = 200
# The force solver must not clip the torques to the limits under test.
NO_LIMITS = ContactParams(torque_limits=False)


@pytest.fixture(scope="module")
def tau(robot, walk200) -> np.ndarray:
    """Motor torques of the built-in robot's default tripod gait, (T, 18) N·m."""
    return analyze(robot, walk200, contact=NO_LIMITS).tau_motor


@pytest.mark.parametrize("name", sorted(DESCRIPTIONS))
def test_registry_robots_default_gaits_stay_within_their_effort_limits(name):
    robot = load(name)
    gait = dataclasses.replace(robot_gait(description(name)), samples=SAMPLES)
    motion = tripod_gait(robot, gait)
    findings = torque_findings(robot, analyze(robot, motion, contact=NO_LIMITS).tau_motor,
                               motion.t)
    assert findings == [], "\n".join(f.message for f in findings)


def test_torques_over_the_limit_are_flagged_per_joint_at_the_peak(robot, walk200, tau):
    """Scaled by 12, the gait's torques exceed the AX-18A's 1.8 N·m on the loaded joints only."""
    scaled = 12.0 * tau
    findings = torque_findings(robot, scaled, walk200.t)
    limits = robot.model.effortLimit[6:]
    peaks = np.abs(scaled).max(axis=0)
    over = [n for n, p, lim in zip(robot.joint_names, peaks, limits, strict=True) if p > lim]
    assert 0 < len(over) < robot.nj
    assert [f.where.split()[1] for f in findings] == over
    for found in findings:
        col = robot.column(found.where.split()[1])
        k = int(np.argmax(np.abs(scaled[:, col])))
        assert found.check == "joint_torque" and found.unit == "N·m"
        assert found.value == pytest.approx(peaks[col], rel=1e-12)
        assert found.where.endswith(f"at t = {walk200.t[k]:.4g} s")
        assert found.allowed == f"|τ| ≤ {limits[col]:.4g} N·m (URDF effort limit)"
        assert "spring" in found.remedy and "slow the gait" in found.remedy
    assert torque_findings(robot, tau, walk200.t) == []


def test_without_times_the_sample_is_named(robot, tau):
    tau = tau.copy()
    tau[17, robot.column("LM_femur")] = -2.5
    (found,) = torque_findings(robot, tau)
    assert found.where == "joint LM_femur at sample 17" and found.value == 2.5


def test_a_joint_without_effort_limit_is_reported_and_the_others_still_checked(urdf_with_limit,
                                                                              tau):
    robot = urdf_with_limit("RF_tibia", "effort", "0")
    (missing,) = torque_findings(robot, tau)
    assert missing.check == "effort_limit_missing" and missing.where == "joint RF_tibia"
    assert missing.value == 0.0 and "<limit effort=" in missing.remedy
    loud = tau.copy()
    loud[3, robot.column("LF_coxa")] = 5.0
    assert [f.check for f in torque_findings(robot, loud)] == ["joint_torque",
                                                              "effort_limit_missing"]


def test_bad_shapes_raise(robot, tau):
    with pytest.raises(InvalidParameterError, match=r"tau = .*shape \(T, 18\)"):
        torque_findings(robot, tau[:, :6])
    with pytest.raises(InvalidParameterError, match=r"invalid t = "):
        torque_findings(robot, tau, np.zeros(3))
