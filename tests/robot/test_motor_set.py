"""Tests of hexaleg.robot.motor_set: one motor per joint class, through the dynamics and energy."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

from hexaleg.dynamics import energy
from hexaleg.dynamics.prepare import analyze, prepare
from hexaleg.dynamics.reference import solve_reference
from hexaleg.dynamics.solver import solve_fast
from hexaleg.errors import InvalidParameterError, TorqueLimitError, UnknownNameError
from hexaleg.robot.catalogue import CATALOGUE
from hexaleg.robot.description import RobotDescription
from hexaleg.robot.motor import generic_actuator
from hexaleg.robot.motor_set import MotorSet

STRONG, LIGHT = CATALOGUE["XM430-W350"], CATALOGUE["XL430-W250"]


def _set(robot, femur=STRONG, other=LIGHT):
    return MotorSet.per_class(robot.joint_classes, robot.joint_names,
                              {"coxa": other, "femur": femur, "tibia": other})


def test_each_joint_gets_its_class_motor(robot):
    motors = _set(robot)
    femur = np.array([j.endswith("femur") for j in robot.joint_names])
    assert femur.sum() == 6
    assert np.array_equal(motors.stall_torque, np.where(femur, STRONG.stall_torque,
                                                        LIGHT.stall_torque))
    assert np.array_equal(motors.joule_coefficient,
                          np.where(femur, STRONG.joule_coefficient, LIGHT.joule_coefficient))
    assert motors.name == "XL430-W250 (coxa, tibia) · XM430-W350 (femur)"
    tau = np.linspace(-1.0, 1.0, 2 * len(femur)).reshape(2, -1)
    np.testing.assert_array_equal(motors.current(tau), np.where(
        femur, STRONG.current(tau), LIGHT.current(tau)))  # each joint its own k_t G


def test_metrics_per_joint_are_each_motors_own(robot, walk200):
    """Every per-joint energy equals a one-joint metrics call with that joint's motor alone
    (a regenerating femur motor: its joints' electrical energy is the regenerating one)."""
    a = analyze(robot, walk200)
    motors = _set(robot, femur=dataclasses.replace(STRONG, regeneration=True))
    m = energy.metrics(a.tau_motor, a.qdot, walk200.dt, motors)
    femur = np.array([j.endswith("femur") for j in robot.joint_names])
    joint = m["joint"]
    assert np.array_equal(joint["electrical"], np.where(femur, joint["electrical_regen"],
                                                        joint["electrical_noregen"]))
    assert np.any(joint["electrical_regen"][femur] < joint["electrical_noregen"][femur])
    for j, name in enumerate(robot.joint_names):
        alone = energy.metrics(a.tau_motor[:, j], a.qdot[:, j], walk200.dt, motors.motors[j])
        for key in energy.ENERGY_KEYS:
            assert m["joint"][key][j] == pytest.approx(alone["joint"][key][0], rel=1e-13), (
                name, key)
    assert m["total"]["joule"] == pytest.approx(m["joint"]["joule"].sum(), rel=1e-14)


def test_one_motor_everywhere_equals_the_motor(robot, walk200):
    """A set with the same motor on every class gives the analysis of that motor, bit for bit."""
    one = analyze(robot, walk200, motor=LIGHT)
    same = analyze(robot, walk200, motor=_set(robot, femur=LIGHT))
    assert np.array_equal(one.forces, same.forces)
    for key in energy.ENERGY_KEYS:
        assert one.metrics["total"][key] == same.metrics["total"][key]


def test_force_program_weighs_each_joint_by_its_motor(robot, walk200):
    """The Joule-optimal forces move when the femur's motor changes (its weight does), and the
    analysis' Joule energy is the minimum: no other feasible forces (the light motor's optimum)
    cost less under the set's own weights."""
    light = analyze(robot, walk200, motor=LIGHT)
    mixed = prepare(robot, walk200, motor=_set(robot))
    a = mixed.evaluate(None)
    assert np.abs(a.forces - light.forces).max() > 1e-3
    other = mixed.metrics(light.tau_motor)
    assert a.metrics["total"]["joule"] <= other["total"]["joule"] * (1 + 1e-12)
    assert np.array_equal(mixed.system.tau_max, _set(robot).stall_torque)


def test_electrical_objective_with_per_joint_efficiency_matches_cvxpy(robot, walk200):
    motors = _set(robot)
    prepared = prepare(robot, walk200, motor=motors)
    sys = prepared.system
    assert np.array_equal(sys.efficiency, motors.gearbox_efficiency)
    tau_s = np.zeros_like(prepared.q)
    w = prepared.weights("electrical")
    samples = np.arange(0, walk200.n_samples, 25)
    f_fast, _, _ = solve_fast(sys, tau_s, "electrical", w, prepared.contact)
    f_ref = solve_reference(sys, tau_s, "electrical", w, prepared.contact, samples=samples)

    def cost(f):
        tau = sys.torques(f, tau_s)[samples]
        power = motors.electrical_power(tau, sys.qdot[samples], regeneration=False)
        return power.sum(1) + prepared.contact.regularization * (tau**2).sum(1)

    assert np.allclose(cost(f_fast), cost(f_ref), atol=1e-8)


def test_motor_set_must_fit_the_robot(robot, walk200):
    wrong = MotorSet(robot.joint_names[::-1], ("coxa",) * robot.nj, (("coxa", LIGHT),))
    with pytest.raises(InvalidParameterError, match="motor joints"):
        prepare(robot, walk200, motor=wrong)
    with pytest.raises(InvalidParameterError, match="each joint class"):
        MotorSet(robot.joint_names, ("coxa",) * robot.nj, (("femur", LIGHT),))


def _spider_toml():
    from conftest import SPIDER

    return SPIDER


def _description(tmp_path, motor: str) -> RobotDescription:
    toml = _spider_toml().read_text().replace('heading = "+y"', f'heading = "+y"\nmotor = {motor}')
    path = tmp_path / "spider.toml"
    path.write_text(toml)
    (tmp_path / "spider.urdf").write_text((_spider_toml().parent / "spider.urdf").read_text())
    return RobotDescription.from_toml(path)


def test_description_names_a_motor_per_class(tmp_path, spider):
    desc = _description(tmp_path, '{femur = "XM430-W350", coxa = "XL430-W250"}')
    motors = desc.actuator(spider)
    assert isinstance(motors, MotorSet)
    table = dict(motors.by_class)
    assert table["femur"] is STRONG and table["coxa"] is LIGHT
    assert table["tibia"].name == "generic (spider URDF limits)"  # not named: from the URDF
    same = _description(tmp_path, '{femur = "MX-64", coxa = "MX-64", tibia = "MX-64"}')
    assert same.actuator(spider) is CATALOGUE["MX-64"]


@pytest.mark.parametrize(("motor", "error", "match"), [
    ('{femur = "XM999"}', UnknownNameError, "XM999"),
    ('{knee = "MX-64"}', UnknownNameError, "knee"),
    ("{}", InvalidParameterError, "joint class"),
])
def test_bad_motor_tables_name_the_value(tmp_path, spider, motor, error, match):
    with pytest.raises(error, match=match):
        _description(tmp_path, motor).actuator(spider)


def test_report_lists_the_motor_of_every_class(tmp_path):
    from hexaleg.cli import main

    _description(tmp_path, '{femur = "XM430-W350"}')
    config = tmp_path / "report.toml"
    config.write_text("[gait]\nsamples = 40\n[report]\nstiffness_points = 3\npaper_samples = 8\n")
    out = tmp_path / "report"
    assert main(["report", "--robot", str(tmp_path / "spider.toml"), "--config", str(config),
                 "--out", str(out)]) == 0
    data = json.loads((out / "report.json").read_text())
    classes = {c["joint_class"]: c for c in data["motor"]["classes"]}
    assert classes["femur"]["name"] == "XM430-W350"
    assert classes["femur"]["stall_torque"]["value"] == STRONG.stall_torque
    assert classes["coxa"]["name"].startswith("generic")
    page = (out / "report.html").read_text()
    assert "motor (femur)" in page and "XM430-W350" in page
    assert "names no catalogue motor for coxa, tibia" in page


def test_torque_limit_error_names_the_motor_and_the_remedy(robot, walk200):
    tiny = generic_actuator(0.1, 6.0, name="tiny servo")
    with pytest.raises(TorqueLimitError, match=r"tiny servo.*stronger") as info:
        analyze(robot, walk200, motor=tiny)
    assert "torque_limits" in str(info.value)


def test_a_class_with_a_zero_urdf_effort_is_named(urdf_with_limit):
    """The generic actuator's error used to name neither the joint class nor its joints."""
    from hexaleg.robot.motor_set import class_motors

    robot = urdf_with_limit("RF_tibia", "effort", "0")
    for joint in robot.joint_classes["tibia"]:
        robot.model.effortLimit[6 + robot.column(joint)] = 0.0
    with pytest.raises(InvalidParameterError, match=r"URDF effort limit of joint class 'tibia' "
                                                    r"\(.*RF_tibia.*\) = 0\.0; .*<limit effort="):
        class_motors(robot, {}, "generic")


def test_joints_on_no_leg_get_their_own_actuator_from_their_own_limits():
    """An arm's joint is its own motor class: its generic actuator's stall torque is its own
    URDF effort limit (1.5 N·m), not a leg class's (3 N·m); no joint is left without a motor
    (issue #55: a KeyError on the first joint outside the legs)."""
    from pathlib import Path

    data = Path(__file__).resolve().parents[1] / "data"
    desc = RobotDescription.from_toml(data / "humanoid.toml")
    robot = desc.load()
    motors = desc.actuator(robot)
    assert isinstance(motors, MotorSet)
    stall = dict(zip(motors.joint_names, motors.stall_torque, strict=True))
    assert stall["L_knee"] == pytest.approx(3.0) and stall["L_elbow"] == pytest.approx(1.5)
    assert stall["waist"] == pytest.approx(1.5)
    assert motors.joint_names == robot.joint_names
    classes = dict(zip(motors.joint_names, motors.joint_classes, strict=True))
    assert classes["L_elbow"] == "L_elbow" and classes["L_knee"] == "knee"
    with pytest.raises(InvalidParameterError, match=r"MotorSet joints.*waist"):
        MotorSet.per_class(robot.joint_classes, robot.joint_names,
                           {k: LIGHT for k in robot.joint_classes})


def test_a_joint_on_no_leg_takes_a_catalogue_motor_by_its_name(tmp_path):
    from pathlib import Path

    data = Path(__file__).resolve().parents[1] / "data"
    text = (data / "humanoid.toml").read_text().replace(
        'urdf = "humanoid.urdf"', f'urdf = "{data / "humanoid.urdf"}"\n'
        'motor = {L_elbow = "XL430-W250", knee = "XM430-W350"}')
    (tmp_path / "h.toml").write_text(text)
    desc = RobotDescription.from_toml(tmp_path / "h.toml")
    robot = desc.load()
    motors = desc.actuator(robot)
    table = dict(zip(motors.joint_names, motors.motors, strict=True))
    assert table["L_elbow"] is LIGHT and table["R_knee"] is STRONG
    assert table["R_elbow"].name.startswith("generic")
    bad = RobotDescription.from_toml(tmp_path / "h.toml")
    object.__setattr__(bad, "motor", {"elbow": "XL430-W250"})
    with pytest.raises(UnknownNameError, match=r"motor joint class 'elbow'.*L_elbow"):
        bad.actuator(robot)
