"""The quality report of a loaded log: every choice made and every figure to judge the log by."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class MotionQuality:
    """What :func:`hexaleg.load_motion` chose and measured (SI; angles rad).

    Attributes:
        path: The log file.
        rows: Rows in the log.
        rate: The log's sample rate (median stamp interval), Hz.
        resampled: Whether irregular stamps were resampled onto a uniform grid.
        filled: Samples made up by interpolation (dropped rows and NaN runs), all columns.
        derivatives: ``"smoothed"`` (Savitzky–Golay) or ``"given"`` (the log's v_/a_ columns).
        noise: Largest joint noise level σ (third differences), rad.
        cutoff: The smoothing filter's cut-off, Hz (None for given derivatives).
        window: The Savitzky–Golay window, samples (None for given derivatives).
        cycle: ``"auto"``, ``"whole"`` or ``"window"``.
        period: The motion's period (or duration), s.
        cycles: Whole cycles averaged (1 without averaging).
        correlation: The autocorrelation at the period (None without ``"auto"``).
        spread: Largest rms deviation of a joint's cycles from their average, rad.
        steady_from: Where the steady gait begins in the log, s: the cycles before it (a
            settle, a stand, a transient) are left out of the average (``"auto"``; 0 otherwise).
        stance_source: ``"contacts"`` or ``"kinematics"``.
        stance_height: The height threshold of kinematic stance, m (None from contacts).
        stance_speed: The speed threshold of kinematic stance, m/s (None from contacts).
        stance_fractions: Leg → fraction of the samples in stance.
        base_source: ``"log"``, ``"leg odometry"`` or ``"leg odometry + IMU orientation"``.
        slip: Rms speed of the stance feet in the world (their slip), m/s.
        slip_max: Its largest value at one sample, m/s.
        warnings: The warnings issued while loading.
    """

    path: str
    rows: int
    rate: float
    resampled: bool
    filled: int
    derivatives: str
    noise: float
    cutoff: float | None
    window: int | None
    cycle: str
    period: float
    cycles: int
    correlation: float | None
    spread: float
    steady_from: float
    stance_source: str
    stance_height: float | None
    stance_speed: float | None
    stance_fractions: dict[str, float]
    base_source: str
    slip: float
    slip_max: float
    warnings: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """The report as plain JSON-ready values (``{value, unit}`` for quantities)."""
        units = {"rate": "Hz", "noise": "rad", "cutoff": "Hz", "period": "s", "spread": "rad",
                 "steady_from": "s",
                 "stance_height": "m", "stance_speed": "m/s", "slip": "m/s",
                 "slip_max": "m/s"}
        out: dict[str, Any] = {}
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if isinstance(value, tuple):
                value = list(value)
            out[f.name] = {"value": value, "unit": units[f.name]} if f.name in units else value
        return out

    def lines(self) -> list[str]:
        """The report as text lines for a terminal."""
        fractions = " ".join(f"{k} {v:.2f}" for k, v in self.stance_fractions.items())
        smoothing = ("derivatives as logged" if self.cutoff is None else
                     f"Savitzky–Golay order 4, window {self.window}, cut-off "
                     f"{self.cutoff:.2f} Hz")
        steady = (f"; steady from t = {self.steady_from:.3f} s, the log before it left out"
                  if self.steady_from > 0 else "")
        cycles = (f"period {self.period:.4f} s from {self.cycles} cycles (correlation "
                  f"{self.correlation:.3f}, spread {self.spread:.2e} rad{steady})"
                  if self.cycle == "auto" else f"{self.cycle}: {self.period:.4f} s")
        thresholds = ("" if self.stance_height is None else
                      f" (height < {self.stance_height * 1e3:.2f} mm, speed < "
                      f"{self.stance_speed or 0.0:.4f} m/s)")
        return [f"log {self.path}: {self.rows} rows at {self.rate:.1f} Hz"
                f"{', resampled' if self.resampled else ''}, {self.filled} values filled",
                f"noise {self.noise:.2e} rad; {smoothing}",
                f"cycle {cycles}",
                f"stance from {self.stance_source}{thresholds}: {fractions}",
                f"base from {self.base_source}; stance-foot slip rms {self.slip:.4f} m/s, "
                f"max {self.slip_max:.4f} m/s",
                *(f"warning: {w}" for w in self.warnings)]
