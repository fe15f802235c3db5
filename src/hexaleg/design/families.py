"""Spring families as the design program sees them: a geometry, basis terms, magnitudes.

For :func:`hexaleg.design.optimal.optimal_springs` a family is split into its *geometry* —
angles the convex program holds fixed, relative to the centre of each joint's range of motion in
the gait (the convention of :mod:`hexaleg.design.evaluator`) — and its *magnitudes*, which are
decision variables because the spring torque is linear in them
(:mod:`hexaleg.robot.springs.terms`). This module says, per family, which geometry it has, which
terms a geometry gives on a joint, which magnitudes must be ≥ 0, how each physical spring element
deflects (for ``max_deflection``) and which spring law a solution is.

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

A linear spring's reference angle changes nothing (τ₀ − k (q − q_r) spans the same torques for
every q_r), so its optimum over the magnitudes is already the global one.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from hexaleg.checks import one_of
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.robot.springs import (
    SIDES,
    DeadZoneSpring,
    LinearSpring,
    OneSidedSpring,
    PreloadedSpring,
    Spring,
    StiffeningSpring,
    Term,
)

FAMILIES: tuple[str, ...] = ("linear", "dead_zone", "preloaded", "one_sided", "stiffening")
"""Spring families :func:`hexaleg.design.optimal.optimal_springs` designs."""

Geometry = Mapping[str, float | str]
"""A family's geometry: angle name → rad from the joint's centre of motion (and ``side``)."""


@dataclass(frozen=True)
class Element:
    """One physical spring of a law, for ``max_deflection``: the indices of its stiffness term
    and of its preload term (or None) in the family's magnitudes, and whether it is the linear
    spring (deflection |q − q_equilibrium| on both sides) or one engaging past a contact angle."""

    stiffness: int
    preload: int | None = None
    linear: bool = False


@dataclass(frozen=True)
class Family:
    """A spring family for the design program (module docstring).

    Attributes:
        name: One of :data:`FAMILIES`.
        angles: Names of the geometry's angles (rad, from each joint's centre of motion).
        magnitudes: Names of the magnitudes, in term order.
        elements: The physical springs (:class:`Element`), for ``max_deflection``.
        order: ``(low, high, strict)``: angle ``low`` ≤ (``strict``: <) angle ``high``.
        preloaded_stops: Every stop carries a free preload ≥ 0 with its stiffness: then the
            design's value is non-increasing in each angle between two samples' angles
            (:mod:`hexaleg.design.search`), so a stop's best place is just before a sample.
    """

    name: str
    angles: tuple[str, ...]
    magnitudes: tuple[str, ...]
    elements: tuple[Element, ...]
    order: tuple[tuple[str, str, bool], ...] = ()
    preloaded_stops: bool = False

    def side(self, angle: str, geometry: Geometry) -> str:
        """``"above"`` when the terms at ``angle`` act on angles above it, else ``"below"``."""
        if angle == "contact":
            return str(geometry["side"])
        return "above" if angle in ("theta_plus", "above_1", "above_2") else "below"

    def check(self, geometry: Geometry, where: str) -> dict[str, float | str]:
        """``geometry`` checked: exactly this family's angles (and ``side`` for one_sided), finite,
        in order.

        Raises:
            UnknownNameError: a parameter the family does not have (lists the ones it has).
            InvalidParameterError: a missing or non-finite angle, angles out of order, a bad side.
        """
        allowed = (*self.angles, "side") if self.name == "one_sided" else self.angles
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
        if self.name == "one_sided":
            side = geometry.get("side", "above")
            if side not in SIDES:
                raise UnknownNameError(f"{where}.side", side, SIDES)
            out["side"] = side
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
        g = {k: v for k, v in geometry.items() if k != "side"}
        a = {k: centre + float(v) for k, v in g.items()}
        if self.name == "linear":
            return (Term("linear", centre, "k"), Term("constant", centre, "torque_at_reference"))
        if self.name == "dead_zone":
            return (Term("above", a["theta_plus"], "k_plus"),
                    Term("below", a["theta_minus"], "k_minus"))
        if self.name == "preloaded":
            return (Term("above", a["theta_plus"], "k_plus"),
                    Term("below", a["theta_minus"], "k_minus"),
                    Term("step_above", a["theta_plus"], "preload_plus"),
                    Term("step_below", a["theta_minus"], "preload_minus"))
        if self.name == "one_sided":
            side = str(geometry["side"])
            return (Term(side, a["contact"], "k"), Term(f"step_{side}", a["contact"], "preload"))
        return (Term("above", a["above_1"], "k_above_1"), Term("above", a["above_2"], "k_above_2"),
                Term("below", a["below_1"], "k_below_1"), Term("below", a["below_2"], "k_below_2"))

    def nonnegative(self) -> np.ndarray:
        """Which magnitudes must be ≥ 0, shape (len(magnitudes),), bool."""
        return np.array([m != "torque_at_reference" for m in self.magnitudes])

    def spring(self, geometry: Geometry, centre: float, x: Sequence[float] | np.ndarray
               ) -> Spring:
        """The spring law of magnitudes ``x`` (SI, :attr:`magnitudes` order) on a joint whose
        centre of motion is ``centre``; magnitudes a solver left a rounding error below 0 are
        clipped to 0."""
        m = dict(zip(self.magnitudes, x, strict=True))
        for key in m:
            if key != "torque_at_reference":
                m[key] = max(float(m[key]), 0.0)
        g = {k: v for k, v in geometry.items() if k != "side"}
        a = {k: centre + float(v) for k, v in g.items()}
        if self.name == "linear":
            return LinearSpring(m["k"], centre, float(m["torque_at_reference"]))
        if self.name == "dead_zone":
            return DeadZoneSpring(stiffness=m["k_plus"], stiffness_minus=m["k_minus"],
                                  theta_minus=float(g["theta_minus"]),
                                  theta_plus=float(g["theta_plus"]), neutral=centre)
        if self.name == "preloaded":
            return PreloadedSpring(stiffness=m["k_plus"], preload=m["preload_plus"],
                                   theta_minus=float(g["theta_minus"]),
                                   theta_plus=float(g["theta_plus"]),
                                   stiffness_minus=m["k_minus"], preload_minus=m["preload_minus"],
                                   neutral=centre)
        if self.name == "one_sided":
            return OneSidedSpring(m["k"], a["contact"], str(geometry["side"]), m["preload"])
        return StiffeningSpring(
            above=((a["above_1"], m["k_above_1"]), (a["above_2"], m["k_above_2"])),
            below=((a["below_1"], m["k_below_1"]), (a["below_2"], m["k_below_2"])))


    def mirror(self, geometry: Geometry, x: Sequence[float] | np.ndarray
               ) -> tuple[dict[str, float | str], np.ndarray]:
        """The same physical spring on a joint that counts its angle the other way round
        (:mod:`hexaleg.robot.mirror`): the geometry and magnitudes whose law is
        ``τ'(q) = −τ(2c − q)`` for the law ``τ`` of ``(geometry, x)`` on a joint of centre c —
        the angles negated, above and below swapped (with their magnitudes), a linear spring's
        constant torque negated. Its energy is ``U'(q) = U(2c − q)``, so it is conservative too.
        """
        g = {k: v for k, v in geometry.items() if k != "side"}
        m = dict(zip(self.magnitudes, (float(v) for v in x), strict=True))
        swap = {"theta_minus": "theta_plus", "theta_plus": "theta_minus",
                "above_1": "below_1", "above_2": "below_2", "below_1": "above_1",
                "below_2": "above_2", "contact": "contact"}
        out: dict[str, float | str] = {swap[k]: -float(v) for k, v in g.items()}
        if self.name == "one_sided":
            out["side"] = "below" if geometry["side"] == "above" else "above"
        names = {"k_plus": "k_minus", "k_minus": "k_plus", "preload_plus": "preload_minus",
                 "preload_minus": "preload_plus", "k_above_1": "k_below_1",
                 "k_above_2": "k_below_2", "k_below_1": "k_above_1", "k_below_2": "k_above_2"}
        y = {names.get(k, k): v for k, v in m.items()}
        if "torque_at_reference" in y:
            y["torque_at_reference"] = -y["torque_at_reference"]
        return out, np.array([y[k] for k in self.magnitudes])


_FAMILIES = {
    "linear": Family("linear", (), ("k", "torque_at_reference"), (Element(0, 1, linear=True),)),
    "dead_zone": Family("dead_zone", ("theta_minus", "theta_plus"), ("k_plus", "k_minus"),
                        (Element(0), Element(1)), order=(("theta_minus", "theta_plus", True),)),
    "preloaded": Family("preloaded", ("theta_minus", "theta_plus"),
                        ("k_plus", "k_minus", "preload_plus", "preload_minus"),
                        (Element(0, 2), Element(1, 3)),
                        order=(("theta_minus", "theta_plus", False),), preloaded_stops=True),
    "one_sided": Family("one_sided", ("contact",), ("k", "preload"), (Element(0, 1),),
                        preloaded_stops=True),
    "stiffening": Family("stiffening", ("above_1", "above_2", "below_1", "below_2"),
                         ("k_above_1", "k_above_2", "k_below_1", "k_below_2"),
                         (Element(0), Element(1), Element(2), Element(3)),
                         order=(("above_1", "above_2", True), ("below_2", "below_1", True))),
}

CONTAINS: dict[str, tuple[str, ...]] = {"preloaded": ("one_sided", "dead_zone", "linear"),
                                        "dead_zone": ("linear",), "stiffening": ("dead_zone",)}
"""Family → the families it contains (their every law is one of its laws, :func:`embed`; a
linear law is a dead zone :data:`LINEAR_GAP` wide)."""
LINEAR_REACH = 2 * np.pi
"""rad from the centre of motion beyond which a linear spring's equilibrium (a constant torque
where k → 0) is not taken for a dead zone's: its stops would sit turns away (the design's
deflection bound keeps a linear spring's equilibrium within π of the motion)."""
STAGE_OFF = 0.1
"""rad beyond the first stage (and every sample) where an unused second stage is put."""
LINEAR_GAP = 1e-9
"""rad: the width of the dead zone that stands for a linear spring (a dead zone needs
θ⁻ < θ⁺); the laws differ by k·LINEAR_GAP N·m inside it."""


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
    ``magnitudes`` (rad from the centre of motion).

    ``off``: (an angle below, an angle above) every sample's, rad from the centre: a stop there
    never engages. One_sided and dead_zone are preloaded with a side off or no preload; a linear
    law τ₀ − k (q − c) is preloaded with both stops at θ = τ₀ / k (k > 0; k = 0, a constant
    torque: both stops beyond the motion on the side whose preload gives it), and a dead zone
    :data:`LINEAR_GAP` wide at θ (no stop engaged when θ is beyond :data:`LINEAR_REACH`);
    dead_zone is stiffening with its second stages off.

    Raises:
        InvalidParameterError: ``outer`` does not contain ``inner`` (:data:`CONTAINS`).
    """
    below, above = off
    if outer == "preloaded" and inner == "one_sided":
        c = float(geometry["contact"])
        return ({"theta_minus": min(below, c), "theta_plus": c} if geometry["side"] == "above"
                else {"theta_minus": c, "theta_plus": max(above, c)})
    if outer == "preloaded" and inner == "dead_zone":
        return {"theta_minus": float(geometry["theta_minus"]),
                "theta_plus": float(geometry["theta_plus"])}
    if outer == "preloaded" and inner == "linear":
        k, torque = float(magnitudes["k"]), float(magnitudes["torque_at_reference"])
        # k = 0: a constant torque, a preload with both stops beyond the motion on one side
        theta = torque / k if k > 0 else above if torque > 0 else below
        return {"theta_minus": theta, "theta_plus": theta}
    if outer == "dead_zone" and inner == "linear":
        k, torque = float(magnitudes["k"]), float(magnitudes["torque_at_reference"])
        theta = torque / k if k > 0 else np.inf
        if abs(theta) > LINEAR_REACH:  # a (nearly) constant torque is no dead-zone law
            return {"theta_minus": below, "theta_plus": above}
        return {"theta_minus": theta - LINEAR_GAP / 2, "theta_plus": theta + LINEAR_GAP / 2}
    if outer == "stiffening" and inner == "dead_zone":
        plus, minus = float(geometry["theta_plus"]), float(geometry["theta_minus"])
        return {"above_1": plus, "above_2": max(above, plus) + STAGE_OFF,
                "below_1": minus, "below_2": min(below, minus) - STAGE_OFF}
    pairs = ", ".join(f"{i} in {o}" for o, ins in CONTAINS.items() for i in ins)
    raise InvalidParameterError("embed", f"{inner} in {outer}", f"one of {pairs}")


def family(name: str) -> Family:
    """The family called ``name``.

    Raises:
        UnknownNameError: not one of :data:`FAMILIES` (lists them).
    """
    return _FAMILIES[one_of("spring family", name, FAMILIES)]
