"""A spring that engages on one side of a contact angle only (optionally preloaded).

A torsion spring whose leg bears on a stop from one side: past the contact angle it pushes the
joint back with its preload plus Hooke's law (Shigley's Mechanical Engineering Design, 10th ed.,
§10-12); on the other side the lever leaves it and it applies nothing. With side ``"above"``::

    τ = −(P + k (q − θ_c))   for q > θ_c,  else 0;      U = P (q − θ_c)₊ + ½ k (q − θ_c)₊²

and mirrored for ``"below"``. A one-sided spring carries a load that always acts one way (the
body's weight on a knee) without opposing the joint's return.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hexaleg.checks import named_arguments, one_of, real
from hexaleg.robot.springs.law import TermSpring, magnitude
from hexaleg.robot.springs.terms import Term

SIDES: tuple[str, ...] = ("above", "below")
"""Where a one-sided spring engages: for q above its contact angle, or below it."""


@named_arguments
@dataclass(frozen=True)
class OneSidedSpring(TermSpring):
    """A one-sided spring (module docstring).

    Attributes:
        stiffness: k, N·m/rad, ≥ 0.
        contact: θ_c, rad (absolute joint angle) where it engages.
        side: ``"above"`` (engaged for q > θ_c, pushes q down) or ``"below"``.
        preload: P, N·m, ≥ 0, the torque at contact.

    Raises:
        InvalidParameterError: a negative stiffness or preload, an unknown side, or a value that
            is not a finite number.
    """

    stiffness: float
    contact: float
    side: str = "above"
    preload: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "stiffness", magnitude("stiffness", self.stiffness))
        object.__setattr__(self, "preload", magnitude("preload", self.preload))
        object.__setattr__(self, "contact", real("contact", self.contact))
        one_of("side", self.side, SIDES)

    def terms(self) -> tuple[Term, ...]:
        return (Term(self.side, self.contact, "k"),
                Term(f"step_{self.side}", self.contact, "preload"))

    def magnitudes(self) -> np.ndarray:
        return np.array([self.stiffness, self.preload])
