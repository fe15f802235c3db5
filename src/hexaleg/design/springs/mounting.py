"""Where each spring to buy is mounted on each of its joints, in the joint's own angle.

A design's geometry is relative: its angles are measured from the centre of each joint's range of
motion in the gait (:mod:`hexaleg.design.families.family`), so one design serves every joint of a
group whose motions are offset. A builder mounts a stop on one joint, reading that joint's angle
as its encoder reports it — from the joint's zero, the zero of the robot model (URDF). This module
turns each part (:class:`~hexaleg.design.springs.parts.SpringPart`) into one
:class:`Mounting` per joint, every angle both from the joint's zero (``joint angle``) and from its
centre of motion:

* ``centre`` c and the gait's range ``[low, high]`` of the joint;
* ``contact``: where the spring's moving leg rests on its stop, preloaded, ``c + a`` for the
  part's contact angle a (the family's geometry);
* ``free``: where that leg would rest without the stop (the spring unwound), ``c + u_f``;
* ``hard_stop``: the stop that limits the wind-up to the design factor over the joint's whole
  envelope (:class:`~hexaleg.design.springs.envelope.HardStop`), when one is needed.

A joint that counts its angle the other way round from its group's design (a mirrored joint,
:mod:`hexaleg.robot.mirror`) gets ``c − u`` for every relative angle u and the other side, as
:func:`~hexaleg.design.springs.envelope.part_envelope` and
:meth:`~hexaleg.design.families.family.Family.mirror` count it. Everything is SI (rad).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.design.springs.envelope import PartEnvelope
from hexaleg.design.springs.parts import SpringPart
from hexaleg.quantities import quantity

OTHER_SIDE = {"above": "below", "below": "above"}


@dataclass(frozen=True)
class Mounting:
    """One part on one joint (module docstring); angles in rad from the joint's zero.

    Attributes:
        part: The part's index in the design's parts. group, role: The part's.
        joint: The joint. side: The side it acts on, on this joint (``above``: it pushes the
            joint towards lower angles once past ``contact``).
        mirrored: Whether the joint counts its angle the other way round from the design.
        centre: Centre of the joint's motion in the gait. low, high: The gait's range.
        contact: Where the moving leg rests on its stop, or None (no stop: a linear spring).
        engaged_throughout: The spring acts over the whole gait (its contact lies outside the
            range, on the side it does not act on).
        free: Where the moving leg would rest unwound, or None (a constant torque).
        hard_stop: The hard stop limiting its wind-up, or None when none is needed.
    """

    part: int
    group: str
    role: str
    joint: str
    side: str
    mirrored: bool
    centre: float
    low: float
    high: float
    contact: float | None
    engaged_throughout: bool
    free: float | None
    hard_stop: float | None

    def table(self) -> dict[str, Any]:
        """As ``design.json`` holds it: every angle ``{value, unit}`` in rad from the joint's
        zero, with the same angle from the centre of motion beside it (``…_from_centre``)."""

        def pair(name: str, value: float | None) -> dict[str, Any]:
            if value is None:
                return {name: None, f"{name}_from_centre": None}
            return {name: quantity(value, "rad"),
                    f"{name}_from_centre": quantity(value - self.centre, "rad")}

        return {"part": self.part, "group": self.group, "role": self.role, "joint": self.joint,
                "side": self.side, "mirrored": self.mirrored,
                "angles_from": "the joint's zero (the robot model's, as its encoder reads); "
                               "*_from_centre: from the centre of its motion in the gait",
                "centre": quantity(self.centre, "rad"),
                "low": quantity(self.low, "rad"), "high": quantity(self.high, "rad"),
                **pair("contact", self.contact),
                "engaged_throughout": self.engaged_throughout,
                **pair("free", self.free), **pair("hard_stop", self.hard_stop)}


def _joint_angle(u: float | None, centre: float, mirrored: bool) -> float | None:
    """The joint angle of ``u`` rad from the centre of motion (``c − u`` on a mirrored joint)."""
    return None if u is None else centre + (-u if mirrored else u)


def mountings(parts: Sequence[SpringPart], q: np.ndarray, columns: Mapping[str, int], *,
              envelope: Sequence[PartEnvelope] = (),
              mirrored: frozenset[str] = frozenset()) -> tuple[Mounting, ...]:
    """Every part with a spring on each of its joints (module docstring), parts in order.

    Args:
        parts: The parts to buy (a part without a spring — a constant torque, none fits — is
            left out: there is nothing to mount).
        q: Joint angles of the gait the parts were designed on, shape (T, nj), rad.
        columns: Joint → its column of ``q``.
        envelope: The parts' envelopes (:func:`~hexaleg.design.springs.envelope.parts_envelope`); a
            part's hard stop is taken from the entry of its group and side.
        mirrored: Joints that count their angle the other way round from the design.
    """
    stops = {(e.group, e.side): e.stop for e in envelope}
    out: list[Mounting] = []
    for i, p in enumerate(parts):
        if p.spring is None:
            continue
        stop = stops.get((p.group, p.side))
        for j in p.joints:
            qj = q[:, columns[j]]
            low, high = float(qj.min()), float(qj.max())
            c = (low + high) / 2
            flip = j in mirrored
            out.append(Mounting(
                part=i, group=p.group, role=p.role, joint=j,
                side=OTHER_SIDE[p.side] if flip else p.side, mirrored=flip, centre=c,
                low=low, high=high, contact=_joint_angle(p.contact, c, flip),
                engaged_throughout=p.contact is not None and p.engage is None,
                free=_joint_angle(p.free, c, flip),
                hard_stop=None if stop is None else float(stop.angles[j])))
    return tuple(out)


__all__ = ["Mounting", "mountings"]
