"""The ground a gait walks on: a plane inclined along and across the walking direction, and the
body's attitude over it (``GaitParams.slope``, ``cross_slope``, ``attitude``).

In the *walking frame* (x the walking direction h in the base frame at t = 0, y = ẑ × h to its
left, z up) the ground is the plane through the origin ``z = x tan α + y tan β`` (α the slope,
positive uphill; β the cross slope, positive when the ground rises to the left). Its unit normal
is ``n ∝ (−tan α, −tan β, 1)``, its steepest inclination γ has ``tan γ = √(tan² α + tan² β)``
(``cos γ = n_z``), and the walking direction on it, ``d ∝ (1, 0, tan α)``, climbs at exactly α
(the gradient of a plane: Apostol, *Calculus* vol. II, 1969, §8.14).

The **ground frame** G has ``x_G = d``, ``z_G = n``, ``y_G = n × d``; :attr:`Ground.rotation`
``R = Q [d, n × d, n] Qᵀ`` (Q = [h, ẑ × h, ẑ]) takes G coordinates to world coordinates, whose
horizontal axes are the base's at t = 0 on level ground. A gait is generated in G exactly as on
level ground (the base moving along the walking direction at its height above the plane, the
stance feet on z_G = 0, the swing lifting along z_G: clearance above the plane) and mapped to
the world by R; LOCAL base velocities do not change under that map. On the world's ground
gravity is −g ẑ as always, so climbing costs what it should.

Attitudes: ``"plane"`` — the body parallel to the ground (its attitude in G is the yaw alone,
``Rz(ψ)``; ``body_height`` along n); ``"level"`` — the body level in the world (its attitude in
G is :attr:`Ground.tilt` ``= Rᵀ``, so ``R Rz(0) Rᵀ = I``; ``body_height`` measured vertically, the
base ``h cos γ`` from the plane along n; each foothold sits on the plane below its horizontal
place, :func:`level_footholds`). Level ground (α = β = 0) is no :class:`Ground` at all: the
generators skip every rotation, so level gaits stay bit-for-bit what they were.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from hexaleg.errors import InvalidParameterError


@dataclass(frozen=True, eq=False)
class Ground:
    """An inclined ground plane through the world origin and the body's attitude over it.

    Attributes:
        slope: α, rad, along the walking direction (positive uphill).
        cross_slope: β, rad, across it (positive: rising to the left).
        attitude: ``"plane"`` or ``"level"``.
        rotation: R, ground frame → world, shape (3, 3) (module docstring).
        tilt: The base's attitude in the ground frame at zero yaw, shape (3, 3): the identity
            (``"plane"``) or Rᵀ (``"level"``).
        walking: Q, the walking frame's axes [h, ẑ × h, ẑ] as columns, base frame, (3, 3).
    """

    slope: float
    cross_slope: float
    attitude: str
    rotation: np.ndarray
    tilt: np.ndarray
    walking: np.ndarray

    @property
    def normal(self) -> np.ndarray:
        """The plane's unit normal in the world frame, shape (3,)."""
        return self.rotation[:, 2].copy()

    @property
    def steepness(self) -> float:
        """γ, the plane's steepest inclination, rad: ``tan γ = √(tan² α + tan² β)``."""
        return math.atan(math.hypot(math.tan(self.slope), math.tan(self.cross_slope)))

    def quaternions(self, yaw: np.ndarray) -> np.ndarray:
        """The base orientation ``R Rz(ψ) C`` (C = :attr:`tilt`) as unit quaternions (x, y, z, w),
        shape (N, 4): the Hamilton product of the constant ones and ``(0, 0, sin ψ/2, cos ψ/2)``
        (no sign flips between samples)."""
        q_r = pin.Quaternion(self.rotation).coeffs()
        q_c = pin.Quaternion(self.tilt).coeffs()
        q_z = np.zeros((len(yaw), 4))
        q_z[:, 2], q_z[:, 3] = np.sin(yaw / 2), np.cos(yaw / 2)
        return _product(_product(np.broadcast_to(q_r, q_z.shape), q_z),
                        np.broadcast_to(q_c, q_z.shape))

    def base_distance(self, body_height: float) -> float:
        """The base's distance from the plane along its normal, m, for ``body_height``
        (along n for ``"plane"``; vertical for ``"level"``: ``h cos γ``)."""
        return body_height if self.attitude == "plane" else body_height * math.cos(self.steepness)


def _product(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Hamilton product of quaternions (x, y, z, w), row by row, shape (N, 4)."""
    ax, ay, az, aw = a.T
    bx, by, bz, bw = b.T
    return np.stack([aw * bx + ax * bw + ay * bz - az * by,
                     aw * by - ax * bz + ay * bw + az * bx,
                     aw * bz + ax * by - ay * bx + az * bw,
                     aw * bw - ax * bx - ay * by - az * bz], axis=1)


def ground_plane(slope: float, cross_slope: float, attitude: str, direction: np.ndarray
                 ) -> Ground | None:
    """The inclined ground of a gait, or None on level ground (α = β = 0).

    Args:
        slope: α, rad, in (−π/2, π/2), positive uphill along the walking direction.
        cross_slope: β, rad, in (−π/2, π/2), positive rising to the left.
        attitude: ``"plane"`` or ``"level"``.
        direction: The walking direction h, a horizontal unit vector in the base frame, (3,).

    Returns:
        The ground (module docstring), or None.

    Raises:
        InvalidParameterError: an angle outside (−π/2, π/2).
    """
    if slope == 0.0 and cross_slope == 0.0:
        return None
    for name, value in (("slope", slope), ("cross_slope", cross_slope)):
        if not abs(value) < math.pi / 2:
            raise InvalidParameterError(name, value, "an angle in (−π/2, π/2) rad")
    ta, tb = math.tan(slope), math.tan(cross_slope)
    n = np.array([-ta, -tb, 1.0]) / math.sqrt(1.0 + ta * ta + tb * tb)
    d = np.array([1.0, 0.0, ta]) / math.sqrt(1.0 + ta * ta)
    frame = np.column_stack([d, np.cross(n, d), n])  # ground frame in walking coordinates
    h = np.array([direction[0], direction[1], 0.0]) / math.hypot(direction[0], direction[1])
    q = np.column_stack([h, np.cross([0.0, 0.0, 1.0], h), [0.0, 0.0, 1.0]])
    rotation = q @ frame @ q.T
    tilt = np.eye(3) if attitude == "plane" else rotation.T.copy()
    return Ground(float(slope), float(cross_slope), attitude, rotation, tilt, q)


def level_footholds(ground: Ground, feet: np.ndarray, body_height: float) -> np.ndarray:
    """Footholds in the base frame of a level body above the plane (``attitude = "level"``).

    Each foot keeps its horizontal place (x, y) relative to the base and sits on the plane
    below it: ``z = −h + x_w tan α + y_w tan β``, with (x_w, y_w) its place along and to the left
    of the walking direction and h the base's vertical height above the plane.

    Args:
        ground: The ground.
        feet: Footholds, shape (n_legs, 3), base frame (z is replaced).
        body_height: h, m.

    Returns:
        The footholds, shape (n_legs, 3).
    """
    out = np.array(feet, dtype=float)
    along, left = out @ ground.walking[:, 0], out @ ground.walking[:, 1]
    out[:, 2] = -body_height + along * math.tan(ground.slope) + left * math.tan(ground.cross_slope)
    return out
