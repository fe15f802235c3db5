"""#38's must-show: ``hexaleg design --motion`` on logs no one here wrote — a MuJoCo walk after
a drop and a settle, noisy, without contact columns (full pose, joints + IMU, joints alone) —
ends in a design, its motion's quality and residual in design.json."""

from __future__ import annotations

import json

import pytest

import hexaleg
from hexaleg.cli import main
from hexaleg.simulation.walk_log import walk_log

SMALL = """
[design]
families = ["one_sided"]
stop_tolerance = 0.0
controller = "feedforward"
"""
"""A small design on the log (the default ran every family under both servos: ~100 s of CPU
for the three logs, CI's 15 minutes could not hold it)."""


@pytest.fixture(scope="module")
def walk(robot):
    return walk_log(robot, hexaleg.gait(robot), rate=100.0)


@pytest.mark.slow
@pytest.mark.parametrize("parts", [("joints", "base", "imu"), ("joints", "imu"), ("joints",)],
                         ids=["pose", "imu", "joints"])
def test_design_on_a_simulated_walk_log_ends_in_a_design(walk, parts, tmp_path, capsys):
    log = walk.write(tmp_path / "walk.csv", parts)
    out = tmp_path / "design"
    config = tmp_path / "small.toml"  # the log's reading is the point: one family, one servo
    config.write_text(SMALL)
    assert main(["design", "--motion", str(log), "--config", str(config), "--out", str(out)]) \
        == 0
    printed = capsys.readouterr().out
    assert "steady from t = 1.0" in printed  # the drop and the settle left out
    data = json.loads((out / "design.json").read_text(encoding="utf-8"))
    recommended = data["recommended"]
    assert recommended["family"] and recommended["saving"]["electrical"]["value"] > 0.0
    quality = data["motion_quality"]
    assert quality["stance_source"] == "kinematics"
    for leg, simulated in walk.touch.items():
        assert quality["touch_fractions"][leg]["value"] == pytest.approx(simulated, abs=0.05)
