"""docs/optimal.md's table, recomputed: the default gait's rows by hexaleg's pipeline, the
optimal cycle's by Crocoddyl (slow; needs the optimal extra)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

import hexaleg
from hexaleg.design.search.optimal import optimal_springs

DOC = Path(__file__).resolve().parents[2] / "docs" / "optimal.md"


def _rows() -> dict[str, float]:
    text = DOC.read_text(encoding="utf-8")
    table = text[text.index("## The table"):text.index("## How it compares")]
    return {m[1]: float(m[2]) for m in re.finditer(r"^\| ([^|]+?) \| ([0-9.]+) \|", table,
                                                   re.MULTILINE)}


@pytest.fixture(scope="module")
def default_rows():
    run = hexaleg.Scenario.load("hexaleg")
    prepared = run.prepare()
    d = run.motion().distance
    bare = prepared.evaluate(hexaleg.SpringSet()).metrics["total"]["electrical"] / d
    springs = optimal_springs(prepared, list(run.model.joint_classes), family="linear",
                              metric="electrical")
    return run, springs, bare, springs.analysis.metrics["total"]["electrical"] / d


def test_the_default_gaits_rows(default_rows):
    _, _, bare, sprung = default_rows
    rows = _rows()
    assert rows["default gait (hexaleg's pipeline)"] == pytest.approx(bare, abs=0.005)
    assert rows["default gait with its linear springs"] == pytest.approx(sprung, abs=0.005)


@pytest.mark.slow
def test_the_optimal_rows(default_rows):
    pytest.importorskip("crocoddyl")
    from hexaleg.design.codesign.alternation import alternate
    from hexaleg.optimal.problem import OptimalParams, build_problem
    from hexaleg.optimal.solve import solve

    run, springs, _, _ = default_rows
    rows = _rows()
    params = OptimalParams(nodes=40)
    bare = solve(run.model, build_problem(run.model, run.motion(), run.actuator,
                                          hexaleg.SpringSet(), params))
    assert rows["optimal cycle, no springs"] == pytest.approx(bare.energy_per_metre, abs=0.005)
    alt = alternate(run.model, run.motion(), run.actuator, run.contact, springs=springs.springs,
                    params=params, rounds=3)
    assert rows["optimal cycle with its springs (alternation)"] == pytest.approx(
        alt.best.energy_per_metre, abs=0.005)
