"""Basis torques of spring laws: every family is a sum of magnitudes times these terms.

For a fixed spring *geometry* (contact angles, reference angle, stage breakpoints) a spring's
torque on its joint is linear in the spring's *magnitudes* (stiffnesses, preloads, a constant
torque)::

    τ_s(q) = Σ_b x_b φ_b(q),        U(q) = Σ_b x_b ψ_b(q),        φ_b = −dψ_b/dq exactly

which is what lets the design layer treat the magnitudes as decision variables of one convex
program (:mod:`hexaleg.design.search.optimal`). Each :class:`Term` is one φ_b with its potential
ψ_b; angles are absolute joint angles, rad. The kinds (a = the term's angle):

=============  ==========================  ==========================  ======================
kind           φ(q), N·m per unit x         ψ(q), J per unit x          x is
=============  ==========================  ==========================  ======================
``above``      −max(q − a, 0)               ½ max(q − a, 0)²            a stiffness ≥ 0, N·m/rad
``below``      +max(a − q, 0)               ½ max(a − q, 0)²            a stiffness ≥ 0, N·m/rad
``step_above`` −1 for q > a, else 0         max(q − a, 0)               a preload ≥ 0, N·m
``step_below`` +1 for q < a, else 0         max(a − q, 0)               a preload ≥ 0, N·m
``linear``     −(q − a)                     ½ (q − a)²                  a stiffness ≥ 0, N·m/rad
``constant``   +1                           −(q − a)                    a torque (any sign), N·m
=============  ==========================  ==========================  ======================

The ramps are the stiffness of a spring that engages at a contact angle (the paper's eq. 8 dead
zone, Hooke's law past contact); the steps are the preload of a spring held by a stop, which
meets the lever already wound up (its torque jumps to the preload at contact, as a pre-tensioned
torsion spring does; Shigley's Mechanical Engineering Design, 10th ed., §10-12); ``linear`` and
``constant`` together are a linear spring with a free equilibrium angle. The potentials are
continuous everywhere, so every law built from them is conservative: the work it does over a
closed path is zero.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from hexaleg.checks import finite_array, real
from hexaleg.errors import InvalidParameterError

KINDS: tuple[str, ...] = ("above", "below", "step_above", "step_below", "linear", "constant")
"""The kinds of :class:`Term` (see the module docstring)."""
SIGNED_KINDS: tuple[str, ...] = ("constant",)
"""Kinds whose magnitude may take either sign; all others are ≥ 0 (a spring stiffness or a
preload)."""


@dataclass(frozen=True)
class Term:
    """One basis torque φ(q) of a spring law and its potential ψ(q) (module docstring).

    Attributes:
        kind: One of :data:`KINDS`.
        angle: Its angle a, rad (contact angle, breakpoint or reference), absolute joint angle.
        name: The magnitude's name in its family (``"k_plus"``, ``"preload_minus"``, …).

    Raises:
        InvalidParameterError: unknown kind or a non-finite angle.
    """

    kind: str
    angle: float
    name: str = ""

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise InvalidParameterError("Term.kind", self.kind, "one of " + ", ".join(KINDS))
        object.__setattr__(self, "angle", real("Term.angle", self.angle,
                                               allowed="a finite angle (rad)"))

    @property
    def nonnegative(self) -> bool:
        """Whether the magnitude must be ≥ 0 (every kind but ``constant``)."""
        return self.kind not in SIGNED_KINDS

    def torque(self, q: np.ndarray) -> np.ndarray:
        """φ(q) per unit magnitude, shape of ``q`` (:func:`basis_torque` at ``q − a``)."""
        return basis_torque(self.kind, q - self.angle)

    def potential(self, q: np.ndarray) -> np.ndarray:
        """ψ(q) per unit magnitude, shape of ``q``; φ = −dψ/dq."""
        d = q - self.angle
        if self.kind == "above":
            return 0.5 * np.maximum(d, 0.0) ** 2
        if self.kind == "below":
            return 0.5 * np.maximum(-d, 0.0) ** 2
        if self.kind == "step_above":
            return np.maximum(d, 0.0)
        if self.kind == "step_below":
            return np.maximum(-d, 0.0)
        if self.kind == "linear":
            return 0.5 * d**2
        return -d


def basis_torque(kind: str, d: np.ndarray) -> np.ndarray:
    """φ per unit magnitude of a term of ``kind`` (one of :data:`KINDS`) at ``d = q − a``, rad
    (the module docstring's table), the shape of ``d``: one term's angles, or the terms of
    ``kind`` of many joints at once (each its own ``a``), the same arithmetic either way."""
    if kind == "above":
        return -np.maximum(d, 0.0)
    if kind == "below":
        return np.maximum(-d, 0.0)
    if kind == "step_above":
        return -(d > 0).astype(float)
    if kind == "step_below":
        return (d < 0).astype(float)
    if kind == "linear":
        return -d
    return np.ones_like(d)


def basis(terms: Sequence[Term], q: ArrayLike) -> np.ndarray:
    """Basis torques of ``terms`` at joint angles ``q``: shape ``q.shape + (len(terms),)``."""
    qa = finite_array("q", q)
    return np.stack([t.torque(qa) for t in terms], axis=-1) if terms else np.zeros(
        (*qa.shape, 0))


def potentials(terms: Sequence[Term], q: ArrayLike) -> np.ndarray:
    """Basis potentials of ``terms`` at ``q``: shape ``q.shape + (len(terms),)``."""
    qa = finite_array("q", q)
    return np.stack([t.potential(qa) for t in terms], axis=-1) if terms else np.zeros(
        (*qa.shape, 0))
