"""SRDF checks: every ``group_state`` joint is a joint of the model, or one it does not have, and
has finite values.

Pinocchio's ``loadReferenceConfigurations`` skips a ``group_state`` joint it does not know and
reads ``value="nan"`` as NaN, so a misspelt joint name or a bad number in a stand pose would leave
that joint at its neutral angle (or NaN) without a word. :func:`check_reference_poses` reads the
SRDF itself first and refuses both, naming the file, the pose, the joint and the value.

One SRDF may serve several robots: example-robot-data ships ``solo.srdf`` for Solo-8 (two joints
a leg, ``solo.urdf``) and Solo-12 (three, ``solo12.urdf``), its poses naming the hip abduction
joints Solo-8 lacks. A pose's joint the model lacks is therefore skipped, as Pinocchio does, but
said in a note naming it — unless it reads as a misspelling: a joint of the model the pose
leaves unset whose name is close to it (``difflib``'s ratio ≥ :data:`MISSPELT`), which is
refused as before with the model's joints. The names of poses are not checked here: an unknown
stand pose is refused where it is asked for (:mod:`hexaleg.robot.stand`).
"""

from __future__ import annotations

import difflib
import math
import xml.etree.ElementTree as ET
from collections.abc import Collection
from pathlib import Path

import pinocchio as pin

from hexaleg.errors import InvalidParameterError, RobotModelError, UnknownNameError

MISSPELT = 0.8
"""``difflib.SequenceMatcher`` ratio from which a pose's unknown joint is taken for a misspelling
of a joint the pose leaves unset (``FL_HAA`` against Solo-8's unset joints: none; ``LF_femr``
against ``LF_femur``: 0.92)."""

def _values(text: str | None) -> list[float] | None:
    """The numbers of a ``value`` attribute, or None when it is not a list of finite numbers."""
    try:
        values = [float(x) for x in (text or "").split()]
    except ValueError:
        return None
    return values if values and all(math.isfinite(v) for v in values) else None


def check_reference_poses(model: pin.Model, path: str | Path,
                          locked: Collection[str] = ()) -> tuple[str, ...]:
    """Check the ``group_state`` poses of an SRDF against a model before Pinocchio loads them.

    Args:
        model: The robot's model (its joint names and their nq, nv).
        path: The SRDF file.
        locked: Joints of the URDF locked at load (wheels, :mod:`hexaleg.robot.wheels`): a
            pose may name them, and their value is not used.

    Returns:
        A note naming the joints the model does not have (skipped) and the poses naming them,
        or none.

    Raises:
        RobotModelError: the file is not well-formed XML.
        UnknownNameError: a pose names a joint the model does not have that reads as a
            misspelling of a joint the pose leaves unset (module docstring; lists its joints).
        InvalidParameterError: a joint's value is not a list of finite numbers, or has as many
            numbers as neither the joint's configuration (nq) nor its velocity (nv).
    """
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError) as e:
        raise RobotModelError(f"SRDF file {path} cannot be read as XML: {e}") from e
    joints = list(model.names)[1:]  # the universe is not a joint
    skipped: dict[tuple[str, ...], list[str]] = {}  # the joints skipped -> the poses naming them
    for state in root.iter("group_state"):
        pose = state.get("name", "?")
        named = {joint.get("name") for joint in state.iter("joint")}
        unset = [j for j in joints if j not in named]
        absent = []
        for joint in state.iter("joint"):
            name = joint.get("name")
            where = f"joint in SRDF {path} pose {pose!r}"
            if name in locked:
                continue
            if name not in joints:
                if any(difflib.SequenceMatcher(None, name or "", j).ratio() >= MISSPELT
                       for j in unset):
                    raise UnknownNameError(where, name, joints)
                absent.append(str(name))
                continue
            text = joint.get("value")
            values = _values(text)
            shape = model.joints[model.getJointId(name)]
            if values is None or len(values) not in (shape.nq, shape.nv):
                raise InvalidParameterError(
                    f"SRDF {path} pose {pose!r} joint {name} value", text,
                    f"{shape.nq} finite number(s) (rad or m; NaN and inf are not numbers here)")
        if absent:
            skipped.setdefault(tuple(absent), []).append(pose)
    if not skipped:
        return ()
    said = "; ".join(f"pose{'s' * (len(poses) > 1)} {', '.join(map(repr, poses))}: "
                     f"{', '.join(absent)}" for absent, poses in skipped.items())
    return (f"SRDF {Path(path).name} names joints {model.name} does not have, skipped as "
            f"Pinocchio does (an SRDF shared with a sibling robot?): {said}",)
