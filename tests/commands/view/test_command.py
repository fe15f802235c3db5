"""Tests of hexaleg.commands.view.command: ``hexaleg view`` on the command line — the page
written with the config's settings, a log's cycle drawn, errors in one line — and a parser that
offers the study's names without importing it."""

from __future__ import annotations

import argparse
import subprocess
import sys

import pytest
from meshcat_scene import clips, page_commands

from hexaleg import GaitParams
from hexaleg.cli import build_parser, main


def test_view_choices_are_the_study_names():
    """``view --motion/--joints/--run`` offer the study's names (``--motion`` also a log
    file), spelled out in the parser so that building it imports neither the study nor
    meshcat."""
    from hexaleg.commands.view.study import MOTIONS
    from hexaleg.outputs.viewer.show import JOINT_QUANTITIES
    from hexaleg.simulation.motion_file import RUNS

    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    choices = {a.dest: a.choices for a in sub.choices["view"]._actions}
    named = sub.choices["view"].get_default("func").args[2]  # --motion: these or a log FILE
    assert tuple(named) == MOTIONS
    assert tuple(choices["joints"]) == tuple(JOINT_QUANTITIES)
    assert tuple(choices["run"]) == RUNS
    code = "import sys, hexaleg.cli as c; c.build_parser(); print('meshcat' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "False"


def test_cli_writes_page_with_config(tmp_path, capsys):
    config = tmp_path / "view.toml"
    config.write_text("[gait]\nperiod = 0.5\nsamples = 200\n\n[view]\nfps = 12\n")
    out = tmp_path / "gait.html"
    assert main(["view", "--config", str(config), "--html", str(out)]) == 0
    assert capsys.readouterr().out.strip() == f"wrote {out}"
    page = out.read_text()
    assert "motor power (W)" in page
    frames = clips(page_commands(page))["/meshcat/pinocchio/visuals/body_0"]["position"]["frames"]
    assert frames[-1] == pytest.approx(12 * 0.5)  # one 0.5 s cycle at 12 keyframes/s


def test_cli_errors_are_one_line(tmp_path, capsys):
    config = tmp_path / "bad.toml"
    config.write_text("[view]\nframes_per_second = 12\n")
    assert main(["view", "--config", str(config), "--html", str(tmp_path / "x.html")]) == 2
    err = capsys.readouterr().err
    assert "frames_per_second" in err and "fps" in err and "Traceback" not in err
    assert main(["view", "--motion", "transform", "--html",
                 str(tmp_path / "no" / "x.html")]) == 2
    assert str(tmp_path / "no" / "x.html") in capsys.readouterr().err


def test_cli_views_a_log(tmp_path, capsys):
    """--motion FILE: the logged cycle is drawn (its period, its quality printed); a [gait]
    table, a --motion that is neither a choice nor a file and --cycle without a log are
    refused by name."""
    import hexaleg
    from hexaleg.motion.recorded.write import write_motion_log

    robot = hexaleg.load()
    gait = hexaleg.gait(robot, GaitParams(period=0.8, samples=80))
    log = write_motion_log(robot, gait, tmp_path / "walk.csv")
    config = tmp_path / "view.toml"
    config.write_text("[view]\nfps = 10\n")
    out = tmp_path / "log.html"
    assert main(["view", "--config", str(config), "--motion", str(log), "--cycle", "whole",
                 "--html", str(out)]) == 0
    printed = capsys.readouterr().out
    assert f"wrote {out}" in printed and "motion: cycle whole: 0.8000 s" in printed
    frames = clips(page_commands(out.read_text()))["/meshcat/pinocchio/visuals/body_0"][
        "position"]["frames"]
    assert frames[-1] == pytest.approx(10 * 0.8)  # the logged 0.8 s cycle, not the 1 s gait
    config.write_text("[gait]\nperiod = 0.5\n")
    assert main(["view", "--config", str(config), "--motion", str(log), "--html",
                 str(out)]) == 2
    err = capsys.readouterr().err
    assert "[gait]" in err and "period" in err and "--motion" in err
    assert main(["view", "--motion", "gati", "--html", str(out)]) == 2
    assert ("one of gait, transform, or a log of the robot's own gait (a CSV or NPZ file, or "
            "a ROS 2 bag directory; docs/motion.md): gati does not exist (did you mean 'gait'?)"
            in capsys.readouterr().err)
    assert main(["view", "--motion", "transform", "--cycle", "whole", "--html", str(out)]) == 2
    assert "--cycle only with --motion FILE" in capsys.readouterr().err
