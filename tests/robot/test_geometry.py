"""Tests of hexaleg.robot.geometry: self-collisions, extents and lowest points of the shapes,
checked against the stated sphere radius, closed forms and dense sampling of the surfaces."""

import math

import numpy as np
import pinocchio as pin
import pytest

from hexaleg.errors import UnknownNameError
from hexaleg.robot.builder import load_params


def test_no_self_collision_in_stand_and_sphere(robot):
    for pose in ("stand", "sphere", "zero"):
        assert robot.self_collisions(robot.pose(pose)) == [], pose


def test_collision_check_detects_overlapping_legs(robot):
    """Legs straight (zero pose), LF's coxa turned +100°: LF's leg crosses LM's at (0, 0.122)."""
    q = robot.pose("zero")
    q[robot.leg("LF").q_index[0]] = math.radians(100)
    hits = robot.self_collisions(q)
    assert any("LF" in a and "LM" in b for a, b in hits), hits


def test_sphere_pose_fits_in_the_stated_ball(robot):
    radius = load_params()["poses"]["sphere_radius"]
    q = robot.pose("sphere")
    assert robot.max_extent(q, "visual") <= radius + 1e-9
    assert robot.max_extent(q, "collision") <= radius + 1e-9
    # ... and the ball is tight: legs stretched out reach far beyond it.
    assert robot.max_extent(robot.pose("stand")) > radius + 0.03


def test_max_extent_is_exact_for_the_straight_legs(robot):
    """zero pose: the farthest point is the foot ball's tip, 0.08 + 0.03 + 0.084 + 0.12 m out;
    the tibia rod ends at the ball's centre, so its rim (hypot(0.304, 0.01)) stays inside."""
    assert robot.max_extent(robot.pose("zero"), "collision") == pytest.approx(
        0.08 + 0.03 + 0.084 + 0.12, rel=1e-12)
    assert math.hypot(0.08 + 0.03 + 0.084 + 0.11, 0.01) < 0.314


def test_lowest_point_is_exact_for_every_primitive(robot):
    """Against dense sampling of each shape's surface (rims of cylinders at 0.01° steps, box
    corners, sphere bottoms) at random configurations: never above, and within 1e-9 m."""
    rng = np.random.default_rng(3)
    angle = np.linspace(0.0, 2 * np.pi, 36001)
    circle = np.stack([np.cos(angle), np.sin(angle), np.zeros_like(angle)], axis=1)
    gdata = pin.GeometryData(robot.visual_model)
    for _ in range(5):
        q = pin.randomConfiguration(robot.model, -np.ones(25), np.ones(25))
        q[3:7] = pin.Quaternion(pin.exp3(rng.normal(size=3))).coeffs()
        pin.updateGeometryPlacements(robot.model, robot.model.createData(), robot.visual_model,
                                     gdata, q)
        lowest = np.inf
        for k, obj in enumerate(robot.visual_model.geometryObjects):
            m, shape, kind = gdata.oMg[k], obj.geometry, type(obj.geometry).__name__
            if kind == "Sphere":
                z = m.translation[2] - shape.radius
            elif kind == "Box":
                corners = np.array(np.meshgrid(*[[-1, 1]] * 3)).reshape(3, -1).T * shape.halfSide
                z = (corners @ m.rotation.T + m.translation)[:, 2].min()
            else:
                assert kind == "Cylinder"
                rims = [circle * shape.radius + [0, 0, s * shape.halfLength] for s in (-1, 1)]
                z = min((r @ m.rotation.T + m.translation)[:, 2].min() for r in rims)
            lowest = min(lowest, z)
        z_exact, _ = robot.lowest_point(q)
        assert z_exact <= lowest + 1e-12 and lowest - z_exact <= 1e-9


def test_lowest_point_in_the_poses(robot):
    assert robot.lowest_point(robot.pose("stand")) == pytest.approx(
        (robot.foot_positions(robot.pose("stand"))[:, 2].min(), "LF_foot_0"), abs=1e-15)
    assert robot.lowest_point(robot.pose("sphere")) == (pytest.approx(-0.0835, abs=1e-15),
                                                         "body_1")
    with pytest.raises(UnknownNameError, match=r"'mesh'.*collision"):
        robot.lowest_point(robot.pose("stand"), "mesh")
