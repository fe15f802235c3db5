"""The outer geometry search: exact along each angle, deterministic, nested families ordered."""

import dataclasses

import numpy as np
import pytest

import hexaleg
from hexaleg.design.families import CONTAINS
from hexaleg.design.search.geometry import EDGE, search_geometry, search_value
from hexaleg.design.search.optimal import optimal_springs
from hexaleg.design.search.setup import design_setup
from hexaleg.motion.legged import gait
from hexaleg.robot.mirror import mirror
from hexaleg.robot.registry import load


def _relative(prepared, kind):
    """Every sample's angle of the class's joints from their centre of motion, rad."""
    q = prepared.q[:, [prepared.robot.column(j) for j in prepared.robot.joints(kind)]]
    return (q - (q.min(0) + q.max(0)) / 2).ravel()


def test_one_sided_search_is_the_best_of_every_stop_place_and_of_a_dense_grid(prepared200):
    """One group: the search's optimum is the minimum over every place a stop can change the
    design (just before each sample's angle, either side), evaluated one by one, and no point
    of a dense grid over the motion beats it."""
    searched = optimal_springs(prepared200, ["tibia"], "one_sided")
    value = search_value(design_setup(prepared200, ["tibia"], "one_sided", "joule", None, None))
    r = np.unique(_relative(prepared200, "tibia"))
    places = [(float(c), "above") for c in r - EDGE] + [(float(c), "below") for c in r + EDGE]
    best = min(value({"tibia": {"contact": c, "side": s}}) for c, s in places)
    assert searched.value == pytest.approx(best, rel=1e-9)
    grid = np.linspace(r.min() - 0.01, r.max() + 0.01, 301)
    dense = min(value({"tibia": {"contact": float(c), "side": s}})
                for c in grid for s in ("above", "below"))
    assert searched.value <= dense * (1 + 1e-9)


def test_a_preloaded_stop_is_best_just_before_a_sample(prepared200):
    """Between two samples' angles the engaged samples are fixed and a preloaded stop's value
    is non-increasing towards the next sample (the search module's argument): measured on the
    tibia, above and below, in the gaps either side of the optimum."""
    setup = design_setup(prepared200, ["tibia"], "one_sided", "joule", None, None)
    value = search_value(setup)
    r = np.unique(_relative(prepared200, "tibia"))
    gaps = np.flatnonzero(np.diff(r) > 1e-4)  # wide enough to sample inside
    for i in gaps[[len(gaps) // 3, len(gaps) // 2, 2 * len(gaps) // 3]]:
        inside = np.linspace(r[i] + 1e-6, r[i + 1] - 1e-6, 7)
        above = [value({"tibia": {"contact": float(c), "side": "above"}}) for c in inside]
        below = [value({"tibia": {"contact": float(c), "side": "below"}}) for c in inside]
        assert np.all(np.diff(above) <= 1e-12 * abs(above[0]))
        assert np.all(np.diff(below) >= -1e-12 * abs(below[0]))


def test_preloaded_search_beats_a_dense_grid_of_both_stops(prepared200):
    """One group, both stops of a preloaded spring: no point of a 41 × 41 grid over the motion
    (θ⁻ ≤ θ⁺) beats the search."""
    searched = optimal_springs(prepared200, ["femur"], "preloaded")
    value = search_value(design_setup(prepared200, ["femur"], "preloaded", "joule", None, None))
    r = _relative(prepared200, "femur")
    grid = np.linspace(r.min() - 0.01, r.max() + 0.01, 41)
    dense = min(value({"femur": {"theta_minus": float(a), "theta_plus": float(b)}})
                for a in grid for b in grid if a <= b)
    assert searched.value <= dense * (1 + 1e-9)


def test_search_is_deterministic_and_says_how_it_found_the_optimum(prepared200):
    a = optimal_springs(prepared200, ["femur", "tibia"], "one_sided")
    b = optimal_springs(prepared200, ["femur", "tibia"], "one_sided")
    assert a.geometry == b.geometry and a.value == b.value
    stage = a.solver["search"]["stages"][0]
    assert stage["converged"] and "coordinate descent" in stage["method"]
    assert stage["levels"]["femur"] > 100


def _families(prepared, groups, **kw):
    return {f: optimal_springs(prepared, groups, f, "joule", metric="electrical", **kw)
            for f in ("linear", "one_sided", "dead_zone", "preloaded")}


def _assert_nested(found):
    for outer, inners in CONTAINS.items():
        for inner in inners:
            if outer in found and inner in found:
                assert found[outer].saving >= found[inner].saving - 1e-6, (outer, inner)


@pytest.mark.slow  # 16 s: the README suite stays within its 5 minutes
def test_nested_families_are_ordered_on_the_hexapod(prepared200):
    """preloaded ⊇ one_sided, dead_zone, linear; dead_zone ⊇ linear: never below them (with
    the design's deflection bound, which keeps a linear spring's equilibrium within reach)."""
    mirrored = mirror(prepared200.robot).mirrored
    _assert_nested(_families(prepared200, ["coxa", "femur", "tibia"], mirrored=mirrored,
                             max_deflection=np.pi))


def test_nested_families_are_ordered_on_a_quadruped():
    robot = load("solo12")
    motion = gait(robot, hexaleg.GaitParams(samples=100, period=0.5, stride_length=0.08,
                                            step_height=0.04, pattern="trot"))
    prepared = hexaleg.prepare(robot, motion)
    _assert_nested(_families(prepared, list(robot.joint_kinds), max_deflection=np.pi))


def test_a_nanometre_of_step_height_moves_no_printed_digit(robot):
    """The search follows the optimum, not the floating-point path: a 1e-9 m change of the step
    height changes the optimum's saving by far less than its printed 0.01 % and its stops by
    far less than a micro-radian (the old local search moved by 1.9 points)."""
    out = []
    for h in (0.03, 0.03 + 1e-9):
        motion = hexaleg.gait(robot, hexaleg.GaitParams(samples=200, step_height=h))
        out.append(optimal_springs(hexaleg.prepare(robot, motion), ["femur", "tibia"],
                                   "preloaded", "joule", metric="electrical"))
    assert abs(out[0].saving - out[1].saving) < 1e-6
    for g in ("femur", "tibia"):
        for k in ("theta_minus", "theta_plus"):
            assert abs(out[0].geometry[g][k] - out[1].geometry[g][k]) < 1e-6


def test_metric_stage_keeps_the_best_start(prepared200):
    """With a metric the search takes the best of the Joule optimum and the starts: a start
    better in the metric is never lost."""
    setup = design_setup(prepared200, ["tibia"], "one_sided", "joule", None, None,
                         metric="electrical")
    joule = search_geometry(dataclasses.replace(setup, metric=None))
    found = search_geometry(setup, [joule.geometry], max_sweeps=0)
    assert found.geometry == joule.geometry and found.method == "the best of its starts"


class _Bounds:
    """A stand-in for scan.RelaxedBounds: given weak and strong bounds, counting tightenings."""

    def __init__(self, weak, strong):
        self.weak, self.strong, self.tightened = np.asarray(weak), np.asarray(strong), []

    def tight(self, i):
        self.tightened.append(i)
        return float(self.strong[i])


@pytest.mark.parametrize("seed", range(20))
def test_candidates_come_in_the_order_of_every_strong_bound_sorted(seed):
    """The scan's order of exact solves (geometry._by_bound) is the stable sort of the strong
    bounds cut at the first not below the limit — as if every strong bound were computed —
    with ties among strong bounds kept by index, the limit read again before each candidate
    (it falls as the exact values come in); a weak bound not below the limit is not
    tightened."""
    from hexaleg.design.search.geometry import _by_bound

    rng = np.random.default_rng(seed)
    n = 40
    strong = np.round(rng.uniform(0, 10, n), 1)  # rounded: ties
    strong[rng.integers(0, n, 3)] = np.inf
    weak = strong - rng.uniform(0, 3, n) * (rng.uniform(size=n) < 0.8)
    falls = np.sort(rng.uniform(3, 9, n))[::-1]  # the limit after each exact value

    def order(candidates):
        out, limit = [], [9.0]
        for i in candidates(lambda: limit[0]):
            out.append(int(i))
            limit[0] = min(limit[0], falls[len(out) - 1])
        return out

    def every(limit):
        for i in np.argsort(strong, kind="stable"):
            if not strong[i] < limit():
                return
            yield i

    bounds = _Bounds(weak, strong)
    assert order(lambda limit: _by_bound(bounds, limit)) == order(every)
    assert all(weak[i] < 9.0 for i in bounds.tightened)
