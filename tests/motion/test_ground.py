"""Tests of hexaleg.motion.ground and gaits on slopes: the plane's geometry, footholds on it and
swing clearance above it, the work of climbing (m g s sin α per cycle, to 1e-6), and friction
cones about the plane's normal (μ below tan α infeasible, above it feasible; an independent
world-frame cvxpy program with the cones written about n agrees)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.dynamics.contact import friction_usage
from hexaleg.errors import InfeasibleForcesError, InvalidParameterError
from hexaleg.motion.ground import ground_plane
from hexaleg.motion.params import GaitParams

ALPHA = math.radians(10.0)
SAMPLES = 100


def test_the_plane_rises_at_the_slope_along_and_the_cross_slope_across():
    alpha, beta = 0.3, -0.2
    heading = np.array([math.cos(0.7), math.sin(0.7), 0.0])
    g = ground_plane(alpha, beta, "plane", heading)
    assert g is not None and ground_plane(0.0, 0.0, "plane", heading) is None
    r = g.rotation
    assert np.allclose(r.T @ r, np.eye(3), atol=1e-15) and np.isclose(np.linalg.det(r), 1.0)
    left = np.cross([0.0, 0.0, 1.0], heading)
    n = g.normal
    expected = -math.tan(alpha) * heading - math.tan(beta) * left + [0.0, 0.0, 1.0]
    assert np.allclose(n, expected / np.linalg.norm(expected), atol=1e-15)
    d = r @ heading  # where the walking direction goes: up the slope at exactly α
    assert math.isclose(math.asin(d[2]), alpha, abs_tol=1e-15)
    assert np.allclose(d[:2] / np.linalg.norm(d[:2]), heading[:2], atol=1e-15)
    across = ground_plane(0.0, beta, "plane", heading)
    assert across is not None
    assert math.isclose(math.asin((across.rotation @ left)[2]), beta, abs_tol=1e-15)
    assert math.isclose(math.tan(g.steepness) ** 2, math.tan(alpha) ** 2 + math.tan(beta) ** 2)
    yaw = np.array([0.0, 0.4, -2.0])
    for attitude in ("plane", "level"):
        h = ground_plane(alpha, beta, attitude, heading)
        assert h is not None
        for q, psi in zip(h.quaternions(yaw), yaw, strict=True):
            expected_rot = h.rotation @ pin.rpy.rpyToMatrix(0, 0, psi) @ h.tilt
            assert np.allclose(pin.Quaternion(q).toRotationMatrix(), expected_rot, atol=1e-15)
    level = ground_plane(alpha, beta, "level", heading)
    assert level is not None and np.allclose(level.rotation @ level.tilt, np.eye(3), atol=1e-15)


@pytest.fixture(scope="module")
def slopes(robot) -> dict[tuple[float, str], hexaleg.Motion]:
    """The default tripod up and down 10°, the body parallel to the ground or level."""
    return {(sign, attitude): hexaleg.gait(robot, GaitParams(
        slope=sign * ALPHA, attitude=attitude, samples=SAMPLES))
        for sign in (1.0, -1.0) for attitude in ("plane", "level")}


@pytest.mark.parametrize("attitude", ["plane", "level"])
def test_feet_stand_on_the_plane_at_rest_and_swing_above_it(robot, slopes, attitude,
                                                            frame_kinematics):
    motion = slopes[(1.0, attitude)]
    n = motion.normal
    assert motion.info["ground"]["normal"] == pytest.approx(n.tolist())
    pos, vel, acc = frame_kinematics(robot, motion)
    assert np.abs(pos - motion.feet).max() <= 1e-9
    height = motion.feet @ n  # distance from the plane through the origin, along its normal
    assert np.abs(height[motion.stance]).max() <= 1e-12
    assert height.max() == pytest.approx(0.03, abs=1e-9)  # the step height above the plane
    assert np.all(height[~motion.stance] >= -1e-12)
    assert np.abs(vel[motion.stance]).max() <= 1e-9 and np.abs(acc[motion.stance]).max() <= 1e-9
    rot = pin.Quaternion(motion.q[0, 3:7]).toRotationMatrix()
    h0 = motion.info["body_height"]
    if attitude == "plane":  # body parallel to the ground, body_height along n
        assert np.allclose(rot[:, 2], n, atol=1e-15)
        assert motion.q[:, :3] @ n == pytest.approx(np.full(SAMPLES, h0), abs=1e-12)
    else:  # level body, body_height measured vertically
        assert np.allclose(rot, np.eye(3), atol=1e-15)
        assert motion.q[:, :3] @ n == pytest.approx(np.full(SAMPLES, h0 * n[2]), abs=1e-12)
    climb = motion.q[1, :3] - motion.q[0, :3]
    assert math.asin(climb[2] / np.linalg.norm(climb)) == pytest.approx(ALPHA, abs=1e-12)


@pytest.mark.parametrize("attitude", ["plane", "level"])
def test_climbing_costs_m_g_s_sin_alpha_per_cycle(robot, slopes, attitude):
    """The stance feet do no work and the motion repeats, so the motors' net work per cycle is
    the rise of potential energy: m g s sin α uphill, the opposite downhill (to 1e-6)."""
    g = float(np.linalg.norm(robot.model.gravity.linear))
    for sign in (1.0, -1.0):
        motion = slopes[(sign, attitude)]
        analysis = hexaleg.prepare(robot, motion).evaluate()
        expected = robot.mass * g * motion.distance * math.sin(sign * ALPHA)
        net = analysis.metrics["total"]["net_work"]
        assert net == pytest.approx(expected, rel=1e-6)


def test_a_cross_slope_does_not_climb(robot):
    motion = hexaleg.gait(robot, GaitParams(cross_slope=ALPHA, samples=SAMPLES))
    analysis = hexaleg.prepare(robot, motion).evaluate()
    assert abs(analysis.metrics["total"]["net_work"]) <= 1e-6 * analysis.metrics["total"][
        "absolute_work"]
    assert motion.q[1, 2] == pytest.approx(motion.q[0, 2], abs=1e-15)


def test_friction_cones_are_about_the_planes_normal(robot, slopes):
    motion = slopes[(1.0, "plane")]
    tan = math.tan(ALPHA)
    with pytest.raises(InfeasibleForcesError, match=r"inclined by γ = 10°.*tan γ = 0\.1763 > "
                       r"μ = 0\.158.*mu.* ≥ 0\.1763"):
        hexaleg.prepare(robot, motion, contact=hexaleg.ContactParams(mu=0.9 * tan))
    # The force program itself, past that check, finds no forces either ...
    grippy = hexaleg.prepare(robot, motion, contact=hexaleg.ContactParams(mu=1.0))
    slippery = dataclasses.replace(grippy, contact=hexaleg.ContactParams(mu=0.9 * tan))
    with pytest.raises(InfeasibleForcesError, match="no contact forces"):
        slippery.evaluate()
    # ... and above tan α it does, inside the cones about n (not about z: there they would
    # lean on less friction), Newton–Euler holding.
    mu = 1.3 * tan
    prepared = hexaleg.prepare(robot, motion, contact=hexaleg.ContactParams(mu=mu))
    analysis = prepared.evaluate()
    usage = friction_usage(analysis.forces, motion.stance, mu, motion.normal)
    assert usage.max() <= 1 + 1e-6 and usage.max() > 0.99
    assert friction_usage(analysis.forces, motion.stance, mu).max() < 0.9
    total = analysis.forces.sum(axis=1)
    rhs = np.empty_like(total)
    data = robot.model.createData()
    for k in range(SAMPLES):
        pin.centerOfMass(robot.model, data, motion.q[k], motion.v[k], motion.a[k])
        rhs[k] = robot.mass * (data.acom[0] - robot.model.gravity.linear)
    assert np.abs(total - rhs).max() <= 1e-8 * np.abs(rhs).max()
    _world_frame_program_agrees(prepared, analysis, mu, motion.normal)


def _world_frame_program_agrees(prepared, analysis, mu, n) -> None:
    """An independent formulation: world-frame forces, the base rows from the world Jacobians,
    cones written about n (‖f − (f·n) n‖ ≤ μ f·n), least Joule loss (cvxpy)."""
    cp = pytest.importorskip("cvxpy")
    robot, motion = prepared.robot, prepared.motion
    c = prepared.weights("joule")
    for k in range(0, SAMPLES, 17):
        legs = np.flatnonzero(motion.stance[k])
        jac = prepared.jacobians[k, legs]  # (n_st, 3, nv), world
        f = cp.Variable((len(legs), 3))
        base = sum(jac[i][:, :6].T @ f[i] for i in range(len(legs)))
        tau = prepared.rnea[k, 6:] - sum(jac[i][:, 6:].T @ f[i] for i in range(len(legs)))
        cones = [cp.norm(f[i] - (f[i] @ n) * n) <= mu * (f[i] @ n) for i in range(len(legs))]
        limits = [cp.abs(tau) <= prepared.system.tau_max]
        problem = cp.Problem(cp.Minimize(cp.sum(cp.multiply(c, tau**2))),
                             [base == prepared.rnea[k, :6], *cones, *limits])
        problem.solve(solver=cp.CLARABEL)
        assert problem.status == cp.OPTIMAL
        assert np.abs(f.value - analysis.forces[k, legs]).max() <= 1e-4 * robot.mass


def test_slope_errors_are_named(robot):
    for bad in (math.pi / 2, -2.0, math.nan):
        with pytest.raises(InvalidParameterError, match=r"invalid slope = .*\(−π/2, π/2\)"):
            GaitParams(slope=bad)
    with pytest.raises(InvalidParameterError, match=r"invalid cross_slope"):
        GaitParams(cross_slope=math.pi)
    with pytest.raises(InvalidParameterError, match=r"invalid attitude = 'upright'.*plane"):
        GaitParams(attitude="upright")
    with pytest.raises(InvalidParameterError, match=r"invalid attitude = 'level'.*yaw_rate"):
        GaitParams(attitude="level", slope=0.1, yaw_rate=0.2)
    with pytest.raises(InvalidParameterError, match=r"Motion.normal"):
        dataclasses.replace(hexaleg.gait(robot, GaitParams(samples=20)),
                            normal=np.array([0.0, 0.0, 2.0]))


def test_turning_on_a_slope_keeps_the_feet_on_it(robot, frame_kinematics):
    motion = hexaleg.gait(robot, GaitParams(slope=0.1, cross_slope=0.05, yaw_rate=0.4,
                                            samples=SAMPLES))
    _, vel, acc = frame_kinematics(robot, motion)
    assert np.abs((motion.feet @ motion.normal)[motion.stance]).max() <= 1e-12
    assert np.abs(vel[motion.stance]).max() <= 1e-9 and np.abs(acc[motion.stance]).max() <= 1e-9
    rot = np.array([pin.Quaternion(q[3:7]).toRotationMatrix() for q in motion.q])
    assert np.allclose(rot[:, :, 2], motion.normal, atol=1e-14)  # yawing about the normal
