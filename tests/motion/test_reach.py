"""Tests of hexaleg.motion.reach: the pieces of the IK-failure diagnosis (the gait-level messages
and suggestions are tested in test_legged.py): the stretched-leg test, the rounding towards the
harmless value, the bounded number of gaits generated, and the error's data surviving pickling."""

from __future__ import annotations

import dataclasses
import math
import pickle

import numpy as np
import pytest

from hexaleg.errors import GaitReachError, UnreachableTargetError
from hexaleg.motion import reach
from hexaleg.motion.legged import tripod_gait
from hexaleg.motion.params import GaitParams


def test_a_straight_leg_is_at_the_workspace_edge_and_the_stand_is_not(robot):
    ratio, sigma, axis = reach._stiffness(robot, 0)
    assert ratio > 0.3  # the stand: knee bent 110°
    straight = dataclasses.replace(robot, poses={**robot.poses, "stand": robot.pose("zero")})
    ratio, sigma, axis = reach._stiffness(straight, 0)
    assert ratio < reach.STRETCHED and sigma[-1] < 1e-12
    # The foot of a straight leg cannot move along the leg: radially, at the hip's yaw (30°).
    assert np.allclose(axis, [math.cos(math.pi / 6), math.sin(math.pi / 6), 0.0], atol=1e-9)


@pytest.mark.parametrize(("value", "toward", "expected"),
                         [(0.2634, 0.0, 0.26), (0.2634, 1.0, 0.27), (0.01234, 0.0913, 0.013),
                          (0.0, 0.0, 0.0), (3.456, 0.0, 3.4)])
def test_suggestions_round_to_two_digits_towards_the_harmless_value(value, toward, expected):
    assert reach._round_toward(value, toward) == expected


def test_the_search_generates_at_most_a_few_gaits(robot, monkeypatch):
    """A verifier that never succeeds: the search gives up after VERIFICATIONS gaits, and the
    message says no single parameter was found."""
    calls = []
    real = reach.explain

    def never(robot, gait, error, leg, t, stance, targets, verify):
        def counted(other):
            calls.append(other)
            return False
        return real(robot, gait, error, leg, t, stance, targets, counted)

    monkeypatch.setattr("hexaleg.motion.legged.explain", never)
    with pytest.raises(GaitReachError, match="No single gait parameter") as err:
        tripod_gait(robot, GaitParams(step_height=0.3, samples=100))
    # the single parameters' gaits, then the step height and stride scaled together
    assert 1 <= len(calls) <= 2 * reach.VERIFICATIONS and err.value.suggestion == {}


def test_where_no_single_parameter_works_the_step_height_and_stride_together_are_named(
        robot, monkeypatch):
    """A gait that generates only with both the step height and the stride shorter (as
    Centauro's: its swing too high for a front hip, its stride too long for a hind hip's yaw)
    is refused naming both values, which were checked by generating the gait with them; the
    sized defaults take such a pair (hexaleg.motion.scaling reads ``suggestion``)."""
    real = reach.explain
    high = GaitParams(step_height=0.3, samples=100)

    def both(robot, gait, error, leg, t, stance, targets, verify):
        def shorter(other):
            return (other.step_height < gait.step_height
                    and other.stride_length < gait.stride_length and verify(other))
        return real(robot, gait, error, leg, t, stance, targets, shorter)

    monkeypatch.setattr("hexaleg.motion.legged.explain", both)
    with pytest.raises(GaitReachError, match="No single gait parameter") as err:
        tripod_gait(robot, high)
    fix = err.value.suggestion
    assert set(fix) == {"step_height", "stride_length"}
    assert fix["step_height"] < high.step_height and fix["stride_length"] < high.stride_length
    assert (f"step_height = {fix['step_height']:g} m and stride_length = "
            f"{fix['stride_length']:g} m together would work") in str(err.value)
    monkeypatch.undo()
    tripod_gait(robot, dataclasses.replace(high, **fix))  # it does


def test_the_error_keeps_its_data_through_pickling(robot):
    """Sweeps run gaits in process pools: the error and its fields cross process boundaries."""
    with pytest.raises(GaitReachError) as err:
        tripod_gait(robot, GaitParams(step_height=0.3, samples=100))
    again = pickle.loads(pickle.dumps(err.value))
    assert isinstance(again, UnreachableTargetError) and str(again) == str(err.value)
    for field in ("leg", "t", "index", "target", "distance", "phase", "parameter", "value",
                  "suggestion"):
        assert getattr(again, field) == getattr(err.value, field), field
