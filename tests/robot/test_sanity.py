"""Tests of hexaleg.robot.sanity: each robot check fires on a deliberately broken copy of the
hexaleg URDF/SRDF, names the link and says what is allowed, and stays silent on every registry
robot."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from hexaleg.robot.model import DEFAULT_SRDF, DEFAULT_URDF, load_robot
from hexaleg.robot.registry import DESCRIPTIONS, load
from hexaleg.robot.sanity import (
    GYRATION_FACTOR,
    TRIANGLE_TOL,
    Finding,
    body_size,
    limit_findings,
    robot_findings,
)

DATA = Path(__file__).resolve().parents[1] / "data"


def broken_urdf(tmp_path: Path, link: str, mass: float | None = None,
                **inertia: float) -> Path:
    """A copy of the hexaleg URDF with ``link``'s mass and/or inertia entries replaced."""
    tree = ET.parse(DEFAULT_URDF)
    element = next(e for e in tree.getroot().iter("link") if e.get("name") == link)
    inertial = element.find("inertial")
    assert inertial is not None
    if mass is not None:
        inertial.find("mass").set("value", repr(mass))  # type: ignore[union-attr]
    for key, value in inertia.items():
        inertial.find("inertia").set(key, repr(value))  # type: ignore[union-attr]
    path = tmp_path / "broken.urdf"
    tree.write(path)
    return path


def stand_srdf(tmp_path: Path, angles: dict[str, float]) -> Path:
    """A copy of the hexaleg SRDF whose ``stand`` pose has the given joint angles."""
    tree = ET.parse(DEFAULT_SRDF)
    stand = next(s for s in tree.getroot().iter("group_state") if s.get("name") == "stand")
    for joint in stand:
        if joint.get("name") in angles:
            joint.set("value", repr(angles[joint.get("name")]))
    path = tmp_path / "stand.srdf"
    tree.write(path)
    return path


def checks(findings: list[Finding]) -> list[str]:
    return [f.check for f in findings]


@pytest.mark.parametrize("name", sorted(DESCRIPTIONS))
def test_registry_robots_pass_every_check(name, upstream_placeholders):
    """Every check but the placeholder limits some upstream URDFs write (named, one finding a
    kind of limit)."""
    findings = robot_findings(load(name))
    assert sorted(f.check for f in findings) == sorted(upstream_placeholders.get(name, set())), \
        "\n".join(f.message for f in findings)


def test_built_in_robot_passes(robot):
    assert robot_findings(robot) == []


@pytest.mark.parametrize("mass", [0.0, -0.045])
def test_zero_or_negative_mass_is_flagged(tmp_path, mass):
    robot = load_robot(broken_urdf(tmp_path, "LF_tibia_link", mass=mass), DEFAULT_SRDF,
                       inertias="keep")
    findings = robot_findings(robot)
    assert checks(findings) == ["mass"]
    (found,) = findings
    assert found.value == mass and found.unit == "kg" and found.allowed == "> 0 kg"
    assert found.where == "link LF_tibia_link (joint LF_tibia, with 1 link fixed to it)"
    assert "fix the URDF <inertial> of link LF_tibia_link" in found.remedy


def test_inertia_that_is_not_positive_definite_is_flagged(tmp_path):
    robot = load_robot(broken_urdf(tmp_path, "LF_femur_link", ixx=-1e-6), DEFAULT_SRDF,
                       inertias="keep")
    (found,) = robot_findings(robot)
    assert found.check == "inertia_definite" and found.value == pytest.approx(-1e-6)
    assert "LF_femur_link" in found.where and "principal moments" in found.remedy


def test_triangle_inequality_of_the_principal_moments(tmp_path):
    """Tibia: I1 = 2.25e-6, I3 = 5.4e-5 kg·m². I2 = I3 − I1 is a thin rod's equality and passes;
    I2 a little smaller than I3 − I1 (beyond TRIANGLE_TOL) violates it; a lot smaller too."""
    i1, i3 = 2.25e-6, 5.4e-5
    on_the_edge = load_robot(broken_urdf(tmp_path, "RM_tibia_link", iyy=i3 - i1), DEFAULT_SRDF)
    assert robot_findings(on_the_edge) == []
    for i2 in (i3 - i1 - 2 * TRIANGLE_TOL * i3, 2e-5):
        robot = load_robot(broken_urdf(tmp_path, "RM_tibia_link", iyy=i2), DEFAULT_SRDF,
                           inertias="keep")
        (found,) = robot_findings(robot)
        assert found.check == "inertia_triangle"
        assert found.value == pytest.approx((i1 + i2) / i3, rel=1e-9)
        assert found.where.startswith("link RM_tibia_link (joint RM_tibia")
        assert "triangle inequality" in found.allowed


def test_femur_size_is_its_bounding_box_corner_from_the_com(robot):
    """Femur: cylinder of radius 0.01 m along x over [0, 0.084] m, CoM at x = 0.047141 m: the
    farthest corner of its bounding box is at the far-from-CoM end, beyond the tibia joint."""
    size = body_size(robot, robot.model.getJointId("LF_femur"))
    assert size == pytest.approx(math.sqrt(0.047141**2 + 2 * 0.01**2), rel=1e-9)


def test_radius_of_gyration_of_half_a_metre_on_a_coxa_is_flagged(tmp_path):
    """The public-URDF story: a 0.58 m radius of gyration on a link a few centimetres long. The
    inertia is isotropic, so only the size check can see it."""
    mass, k = 0.0545, 0.58
    inertia = {key: mass * k**2 for key in ("ixx", "iyy", "izz")}
    robot = load_robot(broken_urdf(tmp_path, "LH_coxa_link", **inertia), DEFAULT_SRDF)
    (found,) = robot_findings(robot)
    size = body_size(robot, robot.model.getJointId("LH_coxa"))
    assert found.check == "radius_of_gyration" and found.unit == "m"
    assert found.value == pytest.approx(k, rel=1e-9)
    assert k > 10 * size and f"{GYRATION_FACTOR * size:.4g} m" in found.allowed
    assert found.where == "link LH_coxa_link (joint LH_coxa)"


def test_radius_of_gyration_threshold_is_the_documented_factor(tmp_path, robot):
    """Just under GYRATION_FACTOR × size passes, just over fires (isotropic coxa inertia)."""
    mass = 0.0545
    size = body_size(robot, robot.model.getJointId("LF_coxa"))
    for factor, fires in ((0.99, False), (1.01, True)):
        k = factor * GYRATION_FACTOR * size
        inertia = {key: mass * k**2 for key in ("ixx", "iyy", "izz")}
        robot = load_robot(broken_urdf(tmp_path, "LF_coxa_link", **inertia), DEFAULT_SRDF)
        assert checks(robot_findings(robot)) == (["radius_of_gyration"] if fires else [])


def test_root_frame_above_the_feet_is_flagged_with_the_body_height(tmp_path):
    """Mirror every leg about the hip plane (femur and tibia angles negated): the feet end up
    0.0913 m above the base origin, the body height is negative."""
    ref = load_robot()
    stand = ref.pose("stand")
    angles = {}
    for leg in ref.legs:
        for name, iq in zip(leg.joint_names, leg.q_index, strict=True):
            angles[name] = -float(stand[iq])
    robot = load_robot(DEFAULT_URDF, stand_srdf(tmp_path, angles))
    (found,) = robot_findings(robot)
    feet = robot.foot_positions(robot.pose("stand"))
    assert found.check == "body_height" and found.unit == "m"
    assert found.value == pytest.approx(-0.0912703, abs=1e-6)
    assert found.value == pytest.approx(-float(np.mean(feet[:, 2])), rel=1e-12)
    assert "stand pose" in found.where and "> 0 m" in found.allowed
    assert "SRDF" in found.remedy and "body" in found.remedy


def test_one_foot_above_the_base_is_named(tmp_path):
    """Only RM's femur raised high: the mean foot is still below the base, RM's foot is not."""
    robot = load_robot(DEFAULT_URDF, stand_srdf(tmp_path, {"RM_femur": 1.5, "RM_tibia": 0.0}))
    (found,) = robot_findings(robot)
    assert found.check == "foot_above_base" and found.value > 0
    assert found.where == "foot RM_foot of leg RM in the stand pose"


def test_without_stand_pose_the_neutral_configuration_is_checked():
    """No SRDF: the neutral configuration (legs straight out) has the feet level with the base,
    body height 0 — flagged, and the finding says which pose it used."""
    robot = load_robot(DEFAULT_URDF, None)
    assert robot.poses == {}
    (found,) = robot_findings(robot)
    assert found.check == "body_height" and found.value == pytest.approx(0.0, abs=1e-12)
    assert "neutral configuration" in found.where


def test_finding_message_is_one_line_with_value_unit_allowed_and_remedy():
    found = Finding("joint_speed", "joint LF_femur at t = 0.25 s", 12.345678, "rad/s",
                    "≤ 10.16 rad/s", "slow the gait")
    assert found.message == ("joint_speed: joint LF_femur at t = 0.25 s: 12.35 rad/s "
                             "(allowed: ≤ 10.16 rad/s); slow the gait")
    assert Finding("x", "y", 0.5, "", "≥ 1", "z").message == "x: y: 0.5 (allowed: ≥ 1); z"
    with pytest.raises(AttributeError):
        found.value = 0.0  # type: ignore[misc]


def test_placeholder_limits_are_flagged_once_a_kind(tmp_path):
    """The spider with the ±10 rad, 1000 N·m, 1000 rad/s an exporter writes on one joint: three
    findings naming it, none on the real limits."""
    text = (DATA / "spider.urdf").read_text()
    real = '<limit lower="-1.2" upper="1.2" effort="1.5" velocity="6"/>'
    assert real in text
    (tmp_path / "spider.urdf").write_text(text.replace(
        real, '<limit lower="-10" upper="10" effort="1000" velocity="1000"/>', 1))
    robot = load_robot(tmp_path / "spider.urdf", legs="auto", heading=(0, 1, 0))
    found = {f.check: f for f in limit_findings(robot)}
    assert set(found) == {"joint_range", "joint_speed_limit", "joint_torque_limit"}
    assert all(f.where == "joint a_j1" for f in found.values())
    assert found["joint_range"].value == 20.0 and found["joint_torque_limit"].value == 1000.0
    assert "placeholder" in found["joint_speed_limit"].remedy
    assert limit_findings(load_robot(DATA / "spider.urdf", legs="auto", heading=(0, 1, 0))) == []


def test_a_stand_outside_the_joint_limits_is_a_finding(tmp_path):
    """Go2-like knees whose range excludes 0, a stand that leaves them at 0: one finding that
    counts the joints and names the first (issue #55: only a note before, if anything)."""
    from hexaleg.robot.description import RobotDescription
    from hexaleg.robot.sanity import stand_limit_findings

    data = Path(__file__).resolve().parents[1] / "data"
    toml = tmp_path / "q.toml"
    toml.write_text(f'[robot]\nname = "q"\nurdf = "{data / "pryquad.urdf"}"\n'
                    'stand = {LF_knee = -1.0}\n')
    robot = RobotDescription.from_toml(toml).load()
    (finding,) = stand_limit_findings(robot)
    assert finding.check == "stand_joint_limits"
    assert "3 joint(s) outside" in finding.where and "LH_knee at +0 rad" in finding.where
    assert finding.value == pytest.approx(0.3)
    assert "stand_joint_limits" in {f.check for f in robot_findings(robot)}
    assert stand_limit_findings(RobotDescription.from_toml(data / "pryquad.toml").load()) == []
