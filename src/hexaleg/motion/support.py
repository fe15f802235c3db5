"""Static stability of a gait: the CoM's margin inside the support polygon of the stance feet.

The support polygon is the convex hull of the stance feet's ground points (Andrew's monotone
chain); the static margin is the signed distance of the centre of mass's ground projection
inside it (McGhee & Frank, "On the stability properties of quadruped creeping gaits", Math.
Biosci. 3, 1968: the static stability margin).
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin

from hexaleg.robot.model import Robot


def support_margin(points: np.ndarray, c: np.ndarray) -> float:
    """Signed distance of ``c`` (2,) inside the convex hull of ``points`` (n, 2), m.

    Positive inside (distance to the nearest edge), negative outside; −inf for fewer than three
    points or a degenerate hull. Hull by Andrew's monotone chain.
    """
    pts = sorted(map(tuple, points))
    if len(pts) < 3:
        return -math.inf

    def cross(o: tuple, a: tuple, b: tuple) -> float:
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    hull: list[tuple] = []
    for seq in (pts, pts[::-1]):
        start = len(hull)
        for pt in seq:
            while len(hull) >= start + 2 and cross(hull[-2], hull[-1], pt) <= 0:
                hull.pop()
            hull.append(pt)
        hull.pop()
    if len(hull) < 3:
        return -math.inf
    dists = []
    for a, b in zip(hull, hull[1:] + hull[:1], strict=True):
        edge = math.hypot(b[0] - a[0], b[1] - a[1])
        dists.append(cross(a, b, tuple(c)) / edge)
    return min(dists)


def static_margins(robot: Robot, q: np.ndarray, feet: np.ndarray, stance: np.ndarray
                   ) -> np.ndarray:
    """The static margin of every sample: the CoM's ground projection inside the stance feet.

    Args:
        robot: The robot.
        q: Configurations, shape (T, nq).
        feet: World foot positions, shape (T, n_legs, 3), m.
        stance: Stance flags, shape (T, n_legs).

    Returns:
        Margins, shape (T,), m (:func:`support_margin`; −inf where fewer than three feet stand).
    """
    margins = np.full(len(q), -math.inf)
    data = robot.model.createData()
    for k in range(len(q)):
        com = pin.centerOfMass(robot.model, data, q[k])
        margins[k] = support_margin(feet[k, stance[k], :2], com[:2])
    return margins
