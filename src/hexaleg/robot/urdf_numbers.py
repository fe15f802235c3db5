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
    _check_limits(root, path)
    _check_sizes(root, path)


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
        RobotModelError: the file cannot be read, is not well-formed XML, or has a number that
            urdfdom would drop (:func:`check_urdf_numbers`).
    """
    try:  # the one bounded reader: a regular file, at most MAX_TEXT_BYTES, UTF-8
        root = ET.fromstring(read_text(path, f"{what} file"))
    except ConfigError as e:
        raise RobotModelError(str(e)) from None
    except ET.ParseError as e:
        raise RobotModelError(f"{what} file {path} is not well-formed XML: {e}") from e
    if what == "URDF":
        check_urdf_numbers(root, path)
