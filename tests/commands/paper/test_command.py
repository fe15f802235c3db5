"""Tests of hexaleg.commands.paper.command: ``hexaleg paper`` says what it computes on stderr and
writes to ``hexaleg-paper/`` by default, like every other command's ``hexaleg-<command>/``."""

from __future__ import annotations

import argparse

from hexaleg.cli import build_parser, main
from hexaleg.commands.paper.command import DEFAULT_OUT, run_paper


def _defaults() -> dict[str, str]:
    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    return {name: p.get_default("out") for name, p in sub.choices.items()
            if p.get_default("out") is not None}


def test_the_default_folder_is_named_like_the_other_commands():
    outs = _defaults()
    assert outs["paper"] == DEFAULT_OUT == "hexaleg-paper"
    assert all(outs[name] == f"hexaleg-{name}" for name in ("report", "design")), outs


def test_progress_on_stderr_and_the_answer_on_stdout(tmp_path, capsys):
    assert run_paper(tmp_path / "p", n=64, simulation=False) == 0
    captured = capsys.readouterr()
    lines = captured.err.splitlines()
    assert len(lines) == 2 and all(line.startswith("hexaleg paper: ") for line in lines)
    assert "64 samples" in lines[0] and "MuJoCo" not in lines[0]
    assert lines[1].startswith("hexaleg paper: done in ") and lines[1].endswith(" s")
    assert "hexaleg paper:" not in captured.out
    assert f"wrote {tmp_path / 'p'}/paper.json" in captured.out
    assert (tmp_path / "p" / "paper.json").is_file()


def test_quiet_without_progress_and_the_cli_reports_progress(tmp_path, capsys):
    assert run_paper(tmp_path / "q", n=64, simulation=False, progress=None) == 0
    assert capsys.readouterr().err == ""
    assert main(["paper", "--out", str(tmp_path / "c"), "--samples", "64",
                 "--no-simulation"]) == 0
    assert capsys.readouterr().err.startswith("hexaleg paper: the paper's joint at 64 samples")


def test_the_forward_run_is_announced_with_its_grid(tmp_path, monkeypatch, capsys):
    """The line before the work names the forward run and its grid (write_paper stubbed: the
    forward run itself is test_write's)."""
    from hexaleg.commands.paper import write
    from hexaleg.paper import summary

    monkeypatch.setattr(write, "write_paper", lambda out, **kw: kw)
    monkeypatch.setattr(summary, "one_line", lambda r: f"ran {r}")
    assert run_paper(tmp_path, n=64, grid=[100, 200, 300]) == 0
    captured = capsys.readouterr()
    assert "its Adams experiment forward in MuJoCo at 3 stiffnesses" in captured.err
    assert "'simulation': True" in captured.out and "'grid': [100, 200, 300]" in captured.out
