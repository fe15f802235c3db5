"""Tests of hexaleg.design.evaluator: a design's metrics agree with the core analysis, physical
invariants of the spring designs (no spring, never-engaged spring, quadratic Joule loss), dead-zone
fractions per joint, and the per-process evaluator cache."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.design.evaluator import METRICS, SAVING_METRICS, clear_cache, evaluator
from hexaleg.dynamics.inertia import joint_range
from hexaleg.dynamics.prepare import analyze
from hexaleg.errors import UnknownNameError
from hexaleg.robot.springs import DeadZoneSpring
from hexaleg.scenario.scenario import Scenario

SAMPLES = 200
RUN = Scenario.load()


@pytest.fixture(scope="module")
def ev():
    return evaluator(RUN.with_gait({"samples": SAMPLES}))


@pytest.fixture(scope="module")
def classes(robot):
    return {c: robot.joints(c) for c in ("coxa", "femur", "tibia")}


def test_row_equals_fresh_analysis_of_the_centred_design(ev, classes):
    """A sweep point's metrics are those of analyze() with the same springs, neutral at the centre
    of each joint's range of motion plus the offset."""
    design = {"femur": {"k": 0.3, "theta_k": 0.04, "offset": -0.05},
              "tibia": {"k": 0.2, "k_minus": 0.5, "theta_minus": -0.03, "theta_plus": 0.08}}
    row = ev.row(classes, design)
    springs = {}
    for j in classes["femur"]:
        lo, hi = joint_range(ev.robot, ev.motion, j)
        springs[j] = DeadZoneSpring(0.3, theta_k=0.04, neutral=(lo + hi) / 2 - 0.05)
    for j in classes["tibia"]:
        lo, hi = joint_range(ev.robot, ev.motion, j)
        springs[j] = DeadZoneSpring(0.2, theta_minus=-0.03, theta_plus=0.08, stiffness_minus=0.5,
                                    neutral=(lo + hi) / 2)
    ref = analyze(ev.robot, ev.motion, springs)
    assert row["status"] == "ok"
    for key in METRICS:
        assert row[key] == pytest.approx(ref.metrics["total"][key], rel=1e-12, abs=1e-15)
        assert row[f"baseline.{key}"] == ref.baseline["total"][key]
    for key in SAVING_METRICS:
        assert row[f"saving.{key}"] == pytest.approx(ref.savings["total"][key], rel=1e-10,
                                                     abs=1e-13)
    # the cached torque basis reproduces the springs' own torques
    tau = ev.spring_torques(classes, design)
    np.testing.assert_allclose(tau, ref.tau_spring, rtol=1e-14, atol=1e-15)


def test_no_spring_and_never_engaged_spring_save_nothing(ev, classes):
    """k = 0, or a dead zone wider than the joint's whole motion, leaves the gait's energy as it
    is: every metric equals the baseline and every saving is exactly 0."""
    wide = 1.01 * max(ev.half_range[j] for j in classes["femur"])
    for design in ({"femur": {"k": 0.0, "theta_k": 0.05}}, {"femur": {"k": 5.0, "theta_k": wide}}):
        row = ev.row(classes, design)
        for key in METRICS:
            assert row[key] == pytest.approx(row[f"baseline.{key}"], rel=1e-13, abs=1e-16)
        for key in SAVING_METRICS:
            assert abs(row[f"saving.{key}"]) < 1e-12


def test_joule_loss_is_quadratic_in_stiffness(ev, classes):
    """With the force program on its unconstrained branch, motor torque is affine in k for a fixed
    dead zone, so the Joule loss ∫ c τ² is exactly quadratic in k: third differences vanish."""
    ks = [0.0, 0.1, 0.2, 0.3]
    joule = [ev.metrics(classes, {"coxa": {"k": k, "theta_k": 0.01}})["total"]["joule"]
             for k in ks]
    third = joule[3] - 3 * joule[2] + 3 * joule[1] - joule[0]
    assert abs(third) < 1e-12 * joule[0]
    assert joule[1] != joule[0]  # the spring does act


def test_dead_zone_fraction_scales_with_each_joints_range(ev, classes):
    design = {"tibia": {"k": 0.5, "dead_zone": 0.4}}
    springs = ev.springs(classes, design)
    for j in classes["tibia"]:
        assert springs[j].theta_k == pytest.approx(0.4 * ev.half_range[j])
        assert springs[j].neutral == pytest.approx(ev.centre[j])


def test_clear_cache_forgets_built_evaluators():
    gait = {"samples": 40}
    first = evaluator(Scenario.load().with_gait(gait))
    assert evaluator(Scenario.load().with_gait(gait)) is first  # built once per process
    clear_cache()
    again = evaluator(Scenario.load().with_gait(gait))
    assert again is not first and evaluator(Scenario.load().with_gait(gait)) is again
    assert again.baseline["total"]["electrical"] == first.baseline["total"]["electrical"]


def test_gait_overrides_on_the_robots_gait():
    assert Scenario.load().with_gait({"samples": 40, "period": 2.0}).gait.period == 2.0
    with pytest.raises(UnknownNameError, match="duty_factor"):  # lists the fields
        Scenario.load().with_gait({"period_s": 2.0})


def test_the_run_is_a_scenario():
    """The evaluator takes the run whole; anything else is named, not an AttributeError."""
    from hexaleg.errors import HexalegError

    for bad in (None, {"samples": 40}):
        with pytest.raises(HexalegError, match=r"evaluator\(run=…\)"):
            evaluator(bad)
