"""Tests of hexaleg.scenario.scenario: a run is the robot's own gait with the file's keys on
top, its own actuator unless a [motor] says otherwise, or a log's cycle — and its warnings are
the run's, whoever asks."""

from __future__ import annotations

import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.motion.params import GaitParams
from hexaleg.motion.recorded.write import write_motion_log
from hexaleg.motion.scaling import robot_gait
from hexaleg.robot.registry import description
from hexaleg.scenario.run_warnings import run_warnings
from hexaleg.scenario.scenario import TABLES, Scenario


def test_the_robots_own_gait_with_the_files_keys_on_top(tmp_path):
    config = tmp_path / "c.toml"
    config.write_text("[gait]\nperiod = 0.7\n[contact]\nmu = 0.4\n")
    run = Scenario.load("solo12", config)
    own = robot_gait(description("solo12"))
    assert run.gait == own.updated({"period": 0.7})
    assert run.gait.groups == own.groups and run.gait.period == 0.7
    assert run.contact.mu == 0.4 and run.where == str(config)
    assert run.actuator == run.description.actuator(run.model)  # no [motor]: its own
    assert run.log is None and run.recorded is None and run.notes == run.model.notes


def test_a_motor_table_puts_one_servo_on_every_joint(tmp_path):
    config = tmp_path / "c.toml"
    config.write_text('[motor]\nbase = "MX-28"\n')
    run = Scenario.load("hexaleg", config)
    assert run.actuator.name == "MX-28"
    assert run.prepare().motor is run.actuator


def test_unknown_tables_and_gait_keys_are_named(tmp_path):
    config = tmp_path / "c.toml"
    config.write_text("[gaits]\nperiod = 0.7\n")
    with pytest.raises(UnknownNameError, match="gaits") as e:
        Scenario.load("hexaleg", config)
    assert all(t in str(e.value) for t in TABLES)
    with pytest.raises(UnknownNameError, match="perod"):
        Scenario.from_tables("hexaleg", {"gait": {"perod": 0.7}})


def test_a_log_is_the_runs_motion_and_refuses_a_gait_table(tmp_path):
    robot = hexaleg.load()
    walk = hexaleg.gait(robot, GaitParams(period=0.8, samples=80))
    log = write_motion_log(robot, walk, tmp_path / "walk.csv")
    run = Scenario.load("hexaleg", log=log, cycle="whole")
    assert run.motion() is run.motion and run.motion.period == pytest.approx(0.8)
    assert run.log == str(log) and any(str(log) in n for n in run.notes)
    with pytest.raises(InvalidParameterError, match=r"\[gait\].*--motion"):
        Scenario.from_tables("hexaleg", {"gait": {"period": 0.5}}, log=log, cycle="whole")


def test_the_warnings_are_the_runs(tmp_path):
    """A robot with sized gait defaults and generic actuators: the run's warnings are
    run_warnings of its played motion, the same lines any command says."""
    run = Scenario.load(str(_spider()))
    played = run.motion()
    assert run.warnings() == run_warnings(run.model, played, run.actuator,
                                          desc=run.description, gait=run.gait)
    assert run.warnings()  # the spider's sized defaults and generic servos say something


def _spider():
    from pathlib import Path

    return Path(__file__).resolve().parents[1] / "data" / "spider.toml"
