"""Robustness maps: a frozen design's saving over a grid of two conditions, and its worst case.

Each cell is one :class:`~hexaleg.design.robust.conditions.Condition` — the two mapped conditions
set, the others nominal — prepared afresh (:func:`~hexaleg.design.robust.conditions.condition_walk`;
cells that walk the same motion, as a payload's at every μ, share it: it is made once)
and evaluated with the frozen springs (:func:`~hexaleg.design.robust.conditions.condition_savings`),
so a cell equals a fresh ``analyze`` of that condition. A cell whose gait cannot be made (a foot out
of reach, a crawl without static margin, a slope the friction cannot hold: status ``"no gait:
…"``) or has no admissible forces even without springs (``"no baseline: …"``) is outside the
robot's envelope (its saving NaN, left out of the worst case); one where only the springs make
it infeasible (``"springs: …"``) counts as −∞, the worst there is. The ``pattern`` axis is the
one whose values are names (strings); every other axis holds numbers.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.checks import finite_array, one_of, typed
from hexaleg.design.evaluator import DEFAULT_METRIC
from hexaleg.design.robust.conditions import (
    condition_savings,
    condition_walk,
    condition_walks,
    same_motion,
)
from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.params import GaitParams
from hexaleg.motion.patterns import PATTERNS, leg_offsets, pattern_offsets
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet
from hexaleg.scenario.condition import CONDITIONS, Condition
from hexaleg.scenario.scenario import Scenario

METRICS: tuple[str, ...] = (DEFAULT_METRIC, "joule")
"""Metrics a map records (the saving of each)."""
NAMED: tuple[str, ...] = ("pattern",)
"""Conditions whose values are names, not numbers."""


def _value(axis: str, value: Any) -> float | str:
    """A map value as a :class:`Condition` takes it: a name, or a float."""
    return str(value) if axis in NAMED else float(value)


def _condition(cells: Mapping[str, Any]) -> Condition:
    """The condition with the mapped ``cells`` (axis → value) set, the others nominal."""
    kwargs: dict[str, Any] = {axis: _value(axis, v) for axis, v in cells.items()}
    return Condition(**kwargs)


@dataclass(frozen=True, eq=False)
class RobustnessMap:
    """A frozen design's savings over a grid of two conditions.

    Attributes:
        axes: The two conditions mapped (of :data:`~hexaleg.scenario.condition.CONDITIONS`).
        values: Their values, shapes (n₁,) and (n₂,): floats (factors; payload a fraction; μ;
            slope in rad), or for the ``pattern`` axis an object array of pattern names (str).
        saving: Metric → saving per cell, shape (n₁, n₂), fraction (NaN outside the envelope,
            −∞ where only the springs make the gait infeasible).
        status: Per cell ``"ok"`` or why there is no number, shape (n₁, n₂).
    """

    axes: tuple[str, str]
    values: tuple[np.ndarray, np.ndarray]
    saving: dict[str, np.ndarray]
    status: np.ndarray

    def condition(self, i: int, j: int) -> Condition:
        """The condition of cell (i, j)."""
        return _condition({self.axes[0]: self.values[0][i], self.axes[1]: self.values[1][j]})

    def worst(self, metric: str = DEFAULT_METRIC) -> tuple[float, Condition | None]:
        """The lowest saving over the cells inside the envelope, and its condition (None when
        no cell is)."""
        s = self.saving[metric]
        if np.all(np.isnan(s)):
            return float("nan"), None
        i, j = np.unravel_index(int(np.nanargmin(s)), s.shape)
        return float(s[i, j]), self.condition(int(i), int(j))


def _axis(name: str, given: Any) -> np.ndarray:
    """One axis's values, checked: pattern names as an object array, else finite floats; each
    value a valid :class:`Condition` (a named error before any cell runs)."""
    one_of("map axis", name, CONDITIONS)
    if name in NAMED:
        if isinstance(given, (str, bytes)) or not isinstance(given, (list, tuple, np.ndarray)) \
                or not len(given):
            raise InvalidParameterError(f"map axis {name}", given, "a non-empty list of "
                                        f"pattern names ({', '.join(PATTERNS)})")
        v = np.array([str(x) if isinstance(x, str) else x for x in given], dtype=object)
    else:
        v = finite_array(f"map axis {name}", given)
        if v.ndim != 1 or not v.size:
            raise InvalidParameterError(f"map axis {name}", given, "a non-empty list of values")
    for x in v:
        _condition({name: x})
    return v


def _check_axes(axes: Mapping[str, Any]) -> tuple[tuple[str, str], tuple[np.ndarray, np.ndarray]]:
    """The two axis names and their values (:func:`_axis`), checked."""
    names = tuple(axes)
    if len(names) != 2:
        raise InvalidParameterError("map axes", names, f"two of {', '.join(CONDITIONS)}")
    return (names[0], names[1]), (_axis(names[0], axes[names[0]]),
                                  _axis(names[1], axes[names[1]]))


def robot_patterns(robot: Robot, gait: GaitParams) -> tuple[str, ...]:
    """The named patterns the robot's legs can walk (:data:`~hexaleg.motion.patterns.PATTERNS`
    for its legs a side: hexapod tripod, ripple, wave; quadruped crawl, trot, pace), the
    nominal gait's first: its ``pattern``, or the pattern whose touch-down offsets its legs'
    equal up to a common shift of the cycle's origin (the hexapod's tripods are the tripod).

    Args:
        robot: The robot (its leg names say side and place).
        gait: The nominal gait.

    Returns:
        Pattern names; empty when the legs' names do not say side and place.
    """
    legs = robot.leg_names
    fit = {}
    for name in PATTERNS:
        try:
            fit[name] = pattern_offsets(name, legs)
        except InvalidParameterError:
            continue
    nominal = gait.pattern
    if nominal is None and fit:
        own = leg_offsets(legs, None, gait.phases, gait.groups)
        for name, offsets in fit.items():
            d = (own - offsets - (own[0] - offsets[0])) % 1.0
            if np.all(np.minimum(d, 1.0 - d) < 1e-9):
                nominal = name
                break
    return tuple(sorted(fit, key=lambda n: n != nominal))


Cell = tuple[str, dict[str, float]]
"""One map cell: its status (``"ok"`` or why there is no number) and metric → saving."""
Mapper = Callable[[Callable[[list[Condition]], list[Cell]], Sequence[list[Condition]]],
                  Sequence[list[Cell]]]
"""How a map's cells are computed: ``mapper(fn, groups)`` is ``[fn(g) for g in groups]``, a
group the cells that walk one motion (:func:`~hexaleg.design.robust.conditions.same_motion`;
e.g. spread over processes, :func:`hexaleg.parallel.forked.fork_map`)."""


def _in_turn(fn: Callable[[list[Condition]], list[Cell]],
             groups: Sequence[list[Condition]]) -> list[list[Cell]]:
    return [fn(g) for g in groups]


def map_cell(run: Scenario, springs: SpringSet, condition: Condition,
             metrics: Sequence[str] = METRICS) -> Cell:
    """One cell: the condition's gait prepared afresh and the frozen ``springs`` on it (NaN
    savings where the gait cannot be made or has no baseline, −∞ where only the springs make
    it infeasible; module docstring)."""
    return _cell(run, springs, condition_walk(run, condition), metrics)


def map_cells(run: Scenario, springs: SpringSet, conditions: Sequence[Condition],
              metrics: Sequence[str] = METRICS, nominal: Motion | None = None) -> list[Cell]:
    """:func:`map_cell` of each of ``conditions`` that walk one motion, the motion made once
    (:func:`~hexaleg.design.robust.conditions.condition_walks`; ``nominal``: the run's own
    motion, when made)."""
    return [_cell(run, springs, p, metrics)
            for p in condition_walks(run, conditions, nominal)]


def _cell(run: Scenario, springs: SpringSet, prepared: Prepared | str,
          metrics: Sequence[str]) -> Cell:
    if isinstance(prepared, str):
        return prepared, {m: float("nan") for m in metrics}
    r = condition_savings(prepared, springs, run.objective, metrics)
    return r["status"], {m: -np.inf if r["status"].startswith("springs") else
                         float(r[f"saving.{m}"]) for m in metrics}


@typed
def robustness_map(run: Scenario, springs: SpringSet,
                   axes: Mapping[str, Sequence[float] | Sequence[str]],
                   metrics: Sequence[str] = METRICS, mapper: Mapper | None = None,
                   nominal: Motion | None = None) -> RobustnessMap:
    """The saving of frozen ``springs`` over a grid of two conditions (module docstring).

    Args:
        run: The run: robot, actuator, force objective, contact and the nominal gait (the
            nominal conditions).
        springs: The frozen springs (absolute angles).
        axes: Two conditions → their values, e.g. ``{"period": [0.5, 1, 2], "stride": [...]}``
            or ``{"slope": [-0.26, 0, 0.26], "pattern": ["tripod", "wave"]}`` (period and
            stride factors, payload a fraction of the robot's mass, μ absolute, slope in rad
            added to the nominal gait's, pattern names).
        metrics: Metrics whose saving is recorded.
        mapper: How the cells are computed (:data:`Mapper`): each motion made once, in the
            group of cells that walk it; default one group after the other.
        nominal: The run's own motion (``run.motion()``) when it is already made: the cells
            of the nominal gait and payload walk it.

    Returns:
        The map; a condition the robot cannot walk is a cell with its reason (``"no gait: …"``).

    Raises:
        UnknownNameError: an axis not in :data:`~hexaleg.scenario.condition.CONDITIONS`, or an
            unknown pattern (lists them).
        InvalidParameterError: not two axes, an axis without values, a value out of range, a
            pattern for other legs than the robot's (lists those that fit).
    """
    (a, b), (va, vb) = _check_axes(axes)
    for name, values in ((a, va), (b, vb)):
        if name == "pattern":
            for p in values:
                pattern_offsets(p, run.model.leg_names)
    conditions = [_condition({a: x, b: y}) for x in va for y in vb]
    groups = same_motion(run, conditions)
    walked = (mapper or _in_turn)(lambda cs: map_cells(run, springs, cs, metrics, nominal),
                                  [[conditions[i] for i in g] for g in groups])
    cells: list[Cell] = [("", {})] * len(conditions)
    for g, done in zip(groups, walked, strict=True):
        for i, cell in zip(g, done, strict=True):
            cells[i] = cell
    out = {m: np.array([s[m] for _, s in cells]).reshape(va.size, vb.size) for m in metrics}
    status = np.array([st for st, _ in cells], dtype=object).reshape(va.size, vb.size)
    return RobustnessMap(axes=(a, b), values=(va, vb), saving=out, status=status)
