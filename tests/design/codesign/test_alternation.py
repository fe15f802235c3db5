"""The alternation of the optimal motion and its springs never raises the energy per metre."""

from __future__ import annotations

import itertools

import pytest

import hexaleg
from hexaleg.design.codesign.alternation import Alternation, Round, alternate
from hexaleg.errors import InvalidParameterError, UnknownNameError


def test_the_best_energy_never_rises():
    """The bookkeeping: a rejected round leaves the best where it was."""
    start = type("R", (), {"energy_per_metre": 10.0})()
    rounds = (Round(hexaleg.SpringSet(), 8.0, 9.0, True, 1.0),
              Round(hexaleg.SpringSet(), 8.5, 9.5, False, 1.0),
              Round(hexaleg.SpringSet(), 8.0, 8.5, True, 1.0))
    energies = Alternation(start, start, hexaleg.SpringSet(), rounds, 0.0).energies
    assert energies == [10.0, 9.0, 9.0, 8.5]


def test_bad_options_are_named(robot, walk):
    run = hexaleg.Scenario.load("hexaleg")
    with pytest.raises(UnknownNameError, match="one_sided"):
        alternate(robot, walk, run.actuator, run.contact, family="one_sided")
    with pytest.raises(InvalidParameterError, match="rounds"):
        alternate(robot, walk, run.actuator, run.contact, rounds=0)


@pytest.mark.slow
def test_the_alternation_lowers_the_energy_and_never_raises_it():
    pytest.importorskip("crocoddyl")
    from hexaleg.optimal.problem import OptimalParams

    run = hexaleg.Scenario.load("hexaleg")
    lines: list[str] = []
    result = alternate(run.model, run.motion(), run.actuator, run.contact,
                       params=OptimalParams(nodes=20, iterations=60), rounds=1, say=lines.append)
    energies = result.energies
    assert all(b <= a for a, b in itertools.pairwise(energies))
    assert result.best.energy_per_metre == energies[-1]
    assert energies[-1] < 0.9 * energies[0]  # the springs pay on the optimal cycle
    assert result.best.residual <= 1e-6
    solves = [line for line in lines if not line.startswith("iteration")]
    assert len(solves) == 1 + len(result.rounds)
    shown = [int(line.split()[1][:-1]) for line in lines if line.startswith("iteration")]
    assert shown and all(k % 20 == 0 for k in shown)  # progress, one line in 20 iterations


@pytest.mark.slow
def test_the_springs_are_designed_on_the_given_groups():
    """Solo-12's front and hind legs bend opposite ways, so one linear spring per joint class
    nearly cancels (measured: 72.1 → 70.8 J/m by the force program); designed per mirrored pair
    (the co-design's ``grouping``), front and hind get their own springs and pay (→ 37.7)."""
    pytest.importorskip("crocoddyl")
    from hexaleg.design.chain.groups import design_groups
    from hexaleg.design.codesign.build import default_gait
    from hexaleg.optimal.problem import OptimalParams

    run = hexaleg.Scenario.load("solo12")
    robot = run.model
    trot = hexaleg.gait(robot, default_gait(robot, "solo12", 0.3, None, 100))
    groups = design_groups(robot, tuple(robot.joint_classes), "mirrored")
    result = alternate(robot, trot, run.actuator, run.contact, groups=groups,
                       params=OptimalParams(nodes=16, iterations=40), rounds=1)
    springs = result.rounds[0].springs
    assert springs["FL_HFE"].stiffness == springs["FR_HFE"].stiffness  # one design a pair
    assert springs["FL_HFE"].stiffness > 2 * springs["HL_HFE"].stiffness  # front ≠ hind
    assert result.rounds[0].designed < 0.6 * result.energies[0]
    assert result.energies[-1] < 0.6 * result.energies[0]
