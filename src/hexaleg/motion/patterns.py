"""Gait patterns: each leg's touch-down phase and the conventional duty factor, by name.

A periodic gait (:func:`hexaleg.motion.legged.gait`) puts leg i in stance while its phase
``φ_i(t) = (t / period − o_i) mod 1`` is below the duty factor β; ``o_i`` is its touch-down
offset (a fraction of the period). The offsets come from, in this order of precedence,

* ``GaitParams.phases``: one offset per leg, in the robot's leg order (any values in [0, 1));
* ``GaitParams.pattern``: a named pattern of :data:`PATTERNS`, from the legs' names (side
  ``L``/``R`` then the place from the front, ``F M H`` or ``1 2 3``; :func:`leg_places`);
* ``GaitParams.groups``: group i of n touches down at ``o = i / n``.

The hexapod patterns and the quadruped crawl are forward **wave gaits** (McGhee & Frank, "On the
stability properties of quadruped creeping gaits", Math. Biosci. 3, 1968; Song & Waldron,
*Machines That Walk*, MIT Press 1989, ch. 2): along each side the legs are placed from back to
front, each one lifted as the one behind it lands — an ipsilateral phase lag of ``1 − β₀`` —
and the two sides are half a cycle apart::

    o(side, k) = (n − 1 − k) (1 − β₀) + (0 for L, ½ for R)   mod 1

with k the leg's place on its side from the front (0) and n legs a side, at the pattern's own
duty factor β₀. β₀ = ½ gives the alternating tripod, ⅔ the ripple (one leg of each side in the
air at a time, the sides half a cycle apart; also called tetrapod), ⅚ the hexapod wave (one leg
at a time), and on four legs β₀ = ⅘ the crawl (lateral sequence LH → LF → RH → RF with a
four-foot phase at each diagonal switch, where the body must cross from one support triangle to
the other; McGhee & Frank's optimally stable creeping gait needs β ≥ ¾). The trot moves the
diagonal pairs together, the pace the lateral pairs (Hildebrand, "Symmetrical gaits of horses",
Science 150, 1965). The offsets are fixed by the pattern; ``GaitParams.duty_factor`` defaults
to β₀ and may be set to any β in (0, 1).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from fractions import Fraction
from types import MappingProxyType
from typing import Any

import numpy as np

from hexaleg.errors import InvalidParameterError, UnknownNameError

PLACES: Mapping[str, int] = MappingProxyType({"F": 0, "M": 1, "H": 2})
"""Rank from the front of the place letters of hexaleg's leg names."""


@dataclass(frozen=True)
class Pattern:
    """A named gait pattern.

    Attributes:
        name: Its name (a key of :data:`PATTERNS`).
        legs_per_side: How many legs a side the pattern is for (3: hexapod, 2: quadruped).
        duty_factor: β₀, the conventional duty factor (the default of ``GaitParams``).
        min_stance_feet: Feet on the ground at every instant at β₀.
        static: Whether the pattern stands on a support polygon throughout (≥ 3 feet) and so
            promises a positive static margin (with the body shift where needed).
        offset: ``offset(side, k, n)``: the touch-down offset of the leg at place k (0 = front)
            of side ``"L"``/``"R"`` with n legs a side, a fraction of the period.
    """

    name: str
    legs_per_side: int
    duty_factor: Fraction
    min_stance_feet: int
    static: bool
    offset: Callable[[str, int, int], Fraction]


def _wave(beta: Fraction) -> Callable[[str, int, int], Fraction]:
    """The forward wave gait's offsets at duty factor β₀ (module docstring)."""
    def offset(side: str, k: int, n: int) -> Fraction:
        return ((n - 1 - k) * (1 - beta) + (Fraction(1, 2) if side == "R" else 0)) % 1
    return offset


def _pairs(together: Callable[[str, int], bool]) -> Callable[[str, int, int], Fraction]:
    """Two pairs half a cycle apart: the legs for which ``together(side, k)`` holds at 0."""
    def offset(side: str, k: int, n: int) -> Fraction:
        return Fraction(0) if together(side, k) else Fraction(1, 2)
    return offset


PATTERNS: Mapping[str, Pattern] = MappingProxyType({p.name: p for p in (
    Pattern("tripod", 3, Fraction(1, 2), 3, True, _wave(Fraction(1, 2))),
    Pattern("ripple", 3, Fraction(2, 3), 4, True, _wave(Fraction(2, 3))),
    Pattern("wave", 3, Fraction(5, 6), 5, True, _wave(Fraction(5, 6))),
    Pattern("crawl", 2, Fraction(4, 5), 3, True, _wave(Fraction(4, 5))),
    Pattern("trot", 2, Fraction(1, 2), 2, False, _pairs(lambda s, k: (s == "L") == (k == 0))),
    Pattern("pace", 2, Fraction(1, 2), 2, False, _pairs(lambda s, k: s == "L")),
)})
"""The named patterns: hexapod ``tripod`` (β₀ ½), ``ripple`` (⅔), ``wave`` (⅚); quadruped
``crawl`` (⅘), ``trot`` (½), ``pace`` (½)."""


def check_pattern(name: Any) -> str:
    """``name`` if it names a pattern of :data:`PATTERNS`.

    Raises:
        UnknownNameError: otherwise; the message lists the patterns.
    """
    if not isinstance(name, str) or name not in PATTERNS:
        raise UnknownNameError("gait pattern", name, PATTERNS)
    return name


def leg_places(legs: Sequence[str]) -> list[tuple[str, int]] | None:
    """Side and place of each leg from its name: ``(side, k)`` with k the rank among that side's
    legs from the front (``LF LM LH`` → 0 1 2; ``L1 L2`` → 0 1).

    Args:
        legs: Leg names in hexaleg's convention: side ``L``/``R``, then ``F M H`` or ``1 2 3 …``.

    Returns:
        One ``(side, k)`` per leg, or None when a name does not follow the convention.
    """
    ranked = []
    for name in legs:
        side, place = name[:1], name[1:]
        rank = PLACES.get(place, int(place) - 1 if place.isdigit() else None)
        if side not in ("L", "R") or rank is None:
            return None
        ranked.append((side, rank))
    out = []
    for side, rank in ranked:
        out.append((side, sorted(r for s, r in ranked if s == side).index(rank)))
    return out


def pattern_offsets(name: str, legs: Sequence[str]) -> np.ndarray:
    """The touch-down offsets of pattern ``name`` for legs ``legs``, shape (n_legs,).

    Args:
        name: A key of :data:`PATTERNS`.
        legs: The robot's leg names, in its order.

    Returns:
        Offsets in [0, 1), fractions of the period (exact ratios, rounded once to float).

    Raises:
        UnknownNameError: no such pattern (lists them).
        InvalidParameterError: the leg names do not say side and place, or the robot does not
            have the pattern's legs per side (the message lists the patterns that fit).
    """
    pattern = PATTERNS[check_pattern(name)]
    places = leg_places(legs)
    if places is None:
        raise InvalidParameterError(
            "pattern", name, f"legs named by side and place (L/R then F M H or 1 2 …); this "
            f"robot's legs are {', '.join(legs)}: give GaitParams.phases or groups instead")
    sides = {s: sum(1 for side, _ in places if side == s) for s in ("L", "R")}
    n = pattern.legs_per_side
    if sides != {"L": n, "R": n}:
        fit = [p.name for p in PATTERNS.values()
               if sides == {"L": p.legs_per_side, "R": p.legs_per_side}]
        raise InvalidParameterError(
            "pattern", name, f"a pattern for {sides['L']} + {sides['R']} legs: "
            f"{', '.join(fit) or 'none named; give GaitParams.phases or groups'} (pattern "
            f"{name!r} is for {n} legs a side)")
    return np.array([float(pattern.offset(side, k, n)) for side, k in places])


def leg_offsets(legs: Sequence[str], pattern: str | None, phases: Sequence[float] | None,
                groups: Sequence[Sequence[str]]) -> np.ndarray:
    """Each leg's touch-down offset, shape (n_legs,): from ``phases``, else ``pattern``, else
    ``groups`` (module docstring).

    Args:
        legs: The robot's leg names, in its order.
        pattern: A pattern name, or None.
        phases: One offset per leg in ``legs`` order, or None.
        groups: Leg groups; group i of n touches down at i / n.

    Raises:
        InvalidParameterError: ``phases`` of the wrong length, a pattern that does not fit the
            legs, or a leg in no group.
        UnknownNameError: a grouped leg the robot does not have, or an unknown pattern.
    """
    if phases is not None:
        if len(phases) != len(legs):
            raise InvalidParameterError(
                "phases", list(phases), f"{len(legs)} touch-down offsets in [0, 1), one per leg "
                f"in the robot's order {', '.join(legs)}")
        return np.asarray(phases, dtype=float)
    if pattern is not None:
        return pattern_offsets(pattern, legs)
    offset = {}
    for i, group in enumerate(groups):
        for leg in group:
            if leg not in legs:
                raise UnknownNameError("leg", leg, legs)
            offset[leg] = i / len(groups)
    missing = [leg for leg in legs if leg not in offset]
    if missing:
        raise InvalidParameterError("groups", groups,
                                    f"every leg of the robot in a group; missing {missing}")
    return np.array([offset[leg] for leg in legs])


def groups_of(legs: Sequence[str], offsets: np.ndarray) -> tuple[tuple[str, ...], ...]:
    """The legs grouped by equal touch-down offset, groups in order of their offset.

    Args:
        legs: Leg names.
        offsets: Their offsets, shape (n_legs,).
    """
    order = sorted(set(np.round(offsets, 12).tolist()))
    return tuple(tuple(leg for leg, o in zip(legs, np.round(offsets, 12), strict=True) if o == x)
                 for x in order)
