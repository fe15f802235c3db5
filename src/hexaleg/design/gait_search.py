"""The outer search of the gait + spring co-design: the gait parameters that minimise the
electrical energy per metre at a required speed, each candidate with its own optimal springs.

The search is derivative-free: a gait is made by leg inverse kinematics and its energy comes
from a convex program whose active set changes with the gait, so the objective is continuous but
not smooth, and a gait that cannot be made has no value at all. scipy's Nelder–Mead simplex
(Nelder & Mead, "A simplex method for function minimization", Comput. J. 7(4), 1965; Gao & Han's
adaptive coefficients for dimension n, Comput. Optim. Appl. 51, 2012, ``adaptive=True``) runs
on the parameters scaled to [0, 1] within their :class:`Space` bounds, restarted
(:data:`RESTARTS`): once from the robot's default gait, then from the best point so far with a
fresh, smaller simplex, and from the opposite corner's midpoint — a restart is the standard cure
for a simplex that collapses early (Nocedal & Wright, *Numerical Optimization*, 2nd ed., 2006,
§9.5). Nelder–Mead rather than CMA-ES: with 5 parameters and ~0.5 s a candidate the budget is
~100 evaluations, where CMA-ES's default population (4 + 3 ln 5 ≈ 8) would run ~12 generations;
the simplex makes progress from the first few evaluations and needs no new dependency.

A candidate that fails (no gait, no admissible forces) or breaks a constraint
(:class:`~hexaleg.design.gait_evaluation.Constraints`) is a penalty, not an error
(:func:`penalised`). Evaluations are cached on the scaled point rounded to 1e-6.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize

from hexaleg.checks import integer
from hexaleg.design.gait_evaluation import PARAMETERS, GaitPoint, with_values
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.motion.params import GaitParams

RESTARTS = 3
"""Simplex runs: from the default gait, from the best so far (smaller simplex), from the middle
of the box between the best and the default gait's mirror."""
FAIL = 3.0
"""A failing gait's value: this many times the reference energy per metre, plus its distance to
the default gait (so the simplex is pulled back towards gaits that exist)."""
WEIGHT = 10.0
"""A constraint's relative violation costs this many reference energies per metre."""
FINALISTS = 6
"""How many of the best distinct feasible gaits the search hands on (:attr:`SearchResult.
finalists`): the co-design simulates each before it chooses (:mod:`hexaleg.design.codesign.
servo`)."""
SPACING = 0.05
"""Two finalists differ by at least this distance in the parameters scaled to [0, 1] (the best
of a cluster stands for it: a simplex's last evaluations are near-copies of its best)."""


@dataclass(frozen=True)
class Space:
    """Bounds of the free gait parameters, SI.

    Attributes:
        bounds: Parameter → (low, high); its keys are the free parameters, a subset of
            :data:`hexaleg.design.gait_evaluation.PARAMETERS`.
    """

    bounds: Mapping[str, tuple[float, float]]

    def __post_init__(self) -> None:
        for name, pair in self.bounds.items():
            if name not in PARAMETERS:
                raise UnknownNameError("co-design parameter", name, PARAMETERS)
            lo, hi = pair
            if not (math.isfinite(lo) and math.isfinite(hi) and 0 < lo < hi):
                raise InvalidParameterError(f"bounds of {name}", pair,
                                            "finite 0 < low < high")
        if not self.bounds:
            raise InvalidParameterError("bounds", dict(self.bounds), "at least one parameter")

    @property
    def names(self) -> tuple[str, ...]:
        """The free parameters, in :data:`PARAMETERS` order."""
        return tuple(p for p in PARAMETERS if p in self.bounds)

    def values(self, u: np.ndarray) -> dict[str, float]:
        """Parameter values at the scaled point ``u`` (clipped to [0, 1])."""
        u = np.clip(u, 0.0, 1.0)
        return {n: lo + float(x) * (hi - lo)
                for n, x, (lo, hi) in zip(self.names, u, (self.bounds[n] for n in self.names),
                                          strict=True)}

    def scaled(self, values: Mapping[str, float]) -> np.ndarray:
        """The scaled point of parameter values (the inverse of :meth:`values`)."""
        return np.array([(values[n] - self.bounds[n][0])
                         / (self.bounds[n][1] - self.bounds[n][0]) for n in self.names])


def default_space(gait: GaitParams, min_step: float, free: Sequence[str] = PARAMETERS,
                  duty_high: float = 0.8) -> Space:
    """The default box about a robot's gait ``gait`` (its resolved values): body height and
    foot radius ×[0.7, 1.3], step height [``min_step``, 1.5 × default], duty factor [the
    pattern's β₀, max(β₀ + 0.05, ``duty_high``)] (β₀ is the least that keeps the pattern's
    support: 0.5 for a tripod or trot, 0.75 for a crawl), period ×[0.5, 2]."""
    assert gait.body_height is not None and gait.foot_radius is not None
    beta = gait.duty_factor
    box = {"body_height": (0.7 * gait.body_height, 1.3 * gait.body_height),
           "foot_radius": (0.7 * gait.foot_radius, 1.3 * gait.foot_radius),
           "step_height": (min_step, max(1.5 * gait.step_height, 2 * min_step)),
           "duty_factor": (beta, max(beta + 0.05, min(duty_high, 0.95))),
           "period": (0.5 * gait.period, 2.0 * gait.period)}
    return Space({n: box[n] for n in PARAMETERS if n in free})


def penalised(point: GaitPoint, reference: float, distance: float, springs: bool) -> float:
    """The search's value of a candidate, J/m: its energy per metre (with its springs when
    ``springs``) when it meets every constraint; plus ``WEIGHT · reference ·`` its summed
    relative violation when it does not; ``FAIL · reference + distance · reference`` (the
    scaled distance to the default gait) when it cannot be made or analysed."""
    if point.error is not None:
        return (FAIL + distance) * reference
    value = point.per_metre_springs if springs else point.per_metre
    return value + WEIGHT * reference * point.violation()


@dataclass(frozen=True)
class SearchResult:
    """What the outer search found.

    Attributes:
        best: The best feasible gait (or the least penalised one when none is feasible).
        value: Its search value, J/m. restarts: Each simplex run's best value, J/m.
        evaluations: Candidates evaluated (cache hits not counted). wall: s.
        history: Every evaluation's value, J/m, in order.
        method: The optimiser and its settings, for the record.
        finalists: Up to :data:`FINALISTS` feasible gaits, best first, each the best of those
            within :data:`SPACING` of it (``best`` first when it is feasible).
    """

    best: GaitPoint
    value: float
    restarts: tuple[float, ...]
    evaluations: int
    wall: float
    history: tuple[float, ...]
    method: str
    finalists: tuple[GaitPoint, ...] = ()

    @property
    def spread(self) -> float:
        """Largest minus smallest restart value, J/m."""
        return max(self.restarts) - min(self.restarts)


def search(evaluate: Callable[[GaitParams], GaitPoint], base: GaitParams, speed: float,
           space: Space, *, springs: bool, reference: float, max_evaluations: int = 120,
           restarts: int = RESTARTS) -> SearchResult:
    """Minimise :func:`penalised` over ``space`` by restarted Nelder–Mead (module docstring).

    Args:
        evaluate: A gait → its evaluated point
            (:func:`~hexaleg.design.gait_evaluation.evaluate_gait`, robot and springs bound).
        base: The gait whose other fields the candidates keep (pattern, samples, …); its values
            of the free parameters are the first start.
        speed: The required speed, m/s.
        space: The free parameters and their bounds.
        springs: Whether the value is the energy with the candidate's springs.
        reference: The reference energy per metre of the penalties, J/m (> 0).
        max_evaluations: Budget of evaluations over all restarts (≥ 10), shared equally by
            the runs still to go.
        restarts: Simplex runs (1 to 5).
    """
    budget = integer("max_evaluations", max_evaluations, low=10, high=10_000)
    runs = integer("restarts", restarts, low=1, high=5)
    start = time.perf_counter()
    u0 = np.clip(space.scaled({n: getattr(base, n) for n in space.names}), 0.0, 1.0)
    cache: dict[tuple[float, ...], tuple[float, GaitPoint]] = {}
    history: list[float] = []

    def f(u: np.ndarray) -> float:
        outside = float(np.sum(np.maximum(0.0, -u) + np.maximum(0.0, u - 1.0)))
        inside = np.clip(u, 0.0, 1.0)
        key = tuple(np.round(inside, 6))
        if key not in cache:
            if len(history) >= budget:
                return math.inf
            point = evaluate(with_values(base, speed, space.values(inside)))
            value = penalised(point, reference, float(np.linalg.norm(inside - u0)), springs)
            cache[key] = (value, point)
            history.append(value)
        return cache[key][0] + WEIGHT * reference * outside

    bests: list[float] = []
    starts = [u0]
    for run in range(runs):
        if len(history) >= budget:
            break
        if run > 0:
            best_u = np.array(min(cache, key=lambda k: cache[k][0]))
            starts.append(best_u if run == 1 else np.clip(0.5 * (best_u + (1.0 - u0)), 0, 1))
        x0 = starts[-1]
        step = 0.25 if run != 1 else 0.1
        simplex = np.vstack([x0] + [x0 + step * (1 if x0[i] < 0.5 else -1) * np.eye(len(x0))[i]
                                    for i in range(len(x0))])
        left = (budget - len(history)) // (runs - run)  # the budget shared by the runs left
        res = minimize(f, x0, method="Nelder-Mead",
                       options={"initial_simplex": simplex, "maxfev": left, "xatol": 1e-3,
                                "fatol": 1e-3 * reference, "adaptive": True})
        bests.append(float(min(res.fun, f(np.clip(res.x, 0, 1)))))
    value, best = min(cache.values(), key=lambda vp: vp[0])
    return SearchResult(best=best, value=value, restarts=tuple(bests),
                        evaluations=len(history), wall=time.perf_counter() - start,
                        history=tuple(history),
                        method=f"scipy Nelder-Mead (adaptive), {len(bests)} restarts, "
                               f"budget {budget} evaluations, parameters scaled to [0, 1]",
                        finalists=finalists(cache))


def finalists(cache: Mapping[tuple[float, ...], tuple[float, GaitPoint]]
              ) -> tuple[GaitPoint, ...]:
    """The best distinct feasible gaits of a search's evaluations (scaled point → value and
    point): in ascending value (ties by the scaled point, so the order is the same whatever
    order they were evaluated in), each kept when it is at least :data:`SPACING` from every one
    kept before it, up to :data:`FINALISTS`."""
    kept: list[tuple[np.ndarray, GaitPoint]] = []
    for key, (_value, point) in sorted(cache.items(), key=lambda kv: (kv[1][0], kv[0])):
        u = np.array(key)
        if not point.feasible or any(np.linalg.norm(u - v) < SPACING for v, _ in kept):
            continue
        kept.append((u, point))
        if len(kept) == FINALISTS:
            break
    return tuple(p for _, p in kept)


__all__ = ["FAIL", "FINALISTS", "RESTARTS", "SPACING", "WEIGHT", "SearchResult", "Space",
           "default_space", "finalists", "penalised", "search"]
