"""The base of the spring families built from basis terms (:mod:`hexaleg.robot.springs.terms`).

A family subclasses :class:`TermSpring` and says which terms it is made of and with which
magnitudes; the torque, the stored energy and the torque basis the design layer's program uses
all follow from those, so every family is conservative by construction (φ = −dψ/dq term by term,
tested for each family).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import cast

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


class ContactAngles:
    """θ⁻ and θ⁺ of a spring with a dead zone, given as the symmetric ``theta_k`` (±θ_k) or as
    ``theta_minus`` / ``theta_plus``, rad relative to its neutral. Mixed into the dataclasses that
    have those three fields."""

    theta_k: float | None
    theta_minus: float | None
    theta_plus: float | None

    def check_contact_angles(self, strict: bool) -> None:
        """Both angles given (directly or through theta_k) and θ⁻ < θ⁺ (``strict``) or ≤.

        Raises:
            InvalidParameterError: naming the missing or out-of-order angle.
        """
        for name in ("theta_minus", "theta_plus"):
            if getattr(self, name) is None and self.theta_k is None:
                raise InvalidParameterError(name, None, "a number, or give theta_k")
        if self.th_minus > self.th_plus or (strict and self.th_minus == self.th_plus):
            raise InvalidParameterError("theta_minus", self.th_minus,
                                        f"{'<' if strict else '<='} theta_plus = {self.th_plus!r}")

    @property
    def th_minus(self) -> float:
        """θ⁻, rad, relative to neutral."""
        return self.theta_minus if self.theta_minus is not None else -cast(float, self.theta_k)

    @property
    def th_plus(self) -> float:
        """θ⁺, rad, relative to neutral."""
        return self.theta_plus if self.theta_plus is not None else cast(float, self.theta_k)
