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


def test_talos_lays_its_real_soles_flat_where_its_srdf_stands_them():
    """Data we did not make: Talos' URDF (example-robot-data) and its SRDF's half_sitting, whose
    sole frames are tilted by 1.7 mrad; the flat stand keeps both feet where the SRDF put them
    (to 1e-12 m), turns the soles flat (to 1e-12) and moves no joint by more than 2 mrad, within
    the URDF limits."""
    robot = read_description(DATA / "talos.toml").load()
    assert robot.soles == {"L1": Sole(0.19, 0.11), "R1": Sole(0.19, 0.11)}
    flat, srdf = robot.pose("stand"), robot.pose("half_sitting")
    flat_data, srdf_data = robot.model.createData(), robot.model.createData()
    pin.framesForwardKinematics(robot.model, flat_data, flat)
    pin.framesForwardKinematics(robot.model, srdf_data, srdf)
    for leg in robot.legs:
        placed, given = flat_data.oMf[leg.foot_frame_id], srdf_data.oMf[leg.foot_frame_id]
        assert robot.model.frames[leg.foot_frame_id].name in ("left_sole_link", "right_sole_link")
        np.testing.assert_allclose(placed.rotation, np.eye(3), atol=1e-12)
        np.testing.assert_allclose(placed.translation, given.translation, atol=1e-12)
        assert np.linalg.norm(pin.log3(given.rotation)) == pytest.approx(1.708e-3, abs=1e-6)
    assert 1e-3 < np.abs(flat - srdf).max() < 2e-3
    assert np.all(flat[7:] >= robot.model.lowerPositionLimit[7:])
    assert np.all(flat[7:] <= robot.model.upperPositionLimit[7:])


def test_talos_sole_lies_inside_its_foots_collision_mesh_underside():
    """The declared 19 x 11 cm sole is inside the underside of Talos' foot collision mesh
    (the vertices within 3 mm of its lowest point, in the ankle link's frame, where the sole
    frame sits 0.107 m down): that underside spans x −0.110…0.099 m, y ±0.062 m, and every
    corner of the sole lies inside its convex hull."""
    from scipy.spatial import Delaunay

    from hexaleg.robot.sources import example_robot_data_dir

    raw = (example_robot_data_dir() / "talos_data" / "meshes" / "v2"
           / "ankle_X_collision.stl").read_bytes()  # binary STL: 80-byte header, count, facets
    count = int(np.frombuffer(raw, "<u4", 1, 80)[0])
    facets = np.frombuffer(raw, np.dtype([("normal", "<f4", 3), ("v", "<f4", (3, 3)),
                                          ("attr", "<u2")]), count, 84)
    v = facets["v"].reshape(-1, 3).astype(float)
    under = v[v[:, 2] < v[:, 2].min() + 0.003]
    assert v[:, 2].min() == pytest.approx(-0.107, abs=1e-3)
    np.testing.assert_allclose(under[:, :2].min(axis=0), [-0.110, -0.062], atol=1e-3)
    np.testing.assert_allclose(under[:, :2].max(axis=0), [0.099, 0.062], atol=1e-3)
    corners = Sole(0.19, 0.11).corners()[:, :2]
    assert (Delaunay(under[:, :2]).find_simplex(corners) >= 0).all()
    assert not (Delaunay(under[:, :2]).find_simplex(Sole(0.21, 0.13).corners()[:, :2]) >= 0).all()
