"""Tests of hexaleg.commands.motors: the catalogue with its derived constants (the fit of a
log's actuators, ``--identify``, is tested with its library in
tests/dynamics/test_identification.py)."""

from __future__ import annotations

from hexaleg.cli import main


def test_motors_lists_the_catalogue_with_derived_constants(capsys):
    assert main(["motors"]) == 0
    out = capsys.readouterr().out
    ax18 = next(line for line in out.splitlines() if line.startswith("AX-18A"))
    # k_t·G = 1.8 N·m / 2.2 A and c = R/(k_t G)² = (12/2.2)/(1.8/2.2)² W/(N·m)² (datasheet).
    assert "0.818" in ax18 and "8.148" in ax18
