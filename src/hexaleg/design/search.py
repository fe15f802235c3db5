"""The outer search over a spring family's geometry; each step is one convex solve.

The magnitudes are optimal for every geometry the search visits (:mod:`hexaleg.design.program`),
so only a few angles per group are searched: the design's value as a function of them is
piecewise smooth (samples enter and leave the engaged regions) and bounded by the joints' range
of motion widened by a wind-up allowance (a contact angle beyond the motion's far end is a
spring engaged throughout, pre-wound by the distance: ``max_deflection`` when given, else
:data:`WIND_UP`, the old optimiser's ±1 rad offset bound). The search: a grid over each group's
angles in turn with the other groups held (two rounds), then bounded Nelder–Mead over all angles
together from the best grid point (:func:`scipy.optimize.minimize`; derivative-free, tolerant of
the kinks). Ordered angles (θ⁻ < θ⁺, stage breakpoints) are searched as unordered pairs and
sorted, so the box needs no ordering constraint. A one-sided spring's side is chosen per group
in the grid rounds. Start geometries (say, each group's optimum alone, or a subset's optimum with
the remaining group's, when the groups are then designed together) are evaluated first and the
grid rounds start from the best of them, so the result is never worse than any start.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import numpy as np

from hexaleg.design.setup import DesignSetup
from hexaleg.errors import InfeasibleForcesError, TorqueLimitError

if TYPE_CHECKING:
    from hexaleg.design.families import Geometry
    from hexaleg.design.program import DesignSolution

TICKS = {1: (-1.0, -0.75, -0.5, -0.25, 0.0, 0.25, 0.5, 0.75, 1.0), 2: (-1.0, -0.5, 0.0, 0.5, 1.0),
         4: (-0.5, 0.5)}
"""Start-grid angles within the range of motion, in units of the group's half range, by the
number of angles of the family; the two wind-up extremes ±(half range + allowance) are added."""
SEPARATION = 1e-9
"""rad between two angles the sort made equal (a dead zone needs θ⁻ < θ⁺)."""
WIND_UP = 1.0
"""rad the search box extends beyond each group's range of motion without ``max_deflection``."""
MAX_EVALUATIONS = 400
"""Convex solves the Nelder–Mead stage may spend."""


def _geometry(name: str, u: np.ndarray, side: str) -> dict[str, float | str]:
    """One group's geometry from its search point ``u`` (rad from the centre of motion)."""
    if name in ("dead_zone", "preloaded"):
        lo, hi = sorted(float(v) for v in u)
        if name == "dead_zone" and hi - lo < SEPARATION:
            hi = lo + SEPARATION
        return {"theta_minus": lo, "theta_plus": hi}
    if name == "one_sided":
        return {"contact": float(u[0]), "side": side}
    a1, a2 = sorted(float(v) for v in u[:2])
    b2, b1 = sorted(float(v) for v in u[2:])
    return {"above_1": a1, "above_2": max(a2, a1 + SEPARATION),
            "below_1": b1, "below_2": min(b2, b1 - SEPARATION)}


def _point(name: str, geometry: Geometry) -> tuple[list[float], str]:
    """The search point and side of one group's geometry (the inverse of :func:`_geometry`)."""
    if name in ("dead_zone", "preloaded"):
        return [float(geometry["theta_minus"]), float(geometry["theta_plus"])], "above"
    if name == "one_sided":
        return [float(geometry["contact"])], str(geometry["side"])
    return [float(geometry[a]) for a in ("above_1", "above_2", "below_2", "below_1")], "above"


def _grid(n: int, ticks: np.ndarray) -> list[tuple[float, ...]]:
    """Start points of one group with ``n`` angles (1, 2 or 4), rad: every tick for one angle,
    unordered pairs for two (they are sorted), pairs of pairs for four."""
    if n == 1:
        return [(float(t),) for t in ticks]
    pairs: list[tuple[float, ...]] = list(
        itertools.combinations_with_replacement((float(t) for t in ticks), 2))
    return pairs if n == 2 else [a + b for a, b in itertools.product(pairs, pairs)]


def search_geometry(setup: DesignSetup, starts: Sequence[Mapping[str, Geometry]] = (), *,
                    rounds: int = 2, max_evaluations: int = MAX_EVALUATIONS
                    ) -> tuple[dict[str, dict[str, float | str]], DesignSolution, int]:
    """The best geometry found, its solution and the number of convex solves (module docstring).

    Args:
        setup: The checked design inputs.
        starts: Geometries to start from, each group → a checked geometry (every group).
        rounds: Grid rounds over the groups (0: Nelder–Mead from the best start alone).
        max_evaluations: Convex solves the Nelder–Mead stage may spend.

    A condensed setup (another metric, stop shifts) is compared by its fast solves
    (``setup.solve(geometry, exact=False)``); the caller certifies the chosen geometry.
    """
    from scipy.optimize import minimize

    fam, groups = setup.fam, list(setup.groups)
    if not fam.angles:
        geometry: dict[str, dict[str, float | str]] = {g: {} for g in groups}
        return geometry, setup.solve(geometry), 1
    n = len(fam.angles)
    wind = setup.max_deflection if setup.max_deflection is not None else WIND_UP
    motion = np.array([setup.half_range(g) for g in groups])
    half = motion + wind
    sides = {g: "above" for g in groups}
    best: dict[str, object] = {"value": np.inf}
    count = 0

    def value(u: np.ndarray) -> float:
        nonlocal count
        count += 1
        geometry = {g: _geometry(fam.name, u[i * n:(i + 1) * n], sides[g])
                    for i, g in enumerate(groups)}
        try:
            solution = setup.solve(geometry, exact=False)
        except (InfeasibleForcesError, TorqueLimitError):
            return np.inf
        if solution.value < best["value"]:  # type: ignore[operator]
            best.update(value=solution.value, geometry=geometry, solution=solution, u=u.copy())
        return solution.value

    u = np.zeros(n * len(groups))
    for start in starts:
        for i, g in enumerate(groups):
            u[i * n:(i + 1) * n], sides[g] = _point(fam.name, start[g])
        value(u)
    if "u" in best:
        u = np.asarray(best["u"])
        sides.update({h: str(best["geometry"][h].get("side", "above"))  # type: ignore[index]
                      for h in groups})
    for _ in range(rounds):
        for i, g in enumerate(groups):
            options = ("above", "below") if fam.name == "one_sided" else (sides[g],)
            ticks = np.array([-half[i], *(motion[i] * np.array(TICKS[n])), half[i]])
            for point in _grid(n, ticks):
                for side in options:
                    sides[g] = side
                    trial = u.copy()
                    trial[i * n:(i + 1) * n] = np.ravel(point)
                    value(trial)
            u = np.asarray(best["u"])
            sides.update({h: str(best["geometry"][h].get("side", "above"))  # type: ignore[index]
                          for h in groups})
    scale = np.repeat(half, n)
    minimize(lambda z: value(np.clip(z, -1.0, 1.0) * scale), np.clip(u / scale, -1.0, 1.0),
             method="Nelder-Mead",
             bounds=[(-1.0, 1.0)] * u.size,
             options={"maxfev": max_evaluations, "xatol": 1e-4, "fatol": 1e-12})
    return best["geometry"], best["solution"], count  # type: ignore[return-value]
