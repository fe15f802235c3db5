"""Tests of the files of ``hexaleg design``: design.html, the files listed, the command line and
its errors."""

from __future__ import annotations

import json

from hexaleg.cli import main


def test_design_html_leads_with_the_answer(written):
    out = written[1]
    data = json.loads((out / "design.json").read_text())
    assert sorted(data["files"]) == sorted(p.name for p in out.iterdir())
    html = (out / "design.html").read_text()
    assert html.index("Fit these springs") < html.index("The springs to buy")
    for plot in ("pareto", "map_period_stride", "map_payload_mu", "robust"):
        assert f'id="plot-{plot}"' in html


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


def test_limits_without_any_saving_say_what_to_change(tmp_path, capsys):
    config = tmp_path / "d.toml"
    config.write_text('[design]\nsamples = 100\nfamilies = ["linear"]\nmax_torque = 1e-7\n'
                      'pareto_fractions = []\n')
    assert main(["design", "--config", str(config), "--out", str(tmp_path / "o")]) == 2
    assert "raise max_torque or max_deflection" in capsys.readouterr().err


def test_an_outer_diameter_no_wire_fits_is_named(tmp_path, capsys):
    config = tmp_path / "d.toml"
    config.write_text('[design]\nsamples = 100\nfamilies = ["linear"]\n'
                      'pareto_fractions = []\n[design.max_outer_diameter]\nfemur = 0.0003\n')
    assert main(["design", "--config", str(config), "--out", str(tmp_path / "o")]) == 2
    assert "thinnest preferred wire" in capsys.readouterr().err


def test_an_unreachable_map_range_is_named(tmp_path, capsys):
    config = tmp_path / "d.toml"
    config.write_text('[design]\nsamples = 100\nfamilies = ["linear"]\npareto_fractions = []\n'
                      'map_stride = [1.0, 8.0]\n')
    assert main(["design", "--config", str(config), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "stride factor" in err and "narrow the stride range" in err
