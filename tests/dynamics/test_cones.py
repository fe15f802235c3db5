"""Tests of hexaleg.dynamics.cones: Nesterov–Todd scaling, the Jordan product, step lengths."""

from __future__ import annotations

import numpy as np

from hexaleg.dynamics import cones


def _interior(n, rng):
    u = rng.normal(size=(3, n))
    u[0] = np.hypot(u[1], u[2]) + rng.uniform(1e-3, 2.0, n)
    return u


def test_nt_scaling_maps_s_and_lambda_to_the_same_point():
    rng = np.random.default_rng(0)
    s, lam = _interior(50, rng), _interior(50, rng)
    S = cones.SocScaling(s, lam)
    np.testing.assert_allclose(S.apply_inverse(s), S.v, atol=1e-12)
    np.testing.assert_allclose(S.apply(lam), S.v, atol=1e-12)
    u = rng.normal(size=(3, 50))
    np.testing.assert_allclose(S.apply(S.apply_inverse(u)), u, atol=1e-12)
    np.testing.assert_allclose(np.einsum("ijt,jt->it", S.inverse_square(), u),
                               S.apply_inverse(S.apply_inverse(u)), atol=1e-10)
    # v ∘ v = (W⁻¹s) ∘ (Wλ) has the same first entry as s ∘ λ (sᵀλ)
    np.testing.assert_allclose(cones.jordan(S.v, S.v)[0], np.einsum("kt,kt->t", s, lam))


def test_jordan_solve_inverts_the_product():
    rng = np.random.default_rng(1)
    v, d = _interior(20, rng), rng.normal(size=(3, 20))
    np.testing.assert_allclose(cones.jordan(v, cones.jordan_solve(v, d)), d, atol=1e-12)


def test_max_steps_reach_the_boundary():
    rng = np.random.default_rng(2)
    v, d = _interior(200, rng), rng.normal(size=(3, 200)) * 3
    a = cones.soc_max_step(v, d)
    hit = np.isfinite(a)
    assert hit.any() and (~hit).any()
    np.testing.assert_allclose(cones.soc_residual(v[:, hit] + a[hit] * d[:, hit]), 0.0,
                               atol=1e-9)
    assert np.all(cones.soc_residual(v + 0.99 * np.where(hit, a, 1e3) * d) > -1e-12)
    s, ds = np.array([1.0, 2.0, 3.0]), np.array([-2.0, 1.0, -1.0])
    np.testing.assert_allclose(cones.nn_max_step(s, ds), [0.5, np.inf, 3.0])
