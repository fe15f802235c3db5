"""A spring family as the design program sees it: :class:`Family`, the base of each family.

For :func:`hexaleg.design.search.optimal.optimal_springs` a family is split into its *geometry* —
angles the convex program holds fixed, relative to the centre of each joint's range of motion in
the gait (the convention of :mod:`hexaleg.design.evaluator`) — and its *magnitudes*, which are
decision variables because the spring torque is linear in them
(:mod:`hexaleg.robot.springs.terms`). A family says which geometry it has, which terms a
geometry gives on a joint, which magnitudes must be ≥ 0, how each physical spring element
deflects (for ``max_deflection``), which spring law a solution is, how the same spring reads on
a mirrored joint, and where its stops sit when they never engage. Each family is one module of
this package and one entry of its registry (:mod:`hexaleg.design.families`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.robot.springs import Spring, Term

Geometry = Mapping[str, float | str]
"""A family's geometry: angle name → rad from the joint's centre of motion (and ``side``)."""
ZERO_MAGNITUDE = 1e-9
"""The design's zero, SI: a spring term's magnitude — a stiffness (N·m/rad), a preload or a
constant torque (N·m) — or the largest torque one spring element gives over the motion (N·m), at
or below this is none: the term is absent. The convex program's zeros come out exactly 0 or at its
round-off (~1e-12), a real stiffness or preload is ~1e-3 or more. One value serves both units
because they are one quantity here — the radian is dimensionless and a joint's motion is of order
1 rad, so a stiffness at this zero gives a torque at this zero over the motion. Every "is this
term absent" of the design reads it: :meth:`Family.idle` (an angle with no value), the parts to
buy (:func:`hexaleg.design.springs.parts.spring_parts`: no part, or a constant-torque spring),
the constant-torque note of :func:`hexaleg.design.search.optimal.optimal_springs`, the design
page's 0 and the spring laws' JSON (:mod:`hexaleg.design.springs.law_json`)."""
IDLE = "nothing acts past it: any angle gives the same spring"
"""Why an idle angle (:meth:`Family.idle`: zero stiffness and preload past it) has no value in a
design's table."""


@dataclass(frozen=True)
class Element:
    """One physical spring of a law, for ``max_deflection``: the indices of its stiffness term
    and of its preload term (or None) in the family's magnitudes, and whether it is the linear
    spring (deflection |q − q_equilibrium| on both sides) or one engaging past a contact angle."""

    stiffness: int
    preload: int | None = None
    linear: bool = False


class Family:
    """A spring family for the design program (module docstring); a subclass per family.

    Attributes:
        name: The family's name (:data:`hexaleg.design.families.FAMILIES`).
        law: The spring class a solution is (:mod:`hexaleg.robot.springs`).
        angles: Names of the geometry's angles (rad, from each joint's centre of motion).
        magnitudes: Names of the magnitudes, in term order.
        elements: The physical springs (:class:`Element`), for ``max_deflection``.
        order: ``(low, high, strict)``: angle ``low`` ≤ (``strict``: <) angle ``high``.
        preloaded_stops: Every stop carries a free preload ≥ 0 with its stiffness: then the
            design's value is non-increasing in each angle between two samples' angles
            (:mod:`hexaleg.design.search.geometry`), so a stop's best place is just before a sample.
        above: The angles whose terms act on angles above them (the others act below).
        stops: Angle → the magnitudes of the terms at that angle
            (:mod:`hexaleg.design.search.scan`).
        contains: The families whose every law is one of this family's (:meth:`embed` gives the
            geometry).
        swap: Mirror: angle → the angle it becomes (:meth:`mirror`).
        swap_magnitudes: Mirror: magnitude → the magnitude it becomes.
    """

    name: ClassVar[str]
    law: ClassVar[type[Spring]]
    angles: ClassVar[tuple[str, ...]] = ()
    magnitudes: ClassVar[tuple[str, ...]]
    elements: ClassVar[tuple[Element, ...]]
    order: ClassVar[tuple[tuple[str, str, bool], ...]] = ()
    preloaded_stops: ClassVar[bool] = False
    above: ClassVar[tuple[str, ...]] = ()
    stops: ClassVar[Mapping[str, tuple[str, ...]]] = {}
    contains: ClassVar[tuple[str, ...]] = ()
    swap: ClassVar[Mapping[str, str]] = {}
    swap_magnitudes: ClassVar[Mapping[str, str]] = {}

    def __repr__(self) -> str:
        return f"family({self.name!r})"

    def side(self, angle: str, geometry: Geometry) -> str:
        """``"above"`` when the terms at ``angle`` act on angles above it, else ``"below"``."""
        return "above" if angle in self.above else "below"

    def idle(self, magnitudes: Mapping[str, float], zero: float = ZERO_MAGNITUDE
             ) -> tuple[str, ...]:
        """The angles past which nothing acts: every magnitude of the terms at the angle
        (:attr:`stops`) is at most ``zero`` in size, so each term's torque ``m · b(q; angle)``
        (:mod:`hexaleg.robot.springs.terms`) is 0 wherever the angle is. Such an angle is
        whatever the geometry search happened to leave there, not a property of the design:
        outputs print none for it (:data:`IDLE`). In :attr:`angles` order."""
        return tuple(a for a in self.angles
                     if all(abs(float(magnitudes[m])) <= zero for m in self.stops[a]))

    def labels(self, geometry: Geometry, where: str) -> dict[str, float | str]:
        """The geometry's entries that are not angles, checked (none but a one-sided spring's
        ``side``)."""
        return {}

    def check(self, geometry: Geometry, where: str) -> dict[str, float | str]:
        """``geometry`` checked: exactly this family's angles (and its labels), finite, in order.

        Raises:
            UnknownNameError: a parameter the family does not have (lists the ones it has).
            InvalidParameterError: a missing or non-finite angle, angles out of order, a bad
                label.
        """
        allowed = (*self.angles, *self.labels({}, where))
        for key in geometry:
            if key not in allowed:
                raise UnknownNameError(f"{where} geometry parameter of family {self.name}", key,
                                       allowed)
        out: dict[str, float | str] = {}
        for key in self.angles:
            value = geometry.get(key)
            if isinstance(value, (bool, str)) or not isinstance(value, (int, float)) or \
                    not np.isfinite(value):
                raise InvalidParameterError(f"{where}.{key}", value, "a finite angle (rad)")
            out[key] = float(value)
        out.update(self.labels(geometry, where))
        for low, high, strict in self.order:
            a, b = float(out[low]), float(out[high])
            if a > b or (a == b and strict):
                raise InvalidParameterError(f"{where}.{low}", a,
                                            f"{'<' if strict else '<='} {high} = {b}")
        return out

    def ordered(self, geometry: Geometry) -> bool:
        """Whether ``geometry``'s angles are in :attr:`order`."""
        return all(float(geometry[lo]) < float(geometry[hi]) if strict
                   else float(geometry[lo]) <= float(geometry[hi])
                   for lo, hi, strict in self.order)

    def terms(self, geometry: Geometry, centre: float) -> tuple[Term, ...]:
        """The basis terms on a joint whose centre of motion is ``centre`` (rad), absolute
        angles, in :attr:`magnitudes` order."""
        raise NotImplementedError(f"family {self.name} gives no terms")

    def nonnegative(self) -> np.ndarray:
        """Which magnitudes must be ≥ 0, shape (len(magnitudes),), bool."""
        return np.array([m != "torque_at_reference" for m in self.magnitudes])

    def clipped(self, x: Sequence[float] | np.ndarray) -> dict[str, float]:
        """Magnitudes ``x`` by name, those that must be ≥ 0 a solver left a rounding error below
        0 clipped to 0."""
        m = {k: float(v) for k, v in zip(self.magnitudes, x, strict=True)}
        for key in m:
            if key != "torque_at_reference":
                m[key] = max(m[key], 0.0)
        return m

    def spring(self, geometry: Geometry, centre: float, x: Sequence[float] | np.ndarray
               ) -> Spring:
        """The spring law of magnitudes ``x`` (SI, :attr:`magnitudes` order) on a joint whose
        centre of motion is ``centre``; magnitudes a solver left a rounding error below 0 are
        clipped to 0 (:meth:`clipped`)."""
        raise NotImplementedError(f"family {self.name} gives no law")

    def mirror(self, geometry: Geometry, x: Sequence[float] | np.ndarray
               ) -> tuple[dict[str, float | str], np.ndarray]:
        """The same physical spring on a joint that counts its angle the other way round
        (:mod:`hexaleg.robot.mirror`): the geometry and magnitudes whose law is
        ``τ'(q) = −τ(2c − q)`` for the law ``τ`` of ``(geometry, x)`` on a joint of centre c —
        the angles negated, above and below swapped (:attr:`swap`, :attr:`swap_magnitudes`), a
        linear spring's constant torque negated. Its energy is ``U'(q) = U(2c − q)``, so it is
        conservative too."""
        g = {k: v for k, v in geometry.items() if k in self.angles}
        m = dict(zip(self.magnitudes, (float(v) for v in x), strict=True))
        out: dict[str, float | str] = {self.swap[k]: -float(v) for k, v in g.items()}
        out.update(self.mirrored_labels(geometry))
        y = {self.swap_magnitudes.get(k, k): v for k, v in m.items()}
        if "torque_at_reference" in y:
            y["torque_at_reference"] = -y["torque_at_reference"]
        return out, np.array([y[k] for k in self.magnitudes])

    def mirrored_labels(self, geometry: Geometry) -> dict[str, float | str]:
        """The labels of the mirrored geometry (:meth:`mirror`)."""
        return {}

    def off(self, below: float, above: float, step: float) -> dict[str, float | str]:
        """The geometry whose stops never engage: each at ``above`` or ``below`` (rad from the
        centre, beyond every sample) on its side; a second stage ``step`` further."""
        geo: dict[str, float | str] = {}
        for a in self.angles:
            geo[a] = above if self.side(a, geo) == "above" else below
        return geo

    def wound(self, side: str, first: float, below: float, above: float, step: float
              ) -> dict[str, float | str] | None:
        """A family without preloaded stops: its first ``side`` stop at ``first`` (beyond the
        motion's far end: engaged throughout, a spring wound up), the others where they never
        engage (``below``, ``above``, a second stage ``step`` further); None for a family whose
        stops carry preloads (the search reaches those from :meth:`off`)."""
        return None

    def embed(self, inner: Family, geometry: Geometry, magnitudes: Mapping[str, float],
              off: tuple[float, float]) -> dict[str, float | str]:
        """The geometry of this family whose laws include ``inner``'s law of ``geometry`` and
        ``magnitudes`` (one of :attr:`contains`; ``off``: angles below and above every sample's).

        Raises:
            InvalidParameterError: this family does not contain ``inner``.
        """
        raise InvalidParameterError("embed", f"{inner.name} in {self.name}",
                                    f"a family {self.name} contains: "
                                    f"{', '.join(self.contains) or 'none'}")


__all__ = ["IDLE", "ZERO_MAGNITUDE", "Element", "Family", "Geometry"]
