"""Tests of hexaleg.commands.design.command: ``hexaleg design`` on the command line writes the
design and prints its answer line. Inputs no design can meet and the failed stage's status and
line: tests/commands/design/test_write.py."""

from __future__ import annotations

from hexaleg.cli import main


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
