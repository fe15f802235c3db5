"""Lower bounds of a stop's scan: the condensed program's value at every candidate at once."""

import numpy as np
import pytest

from hexaleg.design.search.program import _solve_once, torque_gains
from hexaleg.design.search.scan import RelaxedBounds, relaxed_values
from hexaleg.design.search.setup import design_setup
from hexaleg.robot.mirror import mirror


def _first_round(setup, state):
    """The condensed program of ``state`` assembled sample by sample (program module): the
    relaxation the scan computes for many angles at once."""
    problem, p = setup.problem(state), setup.prepared
    gains, c, w = p.gains("joule"), p.weights("joule"), problem.sample_weights
    M = torque_gains(problem)
    Mw = M * (w[:, None, None] * c[None, :, None])
    Q, r = np.einsum("tjx,tjy->xy", Mw, M), np.einsum("tjx,tj->x", Mw, gains.tau0)
    scale = float(np.sum(w[:, None] * c * gains.tau0**2))
    x, _, status = _solve_once(problem, np.zeros(0, dtype=int), Q, r, scale)
    assert status == "Solved"
    return scale + x @ Q @ x + 2 * r @ x


CASES = [
    ("one_sided", {"coxa": {"contact": -0.01, "side": "below"},
                   "femur": {"contact": -0.2, "side": "above"},
                   "tibia": {"contact": 0.19, "side": "below"}}, "femur", "contact", "above"),
    ("one_sided", {"coxa": {"contact": -0.01, "side": "below"},
                   "femur": {"contact": -0.2, "side": "above"},
                   "tibia": {"contact": 0.19, "side": "below"}}, "coxa", "contact", "below"),
    ("preloaded", {"coxa": {"theta_minus": -0.3, "theta_plus": 0.05},
                   "femur": {"theta_minus": -0.1, "theta_plus": 0.1},
                   "tibia": {"theta_minus": 0.0, "theta_plus": 0.1}}, "femur", "theta_minus",
     "below"),
    ("dead_zone", {"coxa": {"theta_minus": -0.3, "theta_plus": 0.05},
                   "femur": {"theta_minus": -0.1, "theta_plus": 0.1},
                   "tibia": {"theta_minus": 0.0, "theta_plus": 0.1}}, "tibia", "theta_plus",
     "above"),
]


@pytest.mark.parametrize(("family", "state", "group", "angle", "side"), CASES)
def test_relaxed_values_are_the_condensed_program_and_bound_the_exact_one(
        prepared200, family, state, group, angle, side):
    """With mirrored joints and the design's deflection rows: the cumulative sums give the
    condensed program sample by sample to 1e-12, and never exceed the exact program."""
    setup = design_setup(prepared200, ["coxa", "femur", "tibia"], family, "joule", None, np.pi,
                         mirrored=mirror(prepared200.robot).mirrored)
    low = state[group]["theta_minus"] + 1e-3 if angle == "theta_plus" else -0.25
    high = state[group]["theta_plus"] - 1e-3 if angle == "theta_minus" else 0.3
    thetas = np.linspace(low, high, 6)
    bounds = relaxed_values(setup, state, group, angle, thetas, side)
    for theta, bound in zip(thetas, bounds, strict=True):
        trial = {**state, group: {**state[group], angle: float(theta)}}
        assert bound == pytest.approx(_first_round(setup, trial), rel=1e-12)
        assert bound <= setup.solve(trial).value * (1 + 1e-12)


def test_a_weaker_bound_stands_only_where_it_cannot_win(prepared200):
    """With ``below``, a candidate keeps the unconstrained bound only when that bound is already
    ≥ ``below``; every value returned stays a lower bound of the exact program."""
    family, state, group, angle, side = CASES[0]
    setup = design_setup(prepared200, ["coxa", "femur", "tibia"], family, "joule", None, np.pi,
                         mirrored=mirror(prepared200.robot).mirrored)
    thetas = np.linspace(-0.25, 0.3, 12)
    strong = relaxed_values(setup, state, group, angle, thetas, side)
    below = float(np.median(strong))
    mixed = relaxed_values(setup, state, group, angle, thetas, side, below=below)
    assert np.all(mixed <= strong * (1 + 1e-12))
    assert np.all((mixed == strong) | (mixed >= below))
    assert np.array_equal(mixed[strong < below], strong[strong < below])


@pytest.mark.parametrize("case", [0, 2])
def test_the_strong_bounds_on_demand_are_relaxed_values_and_above_the_weak_ones(prepared200,
                                                                                case):
    """``RelaxedBounds.tight`` is ``relaxed_values``' strong bound bit for bit, and its weak
    bound (no design rows, no signs) never exceeds it: the geometry search may tighten only the
    candidates it reaches in increasing order (geometry._by_bound)."""
    family, state, group, angle, side = CASES[case]
    setup = design_setup(prepared200, ["coxa", "femur", "tibia"], family, "joule", None, np.pi,
                         mirrored=mirror(prepared200.robot).mirrored)
    thetas = np.linspace(-0.25, 0.3, 12)
    bounds = RelaxedBounds(setup, state, group, angle, thetas, side)
    strong = relaxed_values(setup, state, group, angle, thetas, side)
    assert np.array_equal([bounds.tight(i) for i in range(thetas.size)], strong)
    assert np.all(bounds.weak <= strong)


def test_a_strong_bound_asked_again_is_not_solved_again(prepared200, monkeypatch):
    """``tight(i)`` asked twice (a search scanning again from the same state keeps its
    bounds, geometry.search_geometry) is one Clarabel solve and the same number."""
    from hexaleg.design.search import scan

    family, state, group, angle, side = CASES[0]
    setup = design_setup(prepared200, ["coxa", "femur", "tibia"], family, "joule", None, np.pi,
                         mirrored=mirror(prepared200.robot).mirrored)
    bounds = RelaxedBounds(setup, state, group, angle, np.linspace(-0.25, 0.3, 4), side)
    solves = []
    monkeypatch.setattr(scan, "_solve_once", lambda *a: solves.append(1) or _solve_once(*a))
    first = [bounds.tight(i) for i in (2, 0, 2)]
    assert first[0] == first[2] and len(solves) == 2
    assert bounds.tight(0) == first[1] and len(solves) == 2
