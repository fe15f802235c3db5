"""The contact timing searched about the co-design's gait: a fixed lattice, each timing judged by
hexaleg's prediction of its rebuilt cycle, the least chosen (a stand-in solver whose rebuilt
cycle is the gait itself, so the choice can be checked against the parametric gaits' own
predictions)."""

from __future__ import annotations

import dataclasses
from types import SimpleNamespace

import numpy as np
import pytest

import hexaleg
from hexaleg.design.codesign.alternation import predicted_per_metre
from hexaleg.design.codesign.timing import candidates, search_timing


def test_the_lattice_is_fixed_and_bounded():
    g = hexaleg.GaitParams(duty_factor=0.8, period=1.8, samples=100)
    duties = [c.duty_factor for c in candidates(g)]
    periods = [c.period for c in candidates(g)]
    assert duties == [0.8, 0.85, 0.9, 0.8, 0.8]  # 0.8 + 0.05 written 0.85, not 0.8500000000000001
    assert periods == pytest.approx([1.8, 1.8, 1.8, 1.53, 2.07], rel=1e-12)
    longer = candidates(dataclasses.replace(g, duty_factor=0.85))
    assert [c.duty_factor for c in longer] == [0.85, 0.9, 0.85, 0.85]  # 0.95 is past 0.9
    moved = candidates(dataclasses.replace(g, period=1.8 + 1e-9))
    assert [c.duty_factor for c in moved] == duties


def test_the_least_prediction_is_chosen(monkeypatch, robot):
    pytest.importorskip("crocoddyl")
    import hexaleg.optimal.problem
    import hexaleg.optimal.solve

    def build(_robot, motion, _motor, _springs, _params):
        return motion

    def solve(_robot, motion, **_kwargs):
        return SimpleNamespace(energy_per_metre=1.0, task_space=motion, x=np.zeros((2, 43)))

    monkeypatch.setattr(hexaleg.optimal.problem, "build_problem", build)
    monkeypatch.setattr(hexaleg.optimal.solve, "solve", solve)
    run = hexaleg.Scenario.load("hexaleg")
    chosen = hexaleg.GaitParams(samples=100)  # the default tripod, duty factor 0.5
    springs = hexaleg.SpringSet()
    lines: list[str] = []
    found = search_timing(robot, chosen, run.actuator, springs, run.contact, None,
                          say=lines.append)
    expected = [predicted_per_metre(robot, hexaleg.gait(robot, g), run.actuator, springs,
                                    run.contact)[0] for g in candidates(chosen)]
    assert [c.predicted for c in found.candidates] == pytest.approx(expected, rel=1e-12)
    assert found.best == int(np.argmin(expected)) and found.chosen.predicted == min(expected)
    assert len(lines) == len(expected) and "predicted rebuilt" in lines[0]
    # progress lines to 0.1 J/m, no digit the spread moves (alternation.shown; was 4 digits)
    assert all(f"{e:.1f} J/m predicted rebuilt (the solver's 1.0)" in line
               for e, line in zip(expected, lines, strict=True))
    assert "→ duty" in found.line() and found.data()["chosen"] == found.best


def test_a_timing_whose_gait_cannot_be_made_is_kept_unsolved(monkeypatch, robot):
    """A timing whose gait raises (Solo-12's co-design trot at period × 1.15: a foot out of reach
    in swing) is a candidate without a solve nor a prediction, saying why; the others are solved
    and the least of them chosen. Catches a search that stops the command there."""
    pytest.importorskip("crocoddyl")
    import hexaleg.optimal.problem
    import hexaleg.optimal.solve
    from hexaleg.design.codesign import timing as timing_module
    from hexaleg.errors import UnreachableTargetError

    chosen = hexaleg.GaitParams(samples=100)
    longest = candidates(chosen)[-1]
    made = timing_module.gait

    def gait(robot, g):
        if g == longest:
            raise UnreachableTargetError("leg LF: out of reach in swing", leg="LF")
        return made(robot, g)

    monkeypatch.setattr(timing_module, "gait", gait)
    monkeypatch.setattr(hexaleg.optimal.problem, "build_problem",
                        lambda _robot, motion, *_args: motion)
    monkeypatch.setattr(hexaleg.optimal.solve, "solve", lambda _robot, motion, **_kwargs:
                        SimpleNamespace(energy_per_metre=1.0, task_space=motion,
                                        x=np.zeros((2, 43))))
    run = hexaleg.Scenario.load("hexaleg")
    lines: list[str] = []
    found = search_timing(robot, chosen, run.actuator, hexaleg.SpringSet(), run.contact, None,
                          say=lines.append)
    last = found.candidates[-1]
    assert last.params == longest and last.result is None and last.predicted is None
    assert last.why == "UnreachableTargetError: leg LF: out of reach in swing"
    assert all(c.predicted is not None for c in found.candidates[:-1])
    assert found.best == int(np.argmin([c.predicted for c in found.candidates[:-1]]))
    assert found.data()["candidates"][-1]["solver"] is None
    assert lines[-1].endswith("no gait (UnreachableTargetError: leg LF: out of reach in swing)")


@pytest.mark.slow  # five tiny box-FDDP solves, twice: ~10 s of CPU
def test_the_lattice_solved_side_by_side_is_the_lattice_solved_in_turn(monkeypatch, robot):
    """The timing lattice's solves on two forked workers give the serial run's cycles bit for
    bit, and the same predictions and choice (a map that mixed up the results' order, or a
    worker that solved another candidate, fails here)."""
    pytest.importorskip("crocoddyl")
    from hexaleg.optimal.problem import OptimalParams
    from hexaleg.parallel import workers

    run = hexaleg.Scenario.load("hexaleg")
    chosen = hexaleg.GaitParams(samples=100)
    params = OptimalParams(nodes=10, iterations=3)
    found = {}
    lines: list[str] = []
    for n in (1, 2):
        monkeypatch.setattr(workers, "default_workers", lambda n=n: n)
        found[n] = search_timing(robot, chosen, run.actuator, hexaleg.SpringSet(), run.contact,
                                 params, say=lines.append if n == 1 else None)
    progress = [line for line in lines if "iteration" in line]  # each named by its timing
    assert len({line.split(": iteration")[0] for line in progress}) == 5
    for serial, parallel in zip(found[1].candidates, found[2].candidates, strict=True):
        assert parallel.params == serial.params
        np.testing.assert_array_equal(parallel.result.x, serial.result.x)
        assert parallel.predicted == serial.predicted
    assert found[2].best == found[1].best
    assert len({c.result.energy_per_metre for c in found[1].candidates}) == 5  # five cycles
