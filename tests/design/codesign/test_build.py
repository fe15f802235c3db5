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


def test_the_optimal_motion_on_runge_kutta_knots_is_accepted(monkeypatch):
    """``[codesign.optimal] integrator = "rk4"`` reaches the optimal stage's problem (the
    command once refused every integrator but Euler's); an unknown one is refused before any
    work, naming the allowed ones. The parametric co-design is read back as kept (a stand-in)
    so no search runs."""
    pytest.importorskip("crocoddyl")
    import hexaleg.design.codesign.build as build

    seen = {}

    class Reached(Exception):
        pass

    def stage(_kept, *args):
        seen["params"] = args[-1]
        raise Reached

    from types import SimpleNamespace

    kept = SimpleNamespace(rows=[SimpleNamespace(per_metre=1.0)] * 4, constraints=None)
    monkeypatch.setattr(build, "kept_parametric", lambda _stages, _model: kept)
    monkeypatch.setattr(build, "with_optimal", stage)
    with pytest.raises(Reached):
        codesign(motion="optimal", optimal={"integrator": "rk4"}, max_evaluations=1,
                 restarts=1)
    assert seen["params"].integrator == "rk4"
    with pytest.raises(UnknownNameError, match="rk4"):
        codesign(motion="optimal", optimal={"integrator": "implicit"}, max_evaluations=1,
                 restarts=1)


def test_the_gait_alone_row_takes_its_best_gait_that_works_at_the_rows_sampling():
    """The gait alone's row is its search's best gait where that works at the rows' sampling,
    else the next of its finalists that does, each that fails said in a progress line; where
    none does, a refusal that names ``final_samples`` and the best's error. Catches a row built
    on a gait that leaves a joint's limit between the search's samples (Go2 at 0.3 m/s stopped
    there with an error), or one that skips a best gait that works."""
    from types import SimpleNamespace

    from hexaleg.design.codesign.build import settled

    gaits = [SimpleNamespace(params=name) for name in ("best", "second", "third")]
    found = SimpleNamespace(best=gaits[0], finalists=tuple(gaits))
    said: list[str] = []

    def at_rows(works):
        return lambda params: SimpleNamespace(
            params=params, error=None if params in works else f"{params} leaves a limit")

    assert settled(found, at_rows({"best", "second"}), 200, said.append).params == "best"
    assert not said
    assert settled(found, at_rows({"third"}), 200, said.append).params == "third"
    assert said == ["gait alone: its gait 1 of 3 fails at 200 samples (best leaves a limit); "
                    "the next taken", "gait alone: its gait 2 of 3 fails at 200 samples (second "
                    "leaves a limit); the next taken"]
    with pytest.raises(InvalidParameterError, match=r"final_samples.*200.*one of the gait "
                                                    r"alone's 3 best gaits.*best leaves a limit"):
        settled(found, at_rows(set()), 200, said.append)
    alone = SimpleNamespace(best=gaits[0], finalists=())
    with pytest.raises(InvalidParameterError, match="1 best gaits"):
        settled(alone, at_rows(set()), 200, said.append)
