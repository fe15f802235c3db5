"""The example studies in analysis/ print what their kept logs say (as Crocoddyl checks its
examples' logs).

Each ``analysis/<study>_<robot>.py`` writes a deterministic, rounded text log to stdout; the
expected output is kept in ``analysis/logs/<study>_<robot>.log``. Text equality: the scripts
print a few significant digits, so a change in the code's numbers at that precision — or in the
script — shows up here as a diff.
"""

from __future__ import annotations

import difflib
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
ANALYSIS = ROOT / "analysis"
LOGS = ANALYSIS / "logs"
SCRIPTS = sorted(p for p in ANALYSIS.glob("*_*.py") if not p.name.startswith("bench_"))


def test_every_example_has_a_log_and_every_log_a_script():
    assert SCRIPTS, "no example scripts in analysis/"
    assert sorted(p.stem for p in LOGS.glob("*.log")) == [p.stem for p in SCRIPTS]


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.stem)
def test_example_prints_its_log(script: Path, tmp_path: Path):
    log = LOGS / f"{script.stem}.log"
    regenerate = f"python analysis/{script.name} > analysis/logs/{log.name}"
    # run outside the checkout: MuJoCo writes MUJOCO_LOG.TXT into the working directory
    run = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True,
                         text=True, timeout=300)
    assert run.returncode == 0, f"{script.name} failed:\n{run.stderr}"
    expected = log.read_text()
    if run.stdout != expected:
        diff = "".join(difflib.unified_diff(expected.splitlines(keepends=True),
                                            run.stdout.splitlines(keepends=True),
                                            f"analysis/logs/{log.name} (kept)",
                                            f"python analysis/{script.name} (now)"))
        pytest.fail(f"{script.name} no longer prints its kept log:\n{diff}\nIf the change is "
                    f"intended, regenerate the log:  {regenerate}", pytrace=False)
