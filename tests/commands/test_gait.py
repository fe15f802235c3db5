"""Tests of hexaleg.commands.gait: ``hexaleg gait`` prints the gait's groups, margin and joint
ranges; an unknown robot is named with the registry."""

from __future__ import annotations

from hexaleg.cli import main


def test_gait_summary_reports_margin_and_joint_ranges(capsys):
    assert main(["gait"]) == 0
    out = capsys.readouterr().out
    assert "groups: LF RM LH | RF LM RH" in out
    assert "stance feet per sample: min 3" in out
    assert "LF_femur" in out


def test_unknown_robot_lists_the_registry(capsys):
    assert main(["gait", "--robot", "atlas"]) == 2
    err = capsys.readouterr().err
    assert "unknown robot 'atlas'" in err and "solo12" in err and "Traceback" not in err
