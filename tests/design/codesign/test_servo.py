"""The servo-aware choice of the co-designed gait (issue #41): the search's finalists, simulated
under the servo the robot runs, the least simulated J/m under the worse servo chosen, a finalist
that does not walk never chosen."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from hexaleg.design.codesign.build import codesign_settings
from hexaleg.design.codesign.gait_evaluation import GaitPoint
from hexaleg.design.codesign.gait_search import FINALISTS, SPACING, finalists
from hexaleg.design.codesign.servo import TIE, Screened, choose
from hexaleg.errors import ConfigError, UnknownNameError
from hexaleg.motion.params import GaitParams


def _point(duty: float, per_metre: float = 10.0, error: str | None = None) -> GaitPoint:
    return GaitPoint(GaitParams(duty_factor=duty), 1.0, 2 * per_metre, per_metre, error=error)


def _screened(duty: float, ff: float | None, pos: float | None) -> Screened:
    per = {"feedforward": ff, "position": pos}
    return Screened(_point(duty), per, {k: "walks" if v is not None else "fell"
                                        for k, v in per.items()})


def test_the_least_simulated_energy_under_the_worse_servo_is_chosen():
    """The search's best (least predicted, least under feedforward) loses to a gait whose worse
    servo draws less: the position-only servo decides."""
    rows = (_screened(0.79, 10.6, 13.7), _screened(0.76, 11.3, 13.2), _screened(0.70, 12.6, 13.6))
    assert rows[1].worst == 13.2
    assert choose(rows) is rows[1]
    assert choose([dataclasses.replace(r, per_metre={"feedforward": r.per_metre["feedforward"]})
                   for r in rows]).point is rows[0].point  # feedforward alone: the search's


def test_a_finalist_that_does_not_walk_is_never_chosen():
    fell = _screened(0.79, 5.0, None)  # the best by far under feedforward, falls under position
    no_numbers = Screened(_point(0.8, error="no admissible forces"), {}, {})
    walks = _screened(0.76, 11.3, 13.2)
    assert fell.worst == no_numbers.worst == np.inf
    assert choose([fell, no_numbers, walks]) is walks
    assert choose([fell, no_numbers]) is None


def test_ties_go_to_the_search_s_order():
    a, b = _screened(0.79, 11.0, 12.0), _screened(0.76, 12.0, 11.0)
    assert choose([a, b]) is a and choose([b, a]) is b
    # within the simulation's rounding of the least: still the first; beyond it: the least
    c = _screened(0.7, 12.0 * (1 - TIE / 2), 1.0)
    d = _screened(0.7, 12.0 * (1 - 2 * TIE), 1.0)
    assert choose([a, c]) is a and choose([a, d]) is d


def test_finalists_are_the_best_distinct_feasible_gaits_whatever_the_evaluation_order():
    """Near-copies of a better point (closer than SPACING), infeasible points and points past
    FINALISTS are left out; the order is the value's, ties by the scaled point, not the
    insertion's."""
    cache = {(0.5, 0.5): (10.0, _point(0.5)),
             (0.5, 0.5 + SPACING / 2): (10.1, _point(0.51)),  # a near-copy of the best
             (0.1, 0.1): (9.0, _point(0.1, error="out of reach")),  # infeasible
             (0.9, 0.9): (11.0, _point(0.9)), (0.2, 0.9): (11.0, _point(0.2))}
    cache.update({(1.01 * SPACING * i, 0.0): (12.0 + i, _point(0.3)) for i in range(FINALISTS)})
    got = finalists(cache)
    assert len(got) == FINALISTS
    assert got[:3] == (cache[(0.5, 0.5)][1], cache[(0.2, 0.9)][1], cache[(0.9, 0.9)][1])
    assert finalists(dict(reversed(list(cache.items())))) == got


def test_the_servo_is_named_once():
    assert codesign_settings({"controller": "position"})["controller"] == "position"
    with pytest.raises(ConfigError, match=r"\[codesign\] controller"):
        codesign_settings({"design": {"controller": "position"}})


def test_an_unknown_servo_is_refused_by_name():
    from hexaleg.design.codesign.build import codesign

    with pytest.raises(UnknownNameError, match="feedforward"):
        codesign(controller="torque")
