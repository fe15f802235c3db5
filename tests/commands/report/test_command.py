"""Tests of hexaleg.commands.report.command: ``hexaleg report`` on the command line writes the
report and ends with its answer; an unwritable output directory is one named error."""

from __future__ import annotations

import json
import re

import pytest

from hexaleg.cli import main
from hexaleg.commands.report.write import PLOTS, write_report
from hexaleg.errors import OutputError
from hexaleg.robot.catalogue import DEFAULT_MOTOR


def test_default_cli_run_writes_the_report(tmp_path, capsys):
    out = tmp_path / "default"
    assert main(["report", "--out", str(out)]) == 0
    printed = capsys.readouterr()
    assert "saving" in printed.out and "stiffness curve 41/41" in printed.err
    d = json.loads((out / "report.json").read_text())
    saving = d["design"]["saving"]  # the answer the report leads with (#29): a saving > 0
    assert saving["unit"] == "%" and saving["value"] > 0 and d["design"]["origin"] == "quick"
    last = printed.out.strip().splitlines()[-1]  # the command's last word is the answer
    assert last.startswith(f"quick answer: optimal linear springs on femur, tibia save "
                           f"{saving['value']:+.2f} %")
    assert d["springs"]["design"] == "answer" and d["reference"]["design"] == "paper"
    assert d["gait"]["samples"] == 1000
    assert d["motor"]["name"] == DEFAULT_MOTOR
    assert len(d["stiffness_curve"]["stiffness"]["value"]) == 41
    assert {f"{n}.png" for n in PLOTS} <= {p.name for p in out.iterdir()}
    assert (out / "report.html").stat().st_size > 100_000


def test_unwritable_output_directory_is_an_output_error(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    with pytest.raises(OutputError, match=re.escape(str(blocker / "out"))):
        write_report(blocker / "out", progress=None)
    assert main(["report", "--out", str(blocker / "out")]) == 2
    assert str(blocker / "out") in capsys.readouterr().err
