"""Geared DC servo model: joint torque and speed → current, Joule loss and electrical power.

The model (see ``docs/energy.md`` for the derivation and the sources):

* current for output (joint) torque τ: ``i = τ / (k_t G)``, so the Joule loss is
  ``P_J = R i² = c τ²`` with the Joule coefficient ``c = R / (k_t G)²`` in W/(N·m)² — a convex
  quadratic in τ, the term the force-distribution objectives use;
* constant-efficiency gearbox with the direction of power flow (Verstraten et al., "Energy
  consumption of geared DC motors in dynamic applications: comparing modeling approaches",
  IEEE Robotics and Automation Letters 1(1), 2016): the motor supplies ``P/η`` when it drives the
  load (motoring, joint power ``P = τ q̇ ≥ 0``) and receives ``η P`` when the load back-drives it
  (``P < 0``); that is ``max(P/η, η P)``, a maximum of two linear functions of τ, hence convex;
* electrical power ``P_e = max(P/η, η P) + c τ²`` (convex in τ for a given q̇). With
  regeneration a negative ``P_e`` flows back to the supply; without it the driver burns it, so
  the drawn power is ``max(0, P_e)`` (still convex).

Datasheet stall figures give the constants (:func:`from_datasheet`): the output torque per ampere
``k_t G = τ_stall / I_stall`` (gearbox losses at stall folded in, so the model reproduces the
stall current exactly), ``R = V / I_stall`` (includes the driver), and the gearbox efficiency from
the ideal DC-motor torque–speed line, ``η = τ_stall ω_no_load / (V I_stall)``. These are crude
defaults; replace them with identified values where available (:func:`motor_from_mapping` accepts
a catalogue ``base`` plus overrides). An actuator known only by a URDF joint's effort and velocity
limits gets the same relations under stated assumptions (:func:`generic_actuator`).

The real actuators — ROBOTIS and Feetech servos from their datasheets, and the ODRI brushless
module of Solo-12 — are in :mod:`hexaleg.robot.catalogue`, which builds on this module (and not
the other way round).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np
from numpy.typing import ArrayLike

from hexaleg.checks import named_arguments, positive, real
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.actuator import EVERY_JOINT
from hexaleg.robot.standby import Idle, standby_draw

RPM = 2.0 * math.pi / 60.0
"""One revolution per minute in rad/s (datasheets state speeds in rpm)."""

GENERIC_VOLTAGE = 24.0
"""Reference supply voltage of :func:`generic_actuator`, V (it scales only its current and
resistance: no power or energy depends on it)."""

GENERIC_GEARBOX_EFFICIENCY = 0.7
"""Constant gearbox efficiency η of :func:`generic_actuator` (the datasheet-derived values of the
catalogue's servos span 0.43–0.86, median about 0.63)."""

GENERIC_EFFICIENCY_RANGE = (0.43, 0.86)
"""The span of the datasheet-derived gearbox efficiencies of the catalogue's servos (AX-12A 0.43 …
XL430-W250 0.86): the range of η a generic actuator could have, and so of the energy it implies
(:func:`generic_energy_range`)."""

GENERIC_GEAR_RATIO = 1.0
"""Gear ratio G of :func:`generic_actuator`: its torque constant is stated at the output (G is not
identifiable from two limits, and only ``k_t G`` enters any power)."""



def as_torque_speed(tau: ArrayLike, qdot: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Check joint torques and speeds: same shape, finite.

    Args:
        tau: Joint torques, any shape, N·m.
        qdot: Joint speeds, the same shape as ``tau``, rad/s.

    Returns:
        ``(tau, qdot)`` as float arrays.

    Raises:
        InvalidParameterError: the shapes differ, or a value is NaN or infinite (the message names
            the first bad index).
    """
    t = np.asarray(tau, dtype=float)
    w = np.asarray(qdot, dtype=float)
    if t.shape != w.shape:
        raise InvalidParameterError("qdot", f"array of shape {w.shape}",
                                    f"the shape of tau, {t.shape}")
    for name, arr in (("tau", t), ("qdot", w)):
        if not np.all(np.isfinite(arr)):
            idx = tuple(int(i) for i in np.argwhere(~np.isfinite(arr))[0])
            raise InvalidParameterError(name, f"{arr[idx]} at index {idx}", "finite values")
    return t, w


@named_arguments
@dataclass(frozen=True)
class Motor:
    """A geared DC servo driving one joint: an :class:`~hexaleg.robot.actuator.Actuator` with
    one model on every joint (catalogue servos, brushless modules, generic and identified
    actuators are all instances, built by different constructors).

    Attributes:
        name: Model name, e.g. ``"AX-18A"``.
        gear_ratio: Reduction G (motor speed / joint speed), > 0.
        torque_constant: k_t at the motor shaft, N·m/A, > 0. The output torque per ampere is
            ``k_t G``; taken from stall figures (as in the catalogue) it includes the gearbox
            losses at stall.
        resistance: Winding resistance R, Ω, > 0 (from stall figures it includes the driver).
        gearbox_efficiency: Constant gearbox efficiency η, in (0, 1]: ``P/η`` is drawn when
            motoring, ``η P`` returned when back-driven.
        regeneration: Whether negative electrical power flows back to the supply (the default of
            :meth:`electrical_power`).
        stall_torque: Stall torque at the output, N·m, > 0.
        no_load_speed: No-load speed at the output, rad/s, > 0.
        voltage: Supply voltage of the figures, V, > 0.
        source: Where the values come from (datasheet named), non-empty.
        notes: What was derived or assumed rather than read off the source, in words and
            numbers (e.g. ``R = V / I_stall``, an assumed efficiency), for reports to show; may
            be empty.
    """

    name: str
    gear_ratio: float
    torque_constant: float
    resistance: float
    gearbox_efficiency: float
    regeneration: bool
    stall_torque: float
    no_load_speed: float
    voltage: float
    source: str
    notes: str = ""

    def __post_init__(self) -> None:
        for key in ("name", "source"):
            value = getattr(self, key)
            if not isinstance(value, str) or not value.strip():
                raise InvalidParameterError(f"Motor.{key}", value, "a non-empty string")
        for key in ("gear_ratio", "torque_constant", "resistance", "stall_torque",
                    "no_load_speed", "voltage"):
            positive(f"Motor.{key}", getattr(self, key))
        real("Motor.gearbox_efficiency", self.gearbox_efficiency, low=0.0, low_open=True,
             high=1.0, allowed="a number in (0, 1]")
        if not isinstance(self.regeneration, bool):
            raise InvalidParameterError("Motor.regeneration", self.regeneration, "True or False")
        if not isinstance(self.notes, str):
            raise InvalidParameterError("Motor.notes", self.notes, "a string (may be empty)")

    @property
    def joule_coefficient(self) -> float:
        """``c = R / (k_t G)²``, W/(N·m)²: Joule loss per squared output torque."""
        return self.resistance / (self.torque_constant * self.gear_ratio) ** 2

    @property
    def models(self) -> Mapping[str, Motor]:
        """``{"every joint": self}``: one model drives every joint
        (:attr:`hexaleg.robot.actuator.Actuator.models`)."""
        return MappingProxyType({EVERY_JOINT: self})

    def joint_labels(self, n_joints: int) -> tuple[str, ...]:
        """``("every joint",) * n_joints``: each joint's key in :attr:`models`."""
        return (EVERY_JOINT,) * n_joints

    def idle_power(self, n_joints: int) -> Idle:
        """The standby draw of ``n_joints`` of this servo, ``n I_standby V``, W: its catalogue
        standby current (:data:`hexaleg.robot.standby.STANDBY`, by :attr:`name`; none for a
        servo outside the catalogue) at :attr:`voltage`
        (:func:`hexaleg.robot.standby.standby_draw`)."""
        return standby_draw(((self.name, self.voltage),) * n_joints)

    def current(self, tau: ArrayLike) -> np.ndarray:
        """Winding current for an output torque, ``i = τ / (k_t G)``.

        Args:
            tau: Joint torques, any shape, N·m.

        Returns:
            Currents, the shape of ``tau``, A.
        """
        t, _ = as_torque_speed(tau, np.zeros(np.shape(tau)))
        return t / (self.torque_constant * self.gear_ratio)

    def joule_power(self, tau: ArrayLike) -> np.ndarray:
        """Joule (I²R) loss, ``c τ²``.

        Args:
            tau: Joint torques, any shape, N·m.

        Returns:
            Heat in the windings, the shape of ``tau``, W.
        """
        return self.resistance * self.current(tau) ** 2

    def gearbox_input_power(self, tau: ArrayLike, qdot: ArrayLike) -> np.ndarray:
        """Mechanical power at the motor side of the gearbox, ``max(P/η, η P)`` with ``P = τ q̇``.

        Args:
            tau: Joint torques, any shape, N·m.
            qdot: Joint speeds, the shape of ``tau``, rad/s.

        Returns:
            Power the motor converts to mechanical form (negative when back-driven), W.
        """
        t, w = as_torque_speed(tau, qdot)
        p = t * w
        eta = self.gearbox_efficiency
        return np.maximum(p / eta, p * eta)

    def electrical_power(self, tau: ArrayLike, qdot: ArrayLike,
                         regeneration: bool | None = None) -> np.ndarray:
        """Electrical power drawn by the servo, ``max(P/η, η P) + c τ²`` (clipped at 0 without
        regeneration).

        Args:
            tau: Joint torques, shape (T, n) (any shape works), N·m.
            qdot: Joint speeds, the shape of ``tau``, rad/s.
            regeneration: Whether negative power returns to the supply; ``None`` uses
                :attr:`regeneration`.

        Returns:
            Electrical power per sample and joint, the shape of ``tau``, W.
        """
        if regeneration is None:
            regeneration = self.regeneration
        p = self.gearbox_input_power(tau, qdot) + self.joule_power(tau)
        return p if regeneration else np.maximum(p, 0.0)


def from_datasheet(name: str, *, gear_ratio: float, stall_torque: float, stall_current: float,
                   no_load_speed_rpm: float, voltage: float, source: str,
                   regeneration: bool = False, notes: str = "") -> Motor:
    """Motor constants from the stall and no-load figures of a servo datasheet.

    The ideal geared DC motor (Verstraten et al. 2016, see the module docstring) at supply voltage
    V: at stall the winding carries ``I_stall = V / R``; at no load the back-EMF ``k_e G ω_0``
    equals V. Hence ``k_t G = τ_stall / I_stall`` (the stall torque per ampere, gearbox losses at
    stall included), ``R = V / I_stall`` (driver and wiring included) and
    ``η = τ_stall ω_0 / (V I_stall)`` (the back-EMF constant ``V / ω_0`` against the stall torque
    per ampere: ``k_t = η k_e``).

    Args:
        name: Model name.
        gear_ratio: Reduction G.
        stall_torque: Stall torque at the output, N·m.
        stall_current: Stall current, A, > 0.
        no_load_speed_rpm: No-load output speed, rpm.
        voltage: Supply voltage of the figures, V.
        source: The datasheet.
        regeneration: Whether the supply takes power back.
        notes: Remarks on the figures (variant, voltage chosen, unit conversions); the derivation
            of R, k_t G and η with their values is appended.

    Returns:
        The motor; its :attr:`Motor.notes` say which constants are derived rather than published.

    Raises:
        InvalidParameterError: a figure is not positive, or the figures imply η > 1 (mutually
            inconsistent datasheet values).
    """
    if not stall_current > 0:
        raise InvalidParameterError(f"{name} stall_current", stall_current, "> 0")
    eta = stall_torque * no_load_speed_rpm * RPM / (voltage * stall_current)
    derived = (f"Derived, not datasheet values: k_t G = τ_s / I_s = "
               f"{stall_torque / stall_current:.3f} N·m/A, R = V / I_s = "
               f"{voltage / stall_current:.2f} Ω (driver included), η = τ_s ω_0 / (V I_s) = "
               f"{eta:.3f}.")
    return Motor(name=name, gear_ratio=gear_ratio,
                 torque_constant=stall_torque / (gear_ratio * stall_current),
                 resistance=voltage / stall_current, gearbox_efficiency=eta,
                 regeneration=regeneration, stall_torque=stall_torque,
                 no_load_speed=no_load_speed_rpm * RPM, voltage=voltage, source=source,
                 notes=f"{notes} {derived}".strip())


def generic_energy_range() -> tuple[float, float]:
    """The factors by which a :func:`generic_actuator`'s Joule loss could differ from the one it
    states, over :data:`GENERIC_EFFICIENCY_RANGE`.

    Its Joule coefficient is ``c = ω_0 / (η τ_s)`` (:func:`generic_actuator`), so with the URDF
    limits taken at face value the Joule energy scales as ``η_assumed / η``: from
    ``0.7 / 0.86 = 0.81`` to ``0.7 / 0.43 = 1.63`` times the stated value. The gearbox term
    ``P/η`` moves by the same factors when motoring. A URDF effort limit below the real stall
    torque (a software limit) or a velocity limit below the no-load speed moves ``c`` further, in
    proportion to ``ω_0 / τ_s`` — not bounded by anything in the URDF.

    Returns:
        ``(low, high)``, dimensionless multipliers of the stated energy.
    """
    lo, hi = GENERIC_EFFICIENCY_RANGE
    return GENERIC_GEARBOX_EFFICIENCY / hi, GENERIC_GEARBOX_EFFICIENCY / lo


GENERIC_MARK = "Generic actuator from URDF limits"
"""How :func:`generic_actuator`'s notes begin (what marks a run's actuator as generic)."""


def generic_actuator(effort: float, velocity: float, *, name: str = "generic") -> Motor:
    """An actuator known only by a URDF joint's ``<limit effort=… velocity=…>``.

    Two limits cannot fix a motor, so the rest is assumed, and the motor's :attr:`Motor.notes`
    state every assumption with the resulting values:

    * the effort limit is the stall torque ``τ_s`` at the output and the velocity limit the
      no-load speed ``ω_0`` at the output, both at the supply voltage :data:`GENERIC_VOLTAGE`;
    * a constant gearbox efficiency :data:`GENERIC_GEARBOX_EFFICIENCY` (η), applied by the
      direction of power flow (Verstraten et al. 2016, as for every motor here);
    * gear ratio :data:`GENERIC_GEAR_RATIO` (G = 1: the torque constant is stated at the output);
    * no regeneration (the catalogue's conservative default).

    The ideal geared DC motor (Verstraten et al. 2016; the relations of :func:`from_datasheet`)
    then gives the back-EMF constant ``k_e G = V / ω_0``, the stall torque per ampere
    ``k_t G = η k_e G = η V / ω_0``, the stall current ``I_s = τ_s / (k_t G) = τ_s ω_0 / (η V)``
    and ``R = V / I_s = η V² / (τ_s ω_0)``. The Joule coefficient is ``c = R / (k_t G)² =
    ω_0 / (η τ_s)``: neither the assumed voltage nor the gear ratio changes any power or energy.

    Args:
        effort: The URDF effort limit, N·m, finite and > 0.
        velocity: The URDF velocity limit, rad/s, finite and > 0.
        name: The motor's name.

    Returns:
        The motor, with ``stall_torque == effort`` and ``no_load_speed == velocity``.

    Raises:
        InvalidParameterError: effort or velocity is not a finite number > 0 (a URDF that leaves
            ``effort`` or ``velocity`` at 0 gives no limit to build a motor from), or the name is
            empty.
    """
    for what, value, unit in (("effort", effort, "N·m"), ("velocity", velocity, "rad/s")):
        real(f"{name}: URDF {what} limit ({unit})", value, low=0.0, low_open=True,
             allowed=f"a finite number > 0 (the actuator's peak {what} in {unit}; a URDF "
                     "limit of 0 or none gives nothing to build a motor from)")
    tau_s, omega_0 = float(effort), float(velocity)
    v, eta, g = GENERIC_VOLTAGE, GENERIC_GEARBOX_EFFICIENCY, GENERIC_GEAR_RATIO
    kt_g = eta * v / omega_0
    i_s = tau_s / kt_g
    lo, hi = generic_energy_range()
    notes = (f"{GENERIC_MARK} only (generic_actuator). Assumed: effort "
             f"{tau_s:g} N·m = stall torque and velocity {omega_0:g} rad/s = no-load speed, both "
             f"at the output at {v:g} V; gearbox efficiency η = {eta:g} (constant, by power-flow "
             f"direction); gear ratio G = {g:g} (k_t at the output; only k_t G enters the "
             f"powers); no regeneration. Ideal DC motor (Verstraten et al., IEEE RA-L 2016): "
             f"k_t G = η V / ω_0 = {kt_g:.4g} N·m/A, stall current τ_s ω_0 / (η V) = "
             f"{i_s:.4g} A, R = V / I_s = {v / i_s:.4g} Ω, Joule coefficient c = ω_0 / (η τ_s) "
             f"= {omega_0 / (eta * tau_s):.4g} W/(N·m)², independent of the assumed voltage. "
             f"Range implied: with η anywhere in the catalogue's {GENERIC_EFFICIENCY_RANGE[0]:g}–"
             f"{GENERIC_EFFICIENCY_RANGE[1]:g} the Joule energy and the motoring gearbox "
             f"term are ×{lo:.2f}–×{hi:.2f} of the stated "
             "ones; an effort limit below the real stall torque or a velocity limit below the "
             "no-load speed moves them further, in proportion to ω_0 / τ_s. Give a catalogue "
             "motor (hexaleg motors) or identified constants for energies to trust.")
    return Motor(name=name, gear_ratio=g, torque_constant=kt_g / g, resistance=v / i_s,
                 gearbox_efficiency=eta, regeneration=False, stall_torque=tau_s,
                 no_load_speed=omega_0, voltage=v,
                 source=f"URDF joint limits: effort {tau_s:g} N·m, velocity {omega_0:g} rad/s; "
                        "every other constant assumed (see notes)", notes=notes)
