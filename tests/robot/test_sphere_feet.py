"""Tests of hexaleg.robot.sphere_feet: round feet placed at their sphere's lowest point."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from hexaleg.errors import RobotModelError
from hexaleg.robot.sphere_feet import (
    SETTLE_ROUNDS,
    place_sphere_feet,
    settle_sphere_feet,
    sphere_note,
)

SHIN = ('<collision><origin xyz="0 0 -0.05"/><geometry><cylinder radius="0.006" length="0.10"/>'
        '</geometry></collision>')
BALL = ('<collision><origin xyz="0 0 -0.1"/><geometry><sphere radius="0.015"/></geometry>'
        '</collision>')


def round_footed_spider(tmp_path, stand="stand = {body_height = 0.08}"):
    """The test hexapod with a 15 mm ball at the end of every shank (the shank's tip at its
    centre), loaded from its TOML with ``stand``."""
    from conftest import SPIDER

    from hexaleg.robot.registry import load

    text = (SPIDER.parent / "spider.urdf").read_text()
    assert text.count(SHIN) == 6
    (tmp_path / "spider.urdf").write_text(text.replace(SHIN, SHIN + BALL))
    toml = SPIDER.read_text().replace("stand = {body_height = 0.08}", stand)
    (tmp_path / "spider.toml").write_text(toml)
    return load(str(tmp_path / "spider.toml"))


@pytest.mark.parametrize("stand", ["stand = {body_height = 0.08, feet = {LF = [-0.13, 0.1], "
                                   "RH = [0.14, -0.06]}}",
                                   "stand = {a_j2 = 0.5, a_j3 = 0.4, d_j2 = -0.3, d_j3 = 0.9}"])
def test_a_ball_foot_touches_at_its_lowest_point_in_the_stand(tmp_path, stand):
    """On inclined shanks the foot is the ball's lowest point c − r ẑ, not its tip along the
    shank: the foot frame is 15 mm straight below the ball's centre, the lowest point of the
    robot's collision geometry (hexaleg.robot.geometry, exact for spheres) is that foot, and on
    a solved stand the feet are at −body_height."""
    robot = round_footed_spider(tmp_path, stand)
    assert set(robot.foot_spheres) == set(robot.leg_names)
    q = robot.pose("stand")
    feet = robot.foot_positions(q)
    tilts = []
    for k, leg in enumerate(robot.legs):
        sphere = robot.foot_spheres[leg.name]
        assert sphere.radius == pytest.approx(0.015) and sphere.joint == leg.joint_ids[-1]
        joint = robot.data.oMi[sphere.joint]
        centre = joint.act(sphere.centre)
        np.testing.assert_allclose(feet[k], centre - [0.0, 0.0, 0.015], atol=1e-12)
        shank = joint.rotation @ np.array([0.0, 0.0, -1.0])
        tilts.append(np.arccos(-shank[2]))
        tip = centre + 0.015 * shank  # the far end the found foot used to be
        assert np.linalg.norm(tip - feet[k]) == pytest.approx(0.03 * np.sin(tilts[-1] / 2))
    assert max(tilts) > 0.3  # rad: inclined shanks (the tip is ≥ 4 mm off the contact)
    lifted = q.copy()
    lifted[2] = -feet[:, 2].min()
    z, _ = robot.lowest_point(lifted, "collision")
    assert z == pytest.approx(0.0, abs=1e-12)
    if "body_height" in stand:
        np.testing.assert_allclose(feet[:, 2], -0.08, atol=1e-9)
    assert any("sphere of radius 0.015 m" in n for n in robot.notes)
    assert any(n.startswith("round feet touch the ground at their sphere's lowest point")
               for n in robot.notes)


def _lowest(robot, leg, q):
    """The lowest point of ``leg``'s ball at ``q`` (base at the origin), in the joint's frame."""
    sphere = robot.foot_spheres[leg.name]
    q = np.array(q, dtype=float)
    q[:7] = pin.neutral(robot.model)[:7]
    pin.forwardKinematics(robot.model, robot.data, q)
    rotation = robot.data.oMi[sphere.joint].rotation
    return sphere.centre + sphere.radius * rotation.T @ np.array([0.0, 0.0, -1.0])


def test_placing_moves_each_frame_to_its_ball_s_lowest_point_once(tmp_path):
    robot = round_footed_spider(tmp_path)
    q = robot.pose("stand").copy()
    q[robot.column("a_j2") + 7] += 0.4  # tilt one shank: its lowest point moves on the ball
    assert place_sphere_feet(robot, q) > 1e-3
    for leg in robot.legs:
        frame = robot.model.frames[leg.foot_frame_id]
        np.testing.assert_allclose(frame.placement.translation, _lowest(robot, leg, q),
                                   atol=1e-12)
    assert place_sphere_feet(robot, q) == pytest.approx(0.0, abs=1e-15)  # already there


def test_a_stand_of_joint_angles_is_placed_once_and_noted(tmp_path):
    robot = round_footed_spider(tmp_path)
    stand = robot.pose("stand")
    out, note = settle_sphere_feet(robot, stand)
    np.testing.assert_array_equal(out, stand)
    assert note.startswith("round feet touch the ground at their sphere's lowest point")
    assert note == sphere_note(robot, robot.foot_spheres)
    assert all(f"{leg} [" in note for leg in robot.leg_names)
    assert sphere_note(robot, {}).endswith(": ")  # no round foot, no leg named


def test_a_stand_that_never_settles_is_refused(tmp_path):
    robot = round_footed_spider(tmp_path)
    stand = robot.pose("stand")
    calls = []

    def solve():  # a stand that tilts the shanks back and forth: the frames never settle
        calls.append(1)
        q = stand.copy()
        q[robot.column("a_j2") + 7] += 0.3 * (-1) ** len(calls)
        return q

    with pytest.raises(RobotModelError, match=f"did not settle in {SETTLE_ROUNDS} stand solves"):
        settle_sphere_feet(robot, solve(), solve)
    assert len(calls) == SETTLE_ROUNDS + 1  # the first stand, then one solve a round
