"""A robot description file: one's own robot from the ``[robot]`` table of a TOML file.

:func:`read_description` reads it into a :class:`~hexaleg.robot.description.RobotDescription`
(:meth:`RobotDescription.from_toml <hexaleg.robot.description.RobotDescription.from_toml>`).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

from hexaleg.config import from_mapping, load_toml
from hexaleg.errors import ConfigError
from hexaleg.robot.description import FILES, RobotDescription
from hexaleg.robot.fields import axis, legs_table


def read_description(path: str | Path) -> RobotDescription:
    """A description of one's own robot from the ``[robot]`` table of a TOML file.

    Example (relative paths are relative to the TOML file; ``source`` defaults to
    :data:`FILES`)::

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
        The description (its files are not opened until
        :meth:`~hexaleg.robot.description.RobotDescription.load`).

    Raises:
        ConfigError: the file cannot be read, has no ``[robot]`` table or no
            ``[[robot.legs]]`` tables, or a value has the wrong type.
        UnknownNameError: an unknown key (the message lists the valid keys).
        InvalidParameterError: a value out of range.
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
        if isinstance(data.get("mesh_dirs"), list):
            data["mesh_dirs"] = [str(path.parent / d) if isinstance(d, str) else d
                                 for d in data["mesh_dirs"]]
    if not isinstance(data.get("stand", ""), (str, Mapping)):
        raise ConfigError(f"{where}.stand = {data['stand']!r}; expected a group_state name, "
                          "a table of joint angles or {body_height, feet}")
    if isinstance(data.get("heading"), str):
        data["heading"] = axis(data["heading"], where)
    return from_mapping(RobotDescription, data, where)


__all__ = ["read_description"]
