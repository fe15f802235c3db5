"""Tests of hexaleg.motion.zmp, the walking pattern of gaits on one foot (issue #39): a
quadruped's crawl at duty factor 0.3 and a biped on point feet are balanced so that the moment
about every one-foot sample's stance foot vanishes (measured independently with Pinocchio's
centroidal dynamics), the body's turn is kinematically exact (stance feet at rest under FK,
base velocities the finite differences of its poses), and the forces exist where the friction
allows them — and where it does not, the least friction is named."""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import analyze
from hexaleg.errors import InfeasibleForcesError, InvalidParameterError
from hexaleg.motion.balance import BALANCE_TOL, Sway, Turn
from hexaleg.motion.body import body_motion, in_base_frame
from hexaleg.motion.legged import sample_gait
from hexaleg.motion.params import GaitParams
from hexaleg.motion.scaling import robot_gait
from hexaleg.motion.trajectory import Motion
from hexaleg.motion.zmp import periodic_turn, zmp_reference
from hexaleg.robot.registry import description
from hexaleg.scenario.scenario import Scenario

SAMPLES = 200


@pytest.fixture(scope="module")
def solo() -> hexaleg.Robot:
    return hexaleg.load("solo12")


@pytest.fixture(scope="module")
def crawl(solo) -> tuple[GaitParams, Motion]:
    gait = dataclasses.replace(robot_gait(description("solo12")), pattern="crawl",
                               duty_factor=0.3, samples=SAMPLES)
    return gait, sample_gait(solo, gait)


def test_crawl_at_duty_factor_03_is_balanced_by_the_walking_pattern(solo, crawl):
    """Every sample on one foot: no moment about the foot, all three components, from the
    centroidal momentum (``pin.computeCentroidalMomentumTimeVariation``: ḣ_G about the CoM),
    not from the RNEA the iteration uses."""
    _, motion = crawl
    info = motion.info["balance"]
    assert info["mode"] == "zmp" and info["residual"] <= BALANCE_TOL
    assert motion.stance.sum(axis=1).min() == 1
    model, data = solo.model, solo.model.createData()
    scale = solo.mass * 9.81 * info["height"]
    gravity = model.gravity.linear
    for k in np.flatnonzero(motion.stance.sum(axis=1) == 1):
        pin.computeCentroidalMomentumTimeVariation(model, data, motion.q[k], motion.v[k],
                                                   motion.a[k])
        com = data.com[0]
        force = data.dhg.linear - solo.mass * gravity  # what the contacts push
        foot = motion.feet[k, np.flatnonzero(motion.stance[k])[0]]
        moment = data.dhg.angular + np.cross(com - foot, force)
        assert np.abs(moment).max() <= 1e-8 * scale, (k, moment)


def test_the_walking_pattern_is_kinematically_exact(solo, crawl):
    """FK of q, v, a: feet on their targets, stance feet at rest (velocity and classical
    acceleration); the base's v and a are the central differences of its poses and velocities
    (the turn's rotating-frame terms, ω̇ × p among them, checked)."""
    gait, motion = crawl
    model, data = solo.model, solo.model.createData()
    for k in range(0, motion.n_samples, 7):
        pin.forwardKinematics(model, data, motion.q[k], motion.v[k], motion.a[k])
        pin.updateFramePlacements(model, data)
        for i, leg in enumerate(solo.legs):
            fid = leg.foot_frame_id
            assert np.allclose(data.oMf[fid].translation, motion.feet[k, i], atol=1e-9)
            if motion.stance[k, i]:
                frame = pin.LOCAL_WORLD_ALIGNED
                assert np.abs(pin.getFrameVelocity(model, data, fid, frame).linear).max() <= 1e-8
                assert np.abs(pin.getFrameClassicalAcceleration(model, data, fid, frame)
                              .linear).max() <= 1e-7
    t, h = np.linspace(0.01, gait.period - 0.01, 9), 1e-5
    at, before, after = (sample_gait(solo, gait, t + s) for s in (0.0, -h, h))
    assert np.abs(at.info["balance"]["turn"] - motion.info["balance"]["turn"]) == 0.0
    for k in range(len(t)):
        v = pin.difference(model, before.q[k], after.q[k]) / (2 * h)
        assert np.allclose(v[:6], at.v[k, :6], rtol=0, atol=1e-6)
        assert np.allclose((after.v[k, :6] - before.v[k, :6]) / (2 * h), at.a[k, :6], rtol=0,
                           atol=1e-4)


def test_a_turned_body_s_derivatives_are_exact():
    """body_motion with a sway and a turn on a circular path: the LOCAL velocities are the
    finite differences of the poses, the accelerations those of the velocities; a world point
    seen from the body has the derivatives in_base_frame gives."""
    rng = np.random.default_rng(3)
    sway = Sway.from_samples(np.array([0.0, 1.0, 0.0]), 0.8, 0.02 * rng.normal(size=12))
    turn = Turn.from_samples(np.array([0.0, 0.0, 1.0]), 0.8, 0.1 * rng.normal(size=12))
    t, h = np.linspace(0.05, 0.75, 11), 1e-6

    def body(times):
        return body_motion(times, 0.2, 0.4, 0.3, (sway, turn))

    b, lo, hi = body(t), body(t - h), body(t + h)
    v_world = (hi.base - lo.base) / (2 * h)
    assert np.allclose(np.einsum("nji,nj->ni", b.rot, v_world), b.v, atol=1e-7)
    assert np.allclose((hi.yaw - lo.yaw) / (2 * h), b.w[:, 2], atol=1e-7)
    assert np.allclose((hi.v - lo.v) / (2 * h), b.a, atol=1e-5)
    assert np.allclose((hi.w - lo.w) / (2 * h), b.alpha, atol=1e-5)
    point = np.array([0.3, -0.2, 0.0])
    zeros = np.zeros((len(t), 3))
    _, rel_d, rel_dd = in_base_frame(b, np.tile(point, (len(t), 1)), zeros, zeros)
    rel_lo = in_base_frame(lo, np.tile(point, (len(t), 1)), zeros, zeros)
    rel_hi = in_base_frame(hi, np.tile(point, (len(t), 1)), zeros, zeros)
    assert np.allclose((rel_hi[0] - rel_lo[0]) / (2 * h), rel_d, atol=1e-7)
    assert np.allclose((rel_hi[1] - rel_lo[1]) / (2 * h), rel_dd, atol=1e-5)


def test_periodic_turn_has_the_given_yaw_acceleration():
    rng = np.random.default_rng(5)
    r = rng.normal(size=64)
    r -= r.mean()
    psi = periodic_turn(r, 0.5)
    turn = Turn.from_samples(np.array([0.0, 0.0, 1.0]), 0.5, psi)
    _, _, acc = turn(np.arange(64) * 0.5 / 64)
    assert np.allclose(acc, r, atol=1e-9) and abs(psi.mean()) < 1e-15


def test_zmp_reference_is_the_foot_and_moves_across_two_foot_runs():
    """One foot: the foot. A run of two feet between single supports on A then B: the
    reference moves from A to B linearly, the ends excluded (A and B are the neighbours')."""
    stance = np.array([[1, 0], [1, 1], [1, 1], [1, 1], [0, 1], [0, 1], [1, 1], [1, 0]],
                      dtype=bool)
    feet = np.zeros((8, 2, 3))
    feet[:, 1, 0] = 1.0
    motion = Motion(t=np.arange(8.0), q=np.zeros((8, 7)), v=np.zeros((8, 6)),
                    a=np.zeros((8, 6)), stance=stance, feet=feet, period=8.0, fixed_base=False)
    mask, points = zmp_reference(motion)
    assert mask.all()
    assert np.allclose(points[:, 0], [0.0, 0.25, 0.5, 0.75, 1.0, 1.0, 0.5, 0.0])
    # sample 6 is a one-sample run from B (before) to A (after, wrapping to sample 7 then 0)


def test_the_crawl_s_forces_exist_with_grip_and_the_least_friction_is_named(solo, crawl):
    """With μ = 1.3 (and no stall limit) the one-foot crawl has forces, Newton–Euler exact;
    at the default μ = 0.6 the error names the friction the single support needs: on one
    point foot the force points at the centre of mass, so it needs the CoM's horizontal
    distance from the foot over its height — 1.2 at the diagonal switch, whatever the
    pattern."""
    _, motion = crawl
    result = analyze(solo, motion, contact=ContactParams(mu=1.3, torque_limits=False))
    model, data = solo.model, solo.model.createData()
    for k in range(0, motion.n_samples, 5):
        pin.centerOfMass(model, data, motion.q[k], motion.v[k], motion.a[k])
        rhs = solo.mass * (data.acom[0] - model.gravity.linear)
        assert np.allclose(result.forces[k].sum(axis=0), rhs, rtol=0,
                           atol=1e-8 * np.abs(rhs).max())
    assert not result.forces[~motion.stance].any()
    with pytest.raises(InfeasibleForcesError, match=r"least friction .* μ = 1\.2.*one point "
                       r"foot's force points from the foot at the centre of mass"):
        analyze(solo, motion, contact=ContactParams(torque_limits=False))


def test_balance_zmp_is_asked_for_where_it_applies():
    assert GaitParams(balance="zmp").balance_mode(1) == "zmp"
    assert GaitParams().balance_mode(1) == "zmp"
    with pytest.raises(InvalidParameterError, match="one foot at its fewest"):
        GaitParams(balance="zmp").balance_mode(2)
    assert math.isfinite(BALANCE_TOL)


def test_docs_quote_the_pattern_this_code_finds(crawl):
    """docs/gait.md's table row for Solo-12's crawl is what the walking pattern finds here
    (the sway to 0.1 mm and the turn to 0.1°: converged quantities; the iteration count is
    not pinned, another floating-point path may take one more)."""
    from pathlib import Path

    info = crawl[1].info["balance"]
    x, y = (1e3 * a for a in info["sway"])
    row = f"| Solo-12 crawl, β = 0.3 | ±{x:.1f}, ±{y:.1f} mm | ±{math.degrees(info['turn']):.1f}° |"
    page = (Path(__file__).resolve().parents[2] / "docs" / "gait.md").read_text()
    assert row in page, row


BOLT = """[robot]
name = "bolt"
source = "example-robot-data"
urdf = "bolt_description/robots/bolt.urdf"
srdf = "bolt_description/srdf/bolt.srdf"
stand = "standing"
"""
"""ODRI's Bolt, a point-foot biped of example-robot-data never registered here, described as a
newcomer would: its links are not quite mirror images, so its walk on one foot at a time needs
a small mean moment about the vertical."""


def test_a_gait_always_on_one_foot_names_the_vertical_moment_no_turn_cancels(tmp_path):
    """Bolt at duty factor 0.5 stands on one point foot at every sample: the sway levels the
    horizontal moment, but the vertical one keeps its cycle mean (3e-6 N·m), which a periodic
    turn cannot cancel; the error names that mean and a duty factor with two-foot phases, not a
    slow convergence to be cured by a slower gait."""
    path = tmp_path / "bolt.toml"
    path.write_text(BOLT)
    scenario = Scenario.from_tables(str(path), {"gait": {"samples": 100}})
    assert scenario.gait.duty_factor == 0.5
    with pytest.raises(InfeasibleForcesError, match=r"every sample stands on one point foot "
                       r"\(duty_factor 0\.5 with 2 groups\)") as err:
        scenario.motion()
    message = str(err.value)
    mean = float(re.search(r"a mean of ([-+.e\d]+) N·m", message).group(1))
    assert 1e-7 < abs(mean) < 1e-4
    assert "raise duty_factor above 0.5" in message
