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

import math
from collections.abc import Iterator, Mapping, Sequence
from typing import TYPE_CHECKING, Any

from hexaleg.checks import real, typed
from hexaleg.design.evaluator import DEFAULT_METRIC, Design, evaluator
from hexaleg.dynamics.energy import saving
from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import (
    InfeasibleForcesError,
    InvalidParameterError,
    TorqueLimitError,
    UnknownNameError,
    UnreachableTargetError,
)
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.springs import SpringSet
from hexaleg.scenario.condition import Condition, condition_gait, degrees
from hexaleg.scenario.scenario import Scenario

if TYPE_CHECKING:  # pandas is imported where tables are made: `import hexaleg` stays light
    import pandas as pd

UNWALKABLE: tuple[type[Exception], ...] = (UnreachableTargetError, InfeasibleForcesError,
                                           InvalidParameterError)
"""Why a condition's gait cannot be made: a foot out of reach (``GaitReachError``), no static
margin for a crawl (``StaticMarginError``, an ``InvalidParameterError``), a sway that does not
converge or a ground steeper than the friction holds (``InfeasibleForcesError``, the latter from
:func:`hexaleg.dynamics.contact.check_ground_friction`), a support line a sway cannot cross."""


def condition_prepared(run: Scenario, condition: Condition) -> Prepared:
    """The prepared gait of the run under ``condition`` (:meth:`Scenario.under
    <hexaleg.scenario.scenario.Scenario.under>`): the run's robot, actuator and contact.

    Raises:
        InvalidParameterError: the condition's gait cannot be made (:data:`UNWALKABLE`: a foot
            out of reach, no static margin, a slope the friction cannot hold; names the
            condition, the gait's error and what to change), or its slope added to the nominal
            gait's leaves (−π/2, π/2).
    """
    under = run.under(condition)
    varied = under.gait
    try:
        return under.prepare()
    except UNWALKABLE as e:
        changed = [n for n in ("period", "stride", "payload", "mu", "slope", "pattern")
                   if getattr(condition, n) != getattr(Condition(), n)]
        raise InvalidParameterError(
            "condition", condition.label(),
            f"a condition whose gait the robot can walk; at {condition.label()} (period "
            f"{varied.period:g} s, stride {varied.stride:g} m, slope {degrees(varied.slope)}, "
            f"pattern {varied.pattern or 'nominal'}): {type(e).__name__}: {e} — narrow the "
            f"{' and '.join(changed) or 'gait'} range"
        ) from e


def condition_walk(run: Scenario, condition: Condition) -> Prepared | str:
    """The prepared gait of ``condition`` (:func:`condition_prepared`), or — where it cannot be
    made (:data:`UNWALKABLE`) — why: ``"no gait: <error>: <message>"``, a map cell outside the
    robot's envelope rather than the end of the design."""
    try:
        return run.under(condition).prepare()
    except UNWALKABLE as e:
        return f"no gait: {type(e).__name__}: {e}"


def same_motion(run: Scenario, conditions: Sequence[Condition]) -> list[list[int]]:
    """``conditions``' indices grouped by the motion they walk — the same payload and gait (a
    friction μ changes the forces, not the motion) — in the order each group first appears, so
    that :func:`condition_walks` makes each motion once (Solo-12's three robustness maps walk
    46 motions in 70 cells). A condition whose run cannot be made is a group of its own."""
    keys: list[tuple[float, Any] | None] = []
    groups: list[list[int]] = []
    for i, c in enumerate(conditions):
        try:
            under = run.under(c)
            key: tuple[float, Any] | None = (under.payload, under.gait)
        except InvalidParameterError:  # condition_walks says why, for this one alone
            key = None
        if key is not None and key in keys:
            groups[keys.index(key)].append(i)
        else:
            keys.append(key)
            groups.append([i])
    return groups


def condition_walks(run: Scenario, conditions: Sequence[Condition],
                    nominal: Motion | None = None) -> Iterator[Prepared | str]:
    """:func:`condition_walk` of each of ``conditions`` that walk one motion (a group of
    :func:`same_motion`), the motion made once: the same preparations, each its own (its
    friction, its warm starts), each made when it is asked for (a map evaluates one before the
    next is made: a worker holds one preparation at a time, not its group's).

    Args:
        run: The run.
        conditions: Conditions of one payload and gait.
        nominal: The run's own motion (``run.motion()``) when it is already made: walked by
            conditions of the run's payload and gait instead of made again.
    """
    try:
        unders = [run.under(c) for c in conditions]
        own = (unders[0].payload, unders[0].gait) == (run.payload, run.gait)
        walked = nominal if nominal is not None and own else unders[0].motion()
    except UNWALKABLE as e:
        yield from [f"no gait: {type(e).__name__}: {e}"] * len(conditions)
        return
    for under in unders:
        try:
            yield under.prepare(walked)
        except UNWALKABLE as e:
            yield f"no gait: {type(e).__name__}: {e}"


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
def robustness(run: Scenario, groups: Mapping[str, Sequence[str]], design: Design,
               metric: str = DEFAULT_METRIC, *,
               factors: Sequence[float] = (0.8, 0.9, 1.0, 1.1, 1.2),
               parameters: Sequence[str] = ("period", "stride_length")) -> pd.DataFrame:
    """Saving of a fixed dead-zone design when the gait's period or amplitude changes.

    The design is frozen on the nominal gait — its neutral angles are absolute, taken from the
    nominal ranges of motion — as a built spring would be; only the gait changes.

    Args:
        run: The run: robot, actuator, objective, contact and the nominal gait (the design
            was chosen for it).
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
    springs = evaluator(run).springs(groups, design)
    rows = []
    for p in parameters:
        for fct in factors:
            cond = (Condition(period=float(fct)) if p == "period"
                    else Condition(stride=float(fct)))
            r = condition_savings(condition_prepared(run, cond), springs, run.objective,
                                  (metric,))
            rows.append({"parameter": p, "factor": float(fct),
                         "gait value": getattr(condition_gait(run.gait, cond), p),
                         "value": r[metric], "baseline": r[f"baseline.{metric}"],
                         "saving": r[f"saving.{metric}"], "status": r["status"]})
    return pd.DataFrame(rows)
