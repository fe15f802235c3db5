"""A robot description file: one's own robot from the ``[robot]`` table of a TOML file.

:func:`read_description` reads it into a :class:`~hexaleg.robot.description.RobotDescription`
(:meth:`RobotDescription.from_toml <hexaleg.robot.description.RobotDescription.from_toml>`); the
format and its errors are in its docstring. The reader lives with the description it makes, in
:mod:`hexaleg.robot.description` (``from_toml`` calls it); it is importable from here too.
"""

from __future__ import annotations

from hexaleg.robot.description import read_description

__all__ = ["read_description"]
