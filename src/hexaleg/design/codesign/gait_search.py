"""The outer search of the gait + spring co-design: the gait parameters that minimise the
electrical energy per metre at a required speed, each candidate with its own optimal springs.

The search is derivative-free: a gait is made by leg inverse kinematics and its energy comes
from a convex program whose active set changes with the gait, so the objective is continuous but
not smooth, and a gait that cannot be made has no value at all. It is a compass search — a
generalised pattern search with complete polling (Kolda, Lewis & Torczon, "Optimization by
direct search: new perspectives on some classical and modern methods", SIAM Review 45(3), 2003,
§3 and Algorithm 3.2; Torczon, SIAM J. Optim. 7(1), 1997) — on the parameters scaled to [0, 1]
within their :class:`Space` bounds:

- every candidate lies on a lattice: the default gait's scaled point plus an integer multiple of
  :data:`MIN_STEP` along each parameter, clipped to the box (a face within :data:`FACE` of a
  step of a lattice point is that point, :func:`lattice_bounds`), so a point is computed from
  its integers and not from the path that reached it;
- a poll evaluates the 2n points one step away (+ then − along each parameter in
  :attr:`Space.names` order) — all of them, so they may be solved over the cores and the answer
  does not depend on the order they finish in;
- the best of a poll is the first (in poll order) within :data:`TIE` × the reference energy of
  its least value, and it is taken only when it beats the current point by more than that tie
  (a sufficient decrease); otherwise the step halves, from :data:`STEP` down to
  :data:`MIN_STEP`, after whose failed poll the run ends.

Two candidates' values that differ by rounding (another machine's BLAS, a 1e-9 change of an
input) therefore make the same decision, unless their difference happens to fall within
rounding of the tie itself, and the search ends at the same gait. The optimum is local: each run
ends at a point no poll neighbour at the finest step beats by more than the tie; the runs start
from the default gait and from points across the box (:data:`RESTARTS`), and their spread is
reported (:attr:`SearchResult.spread`) as the search's stated gap.

Why not Nelder–Mead (which this search replaced): every comparison of two vertices' values
decides a simplex's path, so values that differ in their last bits led to another co-designed
gait (duty 0.774 and 11.6 J/m instead of 0.762 and 11.4 J/m, with springs of another family).
Why not CMA-ES: with 5 parameters and ~0.3 s a candidate the budget is ~100 evaluations, where
its default population (4 + 3 ln 5 ≈ 8) would run ~12 generations, and it draws random numbers.

A candidate that fails (no gait, no admissible forces) or breaks a constraint
(:class:`~hexaleg.design.codesign.gait_evaluation.Constraints`) is a penalty, not an error
(:func:`penalised`). Each lattice point is evaluated once.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from hexaleg.checks import integer, real
from hexaleg.design.codesign.gait_evaluation import PARAMETERS, GaitPoint, with_values
from hexaleg.design.search.geometry import Mapper
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.motion.params import GaitParams

RESTARTS = 2
"""Runs of the compass search by default: from the default gait, then from halfway between the
best so far and the default gait's mirror through the box's centre. Up to 5 may be asked for:
then from halfway between the best and the box's centre, and halfway to the default gait
mirrored in the first, then the second half of the parameters."""
STEP = 0.25
"""A run's first step, in the parameters scaled to [0, 1]."""
MIN_STEP = 2.0 ** -5
"""The lattice's spacing and a run's last step (a 64th of each parameter's range)."""
FACE = 1e-6
"""Fraction of :data:`MIN_STEP` within which a lattice point is on a face of the box
(:func:`lattice_bounds`): far above the rounding of the scaled default point (~1e-16) and of a
1e-9 change of a bound, far below a step a search could tell apart."""
TIE = 1e-4
"""Fraction of the reference energy per metre below which two candidates' values are a tie (the
earlier in poll order is kept) and a step is no decrease. The inner program's values agree to
~1e-9 between floating-point paths; a tenth of a per mille is far below what the co-design
prints (0.1 J/m of ~20 J/m)."""
FAIL = 3.0
"""A failing gait's value: this many times the reference energy per metre, plus its distance to
the default gait (so the search is pulled back towards gaits that exist)."""
WEIGHT = 10.0
"""A constraint's relative violation costs this many reference energies per metre."""
FINALISTS = 6
"""How many of the best distinct feasible gaits the search hands on (:attr:`SearchResult.
finalists`): the co-design simulates each before it chooses (:mod:`hexaleg.design.codesign.
servo`)."""
SPACING = 0.15
"""Two finalists differ by at least this distance in the parameters scaled to [0, 1] (the best
of a cluster stands for it): more than a run's last three polls reach about its end (steps
of 1/8, 1/16 and 1/32), whose points are near-copies of its best. At 0.05, every finalist of
the default robot's co-design was one of those (duty factor 0.8, periods 1.66–1.80 s), and the
servo check chose among six versions of one gait."""


@dataclass(frozen=True)
class Space:
    """Bounds of the free gait parameters, SI.

    Attributes:
        bounds: Parameter → (low, high); its keys are the free parameters, a subset of
            :data:`hexaleg.design.codesign.gait_evaluation.PARAMETERS`.
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
        value: Its search value, J/m. restarts: Each run's best value, J/m (a run the
            budget cut short: where it stopped).
        evaluations: Candidates evaluated (each lattice point once). wall: s.
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
           restarts: int = RESTARTS, map_fn: Mapper | None = None,
           progress: Callable[[str], None] | None = None) -> SearchResult:
    """Minimise :func:`penalised` over ``space`` by restarted compass search (module docstring).

    Args:
        evaluate: A gait → its evaluated point
            (:func:`~hexaleg.design.codesign.gait_evaluation.evaluate_gait`, robot and springs
            bound).
        base: The gait whose other fields the candidates keep (pattern, samples, …); its values
            of the free parameters are the first start and the lattice's origin.
        speed: The required speed, m/s.
        space: The free parameters and their bounds.
        springs: Whether the value is the energy with the candidate's springs.
        reference: The reference energy per metre of the penalties and the tie, J/m (> 0).
        max_evaluations: Budget of evaluations over all runs (≥ 10): each run takes what it
            needs of what is left; a poll the budget cuts short evaluates its first points,
            and a run it cuts short ends there (its value is then not a converged one).
        restarts: Runs (1 to 5, :data:`RESTARTS`).
        map_fn: How a poll's candidates are evaluated (``map_fn(fn, items)`` → the list of
            ``fn(item)`` in order, e.g. over the cores); default one after the other. The
            answer does not depend on it.
        progress: Called after each poll with a line: the run, the evaluations against the
            budget, the step, the best value so far and the time left at most (the budget's
            remaining evaluations at the pace so far); None: quiet.
    """
    budget = integer("max_evaluations", max_evaluations, low=10, high=10_000)
    runs = integer("restarts", restarts, low=1, high=5)
    ref = real("reference", reference, low=0.0, low_open=True)
    tie = TIE * ref
    mapper: Mapper = map_fn if map_fn is not None else (lambda fn, items: [fn(x) for x in items])
    start = time.perf_counter()
    names = space.names
    u0 = np.clip(space.scaled({n: getattr(base, n) for n in names}), 0.0, 1.0)
    k_low, k_high = lattice_bounds(u0)
    seen: dict[tuple[int, ...], tuple[float, GaitPoint]] = {}
    history: list[float] = []

    def point(k: tuple[int, ...]) -> np.ndarray:
        return lattice_point(u0, k)

    def one(k: tuple[int, ...]) -> tuple[float, GaitPoint]:
        u = point(k)
        gait = evaluate(with_values(base, speed, space.values(u)))
        return penalised(gait, ref, float(np.linalg.norm(u - u0)), springs), gait

    def solve(ks: list[tuple[int, ...]]) -> None:
        """Evaluate the new lattice points of ``ks``, in order, within the budget."""
        new = list(dict.fromkeys(k for k in ks if k not in seen))[:max(0, budget - len(history))]
        for k, result in zip(new, mapper(one, new), strict=True):
            seen[k] = result
            history.append(result[0])

    def first_best(ks: list[tuple[int, ...]]) -> tuple[int, ...]:
        least = min(seen[k][0] for k in ks)
        return next(k for k in ks if seen[k][0] <= least + tie)

    def lattice(u: np.ndarray) -> tuple[int, ...]:
        return tuple(int(x) for x in np.clip(np.round((u - u0) / MIN_STEP), k_low, k_high))

    bests: list[float] = []
    eye = np.eye(len(names), dtype=int)
    steps = round(STEP / MIN_STEP)
    for run in range(runs):
        if len(history) >= budget:
            break
        if run == 0:
            k = lattice(u0)
        else:
            best_u = point(first_best(list(seen)))
            far = (1.0 - u0, np.full_like(u0, 0.5), _mirrored(u0, 0), _mirrored(u0, 1))[run - 1]
            k = lattice(0.5 * (best_u + far))
        solve([k])
        if k not in seen:
            break
        step = steps
        while step >= 1 and len(history) < budget:
            poll = [tuple(int(x) for x in np.clip(np.array(k) + sign * step * e, k_low, k_high))
                    for e in eye for sign in (1, -1)]
            poll = [p for p in poll if p != k]
            solve(poll)
            done = [p for p in poll if p in seen]
            if done and seen[first_best(done)][0] < seen[k][0] - tie:
                k = first_best(done)
            else:
                step //= 2
            if progress is not None:
                progress(_progress_line(run, runs, len(history), budget, step,
                                        seen[first_best(list(seen))][0],
                                        time.perf_counter() - start))
        bests.append(seen[k][0])
    best = first_best(list(seen))
    return SearchResult(best=seen[best][1], value=seen[best][0], restarts=tuple(bests),
                        evaluations=len(history), wall=time.perf_counter() - start,
                        history=tuple(history),
                        method=f"compass search, complete polls, {len(bests)} runs, budget "
                               f"{budget} evaluations, parameters scaled to [0, 1], steps "
                               f"{STEP:g} to {MIN_STEP:g}, ties within {TIE:g} of "
                               f"{ref:.4g} J/m",
                        finalists=finalists({tuple(point(q)): v for q, v in seen.items()}))


def lattice_bounds(u0: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The lattice's outermost integers along each parameter, shape (n,) each: the lattice is
    ``u0 + k · MIN_STEP`` (``u0`` the default gait's scaled point, shape (n,)), and its outermost
    integers reach, clipped, the box's faces. A face within :data:`FACE` of a step beyond a
    lattice point is that point (:func:`lattice_point`), not one more integer: else a 1e-9 change
    of a bound that the default gait sits a whole number of steps from adds an integer whose
    point is the face and another 8e-10 inside it, two lattice points for one gait (the
    co-design at ``body_high`` 1.300000001: 141 evaluations instead of 138)."""
    k_low = np.floor(-u0 / MIN_STEP + FACE).astype(int)
    k_high = np.ceil((1.0 - u0) / MIN_STEP - FACE).astype(int)
    return k_low, k_high


def lattice_point(u0: np.ndarray, k: tuple[int, ...]) -> np.ndarray:
    """The scaled point of the lattice integers ``k`` (:func:`lattice_bounds`), shape (n,):
    clipped to [0, 1], and on a face where within :data:`FACE` of a step of it."""
    u = u0 + np.array(k, dtype=float) * MIN_STEP
    u = np.where(np.abs(u) <= FACE * MIN_STEP, 0.0, u)
    u = np.where(np.abs(u - 1.0) <= FACE * MIN_STEP, 1.0, u)
    return np.clip(u, 0.0, 1.0)


def _progress_line(run: int, runs: int, done: int, budget: int, step: int, best: float,
                   elapsed: float) -> str:
    """One progress line of :func:`search`: where it is and the time left at most (the budget's
    remaining evaluations at the pace so far)."""
    left = (budget - done) * elapsed / max(done, 1)
    return (f"run {run + 1} of {runs}, {done} of at most {budget} evaluations, step "
            f"1/{round(1 / (max(step, 1) * MIN_STEP))} of each range, best {best:.2f} J/m "
            f"({elapsed:.0f} s; at most {left:.0f} s more at this pace)")


def _mirrored(u: np.ndarray, half: int) -> np.ndarray:
    """``u`` mirrored through the box's centre in the first (``half`` 0) or second half of its
    parameters."""
    out = u.copy()
    cut = (len(u) + 1) // 2
    part = slice(0, cut) if half == 0 else slice(cut, None)
    out[part] = 1.0 - out[part]
    return out


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


__all__ = ["FACE", "FAIL", "FINALISTS", "MIN_STEP", "RESTARTS", "SPACING", "STEP", "TIE",
           "WEIGHT", "SearchResult", "Space", "finalists", "lattice_bounds", "lattice_point",
           "penalised", "search"]
