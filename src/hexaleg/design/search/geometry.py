"""The outer search over a spring family's geometry: deterministic, exhaustive along each angle.

For a fixed geometry the magnitudes are one convex program (:mod:`hexaleg.design.search.program`),
and its value depends on the geometry only through the spring torque at the gait's samples. A term
at angle θ acts on the samples on its side of θ: the samples whose angle from their joint's
centre of motion (a mirrored joint's reflected, :mod:`hexaleg.robot.mirror`) is above θ for an
``above`` stop, below it for a ``below`` one. That set changes only where θ crosses a sample's
angle. These angles, merged where closer than :data:`MERGE`, are the group's *levels*; with stop
shifts (:mod:`hexaleg.design.search.tolerance`) the levels moved by each shift of the group.

**Families whose every stop carries a free preload** (``one_sided``, ``preloaded``:
:attr:`~hexaleg.design.families.Family.preloaded_stops`). Between two levels the engaged samples
are fixed, and an ``above`` stop's torque on them is −(k (r − θ) + p) = −(k r + c) with
c = p − k θ; p ≥ 0 reads c ≥ −k θ, which only loosens as θ grows (a ``below`` stop: as θ
falls), and every design row — the torque and deflection bounds at the motion's ends,
k r_max + c ≤ k Δ — is a condition on k and c alone. The set of reachable torques grows as θ
moves towards the next level, so the value is non-increasing there: the best θ with the other
angles fixed is one of the finitely many angles :data:`EDGE` before a level (or beyond every
sample: the stop never engages). Scanning all of them is exact along that angle — no grid
resolution, no Lipschitz constant.

**Families without** (``dead_zone``, ``stiffening``). The value is smooth between levels but
not monotone: every level is scanned, and the interval around the best is polished by a
bounded Brent search (:func:`scipy.optimize.minimize_scalar`, deterministic) to
:data:`POLISH_TOLERANCE` — when the scan has a best: a scan whose candidates are all
infeasible or, bounded, all unsolved (no bound below the current value) polishes nothing (it
had polished its first two candidates, an interval of no meaning, often infeasible: inf fed to
Brent, scipy's "invalid value" warning). A stop may also sit beyond the motion's far end
(engaged throughout, pre-wound by the distance): the scan reaches ``max_deflection`` past it,
else :data:`WIND_UP`.

**Over the groups**: coordinate descent to a fixed point. From the best start (the given
geometries and "no stop engaged"), each group's angles are scanned in turn with the others held
(a one-sided stop's side with it), until a sweep improves nothing: every angle is then optimal
given the others (:attr:`GeometrySearch.converged`). A family without preloads also descends
from every group's first stop wound up beyond the motion (:func:`_wound_states`), and keeps the
best of the descents. ``window`` limits a scan to that many
candidates on each side of the current angle — the local polish of an expensive program (the
metric's refinement, the stop-tolerant design) from a start the exhaustive search found.

Every step is a fixed sequence of convex solves compared by value, ties kept by the earlier
candidate (values of the condensed program within :data:`TIE`: what its bundle's tolerance can
tell apart, so another machine's rounding does not change a decision), so the search is
deterministic; a tiny change of the gait moves the levels by as much and the optimum with them,
not to another basin. Spread over processes (``map_fn``), a scan solves ahead the candidates it
may ask next but decides on them in the same fixed sequence, one at a time, so the decisions,
the optimum and the count of solves are those of the search in one process.
"""

from __future__ import annotations

import heapq
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from hexaleg.design.search.scan import RelaxedBounds, State
from hexaleg.design.search.setup import DesignSetup
from hexaleg.dynamics.contact import QUADRATIC_OBJECTIVES
from hexaleg.errors import InfeasibleForcesError, TorqueLimitError

if TYPE_CHECKING:
    from hexaleg.design.families import Family, Geometry
    from hexaleg.design.search.program import DesignSolution

Mapper = Callable[[Callable[[Any], Any], Sequence[Any]], list[Any]]
"""``map_fn(fn, items)``: ``[fn(x) for x in items]``, however it is spread over processes."""
TIE = 1e-5
"""Fraction by which a condensed program's geometries (the stop-tolerance design's, a metric's
refinement) must differ to be told apart: their values come from the bundle method stopped at
:data:`~hexaleg.design.search.condensed.SEARCH_TOLERANCE` (1e-6 of the normalised metric), so two
floating-point paths to one geometry's value may differ by that much. Closer values are a tie,
kept by the earlier candidate; exact solves (the quadratic objectives' fast path) tie only when
equal."""
MERGE = 1e-7
"""rad: sample angles closer than this form one level (a stop cannot tell them apart)."""
EDGE = 1e-8
"""rad before a level at which a stop is placed: it engages the whole level."""
OFF = 0.1
"""rad beyond every sample (and shift) where a stop never engages."""
WIND_UP = 1.0
"""rad a stop of a family without preloads may sit beyond the motion's far end without
``max_deflection``."""
POLISH_TOLERANCE = 1e-6
"""rad: the Brent polish's tolerance on an angle of a family without preloads."""
BOUND_SLACK = 1e-9
"""A candidate whose lower bound is not below the best exact value by this fraction is not
solved: it cannot improve the best by more (the bound and the exact value agree to ~1e-12
where no sample binds, and a flat stretch of candidates — a stop that does not help — would
otherwise all be solved)."""
MAX_SWEEPS = 6
"""Sweeps over the groups before the coordinate descent stops unconverged (it says so)."""
AHEAD = 16
"""Exact solves a bounded scan with ``map_fn`` reads ahead at most (1, 2, 4, … as its candidates
keep winning; :func:`_by_bound`): enough for a scan of hundreds (a BLDC hexapod's dead zone, from a
wound-up start) to keep two cores busy at a fork per batch, at most 15 solves spent past its end."""



@dataclass(frozen=True, eq=False)
class GeometrySearch:
    """The best geometry found and how (module docstring).

    Attributes:
        geometry: Group → its geometry (rad from each joint's centre of motion; ``side``).
        solution: Its solution (the search's comparison solve).
        evaluations: Convex solves spent (distinct geometries).
        sweeps: Sweeps of the coordinate descent.
        converged: The last sweep improved nothing: every angle is optimal given the others
            (within ``window`` candidates when windowed); None when no descent ran (the best of
            the starts).
        method: One line on how the optimum was established.
        levels: Group → number of levels (distinct sample angles) a stop may sit before.
    """

    geometry: State
    solution: DesignSolution
    evaluations: int
    sweeps: int
    converged: bool | None
    method: str
    levels: dict[str, int] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready (design.json's ``search`` of each family)."""
        return {"method": self.method, "evaluations": self.evaluations, "sweeps": self.sweeps,
                "converged": self.converged, "levels": dict(self.levels)}


def _levels(r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(lowest, highest) angle of each level of ``r`` (ascending), rad: sorted samples split
    where neighbours are more than :data:`MERGE` apart."""
    u = np.sort(r)
    cut = np.flatnonzero(np.diff(u) > MERGE)
    return u[np.r_[0, cut + 1]], u[np.r_[cut, u.size - 1]]


@dataclass(frozen=True)
class _Axis:
    """The candidate angles of one group's stops: for an ``above`` stop just before each level
    (every shift's), for a ``below`` one just after, ascending, and where each never engages."""

    above: np.ndarray
    below: np.ndarray
    off: tuple[float, float]
    levels: int


def _axis(setup: DesignSetup, group: str, wind: float) -> _Axis:
    r = setup.relative(group).ravel()
    shifts = sorted({float(s.get(group, 0.0)) for s in setup.shifts} or {0.0})
    lo, hi = _levels(r)
    above = np.unique(np.concatenate([lo - s - EDGE for s in shifts]))
    below = np.unique(np.concatenate([hi - s + EDGE for s in shifts]))
    if not setup.fam.preloaded_stops:  # beyond the far end: engaged throughout, wound up
        above = np.r_[above[0] - wind, above]
        below = np.r_[below, below[-1] + wind]
    return _Axis(above, below, off_angles(setup, group), int(lo.size))


def off_angles(setup: DesignSetup, group: str) -> tuple[float, float]:
    """(an angle below, an angle above) every sample of the group and every shift, rad from the
    centre of motion: a stop there never engages."""
    r = setup.relative(group)
    reach = max((abs(float(s.get(group, 0.0))) for s in setup.shifts), default=0.0) + OFF
    return float(r.min()) - reach, float(r.max()) + reach


def _off_state(setup: DesignSetup, axes: Mapping[str, _Axis]) -> State:
    """Every stop where it never engages (no spring acts): the search's own start."""
    return {g: setup.fam.off(*ax.off, OFF) for g, ax in axes.items()}


def _reached(cands: np.ndarray, current: float, reach: float, spacing: float) -> np.ndarray:
    """The candidates (ascending) within ``reach`` of ``current``, thinned to ``spacing``: from
    the lowest, each kept one the first at least ``spacing`` above the last kept, rad.

    Both comparisons allow :data:`MERGE` (angles a stop cannot tell apart). The stop-tolerant
    design (:mod:`hexaleg.design.search.tolerance`) scans levels moved by every shift, multiples
    of t/2, within a reach of 2t every t/2: the same level under two shifts is *exactly* a
    spacing or a reach apart, and without the margin floating-point round-off (~1e-18 rad)
    decided whether it was kept. A 1e-9 change of an input flipped it: the default co-design's
    chosen gait with its speed moved from 0.06 to 0.060000001 m/s thinned the coxa's stops to
    −0.03946 rad instead of −0.03961 (t/2 above −0.04834 but for 2e-18 rad), and the springs to
    buy went from +34.99 % to +35.65 %
    (analysis/bench_logs/same_answer_codesign_motion_optimal.log, the speed's block).
    """
    kept: list[float] = []
    for c in cands[np.abs(cands - current) <= reach + MERGE]:
        if not kept or c - kept[-1] >= spacing - MERGE:
            kept.append(float(c))
    return np.array(kept)


def _wound_states(fam: Family, axes: Mapping[str, _Axis], wind: float) -> list[State]:
    """Starts of a family without preloads: in every group, its first ``above`` stop (then its
    first ``below`` one) wound up beyond the motion's far end — engaged throughout, a linear
    spring pre-wound — the other stops where they never engage
    (:meth:`~hexaleg.design.families.family.Family.wound`). A coordinate descent from "no stop
    engaged" cannot reach them when the stops' order blocks the way."""
    out = []
    for side in ("above", "below"):
        state: State = {}
        for g, ax in axes.items():
            first = float(ax.above[0]) if side == "above" else float(ax.below[-1])
            geo = fam.wound(side, first, *ax.off, OFF)
            if geo is None:
                return []
            state[g] = dict(geo)
        out.append(state)
    return out


def search_geometry(setup: DesignSetup, starts: Sequence[Mapping[str, Geometry]] = (), *,
                    window: int | None = None, reach: float | None = None,
                    spacing: float = 0.0, max_sweeps: int = MAX_SWEEPS,
                    map_fn: Mapper | None = None) -> GeometrySearch:
    """The best geometry by coordinate descent over exhaustive angle scans (module docstring).

    Args:
        setup: The checked design inputs.
        starts: Geometries to start from, each group → a checked geometry (every group); the
            result is never worse than any of them.
        window: Candidates each scan tries on each side of the current angle; None: all.
        reach: Only the candidates within this angle of the current one (rad); None: all.
        spacing: With ``reach``: candidates thinned to this spacing at least (rad), the
            nearest-below kept (both within :data:`MERGE`, :func:`_reached`).
        max_sweeps: Sweeps over the groups at most; 0: the best start alone.
        map_fn: How a scan's candidates are solved: ``map_fn(fn, states)`` is
            ``[fn(s) for s in states]`` in the order given (e.g. the design's forked map over
            the cores, :func:`hexaleg.parallel.forked.fork_map`); default that list in this
            process. The candidates are independent convex programs, so the result is the same
            either way. A bounded scan (exact solves in the order of their lower bound) solves
            the next candidates of that order side by side, up to :data:`AHEAD`, and takes
            their values strictly in the order, one after the other (:func:`_by_bound`): the
            same candidates are taken, the same counted, the same optimum found.

    A condensed setup (another metric, stop shifts) is compared by its fast solves
    (``setup.solve(geometry, exact=False)``); the caller certifies the chosen geometry.
    """
    from scipy.optimize import minimize_scalar

    fam, groups = setup.fam, list(setup.groups)
    if not fam.angles:
        geometry: State = {g: {} for g in groups}
        return GeometrySearch(geometry, setup.solve(geometry), 1, 0, True,
                              "no geometry: the magnitudes' convex program is the global optimum")
    wind = setup.max_deflection if setup.max_deflection is not None else WIND_UP
    axes = {g: _axis(setup, g, wind) for g in groups}
    bounded = not setup.condensed and setup.objective in QUADRATIC_OBJECTIVES
    tie = TIE if setup.condensed else 0.0

    def below(a: float, b: float) -> bool:
        """``a`` better than ``b`` by more than a tie."""
        return a < (b - tie * abs(b) if np.isfinite(b) else b)
    seen: dict[tuple[Any, ...], float] = {}
    solutions: dict[tuple[Any, ...], DesignSolution] = {}
    scanned: dict[tuple[Any, ...], RelaxedBounds] = {}

    def key(state: State) -> tuple[Any, ...]:
        return tuple((g, tuple(sorted(state[g].items()))) for g in groups)

    def record(state: State, solution: DesignSolution | None) -> None:
        seen[key(state)] = np.inf if solution is None else solution.value
        if solution is not None:
            solutions[key(state)] = solution

    ahead: dict[tuple[Any, ...], DesignSolution | None] = {}

    def value(state: State) -> float:
        k = key(state)
        if k not in seen:
            record(state, ahead.pop(k) if k in ahead else _solved(setup, state))
        return seen[k]

    def solve_ahead(states: Sequence[State], spread: Mapper) -> None:
        """Solve side by side (``spread``) the unseen of ``states`` that a bounded scan may ask
        next; each counts, and is kept as seen, only when the scan asks for it."""
        todo = list({key(s): s for s in states
                     if key(s) not in seen and key(s) not in ahead}.values())
        if len(todo) > 1:
            for s, solution in zip(todo, spread(lambda s: _solved(setup, s), todo), strict=True):
                ahead[key(s)] = solution

    def values(states: Sequence[State]) -> np.ndarray:
        """Each state's value, the unseen ones solved through ``map_fn`` first."""
        if map_fn is not None:
            todo = list({key(s): s for s in states if key(s) not in seen}.values())
            if len(todo) > 1:
                for s, solution in zip(todo, map_fn(lambda s: _solved(setup, s), todo),
                                       strict=True):
                    record(s, solution)
        return np.array([value(s) for s in states], dtype=float)

    def moved(state: State, g: str, angle: str, theta: float, side: str | None = None
              ) -> State | None:
        geo = {**state[g], angle: float(theta)}
        if side is not None:
            geo["side"] = side
        return {**state, g: geo} if fam.ordered(geo) else None

    def scan(state: State, g: str, angle: str) -> State:
        """The best of ``state`` and every candidate of one angle, the others held."""
        ax = axes[g]
        options = ([("above", ax.above), ("below", ax.below)] if angle == "contact"
                   else [(None, ax.above if fam.side(angle, state[g]) == "above" else ax.below)])
        best, best_value = state, value(state)
        current = float(state[g][angle])
        for side, cands in options:
            if window is not None:
                at = int(np.searchsorted(cands, current))
                cands = cands[max(0, at - window):at + window + 1]
            if reach is not None:
                cands = _reached(cands, current, reach, spacing)
            trials = [(float(t), tr) for t in cands
                      if (tr := moved(state, g, angle, float(t), side)) is not None]
            if not trials:
                continue
            found = np.full(len(trials), np.inf)
            if bounded:  # exact solves in order of their lower bound, until none can win
                thetas = np.array([t for t, _ in trials])
                where = side or fam.side(angle, state[g])
                scan_key = (key(state), g, angle, where, thetas.tobytes())
                if scan_key not in scanned:  # a scan again from the same state (a sweep
                    # later, when nothing moved): its bounds kept, one sweep's worth
                    own = solutions.get(key(state))
                    scanned[scan_key] = RelaxedBounds(
                        setup, state, g, angle, thetas, where,
                        None if own is None else own.multipliers)
                    while len(scanned) > 2 * len(groups) * len(fam.angles):
                        scanned.pop(next(iter(scanned)))
                bounds = scanned[scan_key]

                def limit(best: float = best_value, found: np.ndarray = found) -> float:
                    """Below which a bound may still win (``found`` fills in as it goes)."""
                    return min(best, float(found.min())) * (1 - BOUND_SLACK)

                read = None if map_fn is None else (
                    lambda ns, trials=trials, spread=map_fn: solve_ahead(
                        [trials[n][1] for n in ns], spread))
                for n in _by_bound(bounds, limit, read, AHEAD):
                    found[n] = value(trials[n][1])
                ahead.clear()  # read ahead past the scan's end: no later scan asks
            else:
                found = values([tr for _, tr in trials])
            i = _first_best(found, tie)
            trials = [(float(v), tr) for v, (_, tr) in zip(found, trials, strict=True)]
            if not fam.preloaded_stops and np.isfinite(trials[i][0]):
                # smooth between levels: polish around the best; none when no candidate was
                # solved (every bound above the current value) or every one is infeasible
                lo = float(trials[max(i - 1, 0)][1][g][angle])
                hi = float(trials[min(i + 1, len(trials) - 1)][1][g][angle])

                def along(theta: float, side: str | None = side) -> float:
                    trial = moved(state, g, angle, theta, side)
                    return np.inf if trial is None else value(trial)

                if hi > lo:
                    res = minimize_scalar(along, bounds=(lo, hi), method="bounded",
                                          options={"xatol": POLISH_TOLERANCE})
                    polished = moved(state, g, angle, float(res.x), side)
                    if polished is not None and below(value(polished), trials[i][0]):
                        trials.append((value(polished), polished))
                        i = len(trials) - 1
            if below(trials[i][0], best_value):
                best, best_value = trials[i][1], trials[i][0]
        return best

    def descend(state: State) -> tuple[State, int, bool]:
        sweeps, converged = 0, False
        while sweeps < max_sweeps and not converged:
            sweeps += 1
            before = value(state)
            for g in groups:
                for angle in fam.angles:
                    state = scan(state, g, angle)
            converged = not below(value(state), before)
        return state, sweeps, converged

    state = _off_state(setup, axes)
    candidates = [{g: dict(start[g]) for g in groups} for start in starts]
    values([state, *candidates])  # each is asked below: solved side by side first
    for candidate in candidates:
        if below(value(candidate), value(state)):
            state = candidate
    state, sweeps, converged = descend(state)
    if window is None and reach is None and not fam.preloaded_stops:
        for wound in _wound_states(fam, axes, wind):  # the descents from every stop wound up
            other, n, done = descend(wound)
            sweeps += n
            if below(value(other), value(state)):
                state, converged = other, done
    how = (f"every angle scanned over {window} levels each side of the current one"
           if window is not None else
           f"every angle scanned within {reach:.4g} rad of the current one every {spacing:.3g} rad"
           if reach is not None else "every angle scanned over all its levels")
    exact = ("the value monotone between levels" if fam.preloaded_stops
             else f"polished to {POLISH_TOLERANCE:g} rad between levels")
    if window is None and reach is None and fam.preloaded_stops:
        exact = "exact along each angle (the value is monotone between levels)"
    method = (f"coordinate descent over the groups, {how}, {exact}; "
              f"{'a fixed point' if converged else 'stopped unconverged'} after {sweeps} "
              f"sweep{'s' if sweeps > 1 else ''}") if max_sweeps else "the best of its starts"
    k = key(state)
    if k not in solutions:  # every candidate infeasible: the start as it is
        solutions[k] = setup.solve(state, exact=False)
    levels = {g: ax.levels for g, ax in axes.items()}
    return GeometrySearch(state, solutions[k], len(seen), sweeps,
                          converged if max_sweeps else None, method, levels)


def _by_bound(bounds: RelaxedBounds, limit: Callable[[], float],
              ahead: Callable[[list[int]], None] | None = None, most: int = 1) -> Iterator[int]:
    """The candidates in increasing order of their strongest bound (ties by index), until the
    next one's is not below ``limit()`` (asked again before each; it cannot win).

    ``bounds.levels`` are the strong bounds from weaker to stronger (the condensed program with
    its design rows, then with the multipliers of the scan's state: :class:`RelaxedBounds`). A
    candidate is tightened to the next level only when its bound comes first in a heap of
    (bound, index, level) — each level is at or above the one before, so every candidate not
    yet tightened fully has a strongest bound above the one yielded: the order and the stop are
    those of every strongest bound sorted (stably), the solves of the candidates never reached
    saved. A bound not below ``limit()`` when its turn comes is not tightened: the stronger ones
    are not below it either.

    With ``ahead``, the next candidates in that order whose bound is below ``limit()`` now — one,
    then twice as many each time all were yielded, at most ``most`` — are handed to
    ``ahead(indices)`` before the first of them is yielded (to solve them side by side), and each
    is still yielded only if its bound is below ``limit()`` when its turn comes: the limit only
    falls as the caller's exact values come in, so a candidate read ahead that an earlier one's
    value puts out of reach ends the scan there, as one after the other. The yielded candidates
    are the same, in the same order, whatever ``most``; only the solves spent ahead and not
    yielded (at most ``most − 1`` a scan) differ.
    """
    levels = bounds.levels
    heap = [(float(b), i, 0) for i, b in enumerate(bounds.weak)]
    heapq.heapify(heap)
    width = 1
    while True:
        batch: list[tuple[float, int]] = []
        while heap and len(batch) < width:
            bound, i, level = heap[0]
            if not bound < limit():
                break
            heapq.heappop(heap)
            if level == len(levels):
                batch.append((bound, i))
            else:
                heapq.heappush(heap, (levels[level](i), i, level + 1))
        if not batch:
            return
        if ahead is not None and len(batch) > 1:
            ahead([i for _, i in batch])
        for bound, i in batch:
            if not bound < limit():
                return
            yield i
        width = min(2 * width, most)


def _first_best(values: np.ndarray, tie: float) -> int:
    """The first of ``values`` within a tie (the fraction ``tie``) of their least."""
    least = float(values.min())
    return int(np.argmax(values <= (least + tie * abs(least) if np.isfinite(least) else least)))


def _solved(setup: DesignSetup, state: State) -> DesignSolution | None:
    """The search's fast solve of ``state`` (``setup.solve(state, exact=False)``), None where no
    forces exist or a motor torque limit cannot be met."""
    try:
        return setup.solve(state, exact=False)
    except (InfeasibleForcesError, TorqueLimitError):
        return None


def search_value(setup: DesignSetup) -> Callable[[Mapping[str, Geometry]], float]:
    """The search's comparison value of a geometry (``inf`` where no forces exist), for tests
    and brute-force checks of :func:`search_geometry`."""
    def value(geometry: Mapping[str, Geometry]) -> float:
        solution = _solved(setup, setup.check_geometry(geometry))
        return float("inf") if solution is None else solution.value
    return value


__all__ = ["EDGE", "MAX_SWEEPS", "MERGE", "GeometrySearch", "Mapper", "off_angles",
           "search_geometry", "search_value"]
