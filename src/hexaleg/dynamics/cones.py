"""Batched operations on the two cones of the force programs, for the interior-point method.

The nonnegative orthant (arrays of any shape, elementwise) and the three-dimensional second-order
cone ``Q = {u : u₀ ≥ ‖(u₁, u₂)‖}`` (arrays (3, …), the components first). For a primal slack ``s``
and a dual multiplier ``λ`` in the interior of a cone, the Nesterov–Todd scaling ``W`` is the
symmetric matrix with ``W⁻¹ s = W λ = v`` (the scaled point); the formulas, the Jordan product
``u ∘ v = (uᵀv, u₀ v₁ + v₀ u₁)`` and its inverse are those of L. Vandenberghe, "The CVXOPT linear
and quadratic cone program solvers" (2010), §§2–4:

    s̄ = s / √(sᵀJs),  λ̄ = λ / √(λᵀJλ),  γ = √((1 + s̄ᵀλ̄) / 2),  w̄ = (s̄ + Jλ̄) / (2γ),
    w = (w̄ + e) / √(2 (w̄₀ + 1))  (w̄'s square root),  β = (sᵀJs / λᵀJλ)^¼,
    W = β (2 w wᵀ − J),  W⁻¹ = (2 J w wᵀ J − J) / β,

with ``J = diag(1, −1, −1)``. ``u₀² − ‖u₁‖²`` is computed as ``(u₀ − ‖u₁‖)(u₀ + ‖u₁‖)``.
"""

from __future__ import annotations

import numpy as np

_J = np.array([1.0, -1.0, -1.0])


def soc_det(u: np.ndarray) -> np.ndarray:
    """``u₀² − u₁² − u₂²`` of (3, …) arrays (positive in the cone's interior)."""
    r = np.hypot(u[1], u[2])
    return (u[0] - r) * (u[0] + r)


def soc_residual(u: np.ndarray) -> np.ndarray:
    """``u₀ − ‖(u₁, u₂)‖``: ≥ 0 in the cone."""
    return u[0] - np.hypot(u[1], u[2])


class SocScaling:
    """The Nesterov–Todd scaling of (3, …) SOC pairs ``(s, λ)`` in the cone's interior."""

    def __init__(self, s: np.ndarray, lam: np.ndarray) -> None:
        ds = np.maximum(soc_det(s), 1e-300)
        dl = np.maximum(soc_det(lam), 1e-300)
        rs, rl = np.sqrt(ds), np.sqrt(dl)
        sb, lb = s / rs, lam / rl
        gamma = np.sqrt(np.maximum((1.0 + np.einsum("k...,k...->...", sb, lb)) / 2.0, 1e-300))
        wbar = (sb + _J.reshape((3,) + (1,) * (s.ndim - 1)) * lb) / (2.0 * gamma)
        # The hyperbolic Householder vector: w = w̄^½ = (w̄ + e) / √(2 (w̄₀ + 1)), W = β(2wwᵀ − J).
        wbar[0] += 1.0
        self.w = wbar / np.sqrt(2.0 * wbar[0])
        self.beta = np.sqrt(rs / rl)
        # The scaled point v = W λ = W⁻¹ s, in CVXOPT's closed form (accurate near the boundary).
        d = 2.0 * gamma + sb[0] + lb[0]
        v = np.empty_like(wbar)
        v[0] = gamma
        v[1:] = ((gamma + lb[0]) / d) * sb[1:] + ((gamma + sb[0]) / d) * lb[1:]
        self.v = v * np.sqrt(rs * rl)

    def _jw(self) -> np.ndarray:
        return _J.reshape((3,) + (1,) * (self.w.ndim - 1)) * self.w

    def apply(self, u: np.ndarray) -> np.ndarray:
        """``W u``."""
        w = self.w
        ju = _J.reshape((3,) + (1,) * (u.ndim - 1)) * u
        return self.beta * (2.0 * w * np.einsum("k...,k...->...", w, u) - ju)

    def apply_inverse(self, u: np.ndarray) -> np.ndarray:
        """``W⁻¹ u``."""
        jw = self._jw()
        ju = _J.reshape((3,) + (1,) * (u.ndim - 1)) * u
        return (2.0 * jw * np.einsum("k...,k...->...", jw, u) - ju) / self.beta

    def inverse_square(self) -> np.ndarray:
        """``W⁻²`` as (3, 3, …) symmetric matrices:
        ``(4‖w‖² Jw (Jw)ᵀ − 2 (Jw wᵀ + w (Jw)ᵀ) + I) / β²``."""
        w = self.w
        n2 = np.einsum("k...,k...->...", w, w)
        b2 = self.beta**2
        Q = np.empty((3, 3, *w.shape[1:]))
        Q[0, 0] = (4.0 * n2 * w[0] ** 2 - 4.0 * w[0] ** 2 + 1.0) / b2
        for i in (1, 2):
            Q[0, i] = Q[i, 0] = -4.0 * n2 * w[0] * w[i] / b2
            for j in range(i, 3):
                Q[i, j] = Q[j, i] = (4.0 * (n2 + 1.0) * w[i] * w[j] + (i == j)) / b2
        return Q


def jordan(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """The SOC Jordan product ``u ∘ v = (uᵀv, u₀ v₁ + v₀ u₁)`` of (3, …) arrays."""
    out = np.empty(np.broadcast_shapes(u.shape, v.shape))
    out[0] = np.einsum("k...,k...->...", u, v)
    out[1:] = u[0] * v[1:] + v[0] * u[1:]
    return out


def jordan_solve(v: np.ndarray, d: np.ndarray) -> np.ndarray:
    """``x`` with ``v ∘ x = d`` for ``v`` in the SOC's interior ((3, …) arrays)."""
    x = np.empty(np.broadcast_shapes(v.shape, d.shape))
    x[0] = (v[0] * d[0] - v[1] * d[1] - v[2] * d[2]) / soc_det(v)
    x[1:] = (d[1:] - x[0] * v[1:]) / v[0]
    return x


def soc_max_step(v: np.ndarray, d: np.ndarray) -> np.ndarray:
    """Largest ``α ≥ 0`` with ``v + α d`` in the SOC (inf if the ray stays in it), for ``v`` in
    its interior; (3, …) arrays → (…)."""
    c = soc_det(v)
    b = 2.0 * (v[0] * d[0] - v[1] * d[1] - v[2] * d[2])
    a = d[0] ** 2 - d[1] ** 2 - d[2] ** 2
    # Smallest positive root of a α² + b α + c (c > 0); none: the ray never leaves the cone.
    disc = b * b - 4.0 * a * c
    sq = np.sqrt(np.maximum(disc, 0.0))
    q = -0.5 * (b + np.where(b >= 0, sq, -sq))
    r1 = np.where(a != 0, q / np.where(a != 0, a, 1.0), np.inf)
    r2 = np.where(q != 0, c / np.where(q != 0, q, 1.0), np.inf)
    r1 = np.where(r1 > 0, r1, np.inf)
    r2 = np.where(r2 > 0, r2, np.inf)
    root = np.minimum(r1, r2)
    # A real root where the ray crosses the negative cone's boundary is not an exit from Q:
    # keep only roots where v₀ + α d₀ ≥ 0.
    out = np.where((disc >= 0) & (v[0] + root * d[0] >= -1e-12 * np.abs(v[0])), root, np.inf)
    return out


def nn_max_step(s: np.ndarray, d: np.ndarray) -> np.ndarray:
    """Largest ``α ≥ 0`` with ``s + α d ≥ 0`` elementwise, for ``s > 0`` (inf if d ≥ 0)."""
    return np.where(d < 0, -s / np.where(d < 0, d, -1.0), np.inf)
