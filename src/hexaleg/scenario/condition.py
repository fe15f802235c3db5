"""One set of operating conditions a run may be put under: :class:`Condition`.

The nominal run is a gait on level ground at the robot's own mass and the ``[contact]`` μ; a
condition scales the gait's period and stride, adds a payload on the body (a point mass at the
base origin, :func:`hexaleg.robot.payload.with_payload`: the dynamics carry it, the joint motion
is the same), sets the floor's friction μ, tilts the ground along the walking direction
(``GaitParams.slope``: footholds on the inclined plane, friction cones about its normal;
:mod:`hexaleg.motion.ground`) or changes the gait pattern (``GaitParams.pattern``, a named pattern
of :data:`hexaleg.motion.patterns.PATTERNS` at its own duty factor β₀, as
``GaitParams.updated({"pattern": …})`` gives it). :meth:`hexaleg.scenario.scenario.Scenario.under`
puts a run under one; the design's robustness maps and robust box
(:mod:`hexaleg.design.robust`) vary conditions this way.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from hexaleg.checks import real
from hexaleg.motion.params import GaitParams
from hexaleg.motion.patterns import check_pattern

CONDITIONS: tuple[str, ...] = ("period", "stride", "payload", "mu", "slope", "pattern")
"""What a condition changes: period and stride as factors of the nominal gait's, payload as a
fraction of the robot's mass, μ absolute, slope (rad) added to the nominal ground's, the pattern
by name (the only condition whose values are strings)."""


@dataclass(frozen=True)
class Condition:
    """One set of operating conditions (module docstring).

    Attributes:
        period: Factor on the gait period, > 0.
        stride: Factor on the stride (body travel per cycle), > 0.
        payload: Payload as a fraction of the robot's mass, ≥ 0.
        mu: Friction coefficient, > 0; None: the run's.
        slope: Inclination of the ground along the walking direction, rad, positive uphill,
            in (−π/2, π/2) as ``GaitParams.slope``; added to the nominal gait's (level by
            default, where it is the slope itself).
        pattern: A named gait pattern (:data:`hexaleg.motion.patterns.PATTERNS`) at its own
            duty factor; None: the nominal gait's legs and duty factor.

    Raises:
        InvalidParameterError: a value out of range.
        UnknownNameError: an unknown pattern (lists them).
    """

    period: float = 1.0
    stride: float = 1.0
    payload: float = 0.0
    mu: float | None = None
    slope: float = 0.0
    pattern: str | None = None

    def __post_init__(self) -> None:
        for name in ("period", "stride"):
            real(name, getattr(self, name), low=0.0, low_open=True,
                 allowed="a factor > 0 of the nominal gait's")
        real("payload", self.payload, low=0.0, allowed="a fraction >= 0 of the robot's mass")
        if self.mu is not None:
            real("mu", self.mu, low=0.0, low_open=True, allowed="a friction coefficient > 0")
        real("slope", self.slope, low=-math.pi / 2, high=math.pi / 2, low_open=True,
             high_open=True, allowed="an angle in (−π/2, π/2) rad, positive uphill")
        if self.pattern is not None:
            check_pattern(self.pattern)

    def label(self) -> str:
        """Short text, e.g. ``period ×0.5, μ 0.3, slope +15°, wave``; ``nominal`` when nothing
        changes."""
        parts = [f"{n} ×{getattr(self, n):g}" for n in ("period", "stride")
                 if getattr(self, n) != 1.0]
        if self.payload:
            parts.append(f"payload {100 * self.payload:g} %")
        if self.mu is not None:
            parts.append(f"μ {self.mu:g}")
        if self.slope:
            parts.append(f"slope {degrees(self.slope)}")
        if self.pattern is not None:
            parts.append(self.pattern)
        return ", ".join(parts) or "nominal"

    def short_label(self) -> str:
        """Compact text for plot ticks: ``P×0.5 S×1 W25% μ0.3 α+15° wave`` (nominal parts left
        out)."""
        parts = [f"{k}×{getattr(self, n):g}" for k, n in (("P", "period"), ("S", "stride"))
                 if getattr(self, n) != 1.0]
        if self.payload:
            parts.append(f"W{100 * self.payload:g}%")
        if self.mu is not None:
            parts.append(f"μ{self.mu:g}")
        if self.slope:
            parts.append(f"α{degrees(self.slope)}")
        if self.pattern is not None:
            parts.append(self.pattern)
        return " ".join(parts) or "nominal"


def degrees(angle: float) -> str:
    """``+15°`` for 15° given in rad (rounded to 1e-6°, so radians(7.5) reads 7.5)."""
    return f"{round(math.degrees(angle), 6):+g}°"


def condition_gait(gait: GaitParams, condition: Condition) -> GaitParams:
    """The nominal gait with the condition's period and stride factors (a gait given by its
    speed keeps its stride factor: the speed scales by stride / period), its slope added to the
    gait's, and its pattern with the pattern's own duty factor and nothing else of the nominal
    legs' timing (``GaitParams.updated({"pattern": …})``).

    Raises:
        InvalidParameterError: the nominal slope plus the condition's leaves (−π/2, π/2).
    """
    speed = None if gait.speed is None else gait.speed * condition.stride / condition.period
    varied = dataclasses.replace(gait, period=gait.period * condition.period,
                                 stride_length=gait.stride_length * condition.stride,
                                 speed=speed, slope=gait.slope + condition.slope)
    if condition.pattern is not None:
        varied = varied.updated({"pattern": condition.pattern}, "condition")
    return varied


__all__ = ["CONDITIONS", "Condition", "condition_gait", "degrees"]
