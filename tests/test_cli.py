"""Tests of hexaleg.cli: subcommands are thin and errors are one clear line."""

from __future__ import annotations

import subprocess
import sys

from hexaleg.cli import main


def test_help_lists_subcommands(capsys):
    assert main([]) == 0
    out = capsys.readouterr().out
    assert "robot" in out


def test_robot_summary(capsys):
    assert main(["robot"]) == 0
    out = capsys.readouterr().out
    assert "nq = 25, nv = 24, actuated joints = 18" in out
    assert "LF_femur" in out


def test_robot_bad_file_is_one_line_error(capsys, tmp_path):
    assert main(["robot", "--urdf", str(tmp_path / "x.urdf")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("hexaleg robot: error: URDF file not found")
    assert "Traceback" not in err


def test_console_script_runs():
    out = subprocess.run([sys.executable, "-m", "hexaleg.cli", "--version"], capture_output=True,
                         text=True, check=True).stdout
    assert out.startswith("hexaleg ")
