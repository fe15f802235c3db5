"""What a run with generic actuators can say without the motor constants it does not have.

A joint whose actuator is generic (:func:`hexaleg.robot.motor.generic_actuator`: built from the
URDF's effort and velocity limits, every other constant assumed) gets an electrical energy that
rests on those assumptions — off by ×0.8–×1.6 for the gearbox efficiency alone, and by far more
when the limits are placeholders or a driver's current limit (issue #40: 3–10× on brushless
quadrupeds). :func:`without_constants` gives, for the generic joints of an analysis (the gait
without springs), what holds whatever the motor:

* the **positive mechanical work** ``∫ max(0, τ q̇) dt`` — the least any motor must convert
  (paper eq. 20);
* the **squared-torque integral** ``∫ τ² dt`` — the Joule loss is ``c`` times it for a motor of
  Joule coefficient ``c = R / (k_t G)²``, the one constant the user must supply
  (:mod:`hexaleg.robot.motor`);
* the **electrical energy with the catalogue's motors of that torque class** — each catalogue
  actuator whose stall torque is within :data:`TORQUE_CLASS` of the class's URDF effort limit,
  run on the same torques and speeds (:func:`hexaleg.dynamics.energy.metrics`): a range from
  real datasheets, or none when the catalogue has no actuator of that class;

* the **sourced band**: each catalogue actuator (every one named with its source) whose peak
  torque is within :data:`SCALE_CLASS` of the class's effort, its gear ratio scaled so that its
  peak torque matches each joint's own URDF effort limit E_j — the same motor behind another
  gearbox: ``G' = G E_j / τ_peak``, so ``k_t G`` grows by ``E_j / τ_peak`` and the Joule
  coefficient ``c = R/(k_t G)²`` becomes ``c' = c (τ_peak / E_j)²`` (= ``R I_peak² / E_j²``:
  the motor's Joule loss at its peak current, spread over the joint's torque range), the
  gearbox efficiency and regeneration kept, the no-load speed divided by the same factor. The
  band is the lowest and highest of those energies, with which actuators; it rests on the
  scaled actuators' constants and the assumption that such a gearbox exists, so it is a band,
  never a bound;

* the **scaling law's figures** (:mod:`hexaleg.robot.scaling_law`): the electrical energy with an
  actuator of each joint's effort from the Joule scaling law fitted on the catalogue, at the
  law and at both ends of its spread — constants assumed, so an estimate, never a bound. Where
  no catalogue actuator is within :data:`SCALE_CLASS` of the class's effort, the band is made
  of these three figures, and says so (``from_law``).

beside the figure the generic actuator states. Sources: the energy metrics of
:mod:`hexaleg.dynamics.energy`; the catalogue of :mod:`hexaleg.robot.catalogue`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.checks import positive
from hexaleg.dynamics import energy
from hexaleg.dynamics.prepare import Analysis
from hexaleg.quantities import quantity
from hexaleg.robot.actuator import joint_models
from hexaleg.robot.catalogue import CATALOGUE
from hexaleg.robot.motor import GENERIC_MARK, Motor
from hexaleg.robot.scaling_law import ENDS, JouleLaw, catalogue_law

TORQUE_CLASS = (0.5, 2.0)
"""A catalogue actuator is of a joint's torque class when its stall torque is within these
factors of the joint's URDF effort limit."""

SCALE_CLASS = (0.25, 4.0)
"""A catalogue actuator enters the sourced band when its peak (stall) torque is within these
factors of the joints' largest URDF effort: its gear ratio is then changed at most 4× either
way (an assumption; the sourced actuators' own ratios span 6 : 1 to 50 : 1, about 8×)."""


def scaled(motor: Motor, effort: float) -> Motor:
    """``motor`` behind a gearbox scaled so that its peak torque is ``effort`` N·m (module
    docstring): ``G' = G · effort / τ_peak``, so ``c' = c (τ_peak / effort)²``; η, R, k_t,
    regeneration and voltage kept; the no-load speed divided by ``effort / τ_peak``.

    Raises:
        InvalidParameterError: ``effort`` not a finite number > 0.
    """
    positive("effort", effort)
    ratio = effort / motor.stall_torque
    return dataclasses.replace(
        motor, name=f"{motor.name} scaled to {effort:.4g} N·m",
        gear_ratio=motor.gear_ratio * ratio, stall_torque=effort,
        no_load_speed=motor.no_load_speed / ratio,
        source=f"{motor.source}; gear ratio scaled by {ratio:.4g} (hexaleg.dynamics."
               "without_constants.scaled)")


@dataclass(frozen=True)
class WithoutConstants:
    """The motor-independent figures of a run's generic joints (module docstring), per cycle.

    Attributes:
        joints: The joints with a generic actuator.
        positive_work: Their positive mechanical work, J.
        torque_squared: Their ``∫ Σ τ² dt``, N²·m²·s.
        stated: Their electrical energy with the generic actuator's assumed constants, J.
        catalogue: Catalogue actuator of their torque class → their electrical energy with it,
            J (empty when the catalogue has none of that class).
        effort: The largest URDF effort limit of these joints, N·m (the torque class's centre).
        band: Catalogue actuator within :data:`SCALE_CLASS` → their electrical energy with it
            scaled to each joint's effort (:func:`scaled`), J (empty: none in that class).
        period: The cycle's period, s, for the band's mean power; None: not one periodic cycle.
        law: ``"scaling law (low|central|high)"`` → their electrical energy with the scaling
            law's actuator of each joint's effort (:meth:`hexaleg.robot.scaling_law.JouleLaw.
            motor`), J: assumed constants.
        from_law: The entries of ``band`` that came from the law (all of them when no catalogue
            actuator is within :data:`SCALE_CLASS`; else none).
        fit: The scaling law those figures used; None: no law figures.
    """

    joints: tuple[str, ...]
    positive_work: float
    torque_squared: float
    stated: float
    catalogue: dict[str, float]
    effort: float
    band: dict[str, float] = dataclasses.field(default_factory=dict)
    period: float | None = None
    law: dict[str, float] = dataclasses.field(default_factory=dict)
    from_law: tuple[str, ...] = ()
    fit: JouleLaw | None = None

    def band_line(self) -> str:
        """The sourced band in words, or that the catalogue has nothing to scale."""
        lo, hi = SCALE_CLASS
        if not self.band:
            return (f"no sourced actuator within {lo:g}–{hi:g} × {self.effort:.3g} N·m to scale")
        low = min(self.band, key=self.band.__getitem__)
        high = max(self.band, key=self.band.__getitem__)
        watts = ("" if self.period is None else
                 f" = {self.band[low] / self.period:.4g}–{self.band[high] / self.period:.4g} W")
        what = ("no catalogue actuator in class, so the band is the scaling law's (assumed "
                "constants)" if self.from_law else
                "each geared to every joint's effort limit: c = c_source (τ_peak/E_j)²")
        return (f"sourced band {self.band[low]:.4g}–{self.band[high]:.4g} J per cycle{watts} "
                f"(low {low}, high {high}, of {', '.join(self.band)}, {what}); a band on "
                f"{'assumed' if self.from_law else 'sourced'} constants, not a bound"
                + self.law_line())

    def law_line(self) -> str:
        """The scaling law's figures in words (empty without them), labelled assumed."""
        if not self.law:
            return ""
        lo, mid, hi = (self.law[f"scaling law ({end})"] for end in ENDS)
        watts = "" if self.period is None else (
            f" = {lo / self.period:.4g}–{hi / self.period:.4g} W")
        return (f"; the Joule scaling law (Wensing et al. 2017, fitted on the catalogue) gives "
                f"{lo:.4g}–{hi:.4g} J{watts}, {mid:.4g} J at the law: assumed constants, an "
                "estimate")

    def line(self) -> str:
        """The figures in one line, the motor choice asked for first."""
        lo, hi = TORQUE_CLASS
        values = sorted(self.catalogue.values())
        span = (f"{values[0]:.4g} J" if len(values) == 1 or values[0] == values[-1]
                else f"{values[0]:.4g}–{values[-1]:.4g} J") if values else ""
        cat = (f"electrical with the catalogue's actuators of their torque class ({lo:g}–{hi:g}"
               f" × {self.effort:.3g} N·m, their largest URDF effort) {span} "
               f"({', '.join(self.catalogue)})" if self.catalogue else
               f"the catalogue has no actuator of their torque class ({lo:g}–{hi:g} × "
               f"{self.effort:.3g} N·m, their largest URDF effort)")
        return (f"name the motor of {len(self.joints)} joints first: no motor is named for them, "
                f"so their electrical energy ({self.stated:.4g} J per cycle) rests on assumed "
                f"constants. Without constants, per cycle: positive mechanical work "
                f"{self.positive_work:.4g} J (the least any motor converts); Joule loss = c × "
                f"{self.torque_squared:.4g} N²·m²·s, c = R/(k_t G)² of the motor you choose; "
                f"{cat}")

    def as_dict(self) -> dict[str, Any]:
        """The figures for a command's JSON, ``{value, unit}`` each."""
        return {"joints": list(self.joints),
                "positive_work": quantity(self.positive_work, "J"),
                "torque_squared": quantity(self.torque_squared, "N²·m²·s"),
                "stated_electrical": quantity(self.stated, "J"),
                "catalogue_electrical": {k: quantity(v, "J") for k, v in self.catalogue.items()},
                "torque_class": {"effort": quantity(self.effort, "N·m"),
                                 "factors": list(TORQUE_CLASS)},
                "sourced_band": self.band_dict(), "band_line": self.band_line(),
                "line": self.line()}


    def band_dict(self) -> dict[str, Any] | None:
        """The sourced band for a JSON: low, high (J per cycle), which actuator gives each,
        every actuator's energy and how they were scaled; None when none was in class."""
        if not self.band:
            return None
        low = min(self.band, key=self.band.__getitem__)
        high = max(self.band, key=self.band.__getitem__)
        power = None if self.period is None else {
            "low": quantity(self.band[low] / self.period, "W"),
            "high": quantity(self.band[high] / self.period, "W")}
        return {"low": quantity(self.band[low], "J"), "high": quantity(self.band[high], "J"),
                "power": power,
                "low_actuator": low, "high_actuator": high,
                "electrical": {k: quantity(v, "J") for k, v in self.band.items()},
                "class": {"effort": quantity(self.effort, "N·m"),
                          "factors": list(SCALE_CLASS)},
                "how": "each catalogue actuator (its constants from the source in its entry) "
                       "with its gear ratio scaled so its peak torque is each joint's URDF "
                       "effort limit E_j: c = R/(k_t G)² becomes c (tau_peak/E_j)^2, eta and "
                       "regeneration kept (hexaleg.dynamics.without_constants.scaled)",
                "is_bound": False,
                "from_law": list(self.from_law),
                "law": self.law_dict(),
                "note": ("no catalogue actuator is of this class: the band is the scaling law's, "
                         "on assumed constants, not a bound" if self.from_law else
                         "a band on sourced actuators scaled by an assumed gearbox, not a "
                         "bound")}

    def law_dict(self) -> dict[str, Any] | None:
        """The scaling law's figures for a JSON (per cycle, and W over the period), the law
        and its fit; None without them."""
        if not self.law:
            return None
        energies = {end: self.law[f"scaling law ({end})"] for end in ENDS}
        return {"electrical": {end: quantity(e, "J") for end, e in energies.items()},
                "power": None if self.period is None else {
                    end: quantity(e / self.period, "W") for end, e in energies.items()},
                "fit": None if self.fit is None else self.fit.as_dict(),
                "assumed": True, "is_bound": False,
                "note": "assumed constants from a scaling law, an estimate: never a bound"}


def _generic_joints(analysis: Analysis) -> list[str]:
    names = analysis.robot.joint_names
    models = joint_models(analysis.motor, len(names))
    return [j for j, m in zip(names, models, strict=True) if m.notes.startswith(GENERIC_MARK)]


def without_constants(analysis: Analysis, *, catalogue: Mapping[str, Motor] = CATALOGUE,
                      law: JouleLaw | None = None) -> WithoutConstants | None:
    """The motor-independent figures of ``analysis``'s generic joints (module docstring); None
    when no joint's actuator is generic.

    Args:
        analysis: An analysis of the gait (its motor torques and speeds; the report passes the
            one without springs).
        catalogue: The sourced actuators to take the torque class's and the band's from (the
            catalogue; a part of it leaves the rest out, as a leave-one-out check does).
        law: The scaling law for the law's figures; None: the one fitted on the whole catalogue
            (:func:`hexaleg.robot.scaling_law.catalogue_law`).
    """
    fitted = catalogue_law() if law is None else law
    joints = _generic_joints(analysis)
    if not joints:
        return None
    robot, motion = analysis.robot, analysis.motion
    cols = [robot.column(j) for j in joints]
    per_joint = analysis.metrics["joint"]
    c = np.broadcast_to(analysis.motor.joule_coefficient, (robot.nj,))
    tau, qdot = analysis.tau_motor[:, cols], analysis.qdot[:, cols]
    dt = float(motion.t[1] - motion.t[0])
    effort = float(np.max(robot.model.effortLimit[[6 + k for k in cols]]))
    lo, hi = TORQUE_CLASS
    in_class = {name: float(energy.metrics(tau, qdot, dt, m, periodic=motion.periodic)[
        "total"]["electrical"]) for name, m in sorted(catalogue.items())
        if lo * effort <= m.stall_torque <= hi * effort}
    efforts = [float(robot.model.effortLimit[6 + k]) for k in cols]
    lo, hi = SCALE_CLASS
    band = {name: _joints_energy(tau, qdot, dt, motion.periodic,
                                 [scaled(m, e) for e in efforts])
            for name, m in sorted(catalogue.items())
            if lo * effort <= m.stall_torque <= hi * effort}
    speeds = [float(robot.model.velocityLimit[6 + k]) for k in cols]
    laws = {f"scaling law ({end})": _joints_energy(
        tau, qdot, dt, motion.periodic,
        [fitted.motor(e, v, end) for e, v in zip(efforts, speeds, strict=True)])
        for end in ENDS}
    from_law: tuple[str, ...] = ()
    if not band:
        band, from_law = dict(laws), tuple(laws)
    return WithoutConstants(
        joints=tuple(joints), positive_work=float(per_joint["positive_work"][cols].sum()),
        torque_squared=float((per_joint["joule"][cols] / c[cols]).sum()),
        stated=float(per_joint["electrical"][cols].sum()), catalogue=in_class, effort=effort,
        band=band, period=motion.period if motion.periodic else None, law=laws,
        from_law=from_law, fit=fitted)


def _joints_energy(tau: np.ndarray, qdot: np.ndarray, dt: float, periodic: bool,
                   motors: list[Motor]) -> float:
    """The electrical energy of (T, n) torques and speeds with ``motors[i]`` on column i, J."""
    return sum(float(energy.metrics(tau[:, [i]], qdot[:, [i]], dt, m, periodic=periodic)[
        "total"]["electrical"]) for i, m in enumerate(motors))


__all__ = ["SCALE_CLASS", "TORQUE_CLASS", "WithoutConstants", "scaled", "without_constants"]
