"""The base of the spring families built from basis terms (:mod:`hexaleg.robot.springs.terms`).

A family subclasses :class:`TermSpring` and says which terms it is made of and with which
magnitudes; the torque, the stored energy and the torque basis the design layer's program uses
all follow from those, so every family is conservative by construction (φ = −dψ/dq term by term,
tested for each family).
"""

from __future__ import annotations

from abc import ABC, abstractmethod

import numpy as np
from numpy.typing import ArrayLike

from hexaleg.checks import finite_array, real
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.springs.terms import Term, basis, potentials


def magnitude(name: str, value: object) -> float:
    """A stiffness (N·m/rad) or preload (N·m): a finite number ≥ 0.

    Raises:
        InvalidParameterError: otherwise, naming ``name``.
    """
    return real(name, value, low=0.0, allowed="a finite number >= 0")


class TermSpring(ABC):
    """A conservative spring law ``τ(q) = Σ_b x_b φ_b(q)``, ``U(q) = Σ_b x_b ψ_b(q)``.

    Subclasses are frozen dataclasses that implement :meth:`terms` (the geometry) and
    :meth:`magnitudes` (x, in the order of the terms).
    """

    @abstractmethod
    def terms(self) -> tuple[Term, ...]:
        """The basis terms, absolute joint angles (the spring's geometry)."""

    @abstractmethod
    def magnitudes(self) -> np.ndarray:
        """The magnitude of each term, shape (len(terms),), SI (N·m/rad or N·m)."""

    def elastic_torque(self, q: ArrayLike) -> np.ndarray:
        """Torque the spring applies to the joint, N·m, shape of ``q``; exactly −dU/dq."""
        return basis(self.terms(), q) @ self.magnitudes()

    def torque(self, q: ArrayLike, v: ArrayLike | None = None) -> np.ndarray:
        """Torque on the joint, N·m, shape of ``q`` (these families have no damping; ``v`` is
        checked for shape only)."""
        if v is not None:
            qa, va = finite_array("q", q), finite_array("v", v)
            if va.shape != qa.shape:
                raise InvalidParameterError("v.shape", va.shape, f"the shape of q, {qa.shape}")
        return self.elastic_torque(q)

    def energy(self, q: ArrayLike) -> np.ndarray:
        """Stored potential energy U(q), J, shape of ``q`` (zero at the angles where every term's
        potential is zero)."""
        return potentials(self.terms(), q) @ self.magnitudes()
