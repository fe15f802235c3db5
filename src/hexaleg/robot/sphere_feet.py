"""Round feet placed at their sphere's lowest point in the stand pose, on the loaded robot.

A found foot that is a sphere, or a capsule's end (:class:`hexaleg.robot.feet.SphereFoot`),
touches the ground at its lowest point, which depends on the leg's posture. Once the robot is
loaded its foot frame is moved there for a given stand (:func:`place_sphere_feet`), repeated with
the stand solved again when the stand depends on the feet (:func:`settle_sphere_feet`): the foot
frame is then a fixed point of the link, where the ground is touched when standing.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np
import pinocchio as pin

from hexaleg.errors import RobotModelError
from hexaleg.robot.feet import SphereFoot
from hexaleg.robot.loaded import Robot


def place_sphere_feet(robot: Robot, q: np.ndarray) -> float:
    """Put each round foot's frame (:attr:`Robot.foot_spheres`) at its sphere's lowest point at
    ``q``.

    With the base at the origin, identity orientation, and ``R`` the last joint's rotation in
    the world at ``q``, the sphere's lowest point (its support point in −z) is
    ``c + r Rᵀ(−ẑ)`` in the joint frame (Ericson, *Real-Time Collision Detection*, 2005, §3.8).

    Args:
        robot: The robot (its model's foot frames are moved).
        q: The configuration, shape (nq,), e.g. the stand pose.

    Returns:
        The largest distance a foot frame moved, m.
    """
    model, data = robot.model, robot.data
    q = np.array(q, dtype=float)
    q[:7] = pin.neutral(model)[:7]
    pin.forwardKinematics(model, data, q)
    moved = 0.0
    for leg in robot.legs:
        sphere = robot.foot_spheres.get(leg.name)
        if sphere is None:
            continue
        down = np.asarray(data.oMi[sphere.joint].rotation).T @ np.array([0.0, 0.0, -1.0])
        point = sphere.centre + sphere.radius * down
        frame = model.frames[leg.foot_frame_id]
        moved = max(moved, float(np.linalg.norm(frame.placement.translation - point)))
        frame.placement = pin.SE3(np.eye(3), point)
        model.frames[leg.foot_frame_id] = frame
    return moved


SETTLE_TOLERANCE = 1e-9
"""m: the round feet are settled when no frame moves farther (:func:`settle_sphere_feet`)."""
SETTLE_ROUNDS = 20


def settle_sphere_feet(robot: Robot, stand: np.ndarray,
                       solve: Callable[[], np.ndarray] | None = None) -> tuple[np.ndarray, str]:
    """The round feet placed at their lowest points in the stand pose, and the stand.

    A stand given by joint angles does not depend on the foot frames: one placement. A stand
    solved for foot positions (``solve``, e.g. :func:`hexaleg.robot.stand.stand_from_feet`)
    does: it is solved again with the moved frames until no frame moves more than
    :data:`SETTLE_TOLERANCE` (a fixed point; each round moves the frame by ``r (1 − cos δ)`` for
    the change δ of the shank's tilt, so two or three rounds suffice).

    Returns:
        The stand, shape (nq,), and a note giving each round foot's contact point.

    Raises:
        RobotModelError: the placement does not settle in :data:`SETTLE_ROUNDS` rounds.
    """
    for _ in range(SETTLE_ROUNDS):
        moved = place_sphere_feet(robot, stand)
        if solve is None or moved <= SETTLE_TOLERANCE:
            break
        stand = solve()
    else:
        raise RobotModelError(f"{robot.name}: the round feet's lowest points did not settle in "
                              f"{SETTLE_ROUNDS} stand solves (last move {moved:.3g} m); give "
                              "the feet as frames or points on the links")
    return stand, sphere_note(robot, robot.foot_spheres)


def sphere_note(robot: Robot, spheres: Mapping[str, SphereFoot]) -> str:
    """Where each round foot touches the ground (its frame's point in its joint's frame)."""
    parts = []
    for leg in robot.legs:
        if leg.name in spheres:
            p = robot.model.frames[leg.foot_frame_id].placement.translation
            parts.append(f"{leg.name} [{', '.join(f'{v:+.4f}' for v in p)}]")
    return ("round feet touch the ground at their sphere's lowest point in the stand pose (m, "
            f"in the last joint's frame; a fixed point of the link while walking): "
            f"{', '.join(parts)}")


__all__ = ["SETTLE_ROUNDS", "SETTLE_TOLERANCE", "place_sphere_feet", "settle_sphere_feet",
           "sphere_note"]
