"""The actuator catalogue: real servos from their manufacturers' datasheets, looked up by name.

Each servo is built by :func:`hexaleg.robot.motor.from_datasheet` from the figures printed on the
manufacturer's specification page — gear ratio, stall torque and stall current at one supply
voltage, no-load speed at that voltage. Its ``source`` names the page and quotes the figures used.
None of these pages publishes a winding resistance or a motor torque constant, so both are derived
as :func:`~hexaleg.robot.motor.from_datasheet` documents (``R = V / I_stall`` with the driver
included, ``k_t G = τ_stall / I_stall``, ``η = τ_stall ω_0 / (V I_stall)``); each entry's
``notes`` say so, with the values.

* ROBOTIS DYNAMIXEL (AX, MX, X series): ROBOTIS e-Manual specification pages, figures at 12 V.
* Feetech STS3215: the 12 V version (ST-3215-C018, 30 kg·cm), from Feetech's product page; its
  torques are in kg·cm, read as kgf·cm (:data:`KGF_CM`), and its speed in s/60°.
* TowerPro MG996R and SG90 (:func:`_towerpro`): hobby PWM servos of hexapod kits and palm-sized
  quadrupeds, from TowerPro's datasheet figures (kgf·cm, s/60°); the SG90's sheet gives no stall
  current, so that figure is a retailer's, said in the entry. Neither publishes a gear ratio:
  G = 1 is stated (only ``k_t G`` enters any power).
* DFRobot DSS-M15S (:func:`_dss_m15s`): a 15 kg·cm metal-gear hobby servo whose maker publishes
  the stall current and gear ratio with the torque and speed (DFRobot wiki, 6 V figures).
* ODRI-4004: the brushless actuator module of Solo-12 (:func:`~hexaleg.robot.brushless.
  odri_actuator`, in :mod:`hexaleg.robot.brushless` with the other brushless quasi-direct-drive
  notes, re-exported here), with stated assumptions. That module also says which registry
  robots' actuators (Unitree A1, GO-M8010-6, ANYdrive) could not be sourced, and why.
* A1-Yang2021: the Unitree A1's joints as published A1 work models their energy
  (:func:`~hexaleg.robot.brushless.a1_energy_model`: ``τ q̇ + 0.3 τ²``, an empirical
  coefficient, not identified constants).

:data:`hexaleg.robot.standby.STANDBY` gives, per catalogue servo, its standby current (the
electronics' draw at rest) where the maker publishes it, with the page, or its family's figure
labelled as such; a test keeps one entry there for each entry here.

:data:`OUTPUT_HUBS` gives, per catalogue servo, the diameter of its output hub (the horn's boss,
the spline or the shaft a torsion spring could wind on) where a source states it as a number,
with that source; where none does, the entry says so and holds None, and
:func:`hexaleg.design.springs.parts.arbor_for` falls back to its stated rule.

The model itself (:class:`~hexaleg.robot.motor.Motor`) and the actuator built from URDF limits
(:func:`~hexaleg.robot.motor.generic_actuator`) are in :mod:`hexaleg.robot.motor`, which does not
import this module (import the catalogue's names from here).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

from hexaleg.checks import typed
from hexaleg.config import from_mapping
from hexaleg.errors import ConfigError, UnknownNameError
from hexaleg.robot.brushless import (
    a1_energy_model,
    cheetah3,
    mini_cheetah,
    odri_actuator,
    odri_actuator_paper,
)
from hexaleg.robot.motor import RPM, Motor, from_datasheet
from hexaleg.robot.standby import EMANUAL

KGF_CM = 9.80665e-2
"""One kilogram-force centimetre in N·m (standard gravity g_n = 9.80665 m/s², 3rd CGPM 1901;
hobby-servo datasheets write it "kg·cm")."""


def _robotis(name: str, url: str, *, gear_ratio: float, stall_torque: float,
             stall_current: float, no_load_speed_rpm: float, voltage: float = 12.0,
             notes: str = "") -> Motor:
    """A DYNAMIXEL from its ROBOTIS e-Manual figures at ``voltage`` (N·m, A, rpm)."""
    figures = (f"gear ratio {gear_ratio:g} : 1, stall torque {stall_torque:g} N·m at "
               f"{voltage:g} V and {stall_current:g} A, no-load speed {no_load_speed_rpm:g} rpm "
               f"at {voltage:g} V")
    return from_datasheet(name, gear_ratio=gear_ratio, stall_torque=stall_torque,
                          stall_current=stall_current, no_load_speed_rpm=no_load_speed_rpm,
                          voltage=voltage,
                          source=f"ROBOTIS e-Manual, {name} specifications, {url}: {figures}",
                          notes=f"{notes} The e-Manual publishes no winding resistance.".strip())


def _sts3215() -> Motor:
    """Feetech STS3215, 12 V version (ST-3215-C018), from Feetech's product page."""
    stall_kgf_cm, seconds_per_60deg = 30.0, 0.222
    rpm = (60.0 / 360.0) / seconds_per_60deg * 60.0  # 1/6 turn in 0.222 s → 45.05 rpm
    return from_datasheet(
        "STS3215-C018", gear_ratio=345.0, stall_torque=stall_kgf_cm * KGF_CM, stall_current=2.7,
        no_load_speed_rpm=rpm, voltage=12.0,
        source="Feetech ST-3215-C018 (STS3215, 12 V version) product page, "
               "https://www.feetechrc.com/525603.html: peak stall torque 30 kg·cm at 12 V, stall "
               "current 2.7 A at 12 V, no-load speed 0.222 s/60° at 12 V",
        notes=f"The 12 V version (30 kg·cm); the 7.4 V STS3215-C001 (19.5 kg·cm) is another servo "
              f"and not in the catalogue. 30 kg·cm read as kgf·cm = {stall_kgf_cm * KGF_CM:.3f} "
              f"N·m; 0.222 s/60° = {rpm:.2f} rpm. The product page gives no gear ratio: 345 : 1 "
              "is Feetech's figure for the C018 variant in its variant list (github.com/"
              "roboninecom/SO-ARM100-101-Parallel-Gripper/issues/5); only k_t G enters the "
              "powers, so it does not change them. Feetech publishes no winding resistance.")


def _towerpro(name: str, *, stall_kgf_cm: float, seconds_per_60deg: float, stall_current: float,
              voltage: float, source: str, notes: str) -> Motor:
    """A TowerPro hobby servo from its datasheet figures: stall torque in kg·cm (read as kgf·cm,
    :data:`KGF_CM`) and speed in s/60° at ``voltage``, stall current in A. No gear ratio is
    published: G = 1 (``k_t`` stated at the output; only ``k_t G`` enters the powers)."""
    rpm = (60.0 / 360.0) / seconds_per_60deg * 60.0
    return from_datasheet(
        name, gear_ratio=1.0, stall_torque=stall_kgf_cm * KGF_CM, stall_current=stall_current,
        no_load_speed_rpm=rpm, voltage=voltage, source=source,
        notes=(f"{stall_kgf_cm:g} kg·cm read as kgf·cm = {stall_kgf_cm * KGF_CM:.4f} N·m; "
               f"{seconds_per_60deg:g} s/60° = {rpm:.1f} rpm. No gear ratio published: G = 1 "
               f"(k_t at the output; powers depend on k_t G only). {notes} TowerPro publishes "
               "no winding resistance."))


def _mg996r() -> Motor:
    """TowerPro MG996R at 6 V (datasheet: 11 kgf·cm, 0.14 s/60°, stall current 2.5 A)."""
    return _towerpro(
        "MG996R", stall_kgf_cm=11.0, seconds_per_60deg=0.14, stall_current=2.5, voltage=6.0,
        source="TowerPro MG996R datasheet (towerpro.com.tw, 'MG996R High Torque Metal Gear Dual "
               "Ball Bearing Servo'): stall torque 9.4 kgf·cm at 4.8 V and 11 kgf·cm at 6 V, "
               "operating speed 0.17 s/60° at 4.8 V and 0.14 s/60° at 6 V, stall current 2.5 A "
               "at 6 V; 55 g. Cross-checked: 11 kg·cm (wellpcb.com/mg996r.html), stall current "
               "~2.5 A (zbotic.in/?p=596368)",
        notes="The 6 V figures. The MG996R is widely cloned and sellers quote 9.4–15 kg·cm; "
              "identify your own servo where it matters.")


def _sg90() -> Motor:
    """TowerPro SG90 micro servo at 4.8 V (datasheet: 1.8 kgf·cm, 0.1 s/60°; stall current
    0.65 A from retailers, the datasheet gives none)."""
    return _towerpro(
        "SG90", stall_kgf_cm=1.8, seconds_per_60deg=0.1, stall_current=0.65, voltage=4.8,
        source="TowerPro SG90 datasheet ('SG90 9 g Micro Servo'): stall torque 1.8 kgf·cm, "
               "operating speed 0.1 s/60°, operating voltage 4.8 V; 9 g. Stall current ~650 mA "
               "at 4.8 V from retailers' specification tables (musefsales.com SG90 product page; "
               "kpower.com/blog/3205.html), not from TowerPro",
        notes="The micro servo of palm-sized quadrupeds and hexapods. The stall current is not "
              "a TowerPro figure (retailers' ~650 mA at 4.8 V), so R and k_t are rougher than "
              "for the other entries.")


_DFROBOT_SER0044 = ("https://wiki.dfrobot.com/DSS-M15S_270°_15KG_DF_Metal_Servo_with_Analog_"
                    "Feedback_SKU__SER0044")


def _dss_m15s() -> Motor:
    """DFRobot DSS-M15S (270°, 15 kg metal-gear servo) at 6 V, from DFRobot's wiki page (SKU
    SER0044, the analog-feedback version of the same servo): 11.5 kg·cm "locking torque", 1.4 A
    stall current, 0.18 s/60° no-load, gear ratio 310 : 1."""
    stall_kgf_cm, seconds_per_60deg = 11.5, 0.18
    rpm = (60.0 / 360.0) / seconds_per_60deg * 60.0  # 1/6 turn in 0.18 s → 55.56 rpm
    eta_7v = 12.0 * KGF_CM * (math.pi / 3.0 / 0.16) / (7.0 * 1.76)
    return from_datasheet(
        "DSS-M15S", gear_ratio=310.0, stall_torque=stall_kgf_cm * KGF_CM, stall_current=1.4,
        no_load_speed_rpm=rpm, voltage=6.0,
        source=f"DFRobot wiki, DSS-M15S 270° 15KG DF Metal Servo with Analog Feedback (SKU "
               f"SER0044), {_DFROBOT_SER0044}: 6 V test environment: operating speed (no load) "
               "0.18 sec/60 degrees, locking torque 11.5 kg·cm, stall current 1.4 A; gear ratio "
               "310:1 (7 V: 0.16 sec/60 degrees, 12 kg·cm, 1.76 A)",
        notes=f"The 6 V figures; the 7 V ones give η = τ_s ω_0 / (V I_s) = {eta_7v:.3f} (the "
              f"DC model cannot match both voltages). {stall_kgf_cm:g} kg·cm read as kgf·cm = "
              f"{stall_kgf_cm * KGF_CM:.4f} N·m (the locking torque taken as the stall torque); "
              f"{seconds_per_60deg:g} s/60° = {rpm:.2f} rpm. DFRobot publishes no winding "
              "resistance.")



CATALOGUE: Mapping[str, Motor] = MappingProxyType({
    m.name: m for m in (
        _robotis("AX-12A", EMANUAL + "ax/ax-12a/", gear_ratio=254.0, stall_torque=1.5,
                 stall_current=1.5, no_load_speed_rpm=59.0),
        _robotis("AX-18A", EMANUAL + "ax/ax-18a/", gear_ratio=254.0, stall_torque=1.8,
                 stall_current=2.2, no_load_speed_rpm=97.0),
        _robotis("MX-28", EMANUAL + "mx/mx-28-2/", gear_ratio=193.0, stall_torque=2.5,
                 stall_current=1.4, no_load_speed_rpm=55.0),
        _robotis("XM540-W150", EMANUAL + "x/xm540-w150/", gear_ratio=152.3, stall_torque=7.3,
                 stall_current=4.4, no_load_speed_rpm=53.0),
        _robotis("XM540-W270", EMANUAL + "x/xm540-w270/", gear_ratio=272.5, stall_torque=10.6,
                 stall_current=4.4, no_load_speed_rpm=30.0),
        _robotis("XL430-W250", EMANUAL + "x/xl430-w250/", gear_ratio=258.5, stall_torque=1.5,
                 stall_current=1.4, no_load_speed_rpm=61.0,
                 notes="12 V is the top of its 6.5–12.0 V range (recommended 11.1 V: 1.4 N·m at "
                       "1.3 A, 57 rpm); the 12 V figures match the other ROBOTIS entries."),
        _robotis("XM430-W350", EMANUAL + "x/xm430-w350/", gear_ratio=353.5, stall_torque=4.1,
                 stall_current=2.3, no_load_speed_rpm=46.0),
        _robotis("MX-64", EMANUAL + "mx/mx-64/", gear_ratio=200.0, stall_torque=6.0,
                 stall_current=4.1, no_load_speed_rpm=63.0,
                 notes="MX-64T/R/AT/AR (same figures under protocol 1.0 and 2.0)."),
        _robotis("MX-106", EMANUAL + "mx/mx-106/", gear_ratio=225.0, stall_torque=8.4,
                 stall_current=5.2, no_load_speed_rpm=45.0,
                 notes="MX-106T/R (same figures under protocol 1.0 and 2.0)."),
        _sts3215(),
        _mg996r(),
        _sg90(),
        _dss_m15s(),
        odri_actuator(),
        odri_actuator_paper(),
        mini_cheetah("hip"),
        mini_cheetah("hip", "katz"),
        mini_cheetah("knee"),
        cheetah3("hip"),
        cheetah3("knee"),
        a1_energy_model(),
    )
})
"""Real actuators, keyed by model name: ROBOTIS, Feetech, TowerPro and DFRobot servos with datasheet
values and the ODRI brushless module of Solo-12 (:func:`odri_actuator`)."""

@dataclass(frozen=True)
class OutputHub:
    """What a torsion spring could wind on at a servo's output.

    Attributes:
        diameter: The hub's (horn boss, spline, shaft) outer diameter, m; None when no source
            states it as a number.
        source: Where the number comes from, or why there is none.
    """

    diameter: float | None
    source: str


_DRAWING_ONLY = ("not sourced: ROBOTIS publishes the output horn's dimensions only as drawing "
                 "images in the e-Manual (no number in its text) and the datasheet figures "
                 "give none; the arbor falls back to the link rule")

_TOWERPRO_HUB = ("not sourced: TowerPro's datasheets give no output hub or spline diameter as a "
                 "number; the arbor falls back to the link rule")

OUTPUT_HUBS: Mapping[str, OutputHub] = MappingProxyType({
    **{name: OutputHub(None, _DRAWING_ONLY) for name in (
        "AX-12A", "AX-18A", "MX-28", "XM540-W150", "XM540-W270", "XL430-W250", "XM430-W350",
        "MX-64", "MX-106")},
    "STS3215-C018": OutputHub(None, "not sourced: Feetech's product page gives no output hub or "
                                    "spline diameter; the arbor falls back to the link rule"),
    **{name: OutputHub(None, _TOWERPRO_HUB) for name in ("MG996R", "SG90")},
    "DSS-M15S": OutputHub(5.8e-3, f"DFRobot wiki SER0044 ({_DFROBOT_SER0044}): 'Gear bracket "
                                  "spline 25T/5.80', a 25-tooth spline of 5.80 mm, read as its "
                                  "outer diameter"),
    "ODRI-4004": OutputHub(None, "not sourced: the ODRI actuator module's documentation gives "
                                 "its output as CAD files, no diameter in text; the arbor falls "
                                 "back to the link rule"),
    **{name: OutputHub(None, "not sourced: the builders' code gives no output flange "
                             "dimension; the arbor falls back to the link rule")
       for name in ("ODRI-4004-RAL2020", "MiniCheetah-hip", "MiniCheetah-hip-Katz",
                    "MiniCheetah-knee", "Cheetah3-hip", "Cheetah3-knee")},
    "A1-Yang2021": OutputHub(None, "not sourced: Unitree publishes no output flange dimension "
                                   "of the A1's joint motor; the arbor falls back to the link "
                                   "rule"),
})
"""Catalogue name → its :class:`OutputHub` (every entry of :data:`CATALOGUE`)."""


def output_hub(name: str) -> OutputHub:
    """The output hub of catalogue servo ``name`` (case-insensitive, as :func:`motor`).

    Raises:
        UnknownNameError: not in the catalogue (lists the names).
    """
    return OUTPUT_HUBS[motor(name).name]


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


@typed
def motor_from_mapping(data: Mapping[str, Any], where: str = "[motor]") -> Motor:
    """Build a motor from a TOML table: a catalogue ``base`` with overrides, or every field.

    Example::

        [motor]
        base = "AX-18A"
        resistance = 3.1        # identified winding resistance, Ω
        regeneration = true

    Args:
        data: Keys are :class:`~hexaleg.robot.motor.Motor` fields, plus optional ``base`` (a
            catalogue name). Without a base every field is required except ``notes``.
        where: Where the table came from, for error messages.

    Returns:
        The motor (validated). Overrides of a base are recorded in its ``source`` and ``notes``.

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
        missing = [f.name for f in dataclasses.fields(Motor)
                   if f.default is dataclasses.MISSING and f.name not in data]
        if missing:
            raise ConfigError(f"{where}: missing keys {', '.join(missing)} "
                              f"(or give base = one of {', '.join(CATALOGUE)})")
        return from_mapping(Motor, data, where)
    base = motor(base_name)
    fields = {f.name: getattr(base, f.name) for f in dataclasses.fields(Motor)}
    if data:
        changed = ", ".join(sorted(data))
        if "source" not in data:
            fields["source"] = f"{base.source}; overridden in {where}: {changed}"
        if "notes" not in data and base.notes:
            fields["notes"] = (f"{base.notes} Overridden in {where}: {changed} (the values above "
                               f"are {base.name}'s).")
    return from_mapping(Motor, {**fields, **data}, where)


def catalogue_table(motors: Mapping[str, Motor] | None = None) -> str:
    """A plain-text table of motors with the constants the energy model uses.

    Args:
        motors: Motors by name; default :data:`CATALOGUE`.

    Returns:
        One header line, one line per motor (G, k_t G N·m/A, R Ω, η, c W/(N·m)², stall torque
        N·m, no-load speed rpm, regeneration), a units line, one source line per motor and one
        line of notes (what was derived or assumed) per motor that has notes.
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
    lines += [f"{name} notes: {m.notes}" for name, m in motors.items() if m.notes]
    return "\n".join(lines)
