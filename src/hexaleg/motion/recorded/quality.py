"""The quality report of a loaded log: every choice made and every figure to judge the log by."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

UNITS: dict[str, str] = {"rows": "rows", "rate": "Hz", "filled": "values", "noise": "rad",
                         "cutoff": "Hz", "position_cutoff": "Hz", "attitude_cutoff": "Hz",
                         "window": "samples",
                         "period": "s", "cycles": "cycles", "correlation": "1", "spread": "rad",
                         "steady_from": "s", "stance_height": "m", "stance_speed": "m/s",
                         "slip": "m/s", "slip_max": "m/s"}
"""The unit of each number of :class:`MotionQuality`."""


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
        position_cutoff, attitude_cutoff: The logged base position's and attitude's cut-offs,
            Hz, each from its own noise (a motion-capture base is noisier for its signal than
            the joints' encoders). None for given derivatives or without the logged quantity
            (a base from leg odometry is smoothed at the joints' cut-off).
        cycle: ``"auto"``, ``"whole"`` or ``"window"``.
        period: The motion's period (or duration), s.
        cycles: Whole cycles averaged (1 without averaging).
        correlation: The autocorrelation at the period (None without ``"auto"``).
        spread: Largest rms deviation of a joint's cycles from their average, rad.
        steady_from: Where the steady gait begins in the log, s: the cycles before it (a
            settle, a stand, a transient) are left out of the average (``"auto"``; 0 otherwise).
        stance_source: ``"plan"``, ``"contacts"`` or ``"kinematics"``.
        stance_height: The height threshold of kinematic stance, m (None from contacts).
        stance_speed: The speed threshold of kinematic stance, m/s (None from contacts).
        stance_fractions: Leg → fraction of the samples in stance (carrying load: what the
            contact forces use).
        touch_fractions: Leg → fraction of the samples the foot touches the ground (the
            kinematic contact: low and still, with the gentle edges of a touch-down and a
            lift-off where it carries little; the stance's own from contact columns).
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
    position_cutoff: float | None
    attitude_cutoff: float | None
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
    touch_fractions: dict[str, float]
    base_source: str
    slip: float
    slip_max: float
    warnings: tuple[str, ...] = ()

    def to_dict(self) -> dict[str, Any]:
        """The report as JSON-ready values (``motion_quality`` of the JSON files): every number
        ``{value, unit}`` (:data:`UNITS`; stance fractions per leg, unit ``"1"``), None stays
        None, strings and flags as they are."""
        out: dict[str, Any] = {}
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if f.name in ("stance_fractions", "touch_fractions"):
                value = {leg: {"value": float(v), "unit": "1"} for leg, v in value.items()}
            elif isinstance(value, tuple):
                value = list(value)
            elif f.name in UNITS and value is not None:
                value = {"value": value, "unit": UNITS[f.name]}
            out[f.name] = value
        return out

    def lines(self) -> list[str]:
        """The report as text lines for a terminal."""
        fractions = " ".join(f"{k} {v:.2f}" for k, v in self.stance_fractions.items())
        touch = " ".join(f"{k} {v:.2f}" for k, v in self.touch_fractions.items())
        smoothing = ("derivatives as logged" if self.cutoff is None else
                     f"Savitzky–Golay order 4, window {self.window}, cut-off "
                     f"{self.cutoff:.2f} Hz")
        base = [f"base {name} {value:.2f} Hz" for name, value in
                (("position", self.position_cutoff), ("attitude", self.attitude_cutoff))
                if value is not None]
        smoothing += f" ({', '.join(base)})" if base else ""
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
                f"stance from {self.stance_source}{thresholds}: {fractions}" + (
                    "" if touch == fractions else f"; touching the ground {touch}"),
                f"base from {self.base_source}; stance-foot slip rms {self.slip:.4f} m/s, "
                f"max {self.slip_max:.4f} m/s",
                *(f"warning: {w}" for w in self.warnings)]
