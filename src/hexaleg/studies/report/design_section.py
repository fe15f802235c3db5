"""The report's lead: the springs ``hexaleg design`` recommends, read from its ``design.json``.

The design takes seconds to tens of seconds (families, maps, the robust program) and the report
must stay fast, so the report does not recompute it: given ``[report] design = "DIR/design.json"``
(or ``hexaleg report --design``), it copies the recommendation's numbers — the saving, the parts
to buy, the worst case of the robustness maps, the robust design's worst case, the saving
predicted and simulated under each controller — into
``report.json`` and leads the page with them; without one it says how to get one.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from hexaleg.checks import is_real
from hexaleg.config import read_json
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError

if TYPE_CHECKING:
    from hexaleg.robot.model import Robot

PART_FIELDS = ("material", "wire_diameter", "mean_diameter", "outer_diameter", "body_turns",
               "rate_nmm_per_deg", "preload_angle", "max_deflection", "max_torque", "mass")
"""The torsion spring's numbers the report shows (of ``TorsionSpring.table()``)."""


def design_section(path: str | Path | None, robot: Robot | None = None) -> dict[str, Any] | None:
    """The recommendation of a ``design.json``, or None without one.

    The file is read by the one bounded reader (:func:`hexaleg.config.read_json`: a regular
    file, bounded, no NaN or Infinity) and checked against what it claims before a number is
    copied: made for ``robot`` (its ``robot.name``), springs on ``robot``'s joints, and every
    saving, mass and part number the page shows finite.

    Args:
        path: The ``design.json`` written by ``hexaleg design``, or None.
        robot: The robot of the report; None: not checked against a robot.

    Returns:
        ``{source, html, label, saving, net_saving, spring_mass, parts, worst, robust,
        simulation}`` — every number ``{value, unit}`` as in ``design.json`` (``simulation``
        empty for a design.json without one).

    Raises:
        ConfigError: the file cannot be read or is not a ``design.json`` (says how to make one).
        InvalidParameterError: a design for another robot, or a number that is not finite.
        UnknownNameError: a recommended spring on a joint ``robot`` does not have.
    """
    if path is None:
        return None
    path = Path(path)
    try:
        data = read_json(path, "design file")
        section = _section(path, data)
    except (ConfigError, ValueError, KeyError, TypeError, AttributeError) as e:
        raise ConfigError(f"[report] design = {str(path)!r}: not a design.json of hexaleg design "
                          f"({type(e).__name__}: {e}); write one with: hexaleg design --out DIR"
                          ) from e
    if robot is not None:
        _check_robot(path, data, robot)
    for key, where in (("saving", "recommended.saving"), ("net_saving", "recommended.net_saving"),
                       ("spring_mass", "recommended.spring_mass"), ("parts", "recommended.parts"),
                       ("worst", "worst"), ("robust", "robust.worst")):
        _check_finite(path, section[key], where)
    return section


def _check_robot(path: Path, data: Mapping[str, Any], robot: Robot) -> None:
    """Refuse a design made for another robot, or springs on joints ``robot`` lacks."""
    owner = data.get("robot")
    owner = owner.get("name") if isinstance(owner, Mapping) else owner
    if owner is not None and owner != robot.name:
        raise InvalidParameterError(f"{path}: robot.name", owner,
                                    f"a design of the report's robot, {robot.name!r} (write one "
                                    f"with: hexaleg design --robot {robot.name} --out DIR)")
    springs = data["recommended"].get("springs") or []
    for entry in springs:
        joint = entry.get("joint") if isinstance(entry, Mapping) else None
        if joint not in robot.joint_names:
            raise UnknownNameError(f"joint in {path} (recommended.springs) for {robot.name}",
                                   joint, robot.joint_names)


def _check_finite(path: Path, value: Any, where: str) -> None:
    """Every ``{value, unit}`` in ``value`` a finite number (or null where nothing was found)."""
    if isinstance(value, Mapping):
        if set(value) == {"value", "unit"}:
            v = value["value"]
            if v is not None and not is_real(v):
                raise InvalidParameterError(f"{path}: {where}", v, "a finite number "
                                            f"({value['unit']}), as hexaleg design writes it")
            return
        for k, v in value.items():
            _check_finite(path, v, f"{where}.{k}")
    elif isinstance(value, list):
        for i, v in enumerate(value):
            _check_finite(path, v, f"{where}[{i}]")
    elif isinstance(value, float) and not is_real(value):
        raise InvalidParameterError(f"{path}: {where}", value, "a finite number")


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
