"""How a spring design built for one gait fares when the gait's period or amplitude changes.

A built spring has fixed neutral angles and contact angles (eq. 8); this study freezes a design on
the nominal gait and re-evaluates the saving (the paper's energy criterion, eq. 20–24, with a
motor model) on gaits with the period or the stride length scaled.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

from hexaleg.checks import real
from hexaleg.design.evaluator import DEFAULT_METRIC, Design, RunSpec, evaluator
from hexaleg.dynamics.energy import saving
from hexaleg.errors import (
    InfeasibleForcesError,
    InvalidParameterError,
    TorqueLimitError,
    UnknownNameError,
)
from hexaleg.motion.params import GaitParams

if TYPE_CHECKING:  # pandas is imported where tables are made: `import hexaleg` stays light
    import pandas as pd


def robustness(run: RunSpec, gait: GaitParams, groups: Mapping[str, Sequence[str]],
               design: Design, metric: str = DEFAULT_METRIC, *,
               factors: Sequence[float] = (0.8, 0.9, 1.0, 1.1, 1.2),
               parameters: Sequence[str] = ("period", "stride_length")) -> pd.DataFrame:
    """Saving of a fixed design when the gait's period or amplitude changes.

    The design is frozen on the nominal gait — its neutral angles are absolute, taken from the
    nominal ranges of motion — as a built spring would be; only the gait changes.

    Args:
        run: Robot, motor, objective, contact.
        gait: The nominal gait (the design was chosen for it).
        groups: Group → joints.
        design: Group → parameters (e.g. ``{g: optimum.design()}``).
        metric: A key of :data:`~hexaleg.design.evaluator.METRICS`.
        factors: Multipliers of each parameter (1 = nominal), > 0.
        parameters: Gait parameters to vary, from ``period`` and ``stride_length`` (amplitude).

    Returns:
        One row per (parameter, factor): ``parameter``, ``factor``, ``gait value``, ``value``,
        ``baseline``, ``saving``, ``status``.

    Raises:
        UnknownNameError: a parameter other than period / stride_length.
        InvalidParameterError: a factor ≤ 0.
    """
    import pandas as pd

    for p in parameters:
        if p not in ("period", "stride_length"):
            raise UnknownNameError("robustness parameter", p, ("period", "stride_length"))
    for fct in factors:
        if not real("factor", fct) > 0:
            raise InvalidParameterError("factor", fct, "> 0")
    nominal = evaluator(run, dataclasses.asdict(gait))
    springs = nominal.springs(groups, design)
    rows = []
    for p in parameters:
        for fct in factors:
            varied = dataclasses.replace(gait, **{p: getattr(gait, p) * fct})
            ev = evaluator(run, dataclasses.asdict(varied))
            base = float(ev.baseline["total"][metric])
            try:
                value = float(ev.prepared.evaluate(springs, run.objective)
                              .metrics["total"][metric])
                status = "ok"
            except (InfeasibleForcesError, TorqueLimitError) as e:
                value, status = math.nan, f"{type(e).__name__}: {e}"
            rows.append({"parameter": p, "factor": float(fct), "gait value": getattr(varied, p),
                         "value": value, "baseline": base,
                         "saving": saving(value, base),
                         "status": status})
    return pd.DataFrame(rows)
