"""Springs as a workshop builds them: the design that keeps its saving over the stops' mounting
error.

A stop (the contact angle of a one-sided spring, a dead zone's edges, a stage's breakpoint) is
mounted to about ±1° (:data:`TOLERANCE`). A design tuned to the gait's extremes loses much of
its saving when every stop is a little off: on the default robot the Joule-optimal one-sided
design's femur contact sits exactly where the middle legs rest for half the cycle, and 0.5° less
engaged turns +15.7 % into −8.6 %. :func:`tolerant_springs` chooses the design by its **worst**
saving over the stated shifts (:func:`scenarios`): every angle moved together by −t, −t/2, 0,
+t/2, +t, each group alone by ±t, and each group against the others (±t, ∓t). Worst case, not
expected: a spring is bought and mounted once, the user cannot choose which error the workshop
makes, and a mean would trade a loss at one mounting for a gain at another the robot never has.

Its magnitudes are the global optimum of the robust convex program — every shifted geometry's
condensed program stacked, the magnitudes shared, the worst metric over its baseline minimised
(:func:`hexaleg.design.search.condensed.solve_condensed`, "worst"; exact where no sample binds, as
there) — and its geometry is searched for the best worst case
(:func:`hexaleg.design.search.geometry.search_geometry`, each step one robust solve, deterministic):
the best of the blind optimum and of it with its stops moved by :data:`MOVES` × t (together and each
group alone), then coordinate descent over each stop within ±:data:`REACH` t every t/2, then one
fine sweep over the :data:`WINDOW` nearest places on each side where a stop, moved by any of
the shifts, meets a sample (where the worst case can change). A robust solve costs ~60 ms (11
shifted programs), so the search is local around these starts, not exhaustive: its gap is not
certified, and design.json says how it was found.

The worst case is checked, not assumed, between the scenarios: :class:`TolerantSprings` gives the
saving on a dense curve of common shifts over [−2t, 2t] for both designs, and its worst
in tolerance is the lowest of the scenarios and of the curve within [−t, t]. Is the worst case
over an interval of shifts at its ends or at 0? Measured on the default robot (one-sided springs,
81 common shifts over ±1°): no — the savings move in steps as samples enter and leave the engaged
region, and the lowest lay inside (tolerance-blind design: −8.64 % at +0.55° against −7.93 % at
the ends and 0; tolerant design: 15.02 % at −0.92° against 15.08 %). Hence the interior common
shifts ±t/2 in the scenarios, and the dense curve in the reported worst case.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from hexaleg.checks import integer, real
from hexaleg.design.families import family
from hexaleg.design.search.geometry import Mapper, search_geometry
from hexaleg.design.search.optimal import OptimalSprings, springs_result
from hexaleg.design.search.setup import Shift, design_setup, motion_centres, shifted
from hexaleg.dynamics.energy import saving
from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import InfeasibleForcesError, TorqueLimitError
from hexaleg.robot.springs import SpringSet

TOLERANCE = math.pi / 180
"""A workshop's stop mounting tolerance, rad (±1°)."""
MOVES = (-4, -3, -2, -1, 1, 2, 3, 4)
"""The search's starts: the blind design with its stops moved by these multiples of t, all
together and each group alone."""
REACH = 2
"""The coarse descent scans each stop within ±REACH·t of its place, every t/2."""
COARSE_SWEEPS = 3
"""Sweeps of the coarse descent at most."""
WINDOW = 3
"""The fine pass: candidate stop places (levels moved by each shift) each scan tries on each
side of the coarse optimum, one sweep."""
CURVE_POINTS = 41
"""Points of the saving-vs-shift curve over [−2t, 2t]."""


def scenarios(groups: Sequence[str], tolerance: float) -> tuple[dict[str, float], ...]:
    """The stop shifts (group → rad) the tolerant design is chosen over (module docstring):
    common −t, −t/2, 0, +t/2, +t; each group alone ±t; each group against the rest (±t, ∓t)."""
    t = float(tolerance)
    out: list[dict[str, float]] = [{g: s * t for g in groups} for s in (-1, -0.5, 0, 0.5, 1)]
    for g in groups:
        for s in (-t, t):
            out.append({g: s})
            if len(groups) > 1:
                out.append({h: (s if h == g else -s) for h in groups})
    unique: list[dict[str, float]] = []
    for shift in out:
        full = {g: shift.get(g, 0.0) for g in groups}
        if full not in unique:
            unique.append(full)
    return tuple(unique)


def shifted_springs(optimum: OptimalSprings, centres: Mapping[str, float],
                    shift: Mapping[str, float]) -> SpringSet:
    """``optimum``'s springs with each joint's stop shifted (joint → rad, every angle of its
    law; joints not named unmoved) — angles from ``centres`` (joint → centre of motion, rad,
    :func:`hexaleg.design.search.setup.motion_centres` of the design's gait)."""
    fam = family(optimum.family)
    out = {}
    for g, joints in optimum.groups.items():
        x = [optimum.magnitudes[g][m] for m in fam.magnitudes]
        for j in joints:
            geo = shifted(fam, {g: optimum.geometry[g]}, {g: float(shift.get(j, 0.0))})[g]
            if j in optimum.mirrored:  # the same physical spring, its stop shifted the same way
                mirrored_geo, mirrored_x = fam.mirror(geo, x)
                out[j] = fam.spring(mirrored_geo, centres[j], mirrored_x)
            else:
                out[j] = fam.spring(geo, centres[j], x)
    return SpringSet(out)


def _saving(prepared: Prepared, springs: SpringSet, metric: str) -> float:
    base = float(prepared.baseline("joule")["total"][metric])
    try:
        value = float(prepared.evaluate(springs, "joule").metrics["total"][metric])
    except (InfeasibleForcesError, TorqueLimitError):
        return -np.inf
    return saving(value, base)


@dataclass(frozen=True, eq=False)
class TolerantSprings:
    """The tolerant design and the tolerance-blind one it replaces (module docstring).

    Attributes:
        tolerance: t, rad. metric: The saving kept (``"electrical"`` or ``"joule"``).
        scenarios: The stop shifts the design is chosen over (group → rad).
        optimum: The tolerant design (nominal analysis, saving, solver).
        blind: The tolerance-blind design it was searched from.
        shifts: The curve's common stop shifts, shape (n,), rad (added to every angle).
        curve: ``{"tolerant", "blind"}`` → saving at each shift, shape (n,), fraction.
        nominal: ``{"tolerant", "blind"}`` → saving as designed, fraction.
        worst: ``{"tolerant", "blind"}`` → lowest saving over the scenarios and the curve
            within [−t, t], fraction.
    """

    tolerance: float
    metric: str
    scenarios: tuple[dict[str, float], ...]
    optimum: OptimalSprings
    blind: OptimalSprings
    shifts: np.ndarray
    curve: dict[str, np.ndarray]
    nominal: dict[str, float]
    worst: dict[str, float]

    @property
    def chosen(self) -> str:
        """``"tolerant"`` when its worst saving beats the tolerance-blind design's, else
        ``"blind"``: the design to build."""
        return "tolerant" if self.worst["tolerant"] > self.worst["blind"] else "blind"

    def to_dict(self) -> dict[str, object]:
        """JSON-ready: every number ``{value, unit}`` (design.json's ``stop_tolerance``)."""
        return {"tolerance": {"value": self.tolerance, "unit": "rad"},
                "metric": self.metric,
                "shifts": {"value": self.shifts.tolist(), "unit": "rad"},
                **{name: {"nominal_saving": {"value": self.nominal[name], "unit": "1"},
                          "worst_saving": {"value": self.worst[name], "unit": "1"},
                          "curve": {"value": self.curve[name].tolist(), "unit": "1"}}
                   for name in ("tolerant", "blind")}}


def tolerant_springs(prepared: Prepared, blind: OptimalSprings, tolerance: float = TOLERANCE,
                     metric: str = "electrical", *, max_torque: float | None = None,
                     max_deflection: float | None = None,
                     starts: Sequence[Mapping[str, Mapping[str, float | str]]] = (),
                     window: int = WINDOW, map_fn: Mapper | None = None) -> TolerantSprings:
    """The design with the best worst saving over the stops' mounting error (module docstring).

    Args:
        prepared: The gait ``blind`` was designed on.
        blind: The tolerance-blind optimum (:func:`hexaleg.design.search.optimal.optimal_springs`,
            objective joule, any metric): family, groups, the search's first start.
        tolerance: t, rad, > 0 and ≤ 0.1 (≈ 5.7°).
        metric: ``"electrical"`` or ``"joule"``: the saving kept.
        max_torque: As ``optimal_springs``, at every shift. max_deflection: Likewise.
        starts: Further geometries to start from (group → geometry).
        window: Candidate stop places each scan tries on each side of the current one, ≥ 1.
        map_fn: How the searches solve a scan's candidates
            (:func:`~hexaleg.design.search.geometry.search_geometry`); default one after another
            here.

    Raises:
        InvalidParameterError: a tolerance out of range, a bad count, a blind design of another
            objective.
        UnknownNameError: an unknown metric.
    """
    t = real("stop tolerance", tolerance, low=0.0, high=0.1, low_open=True,
             allowed="an angle in (0, 0.1] rad (1° = 0.01745)")
    window = integer("window", window, low=1)
    setup = design_setup(prepared, blind.groups, blind.family, blind.objective, max_torque,
                         max_deflection, metric, scenarios(list(blind.groups), t),
                         mirrored=blind.mirrored)
    fam = setup.fam
    first = [setup.check_geometry(blind.geometry)]
    if fam.angles:
        first += [setup.check_geometry(s) for s in starts]
        groups = list(blind.groups)
        moves = [{g: k * t for g in groups} for k in MOVES] + [
            {g: k * t} for g in groups for k in MOVES if len(groups) > 1]
        first += [m for m in (shifted(fam, blind.geometry, mv) for mv in moves)
                  if all(fam.ordered(m[g]) for g in groups)]
        coarse = search_geometry(setup, first, reach=REACH * t, spacing=t / 2,
                                 max_sweeps=COARSE_SWEEPS, map_fn=map_fn)
        found = search_geometry(setup, [coarse.geometry], window=window, max_sweeps=1,
                                map_fn=map_fn)
        chosen, count = found.geometry, coarse.evaluations + found.evaluations
        how = {"stages": [coarse.to_dict(), found.to_dict()]}
    else:
        chosen, count, how = first[0], 1, {}
    baseline = float(prepared.baseline("joule")["total"][metric])
    optimum = springs_result(setup, chosen, setup.solve(chosen), count + 1, baseline)
    optimum = dataclasses.replace(optimum, solver={**optimum.solver, "search": how})
    centres = motion_centres(prepared, [j for js in blind.groups.values() for j in js])
    shifts = np.linspace(-2 * t, 2 * t, CURVE_POINTS)
    curve, nominal, worst = {}, {}, {}
    for name, design in (("tolerant", optimum), ("blind", blind)):
        joints = [j for js in design.groups.values() for j in js]
        curve[name] = np.array([_saving(prepared, shifted_springs(
            design, centres, dict.fromkeys(joints, float(s))), metric) for s in shifts])
        nominal[name] = _saving(prepared, design.springs, metric)
        at = [_saving(prepared, shifted_springs(
            design, centres, {j: sc[g] for g, js in design.groups.items() for j in js}), metric)
              for sc in setup.shifts]
        inside = curve[name][np.abs(shifts) <= t * (1 + 1e-9)]
        worst[name] = float(min(min(at), inside.min()))
    return TolerantSprings(tolerance=t, metric=metric,
                           scenarios=tuple(dict(s) for s in setup.shifts), optimum=optimum,
                           blind=blind, shifts=shifts, curve=curve, nominal=nominal,
                           worst=worst)


__all__ = [
    "CURVE_POINTS",
    "MOVES",
    "REACH",
    "TOLERANCE",
    "WINDOW",
    "Shift",
    "TolerantSprings",
    "scenarios",
    "shifted_springs",
    "tolerant_springs",
]
