"""Which feet are on the ground: from the log's contact columns, or from the feet's motion.

Without contact sensors a foot is in stance where it is both low and still relative to the
ground the stance feet define: its height above the lowest foot of its sample below ``h_c`` and
its speed relative to the median velocity of the low feet below ``v_c`` (the kinematic contact
detection of leg odometry, e.g. Bloesch et al., "State estimation for legged robots", RSS 2012,
§IV, with thresholds instead of a filter). The thresholds are chosen from the data and reported:
each the larger of :data:`SNR` × the quantity's noise level and :data:`FRACTION` of its 98th
percentile over the cycle (the swing's height and speed).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

SNR = 4.0
"""Thresholds at least this many times the noise level of foot height and speed."""
FRACTION = 0.01
MIN_RUN = 0.05
"""Runs of stance or swing shorter than this fraction of the samples are flicker at a touch-down
or lift-off (a run-length filter): swing gaps are filled, then stance blips removed."""
"""Thresholds at least this fraction of the swing's height and speed (98th percentiles)."""


@dataclass(frozen=True)
class Stance:
    """Stance flags and how they were found.

    Attributes:
        stance: Feet in stance, shape (T, n_legs), bool.
        source: ``"contacts"`` (the log's contact columns) or ``"kinematics"``.
        height: The height threshold h_c, m (None from contacts).
        speed: The speed threshold v_c, m/s (None from contacts).
    """

    stance: np.ndarray
    source: str
    height: float | None = None
    speed: float | None = None

    @property
    def fractions(self) -> np.ndarray:
        """Fraction of the samples each foot is in stance, shape (n_legs,)."""
        return self.stance.mean(axis=0)


def from_contacts(contacts: np.ndarray) -> Stance:
    """Stance from contact columns (T, n_legs) of 0/1 values (or their cycle averages: a foot
    is in stance where more than half the cycles had it down)."""
    return Stance(stance=np.asarray(contacts, dtype=float) > 0.5, source="contacts")


def detect(feet: np.ndarray, feet_velocity: np.ndarray, *, noise_height: float = 0.0,
           noise_speed: float = 0.0) -> Stance:
    """Stance from the feet's positions and velocities (module docstring).

    Args:
        feet: Foot positions, shape (T, n_legs, 3), m, in a frame whose z is about the ground's
            normal (the world, or the base frame of a level-walking body).
        feet_velocity: Their time derivatives in the same frame, shape (T, n_legs, 3), m/s.
        noise_height: Noise level of a foot's height, m.
        noise_speed: Noise level of a foot's speed, m/s; 0: estimated from the low feet's
            speeds (a still foot's measured speed follows a Maxwell distribution of median
            1.538 σ for noise σ per axis).

    Returns:
        The stance flags and the thresholds used.
    """
    z = feet[..., 2]
    height = z - z.min(axis=1, keepdims=True)
    h_c = max(SNR * noise_height, FRACTION * float(np.percentile(height, 98)), 1e-9)
    low = height < h_c
    ground_velocity = np.zeros((feet.shape[0], 3))
    for k in range(feet.shape[0]):
        ground_velocity[k] = np.median(feet_velocity[k, low[k]], axis=0)
    speed = np.linalg.norm(feet_velocity - ground_velocity[:, None], axis=2)
    if not noise_speed and low.any():  # a still foot's noise speed is Maxwell-distributed:
        noise_speed = float(np.median(speed[low])) / 1.538  # median 1.538 σ
    v_c = max(SNR * noise_speed, FRACTION * float(np.percentile(speed, 98)), 1e-9)
    stance = _fill_short_runs(low & (speed < v_c), max(2, round(MIN_RUN * len(feet))))
    lost = ~stance.any(axis=1)  # no foot still: the low feet carry the robot, or the lowest
    stance[lost] = low[lost]
    stance[lost & ~low.any(axis=1), np.argmin(height[lost & ~low.any(axis=1)], axis=1)] = True
    return Stance(stance=stance, source="kinematics", height=h_c, speed=v_c)


def _fill_short_runs(flags: np.ndarray, shortest: int) -> np.ndarray:
    """``flags`` (T, n) with each column's runs of False, then of True, shorter than
    ``shortest`` samples flipped (runs that touch the ends kept)."""
    out = flags.copy()
    for value in (False, True):
        for j in range(out.shape[1]):
            col = out[:, j]
            edges = np.flatnonzero(np.diff(col.astype(np.int8))) + 1
            bounds = np.concatenate([[0], edges, [len(col)]])
            for lo, hi in itertools.pairwise(bounds):
                if col[lo] == value and hi - lo < shortest and lo > 0 and hi < len(col):
                    col[lo:hi] = not value
    return out
