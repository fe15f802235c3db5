"""The condensed active-set solve of the design program."""

import numpy as np
import pytest

from hexaleg.design.search.optimal import optimal_springs
from hexaleg.design.search.program import DesignProblem, solve_design
from hexaleg.errors import InvalidParameterError


def test_without_binding_samples_it_is_least_squares(prepared200, femur_linear):
    problem = femur_linear(prepared200)
    sol = solve_design(problem)
    assert sol.rounds == 1 and sol.explicit.size == 0
    # Unconstrained least squares in x from the same gains: equal where k > 0 stays feasible.
    gains = prepared200.gains("joule")
    M = np.einsum("tjs,tsx->tjx", gains.G[:, :, problem.cols], problem.B)
    wc = problem.sample_weights[:, None] * prepared200.weights("joule")
    A = (np.sqrt(wc)[..., None] * M).reshape(-1, 2)
    b = -(np.sqrt(wc) * gains.tau0).reshape(-1)
    x_ls = np.linalg.lstsq(A, b, rcond=None)[0]
    if x_ls[0] >= 0:
        np.testing.assert_allclose(sol.x, x_ls, atol=1e-8)
    else:  # the bound binds: k = 0 and the constant is the 1-D least squares
        assert sol.x[0] == pytest.approx(0.0, abs=1e-9)
        np.testing.assert_allclose(sol.x[1], np.linalg.lstsq(A[:, 1:], b, rcond=None)[0][0],
                                   atol=1e-8)


def test_active_set_adds_the_samples_whose_cones_bind(slippery200):
    res = optimal_springs(slippery200, ["coxa", "femur", "tibia"], "linear")
    assert res.solver["clarabel_solves"] >= 2 and res.solver["explicit_samples"] > 0
    f, stance = res.analysis.forces, slippery200.system.stance
    assert np.all(np.hypot(f[..., 0], f[..., 1])[stance] <= 0.3 * f[..., 2][stance] + 1e-7)
    assert res.analysis.resolved.any()  # the evaluation re-solves the same samples exactly


def test_spring_torques_fill_the_sprung_columns(prepared200, femur_linear):
    problem = femur_linear(prepared200)
    tau = problem.spring_torques(np.array([1.0, 0.0]))
    assert tau.shape == prepared200.q.shape
    assert np.all(tau[:, np.setdiff1d(np.arange(18), problem.cols)] == 0)


def test_quadratic_objectives_only(prepared200, femur_linear):
    problem = femur_linear(prepared200)
    bad = DesignProblem(prepared200, "electrical", problem.cols, problem.B, problem.nonnegative,
                        problem.G, problem.h)
    with pytest.raises(InvalidParameterError, match="objective"):
        solve_design(bad)
    assert optimal_springs(prepared200, ["femur"]).solver["clarabel_solves"] == 1


def test_fast_assembly_is_the_sparse_one(prepared200, femur_linear):
    """The program without explicit samples is handed to Clarabel as the same CSC arrays the
    scipy.sparse path builds (so the same solve, bit for bit), and the torque gains are cached
    per problem as einsum computes them."""
    import scipy.sparse as sp

    from hexaleg.design.search.program import _Assembler, torque_gains

    problem = femur_linear(prepared200)
    M = torque_gains(problem)
    assert torque_gains(problem) is M
    G = prepared200.gains("joule").G
    np.testing.assert_array_equal(M, np.einsum("tjs,tsx->tjx", G[:, :, problem.cols],
                                               problem.B))
    asm = _Assembler()
    asm.add(-np.eye(2), np.arange(2), np.zeros(2), None)
    asm.add(np.array([[1.0, 0.0], [0.5, -2.0]]), np.arange(2), np.ones(2), None)
    (fast, bf), (ref, br) = asm.dense(2), asm.matrices(2)
    assert isinstance(ref, sp.csc_matrix)
    for name in ("data", "indices", "indptr"):
        np.testing.assert_array_equal(getattr(fast, name), getattr(ref, name))
    np.testing.assert_array_equal(bf, br)


def test_the_multipliers_price_the_binding_samples(slippery200):
    """The active set's multipliers (the friction cones bind at μ = 0.3) are those of its
    explicit samples and meet complementary slackness at the optimum: each sample's Lagrangian
    term ``torque · τ + force · f + constant`` is ≤ 0 (the multipliers in their dual cones, the
    forces feasible) and their sum is 0 but for the solver's tolerance."""
    from hexaleg.design.search.setup import design_setup

    setup = design_setup(slippery200, ["coxa", "femur", "tibia"], "linear", "joule", None, None)
    problem = setup.problem(setup.check_geometry({}))
    sol = solve_design(problem)
    m = sol.multipliers
    assert m is not None and np.array_equal(m.samples, sol.explicit) and sol.explicit.size > 20
    system = slippery200.system
    k = m.samples
    tau = (system.b_joint[k] - np.einsum("tjf,tf->tj", system.D[k], sol.forces[k])
           - problem.spring_torques(sol.x)[k])
    terms = np.sum(m.torque * tau, axis=1) + np.sum(m.force * sol.forces[k], axis=1) + m.constant
    assert np.abs(m.force).max() > 1e-4 * sol.value  # the cones bind: priced
    assert np.all(terms <= 1e-9 * sol.value)
    assert abs(terms.sum()) <= 1e-7 * sol.value


def test_a_program_without_explicit_samples_has_no_multipliers(prepared200, femur_linear):
    assert solve_design(femur_linear(prepared200)).multipliers is None


def test_the_dual_cone_projection():
    """``_dual_cone`` is the Euclidean projection onto the nonnegative orthant or the
    second-order cone (Moreau: y = P(y) + its part in the polar cone, the two orthogonal)."""
    from hexaleg.design.search.program import _dual_cone

    rng = np.random.default_rng(3)
    for y in rng.normal(size=(200, 3)):
        p = _dual_cone(y, True)
        assert np.hypot(p[1], p[2]) <= p[0] + 1e-12
        rest = y - p
        assert np.hypot(rest[1], rest[2]) <= -rest[0] + 1e-12  # in the polar cone
        assert abs(p @ rest) <= 1e-12
        np.testing.assert_allclose(_dual_cone(p, True), p, atol=1e-15)
        np.testing.assert_array_equal(_dual_cone(y, False), np.maximum(y, 0.0))
