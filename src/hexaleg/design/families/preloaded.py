"""The preloaded family: two stops ``theta_minus ≤ theta_plus``, past each a stiffness and a
preload (``k_plus``, ``k_minus``, ``preload_plus``, ``preload_minus`` ≥ 0). Every stop carries a
free preload, so a stop's best place is just before a sample
(:mod:`hexaleg.design.search.geometry`). It contains ``one_sided``, ``dead_zone`` and ``linear``."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import ClassVar

import numpy as np

from hexaleg.design.families.family import Element, Family, Geometry
from hexaleg.robot.springs import PreloadedSpring, Spring, Term


class Preloaded(Family):
    """``preloaded``: two preloaded stops (module docstring)."""

    name = "preloaded"
    law = PreloadedSpring
    angles = ("theta_minus", "theta_plus")
    magnitudes = ("k_plus", "k_minus", "preload_plus", "preload_minus")
    elements = (Element(0, 2), Element(1, 3))
    order = (("theta_minus", "theta_plus", False),)
    preloaded_stops = True
    above = ("theta_plus",)
    stops: ClassVar[Mapping[str, tuple[str, ...]]] = {
        "theta_plus": ("k_plus", "preload_plus"), "theta_minus": ("k_minus", "preload_minus")}
    contains = ("one_sided", "dead_zone", "linear")
    swap: ClassVar[Mapping[str, str]] = {"theta_minus": "theta_plus", "theta_plus": "theta_minus"}
    swap_magnitudes: ClassVar[Mapping[str, str]] = {
        "k_plus": "k_minus", "k_minus": "k_plus", "preload_plus": "preload_minus",
        "preload_minus": "preload_plus"}

    def terms(self, geometry: Geometry, centre: float) -> tuple[Term, ...]:
        """Stiffness and preload above ``theta_plus``, and below ``theta_minus``."""
        plus, minus = centre + float(geometry["theta_plus"]), centre + float(
            geometry["theta_minus"])
        return (Term("above", plus, "k_plus"), Term("below", minus, "k_minus"),
                Term("step_above", plus, "preload_plus"),
                Term("step_below", minus, "preload_minus"))

    def spring(self, geometry: Geometry, centre: float, x: Sequence[float] | np.ndarray
               ) -> Spring:
        """The preloaded spring, neutral at the centre."""
        m = self.clipped(x)
        return PreloadedSpring(stiffness=m["k_plus"], preload=m["preload_plus"],
                               theta_minus=float(geometry["theta_minus"]),
                               theta_plus=float(geometry["theta_plus"]),
                               stiffness_minus=m["k_minus"], preload_minus=m["preload_minus"],
                               neutral=centre)

    def embed(self, inner: Family, geometry: Geometry, magnitudes: Mapping[str, float],
              off: tuple[float, float]) -> dict[str, float | str]:
        """One-sided and dead-zone laws with a side off or no preload; a linear law
        τ₀ − k (q − c) with both stops at θ = τ₀ / k (k > 0; k = 0, a constant torque: both
        stops beyond the motion on the side whose preload gives it)."""
        below, above = off
        if inner.name == "one_sided":
            c = float(geometry["contact"])
            return ({"theta_minus": min(below, c), "theta_plus": c}
                    if geometry["side"] == "above"
                    else {"theta_minus": c, "theta_plus": max(above, c)})
        if inner.name == "dead_zone":
            return {"theta_minus": float(geometry["theta_minus"]),
                    "theta_plus": float(geometry["theta_plus"])}
        if inner.name == "linear":
            k, torque = float(magnitudes["k"]), float(magnitudes["torque_at_reference"])
            # k = 0: a constant torque, a preload with both stops beyond the motion on one side
            theta = torque / k if k > 0 else above if torque > 0 else below
            return {"theta_minus": theta, "theta_plus": theta}
        return super().embed(inner, geometry, magnitudes, off)


__all__ = ["Preloaded"]
