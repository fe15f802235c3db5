"""The report's lead: the springs ``hexaleg design`` recommends, read from its ``design.json``.

The design takes seconds to tens of seconds (families, maps, the robust program) and the report
must stay fast, so the report does not recompute it: given ``[report] design = "DIR/design.json"``
(or ``hexaleg report --design``), it copies the recommendation's numbers — the saving, the parts
to buy, the worst case of the robustness maps, the robust design's worst case, the saving
predicted and simulated under each controller — into
``report.json`` and leads the page with them; without one it says how to get one.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

from hexaleg.errors import ConfigError

PART_FIELDS = ("material", "wire_diameter", "mean_diameter", "outer_diameter", "body_turns",
               "rate_nmm_per_deg", "preload_angle", "max_deflection", "max_torque", "mass")
"""The torsion spring's numbers the report shows (of ``TorsionSpring.table()``)."""


def design_section(path: str | Path | None) -> dict[str, Any] | None:
    """The recommendation of a ``design.json``, or None without one.

    Args:
        path: The ``design.json`` written by ``hexaleg design``, or None.

    Returns:
        ``{source, html, label, saving, net_saving, spring_mass, parts, worst, robust,
        simulation}`` — every number ``{value, unit}`` as in ``design.json`` (``simulation``
        empty for a design.json without one).

    Raises:
        ConfigError: the file cannot be read or is not a ``design.json`` (says how to make one).
    """
    if path is None:
        return None
    path = Path(path)
    try:
        return _section(path, json.loads(path.read_text(encoding="utf-8")))
    except (OSError, ValueError, KeyError, TypeError, AttributeError) as e:
        raise ConfigError(f"[report] design = {str(path)!r}: not a design.json of hexaleg design "
                          f"({type(e).__name__}: {e}); write one with: hexaleg design --out DIR"
                          ) from e


def _section(path: Path, data: dict[str, Any]) -> dict[str, Any]:
    """The section from the parsed ``design.json`` (a missing key raises KeyError)."""
    rec = data["recommended"]
    parts = []
    for p in rec["parts"]:
        spring = p.get("torsion_spring") or {}
        parts.append({"group": p["group"], "side": p["side"], "role": p["role"],
                      "joints": len(p["joints"]), "rate": p["rate"],
                      "max_outer_diameter": p["max_outer_diameter"], "problem": p["problem"],
                      **{k: spring.get(k) for k in PART_FIELDS}})
    robust = data.get("robust")
    return {
        "source": str(path), "html": path.resolve().with_name("design.html").as_uri(),
        "label": rec["label"], "groups": list(rec["groups"]), "pays": data.get("pays", True),
        "metric": data["settings"]["metric"], "samples": data["gait"]["samples"],
        "saving": rec["saving"], "net_saving": rec["net_saving"],
        "spring_mass": rec["spring_mass"], "parts": parts, "worst": data["worst"],
        "robust": None if robust is None else robust["worst"],
        "simulation": data.get("simulation", []),
    }
