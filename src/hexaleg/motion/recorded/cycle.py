"""The gait cycle of a log: its period from the joint signals, its cycles averaged into one.

The period is the lag of the first peak of the joint signals' summed autocorrelation (each
column standardised; computed by FFT, Wiener–Khinchin), refined by a parabola through the peak.
The autocorrelation's peak is biased by its overlap weighting (+0.0014 of the period on a
noise-free two-cycle log), so the period is then refined where the log and its copy shifted by k
periods differ least: the squared difference function d(τ) = Σ |x(t + τ) − x(t)|² over their
overlap (the difference function of YIN, de Cheveigné & Kawahara, J. Acoust. Soc. Am. 111(4),
2002, eq. 6), the shifted copy a cubic spline at fractional lags, d minimised by Brent's method
within a sample of k times the first estimate, for the largest k that leaves a period of
overlap (k periods measured at once: the error shrinks as 1/k). The log's whole cycles are then
resampled onto one phase grid and averaged (the ensemble average of phase-locked cycles), and
their spread — the rms deviation of a cycle from the average — reported.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hexaleg.errors import InvalidParameterError

MIN_CORRELATION = 0.5
"""Smallest normalised autocorrelation a period's peak must reach to count as a repeating gait."""
STEADY_FACTOR = 3.0
"""A cycle of the log is steady when it deviates from the median cycle by at most this many times
the typical (median) cycle's deviation; the unsteady cycles at the log's start (a settle, a stand,
a transient) are left out of the average."""
MIN_CYCLE_SAMPLES = 10
"""Fewest rows a cycle of the log may have: below it the foot's lift-off and touch-down (a tenth
of a cycle each) fall between samples, and the gait's harmonics above the fifth alias
(Nyquist–Shannon)."""


@dataclass(frozen=True)
class Cycles:
    """A log's cycles averaged into one.

    Attributes:
        period: The period, s.
        start: Time of the first cycle's start in the log, s.
        count: Whole cycles averaged.
        samples: Samples of the averaged cycle M (``period / M`` its spacing).
        correlation: The autocorrelation at the period (1: cycles identical).
        mean: The averaged cycle, shape (M, n).
        spread: Rms deviation of the cycles from ``mean`` per column, shape (n,).
    """

    period: float
    start: float
    count: int
    samples: int
    correlation: float
    mean: np.ndarray
    spread: np.ndarray


def _autocorrelation(x: np.ndarray) -> np.ndarray:
    """Summed normalised autocorrelation of the columns of x (N, n) for lags 0 … N−1."""
    n = x.shape[0]
    z = x - x.mean(axis=0)
    scale = np.sqrt((z**2).sum(axis=0))
    z = z[:, scale > 0] / scale[scale > 0]
    if z.shape[1] == 0:
        return np.zeros(n)
    f = np.fft.rfft(z, n=2 * n, axis=0)
    acf = np.fft.irfft(np.abs(f) ** 2, axis=0)[:n].sum(axis=1) / z.shape[1]
    return acf * n / np.maximum(n - np.arange(n), 1)  # unbiased: each lag by its overlap


def _peak(acf: np.ndarray, near: int, width: int) -> tuple[float, float]:
    """The highest peak of acf within ``width`` of lag ``near``, refined by a parabola."""
    lo, hi = max(near - width, 1), min(near + width + 1, len(acf) - 1)
    k = lo + int(np.argmax(acf[lo:hi]))
    if 0 < k < len(acf) - 1:
        a, b, c = acf[k - 1], acf[k], acf[k + 1]
        den = a - 2 * b + c
        shift = 0.5 * (a - c) / den if den < 0 else 0.0
        return k + float(np.clip(shift, -0.5, 0.5)), float(b - 0.25 * (a - c) * shift)
    return float(k), float(acf[k])


def find_period(x: np.ndarray, dt: float, where: str = "motion log") -> tuple[float, float]:
    """The period of the joint signals ``x`` (N, n) sampled every ``dt`` s, and its correlation.

    Raises:
        InvalidParameterError: no lag up to half the log correlates by
            :data:`MIN_CORRELATION` (the log is shorter than two cycles, or does not repeat), or
            the cycle has fewer than :data:`MIN_CYCLE_SAMPLES` rows; the message names the rate
            and says what to give instead.
    """
    n = x.shape[0]
    duration = n * dt
    acf = _autocorrelation(np.asarray(x, dtype=float))
    half = n // 2
    negative = np.flatnonzero(acf[1:half] < 0)
    if negative.size == 0 or negative[0] + 3 > half:
        raise InvalidParameterError(
            f"{where}: cycle='auto'", f"no repeating cycle in {duration:.3f} s sampled at "
            f"{1 / dt:.3g} Hz", "a log of at least two gait cycles, each of at least "
            f"{MIN_CYCLE_SAMPLES} rows; for a shorter log give the window of one cycle, "
            "cycle=(t0, t1), or cycle='whole'")
    first = int(negative[0]) + 1
    seg = acf[first:half + 1]
    peaks = np.flatnonzero((seg[1:-1] >= seg[:-2]) & (seg[1:-1] >= seg[2:])) + 1
    if peaks.size == 0:
        peaks = np.array([int(np.argmax(seg))])
    best = float(seg[peaks].max())  # the first peak nearly as high as the highest is the
    near = np.flatnonzero(seg[peaks] >= best - 0.1 * abs(best))  # period, not a multiple
    lag = first + int(peaks[near[0]])
    period, corr = _peak(acf, lag, 1)
    if corr < MIN_CORRELATION:
        raise InvalidParameterError(
            f"{where}: cycle='auto'", f"best repeat {period * dt:.3f} s correlates "
            f"{corr:.2f}", f"a gait that repeats (correlation >= {MIN_CORRELATION}) over at "
            "least two cycles; give a window, cycle=(t0, t1), or cycle='whole'")
    if period < MIN_CYCLE_SAMPLES:
        raise InvalidParameterError(
            f"{where}: cycle='auto'", f"a cycle of {period * dt:.3f} s sampled {period:.1f} "
            f"times ({1 / dt:.3g} Hz)", f"at least {MIN_CYCLE_SAMPLES} rows a cycle (a rate of "
            f"{MIN_CYCLE_SAMPLES / (period * dt):.3g} Hz or more for this gait): log faster")
    multiple = max(int(n // period) - 1, 1)  # k periods at once, a period of overlap left
    return _refine(np.asarray(x, dtype=float), multiple * period) / multiple * dt, corr


def _refine(x: np.ndarray, lag: float) -> float:
    """The lag within a sample of ``lag`` (samples) where x (N, n) and its shifted copy differ
    least (module docstring: the squared difference function, cubic-spline shifts, Brent)."""
    from scipy.interpolate import CubicSpline
    from scipy.optimize import minimize_scalar

    n = x.shape[0]
    z = x - x.mean(axis=0)
    scale = np.sqrt((z**2).mean(axis=0))
    z = z[:, scale > 0] / scale[scale > 0]
    spline = CubicSpline(np.arange(n), z, axis=0)
    base = np.arange(n - math.ceil(lag + 1.0))

    def difference(tau: float) -> float:
        return float(np.mean((spline(base + tau) - z[base]) ** 2))

    fit = minimize_scalar(difference, bounds=(lag - 1.0, lag + 1.0), method="bounded",
                          options={"xatol": 1e-6})
    return float(fit.x)


def _stacked(t: np.ndarray, x: np.ndarray, period: float, dt: float, start: float
             ) -> np.ndarray:
    """The whole cycles of ``x`` (N, n) from ``start``, each linearly interpolated onto a grid of
    ``round(period / dt)`` phases (at least 8), shape (cycles, phases, n)."""
    samples = max(round(period / dt), 8)
    # the last cycle needs its last phase, a phase step before its end, inside the log
    count = max(math.floor((t[-1] - start + period / samples) / period + 1e-6), 0)
    phase = np.arange(samples) / samples * period
    stacked = np.empty((count, samples, x.shape[1]))
    for c in range(count):
        at = start + c * period + phase
        for j in range(x.shape[1]):
            stacked[c, :, j] = np.interp(at, t, x[:, j])
    return stacked


def steady_start(t: np.ndarray, x: np.ndarray, period: float, dt: float) -> float:
    """Where the log's steady gait begins, s: the start of its first cycle that deviates from
    the median cycle by at most :data:`STEADY_FACTOR` times the median deviation (each column
    standardised, rms over phases and columns), when the cycles before it do not; 0 when the
    first cycle is steady or the log has fewer than four cycles.

    Args:
        t: Uniform times, shape (N,), s. x: The joints, shape (N, n). period: The period, s.
        dt: The log's spacing, s.
    """
    stacked = _stacked(t, x, period, dt, 0.0)
    if len(stacked) < 4:
        return 0.0
    scale = x.std(axis=0)
    z = stacked[..., scale > 0] / scale[scale > 0]
    deviation = np.sqrt(((z - np.median(z, axis=0)) ** 2).mean(axis=(1, 2)))
    typical = max(float(np.median(deviation)), 1e-12)
    first = 0
    while first < len(stacked) - 2 and deviation[first] > STEADY_FACTOR * typical:
        first += 1
    return float(first * period)


def average_cycles(t: np.ndarray, x: np.ndarray, period: float, dt: float, *,
                   correlation: float = 1.0, start: float = 0.0) -> Cycles:
    """The whole cycles of ``x`` from ``start`` averaged on a grid of ``round(period / dt)``
    phases (each cycle linearly interpolated onto it).

    Args:
        t: Uniform times, shape (N,), s.
        x: Values, shape (N, n).
        period: The period, s.
        dt: The log's spacing, s (the averaged cycle keeps about its rate).
        correlation: The period's autocorrelation, reported.
        start: Where the first cycle starts, s.

    Raises:
        InvalidParameterError: fewer than two whole cycles from ``start``.
    """
    stacked = _stacked(t, x, period, dt, start)
    if len(stacked) < 2:
        raise InvalidParameterError("motion log: cycles", f"{len(stacked)} whole cycle(s) of "
                                    f"{period:.4f} s in {t[-1] - start:.4f} s",
                                    "at least two for cycle='auto'; give cycle=(t0, t1)")
    count, samples = stacked.shape[:2]
    mean = stacked.mean(axis=0)
    spread = np.sqrt(((stacked - mean) ** 2).mean(axis=(0, 1)))
    return Cycles(period=period, start=start, count=count, samples=samples,
                  correlation=correlation, mean=mean, spread=spread)
