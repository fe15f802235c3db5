"""Tests of hexaleg.design.robust.conditions (conditions) and robustness_map."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import hexaleg
from hexaleg.design.robust.conditions import condition_prepared, condition_walk
from hexaleg.design.robust.maps import robot_patterns, robustness_map
from hexaleg.design.search.optimal import optimal_springs
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.robot.payload import with_payload
from hexaleg.scenario.condition import Condition, condition_gait
from hexaleg.scenario.scenario import Scenario

RUN = Scenario.load().with_gait({"samples": 100})
GAIT = RUN.gait


@pytest.fixture(scope="module")
def springs():
    return optimal_springs(condition_prepared(RUN, Condition()), ["tibia"],
                           "linear").springs


def test_nominal_cell_is_the_design_and_payload_cells_carry_the_mass(springs):
    mp = robustness_map(RUN, springs, {"payload": [0.0, 0.3], "mu": [0.6]})
    robot = hexaleg.load()
    nominal = hexaleg.prepare(robot, hexaleg.gait(robot, GAIT))
    a = nominal.evaluate(springs)
    assert mp.saving["electrical"][0, 0] == pytest.approx(a.savings["total"]["electrical"])
    heavy = with_payload(robot, 0.3 * robot.mass)
    assert heavy.mass == pytest.approx(1.3 * robot.mass)
    b = hexaleg.prepare(heavy, hexaleg.gait(heavy, GAIT)).evaluate(springs)
    assert mp.saving["joule"][1, 0] == pytest.approx(b.savings["total"]["joule"])
    assert b.baseline["total"]["joule"] > a.baseline["total"]["joule"]
    assert (mp.status == "ok").all()


def test_conditions_scale_the_gait():
    g = condition_gait(GAIT, Condition(period=2.0, stride=0.5))
    assert g.period == 2 * GAIT.period and g.stride == pytest.approx(0.5 * GAIT.stride)
    assert Condition(period=0.5, mu=0.3).label() == "period ×0.5, μ 0.3"
    assert Condition().label() == "nominal"


def test_bad_maps_are_named(springs):
    with pytest.raises(UnknownNameError, match="mu, pattern, payload, period, slope, stride"):
        robustness_map(RUN, springs, {"heading": [0.0], "mu": [0.6]})
    with pytest.raises(InvalidParameterError, match="two of"):
        robustness_map(RUN, springs, {"mu": [0.6]})
    for values in ([], 0.6, ["slippery"], [float("nan")]):
        with pytest.raises(InvalidParameterError, match="map axis mu"):
            robustness_map(RUN, springs, {"period": [1.0], "mu": values})
    with pytest.raises(InvalidParameterError, match="factor > 0"):
        Condition(period=0.0)


def test_bad_slopes_and_patterns_are_named_before_any_cell_runs(springs):
    with pytest.raises(InvalidParameterError, match=r"invalid slope = 1\.6.*\(−π/2, π/2\)"):
        robustness_map(RUN, springs, {"slope": [0.0, 1.6], "pattern": ["tripod"]})
    with pytest.raises(UnknownNameError, match=r"unknown gait pattern 'gallop'; .* ripple, "
                                               r"tripod, trot, wave"):
        robustness_map(RUN, springs, {"slope": [0.0], "pattern": ["wave", "gallop"]})
    for values in ("wave", [], None):
        with pytest.raises(InvalidParameterError, match="map axis pattern"):
            robustness_map(RUN, springs, {"slope": [0.0], "pattern": values})
    with pytest.raises(InvalidParameterError, match="3 \\+ 3 legs: tripod, ripple, wave"):
        robustness_map(RUN, springs, {"slope": [0.0], "pattern": ["crawl"]})


def test_slope_pattern_cells_equal_a_fresh_public_analysis(springs):
    """Each cell is the springs on that slope and pattern analysed afresh with the public API
    (the pattern at its own duty factor); the tripod on the level is the nominal gait."""
    slopes = [math.radians(-10), 0.0, math.radians(12)]
    mp = robustness_map(RUN, springs, {"slope": slopes, "pattern": ["tripod", "wave"]})
    assert mp.axes == ("slope", "pattern") and list(mp.values[1]) == ["tripod", "wave"]
    assert all(type(v) is str for v in mp.values[1])
    assert (mp.status == "ok").all()
    robot = hexaleg.load()
    for i, j in ((0, 1), (2, 1), (2, 0)):
        params = hexaleg.GaitParams(samples=100, pattern=str(mp.values[1][j]), slope=slopes[i])
        assert params.duty_factor == (5 / 6 if j else 0.5)
        fresh = hexaleg.prepare(robot, hexaleg.gait(robot, params)).evaluate(springs)
        for m in ("electrical", "joule"):
            assert mp.saving[m][i, j] == pytest.approx(fresh.savings["total"][m], rel=1e-9)
        assert mp.condition(i, j) == Condition(slope=slopes[i], pattern=params.pattern)
    nominal = hexaleg.prepare(robot, hexaleg.gait(robot, GAIT)).evaluate(springs)
    assert mp.saving["joule"][1, 0] == pytest.approx(nominal.savings["total"]["joule"],
                                                     rel=1e-12)
    assert mp.saving["joule"][0, 1] != pytest.approx(mp.saving["joule"][0, 0], rel=1e-3)
    worst, where = mp.worst("electrical")
    assert worst == mp.saving["electrical"].min() and where is not None
    assert where.label().startswith("slope ")


def test_a_condition_the_robot_cannot_walk_is_a_cell_with_its_reason(springs):
    """Out of reach (stride ×8) and a slope steeper than the friction holds are cells outside
    the envelope (NaN, left out of the worst case), not the end of the map;
    condition_prepared alone still names the condition and what to change."""
    mp = robustness_map(RUN, springs, {"stride": [1.0, 8.0], "mu": [0.6]})
    assert mp.status[0, 0] == "ok"
    assert mp.status[1, 0].startswith("no gait: GaitReachError: leg ")
    assert np.isnan(mp.saving["electrical"][1, 0]) and np.isnan(mp.saving["joule"][1, 0])
    assert mp.worst("joule")[1] == Condition(mu=0.6)
    steep = robustness_map(RUN, springs, {"slope": [math.radians(20)], "mu": [0.6, 0.3]})
    assert steep.status[0, 0] == "ok"
    assert steep.status[0, 1].startswith("no gait: InfeasibleForcesError: the ground is "
                                         "inclined by γ = 20°")
    assert np.isnan(steep.saving["electrical"][0, 1])
    with pytest.raises(InvalidParameterError, match="narrow the stride range"):
        condition_prepared(RUN, Condition(stride=8.0))
    with pytest.raises(InvalidParameterError, match="narrow the mu and slope range"):
        condition_prepared(RUN, Condition(mu=0.3, slope=math.radians(20)))


def test_a_crawl_without_static_margin_is_a_cell():
    """Solo-12's crawl at its own period keeps no static margin: a StaticMarginError cell."""
    run = Scenario.load("solo12").with_gait({"samples": 100})
    assert robot_patterns(run.model, run.gait) == ("trot", "crawl", "pace")
    reason = condition_walk(run, Condition(pattern="crawl"))
    assert isinstance(reason, str) and reason.startswith("no gait: StaticMarginError: ")


def test_robot_patterns_put_the_nominal_first():
    robot = hexaleg.load()
    assert robot_patterns(robot, GAIT) == ("tripod", "ripple", "wave")
    assert robot_patterns(robot, GAIT.updated({"pattern": "wave"})) == ("wave", "tripod",
                                                                          "ripple")
    swapped = dataclasses.replace(GAIT, groups=GAIT.groups[::-1])  # the same tripod, half later
    assert robot_patterns(robot, swapped)[0] == "tripod"
    crawl_like = GAIT.updated({"phases": [0.0, 0.1, 0.2, 0.3, 0.4, 0.5]})
    assert robot_patterns(robot, crawl_like) == ("tripod", "ripple", "wave")
