"""The one-sided family: one stop ``contact`` acting on one ``side`` (above or below it), with a
stiffness ``k`` and a preload (both ≥ 0): a torsion spring that only pushes one way."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import ClassVar

import numpy as np

from hexaleg.design.families.family import Element, Family, Geometry
from hexaleg.errors import UnknownNameError
from hexaleg.robot.springs import SIDES, OneSidedSpring, Spring, Term


class OneSided(Family):
    """``one_sided``: one preloaded stop on one side (module docstring)."""

    name = "one_sided"
    law = OneSidedSpring
    angles = ("contact",)
    magnitudes = ("k", "preload")
    elements = (Element(0, 1),)
    preloaded_stops = True
    stops: ClassVar[Mapping[str, tuple[str, ...]]] = {"contact": ("k", "preload")}
    swap: ClassVar[Mapping[str, str]] = {"contact": "contact"}

    def side(self, angle: str, geometry: Geometry) -> str:
        """The geometry's ``side``."""
        return str(geometry["side"])

    def labels(self, geometry: Geometry, where: str) -> dict[str, float | str]:
        """``side``, one of :data:`hexaleg.robot.springs.SIDES` (default above).

        Raises:
            UnknownNameError: another side (lists them).
        """
        side = geometry.get("side", "above")
        if side not in SIDES:
            raise UnknownNameError(f"{where}.side", side, SIDES)
        return {"side": side}

    def terms(self, geometry: Geometry, centre: float) -> tuple[Term, ...]:
        """``k`` and ``preload`` past ``contact`` on its side."""
        side, contact = str(geometry["side"]), centre + float(geometry["contact"])
        return (Term(side, contact, "k"), Term(f"step_{side}", contact, "preload"))

    def spring(self, geometry: Geometry, centre: float, x: Sequence[float] | np.ndarray
               ) -> Spring:
        """The one-sided spring at the absolute contact angle."""
        m = self.clipped(x)
        return OneSidedSpring(m["k"], centre + float(geometry["contact"]), str(geometry["side"]),
                              m["preload"])

    def mirrored_labels(self, geometry: Geometry) -> dict[str, float | str]:
        """The other side."""
        return {"side": "below" if geometry["side"] == "above" else "above"}

    def off(self, below: float, above: float, step: float) -> dict[str, float | str]:
        """The stop above every sample, acting above."""
        return {"contact": above, "side": "above"}


__all__ = ["OneSided"]
