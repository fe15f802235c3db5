"""Tests of hexaleg.robot.description_file: the ``[robot]`` table of one's own robot's TOML file
parsed into a description's keyword arguments (its values are checked by the description:
tests/robot/test_description.py)."""

from __future__ import annotations

import pytest
from conftest import SPIDER

from hexaleg.errors import ConfigError
from hexaleg.robot.description import RobotDescription
from hexaleg.robot.description_file import description_table
from hexaleg.robot.feet import LegSpec
from hexaleg.robot.sources import EXAMPLE_ROBOT_DATA, FILES


def test_the_test_robot_reads_with_its_paths_relative_to_the_file():
    data, where = description_table(SPIDER)
    assert where == f"{SPIDER} [robot]"
    assert data["source"] == FILES and data["urdf"] == str(SPIDER.parent / "spider.urdf")
    assert data["heading"] == (0.0, 1.0, 0.0)  # "+y", the axis it names
    assert RobotDescription(**data) == RobotDescription.from_toml(SPIDER)


def test_lists_become_the_descriptions_tuples_and_legs_its_specs(tmp_path):
    """Paths of another source stay as given (relative to that source's directory)."""
    path = tmp_path / "robot.toml"
    path.write_text(f'[robot]\nname = "x"\nurdf = "x/x.urdf"\nsource = "{EXAMPLE_ROBOT_DATA}"\n'
                    'joint_kinds = ["a", "b"]\nroot_offset = [0.0, 0.0, 0.1]\n'
                    '[[robot.legs]]\nname = "LF"\njoints = ["j1", "j2"]\nfoot = "f"\n')
    data, _ = description_table(path)
    assert data["urdf"] == "x/x.urdf"
    assert data["joint_kinds"] == ("a", "b") and data["root_offset"] == (0.0, 0.0, 0.1)
    assert data["legs"] == (LegSpec("LF", ("j1", "j2"), "f"),)


def test_mesh_directories_are_relative_to_the_file(tmp_path):
    """``mesh_dirs`` of a robot's own files are relative to its TOML file, like its URDF
    (they were kept as written — relative to wherever the command ran — as the list had
    already been made a tuple when the paths were resolved); another source's stay as given."""
    path = tmp_path / "robot.toml"
    path.write_text('[robot]\nname = "x"\nurdf = "x.urdf"\nmesh_dirs = ["meshes", "."]\n')
    data, _ = description_table(path)
    assert data["mesh_dirs"] == (str(tmp_path / "meshes"), str(tmp_path / "."))
    path.write_text(f'[robot]\nname = "x"\nurdf = "x.urdf"\nsource = "{EXAMPLE_ROBOT_DATA}"\n'
                    'mesh_dirs = ["meshes"]\n')
    assert description_table(path)[0]["mesh_dirs"] == ("meshes",)


@pytest.mark.parametrize(("text", "says"), [
    ("[other]\nx = 1\n", r"\[robot\] table"),
    ('[robot]\nname = "x"\nurdf = "x.urdf"\nstand = 3\n', "stand"),
    ('[robot]\nname = "x"\nurdf = "x.urdf"\nlegs = 3\n', r"\[\[robot.legs\]\]"),
])
def test_a_bad_description_file_is_named(tmp_path, text, says):
    path = tmp_path / "robot.toml"
    path.write_text(text)
    with pytest.raises(ConfigError, match=says):
        description_table(path)
