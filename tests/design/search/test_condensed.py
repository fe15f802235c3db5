"""The condensed metric program: the electrical design against an independent cvxpy program,
and no springs where none saves."""

from __future__ import annotations

import numpy as np
import pytest

import hexaleg
from hexaleg.design.search.condensed import Condensed, rows, solve_condensed
from hexaleg.design.search.optimal import design_problem
from hexaleg.design.search.program import DesignProblem
from hexaleg.design.search.program_reference import solve_metric_reference
from hexaleg.errors import InvalidParameterError

GEOMETRY = {"femur": {"contact": -0.18, "side": "above"},
            "tibia": {"contact": 0.18, "side": "below"}}


@pytest.fixture(scope="module")
def prepared100(robot):
    return hexaleg.prepare(robot, hexaleg.gait(robot, hexaleg.GaitParams(samples=100)))


def test_electrical_design_matches_the_cvxpy_program(prepared100):
    """The condensed optimum (gains K, G, bundle method) against the program written with the
    forces as variables held Joule-optimal by their KKT conditions: same value to 1e-6."""
    problem = design_problem(prepared100, {"femur": "femur", "tibia": "tibia"}, "linear",
                             {"femur": {}, "tibia": {}})
    solution = solve_condensed([problem], "electrical")
    base = Condensed(problem, "electrical").base
    x_ref, value_ref = solve_metric_reference(problem, "electrical")
    assert solution.explicit == (0,)
    assert np.count_nonzero(np.abs(solution.x) > 1e-6) >= 2  # springs that act, not the baseline
    assert solution.values[0] * base == pytest.approx(value_ref, rel=1e-6)
    # the reference's magnitudes are no better in the condensed function
    assert Condensed(problem, "electrical").oracle(x_ref)[0] >= solution.values[0] - 1e-7
    np.testing.assert_allclose(solution.x, x_ref, rtol=1e-3, atol=1e-5)


def test_joule_metric_equals_the_active_set_optimum(prepared100):
    from hexaleg.design.search.program import solve_design

    problem = design_problem(prepared100, {"femur": "femur", "tibia": "tibia"}, "one_sided",
                             GEOMETRY)
    exact = solve_design(problem)
    solution = solve_condensed([problem], "joule")
    assert solution.values[0] * Condensed(problem, "joule").base == pytest.approx(exact.value,
                                                                                  rel=1e-7)


def test_a_spring_that_only_costs_energy_gets_magnitude_zero(prepared100):
    """A torque that adds to the motor's wherever it acts (a swing leg's joint while it drives
    the motion; stance forces do not depend on it): every magnitude > 0 costs electrical energy,
    so the optimum is no spring, from any start."""
    p = prepared100
    col = p.robot.column(p.robot.joints("femur")[0])
    leg = next(i for i, lg in enumerate(p.robot.legs) if col in lg.columns)
    tau0 = p.gains("joule").tau0[:, col]
    qd = p.system.qdot[:, col]
    swing = ~p.motion.stance[:, leg] & (tau0 * qd > 0)
    assert swing.sum() > 5
    B = np.where(swing, -np.sign(tau0), 0.0)[:, None, None]  # τ = τ₀ − B x: |τ| grows
    problem = DesignProblem(p, "joule", np.array([col]), B, np.array([True]), np.zeros((0, 1)),
                            np.zeros(0))
    solution = solve_condensed([problem], "electrical", x0=np.array([1.0]))
    assert solution.x[0] == pytest.approx(0.0, abs=1e-9)
    assert solution.values[0] == pytest.approx(1.0, abs=1e-9)  # the baseline, no cost


def test_bad_arguments_are_named(prepared100):
    problem = design_problem(prepared100, ["femur"], "one_sided",
                             {"femur": GEOMETRY["femur"]})
    with pytest.raises(InvalidParameterError, match="joule or electrical"):
        solve_condensed([problem], "positive_work")
    with pytest.raises(InvalidParameterError, match="worst or mean"):
        solve_condensed([problem], "electrical", "median")
    with pytest.raises(InvalidParameterError, match="at least one"):
        solve_condensed([], "electrical")


class _Quadratic:
    """A stand-in for :class:`Condensed`: ``oracle`` only (what ``preferred`` uses)."""

    def __init__(self, weights, centre, offset=0.0):
        self.w, self.c, self.offset = (np.asarray(weights, float), np.asarray(centre, float),
                                       offset)

    def oracle(self, x):
        d = x - self.c
        return float(self.w @ d**2) + self.offset, 2 * self.w * d


def test_equal_worst_cases_are_decided_by_the_preferred_problem():
    """max(x₀² + 1, (x₁ − 2)²) is 1 on the whole segment x₀ = 0, 1 ≤ x₁ ≤ 3: the worst case
    leaves x₁ free. Of that set the second problem prefers x₁ = 2 (value 0): from (0, 1.5)
    the stage moves there and keeps the worst at 1 (analytic)."""
    from hexaleg.design.search.condensed import preferred

    data = [_Quadratic([1.0, 0.0], [0.0, 0.0], 1.0), _Quadratic([0.0, 1.0], [0.0, 2.0])]
    none = np.zeros(2, bool)
    x, info = preferred(data, 1, np.array([0.0, 1.5]), np.zeros((0, 2)), np.zeros(0), none,
                         none)
    assert info["kept"] and info["before"] == pytest.approx(0.25)
    np.testing.assert_allclose(x, [0.0, 2.0], atol=1e-4)
    assert max(d.oracle(x)[0] for d in data) == pytest.approx(1.0, abs=1e-9)
    assert info["after"] == pytest.approx(0.0, abs=1e-8)


class _Stalling:
    """A stand-in for a cvxpy problem whose Clarabel solve stalls at a relative gap ``stall``:
    it raises where the rung's reduced tolerance is tighter, reports "inaccurate" where the
    reduced tolerance is met; records the rungs tried."""

    def __init__(self, stall):
        self.stall, self.tried, self.status = stall, [], None

    def solve(self, solver=None, **kw):
        import cvxpy as cp

        self.tried.append(kw["tol_gap_abs"])
        if kw["tol_gap_abs"] >= self.stall:
            self.status = cp.OPTIMAL
        elif kw.get("reduced_tol_gap_abs", 5e-5) >= self.stall:
            self.status = cp.OPTIMAL_INACCURATE
        else:
            raise cp.error.SolverError("Solver 'CLARABEL' failed")


def test_the_explicit_program_climbs_from_its_own_tolerance_to_the_loosest():
    """The explicit program's ladder starts at TOLERANCE (tighter rungs are never tried: a
    program that stalls there fails them too) and ends at the last of LOOSER: a program that
    stalls at a gap of 1.8e-6 (the default robot's co-design candidate did) is accepted at the
    rung whose reduced tolerance it meets; one that stalls above the loosest fails, named."""
    import cvxpy as cp

    from hexaleg.design.search.condensed import LOOSER, TOLERANCE, _solve

    converged = _Stalling(1e-9)
    assert _solve(converged) == cp.OPTIMAL and converged.tried == [TOLERANCE]
    stalled = _Stalling(1.8e-6)
    assert _solve(stalled) == cp.OPTIMAL
    assert min(stalled.tried) == TOLERANCE and stalled.tried[-1] == 1e-6
    hopeless = _Stalling(1e-3)
    assert _solve(hopeless).startswith("failed (")
    assert hopeless.tried[-1] == LOOSER[-1] and min(hopeless.tried) == TOLERANCE


def test_a_solver_failure_is_not_called_an_empty_program(prepared100, monkeypatch):
    """Clarabel failing at every rung is named as the solver's failure, not as a program without
    a solution; an infeasible status keeps the infeasibility's wording."""
    import hexaleg.design.search.condensed as condensed
    from hexaleg.design.search.condensed import explicit_program
    from hexaleg.errors import InfeasibleForcesError

    problem = design_problem(prepared100, {"femur": "femur"}, "linear", {"femur": {}})
    data = [Condensed(problem, "joule")]
    engaged = np.ones(problem.nx, dtype=bool)
    args = (data, "worst", problem.nonnegative, engaged, np.zeros((0, problem.nx)), np.zeros(0))
    monkeypatch.setattr(condensed, "_solve", lambda p: "failed (Solver 'CLARABEL' failed)")
    with pytest.raises(InfeasibleForcesError, match="the solver failed; that is no proof"):
        explicit_program(*args)
    monkeypatch.setattr(condensed, "_solve", lambda p: "infeasible")
    with pytest.raises(InfeasibleForcesError, match=r"has no solution \(Clarabel: infeasible"):
        explicit_program(*args)


def test_a_searchs_stacked_rows_are_each_distinct_row_once(prepared100):
    """The comparisons of a stop-tolerance search stack each distinct design row once (the same
    program: every row of the stack is one of them), in the order of first occurrence; the
    certified solve keeps them all."""
    from hexaleg.design.search.setup import design_setup

    shifts = ({"femur": -0.02, "tibia": 0.0}, {"femur": 0.0, "tibia": 0.0},
              {"femur": 0.02, "tibia": -0.02})
    setup = design_setup(prepared100, {"femur": "femur", "tibia": "tibia"}, "one_sided", "joule",
                         2.0, 0.3, "electrical", shifts)
    problems = setup.problems(setup.check_geometry(GEOMETRY))
    G, h, nonneg, fixed = rows(problems)
    Gd, hd, nonneg_d, fixed_d = rows(problems, distinct=True)
    every, kept = np.c_[G, h], np.c_[Gd, hd]
    assert len(np.unique(kept, axis=0)) == len(kept) < len(every)
    first = [i for i, r in enumerate(every) if not any((every[:i] == r).all(axis=1))]
    np.testing.assert_array_equal(kept, every[first])
    assert (nonneg_d == nonneg).all() and (fixed_d == fixed).all()
    # the comparison solve and the certified one: the same optimum to the bundle's tolerance
    fast = solve_condensed(problems, "electrical", exact=False)
    exact = solve_condensed(problems, "electrical")
    assert fast.values.max() == pytest.approx(exact.values.max(), rel=1e-4)
