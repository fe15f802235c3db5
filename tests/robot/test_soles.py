"""Feet with soles: the declared rectangle, and the stand that lays each sole flat."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from hexaleg.errors import InvalidParameterError, RobotModelError
from hexaleg.robot.description import read_description
from hexaleg.robot.soles import Sole, sole_of

DATA = Path(__file__).parents[1] / "data"


def test_corners_are_the_rectangle_about_the_foot_frame():
    c = Sole(0.18, 0.09).corners()
    np.testing.assert_array_equal(c, [[0.09, 0.045, 0], [0.09, -0.045, 0], [-0.09, 0.045, 0],
                                      [-0.09, -0.045, 0]])
    assert sole_of("r", [0.18, 0.09]) == Sole(0.18, 0.09)


@pytest.mark.parametrize("bad", [[0.1], [0.1, 0.0], [0.1, -0.05], [float("nan"), 0.1], "ab",
                                 None, [0.1, "x"]])
def test_a_sole_that_is_not_two_positive_lengths_is_refused_by_name(bad):
    with pytest.raises(InvalidParameterError, match="r: sole"):
        sole_of("r", bad)


def test_the_biped_on_soles_stands_with_both_soles_flat_at_the_analytic_angles():
    """biped6's stand (body_height 0.5 m): each sole flat (the foot frame's axes the base's)
    under its hip. Thigh and shank are both 0.22 m, the hip pitch axis 0.09 m below the base and
    the ankle 0.06 m above the sole, so hip pitch = ankle pitch = −acos(0.35 / 0.44) and the
    knee twice that, the yaw and the rolls zero."""
    robot = read_description(DATA / "biped6.toml").load()
    assert set(robot.soles) == {"L1", "R1"} and robot.soles["L1"] == Sole(0.18, 0.09)
    q = robot.pose("stand")
    data = robot.model.createData()
    pin.framesForwardKinematics(robot.model, data, q)
    half = np.arccos(0.35 / 0.44)
    for leg, y in zip(robot.legs, (0.08, -0.08), strict=True):
        frame = data.oMf[leg.foot_frame_id]
        np.testing.assert_allclose(frame.rotation, np.eye(3), atol=1e-12)
        np.testing.assert_allclose(frame.translation, [0, y, -0.5], atol=1e-9)
        np.testing.assert_allclose(q[leg.q_index], [0, 0, -half, 2 * half, -half, 0],
                                   atol=1e-10)
    assert "→ L_sole (a 180 × 90 mm sole, flat in the stand)" in robot.summary()


def test_a_leg_that_cannot_turn_its_foot_is_refused_a_sole(tmp_path):
    """The point-foot biped's hip roll, hip pitch and knee cannot lay a foot flat."""
    text = (DATA / "biped.toml").read_text().replace(
        'urdf = "biped.urdf"', f'urdf = "{DATA / "biped.urdf"}"\nsole = [0.06, 0.03]')
    (tmp_path / "b.toml").write_text(text)
    with pytest.raises(RobotModelError, match=r"cannot lay its sole flat.*six joints"):
        read_description(tmp_path / "b.toml").load()
