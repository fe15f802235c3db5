"""Tests of hexaleg.scenario.condition: a set of operating conditions, its labels and checks, and
the nominal gait it makes."""

from __future__ import annotations

import math

import pytest

from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.motion.params import GaitParams
from hexaleg.scenario.condition import CONDITIONS, Condition, condition_gait, degrees

SAMPLES = 200


def test_slope_and_pattern_conditions_are_labelled_and_checked():
    c = Condition(period=0.5, slope=math.radians(15), pattern="wave")
    assert c.label() == "period ×0.5, slope +15°, wave"
    assert Condition(slope=math.radians(-7.5)).label() == "slope -7.5°"
    assert Condition(pattern="ripple").short_label() == "ripple"
    assert Condition(slope=math.radians(15)).short_label() == "α+15°"
    for bad in (math.pi / 2, -2.0, float("nan")):
        with pytest.raises(InvalidParameterError, match=r"slope.*\(−π/2, π/2\)"):
            Condition(slope=bad)
    with pytest.raises(UnknownNameError, match="crawl, pace, ripple, tripod, trot, wave"):
        Condition(pattern="gallop")


def test_the_nominal_condition_is_labelled_nominal_and_every_field_is_a_condition():
    assert Condition().label() == "nominal" and Condition().short_label() == "nominal"
    assert Condition(period=0.5, payload=0.25, mu=0.3).label() == "period ×0.5, payload 25 %, μ 0.3"
    assert set(CONDITIONS) == {"period", "stride", "payload", "mu", "slope", "pattern"}
    assert degrees(math.radians(7.5)) == "+7.5°"
    for bad in ({"period": 0.0}, {"stride": -1.0}, {"payload": -0.1}, {"mu": 0.0}):
        with pytest.raises(InvalidParameterError):
            Condition(**bad)


def test_condition_gait_adds_the_slope_and_takes_the_patterns_duty_factor():
    nominal = GaitParams(samples=SAMPLES, duty_factor=0.55, slope=0.05)
    g = condition_gait(nominal, Condition(slope=0.1, pattern="ripple", stride=2.0))
    assert g.slope == pytest.approx(0.15) and g.pattern == "ripple"
    assert g.duty_factor == pytest.approx(2 / 3)  # ripple's β₀, not the nominal 0.55
    assert g == nominal.updated({"pattern": "ripple", "slope": 0.05 + 0.1,
                                 "stride_length": 2 * nominal.stride_length})
    same = condition_gait(nominal, Condition())
    assert same == nominal  # the nominal condition changes nothing
    assert condition_gait(nominal, Condition(slope=math.radians(5))).duty_factor == 0.55


def test_condition_gait_scales_the_period_and_stride():
    nominal = GaitParams(samples=SAMPLES)
    g = condition_gait(nominal, Condition(period=0.5, stride=1.5))
    assert g.period == pytest.approx(0.5 * nominal.period)
    assert g.stride_length == pytest.approx(1.5 * nominal.stride_length)
