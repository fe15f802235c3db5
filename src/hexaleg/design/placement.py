"""Which joint groups benefit from a spring: each group's optimum alone, then every combination.

The paper leaves "the appropriate elastic joint assembly position" as future work; this study
answers it for one gait and one motor with dead-zone springs (eq. 8) optimised per group by
:func:`hexaleg.design.optimise.optimise`.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from hexaleg.design.evaluator import DEFAULT_METRIC, Evaluator
from hexaleg.design.optimise import Optimum, optimise
from hexaleg.dynamics.energy import saving

if TYPE_CHECKING:  # pandas is imported where tables are made: `import hexaleg` stays light
    import pandas as pd


def placement(ev: Evaluator, groups: Mapping[str, Sequence[str]],
              metric: str = DEFAULT_METRIC, *,
              starts: Mapping[str, Sequence[float]] | None = None,
              **options: Any) -> tuple[dict[str, Optimum], pd.DataFrame]:
    """Which groups benefit from a spring: each group's optimum, then every combination.

    Each group is optimised alone (:func:`~hexaleg.design.optimise.optimise`, others without
    springs); every combination of two or more groups is then evaluated with each group at its
    own optimum (not re-optimised jointly — the groups interact only through the shared foot
    forces).

    Args:
        ev: Evaluator of the gait.
        groups: Group → joints, e.g. ``{"coxa": robot.joints("coxa"), …}``.
        metric: A key of :data:`~hexaleg.design.evaluator.METRICS`.
        starts: Group → (k, θ_k[, offset]) to start from (e.g. a sweep's best point) instead of
            a grid.
        **options: More :func:`~hexaleg.design.optimise.optimise` keyword arguments.

    Returns:
        (group → optimum, table with one row per set of sprung groups: ``springs``, ``value``,
        ``baseline``, ``saving``, ``benefits`` (saving > 0), sorted by saving, best first).
    """
    import pandas as pd

    starts = starts or {}
    optima = {g: optimise(ev, g, joints, metric, start=starts.get(g), **options)
              for g, joints in groups.items()}
    rows = []
    names = list(groups)
    base = float(ev.baseline["total"][metric])
    for r in range(1, len(names) + 1):
        for combo in itertools.combinations(names, r):
            design = {g: optima[g].design() for g in combo}
            value = optima[combo[0]].value if r == 1 else ev.value(groups, design, metric)
            rows.append({"springs": "+".join(combo), "value": value, "baseline": base,
                         "saving": saving(value, base),
                         **{f"{g}.{p}": v for g in combo for p, v in design[g].items()}})
    table = pd.DataFrame(rows).sort_values("saving", ascending=False, kind="stable")
    table["benefits"] = table["saving"] > 0
    return optima, table.reset_index(drop=True)
