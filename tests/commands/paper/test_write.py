"""Tests of hexaleg.commands.paper.write: the files of ``hexaleg paper``."""

from __future__ import annotations

import json

import numpy as np
import pytest
from conftest import FORWARD_GRID, FORWARD_SAMPLES

from hexaleg.cli import main
from hexaleg.commands.paper.write import write_paper
from hexaleg.errors import InvalidParameterError, OutputError
from hexaleg.paper.figures import forward_figures
from hexaleg.paper.forward import K_GRID, adams_model, max_stiffness
from hexaleg.paper.joint import PaperJoint
from hexaleg.paper.reproduce import simulation_section

J0 = PaperJoint()


def test_report_files_and_cli(tmp_path, capsys, forward):
    grid = [f"{k:g}" for k in FORWARD_GRID]
    assert main(["paper", "--out", str(tmp_path), "--samples", str(FORWARD_SAMPLES),
                 "--grid", *grid]) == 0
    out = capsys.readouterr().out
    assert "713.544" in out
    assert f"forward (MuJoCo) mean-torque optimum: {forward.optima['mean_abs'].simulated:.0f}" \
        in out
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
    assert sorted(p.name for p in tmp_path.glob("sim_*.png")) == sorted(forward_figures(forward,
                                                                                        64))
    summary = (tmp_path / "summary.md").read_text()
    assert "713.5" in summary and "## The Adams experiment forward (MuJoCo)" in summary
    assert saved["simulation"] == json.loads(json.dumps(simulation_section(forward)))


def test_no_simulation_leaves_the_forward_run_out(tmp_path):
    r = write_paper(tmp_path, n=64, simulation=False)
    assert "simulation" not in r and "simulation" not in json.loads(
        (tmp_path / "paper.json").read_text())
    assert not list(tmp_path.glob("sim_*.png")) and len(list(tmp_path.glob("fig*.png"))) == 9


def test_the_cli_grid_default_is_the_librarys(capsys):
    """The parser states K_GRID without importing the study (it takes seconds to import)."""
    with pytest.raises(SystemExit):
        main(["paper", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    first, step = K_GRID[0], K_GRID[1] - K_GRID[0]
    assert set(np.diff(K_GRID)) == {step}
    assert f"default: {first:g} to {K_GRID[-1]:g} in steps of {step:g}" in text


def test_a_bad_grid_is_refused_before_anything_is_written(tmp_path, capsys):
    out = tmp_path / "paper-out"
    assert main(["paper", "--grid", "0", "100", "200", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "stiffness grid value = 0.0" in err and "> 0" in err
    assert not out.exists()
    with pytest.raises(InvalidParameterError, match="increasing"):
        write_paper(out, grid=[300.0, 200.0, 100.0])
    assert not out.exists()


def test_unwritable_directory_is_an_output_error(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(OutputError, match="cannot write the paper report to"):
        write_paper(blocker / "out")


def test_a_grid_without_the_forward_run_is_refused(tmp_path, capsys):
    """The grid is the forward run's: with --no-simulation it would be silently ignored."""
    out = tmp_path / "p"
    assert main(["paper", "--no-simulation", "--grid", "100", "200", "300",
                 "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "stiffness grid = [100.0, 200.0, 300.0]" in err and "--no-simulation" in err
    assert not out.exists()


def test_a_grid_value_too_stiff_to_integrate_is_refused_before_anything_is_written(tmp_path,
                                                                                  capsys):
    """--grid … 1e100 used to end in a TypeError after the figures and paper.json were
    written (the forward run diverged, its saving came out None)."""
    out = tmp_path / "paper-out"
    assert main(["paper", "--grid", "100", "200", "1e100", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    limit = max_stiffness(adams_model(PaperJoint()))
    assert "stiffness grid value = 1e+100" in err and f"<= {limit:.3g}" in err
    assert not out.exists()
    assert 4e7 < limit < 5e7  # h·ω ≤ 1 for Table 2's arms at the 0.2 ms step
