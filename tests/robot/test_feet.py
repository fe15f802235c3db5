"""Feet as a point on a link, or found at the tip of a leg's last link."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from hexaleg.errors import RobotModelError
from hexaleg.robot.feet import LegSpec, farthest_points
from hexaleg.robot.model import HEXALEG_LEGS, load_robot


def test_found_feet_are_the_shank_tips(spider):
    """The test hexapod's shanks are 0.10 m cylinders hanging from the knee: the foot is the
    bottom of the axis, not a point on the rim."""
    for leg in spider.legs:
        frame = spider.model.frames[leg.foot_frame_id]
        assert frame.name == f"{leg.name}_foot" and frame.parentJoint == leg.joint_ids[-1]
        np.testing.assert_allclose(frame.placement.translation, [0.0, 0.0, -0.10], atol=1e-12)
    assert any("feet found at the tip" in n for n in spider.notes)


def test_point_on_a_link_is_the_given_frame(robot):
    """The built-in robot's feet re-given as points on the tibia links land where its foot
    frames are."""
    model = robot.model
    legs = []
    for spec in HEXALEG_LEGS:
        foot = model.frames[model.getFrameId(spec.foot)]
        body = model.frames[foot.parentFrame]
        while body.type != pin.FrameType.BODY:  # up through the fixed joint's frame
            body = model.frames[body.parentFrame]
        point = (body.placement.inverse() * foot.placement).translation
        legs.append(LegSpec(spec.name, spec.joints, body.name, tuple(point)))
    again = load_robot(legs=legs)
    q = robot.pose("stand")
    np.testing.assert_allclose(again.foot_positions(q), robot.foot_positions(q), atol=1e-12)


def test_bad_feet_are_named(robot):
    with pytest.raises(RobotModelError, match="foot link 'nope' not in the URDF; links found"):
        load_robot(legs=[LegSpec("LF", HEXALEG_LEGS[0].joints, "nope", (0.0, 0.0, 0.0)),
                         *HEXALEG_LEGS[1:]])
    with pytest.raises(RobotModelError, match=r"foot point \(1, 2\)"):
        LegSpec("LF", ("a",), "link", (1, 2))  # type: ignore[arg-type]


def test_tip_rules_of_each_shape():
    box = pin.GeometryObject("b", 0, pin.SE3(np.eye(3), np.array([0.0, 0.0, -0.1])),
                             pin.hppfcl.Box(0.02, 0.04, 0.2))
    tips = np.array(farthest_points(box))
    assert tips.shape == (6, 3) and np.isclose(tips[:, 2].min(), -0.2)
    sphere = pin.GeometryObject("s", 0, pin.SE3(np.eye(3), np.array([0.0, 0.0, -0.1])),
                                pin.hppfcl.Sphere(0.01))
    np.testing.assert_allclose(farthest_points(sphere)[0], [0.0, 0.0, -0.11])
    capsule = pin.GeometryObject("c", 0, pin.SE3(np.eye(3), np.zeros(3)),
                                 pin.hppfcl.Capsule(0.01, 0.2))
    np.testing.assert_allclose(sorted(p[2] for p in farthest_points(capsule)), [-0.11, 0.11])


def test_a_capsule_end_is_the_ball_of_its_tip_side():
    from hexaleg.robot.feet import sphere_of_tip

    capsule = pin.GeometryObject("c", 0, pin.SE3(np.eye(3), np.array([0.0, 0.0, -0.1])),
                                 pin.hppfcl.Capsule(0.01, 0.2))
    low, high = sorted(farthest_points(capsule), key=lambda p: p[2])
    for tip, centre in ((low, -0.2), (high, 0.0)):
        sphere = sphere_of_tip(capsule, tip, 3)
        assert sphere is not None and sphere.radius == 0.01 and sphere.joint == 3
        np.testing.assert_allclose(sphere.centre, [0.0, 0.0, centre], atol=1e-15)
    box = pin.GeometryObject("b", 0, pin.SE3.Identity(), pin.hppfcl.Box(0.1, 0.1, 0.1))
    assert sphere_of_tip(box, np.zeros(3), 3) is None
