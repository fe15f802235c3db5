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

Datasheet stall figures give the constants (ROBOTIS e-Manual, see :data:`CATALOGUE`): the
output torque per ampere ``k_t G = τ_stall / I_stall`` (gearbox losses at stall folded in, so the
model reproduces the stall current exactly), ``R = V / I_stall`` (includes the driver), and the
gearbox efficiency from the ideal DC-motor torque–speed line, ``η = τ_stall ω_no_load /
(V I_stall)``. These are crude defaults; replace them with identified values where available
(:func:`motor_from_mapping` accepts a catalogue ``base`` plus overrides).

One brushless actuator is in the catalogue too, the ODRI module that drives Solo-12 (T-Motor
Antigravity 4004 300 kV, 9 : 1 two-stage timing belt): in the rotor (dq) frame a field-oriented
brushless motor is this DC model with ``i`` the q-axis current, and the copper loss of a star
winding of phase resistance ``R_s`` is ``(3/2) R_s i²`` (amplitude-invariant currents), so
``R = (3/2) R_s`` — see :func:`odri_actuator` for the figures and what is assumed.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from hexaleg.checks import positive, real
from hexaleg.config import from_mapping
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError

RPM = 2.0 * math.pi / 60.0
"""One revolution per minute in rad/s (datasheets state speeds in rpm)."""


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


@dataclass(frozen=True)
class Motor:
    """A geared DC servo driving one joint.

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

    @property
    def joule_coefficient(self) -> float:
        """``c = R / (k_t G)²``, W/(N·m)²: Joule loss per squared output torque."""
        return self.resistance / (self.torque_constant * self.gear_ratio) ** 2

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
                   regeneration: bool = False) -> Motor:
    """Motor constants from the stall and no-load figures of a servo datasheet.

    ``k_t = τ_stall / (G I_stall)``, ``R = V / I_stall`` and ``η = τ_stall ω_no_load / (V I_stall)``
    (the ideal DC motor's back-EMF constant ``V / ω_no_load`` against the stall torque per ampere).

    Args:
        name: Model name.
        gear_ratio: Reduction G.
        stall_torque: Stall torque at the output, N·m.
        stall_current: Stall current, A, > 0.
        no_load_speed_rpm: No-load output speed, rpm.
        voltage: Supply voltage of the figures, V.
        source: The datasheet.
        regeneration: Whether the supply takes power back.

    Returns:
        The motor.

    Raises:
        InvalidParameterError: a figure is not positive, or the figures imply η > 1 (mutually
            inconsistent datasheet values).
    """
    if not stall_current > 0:
        raise InvalidParameterError(f"{name} stall_current", stall_current, "> 0")
    eta = stall_torque * no_load_speed_rpm * RPM / (voltage * stall_current)
    return Motor(name=name, gear_ratio=gear_ratio,
                 torque_constant=stall_torque / (gear_ratio * stall_current),
                 resistance=voltage / stall_current, gearbox_efficiency=eta,
                 regeneration=regeneration, stall_torque=stall_torque,
                 no_load_speed=no_load_speed_rpm * RPM, voltage=voltage, source=source)


def _robotis(name: str, url: str, **figures: Any) -> Motor:
    return from_datasheet(name, source=f"ROBOTIS e-Manual, {name} specifications, {url} "
                                       "(stall and no-load figures at 12 V)", **figures)


def odri_actuator() -> Motor:
    """The Open Dynamic Robot Initiative actuator module v1 of Solo-12 (Grimminger et al.,
    "An Open Torque-Controlled Modular Robot Architecture for Legged Locomotion Research",
    IEEE RA-L 5(2), 2020).

    Figures from the module's documentation (open-dynamic-robot-initiative,
    open_robot_actuator_hardware, "Brushless Actuator Module v1"): gear ratio 9 (3 : 1 × 3 : 1),
    2.5 N·m at the output at 12 A (so ``k_t G = 2.5 / 12`` N·m/A, belt losses included, as for
    the servos' stall figures), phase resistance ``R_s`` = 0.23255 Ω identified with TI
    Motorware, motor 300 rpm/V. Assumed: the 12 A is the q-axis current amplitude, so
    ``R = 1.5 R_s``; a 24 V supply, giving the no-load output speed 300 · 24 / 9 = 800 rpm; a
    belt efficiency of 0.9 (two stages); 2.5 N·m, the torque at the 12 A current limit, stands
    for the stall torque.
    """
    return Motor(name="ODRI-4004", gear_ratio=9.0, torque_constant=2.5 / 12.0 / 9.0,
                 resistance=1.5 * 0.23255, gearbox_efficiency=0.9, regeneration=False,
                 stall_torque=2.5, no_load_speed=300.0 * 24.0 / 9.0 * RPM, voltage=24.0,
                 source="ODRI actuator module v1 (Solo-12), open-dynamic-robot-initiative/"
                        "open_robot_actuator_hardware: 9:1, 2.5 N·m at 12 A, R_s 0.23255 Ω; "
                        "R = 1.5 R_s, 24 V and η = 0.9 assumed")


CATALOGUE: Mapping[str, Motor] = MappingProxyType({
    m.name: m for m in (
        _robotis("AX-12A", "https://emanual.robotis.com/docs/en/dxl/ax/ax-12a/",
                 gear_ratio=254.0, stall_torque=1.5, stall_current=1.5,
                 no_load_speed_rpm=59.0, voltage=12.0),
        _robotis("AX-18A", "https://emanual.robotis.com/docs/en/dxl/ax/ax-18a/",
                 gear_ratio=254.0, stall_torque=1.8, stall_current=2.2,
                 no_load_speed_rpm=97.0, voltage=12.0),
        _robotis("MX-28", "https://emanual.robotis.com/docs/en/dxl/mx/mx-28-2/",
                 gear_ratio=193.0, stall_torque=2.5, stall_current=1.4,
                 no_load_speed_rpm=55.0, voltage=12.0),
        _robotis("XM540-W150", "https://emanual.robotis.com/docs/en/dxl/x/xm540-w150/",
                 gear_ratio=152.3, stall_torque=7.3, stall_current=4.4,
                 no_load_speed_rpm=53.0, voltage=12.0),
        _robotis("XM540-W270", "https://emanual.robotis.com/docs/en/dxl/x/xm540-w270/",
                 gear_ratio=272.5, stall_torque=10.6, stall_current=4.4,
                 no_load_speed_rpm=30.0, voltage=12.0),
        odri_actuator(),
    )
})
"""Real actuators, keyed by model name: ROBOTIS servos with datasheet values (e-Manual) and the
ODRI brushless module of Solo-12 (:func:`odri_actuator`)."""

DEFAULT_MOTOR = "AX-18A"
"""The servo whose stall torque (1.8 N·m) and no-load speed (97 rpm) are the robot's joint limits
(``urdf/hexaleg.toml`` [servo])."""


def motor(name: str = DEFAULT_MOTOR) -> Motor:
    """Look up a servo in :data:`CATALOGUE` (case-insensitive).

    Args:
        name: Model name, e.g. ``"AX-18A"``.

    Returns:
        The motor.

    Raises:
        UnknownNameError: the name is not in the catalogue; the message lists the valid names.
    """
    for key, value in CATALOGUE.items():
        if isinstance(name, str) and key.lower() == name.strip().lower():
            return value
    raise UnknownNameError("motor", name, CATALOGUE)


def motor_from_mapping(data: Mapping[str, Any], where: str = "[motor]") -> Motor:
    """Build a motor from a TOML table: a catalogue ``base`` with overrides, or every field.

    Example::

        [motor]
        base = "AX-18A"
        resistance = 3.1        # identified winding resistance, Ω
        regeneration = true

    Args:
        data: Keys are :class:`Motor` fields, plus optional ``base`` (a catalogue name).
        where: Where the table came from, for error messages.

    Returns:
        The motor (validated).

    Raises:
        UnknownNameError: unknown key or unknown base name.
        ConfigError: a value of the wrong type, or fields missing without a ``base``.
        InvalidParameterError: a value out of range.
    """
    if not isinstance(data, Mapping):
        raise ConfigError(f"{where}: expected a table of keys, got {data!r}")
    data = dict(data)
    base_name = data.pop("base", None)
    if base_name is None:
        missing = [f.name for f in dataclasses.fields(Motor) if f.name not in data]
        if missing:
            raise ConfigError(f"{where}: missing keys {', '.join(missing)} "
                              f"(or give base = one of {', '.join(CATALOGUE)})")
        return from_mapping(Motor, data, where)
    base = motor(base_name)
    fields = {f.name: getattr(base, f.name) for f in dataclasses.fields(Motor)}
    if "source" not in data and data:
        fields["source"] = f"{base.source}; overridden in {where}: {', '.join(sorted(data))}"
    return from_mapping(Motor, {**fields, **data}, where)


def catalogue_table(motors: Mapping[str, Motor] | None = None) -> str:
    """A plain-text table of motors with the constants the energy model uses.

    Args:
        motors: Motors by name; default :data:`CATALOGUE`.

    Returns:
        One header line, one line per motor (G, k_t G N·m/A, R Ω, η, c W/(N·m)², stall torque
        N·m, no-load speed rpm, regeneration) and one source line per motor.
    """
    motors = CATALOGUE if motors is None else motors
    lines = [f"{'motor':<12} {'G':>7} {'k_t·G':>7} {'R':>6} {'eta':>5} {'c':>7} "
             f"{'stall':>6} {'rpm':>5}  regen"]
    for name, m in motors.items():
        lines.append(f"{name:<12} {m.gear_ratio:7.1f} {m.torque_constant * m.gear_ratio:7.3f} "
                     f"{m.resistance:6.2f} {m.gearbox_efficiency:5.3f} "
                     f"{m.joule_coefficient:7.3f} {m.stall_torque:6.2f} "
                     f"{m.no_load_speed / RPM:5.0f}  {'yes' if m.regeneration else 'no'}")
    lines.append("units: k_t·G N·m/A at the output, R ohm, c = R/(k_t·G)^2 W/(N·m)^2, "
                  "stall torque N·m; default " + DEFAULT_MOTOR)
    lines += [f"{name}: {m.source}" for name, m in motors.items()]
    return "\n".join(lines)
