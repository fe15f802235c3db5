"""``hexaleg.load_design``: a ``design.json`` read back as the springs to fit and what they were
designed for.

``hexaleg design`` writes, beside every number, the gait it designed on as its parameters
(``gait.parameters``, the fields of :class:`~hexaleg.motion.params.GaitParams`) and the robot
by name. :func:`load_design` reads them back: the recommended springs as a
:class:`~hexaleg.robot.springs.SpringSet` (the one reader,
:func:`hexaleg.studies.simulate.design_file.read_design`, every value checked: finite, in its
unit, on the robot's joints), the gait re-made from its parameters over the robot's own
(checked as a ``[gait]`` table is), and the predicted saving. ``hexaleg simulate --springs
design.json`` and ``hexaleg report --design`` use the same gait, so the three commands predict
the same number for the same springs.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass, fields
from pathlib import Path
from typing import Any

from hexaleg.checks import is_real, typed
from hexaleg.errors import ConfigError, InvalidParameterError
from hexaleg.motion.params import GaitParams
from hexaleg.robot.registry import description
from hexaleg.robot.springs import SpringSet
from hexaleg.studies.simulate.design_file import read_design, read_document


@dataclass(frozen=True, eq=False)
class LoadedDesign:
    """A design file read back.

    Attributes:
        robot: The robot's registered name or description file.
        springs: The recommended springs, SI.
        gait: The gait they were designed on (None for a hand-written file without one).
        metric: The metric the design was ranked by (None without one).
        saving: The predicted saving of that metric, fraction (None without one).
        pays: Whether the springs pay for their mass (None without the answer).
        log: The motion log the design was made on (``gait.motion.path``), None on a generated
            gait; such a design has no ``gait`` to re-make.
    """

    robot: str
    springs: SpringSet
    gait: GaitParams | None
    metric: str | None
    saving: float | None
    pays: bool | None
    log: str | None = None


GAIT_UNITS: dict[str, str] = {
    "period": "s", "duty_factor": "1", "stride_length": "m", "speed": "m/s", "step_height": "m",
    "body_height": "m", "foot_radius": "m", "yaw_rate": "rad/s", "phases": "1", "heading": "rad",
    "slope": "rad", "cross_slope": "rad", "min_static_margin": "m"}
"""The SI unit of each numeric field of :class:`GaitParams` (``{value, unit}`` in JSON)."""


def gait_parameters(gait: GaitParams) -> dict[str, Any]:
    """The gait's set fields for JSON, numbers as ``{value, unit}`` (:data:`GAIT_UNITS`): what
    :func:`design_gait` reads back to a :class:`GaitParams` that walks the same. With a
    ``speed`` the stride is ``speed × period`` (the speed wins), and ``stride_length`` is
    written as that: the stride the gait walks, not the field's unused default (#41: 0.06 m
    for a co-designed gait that walks 0.102 m a cycle)."""
    plain = json.loads(json.dumps({f.name: getattr(gait, f.name) for f in fields(gait)
                                   if getattr(gait, f.name) is not None}))
    plain["stride_length"] = gait.stride
    return {k: {"value": v, "unit": GAIT_UNITS[k]} if k in GAIT_UNITS else v
            for k, v in plain.items()}


def _plain(table: Mapping[str, Any], where: str) -> dict[str, Any]:
    """``gait.parameters`` as a ``[gait]`` table: each ``{value, unit}`` in its SI unit."""
    out = {}
    for k, v in table.items():
        if isinstance(v, Mapping) and set(v) == {"value", "unit"}:
            if v["unit"] != GAIT_UNITS.get(k):
                raise InvalidParameterError(f"{where}.{k}.unit", v["unit"],
                                            GAIT_UNITS.get(k, "no unit: a plain value"))
            v = v["value"]
        out[k] = v
    return out


def design_gait(data: Mapping[str, Any], robot: str, where: str) -> GaitParams | None:
    """The gait of a design document (``gait.parameters`` over the robot's own gait), or None
    when it has none.

    Raises:
        ConfigError: ``gait.parameters`` not a table. UnknownNameError, InvalidParameterError:
            a key or value a ``[gait]`` table may not have (named).
    """
    gait = data.get("gait")
    table = gait.get("parameters") if isinstance(gait, Mapping) else None
    if table is None:
        return None
    if not isinstance(table, Mapping):
        raise ConfigError(f"{where}: gait.parameters must be a table of gait parameters, got "
                          f"{type(table).__name__}")
    where = f"{where}: gait.parameters"
    return GaitParams.for_robot(description(robot)).updated(_plain(table, where), where)


@typed
def load_design(path: str | Path, robot: str | None = None) -> LoadedDesign:
    """The springs a design file recommends and what they were designed for (module
    docstring).

    Args:
        path: A ``design.json`` of ``hexaleg design`` (or a hand-written design file,
            :mod:`hexaleg.studies.simulate.design_file`).
        robot: The robot to load it for; default the file's (``hexaleg`` when it names none).

    Raises:
        ConfigError: the file is missing, not JSON or malformed.
        InvalidParameterError: a design for another robot than ``robot``, a non-finite saving,
            a saving that is not a table of metrics.
        UnknownNameError: an unknown robot, family, parameter or joint (lists the valid ones).
    """
    path = Path(path)
    data = read_document(path)
    owner = data.get("robot")
    owner = owner.get("name") if isinstance(owner, Mapping) else owner
    name = robot or (owner if isinstance(owner, str) else "hexaleg")
    loaded = description(name).load()
    springs = read_design(path, loaded, name)
    settings = data.get("settings")
    metric = settings.get("metric") if isinstance(settings, Mapping) else None
    saving = None
    rec = data.get("recommended")
    if isinstance(rec, Mapping) and isinstance(metric, str):
        table = rec.get("saving", {})
        if not isinstance(table, Mapping):
            raise InvalidParameterError(f"{path}: recommended.saving", table,
                                        "a table of metric = {value, unit} (design.json's)")
        value = table.get(metric, {})
        value = value.get("value") if isinstance(value, Mapping) else None
        if value is not None:
            if not is_real(value):
                raise InvalidParameterError(f"{path}: recommended.saving.{metric}", value,
                                            "a finite saving in %")
            saving = float(value) / 100
    pays = data.get("pays")
    gait = data.get("gait")
    motion = gait.get("motion") if isinstance(gait, Mapping) else None
    log = motion.get("path") if isinstance(motion, Mapping) else None
    return LoadedDesign(robot=name, springs=springs, gait=design_gait(data, name, str(path)),
                        metric=metric if isinstance(metric, str) else None, saving=saving,
                        pays=pays if isinstance(pays, bool) else None,
                        log=str(log) if log is not None else None)


__all__ = ["GAIT_UNITS", "LoadedDesign", "design_gait", "gait_parameters", "load_design"]
