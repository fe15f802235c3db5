"""Static stability of a gait: the CoM's margin inside the support polygon of the stance feet.

The support polygon is the convex hull of the stance feet's ground points (Andrew's monotone
chain); the static margin is the signed distance of the centre of mass's ground projection
inside it (McGhee & Frank, "On the stability properties of quadruped creeping gaits", Math.
Biosci. 3, 1968: the static stability margin). Across a change of stance the CoM must be inside
the polygons before and after it (:func:`switch_margin`, what the body shift of
:mod:`hexaleg.motion.shift` keeps).
"""

from __future__ import annotations

import math

import numpy as np
import pinocchio as pin

from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot


def _cross(o: tuple, a: tuple, b: tuple) -> float:
    """z of (a − o) × (b − o): > 0 when o → a → b turns counter-clockwise."""
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])


def _hull(points: np.ndarray) -> list[tuple]:
    """The convex hull of ``points`` (n, 2), counter-clockwise, by Andrew's monotone chain
    (pure Python: a support polygon has a handful of points); fewer than three vertices for
    fewer than three points or a degenerate hull."""
    pts = sorted(map(tuple, points))
    if len(pts) < 3:
        return []
    hull: list[tuple] = []
    for seq in (pts, pts[::-1]):
        start = len(hull)
        for pt in seq:
            while len(hull) >= start + 2 and _cross(hull[-2], hull[-1], pt) <= 0:
                hull.pop()
            hull.append(pt)
        hull.pop()
    return hull


def support_margin(points: np.ndarray, c: np.ndarray) -> float:
    """Signed distance of ``c`` (2,) inside the convex hull of ``points`` (n, 2), m.

    Positive inside (distance to the nearest edge), negative outside; −inf for fewer than three
    points or a degenerate hull. Hull by Andrew's monotone chain.
    """
    hull = _hull(points)
    if len(hull) < 3:
        return -math.inf
    dists = []
    for a, b in zip(hull, hull[1:] + hull[:1], strict=True):
        edge = math.hypot(b[0] - a[0], b[1] - a[1])
        dists.append(_cross(a, b, tuple(c)) / edge)
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


def polygon_edges(points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The edges of the convex hull of ``points`` (n, 2) as half-planes ``ν · x ≥ b``.

    Returns:
        ν (E, 2) inward unit normals and b (E,) (Andrew's monotone chain, counter-clockwise;
        E = 0 for fewer than three points or a degenerate hull).
    """
    hull = _hull(np.asarray(points, dtype=float))
    if len(hull) < 3:
        return np.zeros((0, 2)), np.zeros(0)
    a = np.array(hull)
    edge = np.roll(a, -1, axis=0) - a
    normal = np.stack([-edge[:, 1], edge[:, 0]], axis=1) / np.linalg.norm(edge, axis=1)[:, None]
    return normal, np.einsum("ij,ij->i", normal, a)


Edges = list[tuple[int, np.ndarray, np.ndarray]]
"""``(k, ν, b)``: sample k must be inside the half-planes ``ν · x ≥ b`` (:func:`polygon_edges`)."""


class SupportCycle:
    """A periodic gait's cycle grid and its end: sample N is sample 0 one cycle later, moved by
    the rigid motion of one cycle (``motion.info["cycle"]``, 4 × 4, world), so that the last
    interval [t_N−1, T] is checked like the others.

    Attributes:
        cycle: The rigid motion of one cycle, (4, 4).
        stance: Stance flags at the N + 1 samples, (N+1, n_legs).
        feet: World feet at the N + 1 samples, (N+1, n_legs, 3), m.
    """

    def __init__(self, motion: Motion) -> None:
        self.cycle = np.asarray(motion.info.get("cycle", np.eye(4)), dtype=float)
        rot, shift = self.cycle[:3, :3], self.cycle[:3, 3]
        self.stance = np.vstack([motion.stance, motion.stance[:1]])
        self.feet = np.concatenate([motion.feet, (motion.feet[:1] @ rot.T) + shift])

    def points(self, x: np.ndarray, vectors: bool = False) -> np.ndarray:
        """World points (``vectors``: free vectors) at the N samples, (N, 3) → (N+1, 3)."""
        end = self.cycle[:3, :3] @ x[0] + (0.0 if vectors else self.cycle[:3, 3])
        return np.vstack([x, end])

    def polygons(self) -> Edges:
        """The support polygons the CoM must be in at each of the N + 1 samples: sample k's own,
        and where the stance changes between k and k + 1 each end's polygon at the other end
        too (E = 0 entries: fewer than three feet)."""
        n = len(self.stance)
        own = [polygon_edges(self.feet[k, self.stance[k], :2]) for k in range(n)]
        out = [(k, *own[k]) for k in range(n)]
        for k in range(n - 1):
            if not np.array_equal(self.stance[k], self.stance[k + 1]):
                out += [(k + 1, *own[k]), (k, *own[k + 1])]
        return out


def edge_margin(edges: Edges, xy: np.ndarray) -> float:
    """The smallest margin of points ``xy`` (N+1, 2) inside the polygons each sample must be in
    (:meth:`SupportCycle.polygons`), m; −inf where a sample has no polygon."""
    return min(float((nu @ xy[k] - b).min()) if len(b) else -math.inf for k, nu, b in edges)


def switch_margin(robot: Robot, motion: Motion) -> float:
    """The static margin across switches, m: the CoM's smallest margin over the cycle inside
    every support polygon it must be in at each sample — its own and, across a change of
    stance, the neighbour's (before and after the switch, at both ends of the sample interval
    holding it; the polygons being convex, the chord between the ends is inside both). At most
    the per-sample margin (:func:`static_margins`): the default tripod has 0.0815 m per sample
    and 0.0813 m across its switches (the CoM moves 0.3 mm a sample at 200 samples); a crawl
    at β = ¾ hands one triangle to the next on their shared diagonal and has none."""
    grid = SupportCycle(motion)
    data = robot.model.createData()
    com = np.array([pin.centerOfMass(robot.model, data, q) for q in motion.q])
    return edge_margin(grid.polygons(), grid.points(com)[:, :2])
