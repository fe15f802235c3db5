"""Tests of hexaleg.design.robustness: a frozen design on gaits with the period or stride scaled."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.design.evaluator import RunSpec, evaluator
from hexaleg.design.robustness import robustness
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
