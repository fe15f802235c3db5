"""Tests of hexaleg.design.robust.conditions: a frozen design on gaits with the period or stride
scaled."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.design.evaluator import RunSpec, evaluator
from hexaleg.design.robust.conditions import robustness
from hexaleg.errors import UnknownNameError
from hexaleg.motion.params import GaitParams

SAMPLES = 200
RUN = RunSpec()


@pytest.fixture(scope="module")
def ev():
    return evaluator(RUN, {"samples": SAMPLES})


@pytest.fixture(scope="module")
def classes(robot):
    return {c: robot.joints(c) for c in ("coxa", "femur", "tibia")}


def test_robustness_at_nominal_equals_the_design_and_varies_off_it(ev, classes):
    design = {"coxa": {"k": 0.1, "theta_k": 0.005}}
    table = robustness(RUN, GaitParams(samples=SAMPLES), classes, design,
                       factors=(0.8, 1.0, 1.2))
    assert len(table) == 6 and (table["status"] == "ok").all()
    nominal = ev.row(classes, design)["saving.electrical"]
    at_one = table[table["factor"] == 1.0]["saving"]
    np.testing.assert_allclose(at_one, nominal, rtol=1e-9)
    period = table[table["parameter"] == "period"]
    np.testing.assert_allclose(period["gait value"], [0.8, 1.0, 1.2])
    assert period["saving"].nunique() == 3
    with pytest.raises(UnknownNameError, match=r"duty_factor.*period, stride_length"):
        robustness(RUN, GaitParams(samples=SAMPLES), classes, design, parameters=("duty_factor",))


# --------------------------------------------------------------- slope and pattern conditions

def test_slope_and_pattern_conditions_are_labelled_and_checked():
    import math

    from hexaleg.design.robust.conditions import Condition
    from hexaleg.errors import InvalidParameterError

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


def test_condition_gait_adds_the_slope_and_takes_the_patterns_duty_factor():
    import math

    from hexaleg.design.robust.conditions import Condition, condition_gait

    nominal = GaitParams(samples=SAMPLES, duty_factor=0.55, slope=0.05)
    g = condition_gait(nominal, Condition(slope=0.1, pattern="ripple", stride=2.0))
    assert g.slope == pytest.approx(0.15) and g.pattern == "ripple"
    assert g.duty_factor == pytest.approx(2 / 3)  # ripple's β₀, not the nominal 0.55
    assert g == nominal.updated({"pattern": "ripple", "slope": 0.05 + 0.1,
                                 "stride_length": 2 * nominal.stride_length})
    same = condition_gait(nominal, Condition())
    assert same == nominal  # the nominal condition changes nothing
    assert condition_gait(nominal, Condition(slope=math.radians(5))).duty_factor == 0.55


def test_uphill_the_motors_lift_the_robot_and_pay_for_it():
    """Net work over a periodic cycle is the potential energy gained, m g s sin α (the kinetic
    energy is periodic, the springs conservative), with or without the springs: the motors of a
    robot walking a stride s up a slope α lift it by s sin α — to the trapezoid rule's
    quadrature error (~1e-7 relative on the tripod, ~2e-5 on the wave at 100 samples; 3e-6 J
    on the level wave). Uphill the same
    springs cost more energy in total than on the level or downhill."""
    import math

    from hexaleg.design.robust.conditions import Condition, condition_prepared
    from hexaleg.design.search.optimal import optimal_springs
    from hexaleg.units import G

    gait = RUN.gait({"samples": 100})
    springs = optimal_springs(condition_prepared(RUN, gait, Condition()), ["tibia"],
                              "linear").springs
    for pattern, payload in ((None, 0.0), ("wave", 0.3)):
        electrical = {}
        for deg in (-15.0, 0.0, 10.0, 15.0):
            c = Condition(slope=math.radians(deg), pattern=pattern, payload=payload)
            p = condition_prepared(RUN, gait, c)
            rise = gait.stride * math.sin(math.radians(deg))
            mgh = p.robot.mass * G * rise
            assert p.robot.mass == pytest.approx((1 + payload) * RUN.load().mass)
            base = p.baseline("joule")["total"]
            sprung = p.evaluate(springs, "joule").metrics["total"]
            for total in (base, sprung):
                assert total["net_work"] == pytest.approx(mgh, rel=1e-4, abs=2e-5)
            electrical[deg] = sprung["electrical"]
        assert electrical[15.0] > electrical[10.0] > electrical[0.0]
        assert electrical[15.0] > electrical[-15.0]
