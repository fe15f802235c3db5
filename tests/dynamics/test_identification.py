"""Tests of hexaleg.dynamics.identification: a log no one here wrote — a MuJoCo walk whose
actuator columns come from another actuator than the one the analysis assumes — gives that
actuator's constants back; without logged torques, the analysis' torques and a residual that
says how far to trust them; the command prints a [motor] table that loads as the fitted motor."""

from __future__ import annotations

import dataclasses
import re
import warnings

import numpy as np
import pytest

import hexaleg
from hexaleg.cli import main
from hexaleg.dynamics.identification import identify_motion
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.catalogue import motor, motor_from_mapping
from hexaleg.simulation.walk_log import walk_log

BASE = motor("AX-18A")
TRUE = dataclasses.replace(BASE, name="true", torque_constant=0.9 * BASE.torque_constant,
                           resistance=1.2 * BASE.resistance, gearbox_efficiency=0.55)
"""The actuator the log's currents and powers come from (the analysis assumes BASE)."""


@pytest.fixture(scope="module")
def walk(robot):
    return walk_log(robot, hexaleg.gait(robot), actuator=TRUE, rate=100.0)


def _load(robot, path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the loader's notes on a simulated walk's handovers
        return hexaleg.load_motion(robot, path)


def _ratio(m):
    return {"k_t G": m.torque_constant * m.gear_ratio / (TRUE.torque_constant * TRUE.gear_ratio),
            "η": m.gearbox_efficiency / TRUE.gearbox_efficiency,
            "c": m.joule_coefficient / TRUE.joule_coefficient}


def test_a_simulated_walk_s_actuator_comes_back_within_2_percent(robot, walk, tmp_path):
    """Currents, torques and powers logged at 100 Hz through a settle and 10 cycles, averaged
    into one cycle by the loader: k_t G, η and c of the actuator that drew them within 2 %."""
    motion = _load(robot, walk.write(tmp_path / "walk.csv",
                                     ("joints", "base", "imu", "actuators")))
    measured = motion.info["measured"]
    assert {k.split("_", 1)[0] for k in measured} == {"current", "torque", "power"}
    assert all(v.shape == (motion.n_samples,) for v in measured.values())
    fits = identify_motion(robot, motion, BASE)
    assert list(fits) == ["every joint"]
    fit = fits["every joint"]
    assert fit.torque == "logged" and len(fit.joints) == 18
    for name, r in _ratio(fit.identification.motor).items():
        assert r == pytest.approx(1.0, abs=0.0005), name  # docs/motion.md: within 0.05 %
    assert fit.identification.power.relative_residual < 0.05


def test_without_logged_torques_the_analysis_torques_and_a_residual_that_says_so(
        robot, walk, tmp_path):
    """The analysis' Joule-optimal torques are not the simulation's: the constants move by up to
    ~10 % and the relative residual (≈ 13 %) says the torques do not explain the currents."""
    columns = {k: v for k, v in walk.columns.items() if not k.startswith("torque_")}
    motion = _load(robot, dataclasses.replace(walk, columns=columns).write(
        tmp_path / "walk.csv", ("joints", "base", "imu", "actuators")))
    fit = identify_motion(robot, motion, BASE)["every joint"]
    assert fit.torque == "analysis"
    worst = max(abs(r - 1.0) for r in _ratio(fit.identification.motor).values())
    assert 0.05 < worst < 0.085  # docs/motion.md: within 8 %
    assert round(100 * fit.identification.current.relative_residual) == 13  # docs: 13 %
    assert "torques from the analysis (Joule-optimal foot forces" in fit.lines()[0]


def test_a_motion_without_measurements_is_named(robot, walk200):
    with pytest.raises(InvalidParameterError, match="current_<joint>"):
        identify_motion(robot, walk200, BASE)
    with pytest.raises(InvalidParameterError, match="a Motion loaded from a log"):
        identify_motion(robot, "walk.csv", BASE)  # type: ignore[arg-type]


def test_a_measurement_column_in_mA_and_of_an_unknown_joint(robot, walk, tmp_path):
    """Units in brackets are read (mA → A); a column of a joint the robot lacks is named."""
    path = walk.write(tmp_path / "walk.csv", ("joints", "actuators"))
    text = path.read_text().split("\n", 1)
    header = text[0].replace("current_LF_coxa", "current_LF_coxa [mA]")
    rows = np.loadtxt(path, delimiter=",", skiprows=1)
    col = text[0].split(",").index("current_LF_coxa")
    rows[:, col] *= 1000.0
    milli = tmp_path / "milli.csv"
    np.savetxt(milli, rows, delimiter=",", header=header, comments="", fmt="%.9g")
    a = _load(robot, path).info["measured"]["current_LF_coxa"]
    b = _load(robot, milli).info["measured"]["current_LF_coxa"]
    np.testing.assert_allclose(b, a, rtol=1e-6, atol=1e-9)
    bad = tmp_path / "bad.csv"
    bad.write_text(path.read_text().replace("current_LF_coxa", "current_LF_knee", 1))
    with pytest.raises(hexaleg.HexalegError, match=r"current_LF_knee.*current_<joint>"):
        _load(robot, bad)


def test_the_command_prints_the_fit_and_a_motor_table_that_loads(walk, tmp_path, capsys):
    path = walk.write(tmp_path / "walk.csv", ("joints", "base", "imu", "actuators"))
    assert main(["motors", "--identify", str(path)]) == 0
    out = capsys.readouterr().out
    assert "torques from the log" in out and "from the currents: residual" in out
    table = out.split("[motor]", 1)[1].split("\n", 1)[1]
    values = dict(re.findall(r"^(\w+) = (\S+)$", table, re.M))
    fitted = motor_from_mapping({k: (v.strip('"') if k == "base" else float(v))
                                 for k, v in values.items()}, "printed [motor]")
    for name, r in _ratio(fitted).items():
        assert r == pytest.approx(1.0, abs=0.02), name


@pytest.mark.parametrize(("argv", "says"), [
    (["motors", "--robot", "solo12"], "--robot = 'solo12'; allowed: only with --identify"),
    (["motors", "AX-18A", "--identify", "x.csv"], "none with --identify"),
])
def test_identify_options_are_checked(argv, says, capsys):
    assert main(argv) == 2
    assert says in capsys.readouterr().err
