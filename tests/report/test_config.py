"""Tests of hexaleg.report.config: the report's TOML tables, their errors (naming the key
and the valid ones) and the springs a configuration builds."""

from __future__ import annotations

import dataclasses
import re

import pytest

from hexaleg import GaitParams, gait
from hexaleg.cli import main
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.report.config import ReportConfig, ReportParams, SpringDesign
from hexaleg.robot.catalogue import motor
from hexaleg.robot.springs import SpringSet
from hexaleg.scenario.scenario import Scenario


def _config(tmp_path, text):
    path = tmp_path / "c.toml"
    path.write_text(text)
    return path


def test_unknown_key_names_the_key_and_the_valid_ones(tmp_path):
    with pytest.raises(UnknownNameError, match=r"'titel'.*paper_samples.*title"):
        ReportConfig.from_toml(_config(tmp_path, '[report]\ntitel = "x"\n'))
    with pytest.raises(UnknownNameError, match=r"'reprot'.*contact.*gait.*motor.*report.*springs"):
        ReportConfig.from_toml(_config(tmp_path, "[reprot]\n"))
    with pytest.raises(UnknownNameError, match=r"'stiffnes'.*dead_zone.*design.*joints"):
        ReportConfig.from_toml(_config(tmp_path, "[springs]\nstiffnes = 1.0\n"))
    with pytest.raises(UnknownNameError, match=r"'mu_'.*cone.*mu"):
        ReportConfig.from_toml(_config(tmp_path, "[contact]\nmu_ = 0.5\n"))
    with pytest.raises(UnknownNameError, match=r"'stride'.*stride_length"):
        ReportConfig.from_toml(_config(tmp_path, "[gait]\nstride = 0.1\n"))


def test_wrong_type_names_the_key_and_the_type(tmp_path, capsys):
    path = _config(tmp_path, '[gait]\nperiod = "slow"\n')
    with pytest.raises(ConfigError, match=r"gait\]\.period = 'slow'.*expected a number"):
        ReportConfig.from_toml(path)
    assert main(["report", "--config", str(path), "--out", str(tmp_path / "o")]) == 2
    assert "period" in capsys.readouterr().err
    with pytest.raises(ConfigError, match=r"stiffness_points = 2.5.*integer"):
        ReportConfig.from_toml(_config(tmp_path, "[report]\nstiffness_points = 2.5\n"))
    with pytest.raises(ConfigError, match=r"regeneration"):
        ReportConfig.from_toml(_config(tmp_path, '[motor]\nbase = "AX-18A"\n'
                                                 'regeneration = "yes"\n'))


def test_out_of_range_values(tmp_path):
    for text, match in (('[report]\nobjective = "fast"\n', "joule"),
                        ('[report]\ncurve_metrics = ["joules"]\n', "electrical"),
                        ("[report]\nstiffness_min = 1.0\nstiffness_max = 0.5\n", "stiffness_max"),
                        ('[springs]\ndesign = "centred"\n', "stiffness"),
                        ('[springs]\ndesign = "paper"\nstiffness = 1.0\n', "centred"),
                        ('[springs]\ndesign = "linear"\n', "paper")):
        with pytest.raises((InvalidParameterError, UnknownNameError), match=match):
            ReportConfig.from_toml(_config(tmp_path, text))


def test_direct_construction_rejects_wrong_types():
    for kwargs, name in (({"title": 5}, "title"), ({"stiffness_points": "x"}, "stiffness_points"),
                         ({"stiffness_min": float("nan")}, "stiffness_min"),
                         ({"curve_metrics": "joule"}, "curve_metrics"),
                         ({"paper_samples": 4}, "paper_samples")):
        with pytest.raises(InvalidParameterError, match=name):
            ReportParams(**kwargs)
    with pytest.raises(InvalidParameterError, match="stiffness"):
        SpringDesign("centred", stiffness="1")
    with pytest.raises(InvalidParameterError, match="dead_zone"):
        SpringDesign("centred", stiffness=1.0, dead_zone=1.0)


def test_spring_tables_build_the_configured_springs(tmp_path, robot):
    cfg = ReportConfig.from_toml(_config(tmp_path, """
[springs.LF_femur]
stiffness = 0.5
theta_k = 0.1
neutral = 0.5
"""))
    assert isinstance(cfg.springs, SpringSet) and cfg.springs["LF_femur"].stiffness == 0.5
    cfg = ReportConfig.from_toml(_config(tmp_path, """
[springs]
design = "centred"
joints = "tibia"
stiffness = 0.2
dead_zone = 0.25
[motor]
base = "MX-28"
"""))
    assert cfg.springs == SpringDesign("centred", "tibia", 0.2, 0.25)
    assert cfg.motor == motor("MX-28")
    motion = gait(robot, GaitParams(samples=40))
    s = cfg.spring_set(robot, motion)
    assert set(s) == set(robot.joints("tibia"))
    q = motion.q[:, 7 + robot.column("LF_tibia")]
    assert s["LF_tibia"].neutral == pytest.approx((q.max() + q.min()) / 2)
    assert s["LF_tibia"].stiffness == 0.2
    assert s["LF_tibia"].theta_k == pytest.approx(0.25 * (q.max() - q.min()) / 2)
    assert not ReportConfig.from_toml(_config(tmp_path, '[springs]\ndesign = "baseline"\n')
                                      ).spring_set(robot, motion)
    with pytest.raises(UnknownNameError, match="femur"):
        ReportConfig.from_toml(_config(tmp_path, '[springs]\ndesign = "paper"\njoints = "knee"\n'
                                       )).spring_set(robot, motion)


def test_unknown_spring_design_lists_the_designs(tmp_path):
    """No springs is the ``baseline`` design (the one name for it); ``"none"`` is not one."""
    for text in ('[springs]\ndesign = "linear"\n', '[springs]\ndesign = "none"\n'):
        with pytest.raises(InvalidParameterError,
                           match=re.escape("one of paper, centred, baseline")):
            ReportConfig.from_toml(_config(tmp_path, text))


def test_a_run_gives_the_robot_and_the_files_keys(tmp_path):
    """The report of a run (Scenario): the built-in robot's is the defaults but for its title;
    another robot's gait with the file's keys on top."""
    config = ReportConfig.from_scenario(Scenario.load())
    report = dataclasses.replace(ReportConfig().report, title=config.report.title)
    assert config == dataclasses.replace(ReportConfig(), report=report,
                                         robot_description=config.robot_description,
                                         robot="hexaleg")
    (tmp_path / "c.toml").write_text("[gait]\nperiod = 0.7\n")
    run = Scenario.load("solo12", tmp_path / "c.toml")
    config = ReportConfig.from_scenario(run)
    assert len(run.model.legs) == 4
    assert config.gait.period == 0.7 and config.gait.groups == (("LF", "RH"), ("RF", "LH"))
