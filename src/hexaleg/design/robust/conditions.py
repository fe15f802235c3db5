"""How a spring design built for one gait fares when the conditions change.

A built spring has fixed angles: the design is frozen on the nominal gait (absolute neutral and
contact angles) and re-evaluated — the energy metrics with the springs against the baseline
without them (the paper's energy criterion, eq. 20–24, with a motor model) — under a changed
:class:`Condition`: the gait's period and stride scaled, a payload on the body (a point mass at
the base origin, :func:`hexaleg.robot.payload.with_payload`: the dynamics carry it, the joint
motion is the same), the floor's friction μ, the ground's slope along the walking direction
(``GaitParams.slope``: footholds on the inclined plane, friction cones about its normal;
:mod:`hexaleg.motion.ground`) and the gait pattern (``GaitParams.pattern``, a named pattern of
:data:`hexaleg.motion.patterns.PATTERNS` at its own duty factor β₀, as
``GaitParams.updated({"pattern": …})`` gives it).

:func:`condition_prepared` builds the prepared gait of a condition (a named error where it cannot
be made), :func:`condition_walk` the same or the reason it cannot (for the maps: a condition the
robot cannot walk is a cell of the map, not the end of the design), :func:`condition_savings`
evaluates frozen springs on it; :mod:`hexaleg.design.robust.maps` runs grids of conditions and
:mod:`hexaleg.design.robust.box` designs for a box of them. :func:`robustness` is the one-parameter
table (period or stride) of a dead-zone design.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from hexaleg.checks import real, typed
from hexaleg.design.evaluator import DEFAULT_METRIC, Design, RunSpec, evaluator
from hexaleg.dynamics.energy import saving
from hexaleg.dynamics.prepare import Prepared, prepare
from hexaleg.errors import (
    InfeasibleForcesError,
    InvalidParameterError,
    TorqueLimitError,
    UnknownNameError,
    UnreachableTargetError,
)
from hexaleg.motion.legged import tripod_gait
from hexaleg.motion.params import GaitParams
from hexaleg.motion.patterns import check_pattern
from hexaleg.robot.payload import with_payload
from hexaleg.robot.springs import SpringSet

if TYPE_CHECKING:  # pandas is imported where tables are made: `import hexaleg` stays light
    import pandas as pd

CONDITIONS: tuple[str, ...] = ("period", "stride", "payload", "mu", "slope", "pattern")
"""What a condition changes: period and stride as factors of the nominal gait's, payload as a
fraction of the robot's mass, μ absolute, slope (rad) added to the nominal ground's, the pattern
by name (the only condition whose values are strings)."""
UNWALKABLE: tuple[type[Exception], ...] = (UnreachableTargetError, InfeasibleForcesError,
                                           InvalidParameterError)
"""Why a condition's gait cannot be made: a foot out of reach (``GaitReachError``), no static
margin for a crawl (``StaticMarginError``, an ``InvalidParameterError``), a sway that does not
converge or a ground steeper than the friction holds (``InfeasibleForcesError``, the latter from
:func:`hexaleg.dynamics.contact.check_ground_friction`), a support line a sway cannot cross."""


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
            parts.append(f"slope {_degrees(self.slope)}")
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
            parts.append(f"α{_degrees(self.slope)}")
        if self.pattern is not None:
            parts.append(self.pattern)
        return " ".join(parts) or "nominal"


def _degrees(angle: float) -> str:
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


def _prepared(run: RunSpec, varied: GaitParams, condition: Condition) -> Prepared:
    """The prepared ``varied`` gait (``condition_gait``) with the condition's payload and μ."""
    robot = run.load()
    if condition.payload:
        robot = with_payload(robot, condition.payload * robot.mass,
                             note=f"payload {100 * condition.payload:g} % of the robot's mass")
    motion = tripod_gait(robot, varied)
    contact = run.contact if condition.mu is None else dataclasses.replace(run.contact,
                                                                           mu=condition.mu)
    return prepare(robot, motion, motor=run.actuator(), contact=contact)


def condition_prepared(run: RunSpec, gait: GaitParams, condition: Condition) -> Prepared:
    """The prepared gait of ``condition`` on the run's robot, actuator and contact settings.

    Raises:
        InvalidParameterError: the condition's gait cannot be made (:data:`UNWALKABLE`: a foot
            out of reach, no static margin, a slope the friction cannot hold; names the
            condition, the gait's error and what to change), or its slope added to the nominal
            gait's leaves (−π/2, π/2).
    """
    varied = condition_gait(gait, condition)
    try:
        return _prepared(run, varied, condition)
    except UNWALKABLE as e:
        changed = [n for n in ("period", "stride", "payload", "mu", "slope", "pattern")
                   if getattr(condition, n) != getattr(Condition(), n)]
        raise InvalidParameterError(
            "condition", condition.label(),
            f"a condition whose gait the robot can walk; at {condition.label()} (period "
            f"{varied.period:g} s, stride {varied.stride:g} m, slope {_degrees(varied.slope)}, "
            f"pattern {varied.pattern or 'nominal'}): {type(e).__name__}: {e} — narrow the "
            f"{' and '.join(changed) or 'gait'} range"
        ) from e


def condition_walk(run: RunSpec, gait: GaitParams, condition: Condition) -> Prepared | str:
    """The prepared gait of ``condition`` (:func:`condition_prepared`), or — where it cannot be
    made (:data:`UNWALKABLE`) — why: ``"no gait: <error>: <message>"``, a map cell outside the
    robot's envelope rather than the end of the design."""
    try:
        return _prepared(run, condition_gait(gait, condition), condition)
    except UNWALKABLE as e:
        return f"no gait: {type(e).__name__}: {e}"


def condition_savings(prepared: Prepared, springs: SpringSet, objective: str,
                      metrics: Sequence[str] = (DEFAULT_METRIC, "joule")) -> dict[str, Any]:
    """Frozen ``springs`` on one condition: each metric with and without them and the saving.

    Returns:
        ``{"status", "<m>", "baseline.<m>", "saving.<m>"}`` per metric; status ``"ok"``,
        ``"no baseline: …"`` (the condition has no admissible forces even without springs) or
        ``"springs: …"`` (none with the springs); NaN where there is no number.
    """
    out: dict[str, Any] = {}
    try:
        base = prepared.baseline(objective)["total"]
    except (InfeasibleForcesError, TorqueLimitError) as e:
        out["status"] = f"no baseline: {type(e).__name__}: {e}"
        for m in metrics:
            out.update({m: math.nan, f"baseline.{m}": math.nan, f"saving.{m}": math.nan})
        return out
    try:
        total = prepared.evaluate(springs, objective).metrics["total"]
        out["status"] = "ok"
    except (InfeasibleForcesError, TorqueLimitError) as e:
        total, out["status"] = None, f"springs: {type(e).__name__}: {e}"
    for m in metrics:
        value = math.nan if total is None else float(total[m])
        out.update({m: value, f"baseline.{m}": float(base[m]),
                    f"saving.{m}": saving(value, float(base[m]))})
    return out


@typed
def robustness(run: RunSpec, gait: GaitParams, groups: Mapping[str, Sequence[str]],
               design: Design, metric: str = DEFAULT_METRIC, *,
               factors: Sequence[float] = (0.8, 0.9, 1.0, 1.1, 1.2),
               parameters: Sequence[str] = ("period", "stride_length")) -> pd.DataFrame:
    """Saving of a fixed dead-zone design when the gait's period or amplitude changes.

    The design is frozen on the nominal gait — its neutral angles are absolute, taken from the
    nominal ranges of motion — as a built spring would be; only the gait changes.

    Args:
        run: Robot, motor, objective, contact.
        gait: The nominal gait (the design was chosen for it).
        groups: Group → joints.
        design: Group → parameters (e.g. ``{g: optimum.design()}``).
        metric: A key of :data:`~hexaleg.design.evaluator.METRICS`.
        factors: Multipliers of each parameter (1 = nominal), > 0.
        parameters: Gait parameters to vary, from ``period`` and ``stride_length`` (amplitude).

    Returns:
        One row per (parameter, factor): ``parameter``, ``factor``, ``gait value``, ``value``,
        ``baseline``, ``saving``, ``status``.

    Raises:
        UnknownNameError: a parameter other than period / stride_length.
        InvalidParameterError: a factor ≤ 0.
    """
    import pandas as pd

    for p in parameters:
        if p not in ("period", "stride_length"):
            raise UnknownNameError("robustness parameter", p, ("period", "stride_length"))
    for fct in factors:
        real("factor", fct, low=0.0, low_open=True, allowed="> 0")
    springs = evaluator(run, dataclasses.asdict(gait)).springs(groups, design)
    rows = []
    for p in parameters:
        for fct in factors:
            cond = (Condition(period=float(fct)) if p == "period"
                    else Condition(stride=float(fct)))
            r = condition_savings(condition_prepared(run, gait, cond), springs, run.objective,
                                  (metric,))
            rows.append({"parameter": p, "factor": float(fct),
                         "gait value": getattr(condition_gait(gait, cond), p),
                         "value": r[metric], "baseline": r[f"baseline.{metric}"],
                         "saving": r[f"saving.{metric}"], "status": r["status"]})
    return pd.DataFrame(rows)
