"""A linear torsion spring with a free equilibrium angle: τ = τ₀ − k (q − q_r).

Hooke's law for a helical torsion spring (Shigley's Mechanical Engineering Design, 10th ed.,
§10-12: M = k' θ) mounted so that at the reference angle q_r it already applies ``τ₀``; its
equilibrium angle is ``q_r + τ₀ / k``. With k = 0 and τ₀ ≠ 0 it is a constant-torque spring
(a spring motor or a gravity compensator), which this law states directly instead of as a
dead-zone spring of zero width.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hexaleg.checks import named_arguments, real
from hexaleg.robot.springs.law import TermSpring, magnitude
from hexaleg.robot.springs.terms import Term


@named_arguments
@dataclass(frozen=True)
class LinearSpring(TermSpring):
    """τ(q) = torque_at_reference − stiffness · (q − reference); U = ½ k (q − q_r)² − τ₀ (q − q_r).

    Attributes:
        stiffness: k, N·m/rad, ≥ 0.
        reference: q_r, rad (absolute joint angle).
        torque_at_reference: τ₀, N·m, the torque at q_r (any sign).

    Raises:
        InvalidParameterError: k < 0 or a value that is not a finite number.
    """

    stiffness: float
    reference: float = 0.0
    torque_at_reference: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", magnitude("stiffness", self.stiffness))
        for name in ("reference", "torque_at_reference"):
            object.__setattr__(self, name, real(name, getattr(self, name)))

    @property
    def equilibrium(self) -> float | None:
        """The angle where the torque is zero, rad; None for a constant-torque spring (k = 0)."""
        if self.stiffness == 0.0:
            return None if self.torque_at_reference else self.reference
        return self.reference + self.torque_at_reference / self.stiffness

    def terms(self) -> tuple[Term, ...]:
        return (Term("linear", self.reference, "k"),
                Term("constant", self.reference, "torque_at_reference"))

    def magnitudes(self) -> np.ndarray:
        return np.array([self.stiffness, self.torque_at_reference])
