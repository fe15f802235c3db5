"""Resampling a log onto a uniform grid: irregular stamps, dropped samples and short NaN runs.

The grid spacing is the median stamp interval; every column is interpolated linearly onto it
(a contact or stance column to its nearest stamp; a quaternion renormalised afterwards). A gap —
dropped rows or a run of missing values — longer than ``max_gap`` is not made up: it is an error
that names the column, where the gap is and what to do.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from hexaleg.errors import InvalidParameterError
from hexaleg.motion.limits import check_samples
from hexaleg.motion.recorded.read import BASE_QUATERNION, Log

UNIFORM_TOLERANCE = 1e-6
"""Largest relative deviation of a stamp interval from the median for a log kept as stamped."""
MAX_STEP = 0.5
"""s: the longest median interval between a log's stamps (2 Hz). A gait is sampled faster (a
cycle needs about ten samples: the foot's lift-off and touch-down are a tenth of it); a slower
"rate" is more often milliseconds read as seconds, and is refused with both readings named."""


@dataclasses.dataclass(frozen=True)
class Resampled:
    """A log on a uniform grid.

    Attributes:
        log: The log, ``t`` uniform from 0 (s), every column finite.
        dt: The grid spacing, s.
        filled: Samples made up per column (dropped rows and NaN runs interpolated).
        resampled: Whether the stamps were irregular (the grid is not the log's own).
    """

    log: Log
    dt: float
    filled: dict[str, int]
    resampled: bool


def _check_time(t: np.ndarray, where: str) -> None:
    if len(t) < 2:
        raise InvalidParameterError(f"{where} rows", len(t), "at least 2 rows (a log of a gait "
                                    "holds at least one cycle)")
    if not np.all(np.isfinite(t)):
        k = int(np.flatnonzero(~np.isfinite(t))[0])
        raise InvalidParameterError(f"{where} time at row {k + 2}", float(t[k]),
                                    "a finite time stamp on every row")
    step = np.diff(t)
    if np.any(step <= 0):
        k = int(np.flatnonzero(step <= 0)[0])
        raise InvalidParameterError(
            f"{where} time at row {k + 3}", float(t[k + 1]),
            f"stamps that increase: it follows {float(t[k])} s; sort the log by time and drop "
            "repeated rows (or give the time column its unit, e.g. 'time [ms]')")


def _gaps(bad: np.ndarray) -> list[tuple[int, int]]:
    """Runs of True in ``bad`` (N,) as (start, stop) index pairs."""
    edges = np.diff(np.concatenate([[0], bad.astype(np.int8), [0]]))
    return list(zip(np.flatnonzero(edges == 1).tolist(), np.flatnonzero(edges == -1).tolist(),
                    strict=True))


def resample(log: Log, *, max_gap: float = 0.05) -> Resampled:
    """``log`` on a uniform grid of its median stamp interval, starting at t = 0.

    Args:
        log: The log as read.
        max_gap: Longest gap filled by interpolation, s (dropped rows or a NaN run).

    Raises:
        InvalidParameterError: stamps not increasing (the row named); stamps further apart than
            :data:`MAX_STEP` (the rate named, and the unit the time was read in); a column's gap
            longer
            than ``max_gap`` (the column, its time and length named); more samples than a motion
            may have (:func:`hexaleg.motion.limits.check_samples`).
    """
    where = f"motion log {log.path}" if log.path else "motion log"
    t = np.asarray(log.t, dtype=float)
    _check_time(t, where)
    dt = float(np.median(np.diff(t)))
    if dt > MAX_STEP:
        raise InvalidParameterError(
            f"{where} time steps", f"{dt:g} s (a rate of {1 / dt:.3g} rows a second, the time "
            f"column read in {log.units.get('time', 's')})",
            f"rows at least every {MAX_STEP} s ({1 / MAX_STEP:g} Hz: a gait's cycle needs 10 "
            "samples or more); if the time column is not in seconds give its unit, e.g. "
            "'time [ms]' (a 100 Hz log in ms reads as steps of 10 s)")
    span = t[-1] - t[0]
    irregular = bool(np.max(np.abs(np.diff(t) - dt)) > UNIFORM_TOLERANCE * dt)
    n = round(span / dt) + 1 if irregular else len(t)
    check_samples(n, f"samples of the resampled {where}")
    grid = t[0] + dt * np.arange(n) if irregular else t
    if irregular:  # a dropped stamp is a gap in every column
        step = np.diff(t)
        k = int(np.argmax(step))
        if step[k] > max_gap + dt:
            raise InvalidParameterError(
                f"{where}: gap after t = {t[k] - t[0]:.4f} s", f"{step[k]:.4f} s",
                f"at most max_gap = {max_gap} s without rows; give a window without it "
                "(cycle=(t0, t1)) or a larger max_gap")
    columns: dict[str, np.ndarray] = {}
    filled: dict[str, int] = {}
    for name, values in log.columns.items():
        ok = np.isfinite(values)
        if not ok.any():
            raise InvalidParameterError(f"{where} column {name!r}", "no finite value",
                                        "numbers on most rows; drop the column or fill it")
        for start, stop in _gaps(~ok):
            t0 = t[max(start - 1, 0)]
            t1 = t[min(stop, len(t) - 1)]
            if t1 - t0 > max_gap + dt or start == 0 or stop == len(t):
                raise InvalidParameterError(
                    f"{where} column {name!r}", f"{stop - start} missing values from "
                    f"t = {t[start] - t[0]:.4f} s", f"runs of NaN shorter than max_gap = "
                    f"{max_gap} s inside the log; cut the log (cycle=(t0, t1)) or fill them")
        if name.startswith(("contact_", "stance_")):
            index = np.searchsorted(t[ok], grid).clip(1, ok.sum() - 1)
            tk = t[ok]
            nearest = np.where(grid - tk[index - 1] < tk[index] - grid, index - 1, index)
            columns[name] = values[ok][nearest]
        else:
            columns[name] = np.interp(grid, t[ok], values[ok])
        filled[name] = int(n - ok.sum()) if irregular else int((~ok).sum())
    if all(q in columns for q in BASE_QUATERNION):
        quat = np.stack([columns[q] for q in BASE_QUATERNION], axis=1)
        norm = np.linalg.norm(quat, axis=1)
        if np.any(np.abs(norm - 1.0) > 0.1):
            k = int(np.argmax(np.abs(norm - 1.0)))
            raise InvalidParameterError(f"{where} base quaternion at t = {grid[k] - t[0]:.4f} s",
                                        f"norm {norm[k]:.3f}", "unit quaternions "
                                        "(base_qx, base_qy, base_qz, base_qw; w last)")
        for i, q in enumerate(BASE_QUATERNION):
            columns[q] = quat[:, i] / norm
    out = dataclasses.replace(log, t=grid - grid[0], columns=columns)
    return Resampled(log=out, dt=dt, filled=filled, resampled=irregular)
