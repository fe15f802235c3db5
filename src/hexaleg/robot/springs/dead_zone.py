"""Dead-zone torsion springs at the joints: the paper's nonlinear elastic joint, generalised.

The paper (eq. 8) puts a main torsion spring at the femur joint that only engages once the joint
has turned past a contact angle ±θ_k; inside the dead zone only a very soft secondary spring k₂
acts. :class:`DeadZoneSpring` generalises that law per joint, and :class:`SpringSet` assigns
springs to any of a robot's actuated joints (:mod:`hexaleg.robot.springs.spring_set`).

The α convention
----------------
The paper's eq. 7 stores ``P₂ = ½ k (α Δθ)²`` in the main spring (α converts the joint rotation
into the spring's rotation when the spring is off the joint axis), but eq. 14 applies the torque
``k α (θ − θ_k)`` — eq. 7 differentiated gives ``k α² (θ − θ_k)``, so the two differ by a factor α.
hexaleg offers both, each exactly conservative (torque = −dU/dq):

* ``convention="eq7"`` (default, the consistent model): α is a transmission ratio between the joint
  and the spring; the spring stores ``U = ½ k (α Δ)²`` and, by virtual work, applies
  ``τ = −k α² Δ`` to the joint (Δ = compression past the contact angle).
* ``convention="eq14"`` (the paper's torque): ``τ = −k α Δ`` and ``U = ½ k α Δ²``; a spring of
  stiffness k in this convention is the eq7 spring of stiffness k/α.

In both, Δθ of eq. 7 is read as the compression past the contact angle (Δ = q − q₀ − θ⁺ beyond
θ⁺), not the whole joint angle: eq. 14 says so, and the whole-angle reading would make the
potential jump at contact. The secondary spring k₂ acts directly on the joint (no α), linearly
about the neutral angle everywhere; viscous damping belongs to the main spring (it acts only while
the main spring is engaged) and goes through the same transmission factor as its stiffness.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from hexaleg.checks import finite_array, named_arguments, real
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.springs.law import ContactAngles
from hexaleg.robot.springs.terms import Term
from hexaleg.units import deg_to_rad, nmm_per_deg_to_nm_per_rad, nmms_per_deg_to_nms_per_rad

CONVENTIONS: tuple[str, ...] = ("eq7", "eq14")
"""α conventions of :class:`DeadZoneSpring` (see the module docstring)."""


class TorqueBasis(NamedTuple):
    """Per-unit-coefficient torque shapes of a spring; each array has the shape of q, N·m per unit.

    The spring torque is linear in its four coefficients for fixed contact angles::

        torque = k⁺·plus + k⁻·minus + k₂·k2 + c·damping

    Attributes:
        plus: Torque of the main spring beyond θ⁺ per unit k⁺ (N·m per N·m/rad).
        minus: Torque of the main spring below θ⁻ per unit k⁻ (N·m per N·m/rad).
        k2: Torque of the secondary spring per unit k₂ (N·m per N·m/rad).
        damping: Damping torque per unit damping coefficient (N·m per N·m·s/rad); zero when v
            is None.
    """

    plus: np.ndarray
    minus: np.ndarray
    k2: np.ndarray
    damping: np.ndarray


Parameter = float | np.ndarray
"""A law's parameter: one law's number, or many joints' laws' at once (an array that broadcasts
with the angles)."""


def zone_basis(d: np.ndarray, v: np.ndarray | None, th_minus: Parameter, th_plus: Parameter,
               a: Parameter) -> TorqueBasis:
    """:meth:`DeadZoneSpring.torque_basis` at ``d = q − neutral`` and speed ``v`` (rad and
    rad/s, one shape; ``v`` None: no damping), for contact angles θ⁻ ``th_minus`` and θ⁺
    ``th_plus`` (rad, relative to the neutral) and transmission ``a``
    (:attr:`DeadZoneSpring.transmission`): one law's numbers, or many joints' laws at once
    (:data:`Parameter`), the same arithmetic either way: the paper's eq. 8 and 14 per unit
    coefficient, in the α convention of the module docstring (``a`` = α² or α). Unchecked: the
    law checks its input."""
    plus = -a * np.maximum(d - th_plus, 0.0)
    minus = -a * np.minimum(d - th_minus, 0.0)
    if v is None:
        damp = np.zeros_like(d)
    else:
        engaged = (d > th_plus) | (d < th_minus)
        damp = np.where(engaged, -a * v, 0.0)
    return TorqueBasis(plus, minus, -d, damp)


def zone_torque(basis: TorqueBasis, k_plus: Parameter, k_minus: Parameter, k2: Parameter,
                damping: Parameter) -> np.ndarray:
    """:meth:`DeadZoneSpring.torque` from its :func:`zone_basis` and coefficients k⁺, k⁻
    (N·m/rad, the spring's), k₂ (N·m/rad) and damping (N·m·s/rad): one law's numbers, or many
    joints' laws at once (:data:`Parameter`), N·m, the shape of the basis."""
    return (k_plus * basis.plus + k_minus * basis.minus + k2 * basis.k2
            + damping * basis.damping)


@named_arguments
@dataclass(frozen=True)
class DeadZoneSpring(ContactAngles):
    """A dead-zone torsion spring on one joint (paper eq. 7–8, generalised).

    With Δ = q − neutral, the main spring is engaged for Δ > θ⁺ (stiffness k⁺) and Δ < θ⁻
    (stiffness k⁻) and free in the dead zone θ⁻ ≤ Δ ≤ θ⁺; the secondary spring k₂ acts everywhere.
    Potential (convention eq7, paper eq. 7 with Δθ = compression; ``a = α²``, eq14: ``a = α``)::

        U = ½ a k⁺ (Δ − θ⁺)²   for Δ > θ⁺
            ½ a k⁻ (Δ − θ⁻)²   for Δ < θ⁻      (+ ½ k₂ Δ² everywhere)
            0                   otherwise

    and the torque applied to the joint is ``−dU/dq − a c v`` (damping only while engaged).
    The paper's symmetric spring is ``theta_k = θ_k`` with k⁺ = k⁻ = k₁.

    Attributes:
        stiffness: k⁺, N·m/rad, main spring beyond θ⁺ (and k⁻ when stiffness_minus is None).
        theta_k: Symmetric contact angle, rad, > 0 (the paper's ±θ_k); gives θ⁻/θ⁺ defaults.
        theta_minus: θ⁻, rad, relative to neutral (default −theta_k).
        theta_plus: θ⁺, rad, relative to neutral (default +theta_k).
        stiffness_minus: k⁻, N·m/rad (default = stiffness).
        k2: Secondary spring, N·m/rad, linear about neutral everywhere.
        alpha: Angle conversion factor α (eq. 7), > 0.
        damping: Viscous damping of the main spring, N·m·s/rad, acting while it is engaged.
        neutral: Joint angle, rad, at the dead-zone centre (Δ = 0).
        convention: ``"eq7"`` (torque k α² Δ, consistent with eq. 7) or ``"eq14"`` (torque k α Δ,
            the paper's eq. 14).

    Raises:
        InvalidParameterError: a stiffness or damping is negative, α ≤ 0, θ_k ≤ 0, θ⁻ ≥ θ⁺, a
            contact angle is missing, a value is NaN/inf, or the convention is unknown.
    """

    stiffness: float
    theta_k: float | None = None
    theta_minus: float | None = None
    theta_plus: float | None = None
    stiffness_minus: float | None = None
    k2: float = 0.0
    alpha: float = 1.0
    damping: float = 0.0
    neutral: float = 0.0
    convention: str = "eq7"

    def __post_init__(self) -> None:
        for name in ("stiffness", "theta_k", "theta_minus", "theta_plus", "stiffness_minus",
                     "k2", "alpha", "damping", "neutral"):
            value = getattr(self, name)
            if value is not None or name in ("stiffness", "k2", "alpha", "damping", "neutral"):
                object.__setattr__(self, name, real(name, value,
                                                    allowed="a finite real number (no NaN or inf)"))
        for name in ("stiffness", "stiffness_minus", "k2", "damping"):
            value = getattr(self, name)
            if value is not None and value < 0:
                raise InvalidParameterError(name, value, ">= 0")
        if self.alpha <= 0:
            raise InvalidParameterError("alpha", self.alpha, "> 0")
        if self.theta_k is not None and (self.theta_k < 0 or (
                self.theta_k == 0 and (self.theta_minus is None or self.theta_plus is None))):
            raise InvalidParameterError(
                "theta_k", self.theta_k, "> 0 rad: the dead zone is ±theta_k about the neutral, "
                "so 0 leaves no dead zone at all; for a spring engaged everywhere use "
                "LinearSpring(stiffness, reference=neutral)")
        self.check_contact_angles(strict=True)
        if self.convention not in CONVENTIONS:
            raise InvalidParameterError("convention", self.convention,
                                        f"one of {', '.join(CONVENTIONS)}")

    @property
    def k_minus(self) -> float:
        """k⁻, N·m/rad."""
        return self.stiffness if self.stiffness_minus is None else self.stiffness_minus

    @property
    def transmission(self) -> float:
        """Factor from spring stiffness to joint stiffness: α² (eq7) or α (eq14)."""
        return self.alpha**2 if self.convention == "eq7" else self.alpha

    def _delta(self, q: ArrayLike) -> np.ndarray:
        return finite_array("q", q) - self.neutral

    def compression(self, q: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """Compressions past the contact angles.

        Args:
            q: Joint angles, rad, any shape.

        Returns:
            (beyond θ⁺ ≥ 0, below θ⁻ ≤ 0), rad, each the shape of q; zero in the dead zone.
        """
        d = self._delta(q)
        return np.maximum(d - self.th_plus, 0.0), np.minimum(d - self.th_minus, 0.0)

    def engaged(self, q: ArrayLike) -> np.ndarray:
        """Whether the main spring is in contact (Δ outside [θ⁻, θ⁺]), bool, shape of q."""
        d = self._delta(q)
        return (d > self.th_plus) | (d < self.th_minus)

    def torque_basis(self, q: ArrayLike, v: ArrayLike | None = None) -> TorqueBasis:
        """Torque shapes per unit k⁺, k⁻, k₂ and damping, for stiffness sweeps.

        For fixed contact angles, α and convention the torque is linear in the coefficients:
        ``torque(q, v) == k⁺·b.plus + k⁻·b.minus + k₂·b.k2 + c·b.damping``.

        Args:
            q: Joint angles, rad, any shape.
            v: Joint velocities, rad/s, same shape as q, or None (no damping).

        Returns:
            The four shapes, each the shape of q.
        """
        d = self._delta(q)
        va = None
        if v is not None:
            va = finite_array("v", v)
            if va.shape != d.shape:
                raise InvalidParameterError("v.shape", va.shape, f"the shape of q, {d.shape}")
        return zone_basis(d, va, self.th_minus, self.th_plus, self.transmission)

    def terms(self) -> tuple[Term, ...]:
        """The elastic law as basis terms (:mod:`hexaleg.robot.springs.terms`): ramps at the two
        contact angles and the secondary spring, absolute joint angles."""
        return (Term("above", self.neutral + self.th_plus, "k_plus"),
                Term("below", self.neutral + self.th_minus, "k_minus"),
                Term("linear", self.neutral, "k2"))

    def magnitudes(self) -> np.ndarray:
        """Joint-side magnitudes of :meth:`terms`: a k⁺, a k⁻ (a the transmission), k₂."""
        a = self.transmission
        return np.array([a * self.stiffness, a * self.k_minus, self.k2])

    def elastic_torque(self, q: ArrayLike) -> np.ndarray:
        """Conservative torque on the joint, N·m, shape of q; exactly −dU/dq."""
        b = self.torque_basis(q)
        return self.stiffness * b.plus + self.k_minus * b.minus + self.k2 * b.k2

    def torque(self, q: ArrayLike, v: ArrayLike | None = None) -> np.ndarray:
        """Torque the spring applies to the joint, N·m, shape of q (elastic + damping).

        Args:
            q: Joint angles, rad, any shape.
            v: Joint velocities, rad/s, same shape, or None to omit damping.
        """
        return zone_torque(self.torque_basis(q, v), self.stiffness, self.k_minus, self.k2,
                           self.damping)

    def energy(self, q: ArrayLike) -> np.ndarray:
        """Stored potential energy U(q), J, shape of q (eq. 7 with Δθ = compression)."""
        d = self._delta(q)
        up, um = np.maximum(d - self.th_plus, 0.0), np.minimum(d - self.th_minus, 0.0)
        a = self.transmission
        return 0.5 * a * (self.stiffness * up**2 + self.k_minus * um**2) + 0.5 * self.k2 * d**2

    def with_stiffness(self, stiffness: float) -> DeadZoneSpring:
        """A copy with k⁺ (and k⁻ if it followed k⁺) replaced, N·m/rad."""
        return DeadZoneSpring(stiffness, self.theta_k, self.theta_minus, self.theta_plus,
                              self.stiffness_minus, self.k2, self.alpha, self.damping,
                              self.neutral, self.convention)

    @classmethod
    def from_paper(cls, k_nmm_per_deg: float, theta_k_deg: float, alpha: float = 1.0, *,
                   k2_nmm_per_deg: float = 0.0, damping_nmms_per_deg: float = 0.0,
                   neutral_deg: float = 0.0, convention: str = "eq7") -> DeadZoneSpring:
        """A symmetric spring from the paper's units (Tables 4–5, Section 4.2).

        Args:
            k_nmm_per_deg: Main spring stiffness k₁, N·mm/deg (Table 4: 400).
            theta_k_deg: Contact angle θ_k, deg (Section 4.2: 7.32).
            alpha: Angle conversion factor α (Section 4.2: 1.05).
            k2_nmm_per_deg: Secondary spring, N·mm/deg (Table 5: 0.01).
            damping_nmms_per_deg: Main spring damping, N·mm·s/deg (Table 4: 1).
            neutral_deg: Joint angle at the dead-zone centre, deg.
            convention: ``"eq7"`` or ``"eq14"``.

        Returns:
            The spring in SI.
        """
        for name, value in (("k_nmm_per_deg", k_nmm_per_deg), ("theta_k_deg", theta_k_deg),
                            ("k2_nmm_per_deg", k2_nmm_per_deg),
                            ("damping_nmms_per_deg", damping_nmms_per_deg),
                            ("neutral_deg", neutral_deg)):
            finite_array(name, value)
        return cls(stiffness=float(nmm_per_deg_to_nm_per_rad(k_nmm_per_deg)),
                   theta_k=float(deg_to_rad(theta_k_deg)), alpha=alpha,
                   k2=float(nmm_per_deg_to_nm_per_rad(k2_nmm_per_deg)),
                   damping=float(nmms_per_deg_to_nms_per_rad(damping_nmms_per_deg)),
                   neutral=float(deg_to_rad(neutral_deg)), convention=convention)
