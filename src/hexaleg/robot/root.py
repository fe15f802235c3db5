"""The root (base) frame above the feet: checked where the stand is made, or moved by an offset.

The free-flyer base of the loaded robot is the URDF's root link: its origin is where gaits put
the body (at the stand's body height above the ground) and the point the body turns about. A
URDF whose root link is a foot-level frame (a "footprint" link under the body) has that origin
below the feet: every gait then places the body under the ground — the stand's body height
comes out negative and the simulation has no contact to stand on. It is caught where the stand
pose is made (:meth:`hexaleg.robot.description.RobotDescription.load`):

* by default a :class:`~hexaleg.errors.RobotModelError` names the height found, what is allowed
  and the fix: a ``root_offset`` for the description (numbers to paste: the base body's centre
  of mass, when that is above the feet), a URDF whose root link is in the body, or a stand pose
  with the legs below the body;
* ``root_offset = [x, y, z]`` (m, in the URDF root link's frame; opt-in, stated in the robot's
  notes) loads the URDF with a new massless root link :data:`ROOT_LINK` at that point and the
  old root fixed to it (:func:`with_root_offset`): the same rigid bodies and the same inertia
  (Pinocchio merges the fixed joint), only the base frame moved, without rotation.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import pinocchio as pin

from hexaleg.errors import InvalidParameterError, RobotModelError
from hexaleg.robot.loaded import Robot
from hexaleg.robot.sanity import body_name

ROOT_LINK = "hexaleg_root"
"""Name of the root link :func:`with_root_offset` adds (underscores appended if taken)."""


def root_link(root: ET.Element, path: Path) -> str:
    """The URDF's root link: the one link that is no joint's child.

    Raises:
        RobotModelError: no such link, or several (names them).
    """
    children = {c.get("link") for j in root.iter("joint") for c in j.iter("child")}
    roots = [n for link in root.iter("link") if (n := link.get("name", "")) not in children]
    if len(roots) != 1:
        raise RobotModelError(f"URDF {path}: {len(roots)} root links ({', '.join(roots)}); a "
                              "robot has exactly one link that is no joint's child")
    return roots[0]


def with_root_offset(xml: str, path: Path, offset: Sequence[float]) -> tuple[str, str]:
    """URDF text whose root frame is moved to ``offset`` in the old root link's frame.

    Adds a massless link :data:`ROOT_LINK` and a fixed joint from it to the old root link with
    origin ``−offset`` (no rotation): the old root's origin is then at ``−offset`` in the new
    root's frame, i.e. the new root sits at ``offset`` in the old one's.

    Args:
        xml: The URDF text.
        path: The URDF file (for messages).
        offset: ``[x, y, z]``, m, finite.

    Returns:
        The URDF text and a note saying what was moved.

    Raises:
        InvalidParameterError: an offset that is not three finite numbers.
        RobotModelError: the URDF has not exactly one root link.
    """
    d = np.asarray(offset, dtype=float)
    if d.shape != (3,) or not np.all(np.isfinite(d)):
        raise InvalidParameterError("robot.root_offset", list(offset), "[x, y, z] (m, finite, "
                                    "in the URDF root link's frame)")
    robot = ET.fromstring(xml)
    old = root_link(robot, path)
    names = {e.get("name") for e in (*robot.iter("link"), *robot.iter("joint"))}
    name = ROOT_LINK
    while name in names or f"{name}_joint" in names:
        name += "_"
    ET.SubElement(robot, "link", name=name)
    joint = ET.SubElement(robot, "joint", name=f"{name}_joint", type="fixed")
    ET.SubElement(joint, "parent", link=name)
    ET.SubElement(joint, "child", link=old)
    ET.SubElement(joint, "origin", xyz=" ".join(repr(float(-v)) for v in d), rpy="0 0 0")
    text = ", ".join(f"{v:+.4g}" for v in d)
    note = (f"root frame moved (root_offset): the base frame is at [{text}] m in the URDF root "
            f"link {old}'s frame, not at its origin")
    return ET.tostring(robot, encoding="unicode"), note


def root_height(robot: Robot, q: np.ndarray) -> float:
    """Height of the base origin above the mean foot at ``q`` (nq,), base at the origin with
    identity orientation: ``h = z_base − mean_i z_foot,i``, m."""
    q = np.array(q, dtype=float)
    q[:7] = pin.neutral(robot.model)[:7]
    return float(-robot.foot_positions(q)[:, 2].mean())


def check_root(robot: Robot, q: np.ndarray, pose: str) -> None:
    """The base origin above the mean foot in the stand pose (module docstring).

    Args:
        robot: The loaded robot.
        q: Its stand pose, shape (nq,).
        pose: What ``q`` is, in words (``"the stand pose"``).

    Raises:
        RobotModelError: :func:`root_height` ≤ 0; names it, what is allowed and the fixes, with
            a ``root_offset`` to paste when the base body's centre of mass is above the feet.
    """
    height = root_height(robot, q)
    if height > 0:
        return
    model = robot.model
    root = body_name(model, 1).split(" (")[0]
    com = np.asarray(model.inertias[1].lever, dtype=float)
    lift = float(com[2]) + height  # the CoM's height above the mean foot
    if lift > 0:
        paste = ", ".join(f"{v:.4g}" for v in com + 0.0)
        offset = (f"root_offset = [{paste}] to the description's [robot] table (the base "
                  f"body's centre of mass, {lift:.4g} m above the mean foot; a stated repair)")
    else:
        offset = ("root_offset = [x, y, z] (m, in the root link's frame, a point of the body "
                  "above the feet) to the description's [robot] table")
    raise RobotModelError(
        f"{robot.name}: the base origin is {height:+.4g} m above the mean foot in {pose} "
        f"(allowed: > 0 m, the base above the feet): the URDF's root ({root}) sits below "
        f"the feet, so every gait would put the body under the ground. Add {offset}, or make "
        "a link in the body the URDF's root, or pose the legs below the body in the stand")


__all__ = ["ROOT_LINK", "check_root", "root_height", "root_link", "with_root_offset"]
