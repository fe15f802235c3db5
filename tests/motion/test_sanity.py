"""Tests of hexaleg.motion.sanity: joint speeds and angles against the URDF limits and the static
margin fire on gaits built to break them, name the joint (or feet) and the remedy, and stay silent
on every registry robot's default gait."""

from __future__ import annotations

import dataclasses
import re

import numpy as np
import pytest

import hexaleg
from hexaleg.motion.legged import tripod_gait
from hexaleg.motion.params import GaitParams
from hexaleg.motion.sanity import (
    motion_findings,
    position_findings,
    speed_findings,
    support_findings,
)
from hexaleg.motion.scaling import robot_gait
from hexaleg.robot.registry import DESCRIPTIONS, description, load

SAMPLES = 200


@pytest.fixture(scope="module")
def solo() -> hexaleg.Robot:
    return load("solo12")


@pytest.mark.parametrize("name", sorted(DESCRIPTIONS))
def test_registry_robots_default_gaits_pass_every_check(name):
    robot = load(name)
    gait = dataclasses.replace(robot_gait(description(name)), samples=SAMPLES)
    findings = motion_findings(robot, tripod_gait(robot, gait))
    assert findings == [], "\n".join(f.message for f in findings)


def test_too_fast_a_gait_is_flagged_and_the_suggested_period_fixes_it(robot):
    """Period 0.25 s: the swing femurs and tibias exceed the 10.16 rad/s of the AX-18A's URDF
    limit. Speeds scale as 1/period along the same path, so the suggested period (the largest
    over the joints) brings every joint back within its limit."""
    fast = tripod_gait(robot, GaitParams(period=0.25, samples=SAMPLES))
    findings = speed_findings(robot, fast)
    assert findings and {f.check for f in findings} == {"joint_speed"}
    limits = robot.model.velocityLimit[6:]
    peaks = np.abs(fast.v[:, 6:]).max(axis=0)
    over = [name for name, peak, lim in zip(robot.joint_names, peaks, limits, strict=True)
            if peak > lim]
    assert [f.where.split()[1] for f in findings] == over
    for found in findings:
        col = robot.column(found.where.split()[1])
        assert found.value == pytest.approx(peaks[col], rel=1e-12) and found.unit == "rad/s"
        assert f"≤ {limits[col]:.4g} rad/s" in found.allowed
    periods = [float(re.search(r"period ≥ ([0-9.]+) s", f.remedy).group(1))  # type: ignore[union-attr]
               for f in findings]
    slow = tripod_gait(robot, GaitParams(period=max(periods) * 1.001, samples=SAMPLES))
    assert speed_findings(robot, slow) == []


def test_scaled_velocities_are_flagged_on_every_joint_over_its_limit(robot, walk200):
    scaled = dataclasses.replace(walk200, v=walk200.v * 4.0)
    findings = motion_findings(robot, scaled)
    peaks = 4.0 * np.abs(walk200.v[:, 6:]).max(axis=0)
    assert len(findings) == int((peaks > robot.model.velocityLimit[6:]).sum()) > 0
    assert all(f.check == "joint_speed" and "slow the motion" in f.remedy for f in findings)


def test_a_joint_without_velocity_limit_is_reported_not_skipped(urdf_with_limit, walk200):
    robot = urdf_with_limit("LM_coxa", "velocity", "0")
    (found,) = motion_findings(robot, walk200)
    assert found.check == "velocity_limit_missing" and found.where == "joint LM_coxa"
    assert found.value == 0.0 and "<limit velocity=" in found.remedy


def test_joint_outside_its_position_limits_is_flagged_at_its_worst_sample(robot, walk200):
    q = walk200.q.copy()
    col = robot.column("RH_tibia")
    iq = 7 + col
    lo = robot.model.lowerPositionLimit[iq]
    q[50, iq], q[120, iq] = lo - 0.05, lo - 0.2
    (found,) = position_findings(robot, dataclasses.replace(walk200, q=q))
    assert found.check == "joint_position" and found.unit == "rad"
    assert found.value == pytest.approx(lo - 0.2)
    assert found.where == f"joint RH_tibia at t = {walk200.t[120]:.4g} s"
    assert f"[{lo:.4g}, " in found.allowed and "RH_tibia" in found.remedy
    assert position_findings(robot, walk200) == []


def test_gait_on_one_side_of_the_body_has_a_negative_static_margin(robot):
    """Hexapod groups {LF, LM, LH} and {RF, RM, RH}: three feet always stand, all on one side,
    so the CoM is outside every support triangle."""
    side = tripod_gait(robot, GaitParams(groups=(("LF", "LM", "LH"), ("RF", "RM", "RH")),
                                         samples=SAMPLES, balance="none"))
    (found,) = motion_findings(robot, side)
    assert found.check == "static_margin" and found.value < -0.05 and found.unit == "m"
    assert found.value == pytest.approx(side.info["static_margin"], rel=1e-12)
    assert "(200 of 200 samples negative)" in found.where
    assert "duty_factor" in found.remedy


def test_quadruped_crawl_with_negative_static_margin(solo):
    """Solo-12 crawl LF → LH → RF → RH (one leg at a time, β = 0.75, no CoM shift: balance
    'none'): the pairs of the same side swing back to back and the CoM leaves the support
    triangle."""
    gait = dataclasses.replace(robot_gait(description("solo12")), duty_factor=0.75,
                               groups=(("LF",), ("LH",), ("RF",), ("RH",)), samples=SAMPLES,
                               balance="none")
    crawl = tripod_gait(solo, gait)
    assert crawl.info["min_stance_feet"] == 3
    (found,) = support_findings(solo, crawl)
    assert found.check == "static_margin"
    assert found.value < -0.01
    assert found.value == pytest.approx(crawl.info["static_margin"], rel=1e-12)


def test_two_feet_without_balance_are_flagged_and_balanced_trot_is_not(solo):
    base = dataclasses.replace(robot_gait(description("solo12")), samples=SAMPLES)
    rigid = tripod_gait(solo, dataclasses.replace(base, balance="none"))
    (found,) = support_findings(solo, rigid)
    two = int((rigid.stance.sum(axis=1) < 3).sum())
    assert found.check == "static_support" and found.value == 2.0 and found.unit == "feet"
    assert f"{two} of {SAMPLES} samples on fewer than 3 feet" in found.where
    assert "balance = 'auto'" in found.remedy
    assert support_findings(solo, tripod_gait(solo, base)) == []


def test_held_base_is_not_a_support_problem(robot, walk200):
    """A base resting on a support (``Motion.supported``) with every foot in the air."""
    held = dataclasses.replace(walk200, stance=np.zeros_like(walk200.stance),
                               supported=np.ones(walk200.n_samples, dtype=bool))
    assert support_findings(robot, held) == []
    airborne = dataclasses.replace(held, supported=np.zeros(walk200.n_samples, dtype=bool))
    (found,) = support_findings(robot, airborne)
    assert found.check == "static_support" and found.value == 0.0
