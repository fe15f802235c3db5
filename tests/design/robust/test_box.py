"""Tests of hexaleg.design.robust.box: the robust design over a box of conditions."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.design.families import family
from hexaleg.design.robust.box import robust_springs
from hexaleg.design.robust.conditions import condition_prepared
from hexaleg.design.search.optimal import optimal_springs
from hexaleg.dynamics.energy import saving
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.springs import SpringSet
from hexaleg.scenario.condition import Condition
from hexaleg.scenario.scenario import Scenario

RUN = Scenario.load().with_gait({"samples": 120})
GAIT = RUN.gait
BOX = (Condition(), Condition(period=0.75), Condition(stride=1.25, payload=0.2))


@pytest.fixture(scope="module")
def box():
    nominal = condition_prepared(RUN, Condition())
    best = optimal_springs(nominal, ["femur", "tibia"], "linear")
    return nominal, best, [condition_prepared(RUN, c) for c in BOX]


def _worst(conditions, springs, metric):
    return min(saving(p.evaluate(springs, "joule").metrics["total"][metric],
                      p.baseline("joule")["total"][metric]) for p in conditions)


@pytest.mark.parametrize("metric", ["joule", "electrical"])
def test_robust_worst_case_beats_the_nominal_and_every_nearby_design(box, metric):
    nominal, best, preps = box
    r = robust_springs(best, nominal, preps, "worst", metric)
    assert r.solver["explicit_samples"] == [0, 0, 0]
    assert r.worst >= r.nominal_worst - 1e-12
    assert r.worst == pytest.approx(_worst(preps, r.springs, metric), rel=1e-9)
    # the optimum ≥ every point of a grid about it (two magnitudes of the femur varied)
    fam = family("linear")
    x = np.concatenate([[r.magnitudes[g][m] for m in fam.magnitudes] for g in r.groups])
    for dk in (-0.3, 0.3):
        for dt in (-0.01, 0.01):
            y = x.copy()
            y[0], y[1] = max(x[0] * (1 + dk), 0.0), x[1] + dt
            springs = SpringSet({j: fam.spring({}, r.springs[j].reference, y[2 * i:2 * i + 2])
                                 for i, g in enumerate(r.groups) for j in r.groups[g]})
            assert _worst(preps, springs, metric) <= r.worst + 1e-9


def test_the_nominal_gait_decides_between_designs_of_equal_worst(box):
    """The worst case leaves directions free (the conditions that do not set it); preferring the
    nominal condition picks, of the magnitudes with that worst, the one that saves most on the
    nominal gait: the worst is kept to the bundle's tolerance and the nominal saving is not
    below the unpreferred design's, and the stage records what it did."""
    nominal, best, preps = box
    free = robust_springs(best, nominal, preps, "worst", "joule")
    chosen = robust_springs(best, nominal, preps, "worst", "joule", prefer=0)
    assert chosen.worst == pytest.approx(free.worst, abs=1e-6)
    assert chosen.saving[0] >= free.saving[0] - 1e-7
    info = chosen.solver["preferred"]
    assert info["kept"] and info["after"] <= info["before"] + 1e-9
    assert "preferred" not in free.solver


def test_mean_mode_maximises_the_mean(box):
    nominal, best, preps = box
    r = robust_springs(best, nominal, preps, "mean", "joule")
    worst = robust_springs(best, nominal, preps, "worst", "joule")
    assert r.saving.mean() >= worst.saving.mean() - 1e-9
    assert r.saving.mean() >= r.nominal_saving.mean() - 1e-9


def test_binding_cones_get_explicit_forces(box):
    nominal, best, _ = box
    slippery = [nominal, condition_prepared(RUN, Condition(mu=0.3))]
    r = robust_springs(best, nominal, slippery, "worst", "joule")
    assert r.solver["explicit_samples"][1] > 0
    assert r.solver["path"].startswith("cvxpy")
    assert r.worst >= r.nominal_worst - 1e-9
    assert r.worst == pytest.approx(_worst(slippery, r.springs, "joule"), rel=1e-7)


def test_bad_arguments_are_named(box):
    nominal, best, preps = box
    with pytest.raises(InvalidParameterError, match="worst or mean"):
        robust_springs(best, nominal, preps, "median")
    with pytest.raises(InvalidParameterError, match="joule or electrical"):
        robust_springs(best, nominal, preps, "worst", "positive_work")
    with pytest.raises(InvalidParameterError, match="at least one"):
        robust_springs(best, nominal, [], "worst")


def test_the_stacked_program_holds_only_the_conditions_that_can_set_the_worst(box, monkeypatch):
    """The explicit program starts from the bundle's optimum with the conditions near its worst
    (and those with explicit samples) and is the whole box's optimum: the same worst saving as
    the program of every condition, to the solver's tolerance."""
    import hexaleg.design.robust.box as box_module

    nominal, best, conditions = box
    slippery = [*conditions, condition_prepared(RUN, Condition(mu=0.3))]
    held = robust_springs(best, nominal, slippery, "worst", "joule")
    assert held.solver["explicit_samples"][-1] > 0
    assert held.solver.get("problems_in_program", len(slippery)) < len(slippery)
    every = box_module.explicit_program
    monkeypatch.setattr(box_module, "explicit_program",
                        lambda *a, start=None: every(*a))  # every condition held
    whole = robust_springs(best, nominal, slippery, "worst", "joule")
    assert "problems_in_program" not in whole.solver
    assert held.worst == pytest.approx(whole.worst, abs=1e-7)
    assert held.worst == pytest.approx(_worst(slippery, held.springs, "joule"), rel=1e-7)
