"""Mirrored joints: which joints count their angle the other way round from their mirror twin.

Many URDFs mirror the left and right legs' joint axes, so the same physical (mirror-symmetric)
motion has opposite signs on the two sides; others keep one axis direction for every leg. A
spring designed once per joint class must then be mirrored on the joints whose sign convention
is the other one, or one design cannot serve both sides.

The test is geometric (the joint axes in the standing pose, in the base frame): with ``l`` the
base's lateral axis (``up × heading``, pointing left) the sagittal mirror is ``M = I − 2 l lᵀ``.
A rotation by θ about axis ``a``, reflected by ``M``, is a rotation by θ about ``−M a`` (a proper
rotation conjugated by a reflection: ``M R(a, θ) M = R(det(M) · M a, θ)``, det M = −1; e.g.
Murray, Li & Sastry, *A Mathematical Introduction to Robotic Manipulation*, §2.2). So a right
leg's joint of axis ``b`` whose left twin has axis ``a`` keeps the left leg's sign convention
when ``b = −M a`` and counts the other way round (is *mirrored*) when ``b = M a``. A leg's twin
is the leg on the other side whose hip is nearest to the mirror image of its hip. The left legs
are the reference: their joints have sign +1.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from hexaleg.errors import InvalidParameterError
from hexaleg.robot.model import Robot

PARALLEL = 0.9
"""|cos| between a joint axis and its twin's mirror image above which they are taken as parallel;
below it the sign is undetermined (the axes are not mirror images) and +1 is kept, with a note."""


@dataclass(frozen=True)
class Mirror:
    """The sign convention of every joint relative to its mirror twin (module docstring).

    Attributes:
        signs: Joint → +1 (the reference side's convention) or −1 (mirrored).
        twins: Leg → its mirror twin (left and right both listed; a leg on the mirror plane or
            without a twin is its own).
        notes: What could not be decided, in words.
    """

    signs: dict[str, int]
    twins: dict[str, str]
    notes: tuple[str, ...] = ()

    @property
    def mirrored(self) -> tuple[str, ...]:
        """The joints that count their angle the other way round (sign −1), in model order."""
        return tuple(j for j, s in self.signs.items() if s < 0)

    def summary(self) -> str:
        """One line: which joints are mirrored."""
        if not self.mirrored:
            return "no mirrored joints: every leg counts its joint angles the same way round"
        return f"mirrored joints (angles counted the other way round): {', '.join(self.mirrored)}"


def _axes(robot: Robot, q: np.ndarray) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:
    """Joint → its axis (unit, base frame) and leg → its first joint's position (base frame), at
    ``q`` with the base at the origin."""
    q = q.copy()
    q[:7] = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]
    model, data = robot.model, robot.data
    pin.computeJointJacobians(model, data, q)
    axes = {}
    for leg in robot.legs:
        for j, v in zip(leg.joint_names, leg.v_index, strict=True):
            w = np.asarray(data.J[3:6, int(v)], dtype=float)
            axes[j] = w / np.linalg.norm(w) if np.linalg.norm(w) > 0 else w
    hips = {leg.name: np.asarray(data.oMi[leg.joint_ids[0]].translation, dtype=float).copy()
            for leg in robot.legs}
    return axes, hips


def mirror(robot: Robot, q: np.ndarray | None = None) -> Mirror:
    """Which joints are mirrored relative to their twin (module docstring).

    Args:
        robot: The robot.
        q: The configuration whose axes are compared (default the ``stand`` pose, else
            Pinocchio's neutral), shape (nq,).

    Raises:
        InvalidParameterError: ``q`` of another shape or not finite.
    """
    if q is None:
        q = robot.pose("stand") if "stand" in robot.poses else pin.neutral(robot.model)
    q = np.asarray(q, dtype=float)
    if q.shape != (robot.model.nq,) or not np.all(np.isfinite(q)):
        raise InvalidParameterError("q", f"shape {q.shape}",
                                    f"a finite configuration of shape ({robot.model.nq},)")
    up = np.array([0.0, 0.0, 1.0])
    lateral = np.cross(up, robot.heading)
    lateral /= np.linalg.norm(lateral)
    m = np.eye(3) - 2.0 * np.outer(lateral, lateral)
    axes, hips = _axes(robot, q)
    signs = {j: 1 for leg in robot.legs for j in leg.joint_names}
    twins = {leg.name: leg.name for leg in robot.legs}
    notes = []
    side = {n: float(h @ lateral) for n, h in hips.items()}
    scale = max((abs(s) for s in side.values()), default=0.0)
    lefts = [leg for leg in robot.legs if side[leg.name] > 1e-6 * max(scale, 1e-12)]
    rights = [leg for leg in robot.legs if side[leg.name] < -1e-6 * max(scale, 1e-12)]
    for leg in rights:
        image = m @ hips[leg.name]
        twin = min(lefts, key=lambda t: float(np.linalg.norm(hips[t.name] - image)), default=None)
        if twin is None:
            continue
        twins[leg.name], twins[twin.name] = twin.name, leg.name
        for a_name, b_name in zip(twin.joint_names, leg.joint_names, strict=True):
            a, b = axes[a_name], axes[b_name]
            same = float(b @ (-m @ a))
            if same > PARALLEL:
                continue
            if same < -PARALLEL:
                signs[b_name] = -1
                continue
            notes.append(f"{b_name}: its axis is not the mirror image of {a_name}'s (cos "
                         f"{same:+.2f}); counted as not mirrored")
    return Mirror(signs=signs, twins=twins, notes=tuple(notes))


__all__ = ["PARALLEL", "Mirror", "mirror"]
