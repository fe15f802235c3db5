"""The outer search of the co-design: bounded, penalised, not stuck (a dense grid on a reduced
problem never beats it by more than the grid's resolution), at a lattice point no neighbour
beats, and the same answer whatever the rounding of its values, the order they are solved in or
a 1e-9 change of the start."""

from __future__ import annotations

import dataclasses
import functools
import itertools
from collections.abc import Callable

import numpy as np
import pytest

from hexaleg.design.codesign.box import default_space
from hexaleg.design.codesign.gait_evaluation import (
    Constraints,
    GaitPoint,
    evaluate_gait,
    with_values,
)
from hexaleg.design.codesign.gait_search import (
    FAIL,
    MIN_STEP,
    TIE,
    Space,
    lattice_bounds,
    lattice_point,
    penalised,
    search,
)
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


SPACE = Space({"body_height": (0.05, 0.15), "duty_factor": (0.5, 0.9), "period": (0.5, 2.0)})


def synthetic(value: Callable[[np.ndarray], float], space: Space = SPACE
              ) -> Callable[[GaitParams], GaitPoint]:
    """An ``evaluate`` whose energy per metre (with springs) is ``value`` of the scaled point."""
    def evaluate(g: GaitParams) -> GaitPoint:
        u = space.scaled({n: getattr(g, n) for n in space.names})
        return GaitPoint(params=g, distance=1.0, baseline=1.0, sprung=value(u))
    return evaluate


def bowl(u: np.ndarray) -> float:
    return 1.0 + float(np.sum(np.array([1.0, 3.0, 0.5]) * (u - np.array([0.31, 0.77, 0.18])) ** 2))


def test_a_bowl_is_found_to_the_lattice_and_no_neighbour_beats_it():
    """A separable quadratic in the box: the search ends within a lattice step of its minimiser
    on every parameter, at a point each of whose 2n neighbours one finest step away is not
    lower by more than the tie (the stated local optimality)."""
    result = search(synthetic(bowl), BASE, 0.06, SPACE, springs=True, reference=1.0,
                    max_evaluations=400, restarts=2)
    u = SPACE.scaled({n: getattr(result.best.params, n) for n in SPACE.names})
    assert np.all(np.abs(u - np.array([0.31, 0.77, 0.18])) <= MIN_STEP)
    for i in range(3):
        for sign in (1, -1):
            v = np.clip(u + sign * MIN_STEP * np.eye(3)[i], 0, 1)
            assert bowl(v) >= result.value - TIE
    assert result.value == pytest.approx(bowl(u), abs=1e-15)
    assert result.evaluations < 400 and len(result.restarts) == 2
    assert result.spread <= TIE  # both runs end at the same point


def twin(u: np.ndarray) -> float:
    """Two equal basins, mirror images about the default gait's body height (scaled 0.5)."""
    a = min((u[0] - 0.2) ** 2, (u[0] - 0.8) ** 2)
    return 1.0 + a + float(np.sum((u[1:] - 0.4) ** 2))


def test_rounding_noise_does_not_move_the_search():
    """Every value perturbed by a relative 1e-12 (another machine's rounding; a different draw
    each time): the search makes the same decisions, evaluates the same points and ends at the
    same gait. Its first poll ties the two basins: a search that takes the least value of a
    poll goes to one basin or the other with the noise."""
    base = dataclasses.replace(BASE, body_height=0.1, duty_factor=0.7, period=1.25)
    ends, paths = set(), set()
    for seed in range(6):
        noise = np.random.default_rng(seed).standard_normal

        def noisy(u: np.ndarray, noise: Callable[[], float] = noise) -> float:
            return twin(u) * (1 + 1e-12 * noise())
        result = search(synthetic(noisy), base, 0.06, SPACE, springs=True, reference=1.0,
                        max_evaluations=200, restarts=1)
        ends.add(tuple(round(getattr(result.best.params, n), 12) for n in SPACE.names))
        paths.add(len(result.history))
    assert len(ends) == 1 and len(paths) == 1
    # the + basin, polled first
    assert abs(next(iter(ends))[0] - (0.05 + 0.8 * 0.1)) <= MIN_STEP * 0.1


def test_a_tiny_change_of_the_start_changes_nothing_printed():
    """The default gait's body height moved by 1e-9 m (the lattice moves with it): the same
    number of evaluations and the same answer to 1e-8."""
    base = dataclasses.replace(BASE, body_height=0.1, duty_factor=0.7, period=1.25)
    a = search(synthetic(bowl), base, 0.06, SPACE, springs=True, reference=1.0,
               max_evaluations=300)
    moved = dataclasses.replace(base, body_height=0.1 + 1e-9)
    b = search(synthetic(bowl), moved, 0.06, SPACE, springs=True, reference=1.0,
               max_evaluations=300)
    assert a.evaluations == b.evaluations
    for n in SPACE.names:
        assert getattr(a.best.params, n) == pytest.approx(getattr(b.best.params, n), abs=1e-8)


def beyond(u: np.ndarray) -> float:
    """Lowest beyond the body height's upper face (scaled 1.3): the optimum sits on the face,
    as the default co-design's chosen gait does on ``body_high``."""
    return 1.0 + float(np.sum((u - np.array([1.3, 0.6, 0.4])) ** 2))


def test_a_nano_change_of_a_face_the_start_is_whole_steps_from_changes_nothing():
    """The body height's upper bound moved by 1e-9 of itself, the default gait a whole number of
    lattice steps (16) from it: the same evaluations and the same answer. The face had become
    one integer more (ceil of 16.00000002), its point the face and the one before 8e-10 inside
    it: two lattice points for one gait, the co-design's 138 evaluations 141."""
    base = dataclasses.replace(BASE, body_height=0.1, duty_factor=0.7, period=1.25)
    moved = Space({**SPACE.bounds, "body_height": (0.05, 0.15 * (1 + 1e-9))})
    a = search(synthetic(beyond), base, 0.06, SPACE, springs=True, reference=1.0,
               max_evaluations=300)
    b = search(synthetic(beyond, moved), base, 0.06, moved, springs=True, reference=1.0,
               max_evaluations=300)
    assert a.evaluations == b.evaluations
    assert a.best.params.body_height == 0.15
    assert b.best.params.body_height == 0.15 * (1 + 1e-9)  # on the face, not 8e-10 inside
    for n in ("duty_factor", "period"):
        assert getattr(a.best.params, n) == getattr(b.best.params, n)


def test_the_lattice_reaches_a_face_a_rounding_beyond_a_point_at_that_point():
    """:func:`lattice_bounds`: no integer for a face within ``FACE`` of a step beyond a lattice
    point; :func:`lattice_point` puts that point on the face."""
    u0 = np.array([0.5 - 8e-10, 0.5, 0.0, 1 / 3, 8e-10])
    low, high = lattice_bounds(u0)
    assert high.tolist() == [16, 16, 32, 22, 32] and low.tolist() == [-16, -16, 0, -11, 0]
    assert lattice_point(u0, (16, 16, 32, 22, 0)).tolist() == [1.0, 1.0, 1.0, 1.0, 0.0]
    assert lattice_point(u0, (15, 0, 1, 0, 1)).tolist() == pytest.approx(
        [1 - MIN_STEP - 8e-10, 0.5, MIN_STEP, 1 / 3, MIN_STEP + 8e-10], abs=1e-15)


def test_the_order_a_poll_is_solved_in_changes_nothing():
    """A map that solves a poll's candidates in reverse order (returning them in order) and one
    over forked processes give the serial search's result bit for bit; a map that returns
    them shuffled moves it (so the test would catch a search that leaned on the order)."""
    from hexaleg.parallel.forked import fork_map

    def reverse(fn, items):
        return [fn(x) for x in items[::-1]][::-1]

    def shuffled(fn, items):
        out = [fn(x) for x in items]
        return out[1:] + out[:1]

    runs = [search(synthetic(bowl), BASE, 0.06, SPACE, springs=True, reference=1.0,
                   max_evaluations=150, map_fn=m) for m in (None, reverse, fork_map, shuffled)]
    serial = runs[0]
    for other in runs[1:3]:
        assert other.history == serial.history and other.value == serial.value
        assert other.best.params == serial.best.params
    assert runs[3].history != serial.history


def test_the_budget_stops_a_run_where_it_is():
    result = search(synthetic(bowl), BASE, 0.06, SPACE, springs=True, reference=1.0,
                    max_evaluations=13, restarts=3)
    assert result.evaluations == 13 and len(result.restarts) == 1


def test_progress_says_where_the_search_is_and_changes_nothing():
    """One line a poll: the run, the evaluations against the budget, the step, the best so far
    and the time left at most; the search with it evaluates the same points (issue #57: the
    co-design printed nothing for minutes)."""
    lines: list[str] = []
    quiet = search(synthetic(bowl), BASE, 0.06, SPACE, springs=True, reference=1.0,
                   max_evaluations=60, restarts=2)
    said = search(synthetic(bowl), BASE, 0.06, SPACE, springs=True, reference=1.0,
                  max_evaluations=60, restarts=2, progress=lines.append)
    assert said.history == quiet.history and said.value == quiet.value
    assert lines and lines[0].startswith("run 1 of 2, ")
    done = [int(line.split(", ")[1].split(" of ")[0]) for line in lines]
    assert done == sorted(done) and done[-1] == said.evaluations
    assert all(" of at most 60 evaluations, step 1/" in line for line in lines)
    assert "step 1/4 of each range" in lines[0]
    assert f"best {said.value:.2f} J/m" in lines[-1]
    assert all("s more at this pace)" in line for line in lines)
