"""The paper's single-joint nonlinear elastic joint, reproduced in consistent units.

One lever (the femur, Table 6) driven by ``θ(t) = A sin(ωt + φ) + B`` (eq. 16, eq. 25: A = 0.3
rad, ω = 2 rad/s), a dead-zone torsion spring at the joint (eq. 8, contact angle θ_k = 7.32°,
α = 1.05) and the motor torque that tracks the trajectory exactly (eq. 13/14/17)::

    M(t) = J θ̈ + s m g l sin θ − τ_s(θ, k),      J = m l² + I   (eq. 5, 13)

with ``s = +1`` for the hanging lever of eq. 6 (potential −m g l cos θ) and ``s = −1`` upright.
The paper's constants (θ_k, A, ω, α) come from :mod:`hexaleg.design.rules`, the trajectory from
:class:`hexaleg.motion.profiles.Sinusoid`.

Signs and conventions (see docs/paper.md):

* The spring torque on the joint τ_s is restoring, ``τ_s = −κ (θ − θ_k sgn θ)`` when engaged, as
  the Lagrangian of eq. 10 gives. Eq. 14 prints ``− k α (f − θ_k)`` in M, i.e. ``τ_s`` with the
  opposite sign; with that sign eq. 18 has no positive root, and eq. 19 (k_M > 0) follows only
  with the restoring sign used here.
* κ is the joint stiffness: ``κ = k α`` in the paper's eq. 14 convention (the default here,
  ``convention="eq14"``) and ``κ = k α²`` in the energy-consistent eq. 7 convention (``"eq7"``);
  both come from :class:`hexaleg.robot.springs.DeadZoneSpring`.
* Eq. 19 ``k_M = ω² (m l² + I) / α`` with Table 6 gives 713.547 only with m in kg, l in mm and
  I in kg·mm²: the number is in kg·mm²·s⁻²/rad = 1e-6 N·m/rad, not N·mm/deg.
  :func:`hexaleg.paper.readings.k_M_paper_number` reproduces that arithmetic;
  :meth:`PaperJoint.k_M` is SI.

Closed forms (no gravity, B = 0; derived in docs/paper.md), in joint stiffness κ, with
``φ_k = arcsin(θ_k/A)``, ``c = J ω²``:

* peak |M| is flat and equal to ``c θ_k`` for ``c ≤ κ ≤ c (A + θ_k)/(A − θ_k)``; saving 1 − θ_k/A;
* ∫M² dt is least at ``κ = c (A² S₂ − A θ_k S₁) / (A² S₂ − 2 A θ_k S₁ + θ_k² L)``, with
  ``L = π/2 − φ_k``, ``S₁ = cos φ_k``, ``S₂ = L/2 + sin(2φ_k)/4``;
* mean |M| is least at ``κ = c θ₀/(θ₀ − θ_k)``, ``θ₀ = A sin φ₀`` where φ₀ solves
  ``2A cos φ₀ + 2θ_k φ₀ = A cos φ_k + θ_k (φ_k + π/2)``;
* positive and absolute work are least at ``κ = c (1 + √2 θ_k / (A − θ_k))``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import brentq

from hexaleg.checks import finite_array, real
from hexaleg.design.rules import PAPER_ALPHA, PAPER_AMPLITUDE, PAPER_OMEGA, PAPER_THETA_K
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.profiles import Sinusoid
from hexaleg.robot.springs import CONVENTIONS, DeadZoneSpring
from hexaleg.units import G, kgmm2_to_kgm2, mm_to_m

POSTURES: dict[str, float] = {"hanging": 1.0, "upright": -1.0}
"""Sign s of the gravity torque s·m·g·l·sin θ: eq. 6/13 (hanging lever, restoring) or upright."""

_TABLE6 = {"mass": 3.611e-2, "com": float(mm_to_m(47.141)), "length": float(mm_to_m(84.0)),
           "inertia": float(kgmm2_to_kgm2(107.059))}


def _stiffness(k: ArrayLike) -> np.ndarray:
    ka = finite_array("k", k)
    if np.any(ka < 0):
        raise InvalidParameterError("k", k, "stiffness >= 0 N·m/rad")
    return ka


@dataclass(frozen=True)
class PaperJoint:
    """The paper's single elastic joint in SI (defaults: Table 6, eq. 25, Section 4.2).

    Attributes:
        mass: Equivalent body mass m, kg (Table 6: 3.611e-2).
        com: Centre of mass to the rotation axis l, m (Table 6: 47.141 mm).
        inertia: Moment of inertia I about the centre of mass, kg·m² (Table 6: 107.059 kg·mm²).
        length: Leg length L, m (Table 6: 84 mm; not used by the dynamics).
        amplitude: A of eq. 16, rad (eq. 25: 0.3).
        omega: ω of eq. 16, rad/s, > 0 (eq. 25: 2).
        phase: φ of eq. 16, rad (eq. 25: 0).
        offset: B of eq. 16, rad (eq. 25: 0).
        theta_k: Contact angle θ_k, rad (Section 4.2: 7.32°).
        alpha: Angle conversion factor α (Section 4.2: 1.05).
        gravity: g, m/s², ≥ 0.
        posture: ``"hanging"`` (eq. 6, s = +1) or ``"upright"`` (s = −1).
        convention: Spring α convention, ``"eq14"`` (κ = kα, the paper's) or ``"eq7"`` (κ = kα²).

    Raises:
        InvalidParameterError: NaN/inf, m < 0, l < 0, I < 0, A ≤ 0, ω ≤ 0, α ≤ 0, θ_k < 0,
            g < 0, unknown posture or convention, or ``|B| + A ≤ θ_k`` (the spring never engages).
    """

    mass: float = _TABLE6["mass"]
    com: float = _TABLE6["com"]
    inertia: float = _TABLE6["inertia"]
    length: float = _TABLE6["length"]
    amplitude: float = PAPER_AMPLITUDE
    omega: float = PAPER_OMEGA
    phase: float = 0.0
    offset: float = 0.0
    theta_k: float = PAPER_THETA_K
    alpha: float = PAPER_ALPHA
    gravity: float = G
    posture: str = "hanging"
    convention: str = "eq14"

    def __post_init__(self) -> None:
        for name in ("mass", "com", "inertia", "length", "amplitude", "omega", "phase", "offset",
                     "theta_k", "alpha", "gravity"):
            real(name, getattr(self, name), allowed="a finite real number (no NaN or inf)")
        for name in ("mass", "com", "inertia", "length", "theta_k", "gravity"):
            if getattr(self, name) < 0:
                raise InvalidParameterError(name, getattr(self, name), ">= 0")
        for name in ("amplitude", "omega", "alpha"):
            if getattr(self, name) <= 0:
                raise InvalidParameterError(name, getattr(self, name), "> 0")
        if self.mass * self.com**2 + self.inertia <= 0:
            raise InvalidParameterError("mass, com, inertia", (self.mass, self.com, self.inertia),
                                        "m l² + I > 0")
        if self.posture not in POSTURES:
            raise InvalidParameterError("posture", self.posture, f"one of {', '.join(POSTURES)}")
        if self.convention not in CONVENTIONS:
            raise InvalidParameterError("convention", self.convention,
                                        f"one of {', '.join(CONVENTIONS)}")
        reach = abs(self.offset) + self.amplitude
        if reach <= self.theta_k:
            raise InvalidParameterError(
                "amplitude", self.amplitude,
                f"|offset| + amplitude > theta_k = {self.theta_k!r} rad; with |B| + A = "
                f"{reach!r} rad the joint never leaves the dead zone and the spring never engages")

    # ---- model -------------------------------------------------------------------------------

    @property
    def J(self) -> float:
        """Inertia about the joint axis m l² + I, kg·m² (eq. 5)."""
        return self.mass * self.com**2 + self.inertia

    @property
    def period(self) -> float:
        """Trajectory period 2π/ω, s."""
        return 2 * math.pi / self.omega

    @property
    def transmission(self) -> float:
        """κ/k: α (eq14) or α² (eq7)."""
        return self.alpha if self.convention == "eq14" else self.alpha**2

    @property
    def sinusoid(self) -> Sinusoid:
        """The joint's trajectory A sin(ωt + φ) + B (eq. 16) as a :class:`Sinusoid`."""
        return Sinusoid(self.amplitude, self.omega, self.phase, self.offset)

    def times(self, n: int = 2048) -> np.ndarray:
        """``n`` uniform samples of one period, endpoint excluded, s, shape (n,)."""
        if not isinstance(n, int) or n < 8:
            raise InvalidParameterError("n", n, "an integer >= 8")
        return np.arange(n) * (self.period / n)

    def trajectory(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Eq. 16: θ = A sin(ωt + φ) + B and its first two derivatives (:attr:`sinusoid`).

        Args:
            t: Times, s, any shape.

        Returns:
            (θ rad, θ̇ rad/s, θ̈ rad/s²), each the shape of t.
        """
        return self.sinusoid(finite_array("t", t))

    def spring(self, k: float) -> DeadZoneSpring:
        """The paper's symmetric spring (eq. 8) of stiffness k, N·m/rad, in this convention."""
        return DeadZoneSpring(k, theta_k=self.theta_k, alpha=self.alpha,
                              convention=self.convention)

    def baseline_torque(self, t: ArrayLike, gravity: bool = True) -> np.ndarray:
        """Motor torque without the spring (eq. 13 with k = 0), N·m, shape of t.

        ``M = (m l² + I) θ̈ + s m g l sin θ`` with s from :data:`POSTURES`.
        """
        th, _, thdd = self.trajectory(t)
        tau = self.J * thdd
        if gravity:
            tau = tau + POSTURES[self.posture] * self.mass * self.gravity * self.com * np.sin(th)
        return tau

    def spring_basis(self, t: ArrayLike) -> np.ndarray:
        """Spring torque on the joint per unit k, N·m per N·m/rad, shape of t (eq. 8, 14)."""
        th, _, _ = self.trajectory(t)
        b = self.spring(1.0).torque_basis(th)
        return b.plus + b.minus

    def motor_torque(self, t: ArrayLike, k: ArrayLike, gravity: bool = True) -> np.ndarray:
        """Motor torque with the spring (eq. 14/17, restoring sign), N·m.

        Args:
            t: Times, s, shape (T,).
            k: Spring stiffness(es) in this joint's convention, N·m/rad, scalar or shape (K,).
            gravity: Include the gravity term.

        Returns:
            Shape (T,) for scalar k, else (K, T).
        """
        ka = _stiffness(k)
        tau = self.baseline_torque(t, gravity) - ka[..., None] * self.spring_basis(t)
        return tau

    # ---- eq. 19 and closed forms ---------------------------------------------------------------

    def k_M(self) -> float:
        """Eq. 19: ``k_M = ω² (m l² + I) / α`` (eq14; eq7: / α²), N·m/rad, SI.

        The stiffness at which dM/dt = 0 while the spring is engaged (no gravity): there the
        spring cancels the inertial torque's growth and M stays at −J ω² θ_k.
        """
        return self.omega**2 * self.J / self.transmission

    def _closed_form_check(self) -> None:
        if self.offset != 0.0:
            raise InvalidParameterError("offset", self.offset,
                                        "0 for the closed forms (they assume B = 0)")

    def _phi_k(self) -> float:
        return math.asin(self.theta_k / self.amplitude)

    def closed_form_peak_interval(self) -> tuple[float, float]:
        """No gravity, B = 0: stiffness interval where peak |M| is least, N·m/rad (derived from
        eq. 17): κ ∈ [J ω², J ω² (A + θ_k)/(A − θ_k)], peak J ω² θ_k there."""
        self._closed_form_check()
        c, a, tk = self.J * self.omega**2, self.amplitude, self.theta_k
        return c / self.transmission, c * (a + tk) / (a - tk) / self.transmission

    def closed_form_peak_saving(self) -> float:
        """No gravity, B = 0: peak-torque saving in the flat optimum, 1 − θ_k/A (from eq. 17)."""
        self._closed_form_check()
        return 1.0 - self.theta_k / self.amplitude

    def closed_form_int_sq(self) -> float:
        """No gravity, B = 0: stiffness minimising ∫M² dt over a period, N·m/rad (derived from
        eq. 17; see the module docstring)."""
        self._closed_form_check()
        a, tk, pk = self.amplitude, self.theta_k, self._phi_k()
        L = math.pi / 2 - pk
        s1, s2 = math.cos(pk), L / 2 + math.sin(2 * pk) / 4
        kappa = self.J * self.omega**2 * (a * a * s2 - a * tk * s1) / (
            a * a * s2 - 2 * a * tk * s1 + tk * tk * L)
        return kappa / self.transmission

    def closed_form_mean_abs(self) -> float:
        """No gravity, B = 0: stiffness minimising the mean |M| over a period, N·m/rad (derived
        from eq. 17: the zero θ₀ of M splits the engaged arc into parts of equal ∫(θ − θ_k)dφ)."""
        self._closed_form_check()
        a, tk, pk = self.amplitude, self.theta_k, self._phi_k()
        rhs = a * math.cos(pk) + tk * (pk + math.pi / 2)
        phi0 = brentq(lambda p: 2 * a * math.cos(p) + 2 * tk * p - rhs, pk, math.pi / 2,
                      xtol=1e-15)
        th0 = a * math.sin(phi0)
        return self.J * self.omega**2 * th0 / (th0 - tk) / self.transmission

    def closed_form_work(self) -> float:
        """No gravity, B = 0: stiffness minimising positive (and absolute) motor work per period,
        N·m/rad: κ = J ω² (1 + √2 θ_k/(A − θ_k)) (derived from eq. 20–21, see docs/paper.md)."""
        self._closed_form_check()
        a, tk = self.amplitude, self.theta_k
        return self.J * self.omega**2 * (1 + math.sqrt(2) * tk / (a - tk)) / self.transmission

    def closed_form_zero_work_quarter(self) -> float:
        """No gravity, B = 0: stiffness at which eq. 21 over contact → turning point is zero (the
        spring stores exactly the kinetic energy at contact), N·m/rad: κ = J ω² (A+θ_k)/(A−θ_k)."""
        self._closed_form_check()
        a, tk = self.amplitude, self.theta_k
        return self.J * self.omega**2 * (a + tk) / (a - tk) / self.transmission

    # ---- energy (eq. 20–21) --------------------------------------------------------------------

    def critical_times(self) -> np.ndarray:
        """Times in [0, period) where the spring engages (θ = ±θ_k) or the joint turns, s.

        Every extreme of |M| without gravity lies at one of these (M is affine in θ on each
        branch), so :func:`hexaleg.paper.metrics.metric` ``"peak"`` evaluates them on top
        of the uniform samples.
        """
        a, b, tk = self.amplitude, self.offset, self.theta_k
        psi = [math.pi / 2, 3 * math.pi / 2]
        for c in (tk, -tk):
            if abs(c - b) <= a:
                p = math.asin((c - b) / a)
                psi += [p, math.pi - p]
        return np.sort(np.mod((np.array(psi) - self.phase) / self.omega, self.period))

    def contact_time(self) -> float:
        """First time after the upward zero crossing at which θ reaches θ_k (B = 0), s."""
        self._closed_form_check()
        return (self._phi_k() - self.phase) / self.omega

    def energy(self, k: ArrayLike, t0: float, t1: float, gravity: bool = True,
               n: int = 20001) -> np.ndarray:
        """Eq. 20–21: motor work ∫ M θ̇ dt from t0 to t1 (trapezoid on n samples), J.

        Args:
            k: Stiffness(es), N·m/rad, scalar or (K,).
            t0: Start time, s.
            t1: End time, s, > t0.
            gravity: Include gravity.
            n: Number of samples.

        Returns:
            Scalar or (K,).
        """
        if not (math.isfinite(t0) and math.isfinite(t1) and t1 > t0):
            raise InvalidParameterError("t1", t1, f"finite and > t0 = {t0!r}")
        t = np.linspace(t0, t1, n)
        _, thd, _ = self.trajectory(t)
        return np.trapezoid(self.motor_torque(t, k, gravity) * thd, t, axis=-1)
