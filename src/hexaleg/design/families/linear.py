"""The linear family: τ = τ₀ − k (q − c), no geometry.

A linear spring's reference angle changes nothing (τ₀ − k (q − q_r) spans the same torques for
every q_r), so its optimum over the magnitudes — ``k`` ≥ 0 and ``torque_at_reference`` of any
sign — is already the global one.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from hexaleg.design.families.family import Element, Family, Geometry
from hexaleg.robot.springs import LinearSpring, Spring, Term


class Linear(Family):
    """``linear``: a linear spring (module docstring)."""

    name = "linear"
    law = LinearSpring
    magnitudes = ("k", "torque_at_reference")
    elements = (Element(0, 1, linear=True),)

    def terms(self, geometry: Geometry, centre: float) -> tuple[Term, ...]:
        """``k`` on the angle from the centre, and the constant ``torque_at_reference``."""
        return (Term("linear", centre, "k"), Term("constant", centre, "torque_at_reference"))

    def spring(self, geometry: Geometry, centre: float, x: Sequence[float] | np.ndarray
               ) -> Spring:
        """The linear spring of ``k`` and ``torque_at_reference`` about the centre."""
        m = self.clipped(x)
        return LinearSpring(m["k"], centre, m["torque_at_reference"])


__all__ = ["Linear"]
