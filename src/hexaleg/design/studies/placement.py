"""Where springs pay: the global optimum for every set of sprung groups, and the old search's gap.

The paper leaves "the appropriate elastic joint assembly position" as future work. For every
non-empty set of the given groups (a joint class, a mirrored pair, one joint), this study designs
the springs of one family on exactly those groups *together*, with
:func:`hexaleg.design.search.optimal.optimal_springs` (each group its own design; the magnitudes the
global optimum for the geometry, the geometry searched). A set's search starts from each of its
subsets one group smaller at its optimum, the missing group at its own: the program may leave that
group's magnitudes at 0, so a set never saves less than any of its subsets.

Beside each set it reports how far the old design search was from it: each group's symmetric
dead zone with its neutral offset free in ``offset_bounds`` (grid + Nelder–Mead,
:func:`hexaleg.design.studies.optimise.optimise`), the groups of the set each at their own old
optimum.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import TYPE_CHECKING

from hexaleg.checks import typed
from hexaleg.design.evaluator import Evaluator
from hexaleg.design.families import Geometry
from hexaleg.design.search.optimal import (
    OBJECTIVE_METRIC,
    Groups,
    OptimalSprings,
    optimal_springs,
    resolve_groups,
)
from hexaleg.design.studies.optimise import Optimum, optimise
from hexaleg.dynamics.energy import saving
from hexaleg.dynamics.prepare import Prepared

if TYPE_CHECKING:  # pandas is imported where tables are made: `import hexaleg` stays light
    import pandas as pd

OFFSET_BOUNDS = (-1.0, 1.0)
"""rad: the neutral offset range of the old search (its default before the convex program)."""
SEEDED = ("dead_zone", "preloaded")
"""Families that contain the old search's offset dead zone: with the comparison, each group's
search starts at the old optimum's contact angles, so its optimum is never worse than it."""


@dataclass(frozen=True)
class Placement:
    """The outcome of :func:`placement`.

    Attributes:
        table: One row per set of sprung groups, best first: ``springs`` (the groups joined by
            ``+``), ``groups`` (how many), ``value`` (the objective's metric with the springs,
            :data:`~hexaleg.design.search.optimal.OBJECTIVE_METRIC`), ``baseline``, ``saving``,
            ``benefits`` (saving > 0); with the comparison also ``old_value``, ``old_saving``
            (the old search, each group at its own optimum) and ``gap``
            (``saving − old_saving``: the fraction of the baseline the old search left).
        optima: ``springs`` → the :class:`~hexaleg.design.search.optimal.OptimalSprings` of that
            set.
        old: Group → the old search's optimum, or empty without the comparison.
    """

    table: pd.DataFrame
    optima: dict[str, OptimalSprings]
    old: dict[str, Optimum]


@typed
def placement(prepared: Prepared, groups: Groups, family: str = "preloaded",
              objective: str = "joule", *, max_torque: float | None = None,
              max_deflection: float | None = None, compare: bool = True,
              offset_bounds: tuple[float, float] = OFFSET_BOUNDS) -> Placement:
    """The global optimum of ``family`` on every set of ``groups``, and the old search's gap.

    Args:
        prepared: :func:`hexaleg.prepare` of the gait.
        groups: As :func:`~hexaleg.design.search.optimal.optimal_springs` (``{name: joints}`` or a
            list of classes / joints).
        family: As :func:`~hexaleg.design.search.optimal.optimal_springs`.
        objective: As there.
        max_torque: As there.
        max_deflection: As there.
        compare: Also run the old search per group (dead zone, offset free) and report its gap.
        offset_bounds: The old search's neutral offset range, rad.

    Returns:
        The table (best first), the optimal springs of every set, the old optima.

    Raises:
        HexalegError: as :func:`~hexaleg.design.search.optimal.optimal_springs`.
    """
    import pandas as pd

    resolved = resolve_groups(prepared, groups)
    metric = OBJECTIVE_METRIC[objective]
    ev, old = None, {}
    if compare:
        ev = Evaluator(prepared, objective)
        old = {g: optimise(ev, g, js, metric, offset_bounds=offset_bounds)
               for g, js in resolved.items()}
    optima: dict[str, OptimalSprings] = {}
    for r in range(1, len(resolved) + 1):
        for combo in itertools.combinations(resolved, r):
            starts: list[dict[str, Geometry]] = []
            if r == 1 and family in SEEDED and old:
                g = combo[0]
                starts = [{g: {"theta_minus": old[g].offset - old[g].theta_k,
                               "theta_plus": old[g].offset + old[g].theta_k}}]
            elif r > 1 and family != "linear":  # each subset one smaller, the last group alone
                for missing in combo:
                    sub = "+".join(g for g in combo if g != missing)
                    starts.append({**optima[sub].geometry, missing: optima[missing].geometry[
                        missing]})
            optima["+".join(combo)] = optimal_springs(
                prepared, {g: resolved[g] for g in combo}, family, objective,
                max_torque=max_torque, max_deflection=max_deflection, start=starts or None)
    rows = []
    for name, res in optima.items():
        row: dict[str, object] = {"springs": name, "groups": len(res.groups), "value": res.value,
                                  "baseline": res.baseline, "saving": res.saving}
        if ev is not None:
            value = (old[name].value if name in old else  # the old designs together
                     ev.value(res.groups, {g: old[g].design() for g in res.groups}, metric))
            row.update(old_value=value, old_saving=saving(value, res.baseline),
                       gap=res.saving - saving(value, res.baseline))
        rows.append(row)
    table = pd.DataFrame(rows).sort_values("saving", ascending=False, kind="stable")
    table["benefits"] = table["saving"] > 0
    return Placement(table=table.reset_index(drop=True), optima=optima, old=old)

