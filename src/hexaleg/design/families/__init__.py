"""Spring families as the design program sees them: a geometry, basis terms, magnitudes.

Each family is one module of this package — a :class:`~hexaleg.design.families.family.Family`
subclass: its angles, magnitudes, elements, terms, law, mirror, and the families it contains —
and one entry of :data:`_FAMILIES` below; :mod:`hexaleg.design.search.optimal`, the search, the
scan, the design chain, ``design.json`` and the commands ask this registry.

=============  ============================  ====================================================
family         geometry (rad, from centre)   magnitudes (SI)
=============  ============================  ====================================================
``linear``     none (the constant is free)   ``k`` ≥ 0, ``torque_at_reference`` (any sign)
``dead_zone``  ``theta_minus < theta_plus``  ``k_plus``, ``k_minus`` ≥ 0 (eq. 8, α = 1)
``preloaded``  ``theta_minus ≤ theta_plus``  ``k_plus``, ``k_minus``, ``preload_plus``,
                                             ``preload_minus`` ≥ 0
``one_sided``  ``contact``, ``side``         ``k``, ``preload`` ≥ 0
``stiffening`` ``above_1 < above_2``,        ``k_above_1``, ``k_above_2``, ``k_below_1``,
               ``below_1 > below_2``         ``k_below_2`` ≥ 0 (added stiffness per stage)
=============  ============================  ====================================================
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from hexaleg.checks import one_of
from hexaleg.design.families.dead_zone import LINEAR_GAP, LINEAR_REACH, DeadZone
from hexaleg.design.families.family import IDLE, ZERO_MAGNITUDE, Element, Family, Geometry
from hexaleg.design.families.linear import Linear
from hexaleg.design.families.one_sided import OneSided
from hexaleg.design.families.preloaded import Preloaded
from hexaleg.design.families.stiffening import STAGE_OFF, Stiffening

_FAMILIES: dict[str, Family] = {f.name: f for f in (
    Linear(), DeadZone(), Preloaded(), OneSided(), Stiffening())}
"""The registry: a new family is one module and one entry here."""
FAMILIES: tuple[str, ...] = tuple(_FAMILIES)
"""Spring families :func:`hexaleg.design.search.optimal.optimal_springs` designs."""
CONTAINS: dict[str, tuple[str, ...]] = {n: f.contains for n, f in _FAMILIES.items()
                                        if f.contains}
"""Family → the families it contains (their every law is one of its laws, :func:`embed`)."""


def family(name: str) -> Family:
    """The family called ``name``.

    Raises:
        UnknownNameError: not one of :data:`FAMILIES` (lists them).
    """
    return _FAMILIES[one_of("spring family", name, FAMILIES)]


def containment_waves(names: Sequence[str]) -> list[list[str]]:
    """``names`` in waves, each family in a wave after every family of ``names`` with a geometry
    it contains (:data:`CONTAINS`, transitively), in their order within a wave: the families of
    one wave can be designed side by side, each from the optima of those it contains (one
    without geometry, ``linear``, is one convex solve: designed again where needed rather than
    waited for)."""
    def depth(name: str) -> int:
        return max((depth(f) + 1 for f in CONTAINS.get(name, ())
                    if f in names and _FAMILIES[f].angles), default=0)

    levels = [depth(n) for n in names]
    return [[n for n, lv in zip(names, levels, strict=True) if lv == i]
            for i in range(max(levels, default=-1) + 1)]


def embed(outer: str, inner: str, geometry: Geometry, magnitudes: Mapping[str, float],
          off: tuple[float, float]) -> dict[str, float | str]:
    """The geometry of family ``outer`` whose laws include ``inner``'s law of ``geometry`` and
    ``magnitudes`` (rad from the centre of motion; :meth:`Family.embed` of ``outer``).

    ``off``: (an angle below, an angle above) every sample's, rad from the centre: a stop there
    never engages.

    Raises:
        InvalidParameterError: ``outer`` does not contain ``inner`` (:data:`CONTAINS`).
    """
    return family(outer).embed(family(inner), geometry, magnitudes, off)


__all__ = ["CONTAINS", "FAMILIES", "IDLE", "LINEAR_GAP", "LINEAR_REACH", "STAGE_OFF",
           "ZERO_MAGNITUDE", "Element", "Family", "Geometry", "containment_waves", "embed",
           "family"]
