"""Where a robot description's files come from: hexaleg's own folder, the installed
example-robot-data, or paths as given.

A :class:`~hexaleg.robot.description.RobotDescription` names its URDF and SRDF relative to its
``source``'s directory (:func:`source_dir`). The quadrupeds' files come from the installed
``example-robot-data`` distribution (a cmeel package without a Python module), located through
:mod:`importlib.metadata` (:func:`example_robot_data_dir`), never from the network.
"""

from __future__ import annotations

import importlib.metadata
from pathlib import Path

from hexaleg.errors import RobotModelError
from hexaleg.robot.model import URDF_DIR

BUILTIN = "hexaleg"
"""Files source of the robot shipped with hexaleg (``urdf/hexaleg.urdf`` and ``.srdf``)."""
EXAMPLE_ROBOT_DATA = "example-robot-data"
"""Files source: the installed example-robot-data distribution (paths relative to its
``share/example-robot-data/robots`` directory)."""
FILES = "files"
"""Files source: paths as given (absolute, or relative to the working directory; a TOML
description's relative paths are made relative to its own directory)."""
SOURCES: tuple[str, ...] = (BUILTIN, EXAMPLE_ROBOT_DATA, FILES)


def example_robot_data_dir() -> Path:
    """The ``share/example-robot-data/robots`` directory of the installed example-robot-data.

    Found from the distribution's file list (:func:`importlib.metadata.distribution`), so it does
    not depend on where the package is installed nor on the cmeel prefix's name.

    Returns:
        The directory holding ``<robot>_description/`` folders.

    Raises:
        RobotModelError: example-robot-data is not installed, or its file list has no robots.
    """
    try:
        dist = importlib.metadata.distribution(EXAMPLE_ROBOT_DATA)
    except importlib.metadata.PackageNotFoundError:
        raise RobotModelError("the example-robot-data package is not installed; "
                              "pip install example-robot-data") from None
    for f in dist.files or ():
        parts = f.parts
        for i in range(len(parts) - 2):
            if parts[i:i + 3] == ("share", "example-robot-data", "robots"):
                return Path(str(dist.locate_file(Path(*parts[:i + 3]))))
    raise RobotModelError(f"example-robot-data {dist.version} has no share/example-robot-data/"
                          "robots directory in its file list")


def source_dir(source: str) -> Path:
    """The directory a source's paths are relative to: hexaleg's ``urdf/``
    (``hexaleg.robot.model.URDF_DIR``) for :data:`BUILTIN`, :func:`example_robot_data_dir` for
    :data:`EXAMPLE_ROBOT_DATA`, the working directory for :data:`FILES`."""
    if source == EXAMPLE_ROBOT_DATA:
        return example_robot_data_dir()
    return URDF_DIR if source == BUILTIN else Path()


__all__ = ["BUILTIN", "EXAMPLE_ROBOT_DATA", "FILES", "SOURCES", "example_robot_data_dir",
           "source_dir"]
