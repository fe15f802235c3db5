"""The exact batched force solver: guess, certify, repair, and the interior point for the rest.

For each :class:`~hexaleg.dynamics.reduction.Group` of samples (:mod:`hexaleg.dynamics.reduction`):

1. A guess of every sample's active set (:class:`~hexaleg.dynamics.active_set.State`): the last
   certified one of the same motion and objective when there is one (a sweep's previous stiffness
   choice: the warm start), else "nothing active" for the quadratic objectives (the unconstrained
   optimum) and none for the others.
2. :func:`~hexaleg.dynamics.active_set.solve_state` solves each sample's KKT system on its guess
   and :func:`~hexaleg.dynamics.certificate.verify` checks the KKT conditions of the whole
   program: where they hold the forces are the optimum (exact to rounding).
3. Up to :data:`REPAIRS` rounds of :func:`~hexaleg.dynamics.guesses.repair` on the rest.
4. The batched interior-point method (:mod:`hexaleg.dynamics.ipm`) on what is left, its answer
   turned into a guess (:func:`~hexaleg.dynamics.guesses.from_interior_point`) and certified the
   same way (with repairs).

A sample that none of this certifies is returned as *uncertified* (the caller solves it with
Clarabel, which also names it when it is infeasible): on the default gait in every regime of
the benchmark this does not happen. Every step works on all samples of the group at once.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np

from hexaleg.dynamics.active_set import (
    Solution,
    State,
    empty_state,
    solve_state,
    unconstrained_gains,
)
from hexaleg.dynamics.blocks import Data
from hexaleg.dynamics.certificate import feasible, verify
from hexaleg.dynamics.guesses import from_interior_point, repair
from hexaleg.dynamics.ipm import interior_point

REPAIRS = 3
"""Repair rounds after a guess fails its check (each moves every failed sample's guess once)."""


@dataclass
class Stats:
    """How the samples of the last solves were certified (counts, summed over groups).

    Attributes:
        guessed: By the first guess (the warm start, or the unconstrained optimum).
        repaired: After repairs of that guess.
        interior: Through the interior-point method.
        uncertified: Left to the caller (Clarabel).
        ipm_iterations: Interior-point iterations (the most of any group).
    """

    guessed: int = 0
    repaired: int = 0
    interior: int = 0
    uncertified: int = 0
    ipm_iterations: int = 0


@dataclass
class WarmStart:
    """The certified active sets of the last solve of one motion and objective, per group, to
    start the next solve from (a sweep over spring designs); ``key`` identifies the program (a
    different objective, weights or contact settings start cold)."""

    key: tuple = ()
    states: list[State | None] = field(default_factory=list)
    stats: Stats = field(default_factory=Stats)

    def copy(self) -> WarmStart:
        """A copy to start from (the states are never changed in place)."""
        return WarmStart(self.key, list(self.states), Stats())


def _take(obj: Any, idx: np.ndarray) -> Any:
    """A dataclass of sample arrays (samples last) restricted to samples ``idx``."""
    first = getattr(obj, fields(obj)[0].name)
    if idx.size == first.shape[-1]:
        return obj
    return type(obj)(**{f.name: getattr(obj, f.name)[..., idx] for f in fields(obj)})


def _with_solution(state: State, sol: Solution) -> State:
    return State(state.held, state.piece, state.at, state.feet, sol.z, sol.y_joint, -sol.y_feet)


class _Outcome:
    """The certified states of a group's samples as they come in."""

    def __init__(self, data: Data) -> None:
        self.state = empty_state(data)
        self.ok = np.zeros(data.tau0.shape[1], bool)

    def accept(self, idx: np.ndarray, state: State, sol: Solution, ok: np.ndarray) -> int:
        if ok.any():
            self.state.put(idx[ok], _with_solution(state, sol).take(np.flatnonzero(ok)))
            self.ok[idx[ok]] = True
        return int(ok.sum())


def _certify(data: Data, idx: np.ndarray, guess: State, out: _Outcome, rounds: int
             ) -> tuple[int, int]:
    """Solve and check ``guess`` for samples ``idx`` (of ``data``'s group), then repair the
    failures up to ``rounds`` times; returns the numbers certified on the guess and after
    repairs."""
    sub, state = data.take(idx), guess
    first = repaired = 0
    for r in range(rounds + 1):
        state, sol = solve_state(sub, state, grow=True)
        check = verify(sub, state, sol)
        n = out.accept(idx, state, sol, check.ok)
        if r:
            repaired += n
        else:
            first = n
        bad = np.flatnonzero(~check.ok)
        if not bad.size or r == rounds:
            break
        idx, sub = idx[bad], sub.take(bad)
        state = repair(sub, state.take(bad), _take(sol, bad),
                       _take(check, bad))
    return first, repaired


def solve_group(data: Data, guess: State | None, stats: Stats) -> tuple[State, np.ndarray]:
    """Certified optimal states of a group's programs (module docstring).

    Returns:
        ``(state, ok)``: every sample's state (its ``z`` the solution where ``ok``), and which
        samples are certified, (T,).
    """
    # Guesses that fail (and infeasible samples) may overflow on the way: they are rejected by
    # their checks, not by floating-point warnings.
    with np.errstate(all="ignore"):
        return _solve_group(data, guess, stats)


def _solve_group(data: Data, guess: State | None, stats: Stats) -> tuple[State, np.ndarray]:
    T = data.tau0.shape[1]
    out = _Outcome(data)
    todo = np.arange(T)
    if not data.pieces.K:
        # Quadratic objectives: where the unconstrained optimum meets every inequality it is
        # the optimum (whatever the guess).
        z = np.einsum("mjt,jt->mt", unconstrained_gains(data), data.tau0)
        x = data.local(z, None)
        free = feasible(data, x.tau, x.f)
        out.ok[free] = True
        out.state.z[:, free] = z[:, free]
        stats.guessed += int(free.sum())
        todo = np.flatnonzero(~free)
        if guess is None:
            guess = empty_state(data)
    if guess is not None and todo.size:
        first, repaired = _certify(data, todo, guess.take(todo), out, REPAIRS)
        stats.guessed += first
        stats.repaired += repaired
    rest = np.flatnonzero(~out.ok)
    if rest.size:
        sub = data.take(rest)
        result = interior_point(sub)
        stats.ipm_iterations = max(stats.ipm_iterations, result.iterations)
        first, repaired = _certify(data, rest, from_interior_point(sub, result), out, REPAIRS)
        stats.interior += first + repaired
    stats.uncertified += int((~out.ok).sum())
    return out.state, out.ok
