"""One candidate of the gait + spring co-design: its energy, its constraints, its failures."""

from __future__ import annotations

import dataclasses
import math

import pytest

from hexaleg.design.codesign.gait_evaluation import (
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


def test_the_friction_margin_binds_the_planned_forces(robot):
    """Issue #41: with the whole cone the default gait's Joule-optimal forces use more than
    half of it somewhere; with friction_margin = 0.5 the planned forces stay within half the
    floor's cone (other forces, another energy) and the measure is against the floor's μ."""
    free = evaluate_gait(robot, GAIT, groups=None, family="linear",
                         constraints=Constraints(friction_margin=1.0), min_margin=0.0)
    half = evaluate_gait(robot, GAIT, groups=None, family="linear",
                         constraints=Constraints(friction_margin=0.5), min_margin=0.0)
    use_free, bound_free = free.measures["friction"][:2]
    use_half, bound_half = half.measures["friction"][:2]
    assert use_free > 0.5 and bound_free == pytest.approx(1.0, abs=2e-6)
    assert use_half <= 0.5 + 1e-6 and bound_half == pytest.approx(0.5, abs=2e-6) and half.feasible
    assert half.baseline != free.baseline  # the constraint moved the forces
    assert Constraints().friction_margin == 0.7
    assert Constraints(friction_margin=0.5).planning_contact().mu == pytest.approx(0.3)
    assert Constraints(friction_margin=0.5).contact().mu == 0.6


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
                                    {"friction_margin": 0.0}, {"friction_margin": 1.5},
                                    {"min_foot_clearance": 0.0}, {"torque_limits": 1},
                                    {"min_static_margin": -0.1}, {"min_body_clearance": math.nan}])
def test_bad_constraints_are_named(kwargs):
    with pytest.raises(InvalidParameterError, match=next(iter(kwargs))):
        Constraints(**kwargs)
