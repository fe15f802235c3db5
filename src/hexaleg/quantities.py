"""The one JSON policy of hexaleg: numbers as quantities ``{"value": …, "unit": …}`` in SI (a
saving in %), and a number that is not finite written as ``null`` with a note (:func:`json_text`).

Every JSON file hexaleg writes goes through :func:`json_text`; a page that shows a file's numbers
shows :func:`file_data`, what the file holds. A metric of
:func:`hexaleg.dynamics.energy.metrics` is an energy (J) or, for the torque metrics, a torque
(N·m: :func:`hexaleg.dynamics.energy.metric_unit`); a saving is
:func:`hexaleg.dynamics.energy.savings` in %.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from typing import Any

import numpy as np


def quantity(value: Any, unit: str) -> dict[str, Any]:
    """A quantity ``{"value", "unit"}``, the value a float or, for an array, a flat list of
    floats; a non-finite number stays one here, for :func:`json_text` to write as ``null`` and
    note; None stays None (no value)."""
    if value is None:
        return {"value": None, "unit": unit}
    v = np.asarray(value, dtype=float)
    if v.ndim == 0:
        return {"value": float(v), "unit": unit}
    return {"value": [float(x) for x in v.ravel()], "unit": unit}


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


NON_FINITE = "non_finite"
"""The key :func:`json_text` adds to a JSON object in which it wrote a non-finite number as
null: the paths of those values and what null means there."""


def json_text(data: Mapping[str, Any], indent: int = 1) -> str:
    """``data`` as the text of a JSON file: the one policy of every JSON file hexaleg writes.

    JSON has no NaN or infinity (RFC 8259 §6; Python's ``json`` writes ``NaN``/``Infinity``,
    which :func:`read_json`, and most readers, refuse). A non-finite number (a float, a NumPy
    scalar) is written as ``null``, and :data:`NON_FINITE` lists where, so a file hexaleg writes
    is always one it can read back.
    """
    where: list[str] = []

    def finite(value: Any, path: str) -> Any:
        if isinstance(value, Mapping):
            return {str(k): finite(v, f"{path}.{k}" if path else str(k)) for k, v in value.items()}
        if isinstance(value, (list, tuple)):
            return [finite(v, f"{path}[{i}]") for i, v in enumerate(value)]
        if getattr(value, "ndim", None) == 0 and hasattr(value, "item"):
            value = value.item()  # a NumPy scalar
        if isinstance(value, float) and not math.isfinite(value):
            where.append(path)
            return None
        return value

    out = finite(data, "")
    if where:
        out[NON_FINITE] = {"note": "null here stands for a value that is not a finite number "
                                   "(NaN or infinite: e.g. no stress where no spring fits)",
                           "paths": where}
    return json.dumps(out, indent=indent, ensure_ascii=False, allow_nan=False)


def file_data(data: Mapping[str, Any]) -> dict[str, Any]:
    """``data`` as its JSON file holds it (:func:`json_text` read back): what a page that shows
    the file's numbers shows."""
    out: dict[str, Any] = json.loads(json_text(data))
    return out
