"""Tests of hexaleg.design.robustness (conditions) and robustness_map."""

from __future__ import annotations

import pytest

import hexaleg
from hexaleg.design.codesign import optimal_springs
from hexaleg.design.evaluator import RunSpec
from hexaleg.design.robustness import Condition, condition_gait, condition_prepared
from hexaleg.design.robustness_map import robustness_map
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.robot.payload import with_payload

RUN = RunSpec()
GAIT = RUN.gait({"samples": 100})


@pytest.fixture(scope="module")
def springs():
    return optimal_springs(condition_prepared(RUN, GAIT, Condition()), ["tibia"],
                           "linear").springs


def test_nominal_cell_is_the_design_and_payload_cells_carry_the_mass(springs):
    mp = robustness_map(RUN, GAIT, springs, {"payload": [0.0, 0.3], "mu": [0.6]})
    robot = hexaleg.load_robot()
    nominal = hexaleg.prepare(robot, hexaleg.tripod_gait(robot, GAIT))
    a = nominal.evaluate(springs)
    assert mp.saving["electrical"][0, 0] == pytest.approx(a.savings["total"]["electrical"])
    heavy = with_payload(robot, 0.3 * robot.mass)
    assert heavy.mass == pytest.approx(1.3 * robot.mass)
    b = hexaleg.prepare(heavy, hexaleg.tripod_gait(heavy, GAIT)).evaluate(springs)
    assert mp.saving["joule"][1, 0] == pytest.approx(b.savings["total"]["joule"])
    assert b.baseline["total"]["joule"] > a.baseline["total"]["joule"]
    assert (mp.status == "ok").all()


def test_conditions_scale_the_gait():
    g = condition_gait(GAIT, Condition(period=2.0, stride=0.5))
    assert g.period == 2 * GAIT.period and g.stride == pytest.approx(0.5 * GAIT.stride)
    assert Condition(period=0.5, mu=0.3).label() == "period ×0.5, μ 0.3"
    assert Condition().label() == "nominal"


def test_bad_maps_are_named(springs):
    with pytest.raises(UnknownNameError, match="payload, period, stride"):
        robustness_map(RUN, GAIT, springs, {"slope": [0.0], "mu": [0.6]})
    with pytest.raises(InvalidParameterError, match="two of"):
        robustness_map(RUN, GAIT, springs, {"mu": [0.6]})
    for values in ([], 0.6, ["slippery"], [float("nan")]):
        with pytest.raises(InvalidParameterError, match="map axis mu"):
            robustness_map(RUN, GAIT, springs, {"period": [1.0], "mu": values})
    with pytest.raises(InvalidParameterError, match="narrow the stride range"):
        robustness_map(RUN, GAIT, springs, {"stride": [8.0], "mu": [0.6]})
    with pytest.raises(InvalidParameterError, match="factor > 0"):
        Condition(period=0.0)
