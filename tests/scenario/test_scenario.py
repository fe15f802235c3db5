"""Tests of hexaleg.scenario.scenario: a run is the robot's own gait with the file's keys on
top, its own actuator unless a [motor] says otherwise, or a log's cycle — and its warnings are
the run's, whoever asks."""

from __future__ import annotations

import json

import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.motion.params import GaitParams
from hexaleg.motion.recorded.write import write_motion_log
from hexaleg.motion.scaling import robot_gait
from hexaleg.quantities import json_text
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
    assert run.motion() is run.recorded and run.recorded.period == pytest.approx(0.8)
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


# --------------------------------------------------------------- the run as one object


def test_a_scenario_survives_pickling_whole():
    """A worker receives the run pickled: the same analysis (key) and the same prepared
    baseline on the other side, the robot loaded from that process's cache."""
    import pickle

    run = Scenario.load().with_gait({"samples": 40})
    back = pickle.loads(pickle.dumps(run))
    assert back.key() == run.key() and back.gait == run.gait and back.tables == run.tables
    assert back.model is run.model  # this process's cache: one robot per (name, payload)
    ours, theirs = (r.prepare().baseline("joule")["total"] for r in (run, back))
    assert theirs == ours


def test_under_a_condition_changes_the_friction_the_payload_and_the_gait():
    from hexaleg.scenario.condition import Condition, condition_gait

    run = Scenario.load().with_gait({"samples": 40})
    slippery = run.under(Condition(mu=0.3))
    assert slippery.contact.mu == 0.3 and run.contact.mu != 0.3
    assert slippery.gait == run.gait and slippery.payload == 0.0
    heavy = run.under(Condition(payload=0.2, period=1.5))
    assert heavy.payload == pytest.approx(0.2 * run.model.mass)
    assert heavy.model.mass == pytest.approx(1.2 * run.model.mass)
    assert heavy.gait == condition_gait(run.gait, Condition(period=1.5))
    assert heavy.key() != run.key() and run.under(Condition()).key() == run.key()
    heavier = heavy.under(Condition(payload=0.1))  # on top of the run's payload
    assert heavier.model.mass == pytest.approx(1.3 * run.model.mass)


def test_under_refuses_a_logged_run(tmp_path):
    from hexaleg.scenario.condition import Condition

    robot = hexaleg.load()
    log = write_motion_log(robot, hexaleg.gait(robot, GaitParams(samples=40)),
                           tmp_path / "walk.csv")
    run = Scenario.load("hexaleg", log=log, cycle="whole")
    with pytest.raises(InvalidParameterError, match="cannot be varied"):
        run.under(Condition(mu=0.3))
    assert run.with_samples(80) is run  # a log keeps its own samples


def test_with_samples_and_with_gait_change_the_gait_alone():
    run = Scenario.load()
    fine = run.with_samples(60)
    assert fine.gait.samples == 60 and fine.gait.period == run.gait.period
    assert fine.contact == run.contact and fine.actuator is run.actuator
    assert run.with_gait({"samples": 60}).key() == fine.key()
    with pytest.raises(UnknownNameError, match="duty_factor"):
        run.with_gait({"perod": 1.0})
    data = fine.data()
    assert data["robot"] == "hexaleg" and data["gait"]["samples"] == 60
    assert data["objective"] == "joule" and data["payload"] == {"value": 0.0, "unit": "kg"}
    assert data["gait"]["period"] == {"value": run.gait.period, "unit": "s"}
    assert data["contact"]["mu"] == {"value": run.contact.mu, "unit": "1"}
    assert json.loads(json_text(data)) == data  # JSON as it is, no number without its unit


def test_a_design_builds_the_robot_once(monkeypatch):
    """The URDF is built once per process: the run, the design chain's nominal gait, its
    candidates and their conditions all take the robot from the cache."""
    from hexaleg.design.chain.chain import DesignChain
    from hexaleg.robot.description import RobotDescription
    from hexaleg.scenario.scenario import clear_robots

    loads: list[str] = []
    load = RobotDescription.load

    def counted(self, *args, **kwargs):
        loads.append(self.name)
        return load(self, *args, **kwargs)

    monkeypatch.setattr(RobotDescription, "load", counted)
    clear_robots()
    scenario = Scenario.load("hexaleg")
    DesignChain(scenario).run(stages=("candidates",))  # every family, ~12 s
    assert len(loads) == 1, loads


def _spider():
    from pathlib import Path

    return Path(__file__).resolve().parents[1] / "data" / "spider.toml"
