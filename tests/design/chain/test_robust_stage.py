"""The robust stage never ends a design (issue #39, 5): a corner the legs cannot reach is left
out with a note naming the key that sets it, a failed program leaves no robust design and says
why, and Clarabel failing outright falls to its tolerance ladder, then to a named error."""

from __future__ import annotations

import cvxpy as cp
import numpy as np

from hexaleg.design.chain import robust_stage
from hexaleg.design.chain.chain import DesignChain
from hexaleg.design.search import condensed
from hexaleg.errors import InfeasibleForcesError
from hexaleg.scenario.scenario import Scenario

BOX = {"families": ["linear"], "samples": 100, "robust_period": [1.0, 1.0],
       "robust_payload": [0.0, 0.0], "robust_mu": [0.6, 0.6]}


def test_an_unreachable_corner_is_left_out_and_named():
    scenario = Scenario.from_tables("hexaleg",
                                    {"design": {**BOX, "robust_stride": [1.25, 12.0]}})
    r = DesignChain(scenario).run(stages=("candidates", "robust"))
    assert r.robust is not None
    assert [c.label() for c in r.robust.conditions][1:] == ["stride ×1.25, μ 0.6"]
    note = next(n for n in r.notes if n.startswith("robust box corner"))
    assert "stride ×12" in note and "set by [design] robust_stride)" in note
    assert "out of reach" in note


def test_a_failed_robust_program_leaves_no_robust_design_and_a_note(monkeypatch):
    def fail(*args, **kwargs):
        raise InfeasibleForcesError("the condensed spring program has no solution (Clarabel: "
                                    "failed)")

    monkeypatch.setattr(robust_stage, "robust_springs", fail)
    scenario = Scenario.from_tables("hexaleg",
                                    {"design": {**BOX, "robust_stride": [1.0, 1.25]}})
    r = DesignChain(scenario).run(stages=("candidates", "robust"))
    assert r.robust is None and r.candidates  # the rest of the design stands
    assert any(n.startswith("no robust design: InfeasibleForcesError: the condensed")
               for n in r.notes)


def test_clarabel_failing_outright_falls_to_the_ladder_then_to_a_status(monkeypatch):
    x = cp.Variable(2)
    program = cp.Problem(cp.Minimize(cp.sum_squares(x - np.array([1.0, 2.0]))), [x >= 0])
    calls = []
    solve = cp.Problem.solve

    def flaky(self, *args, **kwargs):
        calls.append(kwargs.get("tol_gap_abs"))
        if len(calls) == 1:
            raise cp.error.SolverError("Solver 'CLARABEL' failed")
        return solve(self, *args, **kwargs)

    monkeypatch.setattr(cp.Problem, "solve", flaky)
    assert condensed._solve(program) == cp.OPTIMAL and len(calls) >= 2
    np.testing.assert_allclose(x.value, [1.0, 2.0], atol=1e-6)

    def broken(self, *args, **kwargs):
        raise cp.error.SolverError("Solver 'CLARABEL' failed")

    monkeypatch.setattr(cp.Problem, "solve", broken)
    status = condensed._solve(cp.Problem(cp.Minimize(cp.sum_squares(x)), [x >= 0]))
    assert status.startswith("failed (") and "CLARABEL" in status


def test_a_failed_stop_tolerance_design_keeps_the_tolerance_blind_one_and_says_so(monkeypatch):
    """Solo-12's one-foot crawl (μ 1.3): the tolerant program's certified solve failed in
    Clarabel after 24 s of finished work and ended the design; now the blind design stands."""
    from hexaleg.design.chain import chain

    def fail(*args, **kwargs):
        raise InfeasibleForcesError("the condensed spring program has no solution (Clarabel: "
                                    "failed)")

    monkeypatch.setattr(chain, "stop_tolerance", fail)
    scenario = Scenario.from_tables("hexaleg", {"design": {
        "families": ["one_sided"], "samples": 100, "robustness": False}})
    r = DesignChain(scenario).run(stages=("candidates", "tolerance"))
    assert r.tolerance is None and r.recommended is r.candidates[0]
    assert any(n.startswith("the design for the stops' mounting error (±1°) failed "
                            "(the condensed spring program has no solution")
               and "tolerance-blind design is recommended" in n for n in r.notes)
