"""Tests of hexaleg.cli: subcommands are thin and errors are one clear line."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from hexaleg.cli import main


def test_help_lists_subcommands(capsys):
    assert main([]) == 0
    out = capsys.readouterr().out
    for name in ("robot", "motors", "gait", "paper", "report", "view", "sweep"):
        assert f"    {name} " in out, name
    # where to start, how long it takes, and where each command's own help is (#43)
    assert "start with:\n  hexaleg report      which springs to fit" in out
    assert "(about 5 s)" in out and "hexaleg COMMAND --help" in out


def test_robot_bad_file_is_one_line_error(capsys, tmp_path):
    assert main(["robot", "--urdf", str(tmp_path / "x.urdf")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("hexaleg robot: error: URDF file not found")
    assert "Traceback" not in err


def test_console_script_runs():
    out = subprocess.run([sys.executable, "-m", "hexaleg.cli", "--version"], capture_output=True,
                         text=True, check=True).stdout
    assert out.startswith("hexaleg ")


def test_an_ascii_console_gets_ascii_spellings_not_a_crash():
    """`PYTHONIOENCODING=ascii hexaleg motors` had ended in UnicodeEncodeError on "·" (#58)."""
    env = {**os.environ, "PYTHONIOENCODING": "ascii"}
    proc = subprocess.run([sys.executable, "-m", "hexaleg.cli", "motors"], capture_output=True,
                          env=env, timeout=120)
    assert proc.returncode == 0 and proc.stderr == b""
    assert proc.stdout.isascii() and b"k_t*G" in proc.stdout


def test_closed_pipe_is_quiet_and_reports_sigpipe():
    """`hexaleg robot | head -n 2`: the reader leaves early; no traceback, status 128+SIGPIPE."""
    read_end, write_end = os.pipe()
    os.close(read_end)  # the reader is gone before the first byte is written: deterministic
    try:
        proc = subprocess.run([sys.executable, "-m", "hexaleg.cli", "robot"], stdout=write_end,
                              stderr=subprocess.PIPE, text=True, timeout=120)
    finally:
        os.close(write_end)
    assert proc.stderr == ""
    assert proc.returncode == 141


def test_hexaleg_warnings_print_as_one_line(tmp_path, capsys):
    """A warning (here: the stale lock of a killed sweep, taken over) is one line on stderr."""
    import json

    args = ["sweep", "--joints", "coxa", "--k", "0,0.1", "--theta-k", "0.01", "--samples", "40",
            "--executor", "serial", "--out", str(tmp_path / "out")]
    assert main(args) == 0
    (tmp_path / "out" / ".lock").write_text(json.dumps({"pid": 999999, "host": "gone",
                                                        "started": "yesterday"}))
    capsys.readouterr()
    assert main(args) == 0
    err = capsys.readouterr().err
    assert "hexaleg sweep: warning: took over the lock of a sweep that ended without releasing " \
           "it (pid 999999 on host gone, started yesterday)" in err
    assert "HexalegWarning" not in err and "warnings.warn" not in err


def test_a_name_in_the_wrong_case_gets_a_hint(capsys):
    assert main(["robot", "--robot", "Solo12"]) == 2
    assert "unknown robot 'Solo12' (did you mean 'solo12'?)" in capsys.readouterr().err


@pytest.mark.parametrize("command", ["report", "design", "paper", "sweep", "codesign"])
def test_long_commands_take_quiet(command, capsys):
    """Every command whose work takes seconds or more prints status lines on stderr and takes
    ``--quiet`` to leave them out (issue #57)."""
    with pytest.raises(SystemExit) as e:
        main([command, "--help"])
    assert e.value.code == 0
    assert "--quiet" in capsys.readouterr().out


def test_quiet_leaves_out_the_status_lines_not_the_answer(capsys, tmp_path):
    args = ["paper", "--no-simulation", "--samples", "256"]
    assert main([*args, "--out", str(tmp_path / "a")]) == 0
    loud = capsys.readouterr()
    assert "hexaleg paper: " in loud.err
    assert main([*args, "--quiet", "--out", str(tmp_path / "b")]) == 0
    quiet = capsys.readouterr()
    assert quiet.err == "" and quiet.out.splitlines()[0] == loud.out.splitlines()[0]


@pytest.mark.parametrize("mine", [None, "egl"])
def test_a_command_loads_mujoco_without_a_renderer_unless_asked(monkeypatch, mine):
    """No command renders with MuJoCo: a command's process imports it with MUJOCO_GL=disable
    (no GLFW, no subprocess for its version), but a user's own MUJOCO_GL is kept."""
    if mine is None:
        monkeypatch.delenv("MUJOCO_GL", raising=False)
    else:
        monkeypatch.setenv("MUJOCO_GL", mine)
    assert main([]) == 0
    assert os.environ["MUJOCO_GL"] == (mine or "disable")
