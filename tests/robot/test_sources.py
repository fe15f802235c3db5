"""Tests of hexaleg.robot.sources: each source's directory, example-robot-data found from the
installed distribution's file list, and a named error without it."""

from __future__ import annotations

import importlib.metadata
from pathlib import Path

import pytest

from hexaleg.errors import RobotModelError
from hexaleg.robot.model import URDF_DIR
from hexaleg.robot.sources import (
    BUILTIN,
    EXAMPLE_ROBOT_DATA,
    FILES,
    SOURCES,
    example_robot_data_dir,
    source_dir,
)


def test_each_source_has_its_directory():
    assert SOURCES == (BUILTIN, EXAMPLE_ROBOT_DATA, FILES)
    assert (source_dir(BUILTIN) / "hexaleg.urdf").is_file() and source_dir(BUILTIN) == URDF_DIR
    assert source_dir(EXAMPLE_ROBOT_DATA) == example_robot_data_dir()
    assert source_dir(FILES) == Path()


def test_example_robot_data_is_found_in_its_file_list():
    robots = example_robot_data_dir()
    assert robots.parts[-3:] == ("share", "example-robot-data", "robots")
    assert (robots / "solo_description" / "robots" / "solo12.urdf").is_file()


def test_without_example_robot_data_the_error_says_how_to_install_it(monkeypatch):
    def missing(name):
        raise importlib.metadata.PackageNotFoundError(name)

    monkeypatch.setattr(importlib.metadata, "distribution", missing)
    with pytest.raises(RobotModelError, match="pip install example-robot-data"):
        example_robot_data_dir()
