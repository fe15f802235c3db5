"""A dead-zone spring held by stops: at each contact angle it meets the lever already wound up.

The paper's eq. 8 spring starts from zero torque at contact. A torsion spring assembled with
pre-tension against a stop instead applies its preload P the moment the lever touches it, and
P + k (compression) beyond (Shigley's Mechanical Engineering Design, 10th ed., §10-12: a torsion
spring's moment is linear in its deflection from free position; the stop holds it at P/k).
With Δ = q − neutral::

    τ = −(P⁺ + k⁺ (Δ − θ⁺))   for Δ > θ⁺          U = P⁺ (Δ − θ⁺) + ½ k⁺ (Δ − θ⁺)²
    τ = +(P⁻ + k⁻ (θ⁻ − Δ))   for Δ < θ⁻          U = P⁻ (θ⁻ − Δ) + ½ k⁻ (θ⁻ − Δ)²
    τ = 0                     in the dead zone     U = 0

The torque jumps at contact; the potential is continuous, so the law is conservative.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hexaleg.checks import named_arguments, real
from hexaleg.robot.springs.law import ContactAngles, TermSpring, magnitude
from hexaleg.robot.springs.terms import Term


@named_arguments
@dataclass(frozen=True)
class PreloadedSpring(TermSpring, ContactAngles):
    """A preloaded dead-zone spring (module docstring).

    Attributes:
        stiffness: k⁺, N·m/rad, ≥ 0 (and k⁻ unless stiffness_minus is given).
        preload: P⁺, N·m, ≥ 0 (and P⁻ unless preload_minus is given).
        theta_k: Symmetric contact angle, rad, ≥ 0 (θ⁻ = −θ_k, θ⁺ = θ_k unless given).
        theta_minus: θ⁻, rad, relative to neutral.
        theta_plus: θ⁺, rad, relative to neutral; θ⁻ ≤ θ⁺.
        stiffness_minus: k⁻, N·m/rad, ≥ 0.
        preload_minus: P⁻, N·m, ≥ 0.
        neutral: Joint angle of the dead zone's reference, rad.

    Raises:
        InvalidParameterError: a negative stiffness or preload, a missing contact angle,
            θ⁻ > θ⁺, or a value that is not a finite number.
    """

    stiffness: float
    preload: float
    theta_k: float | None = None
    theta_minus: float | None = None
    theta_plus: float | None = None
    stiffness_minus: float | None = None
    preload_minus: float | None = None
    neutral: float = 0.0

    def __post_init__(self) -> None:
        for name in ("stiffness", "preload", "stiffness_minus", "preload_minus", "theta_k"):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, magnitude(name, getattr(self, name)))
        for name in ("theta_minus", "theta_plus", "neutral"):
            if getattr(self, name) is not None:
                object.__setattr__(self, name, real(name, getattr(self, name)))
        self.check_contact_angles(strict=False)

    def terms(self) -> tuple[Term, ...]:
        up, down = self.neutral + self.th_plus, self.neutral + self.th_minus
        return (Term("above", up, "k_plus"), Term("below", down, "k_minus"),
                Term("step_above", up, "preload_plus"), Term("step_below", down, "preload_minus"))

    def magnitudes(self) -> np.ndarray:
        k_minus = self.stiffness if self.stiffness_minus is None else self.stiffness_minus
        p_minus = self.preload if self.preload_minus is None else self.preload_minus
        return np.array([self.stiffness, k_minus, self.preload, p_minus])
