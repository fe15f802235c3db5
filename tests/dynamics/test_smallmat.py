"""Tests of hexaleg.dynamics.smallmat: batched tiny-matrix linear algebra against numpy.linalg."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.dynamics import smallmat


def _spd(n, T, rng):
    A = rng.normal(size=(T, n, n))
    return A @ np.transpose(A, (0, 2, 1)) + n * np.eye(n)


@pytest.mark.parametrize("n", [1, 2, 3, 6, 12])
def test_solve_spd_equals_numpy(n):
    rng = np.random.default_rng(n)
    H = _spd(n, 40, rng)
    b, B = rng.normal(size=(40, n)), rng.normal(size=(40, n, 3))
    Hs = np.ascontiguousarray(np.transpose(H, (1, 2, 0)))
    x = smallmat.solve_spd(Hs, np.ascontiguousarray(b.T))
    X = smallmat.solve_spd(Hs, np.ascontiguousarray(np.transpose(B, (1, 2, 0))))
    np.testing.assert_allclose(x.T, np.linalg.solve(H, b[..., None])[..., 0], atol=1e-12)
    np.testing.assert_allclose(np.transpose(X, (2, 0, 1)), np.linalg.solve(H, B), atol=1e-12)
    L = smallmat.cholesky(Hs)
    np.testing.assert_allclose(np.einsum("ikt,jkt->ijt", L, L), Hs, atol=1e-12)
    assert smallmat.definite(Hs, L, 1e-12).all()


def test_gram():
    rng = np.random.default_rng(0)
    M, w = rng.normal(size=(5, 3, 7)), rng.normal(size=(5, 7))
    np.testing.assert_allclose(smallmat.gram(M, w), np.einsum("rpt,rt,rqt->pqt", M, w, M))
    np.testing.assert_allclose(smallmat.gram(M), np.einsum("rpt,rqt->pqt", M, M))


def test_dependent_rows_are_dropped_and_the_rest_solved():
    """Row 2 = row 0 + row 1: its pivot vanishes; the kept rows' system is solved exactly and
    the dropped row's solution is zero (its right-hand side zeroed)."""
    rng = np.random.default_rng(1)
    G = rng.normal(size=(2, 4, 5))  # 2 independent rows in 4 dims, 5 samples
    rows = np.concatenate([G, G[:1] + G[1:2]])  # (3, 4, T)
    S = np.einsum("pmt,qmt->pqt", rows, rows)
    L, kept = smallmat.cholesky_dropping(S, 1e-12)
    assert kept[:2].all() and not kept[2].any()
    rhs = rng.normal(size=(3, 5)) * kept
    y = smallmat.backward(L, smallmat.forward(L, rhs))
    assert not y[2].any()
    for t in range(5):
        np.testing.assert_allclose(S[:2, :2, t] @ y[:2, t], rhs[:2, t], atol=1e-10)
