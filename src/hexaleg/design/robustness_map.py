"""Robustness maps: a frozen design's saving over a grid of two conditions, and its worst case.

Each cell is one :class:`~hexaleg.design.robustness.Condition` — the two mapped conditions set,
the others nominal — prepared afresh (:func:`~hexaleg.design.robustness.condition_prepared`) and
evaluated with the frozen springs (:func:`~hexaleg.design.robustness.condition_savings`), so a
cell equals a fresh ``analyze`` of that condition. A cell whose gait has no admissible forces
even without springs is outside the robot's envelope (its saving NaN, left out of the worst
case); one where only the springs make it infeasible counts as −∞, the worst there is.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from hexaleg.checks import finite_array, one_of
from hexaleg.design.evaluator import DEFAULT_METRIC, RunSpec
from hexaleg.design.robustness import (
    CONDITIONS,
    Condition,
    condition_prepared,
    condition_savings,
)
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.params import GaitParams
from hexaleg.robot.springs import SpringSet

METRICS: tuple[str, ...] = (DEFAULT_METRIC, "joule")
"""Metrics a map records (the saving of each)."""


@dataclass(frozen=True, eq=False)
class RobustnessMap:
    """A frozen design's savings over a grid of two conditions.

    Attributes:
        axes: The two conditions mapped (of :data:`~hexaleg.design.robustness.CONDITIONS`).
        values: Their values, shapes (n₁,) and (n₂,) (factors; payload a fraction; μ).
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
        return Condition(**{self.axes[0]: float(self.values[0][i]),
                            self.axes[1]: float(self.values[1][j])})

    def worst(self, metric: str = DEFAULT_METRIC) -> tuple[float, Condition | None]:
        """The lowest saving over the cells inside the envelope, and its condition (None when
        no cell is)."""
        s = self.saving[metric]
        if np.all(np.isnan(s)):
            return float("nan"), None
        i, j = np.unravel_index(int(np.nanargmin(s)), s.shape)
        return float(s[i, j]), self.condition(int(i), int(j))


def _check_axes(axes: Mapping[str, Sequence[float]]
                ) -> tuple[tuple[str, str], tuple[np.ndarray, np.ndarray]]:
    """The two axis names and their values as 1-D float arrays, checked."""
    names = tuple(axes)
    if len(names) != 2:
        raise InvalidParameterError("map axes", names, f"two of {', '.join(CONDITIONS)}")
    values = []
    for name in names:
        one_of("map axis", name, CONDITIONS)
        v = finite_array(f"map axis {name}", axes[name])
        if v.ndim != 1 or not v.size:
            raise InvalidParameterError(f"map axis {name}", axes[name],
                                        "a non-empty list of values")
        values.append(v)
    return (names[0], names[1]), (values[0], values[1])


def robustness_map(run: RunSpec, gait: GaitParams, springs: SpringSet,
                   axes: Mapping[str, Sequence[float]],
                   metrics: Sequence[str] = METRICS) -> RobustnessMap:
    """The saving of frozen ``springs`` over a grid of two conditions (module docstring).

    Args:
        run: Robot, actuator, force objective, contact (the nominal conditions).
        gait: The nominal gait.
        springs: The frozen springs (absolute angles).
        axes: Two conditions → their values, e.g. ``{"period": [0.5, 1, 2], "stride": [...]}``
            (period and stride factors, payload a fraction of the robot's mass, μ absolute).
        metrics: Metrics whose saving is recorded.

    Returns:
        The map.

    Raises:
        UnknownNameError: an axis not in :data:`~hexaleg.design.robustness.CONDITIONS`.
        InvalidParameterError: not two axes, an axis without values, a value out of range, a
            factor whose gait the robot cannot reach (names it and what to change).
    """
    (a, b), (va, vb) = _check_axes(axes)
    out = {m: np.full((va.size, vb.size), np.nan) for m in metrics}
    status = np.empty((va.size, vb.size), dtype=object)
    for i, x in enumerate(va):
        for j, y in enumerate(vb):
            cond = Condition(**{a: float(x), b: float(y)})
            r = condition_savings(condition_prepared(run, gait, cond), springs, run.objective,
                                  metrics)
            status[i, j] = r["status"]
            for m in metrics:
                out[m][i, j] = -np.inf if r["status"].startswith("springs") else r[f"saving.{m}"]
    return RobustnessMap(axes=(a, b), values=(va, vb), saving=out, status=status)
