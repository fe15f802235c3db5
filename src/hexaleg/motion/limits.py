"""The limits every sampled motion respects: the fewest samples, and the joints' position limits.

Both checks raise :class:`~hexaleg.errors.InvalidParameterError` naming the parameter (or joint),
the bad value and what is allowed; single numbers are checked with :mod:`hexaleg.checks`.
"""

from __future__ import annotations

import numpy as np

from hexaleg.checks import is_integer
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.model import Robot

MIN_SAMPLES = 20
"""Fewest samples per period (or per motion) a motion may have."""


def check_samples(samples: object) -> int:
    """The number of samples of a motion as an int, at least :data:`MIN_SAMPLES`.

    Raises:
        InvalidParameterError: not an integer, or fewer than :data:`MIN_SAMPLES`.
    """
    if not is_integer(samples) or samples < MIN_SAMPLES:
        raise InvalidParameterError("samples", samples, f"an integer ≥ {MIN_SAMPLES}")
    return int(samples)


def check_joint_limits(robot: Robot, q: np.ndarray, t: np.ndarray) -> None:
    """Raise at the first sample where a joint of ``q`` (T, nq) leaves the model's limits.

    Args:
        robot: The robot (its Pinocchio model's position limits).
        q: Configurations, shape (T, nq), free-flyer base first.
        t: Sample times, shape (T,), s (for the message).

    Raises:
        InvalidParameterError: names the joint, the angle, the time and the limits.
    """
    lo, hi = robot.model.lowerPositionLimit[7:], robot.model.upperPositionLimit[7:]
    bad = (q[:, 7:] < lo) | (q[:, 7:] > hi)
    if bad.any():
        k, j = (int(i) for i in np.argwhere(bad)[0])
        raise InvalidParameterError(
            f"trajectory of joint {robot.joint_names[j]}", f"{q[k, 7 + j]:.4f} rad at t = "
            f"{t[k]:.6g} s", f"angles within the joint limits [{lo[j]:.4f}, {hi[j]:.4f}] rad")
