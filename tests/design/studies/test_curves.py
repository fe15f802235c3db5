"""Tests of hexaleg.design.studies.curves: the stiffness curve's points are evaluations of the gait
at that stiffness, infeasible points are recorded, and the curve's savings and best points."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg import DeadZoneSpring, SpringSet, prepare
from hexaleg.design.rules import PAPER_ALPHA, centred_spring, k_M
from hexaleg.design.studies.curves import (
    CURVE_METRICS,
    StiffnessCurve,
    curve_springs,
    stiffness_curve,
)
from hexaleg.errors import UnknownNameError


@pytest.fixture(scope="module")
def prepared(robot, walk200):
    return prepare(robot, walk200)


def test_curve_springs_fill_the_class_with_the_papers_centred_design(robot, walk200):
    own = DeadZoneSpring(stiffness=0.5, theta_k=0.1, neutral=0.55)
    springs = curve_springs(robot, walk200, SpringSet({"LF_femur": own, "LF_tibia": own}),
                            "femur")
    assert set(springs) == set(robot.joints("femur")) | {"LF_tibia"}
    assert springs["LF_femur"] == own and springs["LF_tibia"] == own  # kept as configured
    added = springs["RM_femur"]
    assert added == centred_spring(robot, walk200, "RM_femur", 0.0, alpha=PAPER_ALPHA,
                                   convention="eq14")
    assert added.stiffness == 0.0


def test_points_are_evaluations_at_that_stiffness(robot, walk200, prepared):
    springs = curve_springs(robot, walk200, SpringSet(), "femur")
    ks = np.array([0.0, 0.05, 0.1])
    metrics = ("joule", "electrical", "peak_torque")
    lines = []
    curve = stiffness_curve(prepared, springs, "femur", ks, metrics, progress=lines.append)
    assert curve.joints == robot.joints("femur") and curve.feasible.all()
    assert lines == ["stiffness curve 3/3"]
    for i, k in enumerate(ks):
        trial = SpringSet({j: s.with_stiffness(float(k)) for j, s in springs.items()})
        total = prepared.evaluate(trial).metrics["total"]
        for m in metrics:
            assert curve.totals[m][i] == pytest.approx(total[m], rel=1e-12)
    for m in metrics:  # k = 0: no spring acts, the baseline
        assert curve.baseline[m] == pytest.approx(prepared.baseline()["total"][m], rel=1e-12)
        assert curve.totals[m][0] == pytest.approx(curve.baseline[m], rel=1e-12)
        assert curve.savings(m)[0] == pytest.approx(0.0, abs=1e-9)
    for j in curve.joints:  # eq. 19 for the eq. 14 convention (α = 1.05)
        assert curve.k_M[j] == pytest.approx(k_M(robot, walk200, j, alpha=PAPER_ALPHA))


def test_unknown_metric_and_joint_are_named(robot, walk200, prepared):
    springs = curve_springs(robot, walk200, SpringSet(), "femur")
    with pytest.raises(UnknownNameError, match=r"joules.*electrical"):
        stiffness_curve(prepared, springs, "femur", np.array([0.0]), ("joules",))
    with pytest.raises(UnknownNameError, match="knee"):
        stiffness_curve(prepared, springs, "knee", np.array([0.0]), ("joule",))
    assert "electrical_bus" in CURVE_METRICS and "net_work" not in CURVE_METRICS


def test_savings_and_best_skip_infeasible_points():
    curve = StiffnessCurve(joints=("a",), stiffness=np.array([0.0, 1.0, 2.0]),
                           totals={"joule": np.array([2.0, 1.5, np.nan]),
                                   "peak_torque": np.array([1.0, 1.0, np.nan])},
                           baseline={"joule": 2.0, "peak_torque": 0.0},
                           errors=(None, None, "torque limit"), k_M={"a": 1.0})
    assert curve.feasible.tolist() == [True, True, False]
    np.testing.assert_allclose(curve.savings("joule"), [0.0, 0.25, np.nan])
    # A zero baseline: the one saving() rule (dynamics.energy) — adding a cost where there was
    # none is −inf, not "no saving"; an infeasible point stays NaN.
    np.testing.assert_array_equal(curve.savings("peak_torque"), [-np.inf, -np.inf, np.nan])
    assert curve.best("joule") == 1
    none = StiffnessCurve(joints=("a",), stiffness=np.array([1.0]),
                          totals={"joule": np.array([np.nan])}, baseline={"joule": 1.0},
                          errors=("infeasible",), k_M={"a": 1.0})
    assert none.best("joule") is None
