"""Tests of hexaleg.dynamics.ipm: the batched interior-point method converges on every
objective and friction model to the cvxpy reference (within its tolerance), and leaves an
infeasible sample unconverged."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.dynamics.conic import _clarabel_solve, _conic_program
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.ipm import interior_point
from hexaleg.dynamics.reference import solve_reference


@pytest.mark.parametrize(("objective", "mu", "cone"), [
    ("joule", 0.3, "soc"), ("positive_work", 0.25, "pyramid"), ("electrical", 0.3, "soc")])
def test_interior_point_converges_to_the_reference(robot, walk200, group_data, objective, mu,
                                                   cone):
    contact = ContactParams(mu=mu, cone=cone)
    prepared, g, data, tau_s = group_data(walk200, contact, objective)
    result = interior_point(data)
    assert result.converged.all() and result.iterations <= 25
    f = np.zeros((walk200.n_samples, len(robot.legs), 3))
    f[g.rows[None, :], g.legs] = np.transpose(g.forces(result.z), (1, 2, 0))
    rows = np.arange(0, walk200.n_samples, 20)
    f_ref = solve_reference(prepared.system, tau_s, objective, prepared.weights(objective),
                            contact, samples=rows)
    # interior-point accuracy (the active-set step makes it exact: test_batched)
    assert np.max(np.abs(f.reshape(walk200.n_samples, -1)[rows] - f_ref[rows])) <= 1e-4


def test_an_infeasible_sample_does_not_converge(walk200, group_data):
    """At μ = 0.01 most samples have no forces: exactly those Clarabel proves infeasible do not
    converge, the others do."""
    prepared, g, data, tau_s = group_data(walk200, ContactParams(mu=0.01), "joule")
    result = interior_point(data.take(np.arange(0, 40)), max_iter=40)
    w = prepared.weights("joule")
    solved = [_clarabel_solve(_conic_program(prepared.system, int(k), tau_s, "joule", w,
                                             prepared.contact))[1] == "Solved"
              for k in g.rows[:40]]
    assert 0 < sum(solved) < 40
    assert np.array_equal(result.converged, solved)
