"""Each objective as a per-joint cost of the joint's torque: ``½ ρ τ² + max_k (α_k τ + γ_k τ²)``.

All four objectives of :mod:`hexaleg.dynamics.contact` are sums over joints of a convex function of
that joint's motor torque alone:

- ``"joule"``: ``c τ²`` — ``ρ = 2c``, no pieces;
- ``"torque_squared"``: ``τ²`` — ``ρ = 2``, no pieces;
- ``"positive_work"``: ``max(0, q̇ τ) + ε τ²`` — ``ρ = 2ε``, pieces ``0`` and ``q̇ τ``;
- ``"electrical"``: ``max(0, q̇ τ/η + c τ², η q̇ τ + c τ²) + ε τ²`` — ``ρ = 2ε``, pieces ``0``,
  ``(q̇/η) τ + c τ²`` and ``η q̇ τ + c τ²`` (one fewer where η = 1 everywhere).

Every piece is zero at ``τ = 0``. The interior-point method carries the maximum by an epigraph
variable (:mod:`hexaleg.dynamics.blocks`); the active-set solve (:mod:`hexaleg.dynamics.active_set`)
works on the pieces directly: a joint either lies on one piece or is held at a kink where two
meet (``α_k τ + γ_k τ² = α_l τ + γ_l τ²``: ``τ = 0`` or ``τ = −(α_k − α_l)/(γ_k − γ_l)``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hexaleg.dynamics.contact import QUADRATIC_OBJECTIVES


@dataclass(frozen=True, eq=False)
class Pieces:
    """The per-joint costs of one group's samples.

    Attributes:
        rho: Curvature ``ρ`` of the smooth part, (J, T), W/(N·m)².
        alpha: Linear coefficients of the pieces, (K, J, T), W/(N·m) (K = 0: quadratic
            objectives).
        gamma: Quadratic coefficients of the pieces, (K, J, T), W/(N·m)².
    """

    rho: np.ndarray
    alpha: np.ndarray
    gamma: np.ndarray

    @property
    def K(self) -> int:
        """Number of pieces (0 for the quadratic objectives: no epigraph variables)."""
        return int(self.alpha.shape[0])

    def values(self, tau: np.ndarray) -> np.ndarray:
        """Each piece at ``tau`` (J, T): (K, J, T), W."""
        return (self.alpha + self.gamma * tau) * tau

    def slopes(self, tau: np.ndarray) -> np.ndarray:
        """Each piece's derivative at ``tau`` (J, T): (K, J, T), W/(N·m)."""
        return self.alpha + 2.0 * self.gamma * tau

    def cost(self, tau: np.ndarray) -> np.ndarray:
        """The per-joint cost at ``tau`` (J, T): (J, T), W."""
        out = 0.5 * self.rho * tau * tau
        if self.K:
            out = out + self.values(tau).max(axis=0)
        return out


def pick(stack: np.ndarray, index: np.ndarray) -> np.ndarray:
    """``stack[index[j, t], j, t]`` for ``stack`` (K, J, T) and ``index`` (J, T): each joint's
    entry of its piece (``np.take_along_axis`` as one flat gather, a sweep's hot path)."""
    n = index.size
    return stack.reshape(-1)[index.reshape(-1) * n + np.arange(n)].reshape(index.shape)


def pieces(objective: str, weights: np.ndarray, qdot: np.ndarray, efficiency: np.ndarray,
           regularization: float) -> Pieces:
    """The :class:`Pieces` of ``objective`` for per-joint, per-sample data (J, T).

    Args:
        objective: One of :data:`hexaleg.dynamics.contact.OBJECTIVES`.
        weights: Joule coefficients ``c`` (ones for ``"torque_squared"``), (J, T), W/(N·m)².
        qdot: Joint speeds, (J, T), rad/s.
        efficiency: Gearbox efficiencies η in (0, 1], (J, T).
        regularization: ε of the non-smooth objectives, W/(N·m)².
    """
    if objective in QUADRATIC_OBJECTIVES:
        empty = np.zeros((0, *weights.shape))
        return Pieces(2.0 * weights, empty, empty)
    rho = np.full(weights.shape, 2.0 * regularization)
    zero = np.zeros(weights.shape)
    if objective == "positive_work":
        return Pieces(rho, np.stack([zero, qdot]), np.stack([zero, zero]))
    motoring, generating = qdot / efficiency, qdot * efficiency
    if np.all(efficiency == 1.0):
        return Pieces(rho, np.stack([zero, qdot]), np.stack([zero, weights]))
    return Pieces(rho, np.stack([zero, motoring, generating]), np.stack([zero, weights, weights]))
