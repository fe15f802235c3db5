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
from hexaleg.robot.urdf_numbers import MAX_LINKS, check_urdf_numbers, check_xml

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


def test_a_zero_length_axis_is_named_with_its_joint():
    root = _with(r'<axis xyz="[^"]*"', '<axis xyz="0 0 0"')
    with pytest.raises(RobotModelError, match=r"joint 'LF_coxa', <axis xyz=\"0 0 0\">: a "
                                              r"zero-length axis; allowed: a nonzero direction"):
        check_urdf_numbers(root, Path("robot.urdf"))


@pytest.mark.parametrize("tag", ["joint", "link"])
def test_a_repeated_name_is_named(tag):
    names = re.findall(rf'<{tag} name="([^"]*)"', URDF)
    root = ET.fromstring(URDF.replace(f'<{tag} name="{names[1]}"', f'<{tag} name="{names[0]}"',
                                      1))
    with pytest.raises(RobotModelError, match=rf"the {tag} name '{names[0]}' is given to two "
                                              rf"{tag}s; allowed: one {tag} a name"):
        check_urdf_numbers(root, Path("robot.urdf"))


def test_entities_are_refused_saying_what_to_do(tmp_path):
    path = tmp_path / "lol.urdf"
    path.write_text('<?xml version="1.0"?>\n<!DOCTYPE r [<!ENTITY a "aaaa"><!ENTITY b "&a;&a;">]>'
                    '\n<robot name="r"><link name="l">&b;</link></robot>\n')
    with pytest.raises(RobotModelError, match=r"declares XML entities .*allowed: plain XML .*"
                                              r"xacro"):
        check_xml(path, "URDF")


def test_a_urdf_beyond_the_link_bound_is_refused_before_pinocchio(tmp_path):
    """10,000 links chained by fixed joints had crashed Pinocchio's parser (signal 11)."""
    links = "".join(f'<link name="l{i}"/>' for i in range(MAX_LINKS + 1))
    joints = "".join(f'<joint name="j{i}" type="fixed"><parent link="l{i - 1}"/>'
                     f'<child link="l{i}"/></joint>' for i in range(1, MAX_LINKS + 1))
    path = tmp_path / "chain.urdf"
    path.write_text(f'<robot name="chain">{links}{joints}</robot>')
    with pytest.raises(RobotModelError, match=rf"has {MAX_LINKS + 1} links; allowed: at most "
                                              rf"{MAX_LINKS} "):
        check_xml(path, "URDF")
    path.write_text(f'<robot name="chain">{links}{joints}</robot>'.replace(
        f'<link name="l{MAX_LINKS}"/>', "").replace(
        f'<joint name="j{MAX_LINKS}" type="fixed"><parent link="l{MAX_LINKS - 1}"/><child '
        f'link="l{MAX_LINKS}"/></joint>', ""))
    check_xml(path, "URDF")  # at the bound: read
    assert pin.buildModelFromUrdf(str(path)).nframes == 2 * MAX_LINKS  # and Pinocchio loads it
