"""Angles as the pages print them: from rad to degrees, one decimal, signed, never −0.0.

Its own module so that the HTML filters (:mod:`hexaleg.outputs.html`) and the drawings of the
springs (:mod:`hexaleg.outputs.spring_drawing`) print an angle the same way without importing each
other.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any


def format_degrees(rad: Any, signed: bool = True) -> str:
    """An angle given in rad (a number or a ``{value, unit: rad}`` quantity) in degrees with one
    decimal and its sign (``signed``), never ``-0.0°``; ``—`` for a missing value."""
    x = rad.get("value") if isinstance(rad, Mapping) else rad
    if x is None:
        return "—"
    if isinstance(rad, Mapping) and rad.get("unit") != "rad":
        raise ValueError(f"deg: {rad!r} is not an angle in rad")
    d = round(math.degrees(float(x)), 1) + 0.0
    return f"{d:+.1f}°" if signed else f"{d:.1f}°"


__all__ = ["format_degrees"]
