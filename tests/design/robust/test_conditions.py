"""Tests of hexaleg.design.robust.conditions: a frozen design on gaits with the period or stride
scaled."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hexaleg.design.evaluator import evaluator
from hexaleg.design.robust.conditions import (
    condition_walk,
    condition_walks,
    robustness,
    same_motion,
)
from hexaleg.errors import UnknownNameError
from hexaleg.motion.params import GaitParams
from hexaleg.scenario.condition import Condition
from hexaleg.scenario.scenario import Scenario

SAMPLES = 200
RUN = Scenario.load()


@pytest.fixture(scope="module")
def ev():
    return evaluator(RUN.with_gait({"samples": SAMPLES}))


@pytest.fixture(scope="module")
def classes(robot):
    return {c: robot.joints(c) for c in ("coxa", "femur", "tibia")}


def test_robustness_at_nominal_equals_the_design_and_varies_off_it(ev, classes):
    design = {"coxa": {"k": 0.1, "theta_k": 0.005}}
    table = robustness(RUN.replace(gait=GaitParams(samples=SAMPLES)), classes, design,
                       factors=(0.8, 1.0, 1.2))
    assert len(table) == 6 and (table["status"] == "ok").all()
    nominal = ev.row(classes, design)["saving.electrical"]
    at_one = table[table["factor"] == 1.0]["saving"]
    np.testing.assert_allclose(at_one, nominal, rtol=1e-9)
    period = table[table["parameter"] == "period"]
    np.testing.assert_allclose(period["gait value"], [0.8, 1.0, 1.2])
    assert period["saving"].nunique() == 3
    with pytest.raises(UnknownNameError, match=r"duty_factor.*period, stride_length"):
        robustness(RUN.replace(gait=GaitParams(samples=SAMPLES)), classes, design,
                   parameters=("duty_factor",))


# --------------------------------------------------------------- slope and pattern conditions

def test_uphill_the_motors_lift_the_robot_and_pay_for_it():
    """Net work over a periodic cycle is the potential energy gained, m g s sin α (the kinetic
    energy is periodic, the springs conservative), with or without the springs: the motors of a
    robot walking a stride s up a slope α lift it by s sin α — to the trapezoid rule's
    quadrature error (~1e-7 relative on the tripod, ~2e-5 on the wave at 100 samples; 3e-6 J
    on the level wave). Uphill the same
    springs cost more energy in total than on the level or downhill."""
    import math

    from hexaleg.design.robust.conditions import condition_prepared
    from hexaleg.design.search.optimal import optimal_springs
    from hexaleg.scenario.condition import Condition
    from hexaleg.units import G

    run = RUN.with_gait({"samples": 100})
    gait = run.gait
    springs = optimal_springs(condition_prepared(run, Condition()), ["tibia"],
                              "linear").springs
    for pattern, payload in ((None, 0.0), ("wave", 0.3)):
        electrical = {}
        for deg in (-15.0, 0.0, 10.0, 15.0):
            c = Condition(slope=math.radians(deg), pattern=pattern, payload=payload)
            p = condition_prepared(run, c)
            rise = gait.stride * math.sin(math.radians(deg))
            mgh = p.robot.mass * G * rise
            assert p.robot.mass == pytest.approx((1 + payload) * RUN.model.mass)
            base = p.baseline("joule")["total"]
            sprung = p.evaluate(springs, "joule").metrics["total"]
            for total in (base, sprung):
                assert total["net_work"] == pytest.approx(mgh, rel=1e-4, abs=2e-5)
            electrical[deg] = sprung["electrical"]
        assert electrical[15.0] > electrical[10.0] > electrical[0.0]
        assert electrical[15.0] > electrical[-15.0]


def test_conditions_that_walk_one_motion_share_it_and_prepare_as_alone():
    """A payload's cells at every μ walk one motion, made once (the run's own where they walk
    it), and each preparation is the one it has alone: the same baseline to the bit, the same
    reason where the gait cannot be made (out of reach; a slope the friction cannot hold, at
    the low μ only)."""
    run = RUN.with_gait({"samples": 100})
    steep = math.radians(20)
    conditions = [Condition(mu=0.6), Condition(payload=0.2, mu=0.6), Condition(),
                  Condition(payload=0.2, mu=1.0), Condition(stride=8.0),
                  Condition(slope=steep, mu=0.6), Condition(slope=steep, mu=0.3)]
    groups = same_motion(run, conditions)
    assert groups == [[0, 2], [1, 3], [4], [5, 6]]
    nominal = run.motion()
    for g in groups:
        walks = list(condition_walks(run, [conditions[i] for i in g], nominal))
        for i, walked in zip(g, walks, strict=True):
            alone = condition_walk(run, conditions[i])
            if isinstance(alone, str):
                assert walked == alone
                continue
            assert not isinstance(walked, str)
            assert walked.motion is walks[0].motion  # type: ignore[union-attr]
            assert np.array_equal(walked.motion.q, alone.motion.q)
            assert walked.baseline("joule")["total"] == alone.baseline("joule")["total"]
    assert next(condition_walks(run, [conditions[0]], nominal)).motion is nominal  # type: ignore
    assert isinstance(next(condition_walks(run, [conditions[4]])), str)
    held, slid = list(condition_walks(run, [conditions[5], conditions[6]]))
    assert not isinstance(held, str) and isinstance(slid, str) and "inclined" in slid
