"""The fold into the sphere and back, with the springs to buy and without: what they cost there.

The robot of the paper folds into a sphere; springs designed for walking stay on the joints while
it folds, and a spring that helps the gait can work against the fold (a one-sided spring held
wound up is engaged the whole time). For each way — stand → sphere
(:func:`hexaleg.motion.transform.transform_motion`) and sphere → stand, the same motion run
backwards in time (q(T − t), v → −v(T − t), a(T − t): the same path, so the same gravity and
inertia torques with the velocity-dependent terms reversed) — the motion is analysed
(:meth:`hexaleg.dynamics.prepare.Prepared.evaluate`, the design's actuator, contact and
Joule-optimal forces) with the springs and without: its electrical energy, the largest share of
its servos' torque limit it asks for, or the torque limit it cannot meet.

The **break-even distance** is the walking after which the springs pay for one fold, out and
back: the extra electrical energy of the fold with the springs over the electrical energy they
save per metre walked,

    d* = (E_fold,springs − E_fold,baseline) / ((E_cycle,baseline − E_cycle,springs) / stride),

0 when the springs make the fold cheaper too, None when they save nothing walking. A mission of
``L`` metres walked per fold saves

    s(L) = 1 − (L e_springs + E_fold,springs) / (L e_baseline + E_fold,baseline)

of its electrical energy (e the energy per metre walked): the walking saving for L → ∞, the fold's
for L → 0.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.checks import real
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import prepare
from hexaleg.errors import HexalegError
from hexaleg.motion.trajectory import Motion
from hexaleg.motion.transform import transform_motion
from hexaleg.quantities import quantity
from hexaleg.robot.actuator import Actuator
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet

WAYS = (("stand → sphere", "stand", "sphere"), ("sphere → stand", "sphere", "stand"))
"""The two ways of the fold: (label, start pose, end pose)."""


@dataclass(frozen=True)
class Mission:
    """The ``[mission]`` table: how the robot is used between folds.

    Attributes:
        metres_per_fold: Metres walked per fold into the sphere and back (> 0), or None: the
            design states the break-even distance and no mission saving.
    """

    metres_per_fold: float | None = None

    def __post_init__(self) -> None:
        if self.metres_per_fold is not None:
            object.__setattr__(self, "metres_per_fold", real(
                "[mission] metres_per_fold", self.metres_per_fold, low=0.0, low_open=True,
                allowed="metres walked per fold, > 0"))


def reversed_motion(motion: Motion) -> Motion:
    """``motion`` run backwards in time (module docstring): q(T − t), −v(T − t), a(T − t), the
    stance, feet and support reversed; not periodic."""
    return dataclasses.replace(
        motion, q=motion.q[::-1].copy(), v=-motion.v[::-1], a=motion.a[::-1].copy(),
        stance=motion.stance[::-1].copy(), feet=motion.feet[::-1].copy(),
        supported=motion.supported[::-1].copy(), periodic=False,
        info={**motion.info, "reversed": True})


@dataclass(frozen=True)
class FoldWay:
    """One way of the fold with the springs and without (module docstring), SI.

    Attributes:
        label: ``stand → sphere`` or ``sphere → stand``. duration: s.
        electrical: With the springs, J (None: the servos cannot do it). baseline: Without, J
            (None: they cannot).
        torque_share: Largest |τ_motor| over the servos' torque limit with the springs (None:
            not done). baseline_share: Without.
        error: Why it cannot be done with the springs ("" when it can).
        baseline_error: Why it cannot be done without them.
    """

    label: str
    duration: float
    electrical: float | None
    baseline: float | None
    torque_share: float | None
    baseline_share: float | None
    error: str = ""
    baseline_error: str = ""

    def table(self) -> dict[str, Any]:
        """As ``design.json`` holds it."""
        return {"label": self.label, "duration": quantity(self.duration, "s"),
                "electrical": _q(self.electrical, "J"), "baseline": _q(self.baseline, "J"),
                "torque_share": _q(self.torque_share, "1"),
                "baseline_torque_share": _q(self.baseline_share, "1"),
                "within_torque_limits": not self.error, "error": self.error or None,
                "baseline_error": self.baseline_error or None}


def _q(value: float | None, unit: str) -> dict[str, Any] | None:
    return None if value is None else quantity(value, unit)


@dataclass(frozen=True)
class Fold:
    """The fold both ways and what it costs the springs (module docstring).

    Attributes:
        ways: Stand → sphere and sphere → stand.
        walking: Electrical energy per metre walked with the springs and without, J/m.
        metres_per_fold: The mission's metres walked per fold (``[mission]``), or None.
    """

    ways: tuple[FoldWay, ...]
    walking: tuple[float, float]
    metres_per_fold: float | None = None

    def totals(self) -> tuple[float, float] | None:
        """Electrical energy of the fold out and back with the springs and without, J; None
        when one way cannot be done."""
        with_, without = [], []
        for w in self.ways:
            if w.electrical is None or w.baseline is None:
                return None
            with_.append(w.electrical)
            without.append(w.baseline)
        return float(sum(with_)), float(sum(without))

    @property
    def extra(self) -> float | None:
        """J the fold out and back costs more with the springs (negative: less); None when one
        way cannot be done."""
        t = self.totals()
        return None if t is None else t[0] - t[1]

    @property
    def break_even(self) -> float | None:
        """Metres walked after which the springs pay for a fold out and back (module
        docstring); 0 when they make the fold cheaper too; None when they save nothing walking
        or a way cannot be done."""
        extra = self.extra
        saved = self.walking[1] - self.walking[0]
        if extra is None or saved <= 0:
            return None
        return max(extra, 0.0) / saved

    def mission_saving(self, metres: float) -> float | None:
        """s(L) of the module docstring for ``metres`` walked per fold; None when a way cannot
        be done."""
        t = self.totals()
        if t is None:
            return None
        e_s, e_b = self.walking
        return 1.0 - (metres * e_s + t[0]) / (metres * e_b + t[1])

    def table(self) -> dict[str, Any]:
        """As ``design.json`` holds it (``fold``)."""
        be = self.break_even
        out: dict[str, Any] = {
            "ways": [w.table() for w in self.ways],
            "walking_per_metre": {"with_springs": quantity(self.walking[0], "J/m"),
                                  "baseline": quantity(self.walking[1], "J/m")},
            "extra": _q(self.extra, "J"),
            "break_even": _q(be, "m"),
            "break_even_note": ("the walking after which the springs pay for one fold out "
                                "and back" if be is None or be > 0 else
                                "the springs make the fold cheaper too: they pay from the "
                                "first metre"),
            "mission": None}
        if self.metres_per_fold is not None:
            out["mission"] = {"metres_per_fold": quantity(self.metres_per_fold, "m"),
                              "saving": _q(None if (s := self.mission_saving(
                                  self.metres_per_fold)) is None else 100 * s, "%")}
        return out

    def line(self) -> str:
        """One line for the terminal."""
        parts = []
        for w in self.ways:
            if w.electrical is None:
                parts.append(f"{w.label} not within the servos' torque with the springs "
                             f"({w.error})")
            elif w.baseline is None:
                parts.append(f"{w.label} {w.electrical:.3f} J with the springs (not within "
                             "the servos' torque without)")
            else:
                parts.append(f"{w.label} {w.electrical:.3f} J with the springs, "
                             f"{w.baseline:.3f} J without")
        be = self.break_even
        tail = ("" if self.extra is None else
                "; the springs make the fold cheaper too" if be == 0.0 else
                f"; the springs pay for a fold after {be:.2f} m of walking" if be is not None
                else "; the springs save nothing walking")
        if self.metres_per_fold is not None and (s := self.mission_saving(
                self.metres_per_fold)) is not None:
            tail += (f"; on a mission of {self.metres_per_fold:g} m a fold they save "
                     f"{100 * s:+.2f} %")
        return "the fold: " + ", ".join(parts) + tail


def _way(robot: Robot, label: str, motion: Motion, motor: Actuator,
         contact: ContactParams, springs: SpringSet) -> FoldWay:
    """One way analysed with ``springs`` and without."""
    out: dict[str, Any] = {}
    try:
        p = prepare(robot, motion, motor=motor, contact=contact)
    except HexalegError as e:
        why = f"{type(e).__name__}: {e}"
        return FoldWay(label, motion.period, None, None, None, None, why, why)
    limit = np.asarray(p.system.tau_max, dtype=float)  # the limits the force program holds
    for key, sp in (("with", springs), ("without", {})):
        try:
            a = p.evaluate(sp, "joule")
        except HexalegError as e:
            out[key] = (None, None, f"{type(e).__name__}: {e}")
            continue
        share = float(np.max(np.abs(a.tau_motor) / limit)) if np.all(limit > 0) else math.nan
        out[key] = (float(a.metrics["total"]["electrical"]), share, "")
    (energy, share_w, err), (energy_b, share_b, err_b) = out["with"], out["without"]
    return FoldWay(label, motion.period, energy, energy_b, share_w, share_b, err, err_b)


def fold(robot: Robot, motor: Actuator, contact: ContactParams, springs: SpringSet,
         walking: tuple[float, float], metres_per_fold: float | None = None) -> Fold | None:
    """The fold both ways with ``springs`` and without (module docstring); None for a robot
    without both a ``stand`` and a ``sphere`` pose.

    Args:
        robot: The robot. motor: Its actuators. contact: The contact settings.
        springs: The springs to buy (SI).
        walking: Electrical energy per metre walked with the springs and without, J/m.
        metres_per_fold: The mission's metres walked per fold, or None.
    """
    if not {"stand", "sphere"} <= set(robot.poses):
        return None
    out = transform_motion(robot)
    ways = (_way(robot, WAYS[0][0], out, motor, contact, springs),
            _way(robot, WAYS[1][0], reversed_motion(out), motor, contact, springs))
    return Fold(ways=ways, walking=walking, metres_per_fold=metres_per_fold)


__all__ = ["WAYS", "Fold", "FoldWay", "Mission", "fold", "reversed_motion"]
