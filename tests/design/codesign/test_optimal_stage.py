"""Tests of hexaleg.design.codesign.optimal_stage: the parametric co-design kept before the
optimal motion's stage and read back with this run's robot.

The whole command (a kill in the optimal stage, then the run that resumes) is tested in
tests/commands/codesign/test_write.py (slow)."""

from __future__ import annotations

import dataclasses
import io
import json
import pickle

import numpy as np
import pytest

import hexaleg
from hexaleg.design.chain.checkpoint import StageFiles
from hexaleg.design.codesign.optimal_stage import (
    PARAMETRIC,
    SOLVE,
    KeptSolves,
    keep_parametric,
    kept_parametric,
)
from hexaleg.robot.loaded import Robot


def robots_in(value: object) -> list[Robot]:
    """The robot objects ``value`` refers to, once each."""
    found: dict[int, Robot] = {}

    class Scan(pickle.Pickler):
        def persistent_id(self, obj: object) -> str | None:
            if isinstance(obj, Robot):
                found.setdefault(id(obj), obj)
                return "robot"
            return None

    Scan(io.BytesIO()).dump(value)
    return list(found.values())


def test_the_kept_co_design_is_read_back_with_this_runs_robot(ruled, tmp_path):
    """A co-design whose spring rules carry their own copy of the robot (as they come back from
    their forked child) is kept and read back whole, every robot in it this run's; a run of
    another robot, or with no stages, reads nothing."""
    robot = hexaleg.load()
    theirs = robots_in(ruled)
    assert theirs and all(r is not robot for r in theirs)  # the rules' own robot
    keep_parametric(StageFiles(tmp_path, "k"), ruled, robot)
    assert (tmp_path / f"{PARAMETRIC}.pickle").is_file()
    back = kept_parametric(StageFiles(tmp_path, "k"), robot)
    assert back is not None and robots_in(back) == [robot]
    assert json.dumps(back.to_dict(), default=repr) == json.dumps(ruled.to_dict(), default=repr)
    turned = dataclasses.replace(robot, heading=np.array([0.0, 1.0, 0.0]))
    assert kept_parametric(StageFiles(tmp_path, "k"), turned) is None
    assert kept_parametric(None, robot) is None
    keep_parametric(None, ruled, robot)  # nothing kept, nothing raised


def test_a_kept_solve_is_read_back_by_its_inputs_only(tmp_path):
    """A solve kept by one process is read back by the next for the same inputs (not computed:
    the second compute would fail), computed for other inputs, never kept without stages."""
    robot = hexaleg.load()
    springs = hexaleg.SpringSet()
    inputs = ("round", springs, np.arange(3.0))
    said: list[str] = []
    value = KeptSolves(StageFiles(tmp_path, "k"), robot, said.append)(
        inputs, lambda: np.array([1.5, 2.5]))
    assert KeptSolves.name(inputs).startswith(SOLVE)
    assert (tmp_path / f"{KeptSolves.name(inputs)}.pickle").is_file()

    def never() -> np.ndarray:
        raise AssertionError("a kept solve was computed again")

    again = KeptSolves(StageFiles(tmp_path, "k"), robot, said.append)(
        ("round", hexaleg.SpringSet(), np.arange(3.0)), never)
    np.testing.assert_array_equal(again, value)
    assert said == ["round: solve read back from the kept stage of this run"]
    other = KeptSolves(StageFiles(tmp_path, "k"), robot, said.append)(
        ("round", springs, np.arange(3.0) + 1e-12), lambda: np.zeros(1))
    np.testing.assert_array_equal(other, np.zeros(1))
    calls = []
    for _ in range(2):
        KeptSolves(None, robot, said.append)(inputs, lambda: calls.append(1))
    assert len(calls) == 2


@pytest.mark.slow  # two tiny box-FDDP solves, then one again: ~10 s of CPU
def test_an_alternation_killed_in_a_round_resumes_from_its_kept_solves(tmp_path, monkeypatch):
    """The alternation killed in its round's solve keeps its start's solve; the same run then
    solves the round alone, and a third run solves nothing, with the same energies and springs."""
    pytest.importorskip("crocoddyl")
    from hexaleg.design.codesign.alternation import alternate
    from hexaleg.optimal import solve as solve_module
    from hexaleg.optimal.problem import OptimalParams

    run = hexaleg.Scenario.load("hexaleg")
    real = solve_module.solve
    calls: list[int] = []

    def counted(*args, **kwargs):
        calls.append(1)
        if len(calls) == kill_at:
            raise KeyboardInterrupt
        return real(*args, **kwargs)

    monkeypatch.setattr(solve_module, "solve", counted)

    def alternation():
        return alternate(run.model, run.motion(), run.actuator, run.contact,
                         params=OptimalParams(nodes=10, iterations=8), rounds=1,
                         keep=KeptSolves(StageFiles(tmp_path, "k"), run.model, print))

    kill_at = 2
    with pytest.raises(KeyboardInterrupt):
        alternation()
    assert len(list(tmp_path.glob(f"{SOLVE}*.pickle"))) == 1
    calls.clear()
    kill_at = 0
    resumed = alternation()
    assert len(calls) == 1  # the round's solve alone
    calls.clear()
    again = alternation()
    assert not calls
    assert again.energies == resumed.energies
    assert repr(again.springs) == repr(resumed.springs)
    np.testing.assert_array_equal(again.best.x, resumed.best.x)


def test_the_optimal_motions_springs_are_bought_once_and_kept(tmp_path, monkeypatch, ruled):
    """with_optimal runs the full rules on the alternation's motion after the rows, keeps their
    result, then, where they buy springs, on each repeat of that motion (its spread's: a
    repeat that kept the gait skipped) and says how far the springs move, keeps each, and a
    later process of the same run reads them back instead of designing again; rules that buy
    nothing are not repeated, and none run where the alternation kept the gait."""
    from types import SimpleNamespace

    from hexaleg.design.codesign import optimal_rows as rows_module
    from hexaleg.design.codesign.optimal_stage import RULES, with_optimal

    robot = hexaleg.load()
    kept_gait = False
    motion = hexaleg.gait(robot, hexaleg.GaitParams(samples=40))
    repeat = hexaleg.gait(robot, hexaleg.GaitParams(samples=40, step_height=0.031))

    def rows(*_args, **kwargs):
        assert kwargs["params"] == "the problem's settings"  # with_optimal's, passed on
        alt = SimpleNamespace(kept_gait=kept_gait, motion=motion)
        return rows_module.OptimalRows((), hexaleg.SpringSet(), "linear", None, alt, robot,
                                       "both", 1.0, repeats=(repeat, None))

    monkeypatch.setattr(rows_module, "optimal_rows", rows)
    calls: list[hexaleg.Motion] = []

    answer = ruled.rules  # a design that buys springs, on every motion here
    assert answer.pays

    def rules(m):
        calls.append(m)
        return answer

    stages = StageFiles(tmp_path, "k")
    first = with_optimal(ruled, robot, None, {}, "both", print, stages, rules=rules,
                         params="the problem's settings")
    assert calls == [motion, repeat] and first.optimal.rules is answer
    spread = first.optimal.rules_spread
    assert spread is not None and spread.same == (True, None)
    assert spread.why == ("", "the repeat kept the gait") and set(spread.moved.values()) == {0.0}
    kept = {p.stem for p in tmp_path.glob("*.pickle")}
    assert {KeptSolves.name((RULES, m)) for m in (motion, repeat)} <= kept
    again = with_optimal(ruled, robot, None, {}, "both", print, stages, rules=rules,
                         params="the problem's settings")
    assert len(calls) == 2 and again.optimal.rules_spread == spread
    calls.clear()
    failed = with_optimal(ruled, robot, None, {}, "both", print, None,
                          rules=lambda m: calls.append(m) or "InvalidParameterError: a stand-in",
                          params="the problem's settings")
    assert calls == [motion] and failed.optimal.rules_spread is None  # nothing to compare
    kept_gait = True
    none = with_optimal(ruled, robot, None, {}, "both", print, None, rules=rules,
                        params="the problem's settings")
    assert calls == [motion] and none.optimal.rules is None
