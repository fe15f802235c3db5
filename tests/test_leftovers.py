"""The tests leave nothing in the checkout: they run in a temporary working directory
(tests/conftest.py), where MuJoCo writes its log on a simulation warning."""

from __future__ import annotations

from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]


def test_tests_run_outside_the_checkout():
    cwd = Path.cwd().resolve()
    assert cwd != ROOT and ROOT not in cwd.parents


def test_a_mujoco_warning_logs_into_the_working_directory_not_the_checkout():
    import mujoco

    log = ROOT / "MUJOCO_LOG.TXT"
    before = log.stat().st_mtime_ns if log.exists() else None
    model = mujoco.MjModel.from_xml_string(
        '<mujoco><worldbody><body><freejoint/><geom size=".1"/></body></worldbody></mujoco>')
    data = mujoco.MjData(model)
    data.qpos[0] = np.nan  # "Nan, Inf or huge value in QPOS": MuJoCo warns and logs
    mujoco.mj_step(model, data)
    assert data.warning[mujoco.mjtWarning.mjWARN_BADQPOS].number == 1
    assert "QPOS" in (Path.cwd() / "MUJOCO_LOG.TXT").read_text()
    assert (log.stat().st_mtime_ns if log.exists() else None) == before


def test_every_command_s_default_output_is_ignored_by_git():
    """A command run in the checkout leaves its default output folder there: .gitignore covers
    each (#43: `git status` was dirty after the README's commands)."""
    from hexaleg.cli import build_parser

    ignored = (ROOT / ".gitignore").read_text().splitlines()
    parser = build_parser()
    commands = next(a for a in parser._actions if a.choices and isinstance(a.choices, dict))
    defaults = {name: next((a.default for a in sub._actions if a.dest == "out"), None)
                for name, sub in commands.choices.items()}
    outs = {d for d in defaults.values() if isinstance(d, str)}
    assert {"hexaleg-report", "hexaleg-design", "sweep-results"} <= outs
    for out in outs:
        assert f"/{out}/" in ignored or f"/{out}" in ignored, out
