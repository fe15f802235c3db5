"""A run's warnings (hexaleg.scenario.run_warnings) appear in every command that uses the run —
gait, report, simulate (design: tests/design/chain/test_warnings.py) — printed, on the page
and in the JSON, the same lines each time.

The run: the test hexapod (generic actuator from its URDF limits, gait defaults sized to it) with
a config that sets the period to 0.25 s, so its joints run over their 6 rad/s limits."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import hexaleg
from hexaleg.cli import main
from hexaleg.commands.simulate.write import page
from hexaleg.motion.params import GaitParams
from hexaleg.motion.scaling import robot_gait
from hexaleg.robot.catalogue import motor
from hexaleg.robot.registry import description
from hexaleg.scenario.run_warnings import run_warnings

SPIDER = str(Path(__file__).resolve().parents[1] / "data" / "spider.toml")
CONFIG = "[gait]\nperiod = 0.25\nsamples = 40\n[report]\nstiffness_points = 3\npaper_samples = 8\n"


@pytest.fixture(scope="module")
def config(tmp_path_factory: pytest.TempPathFactory) -> str:
    path = tmp_path_factory.mktemp("warnings") / "fast.toml"
    path.write_text(CONFIG)
    return str(path)


@pytest.fixture(scope="module")
def expected() -> tuple[str, ...]:
    """The run's warnings, from the module's function."""
    desc = description(SPIDER)
    robot = desc.load()
    gait = robot_gait(desc).updated({"period": 0.25, "samples": 40})
    return run_warnings(robot, hexaleg.gait(robot, gait), desc.actuator(robot),
                        desc=desc, gait=gait)


def test_the_runs_warnings_say_speeds_actuator_and_defaults(expected):
    assert len(expected) >= 3
    defaults, *speeds, generic = expected
    assert defaults.startswith("gait defaults sized to spider") and "period" not in defaults
    assert "stride" in defaults  # the config set the period, not the stride
    assert speeds and all(s.startswith("joint_speed: joint ") for s in speeds)
    assert generic.startswith("generic actuator on every joint")


def test_a_catalogue_motor_and_the_reference_robot_have_none():
    robot = hexaleg.load("hexaleg")
    motion = hexaleg.gait(robot, GaitParams(samples=40))
    assert run_warnings(robot, motion, motor("AX-18A"), desc=description("hexaleg"),
                        gait=GaitParams(samples=40)) == ()


def test_gait_prints_them(config, expected, capsys):
    assert main(["gait", "--robot", SPIDER, "--config", config]) == 0
    out = capsys.readouterr().out
    for line in expected:
        assert out.count(f"warning: {line}") == 1  # once: not again as a finding


def test_report_prints_shows_and_writes_them(config, expected, tmp_path, capsys):
    assert main(["report", "--robot", SPIDER, "--config", config, "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    data = json.loads((tmp_path / "report.json").read_text())
    page_text = (tmp_path / "report.html").read_text()
    assert data["warnings"] == list(expected)
    for line in expected:
        assert f"warning: {line}" in out
    assert page_text.count("<b>Warning:</b>") == len(expected)
    assert not any("joint_speed" in n for n in data["notes"])  # said once, as a warning
    defaults = data["gait_defaults"]
    assert defaults["kept"] == ["stride_length", "step_height"]  # the config set the period
    assert defaults["stride_length"] == {"value": robot_gait(SPIDER).stride,
                                         "unit": "m"}


def test_simulate_prints_shows_and_writes_them(config, expected, tmp_path, capsys):
    main(["simulate", "--robot", SPIDER, "--config", config, "--cycles", "2",
          "--out", str(tmp_path)])  # walks or not, the files are written
    out = capsys.readouterr().out
    data = json.loads((tmp_path / "simulate.json").read_text())
    assert data["warnings"] == list(expected)
    assert data["gait_defaults"]["kept"] == ["stride_length", "step_height"]
    assert page(data).count("- warning: ") == len(expected)
    assert (tmp_path / "simulate.md").read_text() == page(data)
    for line in expected:
        assert f"warning: {line}" in out


def test_the_generic_warning_names_a_few_classes_and_counts_the_rest():
    """A humanoid's arms are a motor class each: the line names eight and counts the rest."""
    from pathlib import Path

    from hexaleg.robot.motor import generic_actuator
    from hexaleg.robot.motor_set import MotorSet
    from hexaleg.scenario.run_warnings import generic_warning

    robot = hexaleg.load(str(Path(__file__).resolve().parents[1] / "data" / "humanoid.toml"))
    motors = MotorSet.per_class(
        {**robot.joint_classes, **{j: (j,) for j in robot.other_joints}}, robot.joint_names,
        {k: generic_actuator(float(i + 1), 5.0, name="generic (humanoid URDF limits)")
         for i, k in enumerate([*robot.joint_classes, *robot.other_joints])})
    line = generic_warning(motors)
    assert line.startswith("generic actuator on hip, thigh, knee, waist, L_shoulder, L_elbow, "
                           "R_shoulder, R_elbow: ")
    many = MotorSet.per_class({j: (j,) for j in robot.joint_names}, robot.joint_names,
                              {j: generic_actuator(float(i + 1), 5.0, name="g")
                               for i, j in enumerate(robot.joint_names)})
    assert generic_warning(many).startswith(
        "generic actuator on L_hip_roll, L_hip_pitch, L_knee, R_hip_roll, R_hip_pitch, R_knee, "
        "waist, L_shoulder and 3 more: ")


def test_a_replaced_collision_mesh_is_every_commands_warning():
    """Issue #58: a foot whose collision mesh is missing is found on the box that replaces it;
    only ``hexaleg robot`` said so. The replacement's note (hexaleg.robot.meshes, tested there
    on a URDF with a missing mesh) is now a warning of every run, with what it changes."""
    import dataclasses

    robot = hexaleg.load("hexaleg")
    note = ("link LF_tibia: collision mesh tibia.stl not found; replaced by its inertia box "
            "0.12 × 0.02 × 0.02 m")
    assert note.split(": ", 1)[1].startswith("collision mesh")
    moved = dataclasses.replace(robot, notes=(*robot.notes, note))
    motion = hexaleg.gait(robot, GaitParams(samples=40))
    lines = run_warnings(moved, motion, motor("AX-18A"))
    assert lines == (f"{note}: a foot found on this link, and the springs' fit limits, are the "
                     "replacement's; give the mesh's directory to find the robot's own",)
    assert run_warnings(robot, motion, motor("AX-18A")) == ()
