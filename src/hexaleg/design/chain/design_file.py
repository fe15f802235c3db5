"""A spring design on disk: the ``design.json`` of ``hexaleg design``, or a hand-written one.

Springs are the entries of :mod:`hexaleg.design.springs.law_json` (the one JSON form of a spring law
in hexaleg), one per sprung joint::

    {"family": "linear", "joint": "LF_femur",
     "parameters": {"stiffness": {"value": 0.8, "unit": "N·m/rad"},
                    "reference": {"value": 0.35, "unit": "rad"}}}

``family`` one of :data:`hexaleg.design.springs.law_json.CLASSES`, ``parameters`` the fields of that
spring law (:mod:`hexaleg.robot.springs`), numbers ``{value, unit}``, the text fields plain, a
stiffening spring's stages ``[{"breakpoint": …, "stiffness": …}, …]``. :func:`read_design` takes:

* a ``design.json`` of ``hexaleg design``: its ``recommended`` design's ``springs``, its
  ``robot.name`` checked against the simulated robot;
* ``{"robot": "hexaleg", "springs": [entries]}`` (``robot`` optional), or the springs as a
  table ``{"LF_femur": {"family": …, "parameters": …}, …}``.

Numbers may also be in the paper's units (deg, N·mm/deg, N·mm, N·mm·s/deg; converted by
:mod:`hexaleg.units`). :func:`read_design` reads the springs; :func:`design_table` writes the
entries (as ``simulate.json`` records its springs).

:func:`load_design` is the one reader of a whole design file
(:meth:`hexaleg.design.chain.result.DesignResult.to_json` the one writer): ``hexaleg design``
writes, beside every number, the gait it designed on as its parameters (``gait.parameters``,
the fields of :class:`~hexaleg.motion.params.GaitParams`, :func:`gait_parameters`) and the
robot by name; :func:`load_design` reads back the recommended springs as a
:class:`~hexaleg.robot.springs.SpringSet` (:func:`read_design`, every value checked: finite, in
its unit, on the robot's joints), the gait re-made from its parameters over the robot's own
(checked as a ``[gait]`` table is, :func:`design_gait`), and the predicted saving. ``hexaleg
simulate --springs design.json`` and ``hexaleg report --design`` use the same gait, so the three
commands predict the same number for the same springs.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from hexaleg.checks import is_real, typed
from hexaleg.config import read_json
from hexaleg.design.evaluator import SAVING_METRICS
from hexaleg.design.springs.law_json import spring_entry, spring_from_entry
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.motion.params import GAIT_UNITS, GaitParams, gait_parameters
from hexaleg.motion.scaling import robot_gait
from hexaleg.robot.model import Robot
from hexaleg.robot.registry import description
from hexaleg.robot.springs import SpringSet
from hexaleg.scenario.scenario import robot_model
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


HAND_WRITTEN_KEYS = ("robot", "springs", "gait")
"""The keys of a hand-written design file (module docstring); a misspelt one (``robots``) would
otherwise skip the robot check."""
ENTRY_KEYS = ("family", "joint", "parameters")
"""The keys of one spring entry."""


def _entries(data: Mapping[str, Any], where: str) -> tuple[list[Any], Any]:
    """The spring entries of a design document and the robot it names (or None).

    Raises:
        UnknownNameError: a key a hand-written design file or a spring entry does not have.
    """
    recommended = data.get("recommended")
    if isinstance(recommended, Mapping):  # hexaleg design's design.json
        springs = recommended.get("springs", [])
    else:
        for key in data:
            if key not in HAND_WRITTEN_KEYS:
                raise UnknownNameError(f"key in the design file {where}", key,
                                       HAND_WRITTEN_KEYS)
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
    return springs_of(read_document(path), Path(path), robot, robot_name)


def springs_of(data: Mapping[str, Any], path: Path, robot: Robot,
               robot_name: str | None = None) -> SpringSet:
    """The springs of a design document already read from ``path`` (:func:`read_design`
    without reading it again)."""
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
        for key in entry:
            if key not in ENTRY_KEYS:
                raise UnknownNameError(f"key in the spring entry of {joint} in {path}", key,
                                       ENTRY_KEYS)
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
        document: The file's JSON object as read (once), for readers of its other sections.
    """

    robot: str
    springs: SpringSet
    gait: GaitParams | None
    metric: str | None
    saving: float | None
    pays: bool | None
    log: str | None = None
    document: Mapping[str, Any] = field(default_factory=dict, repr=False)


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


def design_gait(data: Mapping[str, Any], robot: str | None, where: str) -> GaitParams | None:
    """The gait of a design document (``gait.parameters`` over the robot's own gait; over the
    default :class:`~hexaleg.motion.params.GaitParams` when ``robot`` is None, to check the
    table alone), or None when it has none.

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
    base = GaitParams() if robot is None else robot_gait(description(robot))
    return base.updated(_plain(table, where), where)


def recommended_saving(data: Mapping[str, Any], where: str) -> tuple[str | None, float | None]:
    """The metric a design.json ranks by (``settings.metric``) and its recommended saving, a
    fraction; (None, None) for a hand-written file without them.

    Raises:
        InvalidParameterError: a metric that is not one of :data:`hexaleg.design.studies.curves.
            CURVE_METRICS`' energies, a saving table that is not a table, or a saving that is
            not a finite number of at most 100 % (of an energy, more cannot be saved).
    """
    settings = data.get("settings")
    metric = settings.get("metric") if isinstance(settings, Mapping) else None
    if metric is not None and metric not in SAVING_METRICS:
        raise InvalidParameterError(f"{where}: settings.metric", metric,
                                    "one of " + ", ".join(SAVING_METRICS))
    rec = data.get("recommended")
    if not (isinstance(rec, Mapping) and isinstance(metric, str)):
        return None, None
    for key in ("saving", "net_saving"):
        table = rec.get(key, {})
        if not isinstance(table, Mapping):
            raise InvalidParameterError(f"{where}: recommended.{key}", table,
                                        "a table of metric = {value, unit} (design.json's)")
        for name, q in table.items():
            value = q.get("value") if isinstance(q, Mapping) else q
            if value is not None and not (is_real(value) and value <= 100.0):
                raise InvalidParameterError(f"{where}: recommended.{key}.{name}", value,
                                            "a finite saving in %, at most 100 %")
    value = rec.get("saving", {}).get(metric, {})
    value = value.get("value") if isinstance(value, Mapping) else None
    return metric, (None if value is None else float(value) / 100)


@typed
def load_design(path: str | Path, robot: str | None = None) -> LoadedDesign:
    """The springs a design file recommends and what they were designed for (module
    docstring).

    Args:
        path: A ``design.json`` of ``hexaleg design`` (or a hand-written design file,
            module docstring).
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
    springs = springs_of(data, path, robot_model(name), name)  # the run's robot, loaded once
    metric, saving = recommended_saving(data, str(path))
    pays = data.get("pays")
    gait = data.get("gait")
    motion = gait.get("motion") if isinstance(gait, Mapping) else None
    log = motion.get("path") if isinstance(motion, Mapping) else None
    return LoadedDesign(robot=name, springs=springs, gait=design_gait(data, name, str(path)),
                        metric=metric if isinstance(metric, str) else None, saving=saving,
                        pays=pays if isinstance(pays, bool) else None,
                        log=str(log) if log is not None else None, document=data)


__all__ = ["GAIT_UNITS", "PAPER_UNITS", "LoadedDesign", "design_gait", "design_table",
           "gait_parameters", "load_design", "read_design", "read_document", "springs_of"]
