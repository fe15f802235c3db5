"""The joint colour scale of the viewer: a diverging cool-warm map split into N_LEVELS bins.

Source: the diverging cool-warm colour map of K. Moreland, "Diverging Color Maps for Scientific
Visualization", ISVC 2009 (its end and mid colours, interpolated linearly in RGB).
"""

from __future__ import annotations

import numpy as np

N_LEVELS = 11
"""Number of colour bins of the joint markers (odd, so that the middle bin is centred on 0)."""

_COOL = np.array([0.230, 0.299, 0.754])
_NEUTRAL = np.array([0.865, 0.865, 0.865])
_WARM = np.array([0.706, 0.016, 0.150])


def cool_warm(x: np.ndarray) -> np.ndarray:
    """Diverging cool-warm colour map (Moreland 2009), linear in RGB between its three anchors.

    Args:
        x: Positions in the map, any shape, clipped to [0, 1]; 0 is blue, 0.5 neutral grey,
            1 red.

    Returns:
        RGB colours in [0, 1], shape ``x.shape + (3,)``.
    """
    x = np.clip(np.asarray(x, dtype=float), 0.0, 1.0)[..., None]
    lower = _COOL + (_NEUTRAL - _COOL) * (2 * x)
    upper = _NEUTRAL + (_WARM - _NEUTRAL) * (2 * x - 1)
    return np.where(x <= 0.5, lower, upper)


def colours() -> np.ndarray:
    """The colour of each bin: the cool-warm map at the bins' centres.

    Returns:
        RGB colours in [0, 1], shape (N_LEVELS, 3); bin 0 blue, the middle bin grey.
    """
    return cool_warm((np.arange(N_LEVELS) + 0.5) / N_LEVELS)


def value_bins(values: np.ndarray, vmax: float) -> np.ndarray:
    """Colour bin of each value on the symmetric scale [−vmax, vmax] split into N_LEVELS bins.

    Args:
        values: Joint values, any shape.
        vmax: Half-width of the scale (≥ 0); 0 puts every value in the middle (neutral) bin.

    Returns:
        Bin indices in [0, N_LEVELS − 1], same shape as ``values``, int.
    """
    values = np.asarray(values, dtype=float)
    if vmax <= 0:
        return np.full(values.shape, N_LEVELS // 2, dtype=int)
    return np.clip(np.floor((values + vmax) / (2 * vmax) * N_LEVELS), 0, N_LEVELS - 1).astype(int)
