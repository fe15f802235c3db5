"""Smoothing and differentiating logged positions: Savitzky–Golay, its cut-off from the noise.

Method (stated and reported): a Savitzky–Golay filter (Savitzky & Golay, *Anal. Chem.* 36,
1964) of polynomial order :data:`ORDER` gives the smoothed signal and its first and second
derivatives from one local least-squares polynomial per sample (``scipy.signal.savgol_filter``,
``mode="wrap"`` on a periodic cycle, ``"interp"`` otherwise). Its cut-off — the −3 dB frequency
— is ``f_c ≈ (N + 1) / (3.2 M − 4.6) · f_s / 2`` for order N and window 2M + 1 (Schafer, "What is
a Savitzky–Golay filter?", *IEEE Signal Process. Mag.* 28(4), 2011, eq. 11), so the window
follows from the cut-off wanted.

The cut-off is chosen from the data: the noise level σ of each column is estimated from its
third differences (white noise of variance σ² has third differences of variance 20 σ², and a
smooth signal sampled finely has almost none; the median absolute deviation makes it robust:
σ ≈ 1.4826 · MAD(Δ³x) / √20), and the cut-off is the highest frequency at which some column's
spectrum stands :data:`SNR` times above that noise's floor.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

ORDER = 4
"""Polynomial order N of the Savitzky–Golay filter (exact on quartics: a's derivative is exact
on cubic accelerations)."""
SNR = 4.0
"""A harmonic counts as signal where its amplitude is this many times the noise's rms amplitude
(a Rayleigh-distributed noise amplitude exceeds 4 × its rms with probability e⁻¹⁶)."""

MARGIN = 2.0
"""The filter's −3 dB point sits this many times above the highest signal harmonic, so the
signal's band passes nearly unattenuated (a Savitzky–Golay filter is flat to well below f_c)."""


@dataclass(frozen=True)
class Smoothed:
    """Positions smoothed and differentiated.

    Attributes:
        x: Smoothed values, shape (T, n).
        xd: First time derivatives, shape (T, n).
        xdd: Second time derivatives, shape (T, n).
        cutoff: The filter's −3 dB cut-off frequency, Hz.
        window: The Savitzky–Golay window, samples (odd).
        order: Its polynomial order.
    """

    x: np.ndarray
    xd: np.ndarray
    xdd: np.ndarray
    cutoff: float
    window: int
    order: int


def noise_level(x: np.ndarray) -> np.ndarray:
    """Each column's white-noise level σ from its third differences (module docstring).

    Args:
        x: Samples on a uniform grid, shape (N, n), N ≥ 8.

    Returns:
        σ per column, shape (n,), in the units of ``x``.
    """
    d3 = np.diff(np.asarray(x, dtype=float), n=3, axis=0)
    mad = np.median(np.abs(d3 - np.median(d3, axis=0)), axis=0)
    return 1.4826 * mad / math.sqrt(20.0)


def cutoff_frequency(x: np.ndarray, dt: float, sigma: np.ndarray, *, periodic: bool) -> float:
    """The highest frequency where some column's harmonic amplitude exceeds :data:`SNR` times
    the rms amplitude of white noise of level ``sigma`` (module docstring), Hz.

    A non-periodic signal has its straight line through its ends removed first (so the jump
    of its periodic extension does not count as signal).

    Args:
        x: Samples, shape (T, n).
        dt: Sample spacing, s.
        sigma: Noise level per column, shape (n,) (for an average of C cycles, σ/√C).
        periodic: Whether ``x`` is one period of a periodic signal.

    Returns:
        f_c in (1/(T dt), 1/(2 dt)], Hz.
    """
    x = np.asarray(x, dtype=float)
    n = x.shape[0]
    if not periodic:
        ramp = np.linspace(0.0, 1.0, n)[:, None]
        x = x - x[:1] - ramp * (x[-1:] - x[:1])
    amplitude = 2.0 * np.abs(np.fft.rfft(x, axis=0)) / n  # (n//2 + 1, n_cols)
    floor = 2.0 * np.maximum(sigma, 1e-15) / math.sqrt(n)
    above = np.flatnonzero(np.any(amplitude[1:] > SNR * floor, axis=1))
    harmonic = int(above[-1]) + 1 if above.size else 1
    return min(max(harmonic, 1) / (n * dt), 0.5 / dt)


def window_for(cutoff: float, dt: float, samples: int, order: int = ORDER) -> int:
    """The odd Savitzky–Golay window 2M + 1 whose cut-off (Schafer 2011, eq. 11) is at most
    ``cutoff``, within [order + 2 (rounded up to odd), samples]."""
    relative = min(cutoff * 2.0 * dt, 1.0)
    half = math.ceil(((order + 1) / relative + 4.6) / 3.2)
    window = 2 * half + 1
    smallest = order + 2 + (order + 1) % 2
    largest = samples if samples % 2 else samples - 1
    return int(min(max(window, smallest), max(largest, smallest)))


def window_cutoff(window: int, dt: float, order: int = ORDER) -> float:
    """The −3 dB cut-off of a Savitzky–Golay window (Schafer 2011, eq. 11), Hz."""
    half = (window - 1) // 2
    return min((order + 1) / max(3.2 * half - 4.6, order + 1) * 0.5 / dt, 0.5 / dt)


def smooth(x: np.ndarray, dt: float, cutoff: float, *, periodic: bool) -> Smoothed:
    """Smooth ``x`` and differentiate it twice by a Savitzky–Golay filter of cut-off ``cutoff``.

    Args:
        x: Samples, shape (T, n), T ≥ :data:`ORDER` + 3.
        dt: Sample spacing, s.
        cutoff: The signal's highest frequency, Hz (:func:`cutoff_frequency`); the filter's
            −3 dB point is placed at :data:`MARGIN` times it.
        periodic: One period of a periodic signal (wrap around) or not.

    Returns:
        The smoothed values and derivatives, shapes (T, n), and the window and cut-off used.
    """
    from scipy.signal import savgol_filter  # here: scipy.signal costs every command ~1 s

    x = np.asarray(x, dtype=float)
    window = window_for(MARGIN * cutoff, dt, x.shape[0])
    mode = "wrap" if periodic else "interp"
    out = [savgol_filter(x, window, ORDER, deriv=d, delta=dt, axis=0, mode=mode)
           for d in (0, 1, 2)]
    return Smoothed(x=out[0], xd=out[1], xdd=out[2], cutoff=window_cutoff(window, dt),
                    window=window, order=ORDER)
