"""A batched primal–dual interior-point method for a group's reduced force programs.

The method is CVXOPT's ``coneqp`` (L. Vandenberghe, "The CVXOPT linear and quadratic cone program
solvers", 2010; Nocedal & Wright, *Numerical Optimization*, 2nd ed., §16.6 and §19.3 for the
predictor–corrector idea): Mehrotra's predictor–corrector steps on the Nesterov–Todd scaled
Newton equations, started from CVXOPT's default point, with step length 0.99 of the way to the
boundary. What is particular here is that every sample of a group is solved at once and that the
Newton system is condensed through the structure of :mod:`hexaleg.dynamics.blocks`: each
block's scaled Hessian ``Aᵀ W⁻² A`` is a 3 × 3 matrix per foot or a 2 × 2 matrix per joint, the
epigraph variables are eliminated joint by joint, and what is left is one m × m positive definite
system per sample (m = 3 for a tripod), factorised by :mod:`hexaleg.dynamics.smallmat`.

Samples that meet the tolerances stop moving; the rest iterate until all have converged or
:data:`MAX_ITER` is reached (those are reported as not converged: the caller falls back to
Clarabel, which also names an infeasible sample).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hexaleg.dynamics import smallmat
from hexaleg.dynamics.blocks import Block, Data, Local, LocalHessian, make_blocks
from hexaleg.dynamics.cones import SocScaling, jordan, jordan_solve, nn_max_step, soc_max_step

MAX_ITER = 60
"""Iterations before a sample counts as not converged."""
TOL_FEAS = 1e-9
"""Primal (N, N·m, W) and dual (W per N, W per N·m) residual tolerance."""
TOL_GAP = 1e-9
"""Duality gap tolerance relative to max(1 W, |objective|)."""
STEP = 0.99
"""Fraction of the step to the cone's boundary."""


@dataclass
class Result:
    """The interior-point solution: ``z`` (m, T), ``sigma`` (J, T) or None, the blocks with
    their final ``s`` and ``lam``, which samples converged, and the iteration count."""

    z: np.ndarray
    sigma: np.ndarray | None
    blocks: list[Block]
    converged: np.ndarray
    iterations: int


def _per_sample(a: np.ndarray, T: int, how: str) -> np.ndarray:
    r = a.reshape(-1, T)
    return getattr(r, how)(axis=0)


class _Newton:
    """The condensed Newton system at one iterate: local Hessians, their m × m reduction and its
    Cholesky factor; :meth:`solve` gives the direction for given right-hand side vectors."""

    def __init__(self, data: Data, blocks: list[Block], M: list[np.ndarray],
                 sig: bool, curvature: bool = True) -> None:
        self.data, self.blocks, self.M = data, blocks, M
        J, T = data.tau0.shape
        nf = data.fp.shape[1]
        H = LocalHessian(np.zeros((3, 3, nf, T)), data.pieces.rho.copy(), np.zeros((J, T)),
                         np.zeros((J, T)))
        for b, Mb in zip(blocks, M, strict=True):
            b.add_hessian(Mb, H)
            if b.nonlinear and curvature:
                b.add_curvature(H)
        F = H.feet
        for i, j in ((0, 1), (0, 2), (1, 2)):
            F[j, i] = F[i, j]
        self.H = H
        gamma = H.tt - H.ts**2 / H.ss if sig else H.tt
        N = data.N
        Hz = smallmat.gram(data.E, gamma)
        Hz += np.einsum("afpt,abft,bfqt->pqt", N, F, N, optimize=False)
        self.L = smallmat.cholesky(Hz)
        self.sig = sig

    def solve(self, x: Local, U: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray | None,
                                                          Local]:
        """Direction for ``(P + ∇cᵀ W⁻² ∇c) Δ = −∇F + ∇cᵀ ũ`` with ``ũ`` per block ``U``."""
        d = self.data
        g = Local(np.zeros_like(x.f), -d.pieces.rho * x.tau,
                  -np.ones_like(x.tau) if self.sig else None)
        for b, u in zip(self.blocks, U, strict=True):
            b.add_transpose(u, g)
        r_tau = g.tau
        if self.sig:
            assert g.sigma is not None
            r_tau = r_tau - self.H.ts / self.H.ss * g.sigma
        rhs = np.einsum("cfmt,cft->mt", d.N, g.f) - np.einsum("jmt,jt->mt", d.E, r_tau)
        dz = smallmat.backward(self.L, smallmat.forward(self.L, rhs))
        dx = d.direction(dz, None)
        if self.sig:
            assert g.sigma is not None
            dx.sigma = (g.sigma - self.H.ts * dx.tau) / self.H.ss
        return dz, dx.sigma, dx


def _apply_m(b: Block, Mb: np.ndarray, u: np.ndarray) -> np.ndarray:
    """``W⁻² u`` for block ``b`` with scaled Hessian data ``Mb``."""
    if b.soc:
        return np.einsum("ij...,j...->i...", Mb, u)
    return Mb * u


def interior_point(data: Data, max_iter: int = MAX_ITER) -> Result:
    """Solve ``data``'s programs (:mod:`hexaleg.dynamics.ipm`). An infeasible sample's iterates
    may overflow: it stops where it is and is reported as not converged."""
    with np.errstate(all="ignore"):
        return _interior_point(data, max_iter)


def _interior_point(data: Data, max_iter: int) -> Result:
    J, T = data.tau0.shape
    m = data.N.shape[2]
    sig = data.pieces.K > 0
    blocks = make_blocks(data)
    z = np.zeros((m, T))
    sigma = np.zeros((J, T)) if sig else None
    x = data.local(z, sigma)
    # CVXOPT's starting point: x minimising F + ½‖c(x)‖², s = c(x) and λ = −c(x), each shifted
    # into its cone's interior.
    identity = [np.broadcast_to(np.eye(3).reshape((3, 3) + (1,) * (b.value(x).ndim - 1)),
                                (3, 3, *b.value(x).shape[1:])) if b.soc
                else np.ones_like(b.value(x)) for b in blocks]
    for b in blocks:
        b.linearize(x)
    newton = _Newton(data, blocks, identity, sig, curvature=False)
    dz, dsig, _ = newton.solve(x, [-b.value(x) for b in blocks])
    z = z + dz
    if sigma is not None:
        assert dsig is not None
        sigma = sigma + dsig
    x = data.local(z, sigma)
    values = [b.value(x) for b in blocks]
    nu = sum((v[0] if b.soc else v).reshape(-1, T).shape[0] for b, v in zip(blocks, values,
                                                                              strict=True))
    for which in ("s", "lam"):
        vs = [v if which == "s" else -v for v in values]
        low = np.min([_per_sample(v[0] - np.hypot(v[1], v[2]) if b.soc else v, T, "min")
                      for b, v in zip(blocks, vs, strict=True)], axis=0)
        shift = np.where(low <= 1e-8, 1.0 - low, 0.0)
        for b, v in zip(blocks, vs, strict=True):
            v = v.copy()
            if b.soc:
                v[0] += shift
            else:
                v += shift
            setattr(b, which, v)
    converged = np.zeros(T, dtype=bool)
    stalled = np.zeros(T, dtype=bool)
    it = 0
    for it in range(1, max_iter + 1):  # noqa: B007
        x = data.local(z, sigma)
        for b in blocks:
            b.linearize(x)
        rp = [b.s - b.value(x) for b in blocks]
        M: list[np.ndarray] = []
        scal: list[SocScaling | np.ndarray] = []
        for b in blocks:
            if b.soc:
                S = SocScaling(b.s, b.lam)
                scal.append(S)
                M.append(S.inverse_square())
            else:
                scal.append(np.sqrt(b.s * b.lam))
                M.append(b.lam / b.s)
        # Convergence: residuals, gap.
        g = Local(np.zeros_like(x.f), np.zeros_like(x.tau), np.zeros_like(x.tau) if sig else None)
        for b in blocks:
            b.add_transpose(b.lam, g)
        rd_tau = data.pieces.rho * x.tau - g.tau
        rd = np.abs(np.einsum("jmt,jt->mt", data.E, rd_tau)
                    + np.einsum("cfmt,cft->mt", data.N, g.f)).max(axis=0)
        if sig:
            assert g.sigma is not None
            rd = np.maximum(rd, np.abs(1.0 - g.sigma).max(axis=0))
        pres = np.max([_per_sample(np.abs(r), T, "max") for r in rp], axis=0)
        gap = np.sum([_per_sample(b.s * b.lam, T, "sum") for b in blocks], axis=0)
        cost = (0.5 * data.pieces.rho * x.tau**2).sum(0) + (sigma.sum(0) if sigma is not None
                                                             else 0.0)
        converged |= ((pres <= TOL_FEAS) & (rd <= TOL_FEAS)
                      & (gap <= TOL_GAP * np.maximum(1.0, np.abs(cost))))
        if (converged | stalled).all():
            break
        newton = _Newton(data, blocks, M, sig)
        # Predictor (affine scaling): ũ = W⁻² r_p.
        U = [_apply_m(b, Mb, r) for b, Mb, r in zip(blocks, M, rp, strict=True)]
        dz, dsig, dx = newton.solve(x, U)
        ds_a, dl_a = _steps(blocks, M, U, rp, dx)
        alpha_a = _max_step(blocks, scal, ds_a, dl_a, T)
        a1 = np.minimum(1.0, alpha_a)
        mu = gap / nu
        gap_a = np.sum([_per_sample((b.s + a1 * d1) * (b.lam + a1 * d2), T, "sum")
                        for b, d1, d2 in zip(blocks, ds_a, dl_a, strict=True)], axis=0)
        centring = np.clip(gap_a / np.maximum(gap, 1e-300), 0.0, 1.0) ** 3
        # Corrector: ũ = W⁻¹ v⁻¹∘(σ μ e − (W⁻¹Δs_a)∘(WΔλ_a)) + W⁻² r_p.
        U = []
        for b, S, Mb, r, d1, d2 in zip(blocks, scal, M, rp, ds_a, dl_a, strict=True):
            if b.soc:
                assert isinstance(S, SocScaling)
                corr = -jordan(S.apply_inverse(d1), S.apply(d2))
                corr[0] += centring * mu
                U.append(S.apply_inverse(jordan_solve(S.v, corr)) + _apply_m(b, Mb, r))
            else:
                U.append((centring * mu - d1 * d2) / b.s + Mb * r)
        dz, dsig, dx = newton.solve(x, U)
        ds, dl = _steps(blocks, M, U, rp, dx)
        step = np.minimum(1.0, STEP * _max_step(blocks, scal, ds, dl, T))
        # Near the boundary rounding can defeat the step rule; such a sample stops where it is
        # (stalled: not converged, the caller falls back).
        stalled |= ~np.isfinite(step) | ~np.isfinite(dz).all(axis=0)
        step = np.where(converged | stalled, 0.0, step)
        dz = np.where(stalled, 0.0, dz)
        if dsig is not None:
            dsig = np.where(stalled, 0.0, dsig)
        z = z + step * dz
        if sigma is not None:
            assert dsig is not None
            sigma = sigma + step * dsig
        for b, d1, d2 in zip(blocks, ds, dl, strict=True):
            b.s = b.s + step * np.where(stalled, 0.0, d1)
            b.lam = b.lam + step * np.where(stalled, 0.0, d2)
    return Result(z, sigma, blocks, converged, it)


def _steps(blocks: list[Block], M: list[np.ndarray], U: list[np.ndarray], rp: list[np.ndarray],
           dx: Local) -> tuple[list[np.ndarray], list[np.ndarray]]:
    """``Δs = A Δx − r_p`` and ``Δλ = ũ − λ − W⁻² A Δx`` per block."""
    ds, dl = [], []
    for b, Mb, u, r in zip(blocks, M, U, rp, strict=True):
        a = b.linear(dx)
        ds.append(a - r)
        dl.append(u - b.lam - _apply_m(b, Mb, a))
    return ds, dl


def _max_step(blocks: list[Block], scal: list[SocScaling | np.ndarray], ds: list[np.ndarray],
              dl: list[np.ndarray], T: int) -> np.ndarray:
    """Largest step keeping every slack and multiplier in its cone, per sample (T,)."""
    out = np.full(T, np.inf)
    for b, S, d1, d2 in zip(blocks, scal, ds, dl, strict=True):
        if b.soc:
            assert isinstance(S, SocScaling)
            a = np.minimum(soc_max_step(S.v, S.apply_inverse(d1)), soc_max_step(S.v, S.apply(d2)))
        else:
            a = np.minimum(nn_max_step(b.s, d1), nn_max_step(b.lam, d2))
        out = np.minimum(out, _per_sample(a, T, "min"))
    return out
