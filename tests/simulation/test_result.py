"""What a simulation found, read without simulating: each verdict has its meaning, two runs'
stepping spans count once where they overlap, a comparison refuses a run that did not walk, and
a run's real-time figures stay finite at zero wall time."""

from __future__ import annotations

from types import SimpleNamespace
from typing import Any

import pytest

from hexaleg.errors import SimulationError
from hexaleg.simulation.result import VERDICTS, Run, Simulation, verdict_meanings


def _run(name: str, verdict: str = "walks", *, started: float = 0.0, wall: float = 0.0,
         cpu: float = 0.0, metrics: dict[str, float] | None = None) -> Run:
    """A run with a stand-in model (1 ms steps) and trajectory (500 steps): what the result's
    arithmetic reads of them."""
    sim: Any = SimpleNamespace(timestep=1e-3)
    trajectory: Any = SimpleNamespace(n=500)
    return Run(name, sim, trajectory, verdict, f"the {name} run's message",
               metrics=metrics or {}, started=started, wall=wall, cpu=cpu)


def _simulation(springs: Run, baseline: Run) -> Simulation:
    analysis: Any = SimpleNamespace(metrics={"total": {"electrical": 8.0}},
                                    baseline={"total": {"electrical": 10.0}},
                                    savings={"total": {"electrical": 0.2}})
    nothing: Any = None
    return Simulation(nothing, nothing, nothing, nothing, analysis, analysis, springs, baseline,
                      nothing)


def test_every_verdict_has_its_meaning():
    meanings = verdict_meanings()
    assert list(meanings) == list(VERDICTS)
    assert "±10%" in meanings["walks"] and "50%" in meanings["stalled"]


@pytest.mark.parametrize("spans, union", [(((0.0, 2.0), (1.0, 2.0)), 3.0),   # overlap
                                          (((5.0, 1.0), (0.0, 2.0)), 3.0),   # apart
                                          (((0.0, 4.0), (1.0, 1.0)), 4.0)])  # within
def test_the_stepping_wall_is_the_union_of_the_two_runs_spans(spans, union):
    """The sum of the two walls (4, 3, 5) fails where they overlap, the longer alone (2, 2, 4)
    where one does not hold the other."""
    (s0, w0), (s1, w1) = spans
    s = _simulation(_run("springs", started=s0, wall=w0), _run("baseline", started=s1, wall=w1))
    assert s.stepping_wall == pytest.approx(union, abs=1e-15)


def test_the_comparison_refuses_a_run_that_did_not_walk():
    walked = _run("springs", metrics={"electrical": 6.0})
    s = _simulation(walked, _run("baseline", metrics={"electrical": 8.0}))
    assert s.walks and s.simulated() == (6.0, 8.0, 0.25)
    assert s.predicted() == (8.0, 10.0, 0.2)
    fell = _simulation(walked, _run("baseline", "fell"))
    assert not fell.walks
    with pytest.raises(SimulationError, match="the baseline run fell: the baseline run's message"):
        fell.simulated()


def test_a_runs_realtime_figures():
    run = _run("springs", wall=0.25, cpu=0.125)
    assert run.simulated_time == pytest.approx(0.5)
    assert run.realtime_factor == pytest.approx(2.0) and run.cpu_share == pytest.approx(0.5)
    still = _run("springs")
    assert still.realtime_factor == float("inf") and still.cpu_share == 1.0
