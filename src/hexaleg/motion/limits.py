"""The limits every sampled motion respects: the fewest samples, and the joints' position limits.

Both checks raise :class:`~hexaleg.errors.InvalidParameterError` naming the parameter (or joint),
the bad value and what is allowed; single numbers are checked with :mod:`hexaleg.checks`.
"""

from __future__ import annotations

import numpy as np

from hexaleg.checks import MEMORY_BUDGET, count
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.model import Robot

MIN_SAMPLES = 20
"""Fewest samples per period (or per motion) a motion may have."""
SAMPLE_BYTES = 32 * 1024
"""Memory one sample of a motion costs through its analysis (motion, RNEA, Jacobians, stance
system, forces, metrics), B: about 14 kB on the 24-DoF hexapod (growth of the tracemalloc peak
of ``tripod_gait`` + ``prepare`` + ``evaluate`` from 200 to 600 samples; the test checks it stays
below this bound), with a margin for larger robots."""
MAX_SAMPLES = MEMORY_BUDGET // SAMPLE_BYTES
"""Most samples per period (or per motion): :data:`hexaleg.checks.MEMORY_BUDGET` over
:data:`SAMPLE_BYTES`."""


def check_samples(samples: object, name: str = "samples") -> int:
    """The number of samples of a motion as an int in [:data:`MIN_SAMPLES`,
    :data:`MAX_SAMPLES`].

    Args:
        samples: The value given.
        name: The parameter's name, for the error.

    Raises:
        InvalidParameterError: not an integer (a bool or float included), fewer than
            :data:`MIN_SAMPLES`, or more than :data:`MAX_SAMPLES` (the message says how that
            bound follows from memory).
    """
    return count(name, samples, item_bytes=SAMPLE_BYTES, item="one sample",
                 low=MIN_SAMPLES, fix="use fewer samples per period")


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
