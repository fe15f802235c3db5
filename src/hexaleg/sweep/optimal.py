"""Optimal-spring sweeps: at every gait point, the global optimum of a spring family on sets of
groups, instead of a grid of designs.

A spec with an ``[optimal]`` table (:class:`OptimalSpec`) names the family (one or an axis of
several), which sets of the ``[springs.<group>]`` groups are sprung — one group at a time, all
together, or every non-empty set (a placement study) — and the designer's bounds. Each point is
then (gait, family, set of groups) and its row
(:func:`hexaleg.sweep.runner.optimal_chunk`) holds the optimal magnitudes and geometry
(:func:`hexaleg.design.search.optimal.optimal_springs`) with the metrics of the gait with them.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from hexaleg.checks import real
from hexaleg.config import from_mapping
from hexaleg.design.families import FAMILIES, family
from hexaleg.errors import InvalidParameterError, UnknownNameError

SETS: tuple[str, ...] = ("each", "all", "every")
"""Which sets of groups are sprung: one group at a time, all together, every non-empty set."""

OptimalPoint = tuple[str, tuple[str, ...]]
"""(family, sprung groups) of one point of an optimal-spring sweep."""


@dataclass(frozen=True)
class OptimalSpec:
    """The ``[optimal]`` table of a sweep spec.

    Attributes:
        family: Spring families (:data:`~hexaleg.design.families.FAMILIES`), each an axis value.
        sets: One of :data:`SETS`.
        max_torque: Largest spring torque over the gait, N·m, > 0, or None.
        max_deflection: Largest deflection of a spring from its free position, rad, > 0, or None.

    Raises:
        UnknownNameError: an unknown family or set choice (lists the valid ones).
        InvalidParameterError: no family, a bound not > 0.
    """

    family: tuple[str, ...] = ("linear",)
    sets: str = "each"
    max_torque: float | None = None
    max_deflection: float | None = None

    def __post_init__(self) -> None:
        names = (self.family,) if isinstance(self.family, str) else tuple(self.family)
        if not names:
            raise InvalidParameterError("optimal.family", [], f"one or more of {FAMILIES}")
        for name in names:
            family(name)  # UnknownNameError listing the families
        object.__setattr__(self, "family", names)
        if self.sets not in SETS:
            raise UnknownNameError("optimal.sets", self.sets, SETS)
        for name, unit in (("max_torque", "N·m"), ("max_deflection", "rad")):
            value = getattr(self, name)
            if value is not None:
                real(f"optimal.{name}", value, low=0.0, low_open=True,
                     allowed=f"a finite value > 0 ({unit})")

    @classmethod
    def from_mapping(cls, table: Mapping[str, Any], where: str) -> OptimalSpec:
        """From the parsed ``[optimal]`` table (``family`` a name or a list of names)."""
        data = dict(table)
        if isinstance(data.get("family"), (list, str)):
            value = data["family"]
            data["family"] = (value,) if isinstance(value, str) else tuple(value)
        return from_mapping(cls, data, f"{where} [optimal]")

    def points(self, groups: Sequence[str]) -> list[OptimalPoint]:
        """Every (family, set of groups) of one gait, families the outer loop."""
        sets: list[tuple[str, ...]]
        if self.sets == "each":
            sets = [(g,) for g in groups]
        elif self.sets == "all":
            sets = [tuple(groups)]
        else:
            sets = [c for r in range(1, len(groups) + 1)
                    for c in itertools.combinations(groups, r)]
        return [(f, s) for f in self.family for s in sets]

    def columns(self, groups: Sequence[str]) -> list[str]:
        """``<group>.<name>`` columns: every magnitude and angle of the spec's families."""
        names: list[str] = []
        for f in self.family:
            fam = family(f)
            names += [n for n in (*fam.magnitudes, *fam.angles) if n not in names]
        if "one_sided" in self.family:
            names.append("side")
        return [f"{g}.{n}" for g in groups for n in names]

    def to_dict(self) -> dict[str, Any]:
        """Plain JSON-able data (for the store's manifest)."""
        return {"family": list(self.family), "sets": self.sets, "max_torque": self.max_torque,
                "max_deflection": self.max_deflection}

