"""``hexaleg codesign`` on the command line: registered, configured, bad input one line."""

from __future__ import annotations

import json

import pytest

from hexaleg.cli import build_parser, main
from hexaleg.config import load_toml
from hexaleg.design.codesign.build import codesign_settings
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError

SMALL = """[codesign]
samples = 40
final_samples = 40
max_evaluations = 10
restarts = 1
rules = false
curve = false
simulate = false
[codesign.constraints]
min_body_clearance = 0.01
"""


def settings(path):
    """The [codesign] keywords of a config file, as the command reads them."""
    return codesign_settings(load_toml(path).get("codesign", {}) if path else {},
                             f"{path} [codesign]")


def test_registered_with_its_options():
    args = build_parser().parse_args(["codesign", "--speed", "0.05", "--pattern", "wave"])
    assert args.speed == 0.05 and args.pattern == "wave" and args.rules is None  # the default
    assert build_parser().parse_args(["codesign", "--no-rules"]).rules is False
    assert build_parser().parse_args(["codesign"]).motion is None  # [codesign] motion, or gait
    assert build_parser().parse_args(["codesign", "--motion", "optimal"]).motion == "optimal"
    assert build_parser().parse_args(["codesign"]).feedback is None  # [codesign] feedback, or auto
    assert build_parser().parse_args(["codesign", "--feedback", "on"]).feedback == "on"


def test_feedback_is_named_as_simulate_names_it_and_needs_the_optimal_rows(tmp_path, capsys):
    """``--feedback`` takes ``hexaleg simulate``'s values; it sets the optimal rows' balance
    feedback, so without ``--motion optimal`` a value other than auto is refused by name before
    any work, and a config's unknown value is named with what is allowed."""
    simulate = next(a for a in build_parser()._subparsers._group_actions[0].choices[
        "simulate"]._actions if a.dest == "feedback")
    codesign_ = next(a for a in build_parser()._subparsers._group_actions[0].choices[
        "codesign"]._actions if a.dest == "feedback")
    assert codesign_.choices == simulate.choices == ("auto", "on", "off")
    assert main(["codesign", "--feedback", "on", "--out", str(tmp_path / "o")]) == 2
    assert "feedback = 'on'" in capsys.readouterr().err
    bad = tmp_path / "bad.toml"
    bad.write_text('[codesign]\nmotion = "optimal"\nfeedback = "always"\n')
    assert main(["codesign", "--config", str(bad), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "always" in err and "auto" in err and "off" in err


def test_timing_is_a_decision_of_the_optimal_rows_only(tmp_path, capsys):
    """``--timing search`` searches the optimal motion's contact timing: without ``--motion
    optimal`` it is refused by name before any work; an unknown value is named."""
    args = build_parser().parse_args(["codesign", "--motion", "optimal", "--timing", "search"])
    assert args.timing == "search" and build_parser().parse_args(["codesign"]).timing is None
    assert main(["codesign", "--timing", "search", "--out", str(tmp_path / "o")]) == 2
    assert "timing = 'search'" in capsys.readouterr().err
    bad = tmp_path / "bad.toml"
    bad.write_text('[codesign]\nmotion = "optimal"\ntiming = "free"\n')
    assert main(["codesign", "--config", str(bad), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "free" in err and "search" in err


def test_the_optimal_problem_is_set_by_a_codesign_optimal_table(tmp_path, capsys):
    """``[codesign.optimal]`` sets the optimal motion's problem (OptimalParams' keys): refused
    by name without ``motion = "optimal"`` and when it is not a table, before any work; with
    Crocoddyl an unknown key or a bad value is named, with the allowed ones (an unknown
    integrator with the knots the command solves, ``rk4`` among them)."""
    bad = tmp_path / "bad.toml"
    bad.write_text("[codesign.optimal]\nservo_landing_weight = 30\n")
    assert main(["codesign", "--config", str(bad), "--out", str(tmp_path / "o")]) == 2
    assert "[codesign.optimal] sets the optimal motion's problem" in capsys.readouterr().err
    bad.write_text('[codesign]\nmotion = "optimal"\noptimal = 3\n')
    assert main(["codesign", "--config", str(bad), "--out", str(tmp_path / "o")]) == 2
    assert "[codesign.optimal] must be a table" in capsys.readouterr().err
    pytest.importorskip("crocoddyl")
    bad.write_text('[codesign]\nmotion = "optimal"\n[codesign.optimal]\nservo_landing = 30\n')
    assert main(["codesign", "--config", str(bad), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "servo_landing" in err and "servo_landing_weight" in err
    bad.write_text('[codesign]\nmotion = "optimal"\n[codesign.optimal]\n'
                   "servo_landing_weight = -1\n")
    assert main(["codesign", "--config", str(bad), "--out", str(tmp_path / "o")]) == 2
    assert "servo_landing_weight" in capsys.readouterr().err
    bad.write_text('[codesign]\nmotion = "optimal"\n[codesign.optimal]\nmu = 0.9\n')
    assert main(["codesign", "--config", str(bad), "--out", str(tmp_path / "o")]) == 2
    assert "the optimal motion plans on the run's floor, [contact] mu" in capsys.readouterr().err
    bad.write_text('[codesign]\nmotion = "optimal"\n[codesign.optimal]\n'
                   'integrator = "implicit"\n')
    assert main(["codesign", "--config", str(bad), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "implicit" in err and "rk4" in err and "euler" in err


def test_starts_are_a_decision_of_the_optimal_rows_only(tmp_path, capsys):
    """``--starts lattice`` tries other starts of the optimal motion: without ``--motion
    optimal`` it is refused by name before any work; an unknown value is named."""
    args = build_parser().parse_args(["codesign", "--motion", "optimal", "--starts", "lattice"])
    assert args.starts == "lattice" and build_parser().parse_args(["codesign"]).starts is None
    assert main(["codesign", "--starts", "lattice", "--out", str(tmp_path / "o")]) == 2
    assert "starts = 'lattice'" in capsys.readouterr().err
    bad = tmp_path / "bad.toml"
    bad.write_text('[codesign]\nmotion = "optimal"\nstarts = "random"\n')
    assert main(["codesign", "--config", str(bad), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "random" in err and "lattice" in err


@pytest.mark.parametrize(("key", "good", "bad", "allowed"), [
    ("duty_high", "0.9", "0.97", "[0.55, 0.95]"),  # default: the config's, or 0.8
    ("body_high", "1.5", "2.5", "[1, 2]")])  # default: the config's, or 1.3
def test_a_search_bound_is_an_option_and_a_key(tmp_path, capsys, key, good, bad, allowed):
    """``--duty-high`` / ``[codesign] duty_high`` and ``--body-high`` / ``[codesign] body_high``
    are each one setting, the command line winning over the config; out of range it is one line
    naming the value and the range."""
    option = "--" + key.replace("_", "-")
    assert getattr(build_parser().parse_args(["codesign"]), key) is None
    assert getattr(build_parser().parse_args(["codesign", option, good]), key) == float(good)
    config = tmp_path / "c.toml"
    config.write_text(f"[codesign]\n{key} = {good}\n")
    assert settings(config)[key] == float(good)
    config.write_text(f'[codesign]\n{key} = "high"\n')
    with pytest.raises(ConfigError, match=key):
        settings(config)
    config.write_text(f"[codesign]\n{key} = {good}\n")
    assert main(["codesign", "--config", str(config), option, bad,
                 "--out", str(tmp_path / "o")]) == 2  # the command line's value wins
    err = capsys.readouterr().err
    assert key in err and bad in err and allowed in err


def test_config_table_is_checked(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[codesign]\nspeeed = 0.1\n")
    with pytest.raises(UnknownNameError, match="speeed"):
        settings(bad)
    good = tmp_path / "good.toml"
    good.write_text(SMALL)
    assert settings(good)["constraints"].min_body_clearance == 0.01
    assert settings(None) == {}
    rules = tmp_path / "rules.toml"
    rules.write_text("[codesign.design]\nfamilies = [\"preloaded\"]\nlife_cycles = 1e6\n")
    design = settings(rules)["design"]
    assert design.families == ("preloaded",) and design.life_cycles == 1e6
    assert not design.robustness


@pytest.mark.parametrize(("line", "named"), [('simulate = "false"', "simulate"),
                                             ("rules = 1", "rules"), ("curve = 0.0", "curve"),
                                             ('samples = "40"', "samples"),
                                             ("speed = true", "speed")])
def test_config_values_are_type_checked_like_the_design_table(tmp_path, line, named):
    """[codesign] values checked against codesign()'s own annotations, as [design]'s against
    its dataclass: the string "false" is not false (it ran the simulation)."""
    bad = tmp_path / "bad.toml"
    bad.write_text(f"[codesign]\n{line}\n")
    with pytest.raises(ConfigError, match=rf"\[codesign\]\.{named} = "):
        settings(bad)
    assert main(["codesign", "--config", str(bad), "--out", str(tmp_path / "o")]) == 2


def test_an_unknown_family_is_named_not_blamed_on_the_speed(tmp_path):
    from hexaleg.design.codesign.build import codesign

    with pytest.raises(UnknownNameError, match=r"\[codesign\] family.*torsion"):
        codesign(family="torsion")


def test_the_robot_s_own_actuator_is_used(monkeypatch):
    """Every gait the co-design evaluates is prepared with the robot's own actuator (Solo-12's
    ODRI module), not the catalogue's default AX-18A: the default gait, and on its refusal the
    same gait in the whole friction cone."""
    from hexaleg.design.codesign import build
    from hexaleg.design.codesign.gait_evaluation import GaitPoint

    seen = []

    def refuse(robot, params, *, motor=None, **_):
        seen.append(motor)
        return GaitPoint(params=params, distance=params.stride, error="stop here")

    monkeypatch.setattr(build, "evaluate_gait", refuse)
    with pytest.raises(InvalidParameterError, match="stop here"):
        build.codesign("solo12", speed=0.1)
    assert seen and {m.name for m in seen} == {"ODRI-4004"}


def test_runs_and_writes(tmp_path, capsys):
    config = tmp_path / "c.toml"
    config.write_text(SMALL)
    out = tmp_path / "out"
    assert main(["codesign", "--config", str(config), "--speed", "0.06", "--out", str(out)]) == 0
    data = json.loads((out / "codesign.json").read_text())
    assert data["speed"] == {"value": 0.06, "unit": "m/s"}
    assert data["search"]["codesign"]["evaluations"] <= 10
    assert data["settings"]["duty_high"] == {"value": 0.8, "unit": "1"}  # the default bound
    assert data["settings"]["body_high"] == {"value": 1.3, "unit": "1"}  # the default box
    page = (out / "codesign.html").read_text()
    assert "Duty factor searched up to 0.8 " in page
    assert "body height up to 1.3 × the default gait's" in page
    assert data["full_rules"] is None and "inner program" in data["recommended"]["source"]
    printed = capsys.readouterr().out
    assert "J/m" in printed and "search: duty factor ≤ 0.8 ([codesign] duty_high)" in printed
    assert "body height ≤ 1.3 × the default gait's ([codesign] body_high)" in printed


def test_bad_speed_is_one_line(capsys):
    assert main(["codesign", "--speed", "-1"]) == 2
    assert "speed" in capsys.readouterr().err


def test_a_pattern_for_other_legs_is_named_not_the_speed(tmp_path, capsys):
    """Issue #42: --pattern tripod on a quadruped was blamed on the speed."""
    assert main(["codesign", "--robot", "solo12", "--pattern", "tripod", "--no-rules",
                 "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "error: invalid pattern = 'tripod'; allowed: a pattern for 2 + 2 legs" in err
    assert "speed" not in err


def test_tables_codesign_does_not_read_are_refused(tmp_path, capsys):
    """[gait] was silently ignored by codesign: refused, with where the setting goes; so is a
    [contact] key its force programs do not plan with."""
    config = tmp_path / "c.toml"
    config.write_text('[gait]\nperiod = 2.0\n')
    assert main(["codesign", "--config", str(config), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "[gait]: hexaleg codesign does not read it" in err and "--speed" in err
    config.write_text('[contact]\ncone = "pyramid"\n')
    assert main(["codesign", "--config", str(config), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "[contact] cone: hexaleg codesign plans its forces with the defaults" in err
    assert not (tmp_path / "out").exists()


def test_the_floor_and_the_actuator_have_one_home(tmp_path):
    """Issue #53: codesign ignored [contact] and [motor]. Its floor is [contact] mu and
    torque_limits; [codesign.constraints] mu is deprecated and refused beside it; its
    actuator is [motor]."""
    from hexaleg.config import load_toml
    from hexaleg.scenario.scenario import Scenario

    def run(text):
        config = tmp_path / "c.toml"
        config.write_text(text)
        tables = load_toml(config)
        return Scenario.from_tables("hexaleg", tables, str(config)), tables

    s, tables = run("[contact]\nmu = 0.45\n[motor]\nbase = \"AX-12A\"\n")
    kwargs = codesign_settings(tables.get("codesign", {}), "[codesign]", s)
    assert kwargs["constraints"].mu == 0.45 and s.actuator.name == "AX-12A"
    s, tables = run("[codesign.constraints]\nmu = 0.45\n")
    with pytest.warns(DeprecationWarning, match=r"\[contact\] mu = 0.45"):
        kwargs = codesign_settings(tables["codesign"], "[codesign]", s)
    assert kwargs["constraints"].mu == 0.45
    s, tables = run("[contact]\nmu = 0.5\n[codesign.constraints]\nmu = 0.45\n")
    with pytest.raises(ConfigError, match="the floor has one home, \\[contact\\]"):
        codesign_settings(tables["codesign"], "[codesign]", s)
