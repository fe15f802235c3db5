"""Which feet are on the ground: from the log's planned stance, its contact columns, or from the
feet's motion.

A planned stance (``stance_<LEG>`` columns: a planner's, as hexaleg writes a motion) is the
stance as it is (:func:`from_plan`): it says which feet carry the motion, so nothing in the
feet's motion overrides it. Contact switches say which feet touch (:func:`from_contacts`).

Without contact sensors stance is found in two steps.

1. **Low and still.** A foot is a stance candidate where it is both low and still relative to the
   ground the stance feet define: its height above the lowest foot of its sample below ``h_c``
   and its speed relative to the median velocity of the low feet below ``v_c`` (the kinematic
   contact detection of leg odometry, e.g. Bloesch et al., "State estimation for legged robots",
   RSS 2012, §IV, with thresholds instead of a filter). The thresholds are chosen from the data
   and reported: each the larger of :data:`SNR` × the quantity's noise level and
   :data:`FRACTION` of its 98th percentile over the cycle (the swing's height and speed).
2. **The edges: what the body needs.** A foot that leaves and meets the ground gently stays
   within the noise of it for a few samples after lift-off and before touch-down, so step 1
   counts those samples as stance (3–4 samples an edge at 100 Hz in a Dynamixel log of
   hexaleg's tripod, the energy 7 % low: each stance sample too many shares the load between
   more feet). Each swing's lift-off t₀ and touch-down t₁ are found instead from where the foot
   is clearly up (h ≥ h_c): its height is fitted by least squares with a symmetric bump of order
   p, ``h = A (4 s (1 − s))ᵖ`` with ``s = (t − t₀)/(t₁ − t₀)`` (A, t₀, t₁ and p free; p = 1 a
   parabola that lands with a speed, p = 4 hexaleg's swing that leaves and lands at rest with
   zero acceleration and jerk, :func:`~hexaleg.motion.profiles.swing_bump`). Step 1's stance
   candidates inside [t₀, t₁) are the edge band; there a foot is in swing unless the body
   needs it: band feet are taken off the ground, the deepest inside their fitted swing first,
   while the centre of mass stays inside the support polygon of the feet left down by at least
   :data:`MARGIN` of its margin with all candidates down (the static stability margin: McGhee
   & Frank, "On the stability properties of quadruped creeping gaits", Math. Biosci. 3, 1968;
   :func:`~hexaleg.motion.support.support_margin`), so a fit that misses the swing's shape
   cannot leave the body unsupported. A step-1 swing run outside its fitted swing is flicker of
   a foot on the ground (stance).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from hexaleg.motion.support import support_margin

SNR = 4.0
"""Thresholds at least this many times the noise level of foot height and speed."""
FRACTION = 0.01
"""Thresholds at least this fraction of the swing's height and speed (98th percentiles)."""
MIN_RUN = 0.05
"""Runs of stance or swing shorter than this fraction of the samples are flicker at a touch-down
or lift-off (a run-length filter): swing gaps are filled, then stance blips removed."""
MARGIN = 0.5
"""Band feet are lifted only while the feet left down keep the centre of mass at least this
fraction of its static margin with every candidate down (a margin near 0 balances the body on
an edge, e.g. two feet across it, which the dynamics cannot carry)."""
MIN_FIT = 6
"""Fewest samples with h ≥ h_c a swing needs for its edges to be fitted (step 2)."""


@dataclass(frozen=True)
class Stance:
    """Stance flags and how they were found.

    Attributes:
        stance: Feet in stance, shape (T, n_legs), bool.
        source: ``"plan"`` (the log's stance columns), ``"contacts"`` (its contact columns) or
            ``"kinematics"``.
        height: The height threshold h_c, m (None from contacts).
        speed: The speed threshold v_c, m/s (None from contacts).
        touch: Feet on the ground, carrying load or not, shape (T, n_legs), bool: step 1's low
            and still feet (kinematics; a superset of ``stance`` by the edge bands step 2 lifts,
            where a gentle foot touches before it takes its share and after it gave it up); the
            stance itself from contacts.
    """

    stance: np.ndarray
    source: str
    height: float | None = None
    speed: float | None = None
    touch: np.ndarray | None = None

    @property
    def fractions(self) -> np.ndarray:
        """Fraction of the samples each foot is in stance, shape (n_legs,)."""
        return self.stance.mean(axis=0)

    @property
    def touch_fractions(self) -> np.ndarray:
        """Fraction of the samples each foot touches the ground, shape (n_legs,)."""
        return (self.stance if self.touch is None else self.touch).mean(axis=0)


def from_plan(columns: np.ndarray) -> Stance:
    """Stance from planned stance columns (T, n_legs) of 0/1 values (or their cycle averages: a
    foot stands where more than half the cycles had it down), as they are (module docstring)."""
    return Stance(stance=np.asarray(columns, dtype=float) > 0.5, source="plan")


def from_contacts(contacts: np.ndarray, feet: np.ndarray | None = None,
                  com: np.ndarray | None = None, *, periodic: bool = True,
                  noise_height: float = 0.0) -> Stance:
    """Stance from contact columns (T, n_legs) of 0/1 values (or their cycle averages: a foot
    touches where more than half the cycles had it down).

    A contact switch says a foot touches, not that it carries its share: on a soft ground a
    gentle foot touches while its height still follows its swing, tens of ms before it takes
    the load (a MuJoCo walk of hexaleg's tripod: touch 0.57 of the cycle, the energy 6 % low
    with every touching foot sharing the load). With the feet's positions given, step 2 of the
    module docstring runs on the switches: within a foot's fitted swing a touching foot is in
    stance only where the body needs it. A foot the switches have in swing stays in swing.

    Args:
        contacts: The contact columns, shape (T, n_legs).
        feet: Foot positions, shape (T, n_legs, 3), as for :func:`detect`; None: the
            switches as the stance.
        com: The centre of mass, shape (T, 3), as for :func:`detect`.
        periodic: Whether sample T is sample 0 again.
        noise_height: Noise level of a foot's height, m.
    """
    touch = np.asarray(contacts, dtype=float) > 0.5
    if feet is None or com is None:
        return Stance(stance=touch, source="contacts")
    height = feet[..., 2] - feet[..., 2].min(axis=1, keepdims=True)
    h_c = max(SNR * noise_height, FRACTION * float(np.percentile(height, 98)), 1e-9)
    depth = _edge_bands(touch.copy(), height, h_c, periodic)
    return Stance(stance=_needed(touch, depth, feet, com), source="contacts", touch=touch)


def detect(feet: np.ndarray, feet_velocity: np.ndarray, com: np.ndarray, *,
           periodic: bool, noise_height: float = 0.0, noise_speed: float = 0.0) -> Stance:
    """Stance from the feet's positions and velocities (module docstring).

    Args:
        feet: Foot positions, shape (T, n_legs, 3), m, in a frame whose z is about the ground's
            normal (the world, or the base frame of a level-walking body).
        feet_velocity: Their time derivatives in the same frame, shape (T, n_legs, 3), m/s.
        com: The centre of mass in the same frame, shape (T, 3), m.
        periodic: Whether sample T is sample 0 again (a swing may run across the end).
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
    relative = feet_velocity - ground_velocity[:, None]
    speed = np.linalg.norm(relative, axis=2)
    if not noise_speed and low.any():  # a still foot's noise speed is Maxwell-distributed:
        noise_speed = float(np.median(speed[low])) / 1.538  # median 1.538 σ
    v_c = max(SNR * noise_speed, FRACTION * float(np.percentile(speed, 98)), 1e-9)
    stance = _fill_short_runs(low & (speed < v_c), max(2, round(MIN_RUN * len(feet))))
    depth = _edge_bands(stance, height, h_c, periodic)
    touch = stance.copy()
    stance = _needed(stance, depth, feet, com)
    lost = ~stance.any(axis=1)  # no foot still: the low feet carry the robot, or the lowest
    stance[lost] = low[lost]
    stance[lost & ~low.any(axis=1), np.argmin(height[lost & ~low.any(axis=1)], axis=1)] = True
    return Stance(stance=stance, source="kinematics", height=h_c, speed=v_c,
                  touch=touch | stance)


def _runs(flags: np.ndarray, periodic: bool) -> list[tuple[int, int]]:
    """The runs of True in ``flags`` (T,) as (first, last) indices; with ``periodic`` a run
    across the end is one run (its last index then below its first)."""
    n = len(flags)
    if flags.all() or not flags.any():
        return []
    starts = [k for k in range(n) if flags[k] and not flags[k - 1] and (periodic or k > 0)]
    starts += [0] if not periodic and flags[0] else []
    runs = []
    for a in sorted(starts):
        b = a
        while flags[(b + 1) % n] and (periodic or b + 1 < n):
            b = (b + 1) % n if periodic else b + 1
        runs.append((a, b))
    return runs


def _edge_bands(stance: np.ndarray, height: np.ndarray, h_c: float, periodic: bool
                ) -> np.ndarray:
    """How deep each stance candidate lies inside its foot's fitted swing, samples
    (T, n_legs), NaN outside the edge bands (module docstring, step 2); ``stance`` (T, n_legs)
    is set where a swing run of step 1 lies outside its fitted swing."""
    n, legs = stance.shape
    depth = np.full((n, legs), np.nan)
    for j in range(legs):
        for a, b in _runs(~stance[:, j], periodic):
            lo = a - (n if periodic and b < a else 0)  # the run unwrapped: lo … b
            t = np.arange(lo - (b - lo + 1), b + (b - lo + 1) + 1)  # the run and its sides
            if not periodic:
                t = t[(t >= 0) & (t < n)]
            h = height[t % n, j]
            up = (h >= h_c) & (t >= lo) & (t <= b)
            if up.sum() < MIN_FIT:
                continue
            t0, t1 = _fit_swing(t[up].astype(float), h[up])
            inside = (t >= t0) & (t < t1)
            stance[t[~inside & (t >= lo) & (t <= b)] % n, j] = True  # flicker: on the ground
            for m in t[inside & stance[t % n, j]]:
                depth[m % n, j] = min(m - t0, t1 - m)
    return depth


def _fit_swing(t: np.ndarray, h: np.ndarray) -> tuple[float, float]:
    """Lift-off and touch-down (t₀, t₁), samples, of the bump ``A (4 s (1 − s))ᵖ`` fitted to
    the heights ``h`` (N,) at samples ``t`` (N,) of one swing (module docstring, step 2)."""
    span = float(t[-1] - t[0])

    def residual(x: np.ndarray) -> np.ndarray:
        amplitude, t0, t1, p = x
        s = np.clip((t - t0) / (t1 - t0), 0.0, 1.0)
        return amplitude * (4.0 * s * (1.0 - s)) ** p - h

    from scipy.optimize import least_squares  # here: scipy.optimize costs every command ~1 s

    x0 = [float(h.max()), t[0] - 0.1 * span, t[-1] + 0.1 * span, 2.0]
    fit = least_squares(residual, x0, bounds=([0.0, t[0] - span, t[-1], 0.5],
                                              [np.inf, t[0], t[-1] + span, 8.0]))
    return float(fit.x[1]), float(fit.x[2])


def _needed(stance: np.ndarray, depth: np.ndarray, feet: np.ndarray, com: np.ndarray
            ) -> np.ndarray:
    """``stance`` with the edge-band feet lifted, deepest first, while the centre of mass stays
    :data:`MARGIN` of its margin inside the support polygon of the feet left down (module
    docstring, step 2)."""
    out = stance.copy()
    for k in np.flatnonzero(~np.isnan(depth).all(axis=1)):
        least = MARGIN * support_margin(feet[k, out[k], :2], com[k, :2])
        for j in np.argsort(-np.nan_to_num(depth[k], nan=-np.inf)):
            if np.isnan(depth[k, j]):
                break
            out[k, j] = False
            if not support_margin(feet[k, out[k], :2], com[k, :2]) >= max(least, 0.0):
                out[k, j] = True
    return out


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
