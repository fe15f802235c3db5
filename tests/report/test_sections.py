"""Tests of hexaleg.report.sections: the numbers of report.json's sections against the
analysis API computed here independently (the ``independent`` fixture)."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.design.rules import k_M
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import analyze
from hexaleg.robot.catalogue import DEFAULT_MOTOR


def _v(q):
    assert set(q) == {"value", "unit"}, q
    return q["value"]


def test_energy_numbers_equal_the_analysis_api(data, analysed, robot):
    """The page's energies are those of the springs it says it analyses (the answer's),
    recomputed from their laws in report.json through the public API."""
    springs, a = analysed
    assert data["springs"]["design"] == "answer" and data["design"]["origin"] == "quick"
    assert {s["family"] for s in data["springs"]["joints"].values()} == {"linear"}
    assert set(springs) == set(robot.joints("femur")) | set(robot.joints("tibia"))
    totals = data["energy"]["totals"]
    assert set(totals) == set(a.savings["total"])
    for key, row in totals.items():
        assert _v(row["with_springs"]) == pytest.approx(a.metrics["total"][key], rel=1e-12)
        assert _v(row["baseline"]) == pytest.approx(a.baseline["total"][key], rel=1e-12)
        assert _v(row["saving"]) == pytest.approx(100 * a.savings["total"][key], rel=1e-9,
                                                  abs=1e-12)
        assert row["saving"]["unit"] == "%"
        assert row["with_springs"]["unit"] == ("N·m" if "torque" in key else "J")
    for key, joints in data["energy"]["joints"].items():
        for j, name in enumerate(robot.joint_names):
            assert _v(joints[name]["with_springs"]) == pytest.approx(
                a.metrics["joint"][key][j], rel=1e-12, abs=1e-15)
            assert _v(joints[name]["baseline"]) == pytest.approx(
                a.baseline["joint"][key][j], rel=1e-12, abs=1e-15)
    cot = data["cost_of_transport"]["metrics"]
    assert set(cot) == set(a.metrics["cost_of_transport"])
    for key, row in cot.items():
        assert _v(row["with_springs"]) == pytest.approx(a.metrics["cost_of_transport"][key])
        assert _v(row["baseline"]) == pytest.approx(a.baseline["cost_of_transport"][key])
    assert _v(data["cost_of_transport"]["distance"]) == pytest.approx(0.06)


def test_the_reference_is_the_paper_design_on_the_femurs(data, independent, robot):
    """The reference section: the paper's design (eq. 19 k_M, α = 1.05, centred dead zone) on
    the femurs, its energies those of the public API with the same springs."""
    motion, springs, a = independent
    ref = data["reference"]
    assert ref["design"] == "paper"
    assert set(ref["joints"]) == set(springs) == set(robot.joints("femur"))
    for name, s in springs.items():
        row = ref["joints"][name]
        assert _v(row["stiffness"]) == pytest.approx(s.stiffness)
        assert _v(row["k_M"]) == pytest.approx(k_M(robot, motion, name))  # eq. 19, α = 1.05
        assert _v(row["stiffness_over_k_M"]) == pytest.approx(1.0)
        assert _v(row["theta_plus"]) == pytest.approx(s.theta_k)
    assert set(ref["energy"]) == set(a.savings["total"])
    for key, row in ref["energy"].items():
        assert _v(row["with_springs"]) == pytest.approx(a.metrics["total"][key], rel=1e-12)
        assert _v(row["saving"]) == pytest.approx(100 * a.savings["total"][key], rel=1e-9,
                                                  abs=1e-12)
    assert _v(ref["energy"]["electrical"]["saving"]) < 0  # the paper's design costs here


def test_joint_force_and_spring_numbers_equal_the_api(data, analysed, walk200, robot):
    springs, a = analysed
    motion = walk200
    for j, name in enumerate(robot.joint_names):
        row = data["joints"][name]
        assert _v(row["peak_motor_torque"]) == pytest.approx(np.abs(a.tau_motor[:, j]).max())
        assert _v(row["peak_spring_torque"]) == pytest.approx(np.abs(a.tau_spring[:, j]).max(),
                                                              abs=1e-15)
        assert _v(row["angle_min"]) == pytest.approx(motion.q[:, 7 + j].min())
        assert _v(row["peak_power"]) == pytest.approx(np.abs(a.power[:, j]).max())
    for name in springs:
        row = data["springs"]["joints"][name]
        tau = np.abs(a.tau_spring[:, robot.column(name)])
        assert _v(row["peak_torque"]) == pytest.approx(tau.max(), rel=1e-12)
        assert _v(row["engaged_fraction"]) == 1.0  # a linear spring pushes all the time
    mu = ContactParams().mu
    stance = motion.stance.astype(bool)
    for i, leg in enumerate(robot.leg_names):
        f = a.forces[:, i]
        ft, fn = np.hypot(f[:, 0], f[:, 1]), f[:, 2]
        use = np.where(stance[:, i] & (fn > 0), ft / (mu * np.where(fn > 0, fn, 1.0)), 0.0)
        row = data["forces"]["legs"][leg]
        assert _v(row["peak_normal_force"]) == pytest.approx(fn.max())
        assert _v(row["peak_friction_usage"]) == pytest.approx(use.max())



def test_joint_rows_compare_with_the_baseline(data, independent, robot):
    """The per-joint peaks without springs are those of the same gait analysed without any."""
    motion, _, _ = independent
    base = analyze(robot, motion, None, motor=DEFAULT_MOTOR, objective="joule")
    for j, name in enumerate(robot.joint_names):
        row = data["joints"][name]
        assert _v(row["peak_motor_torque_baseline"]) == pytest.approx(
            np.abs(base.tau_motor[:, j]).max())
        assert _v(row["peak_power_baseline"]) == pytest.approx(np.abs(base.power[:, j]).max())


def test_notes_carry_the_sanity_findings(walk):
    from hexaleg.report.sections import notes_section
    from hexaleg.robot.sanity import Finding

    finding = Finding("joint_speed", "joint LF_femur", 9.0, "rad/s", "≤ 6 rad/s",
                      "slow the gait: period ≥ 1.5 s")
    notes = notes_section(("given",), walk, [finding])
    assert notes == ["given", f"check {finding.message}"]
    assert "LF_femur" in notes[1] and "period ≥ 1.5 s" in notes[1]
