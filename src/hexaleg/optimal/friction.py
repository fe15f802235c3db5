"""The friction cone of a stance foot as a Crocoddyl activation of its contact force.

A foot's force ``λ`` (world-aligned axes; level ground, normal ``z``) must lie in the friction
cone ``‖λ_t‖ ≤ μ λ_z``; the problem takes its inner pyramid of four facets (Trinkle et al., "On
dynamic multi-rigid-body contact problems with Coulomb friction", ZAMM 77(4), 1997; Crocoddyl's
``FrictionCone`` with ``inner_appr``): ``A λ ≤ 0`` with the rows ``(±1, 0, −μ/√2)``,
``(0, ±1, −μ/√2)`` and ``(0, 0, −1)`` (the foot pushes, it never pulls). The activation is the
quadratic barrier ``a(λ) = ½ Σ_i max(A_i λ, 0)²`` — zero inside the pyramid — of Crocoddyl's
``ResidualModelContactForce`` (the residual ``λ − 0``); its gradient ``Aᵀ max(Aλ, 0)`` and
Gauss–Newton Hessian ``Σ_{i active} A_iᵀ A_i``.

(Crocoddyl 3.2.1's own ``ResidualModelContactFrictionCone`` fails to create its data on the
robots of this package — a ``MemoryError`` from its constructor — hence this activation of the
force residual, which does the same.)
"""

from __future__ import annotations

from typing import Any

import numpy as np

from hexaleg.checks import positive
from hexaleg.optimal.backend import crocoddyl_module

crocoddyl = crocoddyl_module()
_ActivationModelAbstract: Any = crocoddyl.ActivationModelAbstract
"""Crocoddyl's base class (typed Any: Crocoddyl ships no type information)."""


def pyramid(mu: float) -> np.ndarray:
    """The inner pyramid's rows ``A`` (5, 3) of the cone of friction ``mu`` (module docstring)."""
    positive("friction coefficient", mu)
    s = mu / np.sqrt(2.0)
    return np.array([[1.0, 0.0, -s], [-1.0, 0.0, -s], [0.0, 1.0, -s], [0.0, -1.0, -s],
                     [0.0, 0.0, -1.0]])


class FrictionPyramid(_ActivationModelAbstract):
    """``a(λ) = ½ Σ max(A λ, 0)²`` of a 3-D force residual (module docstring).

    Args:
        mu: The friction coefficient the pyramid is inscribed in.
    """

    def __init__(self, mu: float) -> None:
        crocoddyl.ActivationModelAbstract.__init__(self, 3)
        self.rows = pyramid(mu)

    def calc(self, data: Any, r: np.ndarray) -> None:
        """``data.a_value``: the barrier's value."""
        out = np.maximum(self.rows @ np.asarray(r), 0.0)
        data.a_value = 0.5 * float(out @ out)

    def calcDiff(self, data: Any, r: np.ndarray) -> None:
        """``data.Ar``, ``data.Arr``: its gradient and Gauss–Newton Hessian."""
        g = self.rows @ np.asarray(r)
        active = self.rows[g > 0.0]
        data.Ar[:] = self.rows.T @ np.maximum(g, 0.0)
        data.Arr[:, :] = active.T @ active
