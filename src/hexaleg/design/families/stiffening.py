"""The stiffening family: two stages on each side, ``above_1 < above_2`` and
``below_1 > below_2``, each adding its stiffness (``k_above_1``, ``k_above_2``, ``k_below_1``,
``k_below_2`` ≥ 0) past its angle. It contains ``dead_zone`` (its second stages unused)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import ClassVar

import numpy as np

from hexaleg.design.families.family import Element, Family, Geometry
from hexaleg.robot.springs import Spring, StiffeningSpring, Term

STAGE_OFF = 0.1
"""rad beyond the first stage (and every sample) where an unused second stage is put."""
STAGES = ("above_1", "above_2", "below_1", "below_2")
"""The stages' angles, in magnitude order."""


class Stiffening(Family):
    """``stiffening``: two stages a side (module docstring)."""

    name = "stiffening"
    law = StiffeningSpring
    angles = STAGES
    magnitudes = ("k_above_1", "k_above_2", "k_below_1", "k_below_2")
    elements = (Element(0), Element(1), Element(2), Element(3))
    order = (("above_1", "above_2", True), ("below_2", "below_1", True))
    above = ("above_1", "above_2")
    stops: ClassVar[Mapping[str, tuple[str, ...]]] = {a: (f"k_{a}",) for a in STAGES}
    contains = ("dead_zone",)
    swap: ClassVar[Mapping[str, str]] = {
        "above_1": "below_1", "above_2": "below_2", "below_1": "above_1", "below_2": "above_2"}
    swap_magnitudes: ClassVar[Mapping[str, str]] = {
        "k_above_1": "k_below_1", "k_above_2": "k_below_2", "k_below_1": "k_above_1",
        "k_below_2": "k_above_2"}

    def terms(self, geometry: Geometry, centre: float) -> tuple[Term, ...]:
        """Each stage's stiffness past its angle, on its side."""
        a = {k: centre + float(geometry[k]) for k in STAGES}
        return (Term("above", a["above_1"], "k_above_1"), Term("above", a["above_2"], "k_above_2"),
                Term("below", a["below_1"], "k_below_1"), Term("below", a["below_2"], "k_below_2"))

    def spring(self, geometry: Geometry, centre: float, x: Sequence[float] | np.ndarray
               ) -> Spring:
        """The stiffening spring at the absolute stage angles."""
        m = self.clipped(x)
        a = {k: centre + float(geometry[k]) for k in STAGES}
        return StiffeningSpring(
            above=((a["above_1"], m["k_above_1"]), (a["above_2"], m["k_above_2"])),
            below=((a["below_1"], m["k_below_1"]), (a["below_2"], m["k_below_2"])))

    def off(self, below: float, above: float, step: float) -> dict[str, float | str]:
        """The first stages at ``above`` and ``below``, the second ``step`` further."""
        return {"above_1": above, "above_2": above + step, "below_1": below,
                "below_2": below - step}

    def wound(self, side: str, first: float, below: float, above: float, step: float
              ) -> dict[str, float | str] | None:
        """The first stage of ``side`` at ``first``, every other stage off."""
        if side == "above":
            return {"above_1": first, "above_2": above, "below_1": below, "below_2": below - step}
        return {"above_1": above, "above_2": above + step, "below_1": first,
                "below_2": min(below, first) - step}

    def embed(self, inner: Family, geometry: Geometry, magnitudes: Mapping[str, float],
              off: tuple[float, float]) -> dict[str, float | str]:
        """A dead zone with its second stages :data:`STAGE_OFF` beyond it and every sample."""
        if inner.name != "dead_zone":
            return super().embed(inner, geometry, magnitudes, off)
        below, above = off
        plus, minus = float(geometry["theta_plus"]), float(geometry["theta_minus"])
        return {"above_1": plus, "above_2": max(above, plus) + STAGE_OFF,
                "below_1": minus, "below_2": min(below, minus) - STAGE_OFF}


__all__ = ["STAGE_OFF", "Stiffening"]
