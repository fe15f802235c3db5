"""Tests of hexaleg.commands.options: one loader of a run for every command — the same bad
``[gait]``, ``[design]`` or ``[codesign]`` value is the same named error in each of them, before
anything is computed or written."""

from __future__ import annotations

import argparse

import pytest

from hexaleg.cli import main
from hexaleg.commands.options import check_tables, load_run, print_findings, print_warnings
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError

COMMANDS = {
    "gait": [],
    "report": ["--out", "{out}"],
    "design": ["--out", "{out}"],
    "simulate": ["--out", "{out}"],
    "codesign": ["--out", "{out}"],
    "view": ["--html", "{out}/view.html"],
}
"""Every command that reads a config file, with where it would write."""

BAD = {
    "gait": ('[gait]\nperiod = "slow"\n', r"\[gait\]\.period = 'slow'"),
    "design": ('[design]\nfamilies = ["spiral"]\n', "spiral"),
    "codesign": ('[codesign]\nsimulate = "false"\n', r"\[codesign\]\.simulate = 'false'"),
    "simulate": ("[simulate]\nground = 1\n", "ground"),
    "table": ("[desing]\nsamples = 100\n", "desing"),
}
"""A bad value of each kind of table, and what its error names."""


@pytest.mark.parametrize("bad", list(BAD))
def test_every_command_names_the_same_bad_value_the_same_way(bad, tmp_path, capsys):
    text, named = BAD[bad]
    config = tmp_path / "bad.toml"
    config.write_text(text)
    lines = {}
    for command, extra in COMMANDS.items():
        out = tmp_path / command
        argv = [command, "--config", str(config), *(a.format(out=out) for a in extra)]
        assert main(argv) == 2, command
        err = capsys.readouterr().err
        assert err.startswith(f"hexaleg {command}: error: "), err
        lines[command] = err.removeprefix(f"hexaleg {command}: error: ")
        assert not out.exists(), f"{command} wrote {out} before refusing its config"
    assert len(set(lines.values())) == 1, lines
    import re

    assert re.search(named, lines["gait"]), lines["gait"]


def test_the_tables_are_checked_by_their_owners():
    from hexaleg.scenario.scenario import Scenario

    # the run's own [gait], [contact] and [motor]: once, by the run (issue #53), as load_run does
    check_tables({"gait": {"period": "slow"}}, "c.toml")
    with pytest.raises(ConfigError, match=r"c\.toml \[gait\]\.period"):
        Scenario.from_tables("hexaleg", {"gait": {"period": "slow"}}, "c.toml")
    with pytest.raises(UnknownNameError, match="families"):
        check_tables({"design": {"famlies": ["linear"]}}, "c.toml")
    with pytest.raises(UnknownNameError, match="arrow_length"):
        check_tables({"view": {"arrow": 0.1}}, "c.toml")
    with pytest.raises(InvalidParameterError, match=r"\[design\] samples.*--motion walk\.csv"):
        check_tables({"design": {"samples": 100}}, "c.toml", log="walk.csv")
    with pytest.raises(InvalidParameterError, match=r"\[gait\].*--motion walk\.csv"):
        check_tables({"gait": {"period": 1.0}}, "c.toml", log="walk.csv")
    check_tables({"gait": {"period": 1.0}, "design": {"samples": 100},
                  "codesign": {"speed": 0.05}, "view": {"fps": 10}}, "c.toml")


def test_a_run_is_kept_on_the_commands_options(tmp_path):
    config = tmp_path / "c.toml"
    config.write_text("[gait]\nperiod = 0.8\n[design]\nsamples = 100\n")
    args = argparse.Namespace()
    run = load_run(None, config, args=args)
    assert args.scenario is run and run.robot == "hexaleg" and run.gait.period == 0.8
    assert run.table("design") == {"samples": 100} and run.where == str(config)


def test_warnings_and_findings_are_one_warning_line_each(capsys):
    """Every command prints a run's warnings and the sanity checks' findings alike."""
    from types import SimpleNamespace

    print_warnings(["first", "second"])
    print_findings([SimpleNamespace(message="third")])
    assert capsys.readouterr().out == "warning: first\nwarning: second\nwarning: third\n"
