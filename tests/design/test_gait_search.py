"""The outer search of the co-design: bounded, penalised, and not stuck (a dense grid on a
reduced problem never beats it by more than the grid's resolution)."""

from __future__ import annotations

import dataclasses
import functools
import itertools

import numpy as np
import pytest

from hexaleg.design.gait_evaluation import Constraints, GaitPoint, evaluate_gait, with_values
from hexaleg.design.gait_search import FAIL, Space, default_space, penalised, search
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.motion.params import GaitParams

BASE = GaitParams(samples=60, speed=0.06, body_height=0.0913, foot_radius=0.1889)


def test_space_maps_both_ways_and_checks_its_bounds():
    space = default_space(BASE, 0.015)
    assert space.names == ("body_height", "foot_radius", "step_height", "duty_factor", "period")
    u = space.scaled({n: getattr(BASE, n) for n in space.names})
    assert np.all((u >= 0) & (u <= 1))
    assert space.values(u)["period"] == pytest.approx(1.0)
    with pytest.raises(UnknownNameError):
        Space({"stride_length": (0.1, 0.2)})
    with pytest.raises(InvalidParameterError, match="period"):
        Space({"period": (1.0, 0.5)})


def test_a_failing_gait_is_a_penalty():
    failed = GaitPoint(params=BASE, distance=0.06, error="GaitReachError: out of reach")
    assert penalised(failed, 10.0, 0.5, True) == pytest.approx((FAIL + 0.5) * 10.0)


def test_the_search_is_not_beaten_by_a_dense_grid(robot):
    """Period × duty factor at the default geometry, no springs: a 6 × 6 grid's best is not
    below the search's by more than the grid's resolution (the largest change of the value
    between the grid's best point and a neighbour)."""
    c = Constraints()
    ev = functools.partial(evaluate_gait, robot, groups=None, family="linear", constraints=c,
                           min_margin=0.05)
    space = Space({"duty_factor": (0.5, 0.8), "period": (0.5, 2.0)})
    reference = ev(BASE).per_metre
    result = search(ev, BASE, 0.06, space, springs=False, reference=reference,
                    max_evaluations=40, restarts=2)
    axes = [np.linspace(0, 1, 6)] * 2
    grid = np.full((6, 6), np.inf)
    for (i, a), (j, b) in itertools.product(enumerate(axes[0]), enumerate(axes[1])):
        point = ev(with_values(BASE, 0.06, space.values(np.array([a, b]))))
        grid[i, j] = penalised(point, reference, 0.0, False)
    i, j = np.unravel_index(np.argmin(grid), grid.shape)
    neighbours = [grid[i + di, j + dj] for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1))
                  if 0 <= i + di < 6 and 0 <= j + dj < 6]
    resolution = max(abs(n - grid[i, j]) for n in neighbours)
    assert result.value <= grid[i, j] + resolution
    assert result.best.feasible and result.evaluations <= 40
    assert len(result.restarts) == 2 and result.spread >= 0
    assert result.value <= reference  # never worse than the default gait


def test_search_budget_is_checked(robot):
    with pytest.raises(InvalidParameterError, match="max_evaluations"):
        search(lambda g: GaitPoint(g, 0.06), BASE, 0.06, default_space(BASE, 0.015),
               springs=False, reference=1.0, max_evaluations=2)
    assert dataclasses.is_dataclass(BASE)
