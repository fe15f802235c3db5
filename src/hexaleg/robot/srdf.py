"""SRDF checks: every ``group_state`` joint is a joint of the model and has finite values.

Pinocchio's ``loadReferenceConfigurations`` skips a ``group_state`` joint it does not know and
reads ``value="nan"`` as NaN, so a misspelt joint name or a bad number in a stand pose would leave
that joint at its neutral angle (or NaN) without a word. :func:`check_reference_poses` reads the
SRDF itself first and refuses both, naming the file, the pose, the joint and the value.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from collections.abc import Collection
from pathlib import Path

import pinocchio as pin

from hexaleg.errors import InvalidParameterError, RobotModelError, UnknownNameError


def _values(text: str | None) -> list[float] | None:
    """The numbers of a ``value`` attribute, or None when it is not a list of finite numbers."""
    try:
        values = [float(x) for x in (text or "").split()]
    except ValueError:
        return None
    return values if values and all(math.isfinite(v) for v in values) else None


def check_reference_poses(model: pin.Model, path: str | Path,
                          locked: Collection[str] = ()) -> None:
    """Check the ``group_state`` poses of an SRDF against a model before Pinocchio loads them.

    Args:
        model: The robot's model (its joint names and their nq, nv).
        path: The SRDF file.
        locked: Joints of the URDF locked at load (wheels, :mod:`hexaleg.robot.wheels`): a
            pose may name them, and their value is not used.

    Raises:
        RobotModelError: the file is not well-formed XML.
        UnknownNameError: a pose names a joint the model does not have (lists its joints).
        InvalidParameterError: a joint's value is not a list of finite numbers, or has as many
            numbers as neither the joint's configuration (nq) nor its velocity (nv).
    """
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError) as e:
        raise RobotModelError(f"SRDF file {path} cannot be read as XML: {e}") from e
    joints = list(model.names)[1:]  # the universe is not a joint
    for state in root.iter("group_state"):
        pose = state.get("name", "?")
        for joint in state.iter("joint"):
            name = joint.get("name")
            where = f"joint in SRDF {path} pose {pose!r}"
            if name in locked:
                continue
            if name not in joints:
                raise UnknownNameError(where, name, joints)
            text = joint.get("value")
            values = _values(text)
            shape = model.joints[model.getJointId(name)]
            if values is None or len(values) not in (shape.nq, shape.nv):
                raise InvalidParameterError(
                    f"SRDF {path} pose {pose!r} joint {name} value", text,
                    f"{shape.nq} finite number(s) (rad or m; NaN and inf are not numbers here)")
