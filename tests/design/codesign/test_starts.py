"""The optimal motion's multi-start: a fixed lattice of starts (step height, body height, swing
weight), each judged by hexaleg's prediction of its rebuilt cycle, the least chosen (a stand-in
solver whose rebuilt cycle is the start's gait itself, so the choice can be checked against the
parametric gaits' own predictions)."""

from __future__ import annotations

import dataclasses
from types import SimpleNamespace

import numpy as np
import pytest

import hexaleg
from hexaleg.design.codesign.alternation import predicted_per_metre
from hexaleg.design.codesign.build import default_gait
from hexaleg.design.codesign.starts import search_starts, starts


@dataclasses.dataclass(frozen=True)
class Settings:
    """A stand-in for OptimalParams (the lattice needs no Crocoddyl): its swing weight."""

    swing_weight: float = 100.0


def test_the_lattice_is_fixed_and_keeps_the_foot_clearance():
    g = hexaleg.GaitParams(step_height=0.02, body_height=0.12, samples=100)
    settings = Settings()
    lattice = starts(g, settings, 0.01)
    assert [label for label, _, _ in lattice] == [
        "the gait", "step height × 0.7", "step height × 1.3", "body height × 0.95",
        "body height × 1.05", "body height × 1.15", "body height × 1.25", "swing weight × 0.01"]
    assert [s.step_height for _, s, _ in lattice] == pytest.approx(
        [0.02, 0.014, 0.026, 0.02, 0.02, 0.02, 0.02, 0.02], rel=1e-12)
    assert [s.body_height for _, s, _ in lattice] == pytest.approx(
        [0.12, 0.12, 0.12, 0.114, 0.126, 0.138, 0.15, 0.12], rel=1e-12)
    assert [p.swing_weight for _, _, p in lattice] == [100.0] * 7 + [1.0]
    # at the least foot clearance a lower step is that clearance: a copy of the gait, left out
    at_floor = starts(g, settings, 0.02)
    assert [label for label, _, _ in at_floor][:2] == ["the gait", "step height × 1.3"]
    raised = starts(g, settings, 0.016)  # raised to the clearance, said as it is
    assert raised[1][0] == "step height × 0.8" and raised[1][1].step_height == 0.016
    moved = starts(dataclasses.replace(g, period=1.0 + 1e-9), settings, 0.01)
    assert [label for label, _, _ in moved] == [label for label, _, _ in lattice]


def test_the_least_prediction_is_chosen_and_a_first_solve_is_reused(monkeypatch, robot):
    pytest.importorskip("crocoddyl")
    import hexaleg.optimal.problem
    import hexaleg.optimal.solve

    def build(_robot, motion, _motor, _springs, _params):
        return motion

    def solve(_robot, motion, **_kwargs):  # marked: the solves run in forked workers
        return SimpleNamespace(energy_per_metre=1.0, task_space=motion, x=np.zeros((2, 43)),
                               solved=True)

    monkeypatch.setattr(hexaleg.optimal.problem, "build_problem", build)
    monkeypatch.setattr(hexaleg.optimal.solve, "solve", solve)
    run = hexaleg.Scenario.load("hexaleg")
    chosen = dataclasses.replace(default_gait(robot, "hexaleg", 0.06, None, 100),
                                 duty_factor=0.8, step_height=0.02)
    springs = hexaleg.SpringSet()
    first = SimpleNamespace(energy_per_metre=1.0, task_space=hexaleg.gait(robot, chosen))
    lines: list[str] = []
    found = search_starts(robot, chosen, run.actuator, springs, run.contact, Settings(), 0.015,
                          first=first, say=lines.append)
    lattice = starts(chosen, Settings(), 0.015)
    solved = [getattr(s.result, "solved", False) for s in found.starts]
    assert solved == [False] + [True] * (len(lattice) - 1)  # the gait's own cycle was given
    assert found.starts[0].result is first
    expected = [predicted_per_metre(robot, hexaleg.gait(robot, g), run.actuator, springs,
                                    run.contact)[0] for _, g, _ in lattice]
    assert [s.predicted for s in found.starts] == pytest.approx(expected, rel=1e-12)
    assert found.best == int(np.argmin(expected)) and found.chosen.predicted == min(expected)
    assert found.chosen.params == lattice[found.best][1]
    assert len(lines) == len(expected) and "predicted rebuilt" in lines[0]
    # progress lines to 0.1 J/m, no digit the spread moves (alternation.shown; was 4 digits)
    assert all(f"{e:.1f} J/m predicted rebuilt (the solver's 1.0)" in line
               for e, line in zip(expected, lines, strict=True))
    assert "→ " in found.line() and found.data()["chosen"] == found.best
