"""Tests of hexaleg.dynamics.blocks: each block's linear map is the derivative of its slack, its
transpose is the adjoint, and its Hessian contribution is Aᵀ M A."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.dynamics.blocks import Data, Local, LocalHessian, make_blocks
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.pieces import pieces


def _data(cone, fmin, objective, rng):
    J, nf, m, T = 4, 2, 3, 5
    shape = (J, T)
    return Data(rng.normal(size=(3, nf, T)), rng.normal(size=(3, nf, m, T)),
                rng.normal(size=(J, m, T)), rng.normal(size=shape),
                pieces(objective, np.full(shape, 2.0), rng.normal(size=shape),
                       np.full(shape, 0.7), 1e-4),
                np.full(shape, 1.5), ContactParams(mu=0.5, cone=cone, min_normal_force=fmin))


def _flat(x):
    return np.concatenate([x.f.ravel(), x.tau.ravel()] + ([x.sigma.ravel()]
                                                          if x.sigma is not None else []))


@pytest.mark.parametrize(("cone", "fmin", "objective"),
                         [("soc", 0.0, "joule"), ("pyramid", 1.0, "positive_work"),
                          ("soc", 1.0, "electrical")])
def test_blocks_are_consistent(cone, fmin, objective):
    rng = np.random.default_rng(0)
    data = _data(cone, fmin, objective, rng)
    J, T = data.tau0.shape
    sig = data.pieces.K > 0
    x = Local(rng.normal(size=(3, 2, T)), rng.normal(size=(J, T)),
              rng.normal(size=(J, T)) if sig else None)
    dx = Local(rng.normal(size=(3, 2, T)), rng.normal(size=(J, T)),
               rng.normal(size=(J, T)) if sig else None)
    for b in make_blocks(data):
        b.linearize(x)
        h = 1e-6
        plus = Local(x.f + h * dx.f, x.tau + h * dx.tau,
                     None if x.sigma is None else x.sigma + h * dx.sigma)
        minus = Local(x.f - h * dx.f, x.tau - h * dx.tau,
                      None if x.sigma is None else x.sigma - h * dx.sigma)
        np.testing.assert_allclose((b.value(plus) - b.value(minus)) / (2 * h), b.linear(dx),
                                   atol=1e-6)
        u = rng.normal(size=b.value(x).shape)
        g = Local(np.zeros_like(x.f), np.zeros_like(x.tau),
                  np.zeros_like(x.tau) if sig else None)
        b.add_transpose(u, g)
        np.testing.assert_allclose(np.sum(u * b.linear(dx)), np.dot(_flat(g), _flat(dx)))
        M = rng.uniform(0.5, 2.0, size=b.value(x).shape)
        if b.soc:
            M = np.einsum("ik...,jk...->ij...", rng.normal(size=(3, 3, *M.shape[1:])),
                          rng.normal(size=(3, 3, *M.shape[1:])))
            M = M + np.swapaxes(M, 0, 1)
        H = LocalHessian(np.zeros((3, 3, 2, T)), np.zeros((J, T)), np.zeros((J, T)),
                         np.zeros((J, T)))
        b.add_hessian(M, H)
        F = H.feet.copy()
        for i, j in ((0, 1), (0, 2), (1, 2)):
            F[j, i] = F[i, j]
        Ad = b.linear(dx)
        MAd = np.einsum("ij...,j...->i...", M, Ad) if b.soc else M * Ad
        quad = (np.einsum("aft,abft,bft->", dx.f, F, dx.f) + np.sum(H.tt * dx.tau**2)
                + (2 * np.sum(H.ts * dx.tau * dx.sigma) + np.sum(H.ss * dx.sigma**2)
                   if sig else 0.0))
        np.testing.assert_allclose(quad, np.sum(Ad * MAd), rtol=1e-10)
