"""The fast exact solver of the force program (:mod:`hexaleg.dynamics.contact`), batched per motion.

:func:`solve_fast` is the path sweeps use. For the quadratic objectives the equality-constrained
least-squares solution is linear in the spring torques, ``f = f₀ − K τ_spring``, with per-sample
gains ``K`` computed once per motion (:class:`QuadraticGains`); samples where that solution
violates a friction, normal-force or torque-limit inequality are re-solved exactly with Clarabel
(an interior-point conic solver, :mod:`hexaleg.dynamics.conic`), as are all samples of the
non-quadratic objectives. Where no
inequality binds, the unconstrained optimum is feasible and hence the optimum of the convex
program: the fast path is exact, not an approximation. :mod:`hexaleg.dynamics.reference` (cvxpy)
is what the tests compare it against.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hexaleg.dynamics.conic import raise_unreachable, solve_sample
from hexaleg.dynamics.contact import QUADRATIC_OBJECTIVES, ContactParams, StanceSystem, violations


@dataclass(frozen=True, eq=False)
class QuadraticGains:
    """Exact solution of the equality-constrained quadratic program, linear in the spring torques.

    For weights ``w`` (nj,) the minimiser of Σ_j w_j τ_j² subject to the base rows is
    ``f = K (b_joint − τ_spring) + L b_base``; this holds the per-sample ``K`` (T, 3 n_legs, nj),
    the rigid forces ``f₀ = K b_joint + L b_base`` (T, 3 n_legs), the rigid motor torques
    ``τ₀ = b_joint − D f₀`` (T, nj) and ``G = D K − I`` (T, nj, nj), so that with springs
    ``f = f₀ − K τ_s`` and ``τ = τ₀ + G τ_s`` — only the spring columns of ``K`` and ``G`` are
    touched. Derived from the KKT system ``[H Aᵀ; A 0] [f; λ] = [DᵀW c; b_base]`` with
    ``H = Dᵀ W D`` on the stance columns.
    """

    weights: np.ndarray
    K: np.ndarray
    f0: np.ndarray
    tau0: np.ndarray
    G: np.ndarray


def quadratic_gains(system: StanceSystem, weights: np.ndarray) -> QuadraticGains:
    """Compute :class:`QuadraticGains` for ``system`` and joint weights ``weights`` (nj,), > 0.

    Samples with the same stance pattern are solved as one batch (``numpy.linalg.solve`` on
    stacked KKT matrices).
    """
    T, n_legs = system.stance.shape
    nj = system.D.shape[1]
    K = np.zeros((T, 3 * n_legs, nj))
    L = np.zeros((T, 3 * n_legs, 6))
    patterns, inverse = np.unique(system.stance, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    for p, pattern in enumerate(patterns):
        rows = np.flatnonzero(inverse == p)
        if not pattern.any():
            continue
        cols = np.flatnonzero(np.repeat(pattern, 3))
        n = cols.size
        D = system.D[rows][:, :, cols]  # (Tg, nj, n)
        A = system.A[rows][:, :, cols]  # (Tg, 6, n)
        H = np.einsum("tjk,j,tjl->tkl", D, weights, D)
        kkt = np.zeros((rows.size, n + 6, n + 6))
        kkt[:, :n, :n] = H
        kkt[:, :n, n:] = np.transpose(A, (0, 2, 1))
        kkt[:, n:, :n] = A
        rhs = np.zeros((rows.size, n + 6, nj + 6))
        rhs[:, :n, :nj] = np.transpose(D, (0, 2, 1)) * weights  # DᵀW
        rhs[:, n:, nj:] = np.eye(6)
        sv = np.linalg.svd(A, compute_uv=False)
        if np.all(sv[:, -1] > 1e-9 * sv[:, 0]):
            sol = np.linalg.solve(kkt, rhs)
        else:
            # Rank-deficient base rows (e.g. two point feet cannot push any moment about the line
            # through them): f is still unique where the base wrench is reachable; the
            # pseudo-inverse gives it, and solve_fast rejects samples whose base rows then fail.
            sol = np.linalg.pinv(kkt, rcond=1e-10) @ rhs
        K[np.ix_(rows, cols, np.arange(nj))] = sol[:, :n, :nj]
        L[np.ix_(rows, cols, np.arange(6))] = sol[:, :n, nj:]
    f0 = np.einsum("tkj,tj->tk", K, system.b_joint) + np.einsum("tki,ti->tk", L, system.b_base)
    G = system.D @ K - np.eye(nj)
    return QuadraticGains(np.asarray(weights, dtype=float).copy(), K, f0,
                          system.torques(f0, np.zeros_like(system.b_joint)), G)


def _check_base_rows(system: StanceSystem, f: np.ndarray) -> None:
    """Raise InfeasibleForcesError at the first sample whose stance feet cannot produce the base
    wrench at all (the equality-constrained solution ``f`` (T, 3 n_legs) misses the base rows)."""
    residual = np.abs((system.A @ f[..., None])[..., 0] - system.b_base).max(axis=1)
    scale = 1.0 + np.abs(system.b_base).max(axis=1)
    bad = np.flatnonzero(residual > 1e-8 * scale)
    if bad.size:
        raise_unreachable(system, int(bad[0]), float(residual[bad[0]]))


def solve_fast(system: StanceSystem, tau_spring: np.ndarray, objective: str,
               weights: np.ndarray, contact: ContactParams,
               gains: QuadraticGains | None = None
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Optimal foot forces for every sample (fast exact path).

    Args:
        system: The motion's stance system.
        tau_spring: Spring torques on the joints, shape (T, nj), N·m.
        objective: One of :data:`hexaleg.dynamics.contact.OBJECTIVES`.
        weights: Joule coefficients ``c_j`` (``"joule"``, ``"electrical"``) or ones
            (``"torque_squared"``), shape (nj,), W/(N·m)².
        contact: Contact settings.
        gains: Precomputed :func:`quadratic_gains` for these weights (quadratic objectives).

    Returns:
        ``(f, tau, resolved)``: forces (T, 3 n_legs), N, world frame; motor torques (T, nj), N·m;
        and the mask (T,) of samples that needed the exact conic solve.

    Raises:
        InfeasibleForcesError: no forces satisfy a sample's constraints (names time and feet).
        TorqueLimitError: the torque limits cannot be met (names joint, time, torque).
    """
    T = system.n_samples
    if objective in QUADRATIC_OBJECTIVES:
        if gains is None:
            gains = quadratic_gains(system, weights)
        cols = np.flatnonzero(np.any(tau_spring != 0.0, axis=0))  # joints with a spring
        ts = tau_spring[:, cols, None]
        f = gains.f0 - (gains.K[:, :, cols] @ ts)[..., 0]
        tau = gains.tau0 + (gains.G[:, :, cols] @ ts)[..., 0]
        _check_base_rows(system, f)
        bad = violations(system, f, tau, contact)
    else:
        f = np.zeros((T, system.A.shape[2]))
        bad = np.asarray(system.stance.any(axis=1))
    for k in np.flatnonzero(bad):
        f[k] = solve_sample(system, int(k), tau_spring, objective, weights, contact)
    if objective not in QUADRATIC_OBJECTIVES:
        tau = system.torques(f, tau_spring)
    elif bad.any():
        tau[bad] = system.torques(f[bad], tau_spring[bad], bad)
    return f, tau, bad
