"""The Joule scaling law: an actuator's Joule loss at its peak torque against its torque class,
fitted on the catalogue, to give a Joule coefficient where no catalogue actuator is of a joint's
class. Every figure it gives rests on assumed constants: an estimate, never a bound.

**The law.** Wensing, Wang, Seok, Otten, Lang & Kim, "Proprioceptive actuator design in the MIT
Cheetah: impact mitigation and high-bandwidth physical interaction for dynamic legged robots",
IEEE Transactions on Robotics 33(3), 2017, §III-C ("dimensional analysis of DC motors"): with
fixed rotor and stator thicknesses, thin walls and a constant current density (thermal and
electromagnetic similarity), a motor of gap radius r_g and length l has mass
``M = 2π r_g l (t_s ρ_s + t_r ρ_r)`` and torque ``τ = 2π r_g² l σ_s`` (σ_s the constant shear
stress), so ``τ/M ∝ r_g`` (their eq. 38), and a motor constant (torque squared per ohmic loss)
``K_M² = τ²/(I²R) ∝ r_g³ l`` (their eq. 41; on the Emoteq HT catalogue they measured
``∝ r_g^4.1``). The Joule loss at the torque of that current density is therefore
``τ²/K_M² ∝ r_g l ∝ M`` and, at a given gap radius, ``∝ τ``: **the Joule loss at peak torque
grows as a power of the torque class, P_peak = a τ_peak^β, with β = 1 at a fixed gap radius**
(equivalently ``K_M ∝ τ^(1 − β/2) = √τ``, or ``K_M ∝ √M``). A gearbox moves no point: it
multiplies torque and ``K_M`` alike and leaves ``P_peak`` as it is.

**The fit** (:func:`fit`, :func:`catalogue_law`). For each sourced actuator (every catalogue
entry, each with its source), ``P_peak = c τ_peak²`` — c = R/(k_t G)² its Joule coefficient,
τ_peak its stall (peak) torque at the output, so P_peak = R I_peak², the Joule loss at its peak
current. ``log P_peak = log a + β log τ_peak`` is fitted by least squares over the entries, each
entry one point (two sources of one actuator are two points: their disagreement is part of the
spread). The **spread** is the range of the ratios measured / law over the entries; a figure
from the law is given at the law (``"central"``) and at both ends of that range (``"low"``,
``"high"``).

**An actuator from the law** (:meth:`JouleLaw.motor`) for a joint of effort limit E:
``c = P_peak(E) / E² = a E^(β − 2)`` (times the spread's end), written as k_t G = 1 N·m/A and
R = c Ω (only c enters a power); its gearbox efficiency is assumed: the median of the fitted
entries' η at the law, their highest with the low end and their lowest with the high end (the
figures' range); no regeneration; stall torque E and no-load speed the joint's velocity limit
(which enters no power). Its ``notes`` open with :data:`LAW_MARK`.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.checks import positive
from hexaleg.errors import InvalidParameterError
from hexaleg.quantities import quantity
from hexaleg.robot.catalogue import CATALOGUE
from hexaleg.robot.motor import GENERIC_VOLTAGE, Motor

LAW_MARK = "Assumed actuator from the Joule scaling law"
"""The first words of the ``notes`` of every actuator built from the law: its constants are
assumed, so nothing computed with it is a bound."""

LAW_SOURCE = ("Wensing, Wang, Seok, Otten, Lang & Kim, 'Proprioceptive actuator design in the "
              "MIT Cheetah', IEEE T-RO 33(3), 2017, Sec. III-C: tau = 2 pi r_g^2 l sigma_s, "
              "M = 2 pi r_g l (t_s rho_s + t_r rho_r), K_M^2 = tau^2/(I^2 R) ~ r_g^3 l (eq. 41), "
              "so the Joule loss at peak torque P = tau^2/K_M^2 ~ M, ~ tau at a fixed gap radius")
"""The law's source, as the JSON and the actuators built from it cite it."""

ENDS = ("low", "central", "high")
"""The three figures the law gives: the spread's low end, the law, the spread's high end."""

_ETA_WORD = {"low": "highest", "central": "median", "high": "lowest"}
"""Which of the fitted actuators' efficiencies :meth:`JouleLaw.efficiency` takes at each end."""


def family(name: str) -> str:
    """A catalogue entry's actuator family, for leaving a whole family out of a fit: the name
    up to its first ``-`` (``"MiniCheetah-hip-Katz"`` → ``"MiniCheetah"``, ``"XM540-W270"`` →
    ``"XM540"``)."""
    return name.split("-")[0]


@dataclass(frozen=True)
class JouleLaw:
    """``P_peak = a τ_peak^β`` fitted on sourced actuators (module docstring).

    Attributes:
        coefficient: a, W/(N·m)^β.
        exponent: β, 1.
        members: The fitted actuators' names.
        torques: Their peak torques τ_peak, N·m, in the order of ``members``.
        peak_losses: Their Joule loss at peak torque ``c τ_peak²``, W.
        efficiencies: Their gearbox efficiencies η.
    """

    coefficient: float
    exponent: float
    members: tuple[str, ...]
    torques: tuple[float, ...]
    peak_losses: tuple[float, ...]
    efficiencies: tuple[float, ...]

    def peak_loss(self, torque: float) -> float:
        """The law's Joule loss at a peak torque of ``torque`` N·m, ``a τ^β``, W."""
        return self.coefficient * positive("torque", torque) ** self.exponent

    @property
    def ratios(self) -> tuple[float, ...]:
        """Each member's P_peak over the law's at its torque (the fit's residuals, as factors)."""
        return tuple(p / self.peak_loss(t) for t, p in zip(self.torques, self.peak_losses,
                                                              strict=True))

    @property
    def spread(self) -> tuple[float, float]:
        """The lowest and highest of :attr:`ratios`: the members lie within these factors of
        the law."""
        r = self.ratios
        return min(r), max(r)

    @property
    def log_rms(self) -> float:
        """The RMS of the natural-log residuals (0.41 is a factor e^0.41 = 1.5 either way)."""
        return float(np.sqrt(np.mean(np.log(self.ratios) ** 2)))

    def factor(self, end: str) -> float:
        """The factor on the law at ``end`` (one of :data:`ENDS`)."""
        if end not in ENDS:
            raise InvalidParameterError("end", end, f"one of {', '.join(ENDS)}")
        lo, hi = self.spread
        return {"low": lo, "central": 1.0, "high": hi}[end]

    def efficiency(self, end: str) -> float:
        """The assumed gearbox efficiency at ``end``: the members' highest (``"low"``), median
        (``"central"``) or lowest (``"high"``)."""
        self.factor(end)
        eta = sorted(self.efficiencies)
        return {"low": eta[-1], "central": float(np.median(eta)), "high": eta[0]}[end]

    def joule_coefficient(self, effort: float, end: str = "central") -> float:
        """``c = a E^(β − 2)`` times the spread's factor at ``end``, W/(N·m)², for an actuator
        whose peak torque is ``effort`` N·m."""
        e = positive("effort", effort)
        return self.factor(end) * self.peak_loss(e) / e**2

    def motor(self, effort: float, speed: float, end: str = "central") -> Motor:
        """An actuator of peak torque ``effort`` N·m from the law (module docstring), its
        constants assumed and said in its ``notes``.

        Args:
            effort: The joint's effort limit E, N·m, > 0.
            speed: The joint's velocity limit, rad/s, > 0 (its no-load speed; no power uses it).
            end: Which figure, one of :data:`ENDS`.

        Raises:
            InvalidParameterError: ``effort`` or ``speed`` not > 0, ``end`` not in :data:`ENDS`.
        """
        c = self.joule_coefficient(effort, end)
        eta = self.efficiency(end)
        lo, hi = self.spread
        return Motor(
            name=f"scaling law ({end})", gear_ratio=1.0, torque_constant=1.0, resistance=c,
            gearbox_efficiency=eta, regeneration=False, stall_torque=float(effort),
            no_load_speed=positive("speed", speed), voltage=GENERIC_VOLTAGE,
            source=f"{LAW_SOURCE}; fitted on {len(self.members)} catalogue actuators "
                   "(hexaleg.robot.scaling_law)",
            notes=(f"{LAW_MARK}, not a motor's: P_peak = {self.coefficient:.4g} "
                   f"tau_peak^{self.exponent:.4g} W, the fit's spread x{lo:.3g}-x{hi:.3g}; at "
                   f"{end}: c = {c:.4g} W/(N m)^2 at E = {effort:.4g} N m, assumed eta = "
                   f"{eta:.3g} (the fitted actuators' {_ETA_WORD[end]}), "
                   "k_t G = 1 N m/A and R = c chosen to give c, no regeneration, no-load speed "
                   "the joint's velocity limit (no power uses it)"))

    def as_dict(self) -> dict[str, Any]:
        """The law, its fit and spread for a JSON, ``{value, unit}`` where a unit applies."""
        lo, hi = self.spread
        return {"law": "P_peak = a tau_peak^beta (Joule loss at peak torque against the "
                       "torque class)",
                "coefficient": quantity(self.coefficient, f"W/(N·m)^{self.exponent:.4g}"),
                "exponent": quantity(self.exponent, "1"),
                "spread": {"low": quantity(lo, "1"), "high": quantity(hi, "1")},
                "log_rms": quantity(self.log_rms, "1"),
                "members": list(self.members), "source": LAW_SOURCE,
                "assumed": True, "is_bound": False}


def fit(motors: Mapping[str, Motor]) -> JouleLaw:
    """The law fitted on ``motors`` (module docstring): least squares of ``log c τ_peak²``
    against ``log τ_peak``, each actuator one point, in name order.

    Raises:
        InvalidParameterError: fewer than two distinct peak torques (no slope to fit).
    """
    names = tuple(sorted(motors))
    torques = np.array([motors[n].stall_torque for n in names], dtype=float)
    if np.unique(torques).size < 2:
        raise InvalidParameterError("motors", names,
                                    "actuators with at least two distinct peak torques")
    losses = np.array([float(motors[n].joule_coefficient) * motors[n].stall_torque ** 2
                       for n in names])
    design = np.column_stack([np.ones_like(torques), np.log(torques)])
    (log_a, beta), *_ = np.linalg.lstsq(design, np.log(losses), rcond=None)
    return JouleLaw(coefficient=float(np.exp(log_a)), exponent=float(beta), members=names,
                    torques=tuple(map(float, torques)), peak_losses=tuple(map(float, losses)),
                    efficiencies=tuple(float(motors[n].gearbox_efficiency) for n in names))


@functools.cache
def catalogue_law() -> JouleLaw:
    """The law fitted on every catalogue actuator (:data:`hexaleg.robot.catalogue.CATALOGUE`)."""
    return fit(CATALOGUE)


__all__ = ["ENDS", "LAW_MARK", "LAW_SOURCE", "JouleLaw", "catalogue_law", "family", "fit"]
