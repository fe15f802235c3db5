"""The URDF number check: what urdfdom would drop silently is refused by name; what it reads is
accepted."""

from __future__ import annotations

import re
import xml.etree.ElementTree as ET
from pathlib import Path

import pinocchio as pin
import pytest

from hexaleg.errors import RobotModelError
from hexaleg.robot.model import DEFAULT_URDF
from hexaleg.robot.registry import DESCRIPTIONS, load
from hexaleg.robot.urdf_numbers import check_urdf_numbers

URDF = DEFAULT_URDF.read_text(encoding="utf-8")


def _with(pattern: str, replacement: str) -> ET.Element:
    text, n = re.subn(pattern, replacement, URDF, count=1)
    assert n == 1
    return ET.fromstring(text)


@pytest.mark.parametrize(("pattern", "replacement", "named"), [
    (r'<mass value="[^"]*"', '<mass value="abc"', '<mass value="abc">'),
    (r'<mass value="[^"]*"', '<mass value="nan"', '<mass value="nan">'),
    (r'<mass value="[^"]*"', '<mass value="1_000"', '<mass value="1_000">'),
    (r'ixx="[^"]*"', 'ixx=""', '<inertia ixx="">'),
    (r'<origin xyz="[^"]*"', '<origin xyz="0 0"', '<origin xyz="0 0">'),
    (r'rpy="[^"]*"', 'rpy="0 0 x"', 'rpy="0 0 x">'),
    (r'<axis xyz="[^"]*"', '<axis xyz="0 0 1 0"', '<axis xyz="0 0 1 0">'),
    (r'effort="[^"]*"', 'effort="inf"', 'effort="inf">'),
])
def test_an_unreadable_number_is_named(pattern, replacement, named):
    root = _with(pattern, replacement)
    with pytest.raises(RobotModelError) as e:
        check_urdf_numbers(root, Path("robot.urdf"))
    message = str(e.value)
    assert named in message and "robot.urdf" in message
    assert re.search(r"(link|joint) '\w+'", message)


@pytest.mark.parametrize("value", ["1e-3", "-.5", "5.", " 0.1 ", "+2", "3E+2"])
def test_every_decimal_form_urdfdom_reads_is_accepted(value):
    check_urdf_numbers(_with(r'<mass value="[^"]*"', f'<mass value="{value}"'),
                       Path("robot.urdf"))


def test_the_check_guards_against_a_silent_drop():
    """Without it, Pinocchio (urdfdom) loads a link whose mass it cannot read as massless."""
    bad = re.sub(r'(<link name="body">.*?<mass value=")[^"]*"', r'\1abc"', URDF, count=1,
                 flags=re.S)
    good_mass = pin.computeTotalMass(pin.buildModelFromXML(URDF, pin.JointModelFreeFlyer()))
    bad_mass = pin.computeTotalMass(pin.buildModelFromXML(bad, pin.JointModelFreeFlyer()))
    assert bad_mass < good_mass - 1e-3
    with pytest.raises(RobotModelError, match="link 'body'"):
        check_urdf_numbers(ET.fromstring(bad), Path("robot.urdf"))


@pytest.mark.parametrize("name", sorted(DESCRIPTIONS))
def test_every_registered_robot_passes(name):
    """The built-in robot and every example-robot-data robot of the registry load: the check
    refuses nothing urdfdom reads."""
    assert load(name).mass > 0


@pytest.mark.parametrize("attribute", ["effort", "velocity"])
def test_a_limit_without_effort_or_velocity_is_named(tmp_path, attribute):
    """urdfdom refuses it with "the XML stream does not contain a valid URDF model", naming
    neither the joint nor the attribute; hexaleg's own line names both."""
    tree = ET.parse(DEFAULT_URDF)
    limit = next(j for j in tree.getroot().iter("joint") if j.get("name") == "LF_coxa"
                 ).find("limit")
    del limit.attrib[attribute]
    path = tmp_path / "robot.urdf"
    tree.write(path)
    with pytest.raises(RobotModelError, match=rf"joint 'LF_coxa', <limit> has no {attribute} "
                                              r"attribute; urdfdom requires effort and velocity"):
        check_urdf_numbers(ET.parse(path).getroot(), path)


def test_a_revolute_joint_without_limit_is_named(tmp_path):
    tree = ET.parse(DEFAULT_URDF)
    joint = next(j for j in tree.getroot().iter("joint") if j.get("name") == "LF_coxa")
    joint.remove(joint.find("limit"))
    with pytest.raises(RobotModelError, match=r"joint 'LF_coxa' of type revolute has no <limit>"):
        check_urdf_numbers(tree.getroot(), tmp_path / "robot.urdf")


def test_a_joint_range_upside_down_is_named():
    """lower > upper loaded silently (#42): every range check then used an empty interval."""
    tree = ET.fromstring(URDF)
    limit = next(j for j in tree.iter("joint") if j.get("name") == "LF_femur").find("limit")
    lower, upper = limit.get("lower"), limit.get("upper")
    limit.set("lower", upper)
    limit.set("upper", lower)
    with pytest.raises(RobotModelError, match=r"joint 'LF_femur', <limit lower=.*lower is above "
                                              r"upper"):
        check_urdf_numbers(tree, Path("robot.urdf"))


@pytest.mark.parametrize(("tag", "attribute", "value"), [
    ("sphere", "radius", "-0.01"), ("sphere", "radius", "0"), ("cylinder", "length", "-1"),
    ("box", "size", "0.1 -0.2 0.1")])
def test_a_shape_of_no_size_is_named(tag, attribute, value):
    """A foot sphere of radius −0.01 loaded and moved the body 10 mm without a word (#42)."""
    tree = ET.fromstring(URDF)
    link = next(iter(tree.iter("link")))
    geometry = ET.SubElement(ET.SubElement(link, "collision"), "geometry")
    ET.SubElement(geometry, tag, {attribute: value})
    with pytest.raises(RobotModelError, match=rf"<{tag} {attribute}=\"{value}\">: expected "
                                              r"sizes > 0"):
        check_urdf_numbers(tree, Path("robot.urdf"))
