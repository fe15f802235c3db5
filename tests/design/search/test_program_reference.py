"""The cvxpy formulation of the design program (compared with the fast path in test_codesign)."""

import numpy as np

from hexaleg.design.search.program_reference import solve_design_reference


def test_forces_meet_the_base_rows_and_the_value_is_the_joule_energy(prepared200, femur_linear):
    problem = femur_linear(prepared200)
    sol = solve_design_reference(problem)
    system = prepared200.system
    residual = (system.A @ sol.forces[..., None])[..., 0] - system.b_base
    assert np.abs(residual).max() < 1e-7
    tau = system.torques(sol.forces, problem.spring_torques(sol.x))
    value = np.sum(problem.sample_weights[:, None] * prepared200.weights("joule") * tau**2)
    assert abs(value - sol.value) < 1e-12 * value
    assert sol.x[0] >= -1e-9
