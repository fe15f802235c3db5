"""A standing pose from foot positions and a body height."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.robot.stand import stand_from_feet


def test_feet_land_where_asked(spider):
    q = stand_from_feet(spider, 0.07, {"LF": [-0.17, 0.12]})
    feet = spider.foot_positions(q)
    np.testing.assert_allclose(feet[:, 2], -0.07, atol=1e-9)
    np.testing.assert_allclose(feet[0, :2], [-0.17, 0.12], atol=1e-9)
    zero = spider.foot_positions(np.r_[q[:7], np.zeros(spider.nj)])
    np.testing.assert_allclose(feet[1:, :2], zero[1:, :2], atol=1e-9)  # the others keep x, y
    model = spider.model
    assert np.all(q[7:] >= model.lowerPositionLimit[7:]) and np.all(
        q[7:] <= model.upperPositionLimit[7:])


def test_builtin_stand_is_recovered(robot):
    """The built-in stand's feet and height give back a pose with the same feet."""
    q0 = robot.pose("stand")
    feet = robot.foot_positions(q0)
    q = stand_from_feet(robot, float(-feet[0, 2]), {leg: feet[k, :2] for k, leg in
                                                    enumerate(robot.leg_names)})
    np.testing.assert_allclose(robot.foot_positions(q), feet, atol=1e-9)


def test_unreachable_and_bad_inputs_are_named(spider):
    with pytest.raises(InvalidParameterError, match=r"stand foot of leg LF.*lower body_height"):
        stand_from_feet(spider, 0.5)
    with pytest.raises(InvalidParameterError, match="body_height"):
        stand_from_feet(spider, -0.1)
    with pytest.raises(InvalidParameterError, match=r"stand.feet.LF"):
        stand_from_feet(spider, 0.08, {"LF": [0.1]})
    with pytest.raises(UnknownNameError, match="valid legs are"):
        stand_from_feet(spider, 0.08, {"XX": [0.1, 0.1]})
