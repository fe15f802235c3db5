"""Values of a sweep axis: a number (fixed), a list, a range table, or a command-line range.

A spec file gives each gait or spring parameter as a scalar, a list or a range table
``{start, stop, num, scale = "linear" | "log"}`` (:func:`axis_values`); the command line as
``"0.5"``, ``"0.1,0.2,0.4"`` or ``"start:stop:num[:log]"`` (:func:`parse_range`). See
``docs/sweep.md``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from hexaleg.checks import count, real
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError

_VALUE = "a finite number (an axis is a list of numbers or a range table)"
POINT_BYTES = 2048
"""Memory one point of a sweep costs in the process that runs it, B: its row of the result table
(≈ 60–100 columns), its design and its place in the lists of points to do. The grid's bound
(and so an axis') is :data:`hexaleg.checks.MEMORY_BUDGET` over this."""


def axis_values(name: str, value: Any) -> tuple[float, ...] | float:
    """A scalar (fixed), a list, or a range table ``{start, stop, num, scale}`` → values.

    Raises:
        UnknownNameError: an unknown range key. ConfigError: a value of the wrong type or a
            range without start, stop or num. InvalidParameterError: an empty grid or a value
            that is not finite.
    """
    if isinstance(value, Mapping):
        allowed = ("start", "stop", "num", "scale")
        for key in value:
            if key not in allowed:
                raise UnknownNameError(f"range key of {name}", key, allowed)
        try:
            start, stop, num = float(value["start"]), float(value["stop"]), value["num"]
        except KeyError as e:
            raise ConfigError(f"{name}: a range needs start, stop and num; missing {e}") from None
        except (TypeError, ValueError):
            raise ConfigError(f"{name} = {value!r}: start and stop must be numbers") from None
        scale = value.get("scale", "linear")
        return _range(name, start, stop, num, scale)
    if isinstance(value, (list, tuple)):
        if not value:
            raise InvalidParameterError(name, [], "a non-empty list of values (an empty grid "
                                        "has no points)")
        return tuple(real(f"{name}[{i}]", v, allowed=_VALUE) for i, v in enumerate(value))
    return real(name, value, allowed=_VALUE)


def _range(name: str, start: float, stop: float, num: Any, scale: str = "linear"
           ) -> tuple[float, ...]:
    count(f"{name}.num", num, item_bytes=POINT_BYTES, item="one sweep point",
          fix="at least 1 (an empty grid has no points); split a larger sweep")
    if scale not in ("linear", "log"):
        raise InvalidParameterError(f"{name}.scale", scale, "linear or log")
    for end, v in (("start", start), ("stop", stop)):
        if not math.isfinite(v) or (scale == "log" and v <= 0):
            raise InvalidParameterError(f"{name}.{end}", v,
                                        "a finite number" + (" > 0 for a log range (a "
                                                             "geometric grid cannot start or "
                                                             "stop at 0 or below)"
                                                             if scale == "log" else ""))
    grid = np.geomspace(start, stop, num) if scale == "log" else np.linspace(start, stop, num)
    return tuple(float(x) for x in grid)


def parse_range(name: str, text: str) -> tuple[float, ...] | float:
    """Command-line values: ``"0.5"``, ``"0.1,0.2,0.4"``, ``"start:stop:num"`` or ``"…:log"``.

    Raises:
        InvalidParameterError: not numbers, or an empty range.
    """
    if not isinstance(text, str):
        raise InvalidParameterError(name, text, "a text: a number, comma-separated numbers, or "
                                    "start:stop:num[:log]")
    try:  # only the parsing: a parsed value that is out of range keeps its own reason
        if ":" in text:
            parts = text.split(":")
            if len(parts) not in (3, 4):
                raise ValueError(text)
            scale = parts[3] if len(parts) == 4 else "linear"
            start, stop, num = float(parts[0]), float(parts[1]), int(parts[2])
        elif "," in text:
            values = [float(x) for x in text.split(",") if x.strip()]
        else:
            value = float(text)
    except ValueError:
        raise InvalidParameterError(name, text, "a number, comma-separated numbers, or "
                                    "start:stop:num[:log]") from None
    if ":" in text:
        return _range(name, start, stop, num, scale)
    if "," in text:
        return axis_values(name, values)
    return real(name, value, allowed=_VALUE + " (NaN and inf are not)")
