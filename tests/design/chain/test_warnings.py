"""``hexaleg design`` says its run's warnings (hexaleg.scenario.run_warnings): design.json's
``warnings``, the page, the printed lines — the same lines as the other commands."""

from __future__ import annotations

import types
from collections import defaultdict
from pathlib import Path

import hexaleg
from hexaleg.commands.design.write import design_warnings
from hexaleg.design.chain.chain import DesignChain
from hexaleg.motion.scaling import robot_gait
from hexaleg.outputs.html import render_design_html
from hexaleg.robot.registry import description
from hexaleg.scenario.run_warnings import run_warnings
from hexaleg.scenario.scenario import Scenario

SPIDER = str(Path(__file__).resolve().parents[2] / "data" / "spider.toml")


def test_the_design_run_has_the_warnings_of_its_gait(tmp_path):
    config = tmp_path / "fast.toml"
    config.write_text("[gait]\nperiod = 0.25\nsamples = 40\n")
    run = DesignChain(Scenario.load(SPIDER, str(config))).scenario
    desc = description(SPIDER)
    robot = desc.load()
    gait = run.gait  # the [gait] table over the sized defaults, the design's samples
    assert gait.period == 0.25
    assert gait.stride == robot_gait(desc).stride
    expected = run_warnings(robot, hexaleg.gait(robot, gait), desc.actuator(robot),
                            desc=desc, gait=gait)
    assert any(w.startswith("joint_speed") for w in expected)
    result = types.SimpleNamespace(run=run, gait=run.gait, motion=None)  # read
    assert design_warnings(result) == expected  # type: ignore[arg-type]


def test_design_json_and_page_carry_them(design_written):
    result, _ = design_written
    assert result.data["warnings"] == []  # hexaleg with its AX-18A: none
    assert result.data["gait_defaults"] is None  # the reference robot is not sized
    html = render_design_html({**result.data, "warnings": ["w1", "w2"]}, defaultdict(str))
    assert html.count("<b>Warning:</b>") == 2 and "w2" in html
