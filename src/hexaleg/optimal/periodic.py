"""Periodicity: the final state is the first one moved by the cycle's displacement.

A periodic gait repeats up to a rigid displacement of the world, the cycle's ``H ∈ SE(3)`` (a
stride along the heading on level ground; the motion's ``info["cycle"]`` where the gait wrote
it). The state after one cycle is the first with the base placement left-multiplied by ``H``
(``oM_b(T) = H · oM_b(0)``); the joints' angles, and the base velocity — expressed in the base
frame, Pinocchio's convention — are unchanged. Crocoddyl fixes the initial state of a shooting
problem, so the condition enters as a terminal cost ``½ w ‖x_N ⊖ H·x_0‖²`` (``⊖`` the state
manifold's difference, Crocoddyl's ``ResidualModelState``), driven to zero by a large weight;
how far from zero it ends is reported (``periodicity_gap``).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pinocchio as pin

from hexaleg.errors import InvalidParameterError
from hexaleg.motion.trajectory import Motion


def cycle_displacement(motion: Motion) -> np.ndarray:
    """The cycle's rigid displacement ``H`` (4, 4): ``motion.info["cycle"]`` if the motion
    states it, else ``motion.distance`` along its ``info["direction"]`` (x when none).

    Raises:
        InvalidParameterError: the motion is not periodic, or its cycle is not a rigid transform.
    """
    if not motion.periodic:
        raise InvalidParameterError("motion.periodic", motion.periodic,
                                    "a periodic motion (an optimal gait repeats its cycle)")
    if "cycle" in motion.info:
        h = np.asarray(motion.info["cycle"], dtype=float)
        r = h[:3, :3] if h.shape == (4, 4) else np.zeros((3, 3))
        if not np.allclose(r @ r.T, np.eye(3), atol=1e-9) or not np.isfinite(h).all():
            raise InvalidParameterError("motion.info['cycle']", h.tolist(),
                                        "a 4 × 4 rigid transform")
        return h
    direction = np.asarray(motion.info.get("direction", (1.0, 0.0, 0.0)), dtype=float)
    h = np.eye(4)
    h[:3, 3] = motion.distance * direction / np.linalg.norm(direction)
    return h


def shifted_state(x: np.ndarray, displacement: np.ndarray) -> np.ndarray:
    """State ``x`` (nq + nv,) with its free-flyer placement moved by ``displacement`` (4, 4)."""
    base = pin.XYZQUATToSE3(x[:7])
    moved = pin.SE3(displacement[:3, :3], displacement[:3, 3]) * base
    out = np.array(x, dtype=float)
    out[:7] = pin.SE3ToXYZQUAT(moved)
    return out


def periodicity_gap(xs: list[np.ndarray] | np.ndarray, displacement: np.ndarray,
                    difference: Callable[[np.ndarray, np.ndarray], np.ndarray]) -> float:
    """``‖x_N ⊖ H·x_0‖∞`` of a trajectory, ``difference(a, b)`` the state manifold's ``b ⊖ a``
    (Crocoddyl's ``state.diff``); rad, m, rad/s and m/s mixed, as in the terminal cost."""
    x0, xn = np.asarray(xs[0]), np.asarray(xs[-1])
    target = shifted_state(x0, displacement)
    return float(np.max(np.abs(difference(target, xn))))
