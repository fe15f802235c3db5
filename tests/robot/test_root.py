"""A root frame below the feet: refused where the stand is made with the fix named, or moved by
the stated ``root_offset`` (hexaleg.robot.root)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from hexaleg.cli import main
from hexaleg.errors import ConfigError, InvalidParameterError, RobotModelError
from hexaleg.robot.registry import load

DATA = Path(__file__).resolve().parents[1] / "data"
ROOT = '<link name="base_link">'
BELOW = ('<link name="ground_ref"/>\n  <joint name="ground_to_base" type="fixed"><parent '
         'link="ground_ref"/><child link="base_link"/><origin xyz="0 0 0.3"/></joint>\n  ' + ROOT)
"""The spider's body hung 0.3 m above a massless root link (a "footprint" frame): its feet,
0.1 m below the body at the zero configuration, are 0.2 m above the root."""
STAND = "stand = {body_height = 0.08}"


def footprint_spider(tmp_path: Path, stand: str = STAND, extra: str = "") -> Path:
    """spider.urdf with :data:`BELOW`, its TOML's stand replaced and ``extra`` lines added to
    [robot]; returns the TOML."""
    (tmp_path / "spider.urdf").write_text((DATA / "spider.urdf").read_text().replace(
        ROOT, BELOW, 1))
    toml = (DATA / "spider.toml").read_text().replace(STAND, stand + "\n" + extra)
    (tmp_path / "spider.toml").write_text(toml)
    return tmp_path / "spider.toml"


@pytest.mark.parametrize(("stand", "where"), [
    ("stand = {}", "in the stand pose"),
    (STAND, "in the zero configuration (the stand's feet at body_height below the base cannot "
            "be reached)"),
])
def test_hexaleg_robot_refuses_it_naming_the_offset_to_paste(tmp_path, capsys, stand, where):
    """Standing at the zero configuration the base is 0.2 m under the mean foot; with a body
    height the stand cannot be solved, and the root is the cause named (not "lower
    body_height"). The fix proposed is the body's centre of mass, 0.3 m above the root."""
    toml = footprint_spider(tmp_path, stand)
    assert main(["robot", "--robot", str(toml)]) == 2
    err = capsys.readouterr().err
    assert "the base origin is -0.2 m above the mean foot " + where in err
    assert "allowed: > 0 m" in err and "root (link ground_ref) sits below the feet" in err
    assert "root_offset = [0, 0, 0.3]" in err and "Traceback" not in err


@pytest.mark.parametrize("command", ["design", "simulate"])
def test_design_and_simulate_on_it_end_in_the_named_error(tmp_path, capsys, command):
    toml = footprint_spider(tmp_path)
    assert main([command, "--robot", str(toml), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "root_offset = [0, 0, 0.3]" in err and "Traceback" not in err


def test_the_offset_it_names_gives_back_the_spider(tmp_path, capsys, spider):
    """With ``root_offset = [0, 0, 0.3]`` the base frame is the spider's own: the same bodies
    (base inertia about the same origin), the same stand and feet, and the repair is stated."""
    toml = footprint_spider(tmp_path, extra="root_offset = [0, 0, 0.3]")
    robot = load(str(toml))
    (note,) = [n for n in robot.notes if n.startswith("root frame moved")]
    assert "[+0, +0, +0.3] m in the URDF root link ground_ref's frame" in note
    assert robot.mass == pytest.approx(spider.mass, rel=1e-12)
    a, b = robot.model.inertias[1], spider.model.inertias[1]
    np.testing.assert_allclose(a.lever, b.lever, atol=1e-12)
    np.testing.assert_allclose(a.inertia, b.inertia, atol=1e-15)
    np.testing.assert_allclose(robot.pose("stand"), spider.pose("stand"), atol=1e-9)
    q = spider.pose("stand")
    np.testing.assert_allclose(robot.foot_positions(q), spider.foot_positions(q), atol=1e-12)
    assert main(["robot", "--robot", str(toml)]) == 0
    out = capsys.readouterr().out
    assert "root frame moved (root_offset)" in out and "warning" not in out


def test_simulate_on_the_repaired_robot_ends_in_a_result(tmp_path, capsys):
    toml = footprint_spider(tmp_path, extra="root_offset = [0, 0, 0.3]")
    out = tmp_path / "out"
    assert main(["simulate", "--robot", str(toml), "--cycles", "2", "--out", str(out)]) == 0
    data = json.loads((out / "simulate.json").read_text())
    assert data["robot"] == "spider" and data["verdict"]
    capsys.readouterr()


@pytest.mark.parametrize(("value", "error", "says"), [
    ("[0, 0]", InvalidParameterError, r"root_offset.*\[x, y, z\] \(m, in the URDF"),
    ('[0, 0, "up"]', ConfigError, r"root_offset = \(0, 0, 'up'\).*expected tuple\[float"),
])
def test_a_bad_offset_is_named(tmp_path, value, error, says):
    toml = footprint_spider(tmp_path, extra=f"root_offset = {value}")
    with pytest.raises(error, match=says):
        load(str(toml))


def test_an_offset_still_below_the_feet_is_refused(tmp_path):
    toml = footprint_spider(tmp_path, "stand = {}", "root_offset = [0, 0, 0.1]")
    with pytest.raises(RobotModelError, match=r"-0.1 m above the mean foot in the stand pose"):
        load(str(toml))
