"""Tests of hexaleg.robot.mirror: the joints that count their angle the other way round."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import RIGHT_PITCH, SPIDER, flipped_spider

from hexaleg.robot.mirror import mirror
from hexaleg.robot.registry import load


def test_the_geometric_sign_is_the_gaits_own(robot, walk):
    """Independent check from the motion: on the straight tripod gait a right leg's joint moves
    as its left twin half a period later, times the sign mirror() finds (to the gait's
    symmetry)."""
    m = mirror(robot)
    assert set(m.mirrored) == {"RF_coxa", "RM_coxa", "RH_coxa"}
    half = walk.n_samples // 2
    for leg in robot.legs:
        twin = m.twins[leg.name]
        if twin == leg.name or leg.name.startswith("L"):
            continue
        for j, t in zip(leg.joint_names, robot.legs[robot.leg_names.index(twin)].joint_names,
                        strict=True):
            q, p = walk.q[:, robot.column(j) + 7], np.roll(walk.q[:, robot.column(t) + 7], -half)
            u, w = q - (q.min() + q.max()) / 2, p - (p.min() + p.max()) / 2
            sign = m.signs[j]
            assert np.abs(u - sign * w).max() < 0.05 * np.abs(u).max() + 1e-9, j


def test_registry_robots_mirror_their_yaw_or_abduction_joints():
    for name, joints in (("solo12", {"FR_HAA", "HR_HAA"}), ("a1", {"FR_hip_joint",
                                                                   "RR_hip_joint"})):
        assert set(mirror(load(name)).mirrored) == joints


def test_reversed_axes_are_found_on_a_robot_facing_y(tmp_path):
    """The test hexapod faces +y; reversing the right legs' femur and tibia axes makes them
    mirrored, beside the coxas (vertical axes: mirrored by geometry)."""
    plain = mirror(load(str(SPIDER)))
    assert set(plain.mirrored) == {"d_j1", "e_j1", "f_j1"}
    m = mirror(flipped_spider(tmp_path, RIGHT_PITCH))
    assert set(m.mirrored) == {"d_j1", "e_j1", "f_j1", *RIGHT_PITCH}
    assert not m.notes
    assert "mirrored joints" in m.summary()


def test_a_joint_whose_axis_is_no_mirror_image_is_named(tmp_path):
    """A right femur turned about the leg's own axis has no mirror-image twin: kept at +1 and
    named; a configuration of the wrong size is refused by name."""
    import xml.etree.ElementTree as ET

    from hexaleg.errors import InvalidParameterError

    tree = ET.parse(SPIDER.parent / "spider.urdf")
    for j in tree.getroot().iter("joint"):
        if j.get("name") == "d_j2":
            j.find("axis").set("xyz", "1 0 0")  # type: ignore[union-attr]
    tree.write(tmp_path / "spider.urdf")
    (tmp_path / "spider.toml").write_text(SPIDER.read_text())
    robot = load(str(tmp_path / "spider.toml"))
    m = mirror(robot)
    assert m.signs["d_j2"] == 1 and any(n.startswith("d_j2:") for n in m.notes)
    with pytest.raises(InvalidParameterError, match="q"):
        mirror(robot, np.zeros(3))
