"""The numbers of a URDF, checked before Pinocchio reads it.

Pinocchio parses a URDF with urdfdom, which on a number it cannot read (``<mass value="abc"/>``,
``<origin xyz="0 0"/>``) prints an error to the console and drops the element: the link loads
massless, the joint at the origin — a robot with the wrong dynamics and no exception. Every
numeric attribute urdfdom reads (ROS URDF XML specification, wiki.ros.org/urdf/XML: ``link``,
``joint``) is checked here instead, so that a typo is a :class:`~hexaleg.errors.RobotModelError`
naming the link or joint, the attribute, its value and what is allowed. (Values that read as
numbers but make no physical sense — a negative mass, an indefinite inertia — load, and
:mod:`hexaleg.robot.sanity` reports them with a remedy.)
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

from hexaleg.config import read_text
from hexaleg.errors import ConfigError, RobotModelError

NUMBER = re.compile(r"\s*[+-]?(\d+(\.\d*)?|\.\d+)([eE][+-]?\d+)?\s*")
"""A decimal floating-point literal as urdfdom reads one (no ``nan``, ``inf`` or ``1_000``)."""

VECTORS = {"xyz": 3, "rpy": 3, "size": 3, "scale": 3}
"""Attributes that hold a vector, and their lengths."""

CHECKED: dict[str, tuple[str, ...]] = {
    "origin": ("xyz", "rpy"),
    "mass": ("value",),
    "inertia": ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"),
    "axis": ("xyz",),
    "limit": ("lower", "upper", "effort", "velocity"),
    "dynamics": ("damping", "friction"),
    "box": ("size",),
    "cylinder": ("radius", "length"),
    "sphere": ("radius",),
    "mesh": ("scale",),
}
"""Element tag → its numeric attributes (when present)."""

MAX_LINKS = 1000
"""Most links in a URDF, checked before Pinocchio sees it: its parser recurses once a link down
the tree, and a chain of 10,000 links (fixed joints) ended ``hexaleg robot`` with a segfault
(between 3,500 and 4,000 links on the default 8 MiB stack, measured); the robots hexaleg knows
have at most a few dozen, humanoids with hands a few hundred."""

def _numbers(text: str) -> list[float] | None:
    """The numbers of an attribute, or None if one of its words is not a finite number."""
    words = text.split()
    if not all(NUMBER.fullmatch(w) for w in words):
        return None
    values = [float(w) for w in words]
    return values if all(math.isfinite(v) for v in values) else None


def check_urdf_numbers(root: ET.Element, path: Path) -> None:
    """Check every numeric attribute of the URDF ``root`` (module docstring).

    Raises:
        RobotModelError: names the link or joint, the element, the attribute, the value and
            what is allowed.
    """
    for owner in (*root.iter("link"), *root.iter("joint")):
        name = f"{owner.tag} {owner.get('name', '(unnamed)')!r}"
        for element in owner.iter():
            for attribute in CHECKED.get(element.tag, ()):
                text = element.get(attribute)
                if text is None:
                    continue
                values = _numbers(text)
                size = VECTORS.get(attribute, 1)
                allowed = (f"{size} finite numbers" if size > 1 else "a finite number")
                if values is None or len(values) != size:
                    raise RobotModelError(
                        f"URDF {path}: {name}, <{element.tag} {attribute}=\"{text}\">: expected "
                        f"{allowed} (urdfdom would drop the element and load the robot "
                        "without it)")
    _check_names(root, path)
    _check_axes(root, path)
    _check_limits(root, path)
    _check_sizes(root, path)


def _check_names(root: ET.Element, path: Path) -> None:
    """Every link and joint named once (urdfdom refuses a repeated name saying only that the
    model is not valid)."""
    for tag in ("link", "joint"):
        seen: set[str] = set()
        for element in root.findall(tag):
            name = element.get("name", "(unnamed)")
            if name in seen:
                raise RobotModelError(
                    f"URDF {path}: the {tag} name {name!r} is given to two {tag}s; allowed: "
                    f"one {tag} a name (rename one of them"
                    + (", and the <parent>/<child> that mean it)" if tag == "link" else ")"))
            seen.add(name)


def _check_axes(root: ET.Element, path: Path) -> None:
    """Every moving joint's axis of nonzero length (Pinocchio would load a zero axis as some
    direction, and a leg's chain would then miss its foot without naming the joint)."""
    for joint in root.iter("joint"):
        axis = joint.find("axis")
        if joint.get("type") == "fixed" or axis is None or axis.get("xyz") is None:
            continue
        if all(float(v) == 0 for v in axis.get("xyz", "").split()):
            raise RobotModelError(
                f"URDF {path}: joint {joint.get('name', '(unnamed)')!r}, <axis xyz=\""
                f"{axis.get('xyz')}\">: a zero-length axis; allowed: a nonzero direction such "
                "as \"0 0 1\" (the joint turns or slides along it; omit <axis> for the default "
                "x axis)")


REQUIRED = ("effort", "velocity")
"""Attributes urdfdom requires of every ``<limit>`` (wiki.ros.org/urdf/XML/joint): without one
it refuses the whole model and says only that "the XML stream does not contain a valid URDF
model"."""
MEANING = {"effort": "the actuator's peak torque, N·m (N for a prismatic joint)",
           "velocity": "its peak speed, rad/s (m/s for a prismatic joint)"}
LIMITED = ("revolute", "prismatic")
"""Joint types that must have a ``<limit>`` (the same specification)."""


def _check_limits(root: ET.Element, path: Path) -> None:
    """Every ``<limit>`` with its effort and velocity, every revolute or prismatic joint with
    its ``<limit>``: named here, where urdfdom's refusal names neither the joint nor the
    attribute."""
    for joint in root.iter("joint"):
        name = joint.get("name", "(unnamed)")
        limit = joint.find("limit")
        if limit is None:
            if joint.get("type") in LIMITED:
                raise RobotModelError(
                    f"URDF {path}: joint {name!r} of type {joint.get('type')} has no <limit>; "
                    "a revolute or prismatic joint needs <limit lower=\"…\" upper=\"…\" "
                    "effort=\"…\" velocity=\"…\"/> (rad or m, N·m or N, rad/s or m/s)")
            continue
        for attribute in REQUIRED:
            if limit.get(attribute) is None:
                raise RobotModelError(
                    f"URDF {path}: joint {name!r}, <limit> has no {attribute} attribute; "
                    f"urdfdom requires effort and velocity on every <limit> (give {attribute}"
                    f"=\"…\": {MEANING[attribute]}; 0 only for a joint that is not actuated)")
        lower, upper = limit.get("lower"), limit.get("upper")
        if joint.get("type") in LIMITED and lower is not None and upper is not None \
                and float(lower) > float(upper):
            raise RobotModelError(
                f"URDF {path}: joint {name!r}, <limit lower=\"{lower}\" upper=\"{upper}\">: "
                "lower is above upper; the joint's range is lower ≤ q ≤ upper (swap them)")


SIZES = {"sphere": ("radius",), "cylinder": ("radius", "length"), "box": ("size",)}
"""Geometry attributes that must be > 0 (a negative foot sphere's radius moved the body 10 mm
without a word)."""


def _check_sizes(root: ET.Element, path: Path) -> None:
    """Every sphere, cylinder and box of a link with sizes > 0."""
    for link in root.iter("link"):
        for element in link.iter():
            for attribute in SIZES.get(element.tag, ()):
                text = element.get(attribute)
                if text is not None and min(float(v) for v in text.split()) <= 0:
                    raise RobotModelError(
                        f"URDF {path}: link {link.get('name', '(unnamed)')!r}, <{element.tag} "
                        f"{attribute}=\"{text}\">: expected sizes > 0 (m)")


def check_xml(path: Path, what: str) -> None:
    """Read ``path`` (a ``"URDF"`` or ``"SRDF"`` file) as XML, and check a URDF's numbers.

    Raises:
        RobotModelError: the file cannot be read, declares XML entities, is not well-formed
            XML, a URDF with more than :data:`MAX_LINKS` links, or has a number that urdfdom
            would drop (:func:`check_urdf_numbers`).
    """
    try:  # the one bounded reader: a regular file, at most MAX_TEXT_BYTES, UTF-8
        text = read_text(path, f"{what} file")
    except ConfigError as e:
        raise RobotModelError(str(e)) from None
    if "<!ENTITY" in text:
        raise RobotModelError(
            f"{what} file {path} declares XML entities (<!ENTITY …>); allowed: plain XML "
            "without a DTD's entities (urdfdom does not expand them, and expanding them can "
            "fill memory): write the values out, or generate the file with xacro")
    try:
        root = ET.fromstring(text)
    except ET.ParseError as e:
        raise RobotModelError(f"{what} file {path} is not well-formed XML: {e}") from e
    if what == "URDF":
        links = len(root.findall("link"))
        if links > MAX_LINKS:
            raise RobotModelError(
                f"URDF {path} has {links} links; allowed: at most {MAX_LINKS} (Pinocchio's "
                "URDF parser recurses once a link and crashes near 3,700 chained links on an "
                "8 MiB stack; a legged robot has tens): is it the right file?")
        check_urdf_numbers(root, path)
