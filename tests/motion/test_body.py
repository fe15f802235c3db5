"""Tests of hexaleg.motion.body: the constant-twist body (straight and on an arc), the sway on
top, and foot targets in the moving base frame with exact derivatives."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.balance import Sway
from hexaleg.motion.body import (
    base_state,
    body_motion,
    body_pose,
    heading,
    in_base_frame,
    reference_pose,
    rotz,
)


def test_body_pose_is_a_straight_line_or_an_arc():
    t = np.linspace(0.0, 1.0, 11)
    base, yaw = body_pose(t, 0.1, 0.0, 0.09)
    assert np.allclose(base, np.column_stack([0.1 * t, 0 * t, 0.09 + 0 * t])) and not yaw.any()
    base, yaw = body_pose(t, 0.1, 0.5, 0.09)
    radius = 0.1 / 0.5
    assert np.allclose(np.hypot(base[:, 0], base[:, 1] - radius), radius)  # circle about (0, R)
    assert np.allclose(yaw, 0.5 * t)
    rot = rotz(yaw)
    assert np.allclose(rot @ np.swapaxes(rot, 1, 2), np.eye(3)) and np.allclose(
        rot[3], pin.utils.rpyToMatrix(0.0, 0.0, yaw[3]))


@pytest.mark.parametrize("yaw_rate", [0.0, 0.5])
def test_body_pose_along_a_heading_is_the_forward_pose_turned(yaw_rate):
    t = np.linspace(0.0, 1.0, 11)
    angle = 2.0
    h = np.array([np.cos(angle), np.sin(angle), 0.0])
    forward, yaw = body_pose(t, 0.1, yaw_rate, 0.09)
    turned, yaw2 = body_pose(t, 0.1, yaw_rate, 0.09, h)
    assert np.allclose(turned, forward @ rotz(angle).T, atol=1e-15) and np.array_equal(yaw, yaw2)
    assert np.array_equal(body_pose(t, 0.1, yaw_rate, 0.09, np.array([1.0, 0.0, 0.0]))[0],
                          forward)
    body = body_motion(t, 0.1, yaw_rate, 0.09, None, h)
    assert np.allclose(body.v, 0.1 * h) and np.allclose(body.base, turned)


def test_heading_is_a_horizontal_unit_vector(robot):
    assert np.array_equal(heading(robot), [1.0, 0.0, 0.0])
    odd = dataclasses.replace(robot)
    odd.heading = np.array([0.0, -2.0, 0.0])  # set after loading: not normalised by Robot
    assert np.array_equal(heading(odd), [0.0, -1.0, 0.0])
    for bad in ([0.0, 0.0, 1.0], [0.0, 0.0, 0.0], [np.nan, 1.0, 0.0], [1.0, 0.0]):
        odd.heading = np.array(bad)
        with pytest.raises(InvalidParameterError, match="heading"):
            heading(odd)
    assert isinstance(odd, hexaleg.Robot)


def test_base_state_holds_the_legs_at_the_reference_pose(robot):
    t = np.linspace(0.0, 1.0, 5)
    body = body_motion(t, 0.06, 0.3, 0.09, None)
    q, v, a = base_state(robot, body)
    assert np.array_equal(q[:, 7:], np.tile(reference_pose(robot)[7:], (5, 1)))
    assert np.allclose(q[:, :3], body.base)
    assert np.allclose(2 * np.arctan2(q[:, 5], q[:, 6]), 0.3 * t)
    assert np.allclose(v[:, :6], [0.06, 0, 0, 0, 0, 0.3]) and not a.any() and not v[:, 6:].any()


@pytest.mark.parametrize("yaw_rate", [0.0, 0.4])
def test_foot_targets_in_the_base_frame_have_exact_derivatives(yaw_rate):
    """A world curve seen from the swaying, turning body: ṗ_b and p̈_b equal central
    differences of p_b."""
    rng = np.random.default_rng(3)
    sway = Sway.from_samples(np.array([0.0, 1.0, 0.0]), 1.0, rng.normal(size=16) * 1e-2)

    def seen(t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        p = np.column_stack([0.2 * np.sin(t), 0.1 * np.cos(2 * t), 0.03 * t**2])
        pd = np.column_stack([0.2 * np.cos(t), -0.2 * np.sin(2 * t), 0.06 * t])
        pdd = np.column_stack([-0.2 * np.sin(t), -0.4 * np.cos(2 * t), 0.06 + 0 * t])
        return in_base_frame(body_motion(t, 0.08, yaw_rate, 0.09, sway), p, pd, pdd)

    t, h = np.linspace(0.0, 1.0, 9), 1e-5
    _, d1, d2 = seen(t)
    assert np.allclose((seen(t + h)[0] - seen(t - h)[0]) / (2 * h), d1, atol=1e-8)
    assert np.allclose((seen(t + h)[1] - seen(t - h)[1]) / (2 * h), d2, atol=1e-6)


# --- GaitParams.heading: the walking direction in the base frame (crab walking) ---


def test_walk_direction_turns_the_robots_heading():
    from hexaleg.motion.body import walk_direction

    robot = hexaleg.load()
    assert walk_direction(robot, hexaleg.GaitParams()) is not None
    assert np.array_equal(walk_direction(robot, hexaleg.GaitParams()), [1.0, 0.0, 0.0])
    assert np.allclose(walk_direction(robot, hexaleg.GaitParams(heading=np.pi / 2)),
                       [0.0, 1.0, 0.0], atol=1e-15)
    sideways = dataclasses.replace(robot, heading=np.array([0.0, 1.0, 0.0]))
    assert np.allclose(walk_direction(sideways, hexaleg.GaitParams(heading=np.pi / 2)),
                       [-1.0, 0.0, 0.0], atol=1e-15)


@pytest.mark.parametrize("theta", [0.4, np.pi / 2, 2.5])
def test_energy_at_heading_theta_equals_that_at_minus_theta(theta):
    """The hexapod is left–right symmetric: walking at −θ is the mirror image of walking at θ
    (the tripods swapped, half a cycle later), so every energy is the same to rounding — and
    the crab walk really goes where it is sent, its stance feet at rest."""
    robot = hexaleg.load()
    energies = []
    for sign in (1.0, -1.0):
        motion = hexaleg.gait(robot, hexaleg.GaitParams(heading=sign * theta, samples=100))
        step = motion.q[1, :3] - motion.q[0, :3]
        assert np.allclose(step / np.linalg.norm(step),
                           [np.cos(theta), sign * np.sin(theta), 0.0], atol=1e-12)
        analysis = hexaleg.prepare(robot, motion).evaluate()
        energies.append([analysis.metrics["total"][k]
                         for k in ("electrical", "joule", "positive_work", "absolute_work")])
    left, right = np.array(energies)
    assert np.all(np.abs(left - right) <= 1e-9 * np.abs(left))
    assert left[0] > 1.0


def test_a_robot_whose_urdf_faces_y_walks_forward_with_heading_set(robot, rotated):
    """The body turned by 90° inside its base frame, its heading left at +x (a URDF facing +y
    whose description does not say so): heading = π/2 walks it forward, the same joint motion
    as the original's forward gait, along +y."""
    facing_y = dataclasses.replace(rotated(robot, np.pi / 2), heading=np.array([1.0, 0.0, 0.0]))
    gait = hexaleg.GaitParams(samples=100)
    forward = hexaleg.gait(robot, gait)
    turned = hexaleg.gait(facing_y, dataclasses.replace(gait, heading=np.pi / 2))
    assert np.abs(turned.q[:, 7:] - forward.q[:, 7:]).max() < 1e-9
    assert np.allclose(turned.q[:, :2], forward.q[:, [1, 0]] * [-1.0, 1.0], atol=1e-12)
    assert turned.info["direction"] == pytest.approx([0.0, 1.0, 0.0], abs=1e-15)
    assert np.abs(hexaleg.gait(facing_y, gait).q[:, 7:] - forward.q[:, 7:]).max() > 0.05



WHEELED = Path(__file__).resolve().parents[1] / "data" / "wheeled.toml"
"""The wheeled test quadruped with a two-joint arm (arm_yaw, arm_pitch) on its back."""


def wheeled_moving(tmp_path: Path, moves: str) -> hexaleg.Robot:
    """The wheeled test robot loaded with ``moves = {…}`` in its description."""
    from hexaleg.robot.description import read_description

    path = tmp_path / "w.toml"
    path.write_text(WHEELED.read_text().replace(
        'urdf = "wheeled.urdf"', f'urdf = "{WHEELED.with_suffix(".urdf")}"\nmoves = {moves}'))
    return read_description(path).load()


def test_a_joint_on_no_leg_swings_with_exact_rates(tmp_path):
    """``moves``: q = q₀ + A sin(ωt + φ), its rate and acceleration the exact derivatives
    (central differences), one swing a period; the joints it does not name stay as given."""
    from hexaleg.motion.body import swing_other_joints

    robot = wheeled_moving(tmp_path, "{arm_pitch = {amplitude = 0.3, phase = 0.5}}")
    model = robot.model
    n, period = 2001, 0.8
    t = np.linspace(0.0, period, n)
    q = np.tile(robot.pose("stand"), (n, 1))
    v, a = np.zeros((n, model.nv)), np.zeros((n, model.nv))
    swing_other_joints(robot, period, t, q, v, a)
    joint = model.joints[model.getJointId("arm_pitch")]
    angle = q[:, joint.idx_q]
    assert angle[0] == pytest.approx(robot.pose("stand")[joint.idx_q] + 0.3 * np.sin(0.5))
    assert angle[-1] == pytest.approx(angle[0], abs=1e-12)  # one swing a period
    h = t[1] - t[0]
    np.testing.assert_allclose(np.gradient(angle, h)[1:-1], v[1:-1, joint.idx_v], atol=1e-5)
    np.testing.assert_allclose(np.gradient(v[:, joint.idx_v], h)[1:-1], a[1:-1, joint.idx_v],
                               atol=1e-4)
    others = [i for i in range(6, model.nv) if i != joint.idx_v]
    assert not v[:, others].any() and not a[:, others].any()
    still = np.delete(q, joint.idx_q, axis=1)
    assert (still == np.delete(robot.pose("stand"), joint.idx_q)).all()
