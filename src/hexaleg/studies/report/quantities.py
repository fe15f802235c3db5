"""Numbers of ``report.json`` as quantities ``{"value": …, "unit": …}``.

A metric of :func:`hexaleg.dynamics.energy.metrics` is an energy (J) or, for the torque metrics
(:data:`hexaleg.dynamics.energy.TORQUE_KEYS`), a torque (N·m); a saving is
:func:`hexaleg.dynamics.energy.savings` in %.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from hexaleg.dynamics import energy


def metric_unit(metric: str) -> str:
    """Unit of a metric of :func:`hexaleg.dynamics.energy.metrics`: ``"N·m"`` or ``"J"``."""
    return "N·m" if metric in energy.TORQUE_KEYS else "J"


def quantity(value: Any, unit: str) -> dict[str, Any]:
    """A quantity ``{"value", "unit"}``; arrays become lists, non-finite numbers None."""
    v = np.asarray(value, dtype=float)
    if v.ndim == 0:
        return {"value": float(v) if math.isfinite(v) else None, "unit": unit}
    return {"value": [float(x) if math.isfinite(x) else None for x in v.ravel()], "unit": unit}


def comparison(with_springs: float, baseline: float, saving: float, unit: str) -> dict[str, Any]:
    """One metric with the springs and in the baseline (no springs), and the saving in %.

    Args:
        with_springs: The metric with the springs.
        baseline: The same metric without springs.
        saving: Fraction saved (:func:`hexaleg.dynamics.energy.savings`), 1.
        unit: Unit of the metric.
    """
    return {"with_springs": quantity(with_springs, unit), "baseline": quantity(baseline, unit),
            "saving": quantity(100 * saving, "%")}
