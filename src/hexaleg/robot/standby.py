"""What an actuator draws at rest, powered and holding no load (its electronics): the standby
table of the catalogue's servos and the idle draw of a robot's joints.

:data:`STANDBY` gives, per catalogue servo (:data:`hexaleg.robot.catalogue.CATALOGUE`), its
standby current where the maker publishes it, with the page, or — for the AX-18A, whose page
lists none — its family's figure (the AX-12A's 50 mA) labelled as the family's, with the family's
17–60 mA range. :func:`standby_draw` turns the servos of n joints into their idle draw
``P_idle = Σ_j I_standby,j V_j`` (each servo's standby current at its datasheet voltage) with the
range the sources allow; it is what :meth:`hexaleg.robot.actuator.Actuator.idle_power` of a
:class:`~hexaleg.robot.motor.Motor` returns, and :mod:`hexaleg.dynamics.draw` adds it to the
robot's whole draw.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from types import MappingProxyType

from hexaleg.errors import InvalidParameterError

EMANUAL = "https://emanual.robotis.com/docs/en/dxl/"
"""The ROBOTIS e-Manual's DYNAMIXEL pages (English), the source of the catalogue's ROBOTIS
servos and of their standby currents."""


@dataclass(frozen=True)
class Standby:
    """What a servo draws at rest, powered, holding no load (its electronics).

    Attributes:
        current: The standby current at the entry's voltage
            (:attr:`hexaleg.robot.motor.Motor.voltage`), A; None when no source states it.
        source: Where the number comes from, or why there is none.
        low: The lowest current the source's range allows, A (``current`` when the servo's
            own figure is published).
        high: The highest, A.
        own: Whether ``current`` is this servo's own published figure (False: its family's,
            an assumption the source says).
    """

    current: float | None
    source: str
    low: float | None = None
    high: float | None = None
    own: bool = True

    def __post_init__(self) -> None:
        if self.current is None:
            return
        low = self.current if self.low is None else self.low
        high = self.current if self.high is None else self.high
        if not 0.0 < low <= self.current <= high:
            raise InvalidParameterError(
                "standby current (A) and its range", (low, self.current, high),
                "0 < low <= current <= high")
        object.__setattr__(self, "low", low)
        object.__setattr__(self, "high", high)


_KR_EMANUAL = "https://emanual.robotis.com/docs/kr/dxl/"
_NO_STANDBY = ("not published: the ROBOTIS e-Manual's specification table of this servo lists "
               "no standby current")
_AX12A_STANDBY = ("ROBOTIS' AX-12A product specification as copied in MultipedRobotics/pyservos "
                  "docs/ax12/readme.md: 'Standby Current | 50mA' (and 'Max. Current | 900mA'); "
                  "the current e-Manual page (" + EMANUAL + "ax/ax-12a/) lists no standby row. "
                  "No supply voltage is given with it: taken at the entry's 12 V, the voltage "
                  "of the e-Manual's stall figures")
_DXL_FAMILY = ("standby currents of the DYNAMIXEL family on the ROBOTIS e-Manual: RX-28 "
               "'Standby Current | 50mA', RX-24F '50mA', MX-12W '60 [mA]', XH430-W350 "
               "'40 [mA]', XC330-M181 '17 [mA]' (reference: shared/reference/motor-sources.md, "
               "item 3)")

STANDBY: Mapping[str, Standby] = MappingProxyType({
    **{name: Standby(None, _NO_STANDBY) for name in (
        "MX-28", "XL430-W250", "XM430-W350", "MX-64", "MX-106")},
    "AX-12A": Standby(0.050, _AX12A_STANDBY),
    "AX-18A": Standby(
        0.050, "the AX family's, not the AX-18A's own: ROBOTIS publishes no standby current "
               "for the AX-18A (its e-Manual table, " + EMANUAL + "ax/ax-18a/, has no such "
               "row), so its sibling's figure is used, same AX electronics: " + _AX12A_STANDBY
               + "; range 17–60 mA from the " + _DXL_FAMILY + ". At 12 V, the voltage of the "
               "AX-18A's e-Manual figures ('Stall Torque | 1.8 [N.m] (at 12 [V], 2.2 [A])', "
               "the top of its 'Input Voltage | 9.0 ~ 12.0 [V]')",
        low=0.017, high=0.060, own=False),
    **{name: Standby(0.040, f"ROBOTIS e-Manual (Korean edition), {name} specifications, "
                            f"{_KR_EMANUAL}x/{name.lower()}/: '대기 전류 | 40 [mA]' (standby "
                            "current; the English edition's table stops before it)")
       for name in ("XM540-W150", "XM540-W270")},
    "STS3215-C018": Standby(None, "not published on Feetech's product page"),
    **{name: Standby(None, "not published in TowerPro's datasheet") for name in ("MG996R",
                                                                                 "SG90")},
    "DSS-M15S": Standby(None, "not published on DFRobot's wiki page"),
    "ODRI-4004": Standby(None, "not published: the ODRI actuator module's documentation gives "
                               "no standby draw of its motor driver board"),
    **{name: Standby(None, "not published: the builders' code and papers give no standby "
                           "draw of the motor driver")
       for name in ("ODRI-4004-RAL2020", "MiniCheetah-hip", "MiniCheetah-hip-Katz",
                    "MiniCheetah-knee", "Cheetah3-hip", "Cheetah3-knee")},
    "A1-Yang2021": Standby(None, "not published: the A1 energy model counts the joints' power "
                                 "only, and Unitree gives no standby draw"),
})
"""Catalogue name → its :class:`Standby` draw (every entry of :data:`CATALOGUE`)."""


def standby(name: str) -> Standby:
    """The standby draw of catalogue servo ``name``; a name not in the catalogue (a generic
    actuator from URDF limits) has none.

    Args:
        name: A motor name (:attr:`hexaleg.robot.motor.Motor.name`).
    """
    entry = STANDBY.get(name)
    if entry is None:
        return Standby(None, f"{name} is not a catalogue servo: no datasheet to read a standby "
                             "current from")
    return entry


@dataclass(frozen=True)
class Idle:
    """The standby draw of a robot's joints (:func:`standby_draw`).

    Attributes:
        power: ``Σ_j I_standby,j V_j``, W; None when some servo has no standby figure.
        low: The same with each servo's lowest current of its source's range, W.
        high: With each servo's highest, W.
        missing: The servo models with no standby figure.
        family: The servo models whose figure is their family's, not their own.
        sources: Servo model → where its standby current comes from (or why none).
    """

    power: float | None
    low: float | None
    high: float | None
    missing: tuple[str, ...]
    family: tuple[str, ...]
    sources: dict[str, str]


def standby_draw(servos: Sequence[tuple[str, float]]) -> Idle:
    """The idle draw ``Σ_j I_standby,j V_j`` of one servo per joint, W, with its range: each
    servo's standby current (:func:`standby`, by its name) at its datasheet voltage.

    Args:
        servos: ``(name, voltage V)`` of each joint's servo, in column order.
    """
    entries = {name: standby(name) for name, _ in servos}
    missing = tuple(sorted(name for name, e in entries.items() if e.current is None))
    family = tuple(sorted(name for name, e in entries.items()
                          if e.current is not None and not e.own))
    sources = {name: e.source for name, e in entries.items()}
    if missing:
        return Idle(None, None, None, missing, family, sources)

    def total(key: str) -> float:
        return float(sum(getattr(entries[name], key) * volts for name, volts in servos))

    return Idle(total("current"), total("low"), total("high"), (), family, sources)


def combined(idles: Iterable[Idle]) -> Idle:
    """The idle draw of joints whose draws are ``idles`` (each joint's, in column order): the
    sums in that order, so one servo's joints summed joint by joint give :func:`standby_draw`'s
    number to the bit; None when any is None."""
    parts = list(idles)
    missing = tuple(sorted({name for i in parts for name in i.missing}))
    family = tuple(sorted({name for i in parts for name in i.family}))
    sources: dict[str, str] = {}
    for i in parts:
        sources.update({k: v for k, v in i.sources.items() if k not in sources})

    def total(key: str) -> float | None:
        values = [getattr(i, key) for i in parts]
        return None if missing or any(v is None for v in values) else float(sum(values))

    return Idle(total("power"), total("low"), total("high"), missing, family, sources)


__all__ = ["EMANUAL", "STANDBY", "Idle", "Standby", "combined", "standby", "standby_draw"]
