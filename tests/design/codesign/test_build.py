"""``hexaleg codesign`` on the default robot (issue #31's acceptance, at a reduced budget)."""

from __future__ import annotations

import dataclasses

import pytest
from conftest import BUDGET

import hexaleg
from hexaleg.design.codesign.build import codesign, default_gait
from hexaleg.design.codesign.gait_evaluation import Constraints
from hexaleg.errors import InvalidParameterError, UnknownNameError


def test_codesign_beats_the_default_gait_and_the_sequential_design(codesigned):
    """The reduced search (30 evaluations, 2 restarts) beats the default gait with its best
    springs and the sequential design; the full search's 0.40 of the default gait (≤ 0.65,
    friction margin 0.7) is analysis/codesign_hexaleg.py's kept log (tests/test_examples.py)."""
    default, default_springs, _, best = codesigned.rows
    assert best.per_metre < default_springs.per_metre < default.per_metre
    assert best.per_metre <= codesigned.sequential.per_metre  # beats gait first, then springs
    shares = codesigned.shares
    assert shares["gait"] + shares["springs"] == pytest.approx(shares["codesign"])


def test_reported_gait_and_springs_reproduce_to_one_percent(codesigned):
    robot = hexaleg.load()
    motion = hexaleg.gait(robot, codesigned.chosen)
    prepared = hexaleg.prepare(robot, motion, contact=codesigned.constraints.contact())
    energy = prepared.evaluate(codesigned.springs, "joule").metrics["total"]["electrical"]
    assert energy / codesigned.chosen.stride == pytest.approx(codesigned.rows[3].per_metre,
                                                              rel=0.01)


def test_every_constraint_holds_on_the_result(codesigned):
    c = codesigned.constraints
    m = codesigned.measures
    assert c.min_static_margin == pytest.approx(0.0815, abs=5e-4)  # the default gait's
    for name, (value, bound, _unit, kind) in m.items():
        assert (value >= bound) if kind == "min" else (value <= bound), name
    assert codesigned.chosen.step_height >= c.min_foot_clearance
    assert codesigned.chosen.stride == pytest.approx(0.06 * codesigned.chosen.period)


def test_it_walks_in_mujoco_as_planned(codesigned):
    sim = codesigned.simulation
    assert "error" not in sim
    assert sim["walked"] == pytest.approx(sim["planned"], rel=0.03)
    assert abs(sim["simulated"] - sim["predicted"]) <= 0.02


def test_search_reports_its_effort(codesigned):
    s = codesigned.search
    assert 0 < s.evaluations <= BUDGET["max_evaluations"] and s.wall > 0
    # a run takes what it needs of the budget: the reduced one ends in the first run
    assert 1 <= len(s.restarts) <= BUDGET["restarts"] and codesigned.samples == BUDGET["samples"]
    assert "compass search" in s.method and s.evaluations == BUDGET["max_evaluations"]


def test_pattern_and_bad_input():
    robot = hexaleg.load()
    g = default_gait(robot, "hexaleg", 0.05, "wave", 60)
    assert g.pattern == "wave" and g.duty_factor == pytest.approx(5 / 6)
    with pytest.raises(InvalidParameterError, match="speed"):
        codesign(speed=0.0)
    with pytest.raises(InvalidParameterError, match="samples"):
        codesign(samples=10)
    with pytest.raises(UnknownNameError):
        codesign(pattern="gallop")
    with pytest.raises(InvalidParameterError, match="speed"):
        codesign(speed=5.0, curve=False, simulate=False,
                 constraints=dataclasses.replace(Constraints(), mu=0.6))


def test_a_default_gait_refused_for_the_narrowed_cone_names_friction_margin():
    """The brushless hexapod's default gait at 0.06 m/s needs more of the friction cone than the
    co-design's 0.7 (its femur then over its 2.5 N·m stall torque): the refusal names
    ``friction_margin``, the key that changes it, and with it at 1 the search starts. A gait
    that fails in the whole cone too (a speed no gait walks) is not pointed at the key."""
    from pathlib import Path

    from hexaleg.scenario.scenario import Scenario

    run = Scenario.load(str(Path(__file__).resolve().parents[2] / "data" / "bldc_hexapod.toml"))
    with pytest.raises(InvalidParameterError, match=r"TorqueLimitError.*\[codesign\.constraints"
                                                    r"\] friction_margin = 1 \(now 0\.7\)"):
        codesign(run, speed=0.06, curve=False, simulate=False, rules=False)
    with pytest.raises(InvalidParameterError, match="speed") as refused:
        codesign(speed=5.0, curve=False, simulate=False, rules=False)
    assert "friction_margin" not in str(refused.value)


def test_the_optimal_motion_without_its_extra_names_the_extra(monkeypatch):
    """Before any search: the missing Crocoddyl is said at once, with the extra to install and
    why it pins pin 4.0 (the only crocoddyl wheel reads pin 4.1's models wrongly)."""
    import sys

    from hexaleg.optimal import backend

    monkeypatch.setitem(sys.modules, "crocoddyl", None)  # import crocoddyl → ImportError
    backend.crocoddyl_module.cache_clear()
    try:
        with pytest.raises(backend.BackendError, match=r"hexaleg\[optimal\].*pin 4\.0.*4\.1"):
            codesign(motion="optimal", max_evaluations=1, restarts=1)
    finally:
        backend.crocoddyl_module.cache_clear()
    with pytest.raises(UnknownNameError, match="optimal"):
        codesign(motion="optimised")


def test_the_duty_factor_bound_is_the_search_box_s(monkeypatch):
    """``duty_high`` is the searches' highest duty factor: the box the search gets reaches it
    (0.8 by default, the default gait's + 0.05 where that is higher: a wave's 5/6); a value
    outside [the default gait's + 0.05, 0.95] is refused naming it and that range, before any
    evaluation."""
    from hexaleg.design.codesign import build

    seen = []

    def stop(_evaluate, _base, _speed, space, **_):
        seen.append(space.bounds["duty_factor"])
        raise InvalidParameterError("search", "stopped here", "the test's stop")

    monkeypatch.setattr(build, "search", stop)
    for kwargs, high in (({}, 0.8), ({"duty_high": 0.9}, 0.9),
                         ({"pattern": "wave"}, round(5 / 6 + 0.05, 12))):
        with pytest.raises(InvalidParameterError, match="stopped here"):
            codesign(speed=0.06, curve=False, simulate=False, rules=False, **kwargs)
        assert seen[-1] == (pytest.approx(seen[-1][0]), pytest.approx(high))
    assert seen[0][0] == pytest.approx(0.5)  # the tripod's β₀: the box's low end unchanged
    count = len(seen)
    for bad in (0.99, 0.52, float("nan")):
        with pytest.raises(InvalidParameterError,
                           match=r"\[codesign\] duty_high.*\[0\.55, 0\.95\]"):
            codesign(speed=0.06, curve=False, simulate=False, rules=False, duty_high=bad)
    with pytest.raises(InvalidParameterError, match=r"duty_high.*'0\.9'.*number"):
        codesign(speed=0.06, duty_high="0.9")  # type: ignore[arg-type]
    with pytest.raises(InvalidParameterError, match=r"duty_high.*\[0\.8833.*, 0\.95\]"):
        codesign(speed=0.06, pattern="wave", duty_high=0.85)
    assert len(seen) == count  # refused before the search


def test_the_body_height_bound_is_the_search_box_s(monkeypatch):
    """``body_high`` is the searches' highest body height, × the default gait's: the box the
    search gets reaches it (1.3 × by default), its low end stays 0.7 ×; a value outside [1, 2]
    is refused naming it and that range, before any evaluation. Catches a box whose top stays
    1.3 × whatever is asked (the option ignored), or one scaled by the wrong height."""
    from hexaleg.design.codesign import build

    seen = []

    def stop(_evaluate, base, _speed, space, **_):
        seen.append((space.bounds["body_height"], base.body_height))
        raise InvalidParameterError("search", "stopped here", "the test's stop")

    monkeypatch.setattr(build, "search", stop)
    for kwargs, high in (({}, 1.3), ({"body_high": 1.5}, 1.5), ({"body_high": 1}, 1.0)):
        with pytest.raises(InvalidParameterError, match="stopped here"):
            codesign(speed=0.06, curve=False, simulate=False, rules=False, **kwargs)
        (low, top), body = seen[-1]
        assert (low, top) == (pytest.approx(0.7 * body), pytest.approx(high * body))
    assert seen[0][1] == pytest.approx(0.0913, abs=1e-4)  # the default gait's body height
    count = len(seen)
    for bad in (2.01, 0.99, float("inf")):
        with pytest.raises(InvalidParameterError,
                           match=r"\[codesign\] body_high.*\[1, 2\]"):
            codesign(speed=0.06, curve=False, simulate=False, rules=False, body_high=bad)
    with pytest.raises(InvalidParameterError, match=r"body_high.*'1\.5'.*number"):
        codesign(speed=0.06, body_high="1.5")  # type: ignore[arg-type]
    assert len(seen) == count  # refused before the search
