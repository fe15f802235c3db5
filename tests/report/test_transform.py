"""Tests of hexaleg.report.transform: the stand → sphere section against the analysis
API and the rise of potential energy."""

from __future__ import annotations

import pytest

from hexaleg.dynamics.prepare import analyze
from hexaleg.motion.transform import transform_motion
from hexaleg.robot.catalogue import DEFAULT_MOTOR


def _v(q):
    assert set(q) == {"value", "unit"}, q
    return q["value"]


def test_transform_numbers_equal_the_analysis_api(data, analysed, robot):
    """The stand → sphere section: the public API's numbers for the springs the page analyses,
    and the joints' net work equal to the rise of potential energy (both ways, springs
    conservative)."""
    springs, _ = analysed
    fold = transform_motion(robot)
    a = analyze(robot, fold, springs, motor=DEFAULT_MOTOR, objective="joule")
    section = data["transform"]
    assert set(section["totals"]) == set(a.savings["total"])
    for key, row in section["totals"].items():
        assert _v(row["with_springs"]) == pytest.approx(a.metrics["total"][key], rel=1e-12)
        assert _v(row["baseline"]) == pytest.approx(a.baseline["total"][key], rel=1e-12)
    rise = _v(section["potential_energy_rise"])
    assert _v(section["net_work"]["baseline"]) == pytest.approx(rise, rel=1e-6)
    assert rise > 0.05 and section["rest_height"] == {"value": 0.0835, "unit": "m"}
    # Springs store energy while folding, so the motors' net work is the rise plus that energy.
    stored = a.spring_energy[-1].sum() - a.spring_energy[0].sum()
    assert _v(section["net_work"]["with_springs"]) == pytest.approx(rise + stored, rel=1e-6)
