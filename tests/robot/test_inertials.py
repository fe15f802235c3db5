"""Impossible link inertias: refused at load with the fix named, or repaired by the box rule."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from hexaleg.cli import main
from hexaleg.errors import InvalidParameterError, RobotModelError
from hexaleg.robot.inertials import box_inertia
from hexaleg.robot.model import load_robot
from hexaleg.robot.sanity import robot_findings
from hexaleg.robot.stand import stand_from_feet

DATA = Path(__file__).resolve().parents[1] / "data"
SHIN = '<inertia ixx="2.527e-05" ixy="0" ixz="0" iyy="2.527e-05" iyz="0" izz="5.4e-07"/>'
"""The spider's first shin (a_shin): 30 g, a 12 mm × 100 mm cylinder along z, CoM at its centre."""
PLACEHOLDER = '<inertia ixx="1e-06" ixy="0" ixz="0" iyy="1e-06" iyz="0" izz="5e-05"/>'
"""Principal moments 1e-6, 1e-6, 5e-5 kg·m²: I1 + I2 < I3, no mass distribution has them."""


def broken_spider(tmp_path: Path, old: str = SHIN, new: str = PLACEHOLDER) -> Path:
    """spider.urdf and spider.toml copied to ``tmp_path``, ``old`` replaced once by ``new``;
    returns the TOML description."""
    shutil.copy(DATA / "spider.toml", tmp_path / "spider.toml")
    text = (DATA / "spider.urdf").read_text()
    assert old in text
    (tmp_path / "spider.urdf").write_text(text.replace(old, new, 1))
    return tmp_path / "spider.toml"


def load(tmp_path: Path, **kwargs: str):  # the spider as its TOML loads it: legs found, +y ahead
    return load_robot(tmp_path / "spider.urdf", legs="auto", heading=(0, 1, 0), **kwargs)


def test_impossible_inertia_is_refused_naming_link_moments_allowed_and_fix(tmp_path):
    broken_spider(tmp_path)
    with pytest.raises(RobotModelError) as info:
        load(tmp_path)
    text = str(info.value)
    assert "link 'a_shin': mass 0.03 kg, principal moments 1e-06, 1e-06, 5e-05 kg·m²" in text
    assert "I1 + I2 = 2e-06 < I3 (allowed: I1 + I2 ≥ 0.999 · I3" in text
    # the box of the 12 × 12 × 100 mm cylinder, m (b² + c²) / 12 = 0.03 · (0.012² + 0.1²) / 12
    assert "(12 × 12 × 100 mm)" in text and 'ixx="2.536e-05"' in text and 'izz="7.2e-07"' in text
    assert 'inertias="repair"' in text


def test_repair_writes_the_box_inertia_notes_it_and_the_robot_analyses(tmp_path):
    import hexaleg

    broken_spider(tmp_path)
    robot = load(tmp_path, inertias="repair")
    (note,) = [n for n in robot.notes if n.startswith("inertias repaired")]
    assert "a_shin" in note and "invented" in note and "12 × 12 × 100 mm" in note
    jid = robot.model.getJointId(robot.leg("LF").joint_names[2])
    inertia = robot.model.inertias[jid]
    m, a, c = 0.03, 0.012, 0.1  # CoM at the box's centre: no Steiner term
    expected = m / 12 * np.diag([a * a + c * c, a * a + c * c, 2 * a * a])
    assert inertia.mass == pytest.approx(m)
    np.testing.assert_allclose(inertia.inertia, expected, rtol=1e-12)
    robot.poses["stand"] = stand_from_feet(robot, 0.08)  # as spider.toml's stand
    assert robot_findings(robot) == []
    motion = hexaleg.gait(robot)
    analysis = hexaleg.prepare(robot, motion).evaluate({})
    assert np.isfinite(analysis.metrics["total"]["electrical"])


def test_keep_loads_as_written_and_the_sanity_checks_still_warn(tmp_path):
    broken_spider(tmp_path)
    robot = load(tmp_path, inertias="keep")
    assert [f.check for f in robot_findings(robot)] == ["inertia_triangle"]
    with pytest.raises(InvalidParameterError, match="'refuse' or 'repair' or 'keep'"):
        load(tmp_path, inertias="fix")


def test_negative_mass_is_refused_even_with_repair(tmp_path):
    broken_spider(tmp_path, '<mass value="0.03"/>', '<mass value="-0.03"/>')
    with pytest.raises(RobotModelError, match="negative mass") as info:
        load(tmp_path, inertias="repair")
    assert 'inertias="repair"' not in str(info.value).split("\n")[-1]


def test_box_inertia_of_a_cube_about_its_corner_is_the_textbook_value():
    """A cube of side s about a corner: I_xx = 2/3 m s², I_xy = −1/4 m s² (Meriam & Kraige);
    Steiner's term from the centre's inertia m s²/6 gives it."""
    m, s = 2.0, 0.1
    tensor = box_inertia(m, np.zeros(3), np.full(3, s), np.zeros(3))
    expected = m * s * s * (np.full((3, 3), -0.25) + np.eye(3) * (2 / 3 + 0.25))
    np.testing.assert_allclose(tensor, expected, rtol=1e-12)
    moments = np.linalg.eigvalsh(tensor)
    assert moments[0] + moments[1] >= moments[2]


def test_hexaleg_robot_on_the_broken_description_is_a_named_error(tmp_path, capsys):
    toml = broken_spider(tmp_path)
    assert main(["robot", "--robot", str(toml)]) == 2
    err = capsys.readouterr().err
    assert "a_shin" in err and "triangle inequality" in err and "Traceback" not in err


@pytest.mark.parametrize("command", ["design", "simulate"])
def test_design_and_simulate_on_the_broken_description_end_in_a_named_error(
        tmp_path, capsys, command):
    toml = broken_spider(tmp_path)
    out = tmp_path / "out"
    assert main([command, "--robot", str(toml), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "a_shin" in err and "principal moments" in err and "Traceback" not in err


def test_a_robot_toml_opts_into_the_repair(tmp_path):
    """A command-line user opts in from the robot's TOML (``inertias = "repair"`` in [robot]):
    `hexaleg robot --robot that.toml` then loads, its notes saying what was invented; an unknown
    mode is named."""
    from hexaleg.cli import main
    from hexaleg.errors import InvalidParameterError
    from hexaleg.robot.registry import load as load_registered

    toml = broken_spider(tmp_path)
    toml.write_text(toml.read_text() + 'inertias = "repair"\n')
    robot = load_registered(str(toml))
    assert any(n.startswith("inertias repaired") for n in robot.notes)
    assert main(["robot", "--robot", str(toml)]) == 0
    toml.write_text(toml.read_text().replace('"repair"', '"mend"'))
    with pytest.raises(InvalidParameterError, match="inertias"):
        load_registered(str(toml))


def test_a_repair_of_many_links_is_summarised(tmp_path):
    """Every shin bad (six links): the note spells out three repairs and names the rest, where
    it was one line of every link's inertia (3000 characters on a real robot)."""
    shutil.copy(DATA / "spider.toml", tmp_path / "spider.toml")
    text = (DATA / "spider.urdf").read_text()
    (tmp_path / "spider.urdf").write_text(text.replace(SHIN, PLACEHOLDER))
    robot = load(tmp_path, inertias="repair")
    (note,) = [n for n in robot.notes if n.startswith("inertias repaired")]
    assert note.startswith("inertias repaired on 6 link(s)")
    assert note.count("→") == 3 and "and 3 more by the same rule: " in note
    assert len(note) < 900  # three repairs spelt out, the rest named
