"""Tests of hexaleg.design.chain.ranking: candidates simulated under the servo the robot runs,
the best simulated buildable one chosen, a lost saving flagged."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from hexaleg.design.chain.ranking import (
    FLAG_FRACTION,
    Simulated,
    best_simulated,
    simulate_candidates,
)
from hexaleg.design.robust.conditions import condition_prepared
from hexaleg.scenario.condition import Condition


def _row(candidate, predicted, simulated, net, controller="position"):
    return Simulated(candidate, controller, predicted, simulated,
                     "walks" if simulated is not None else "fell", net)


def test_a_saving_under_half_the_prediction_or_a_fall_is_flagged(design_written):
    c = design_written[0].result.recommended
    assert not _row(c, 0.10, 0.06, 0.05).flagged
    assert _row(c, 0.10, FLAG_FRACTION * 0.10 - 1e-12, 0.0).flagged
    assert _row(c, 0.10, -0.02, -0.03).flagged
    assert _row(c, 0.10, None, -np.inf).flagged


def test_the_best_simulated_buildable_design_wins(design_written):
    r = design_written[0].result
    good, other = r.candidates[0], r.candidates[1]
    unbuildable = dataclasses.replace(other, parts=tuple(
        dataclasses.replace(p, spring=None, problem="too big") for p in other.parts))
    rows = [_row(good, 0.10, 0.04, 0.03), _row(unbuildable, 0.05, 0.09, 0.08),
            _row(other, 0.20, None, -np.inf)]
    assert best_simulated(rows) is rows[0]  # the fallen and the unbuildable are out
    assert best_simulated([rows[1], rows[2]]) is None


def test_under_both_servos_a_design_is_judged_by_its_worse(design_written):
    """A design that saves most under feedforward but least under position-only loses to one
    whose worse servo is better; one that falls under either servo is never recommended."""
    r = design_written[0].result
    a, b = r.candidates[0], r.candidates[1]
    rows = [_row(a, 0.3, 0.30, 0.29, "feedforward"), _row(b, 0.2, 0.20, 0.19, "feedforward"),
            _row(a, 0.3, 0.10, 0.09, "position"), _row(b, 0.2, 0.18, 0.17, "position")]
    assert best_simulated(rows) is rows[3]  # b, as its worse (position) row
    assert best_simulated(rows[:2]) is rows[0]  # under feedforward alone, a
    fell = [_row(a, 0.3, 0.30, 0.29, "feedforward"), _row(a, 0.3, None, -np.inf, "position"),
            *rows[1::2]]
    assert best_simulated(fell).candidate is b
    assert best_simulated(fell[:2]) is None


def test_an_unknown_servo_is_refused_by_name(design_written):
    from hexaleg.errors import UnknownNameError

    r = design_written[0].result
    with pytest.raises(UnknownNameError, match="both"):
        simulate_candidates(None, [r.recommended], "torque", "electrical")


def test_each_candidate_is_simulated_once_beside_one_baseline(design_written):
    """The same design twice is one row; its simulated saving is the controller check's (the
    design's own proof, simulated separately) to the last digit under the same settings."""
    r = design_written[0].result
    rec = r.recommended
    prepared = condition_prepared(r.run.replace(gait=r.gait), Condition())
    rows = simulate_candidates(prepared, [rec, rec], "feedforward", "electrical")
    assert len(rows) == 1 and rows[0].verdict == "walks"
    ff = r.simulation[0]
    assert ff["controller"] == "feedforward"
    assert rows[0].simulated == pytest.approx(ff["simulated"], rel=1e-12)
    assert rows[0].net == pytest.approx(
        ff["simulated"] + rec.net["electrical"] - rec.row["saving.electrical"], rel=1e-12)
