"""Tests of hexaleg.commands.sweep.command: ``hexaleg sweep`` from the one-group flags prints
the summary and where the table is; flags that contradict each other are refused by name."""

from __future__ import annotations

import pandas as pd

from hexaleg.cli import main
from hexaleg.sweep import summary


def test_cli_sweep_prints_summary_and_path(tmp_path, capsys):
    out = tmp_path / "cli"
    code = main(["sweep", "--joints", "coxa", "--k", "0,0.1,0.2", "--theta-k", "0.01",
                 "--samples", "40", "--executor", "serial", "--out", str(out)])
    text = capsys.readouterr().out
    assert code == 0
    assert "3 points" in text and "coxa: electrical =" in text and str(out) in text
    table = pd.read_parquet(next(out.glob("part-*.parquet")))
    assert summary(table).splitlines()[1] in text
    assert main(["sweep", "--joints", "coxas", "--k", "0.1", "--theta-k", "0.01",
                 "--executor", "serial", "--out", str(tmp_path / "bad")]) == 2
    assert "coxa, femur, tibia" in capsys.readouterr().err
    assert main(["sweep", "--joints", "coxa", "--k", "0.1", "--theta-k", "0.01",
                 "--executor", "serial", "--out", str(tmp_path / "bad"),
                 "--metric", "nope"]) == 2
    assert "electrical" in capsys.readouterr().err


def test_a_spec_file_with_flags_or_a_robot_is_refused_by_name(tmp_path, capsys):
    spec = tmp_path / "spec.toml"
    spec.write_text("[springs.coxa]\nk = 0.1\ntheta_k = 0.01\n")
    assert main(["sweep", str(spec), "--joints", "coxa", "--out", str(tmp_path / "a")]) == 2
    assert "either a spec or the flags" in capsys.readouterr().err
    assert main(["sweep", str(spec), "--robot", "solo12", "--out", str(tmp_path / "b")]) == 2
    assert "[sweep] robot" in capsys.readouterr().err
    assert not (tmp_path / "a").exists() and not (tmp_path / "b").exists()


def test_a_sweep_where_every_point_fails_says_why_and_exits_2(tmp_path, capsys):
    """A neutral offset the joint cannot reach: the summary gives the error of the points (it
    printed an empty "best" line), and the command exits 2 (it exited 0)."""
    from hexaleg.cli import main

    argv = ["sweep", "--joints", "femur", "--k", "0.01", "--dead-zone", "0.4", "--offset", "1e9",
            "--executor", "serial", "--samples", "40", "--out", str(tmp_path / "s")]
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert "1 points, none evaluated without error (1 × TorqueLimitError); the first: " in out
    assert "none evaluated" in err
