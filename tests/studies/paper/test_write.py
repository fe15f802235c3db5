"""Tests of hexaleg.studies.paper.write: the files of ``hexaleg paper``."""

from __future__ import annotations

import json

import pytest

from hexaleg.cli import main
from hexaleg.errors import OutputError
from hexaleg.studies.paper.joint import PaperJoint
from hexaleg.studies.paper.write import write_paper

J0 = PaperJoint()


def test_report_files_and_cli(tmp_path, capsys):
    assert main(["paper", "--out", str(tmp_path), "--samples", "512"]) == 0
    assert "713.544" in capsys.readouterr().out
    saved = json.loads((tmp_path / "paper.json").read_text())
    assert saved["k_M_paper_units"] == pytest.approx(713.544, abs=1e-3)
    assert saved["k_M_SI_Nm_per_rad"] == pytest.approx(J0.k_M())
    for key in ("k_M_paper_units", "k_M_SI_Nm_per_rad", "optima", "k_E", "saving_52_81",
                "pinocchio_check"):
        assert key in saved
    assert set(saved["optima"]) == {"no_gravity", "gravity_hanging", "gravity_upright"}
    assert "not reproduced" in saved["k_E"]["verdict"]
    pngs = sorted(p.name for p in tmp_path.glob("fig*.png"))
    assert [p[:5] for p in pngs] == [f"fig{i:02d}" for i in range(5, 14)]
    assert "713.5" in (tmp_path / "summary.md").read_text()


def test_unwritable_directory_is_an_output_error(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(OutputError, match="cannot write the paper report to"):
        write_paper(blocker / "out")
