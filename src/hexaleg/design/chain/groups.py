"""Which joints share one spring design: a joint class, a left/right pair of legs, or one joint.

Legs pair by name: ``L…`` with ``R…`` (``LF``/``RF``, ``LM``/``RM``, ``LH``/``RH``); a leg whose
name has no mirror gets its own group.
"""

from __future__ import annotations

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


def class_of(robot: Robot, joints: tuple[str, ...]) -> str:
    """The joint class of a group's joints (every group lies in one class)."""
    kinds = {k for k, js in robot.joint_classes.items() for j in joints if j in js}
    return sorted(kinds)[0]
