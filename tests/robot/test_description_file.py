"""Tests of hexaleg.robot.description_file: one's own robot from a TOML file."""

from __future__ import annotations

import pytest
from conftest import SPIDER

from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.robot.description import RobotDescription
from hexaleg.robot.description_file import read_description


def test_the_test_robot_reads_with_its_paths_relative_to_the_file():
    desc = read_description(SPIDER)
    assert desc == RobotDescription.from_toml(SPIDER)
    assert desc.urdf.startswith(str(SPIDER.parent))


@pytest.mark.parametrize(("text", "error", "says"), [
    ("[other]\nx = 1\n", ConfigError, r"\[robot\] table"),
    ('[robot]\nname = "x"\nurdf = "x.urdf"\nstand = 3\n', ConfigError, "stand"),
    ('[robot]\nname = "x"\nurdf = "x.urdf"\nspeeed = 3\n', UnknownNameError, "speeed"),
    ('[robot]\nname = "x"\nurdf = "x.urdf"\njoint_kinds = ["a", "b"]\n'
     '[robot.arbor_diameter]\na = -0.001\n', InvalidParameterError, r"arbor_diameter\.a"),
])
def test_a_bad_description_file_is_named(tmp_path, text, error, says):
    path = tmp_path / "robot.toml"
    path.write_text(text)
    with pytest.raises(error, match=says):
        read_description(path)


def test_the_reader_is_the_description_s_own():
    """It lives with the description it makes (from_toml calls it); imported here too."""
    from hexaleg.robot import description

    assert read_description is description.read_description
