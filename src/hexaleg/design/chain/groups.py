"""Which joints share one spring design: a joint class, a left/right pair of legs, or one joint.

Legs pair by name: ``L…`` with ``R…`` (``LF``/``RF``, ``LM``/``RM``, ``LH``/``RH``); a leg whose
name has no mirror gets its own group.

A joint class is the joints at one place in every leg; one spring geometry (a dead zone, a
preload angle) serves it only where its members work over the same angles. Knees that bend
opposite ways (an X-configured quadruped: front knees at −118…−78°, hind at +79…+123°) do not:
:func:`split_by_motion` splits such a class into the members whose ranges over the gait overlap
(counted in their mirror convention), each part its own geometry, and says so.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from hexaleg.errors import UnknownNameError
from hexaleg.robot.model import Robot


def sprung_classes(robot: Robot, classes: tuple[str, ...]) -> tuple[str, ...]:
    """The classes that may carry springs: ``classes`` checked, or every class when empty.

    Raises:
        UnknownNameError: a class the robot does not have (lists them).
    """
    for c in classes:
        if c not in robot.joint_classes:
            raise UnknownNameError("design.classes entry (joint class)", c, robot.joint_classes)
    return classes or tuple(robot.joint_classes)


def design_groups(robot: Robot, classes: tuple[str, ...], grouping: str
                  ) -> dict[str, tuple[str, ...]]:
    """Group name → joints for ``grouping`` (``class``, ``mirrored`` or ``joint``)."""
    by_class = {c: robot.joint_classes[c] for c in classes}
    if grouping == "class":
        return by_class
    out: dict[str, tuple[str, ...]] = {}
    for c, joints in by_class.items():
        if grouping == "joint":
            out.update({j: (j,) for j in joints})
            continue
        legs = {leg.name: j for leg, j in zip(robot.legs, joints, strict=True)}
        done: set[str] = set()
        for name in legs:
            if name in done:
                continue
            mate = ("R" + name[1:]) if name.startswith("L") else (
                ("L" + name[1:]) if name.startswith("R") else "")
            pair = [name] + ([mate] if mate in legs and mate not in done else [])
            done.update(pair)
            out[f"{c} {'/'.join(pair)}"] = tuple(legs[leg] for leg in pair)
    return out


def split_by_motion(robot: Robot, class_groups: Mapping[str, tuple[str, ...]],
                    angles: Mapping[str, tuple[float, float]],
                    signs: Mapping[str, int] | None = None
                    ) -> tuple[dict[str, tuple[str, ...]], list[str]]:
    """Each class split into the members whose ranges of motion overlap (module docstring).

    Two joints of a class share a part when their ranges over the gait overlap (each range in
    the joint's mirror convention: a mirrored joint's ``−hi…−lo``); a class whose members fall
    into several disjoint sets is split, each set named after its legs
    (``"knee LF/RF"``).

    Args:
        robot: The robot. class_groups: Class → its joints.
        angles: Joint → (lowest, highest) angle over the gait, rad.
        signs: Joint → +1 or −1, its mirror convention (:func:`hexaleg.robot.mirror.mirror`);
            None: every joint +1.

    Returns:
        Part → joints (a class not split keeps its name), and one note per class split.
    """
    legs = {j: leg.name for leg in robot.legs for j in leg.joint_names}
    out: dict[str, tuple[str, ...]] = {}
    notes = []
    for cls, joints in class_groups.items():
        spans = {}
        for j in joints:
            lo, hi = angles[j]
            sign = 1 if signs is None else signs.get(j, 1)
            spans[j] = (lo, hi) if sign > 0 else (-hi, -lo)
        parts: list[list[str]] = []
        for j in sorted(joints, key=lambda j: spans[j][0]):  # sweep: a gap starts a part
            if parts and spans[j][0] <= max(spans[k][1] for k in parts[-1]):
                parts[-1].append(j)
            else:
                parts.append([j])
        if len(parts) == 1:
            out[cls] = joints
            continue
        ordered = [tuple(j for j in joints if j in part) for part in parts]
        described = []
        for part in ordered:
            name = "/".join(legs[j] for j in part)
            out[f"{cls} {name}"] = part
            lo, hi = (math.degrees(f(spans[j][i] for j in part)) for f, i in ((min, 0), (max, 1)))
            described.append(f"{name} at {lo:+.0f}…{hi:+.0f}°")
        notes.append(f"joint class {cls} split by its motion: {'; '.join(described)} — disjoint "
                     "ranges, so each gets its own spring geometry")
    return out, notes


def class_of(robot: Robot, joints: tuple[str, ...]) -> str:
    """The joint class of a group's joints (every group lies in one class)."""
    kinds = {k for k, js in robot.joint_classes.items() for j in joints if j in js}
    return sorted(kinds)[0]
