"""The whole draw: what the robot takes from its battery while it walks, not only its motors.

hexaleg's energies are the joint actuators' (:mod:`hexaleg.dynamics.energy`). A robot also
powers its servos' electronics at rest and its computer, sensors and radios; for a small servo
robot these are most of the draw, so a saving on the motors is a much smaller saving on the
battery. The whole draw over one cycle of a periodic motion is

``P = E_motors / T + P_idle + P_electronics``

with E_motors the motors' electrical energy per cycle (``metrics["total"]["electrical"]``), T
the period, ``P_idle = Σ_j I_standby,j V_j`` over the joints' servos (datasheet standby current
at the datasheet voltage, :data:`hexaleg.robot.standby.STANDBY`, as the actuator states it:
:meth:`hexaleg.robot.actuator.Actuator.idle_power`; where a servo's own figure is
not published but its family's is, the family's, named as such, with the family's range giving
``P_idle``'s range and the saving's) and ``P_electronics`` the
robot description's ``electronics_power``. Neither extra depends on the springs, so the saving
on the whole draw is the motors' saving in watts over the whole baseline draw. A term no source
gives is left out and named: the whole draw is then a lower bound and its saving an upper one,
and the result says so (:attr:`WholeDraw.complete`) — unless the motors' draw itself rests on
assumed actuator constants (a generic actuator from URDF limits), when it is an estimate and
never called a bound (:attr:`WholeDraw.is_bound`). With a battery named (``battery_wh``)
it lasts ``3600 · Wh / P`` seconds of walking.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from hexaleg.dynamics.plausibility import uses_generic
from hexaleg.robot.actuator import Actuator

WH = 3600.0
"""One watt-hour in joules."""


@dataclass(frozen=True)
class WholeDraw:
    """The robot's mean electrical draw over one cycle (module docstring).

    Attributes:
        motors: The motors' mean electrical power with the springs, W.
        motors_baseline: The same without springs (the baseline), W.
        idle: The servos' standby draw Σ I V, W; None when some servo's standby current is not
            published (``idle_missing`` names them).
        idle_missing: The servo models with no published standby current (empty: ``idle`` is
            complete).
        idle_sources: Servo model → where its standby current comes from (or why none).
        electronics: The description's ``electronics_power``, W; None: not given.
        speed: Distance per cycle over the period, m/s (0 for a motion in place).
        battery: The named battery's energy, J; None: none named.
        idle_low: The standby draw at the low end of each servo's range, W (``idle`` where the
            servo's own figure is published); None with ``idle``.
        idle_high: The same at the high end, W.
        idle_family: The servo models whose standby figure is their family's, not their own.
        assumed: Whether the motors' draw rests on assumed actuator constants (a generic
            actuator from URDF limits): the draw is then an estimate, never called a bound,
            however many terms are known.
    """

    motors: float
    motors_baseline: float
    idle: float | None
    idle_missing: tuple[str, ...]
    idle_sources: dict[str, str]
    electronics: float | None
    speed: float
    battery: float | None = None
    idle_low: float | None = None
    idle_high: float | None = None
    idle_family: tuple[str, ...] = ()
    assumed: bool = False

    @property
    def complete(self) -> bool:
        """Whether every term is known (else the draw is a lower bound, its saving an upper
        bound)."""
        return self.idle is not None and self.electronics is not None

    @property
    def is_bound(self) -> bool:
        """Whether the draw is a lower bound and its saving an upper one: some term is left out
        and the motors' draw rests on no assumed constants."""
        return not self.complete and not self.assumed

    @property
    def extra(self) -> float:
        """The known draw besides the motors, W (idle and electronics, each when known)."""
        return (self.idle or 0.0) + (self.electronics or 0.0)

    @property
    def total(self) -> float:
        """The whole draw with the springs, W (the known terms)."""
        return self.motors + self.extra

    @property
    def total_baseline(self) -> float:
        """The whole draw without springs, W (the known terms)."""
        return self.motors_baseline + self.extra

    @property
    def saving(self) -> float:
        """The springs' saving on the whole draw, a fraction of the baseline's whole draw
        (:func:`hexaleg.dynamics.energy.saving`'s convention: positive = the springs save)."""
        if self.total_baseline == 0.0:
            return 0.0
        return (self.total_baseline - self.total) / self.total_baseline

    def saving_at(self, idle: float | None) -> float:
        """The saving on the whole draw with the standby draw set to ``idle`` W (the
        electronics as known): the motors' saving in watts over that baseline draw."""
        base = self.motors_baseline + (idle or 0.0) + (self.electronics or 0.0)
        return 0.0 if base == 0.0 else (self.motors_baseline - self.motors) / base

    def saving_range(self) -> tuple[float, float] | None:
        """The saving on the whole draw over the standby draw's range, (low, high) as
        fractions (more idle draw, a smaller saving); None without a standby draw."""
        if self.idle is None or self.idle_low is None or self.idle_high is None:
            return None
        a, b = self.saving_at(self.idle_low), self.saving_at(self.idle_high)
        return (min(a, b), max(a, b))

    def per_metre(self, baseline: bool = False) -> float | None:
        """Energy per metre travelled, J/m; None for a motion in place."""
        if self.speed <= 0.0:
            return None
        return (self.total_baseline if baseline else self.total) / self.speed

    def hours(self, baseline: bool = False) -> float | None:
        """Hours of walking on the named battery; None with no battery or no draw."""
        power = self.total_baseline if baseline else self.total
        if self.battery is None or power <= 0.0:
            return None
        return self.battery / power / 3600.0

    def missing(self) -> list[str]:
        """What the whole draw leaves out, in words (empty when complete)."""
        out = []
        if self.idle is None:
            out.append("the standby draw of " + ", ".join(self.idle_missing)
                       + " (no published standby current)")
        if self.electronics is None:
            out.append("the electronics (the robot description sets no electronics_power)")
        return out

    def line(self) -> str:
        """One line for the commands and pages: the whole draw and the saving on it."""
        bound = "at least " if self.is_bound else ""
        text = (f"whole draw {bound}{self.total:.3g} W with the springs, {bound}"
                f"{self.total_baseline:.3g} W without (motors {self.motors:.3g} W / "
                f"{self.motors_baseline:.3g} W")
        if self.idle is not None:
            text += f", servos at rest {self.idle:.3g} W"
            if self.idle_family:
                text += (f" ({', '.join(self.idle_family)}: its family's standby current, "
                         f"range {self.idle_low:.3g}–{self.idle_high:.4g} W)")
        if self.electronics is not None:
            text += f", electronics {self.electronics:.3g} W"
        text += (f"): saving on the whole draw {'at most ' if self.is_bound else ''}"
                 f"{100 * self.saving:+.2f} %")
        if (r := self.saving_range()) is not None and r[0] != r[1]:
            text += f" ({100 * r[0]:+.2f} to {100 * r[1]:+.2f} % over the standby range)"
        if (h := self.hours()) is not None:
            text += f"; {h:.3g} h on the battery ({self.hours(True):.3g} h without springs)"
        if self.assumed:
            text += ("; an estimate, not a bound: the motors' draw rests on assumed actuator "
                     "constants")
        if not self.complete:
            text += "; not counted: " + "; ".join(self.missing())
        return text

    def _bound(self) -> str | None:
        """What the draw is, in words, when it is not complete or rests on assumptions."""
        if self.complete and not self.assumed:
            return None
        left = "; ".join(self.missing())
        if self.assumed:
            return ("an estimate, not a bound: the motors' draw rests on assumed actuator "
                    "constants (a generic actuator from URDF limits)"
                    + (f"; not counted: {left}" if left else ""))
        return "the draw is a lower bound and its saving an upper bound: " + left

    def as_dict(self) -> dict[str, Any]:
        """JSON form, numbers as ``{value, unit}`` (None where not known)."""
        def one(value: float | None, unit: str) -> dict[str, Any] | None:
            return None if value is None else {"value": value, "unit": unit}

        return {
            "motors": one(self.motors, "W"), "motors_baseline": one(self.motors_baseline, "W"),
            "idle_power": one(self.idle, "W"), "idle_missing": list(self.idle_missing),
            "idle_range": None if self.idle is None else {
                "low": one(self.idle_low, "W"), "high": one(self.idle_high, "W")},
            "idle_family": list(self.idle_family),
            "idle_sources": dict(self.idle_sources),
            "electronics_power": one(self.electronics, "W"),
            "total": one(self.total, "W"), "total_baseline": one(self.total_baseline, "W"),
            "saving": one(self.saving, "1"),
            "saving_range": None if (r := self.saving_range()) is None else {
                "low": one(r[0], "1"), "high": one(r[1], "1"),
                "over": "the servos' standby draw from idle_range's low to its high end"},
            "complete": self.complete,
            "is_bound": self.is_bound, "assumed": self.assumed,
            "bound": self._bound(),
            "energy_per_metre": one(self.per_metre(), "J/m"),
            "energy_per_metre_baseline": one(self.per_metre(True), "J/m"),
            "battery": one(None if self.battery is None else self.battery / WH, "Wh"),
            "hours": one(self.hours(), "h"), "hours_baseline": one(self.hours(True), "h"),
            "source": "hexaleg.dynamics.draw: motors' electrical energy per cycle over the "
                      "period, plus standby currents × the servo's datasheet voltage (each "
                      "servo's source in idle_sources) and the described electronics power",
        }


def whole_draw(energy: float, energy_baseline: float, period: float, distance: float,
               actuator: Actuator, n_joints: int, *, electronics: float | None = None,
               battery_wh: float | None = None) -> WholeDraw:
    """The whole draw of one cycle (module docstring).

    Args:
        energy: The motors' electrical energy per cycle with the springs, J
            (``metrics["total"]["electrical"]`` of :func:`hexaleg.dynamics.energy.metrics`).
        energy_baseline: The same without springs, J.
        period: The cycle's duration, s (> 0).
        distance: Distance travelled per cycle, m.
        actuator: The joints' servos.
        n_joints: The number of joints.
        electronics: The robot's electronics power, W, or None (not known).
        battery_wh: The battery's energy, Wh, or None.
    """
    idle = actuator.idle_power(n_joints)
    return WholeDraw(
        motors=float(energy) / period, motors_baseline=float(energy_baseline) / period,
        idle=idle.power, idle_missing=idle.missing, idle_sources=idle.sources,
        electronics=electronics, speed=max(float(distance), 0.0) / period,
        battery=None if battery_wh is None else battery_wh * WH, idle_low=idle.low,
        idle_high=idle.high, idle_family=idle.family, assumed=uses_generic(actuator))
