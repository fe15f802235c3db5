"""A sweep on a log (``hexaleg sweep --motion FILE``): a hexaleg gait written as a log sweeps as
the generated gait does; its rows' gait columns are what the cycle measures; gait parameters
with --motion are refused by name."""

from __future__ import annotations

import json
import math

import pytest

import hexaleg
from hexaleg.cli import main
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.recorded.write import write_motion_log
from hexaleg.sweep.logged import on_log
from hexaleg.sweep.runner import run_sweep
from hexaleg.sweep.spec import SweepSpec
from hexaleg.sweep.store import MANIFEST

SPRINGS = {"coxa": {"k": (0.0, 0.1, 0.2), "theta_k": (0.01,)}}


@pytest.fixture(scope="module")
def log(tmp_path_factory):
    """The default gait at 50 samples per cycle, written as a CSV log (one cycle)."""
    robot = hexaleg.load()
    gait = hexaleg.gait(robot, hexaleg.GaitParams(samples=50))
    return write_motion_log(robot, gait, tmp_path_factory.mktemp("log") / "walk.csv")


def test_the_logged_gait_sweeps_as_the_generated_one(log, tmp_path):
    generated = run_sweep(SweepSpec(gait={"samples": 50}, springs=SPRINGS), tmp_path / "g",
                          executor="serial").table.sort_values("point")
    logged = run_sweep(on_log(SweepSpec(springs=SPRINGS), log, "whole"), tmp_path / "l",
                       executor="serial").table.sort_values("point")
    for m in ("electrical", "joule"):
        assert logged[m].to_numpy() == pytest.approx(generated[m].to_numpy(), rel=1e-9)
    row = logged.iloc[0]
    assert row["gait.period"] == pytest.approx(1.0) and row["gait.samples"] == 50
    assert row["gait.stride_length"] == pytest.approx(0.06, rel=1e-9)
    assert row["gait.duty_factor"] == pytest.approx(0.5) and math.isnan(row["gait.step_height"])
    manifest = json.loads((tmp_path / "l" / MANIFEST).read_text())
    assert manifest["spec"]["motion"] == {"path": str(log), "cycle": "whole"}
    assert manifest["motion_quality"]["cycle"] == "whole"


def test_cli_sweeps_a_log_and_refuses_gait_parameters(log, tmp_path, capsys):
    args = ["sweep", "--joints", "coxa", "--k", "0,0.1", "--theta-k", "0.01", "--executor",
            "serial", "--motion", str(log), "--cycle", "whole"]
    assert main([*args, "--out", str(tmp_path / "s")]) == 0
    printed = capsys.readouterr().out
    assert "2 points computed" in printed and "motion: log" in printed
    assert main([*args, "--samples", "40", "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err
    assert "samples" in err and "--motion" in err
    spec = tmp_path / "spec.toml"
    spec.write_text("[gait]\nperiod = [0.8, 1.0]\n\n[springs.coxa]\nk = 0.1\ntheta_k = 0.01\n")
    assert main(["sweep", str(spec), "--motion", str(log), "--out", str(tmp_path / "u")]) == 2
    assert "period" in capsys.readouterr().err
    with pytest.raises(InvalidParameterError, match="no gait parameters with --motion"):
        on_log(SweepSpec(gait={"period": 0.8}, springs=SPRINGS), log)
