"""The dead-zone family (eq. 8 of the paper, α = 1): no torque between two stops
``theta_minus < theta_plus``, a stiffness ``k_plus`` above the upper one and ``k_minus`` below
the lower one (both ≥ 0). It contains ``linear`` (a dead zone :data:`LINEAR_GAP` wide at the
linear spring's equilibrium)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import ClassVar

import numpy as np

from hexaleg.design.families.family import Element, Family, Geometry
from hexaleg.robot.springs import DeadZoneSpring, Spring, Term

LINEAR_GAP = 1e-9
"""rad: the width of the dead zone that stands for a linear spring (a dead zone needs
θ⁻ < θ⁺); the laws differ by k·LINEAR_GAP N·m inside it."""
LINEAR_REACH = 2 * np.pi
"""rad from the centre of motion beyond which a linear spring's equilibrium (a constant torque
where k → 0) is not taken for a dead zone's: its stops would sit turns away (the design's
deflection bound keeps a linear spring's equilibrium within π of the motion)."""


class DeadZone(Family):
    """``dead_zone``: two stops, a stiffness past each (module docstring)."""

    name = "dead_zone"
    law = DeadZoneSpring
    angles = ("theta_minus", "theta_plus")
    magnitudes = ("k_plus", "k_minus")
    elements = (Element(0), Element(1))
    order = (("theta_minus", "theta_plus", True),)
    above = ("theta_plus",)
    stops: ClassVar[Mapping[str, tuple[str, ...]]] = {"theta_plus": ("k_plus",),
                                                      "theta_minus": ("k_minus",)}
    contains = ("linear",)
    swap: ClassVar[Mapping[str, str]] = {"theta_minus": "theta_plus", "theta_plus": "theta_minus"}
    swap_magnitudes: ClassVar[Mapping[str, str]] = {"k_plus": "k_minus", "k_minus": "k_plus"}

    def terms(self, geometry: Geometry, centre: float) -> tuple[Term, ...]:
        """``k_plus`` above ``theta_plus``, ``k_minus`` below ``theta_minus``."""
        return (Term("above", centre + float(geometry["theta_plus"]), "k_plus"),
                Term("below", centre + float(geometry["theta_minus"]), "k_minus"))

    def spring(self, geometry: Geometry, centre: float, x: Sequence[float] | np.ndarray
               ) -> Spring:
        """The dead-zone spring, neutral at the centre."""
        m = self.clipped(x)
        return DeadZoneSpring(stiffness=m["k_plus"], stiffness_minus=m["k_minus"],
                              theta_minus=float(geometry["theta_minus"]),
                              theta_plus=float(geometry["theta_plus"]), neutral=centre)

    def wound(self, side: str, first: float, below: float, above: float, step: float
              ) -> dict[str, float | str] | None:
        """One stop at ``first``, the other :data:`LINEAR_GAP` from it towards the motion."""
        if side == "above":
            return {"theta_minus": first - LINEAR_GAP, "theta_plus": first}
        return {"theta_minus": first, "theta_plus": first + LINEAR_GAP}

    def embed(self, inner: Family, geometry: Geometry, magnitudes: Mapping[str, float],
              off: tuple[float, float]) -> dict[str, float | str]:
        """A linear law τ₀ − k (q − c) as a dead zone :data:`LINEAR_GAP` wide at its equilibrium
        θ = τ₀ / k; none engaged (both stops ``off``) when θ is beyond :data:`LINEAR_REACH`."""
        if inner.name != "linear":
            return super().embed(inner, geometry, magnitudes, off)
        below, above = off
        k, torque = float(magnitudes["k"]), float(magnitudes["torque_at_reference"])
        theta = torque / k if k > 0 else np.inf
        if abs(theta) > LINEAR_REACH:  # a (nearly) constant torque is no dead-zone law
            return {"theta_minus": below, "theta_plus": above}
        return {"theta_minus": theta - LINEAR_GAP / 2, "theta_plus": theta + LINEAR_GAP / 2}


__all__ = ["LINEAR_GAP", "LINEAR_REACH", "DeadZone"]
