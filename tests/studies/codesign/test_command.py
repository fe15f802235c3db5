"""``hexaleg codesign`` on the command line: registered, configured, bad input one line."""

from __future__ import annotations

import json

import pytest

from hexaleg.cli import build_parser, main
from hexaleg.errors import UnknownNameError
from hexaleg.studies.codesign.command import settings

SMALL = """[codesign]
samples = 40
final_samples = 40
max_evaluations = 10
restarts = 1
curve = false
simulate = false
[codesign.constraints]
min_body_clearance = 0.01
"""


def test_registered_with_its_options():
    args = build_parser().parse_args(["codesign", "--speed", "0.05", "--pattern", "wave"])
    assert args.speed == 0.05 and args.pattern == "wave" and not args.rules


def test_config_table_is_checked(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[codesign]\nspeeed = 0.1\n")
    with pytest.raises(UnknownNameError, match="speeed"):
        settings(bad)
    good = tmp_path / "good.toml"
    good.write_text(SMALL)
    assert settings(good)["constraints"].min_body_clearance == 0.01
    assert settings(None) == {}


def test_runs_and_writes(tmp_path, capsys):
    config = tmp_path / "c.toml"
    config.write_text(SMALL)
    out = tmp_path / "out"
    assert main(["codesign", "--config", str(config), "--speed", "0.06", "--out", str(out)]) == 0
    data = json.loads((out / "codesign.json").read_text())
    assert data["speed"] == {"value": 0.06, "unit": "m/s"}
    assert data["search"]["codesign"]["evaluations"] <= 10
    assert "J/m" in capsys.readouterr().out


def test_bad_speed_is_one_line(capsys):
    assert main(["codesign", "--speed", "-1"]) == 2
    assert "speed" in capsys.readouterr().err
