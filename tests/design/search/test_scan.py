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


@pytest.fixture(scope="module")
def friction_bound_setup():
    """A dead-zone design on a tripod gait whose friction cone binds (μ = 0.3: the default
    gait's exact program puts about half its samples in its active set), the state's optimum
    and its multipliers."""
    import hexaleg

    robot = hexaleg.load()
    prepared = hexaleg.prepare(robot, hexaleg.gait(robot, hexaleg.GaitParams(samples=60)),
                               contact=hexaleg.ContactParams(mu=0.3))
    setup = design_setup(prepared, ["coxa", "femur", "tibia"], "dead_zone", "joule", None,
                         np.pi, mirrored=mirror(robot).mirrored)
    state = setup.check_geometry(CASES[3][1])
    own = setup.solve(state)
    assert own.explicit.size >= 20 and own.multipliers is not None
    assert np.abs(own.multipliers.force).max() > 0  # the friction rows' multipliers
    return setup, state, own


@pytest.mark.parametrize(("group", "angle", "side"), [("tibia", "theta_plus", "above"),
                                                      ("femur", "theta_minus", "below")])
def test_the_lagrangian_bound_never_exceeds_the_exact_value(friction_bound_setup, group, angle,
                                                            side):
    """The bound built on the state's multipliers (scan._lagrangian) is a lower bound of the
    exact program on a dense sample of the scanned angle, never below the tight bound, equal
    to the exact value at the state itself (strong duality) but for its margin, and there far
    above the tight bound, which ignores the friction cone."""
    setup, state, own = friction_bound_setup
    lo = state[group]["theta_minus"] + 1e-3 if angle == "theta_plus" else -0.25
    hi = state[group]["theta_plus"] - 1e-3 if angle == "theta_minus" else 0.3
    thetas = np.sort(np.r_[np.linspace(lo, hi, 24), state[group][angle]])
    bounds = RelaxedBounds(setup, state, group, angle, thetas, side, own.multipliers)
    exact = np.array([setup.solve({**state, group: {**state[group], angle: float(t)}}).value
                      for t in thetas])
    dual = np.array([bounds.dual(i) for i in range(thetas.size)])
    tight = np.array([bounds.tight(i) for i in range(thetas.size)])
    assert np.all(dual <= exact) and np.all(dual >= tight)
    at = int(np.flatnonzero(thetas == state[group][angle])[0])
    assert dual[at] == pytest.approx(own.value, rel=1e-8)
    assert exact[at] - tight[at] > 1e-4 * exact[at]


def test_without_multipliers_the_strongest_bound_is_the_tight_one(friction_bound_setup):
    """No multipliers (a state whose program has no explicit sample, or no solution): the
    levels' last bound is the tight bound, bit for bit."""
    setup, state, _ = friction_bound_setup
    thetas = np.linspace(0.0, 0.3, 5)
    bounds = RelaxedBounds(setup, state, "tibia", "theta_plus", thetas, "above")
    assert [bounds.dual(i) for i in range(5)] == [bounds.tight(i) for i in range(5)]
