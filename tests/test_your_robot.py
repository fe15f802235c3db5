"""A robot of one's own, end to end: the test hexapod (tests/data/spider.toml — five lines, a URDF
without foot frames, SRDF or body mesh, facing +y) through every command and the optimiser."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd

import hexaleg
from hexaleg.cli import main
from hexaleg.design.evaluator import evaluator
from hexaleg.design.studies.optimise import optimise

SPIDER = str(Path(__file__).resolve().parent / "data" / "spider.toml")  # tests run elsewhere


def test_description_is_five_lines():
    path = Path(__file__).resolve().parent / "data" / "spider.toml"
    lines = [ln for ln in path.read_text().splitlines() if ln.strip() and not ln.startswith("#")]
    assert len(lines) <= 10


def test_robot_and_gait_commands(capsys):
    assert main(["robot", "--robot", SPIDER]) == 0
    out = capsys.readouterr().out
    assert "robot spider:" in out and "legs found from the kinematic tree" in out
    assert "warning" not in out
    assert main(["gait", "--robot", SPIDER]) == 0
    warned = [line for line in capsys.readouterr().out.splitlines() if "warning" in line]
    # the run's warnings only (hexaleg.scenario.run_warnings), no failed check
    assert [w.split(" on ")[0].split(" to ")[0] for w in warned] == [
        "warning: gait defaults sized", "warning: generic actuator"]


def test_the_gait_walks_along_the_heading(spider):
    motion = hexaleg.gait(spider, hexaleg.GaitParams(samples=100))
    step = motion.q[-1, :3] + (motion.q[1, :3] - motion.q[0, :3]) - motion.q[0, :3]
    params = hexaleg.GaitParams()
    assert abs(step[0]) < 1e-9 and np.isclose(step[1], params.stride_length, rtol=1e-6)
    coxa = motion.q[:, 7 + np.array([spider.column(j) for j in spider.joints("coxa")])]
    assert np.ptp(coxa, axis=0).min() > 0.05  # the coxas swing the legs along +y


def test_report_view_sweep_and_optimiser(tmp_path, capsys):
    config = tmp_path / "report.toml"
    config.write_text("[gait]\nsamples = 40\n[report]\nstiffness_points = 3\npaper_samples = 8\n")
    assert main(["report", "--robot", SPIDER, "--config", str(config),
                 "--out", str(tmp_path / "report")]) == 0
    data = json.loads((tmp_path / "report" / "report.json").read_text())
    assert data["robot"]["name"] == "spider" and data["robot"]["legs"][0] == "LF"
    assert data["motor"]["name"] == "generic (spider URDF limits)"
    assert any("names no catalogue motor" in n for n in data["notes"])
    # an own robot gets the quick answer too (it was "no quick answer: unknown robot")
    assert data["design"]["origin"] == "quick" and data["design"]["family"] == "linear"
    assert not any("no quick answer" in n for n in data["notes"])
    assert main(["view", "--robot", SPIDER, "--config", str(config), "--html",
                 str(tmp_path / "view.html")]) == 0
    assert (tmp_path / "view.html").stat().st_size > 10_000
    assert main(["sweep", "--robot", SPIDER, "--joints", "femur", "--family", "linear",
                 "--samples", "40", "--executor", "serial", "--out", str(tmp_path / "sw")]) == 0
    table = pd.read_parquet(next((tmp_path / "sw").glob("part-*.parquet")))
    assert len(table) == 1 and table.loc[0, "status"] == "ok"
    capsys.readouterr()
    ev = evaluator(hexaleg.Scenario.load(SPIDER).with_gait({"samples": 40}))
    best = optimise(ev, "femur", ev.robot.joints("femur"), "joule", grid=(4, 2))
    assert best.value <= best.grid_value and best.joints == ev.robot.joints("femur")
