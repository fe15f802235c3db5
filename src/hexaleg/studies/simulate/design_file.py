"""A spring design on disk: the ``design.json`` of ``hexaleg design``, or a hand-written one.

Springs are the entries of :mod:`hexaleg.design.spring_json` (the one JSON form of a spring law
in hexaleg), one per sprung joint::

    {"family": "linear", "joint": "LF_femur",
     "parameters": {"stiffness": {"value": 0.8, "unit": "N·m/rad"},
                    "reference": {"value": 0.35, "unit": "rad"}}}

``family`` one of :data:`hexaleg.design.spring_json.CLASSES`, ``parameters`` the fields of that
spring law (:mod:`hexaleg.robot.springs`), numbers ``{value, unit}``, the text fields plain, a
stiffening spring's stages ``[{"breakpoint": …, "stiffness": …}, …]``. :func:`read_design` takes:

* a ``design.json`` of ``hexaleg design``: its ``recommended`` design's ``springs``, its
  ``robot.name`` checked against the simulated robot;
* ``{"robot": "hexaleg", "springs": [entries]}`` (``robot`` optional), or the springs as a
  table ``{"LF_femur": {"family": …, "parameters": …}, …}``.

Numbers may also be in the paper's units (deg, N·mm/deg, N·mm, N·mm·s/deg; converted by
:mod:`hexaleg.units`). :func:`read_design` is the one reader; :func:`design_table` writes the
entries (as ``simulate.json`` records its springs).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from hexaleg.config import read_json
from hexaleg.design.spring_json import spring_entry, spring_from_entry
from hexaleg.errors import ConfigError, InvalidParameterError
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet
from hexaleg.units import (
    deg_to_rad,
    nmm_per_deg_to_nm_per_rad,
    nmm_to_nm,
    nmms_per_deg_to_nms_per_rad,
)

PAPER_UNITS = {"deg": ("rad", deg_to_rad), "N·mm/deg": ("N·m/rad", nmm_per_deg_to_nm_per_rad),
               "N·mm": ("N·m", nmm_to_nm), "N·mm·s/deg": ("N·m·s/rad", nmms_per_deg_to_nms_per_rad)}
"""A paper unit → (its SI unit, the conversion)."""


def _si(value: Any) -> Any:
    """A parameter with any ``{value, unit}`` in a paper unit converted to SI (recursively)."""
    if isinstance(value, Mapping) and set(value) == {"value", "unit"} \
            and value["unit"] in PAPER_UNITS and isinstance(value["value"], (int, float)):
        unit, convert = PAPER_UNITS[value["unit"]]
        return {"value": float(convert(value["value"])), "unit": unit}
    if isinstance(value, Mapping):
        return {k: _si(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_si(v) for v in value]
    return value


def _entries(data: Mapping[str, Any], where: str) -> tuple[list[Any], Any]:
    """The spring entries of a design document and the robot it names (or None)."""
    recommended = data.get("recommended")
    if isinstance(recommended, Mapping):  # hexaleg design's design.json
        springs = recommended.get("springs", [])
    else:
        springs = data.get("springs")
        if isinstance(springs, Mapping):
            springs = [{**t, "joint": j} if isinstance(t, Mapping) else t
                       for j, t in springs.items()]
    if not isinstance(springs, list):
        raise ConfigError(f"{where}: expected the design.json of hexaleg design or "
                          "{\"robot\": …, \"springs\": [{family, joint, parameters}, …]}")
    robot = data.get("robot")
    return springs, robot.get("name") if isinstance(robot, Mapping) else robot


def read_document(path: str | Path) -> Mapping[str, Any]:
    """A design file's JSON object, through the one bounded reader
    (:func:`hexaleg.config.read_json`: a regular file of at most
    :data:`~hexaleg.config.MAX_TEXT_BYTES`, UTF-8, no NaN or Infinity).

    Raises:
        ConfigError: the file is missing, not a regular file (a pipe, ``/dev/zero``, a
            directory), too large, unreadable, not JSON, holds NaN/Infinity or is not a JSON
            object.
    """
    return read_json(path, "design file")


def read_design(path: str | Path, robot: Robot, robot_name: str | None = None) -> SpringSet:
    """The springs of a design file (module docstring), checked against ``robot``.

    Args:
        path: The JSON file.
        robot: The simulated robot.
        robot_name: Its registry name or description file, matched against the file's robot
            along with ``robot.name``.

    Returns:
        The springs, SI.

    Raises:
        ConfigError: the file is missing, not JSON, malformed, a joint given twice, or a number
            not in its field's unit (SI or the paper's).
        InvalidParameterError: the file is for another robot, or a value is out of range.
        UnknownNameError: an unknown family, parameter or joint (lists the valid ones).
    """
    path = Path(path)
    data = read_document(path)
    entries, owner = _entries(data, str(path))
    names = {robot.name, *([robot_name] if robot_name else [])}
    if owner is not None and owner not in names:
        raise InvalidParameterError(f"{path}: robot", owner,
                                    f"the simulated robot ({' or '.join(sorted(names))})")
    if not entries:
        raise ConfigError(f"{path}: no springs (its {'recommended.' * ('recommended' in data)}"
                          "springs is empty or missing); a design file names at least one "
                          "spring, {family, joint, parameters}: without springs there is nothing "
                          "to simulate or fit (the baseline is the run without them)")
    springs = {}
    for entry in entries:
        joint = entry.get("joint") if isinstance(entry, Mapping) else None
        if not isinstance(joint, str):
            raise ConfigError(f"{path}: a spring entry without its joint: {entry!r}")
        if joint in springs:
            raise ConfigError(f"{path}: two springs on {joint}; give one entry per joint")
        springs[joint] = spring_from_entry(_si(entry), f"{path}: springs.{joint}")
    out = SpringSet(springs)
    out.columns(robot)  # UnknownNameError listing the robot's joints
    return out


def design_table(springs: SpringSet, robot: str | None = None) -> dict[str, Any]:
    """``springs`` as a design document: ``{"robot": …, "springs": [entries]}``, SI."""
    entries = [spring_entry(j, s) for j, s in springs.items()]
    return {**({"robot": robot} if robot else {}), "springs": entries}
