"""One candidate of the gait + spring co-design: its energy, its constraints, its failures."""

from __future__ import annotations

import dataclasses
import math

import pytest

from hexaleg.design.gait_evaluation import (
    Constraints,
    cost_of_transport,
    evaluate_gait,
    with_values,
)
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.params import GaitParams

GAIT = GaitParams(samples=60, speed=0.06)


def test_default_gait_meets_the_default_constraints(robot):
    point = evaluate_gait(robot, GAIT, groups=["femur", "tibia"], family="linear",
                          constraints=Constraints(), min_margin=0.0)
    assert point.error is None and point.feasible
    assert point.distance == pytest.approx(0.06)
    assert 0 < point.sprung < point.baseline  # springs of the inner program save
    assert point.per_metre == pytest.approx(point.baseline / 0.06)
    assert set(point.measures) == {"joint_speed", "static_margin", "foot_clearance",
                                   "body_clearance", "friction", "torque"}
    assert point.measures["foot_clearance"][0] == pytest.approx(0.03)
    assert 0 < point.measures["body_clearance"][0] < 0.0913  # the body's underside
    assert cost_of_transport(point.per_metre, 2.0) == pytest.approx(point.per_metre / (2.0 * 9.81))


def test_a_constraint_above_the_gait_is_a_violation_not_an_error(robot):
    point = evaluate_gait(robot, GAIT, groups=None, family="linear",
                          constraints=Constraints(min_body_clearance=0.2), min_margin=1.0)
    assert point.error is None and not point.feasible
    assert point.violation() > 0.5  # the margin (≈ 0.08 of 1 m) and the clearance
    assert point.sprung == point.baseline  # no springs asked


def test_a_gait_that_cannot_be_made_carries_its_error(robot):
    tall = dataclasses.replace(GAIT, body_height=0.5)
    point = evaluate_gait(robot, tall, groups=None, family="linear",
                          constraints=Constraints(), min_margin=0.0)
    assert point.error is not None and not point.feasible and math.isnan(point.baseline)


def test_with_values_sets_the_stride_from_the_speed():
    g = with_values(GAIT, 0.1, {"period": 2.0, "duty_factor": 0.6})
    assert g.stride == pytest.approx(0.2) and g.duty_factor == 0.6
    with pytest.raises(InvalidParameterError, match="stride_length"):
        with_values(GAIT, 0.1, {"stride_length": 2.0})


@pytest.mark.parametrize("kwargs", [{"speed_fraction": 0.0}, {"mu": -1.0},
                                    {"min_foot_clearance": 0.0}, {"torque_limits": 1},
                                    {"min_static_margin": -0.1}, {"min_body_clearance": math.nan}])
def test_bad_constraints_are_named(kwargs):
    with pytest.raises(InvalidParameterError, match=next(iter(kwargs))):
        Constraints(**kwargs)
