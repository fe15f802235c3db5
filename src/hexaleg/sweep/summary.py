"""The text summary of a sweep table (``hexaleg sweep`` prints it): the best point per sprung-group
set, compared on a footing the points share.

An energy metric is per cycle (J). Points of different gaits walk different distances in different
times, so a lower energy per cycle may only be a shorter cycle: when the table's periods or
distances per cycle differ, the best point is the lowest energy **per metre** walked (J/m), or per
second (W) where a gait does not move. Torques (N·m) compare as they are. Spring parameters within
``1e-9`` of the table's largest spring parameter are the solver's rounding and print as 0.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from hexaleg.design.evaluator import DEFAULT_METRIC, METRICS
from hexaleg.dynamics.energy import ENERGY_KEYS
from hexaleg.errors import UnknownNameError

if TYPE_CHECKING:  # pandas is imported where tables are made: `import hexaleg` stays light
    import pandas as pd

NOISE = 1e-9
"""A spring parameter below this fraction of the table's largest prints as 0."""


def distance_per_cycle(table: pd.DataFrame) -> pd.Series:
    """Body travel per cycle of each row, m: ``speed · period`` where a speed is set, else the
    stride length (:attr:`hexaleg.motion.params.GaitParams.stride`)."""
    speed = table["gait.speed"] if "gait.speed" in table.columns else None
    stride = table["gait.stride_length"]
    if speed is None:
        return stride.astype(float)
    return (speed * table["gait.period"]).where(speed.notna(), stride).astype(float)


def normalisation(table: pd.DataFrame, metric: str) -> tuple[str, pd.Series | None, str]:
    """How ``metric`` is compared across the table's rows.

    Returns:
        ``(label, divisor, unit)``: the metric per cycle (divisor None, J) when every row has one
        period and one distance per cycle, else per metre (divisor the distance per cycle, J/m) if
        every row moves, else per second (divisor the period, W); torques as they are (N·m).
    """
    if metric not in ENERGY_KEYS and metric != "electrical_bus":
        return metric, None, "N·m"
    if "gait.period" not in table.columns or "gait.stride_length" not in table.columns:
        return metric, None, "J per cycle"
    distance = distance_per_cycle(table)
    if table["gait.period"].nunique() <= 1 and distance.nunique() <= 1:
        return metric, None, "J per cycle"
    if bool((distance > 0).all()):
        return f"{metric} per metre", distance, "J/m"
    return f"{metric} per second", table["gait.period"].astype(float), "W"


def _number(value: float, scale: float) -> str:
    """``value`` to 4 significant digits, 0 where it is rounding noise against ``scale``."""
    return "0" if abs(value) <= NOISE * scale else f"{value:.4g}"


def summary(table: pd.DataFrame, metric: str = DEFAULT_METRIC) -> str:
    """A text summary of a sweep table: the best point (lowest ``metric``, per metre when the
    gaits differ: :func:`normalisation`) per sprung-group set (and per family in an optimal
    sweep), with units; the saving is against no springs on the point's own gait.

    Raises:
        UnknownNameError: ``metric`` is not a column of the table.
    """
    import pandas as pd

    if metric not in table.columns:
        raise UnknownNameError("metric", metric, [m for m in METRICS if m in table.columns])
    ok = table[table["status"] == "ok"]
    if ok.empty:  # every point failed: say why, not an empty "best" line
        kinds = table["status"].str.split(":").str[0].value_counts()
        return (f"{len(table)} points, none evaluated without error ("
                + ", ".join(f"{n} × {k}" for k, n in kinds.items())
                + f"); the first: {table['status'].iloc[0]}")
    label, divisor, unit = normalisation(ok, metric)
    value = ok[metric] if divisor is None else ok[metric] / divisor
    baseline = ok[f"baseline.{metric}"] if divisor is None \
        else ok[f"baseline.{metric}"] / divisor
    basis = "" if divisor is None else (
        f"; the gaits differ in period or distance, so compared in {unit}")
    lines = [f"{len(table)} points, {len(ok)} evaluated without error; best {label} "
             f"(lower is better) per sprung-group set{basis}:"]
    # the inputs: design columns, and the gait parameters the sweep varies
    inputs = [c for c in table.columns if "." in c and not c.startswith(("baseline.", "saving."))
              and (not c.startswith("gait.") or table[c].nunique() > 1)]
    numeric = [c for c in inputs if pd.api.types.is_numeric_dtype(ok[c])]
    design = [c for c in numeric if not c.startswith("gait.")]
    # a spring parameter's noise is against the design's largest magnitude (a column may be all
    # noise: k = 1.8e-13 beside a preload of 0.11), a gait parameter against its own column
    spring_scale = float(np.nan_to_num(ok[design].abs().max().max())) if design else 0.0
    scales = {c: spring_scale if c in design else float(np.nan_to_num(ok[c].abs().max()))
              for c in numeric}
    keys = ["family", "springs"] if "family" in table.columns else ["springs"]
    for key, rows in ok.groupby(keys, sort=False):
        index = value.loc[rows.index].idxmin()
        best = ok.loc[index]
        params = ", ".join(f"{c} = {best[c]}" if isinstance(best[c], str) else
                           f"{c} = {_number(float(best[c]), scales.get(c, 0.0))}"
                           for c in inputs if not pd.isna(best[c]))
        saving = f", saving {100 * best['saving.' + metric]:+.2f} %" \
            if f"saving.{metric}" in ok.columns else ""
        lines.append(f"  {' '.join(key)}: {label} = {value[index]:.6g} {unit} (no springs "
                     f"{baseline[index]:.6g} {unit}){saving} at point {int(best['point'])}: "
                     f"{params}")
    return "\n".join(lines)
