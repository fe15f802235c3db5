"""A robot description file: the ``[robot]`` table of one's own robot's TOML file, parsed.

:func:`description_table` reads the table into the keyword arguments of a
:class:`~hexaleg.robot.description.RobotDescription` — relative paths made relative to the file,
lists turned into the tuples the description holds, the legs into
:class:`~hexaleg.robot.feet.LegSpec`, a named heading into its axis — and
:func:`~hexaleg.robot.description.read_description`
(:meth:`RobotDescription.from_toml <hexaleg.robot.description.RobotDescription.from_toml>`) makes
the description from them, which checks every value.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import Any

from hexaleg.config import load_toml
from hexaleg.errors import ConfigError
from hexaleg.robot.fields import axis, legs_table
from hexaleg.robot.sources import FILES


def description_table(path: str | Path) -> tuple[dict[str, Any], str]:
    """The ``[robot]`` table of a TOML file as a description's keyword arguments.

    Example (relative paths are relative to the TOML file; ``source`` defaults to
    :data:`~hexaleg.robot.sources.FILES`)::

        [robot]
        name = "myquad"
        title = "My quadruped"
        urdf = "myquad.urdf"
        srdf = "myquad.srdf"          # optional
        stand = "standing"            # a group_state, or a table {joint = angle_rad}
        joint_kinds = ["haa", "hfe", "kfe"]
        spring_class = "kfe"
        mesh_dirs = ["."]             # where package:// URIs resolve
        [robot.gait]                  # GaitParams keys (hexaleg.motion.params)
        period = 0.5
        groups = [["LF", "RH"], ["RF", "LH"]]
        [[robot.legs]]
        name = "LF"
        joints = ["LF_HAA", "LF_HFE", "LF_KFE"]
        foot = "LF_FOOT"
        # ... one [[robot.legs]] table per leg

    Args:
        path: The TOML file.

    Returns:
        The table's keys and values, and where they are for messages (``"<path> [robot]"``).

    Raises:
        ConfigError: the file cannot be read, has no ``[robot]`` table, a leg table is not one,
            or the stand is neither a name nor a table.
    """
    path = Path(path)
    where = f"{path} [robot]"
    table = load_toml(path).get("robot")
    if not isinstance(table, Mapping):
        raise ConfigError(f"{path}: expected a [robot] table")
    data = dict(table)
    if "legs" in data:
        data["legs"] = legs_table(data["legs"], where)
    for key in ("joint_kinds", "mesh_dirs", "heading", "root_offset"):
        if isinstance(data.get(key), list):
            data[key] = tuple(data[key])
    data.setdefault("source", FILES)
    if data["source"] == FILES:
        for key in ("urdf", "srdf"):
            if isinstance(data.get(key), str):
                data[key] = str(path.parent / data[key])
        if isinstance(data.get("mesh_dirs"), tuple):  # a list of the file, made a tuple above
            data["mesh_dirs"] = tuple(str(path.parent / d) if isinstance(d, str) else d
                                      for d in data["mesh_dirs"])
    if not isinstance(data.get("stand", ""), (str, Mapping)):
        raise ConfigError(f"{where}.stand = {data['stand']!r}; expected a group_state name, "
                          "a table of joint angles or {body_height, feet}")
    if isinstance(data.get("heading"), str):
        data["heading"] = axis(data["heading"], where)
    return data, where


__all__ = ["description_table"]
