"""Tests of the files of ``hexaleg design``: design.html, the files listed, the command line and
its errors."""

from __future__ import annotations

import json

import pytest

from hexaleg.cli import main


def test_design_html_leads_with_the_answer(written):
    out = written[1]
    data = json.loads((out / "design.json").read_text())
    assert sorted(data["files"]) == sorted(p.name for p in out.iterdir())
    html = (out / "design.html").read_text()
    assert html.index("Fit these springs") < html.index("The springs to buy")
    for plot in ("pareto", "map_period_stride", "map_payload_mu", "robust"):
        assert f'id="plot-{plot}"' in html
    assert html.index("The springs to buy") < html.index('<section id="simulated">')
    for row in data["simulation"]:
        assert f'<td class="name">{row["label"]}</td>' in html
        assert row["simulated_saving"]["unit"] == row["predicted_saving"]["unit"] == "%"


def test_command_line_writes_the_design(tmp_path, capsys):
    config = tmp_path / "d.toml"
    config.write_text('[design]\nsamples = 100\nfamilies = ["linear"]\nmap_period = [1.0]\n'
                      'map_stride = [1.0]\nmap_payload = [0.0]\nmap_mu = [0.6]\n'
                      'robust_period = [1.0, 1.0]\nrobust_stride = [1.0, 1.0]\n'
                      'robust_payload = [0.0, 0.0]\nrobust_mu = [0.6, 0.6]\n'
                      'pareto_fractions = [0.5]\n[report]\ntitle = "shared"\n')
    assert main(["design", "--config", str(config), "--out", str(tmp_path / "o")]) == 0
    out = capsys.readouterr().out
    assert "fit linear" in out and (tmp_path / "o" / "design.html").exists()


BASE = '[design]\nsamples = 100\nfamilies = ["linear"]\npareto_fractions = []\n'


@pytest.mark.parametrize(("extra", "says"), [
    ("[design.max_outer_diameter]\nfemur = 0.0003\n", ["thinnest preferred wire"]),
    ("map_stride = [1.0, 8.0]\n", ["stride factor", "narrow the stride range"]),  # unreachable
])
def test_bad_design_inputs_say_what_to_change(tmp_path, capsys, extra, says):
    """Inputs no design can meet end in a named error that says what to change."""
    config = tmp_path / "d.toml"
    config.write_text(BASE + extra)
    assert main(["design", "--config", str(config), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    for text in says:
        assert text in err


def test_limits_under_which_no_spring_pays_give_that_answer(tmp_path, capsys):
    """A spring torque bound of 0.1 µN·m leaves nothing to save: the design is written and says
    "no springs pay" — an answer, not an error, and never a recommendation that costs energy."""
    config = tmp_path / "d.toml"
    config.write_text(BASE + "max_torque = 1e-7\n")
    assert main(["design", "--config", str(config), "--out", str(tmp_path / "o")]) == 0
    out = capsys.readouterr().out
    assert "no springs pay here" in out
    data = json.loads((tmp_path / "o" / "design.json").read_text())
    assert data["pays"] is False
    assert any(n.startswith("no springs pay") for n in data["notes"])
