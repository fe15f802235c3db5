"""A designed spring's numbers as ``{value, unit}``, in SI and in the paper's units.

The paper states stiffness in N·mm/deg and angles in degrees (Tables 4–5); conversions go through
:mod:`hexaleg.units` only.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from hexaleg.design import families
from hexaleg.quantities import quantity
from hexaleg.units import nm_per_rad_to_nmm_per_deg, nm_to_nmm, rad_to_deg


def magnitudes_table(geometry: Mapping[str, float | str], magnitudes: Mapping[str, float],
                     family: str) -> dict[str, Any]:
    """``{name: {"si": {value, unit}, "paper": {value, unit}}}`` for every angle (rad, deg),
    stiffness (``k…``: N·m/rad, N·mm/deg) and torque (preloads and the constant: N·m, N·mm) of a
    design of ``family``; a one-sided spring's ``side`` as text. An angle past which nothing acts
    (:meth:`~hexaleg.design.families.family.Family.idle`) has no value: both quantities' values
    are None, and ``note`` says why (:data:`~hexaleg.design.families.family.IDLE`)."""
    idle = families.family(family).idle(magnitudes)
    out: dict[str, Any] = {}
    for name, v in geometry.items():
        if isinstance(v, str):
            out[name] = v
        elif name in idle:
            out[name] = {"si": quantity(None, "rad"), "paper": quantity(None, "deg"),
                         "note": families.IDLE}
        else:
            out[name] = {"si": quantity(v, "rad"), "paper": quantity(rad_to_deg(v), "deg")}
    for name, v in magnitudes.items():
        if name.startswith("k"):
            out[name] = {"si": quantity(v, "N·m/rad"),
                         "paper": quantity(nm_per_rad_to_nmm_per_deg(v), "N·mm/deg")}
        else:
            out[name] = {"si": quantity(v, "N·m"), "paper": quantity(nm_to_nmm(v), "N·mm")}
    return out
