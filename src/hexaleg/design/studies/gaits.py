"""The gait study: energy per metre and cost of transport of a gait, with and without the
recommended springs (notebook 05, ``analysis/gaits_hexaleg.py``, ``analysis/gaits_solo12.py``,
docs/gaits.md).

For one gait (:func:`hexaleg.motion.legged.gait`: a pattern, a speed, a slope) on one robot,
:func:`gait_energy` analyses the cycle without springs (the baseline) and with the springs of
:func:`hexaleg.design.search.optimal.optimal_springs` on one joint class — the global optimum of a
spring family's magnitudes for that gait, "the recommended springs" — and reports per cycle the
servos' electrical energy (:meth:`hexaleg.robot.motor.Motor.electrical_power`), the energy per
metre travelled ``E / d`` and the cost of transport ``E / (m g d)`` (eq. 23; Gabrielli & von
Kármán, "What price speed?", Mech. Eng. 72, 1950), d the distance along the ground. A gait that
cannot be made or analysed (a foot out of reach, no admissible forces, a margin the body shift
cannot keep) is a row with its error, not an exception, so a table over patterns, speeds and
slopes always completes; :func:`table_header` and :func:`table_line` print such a table.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from hexaleg.design.search.optimal import Groups, optimal_springs
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import prepare
from hexaleg.errors import HexalegError
from hexaleg.motion.legged import gait
from hexaleg.motion.params import GaitParams
from hexaleg.robot.actuator import Actuator
from hexaleg.robot.model import Robot

METRIC = "electrical"
"""The energy of the study: what the servos draw (no regeneration), J per cycle."""


@dataclass(frozen=True)
class GaitEnergy:
    """One gait of the study.

    Attributes:
        pattern: The gait's pattern (``GaitParams.pattern``; ``"groups"`` without one).
        speed: Speed along the ground, m/s.
        slope: Inclination along the walking direction, rad (positive uphill).
        distance: Distance per cycle along the ground, m.
        energy: Electrical energy per cycle without springs, J (None: see ``error``).
        per_metre: ``energy / distance``, J/m.
        cost_of_transport: ``energy / (m g distance)``, 1.
        energy_springs: With the recommended springs, J per cycle.
        per_metre_springs: With them, J/m.
        cost_of_transport_springs: With them, 1.
        saving: ``1 − energy_springs / energy``, 1.
        springs: The recommended springs' magnitudes, group → name → value (SI).
        error: Why the gait has no numbers (the error's message), or None.
    """

    pattern: str
    speed: float
    slope: float
    distance: float
    energy: float | None = None
    per_metre: float | None = None
    cost_of_transport: float | None = None
    energy_springs: float | None = None
    per_metre_springs: float | None = None
    cost_of_transport_springs: float | None = None
    saving: float | None = None
    springs: dict[str, dict[str, float]] | None = None
    error: str | None = None


def gait_energy(robot: Robot, params: GaitParams, springs: Groups, *,
                family: str = "preloaded", motor: Actuator | str | None = None,
                contact: ContactParams | None = None) -> GaitEnergy:
    """Energy per cycle, per metre and cost of transport of a gait, without springs and with
    the recommended springs on the joints ``springs`` (module docstring).

    Args:
        robot: The robot.
        params: The gait (pattern, speed or period, slope, samples, …).
        springs: Where the springs go, as
            :func:`hexaleg.design.search.optimal.optimal_springs` takes its groups: one shared
            design per group (``{"front": ["FL_KFE", "FR_KFE"], …}``, or joint classes, e.g.
            ``["femur"]``). Solo-12's front and hind knees bend opposite ways, so their torques
            have opposite signs: one group each.
        family: The spring family (:data:`hexaleg.design.families.FAMILIES`).
        motor: The servo of every joint (as :func:`hexaleg.dynamics.prepare.prepare`).
        contact: Contact settings (friction, torque limits); default ``ContactParams()``.

    Returns:
        The row; a gait that cannot be made or analysed has ``error`` set and no numbers.
    """
    row = GaitEnergy(pattern=params.pattern or "groups", speed=params.velocity,
                     slope=params.slope, distance=params.stride)
    try:
        motion = gait(robot, params)
        prepared = prepare(robot, motion, motor=motor, contact=contact)
        best = optimal_springs(prepared, springs, family)
    except HexalegError as err:
        return GaitEnergy(**{**row.__dict__, "error": f"{type(err).__name__}: {err}"})
    base, sprung = best.analysis.baseline, best.analysis.metrics
    energy, with_springs = base["total"][METRIC], sprung["total"][METRIC]
    return GaitEnergy(
        pattern=row.pattern, speed=row.speed, slope=row.slope, distance=row.distance,
        energy=energy, per_metre=energy / row.distance,
        cost_of_transport=base["cost_of_transport"][METRIC], energy_springs=with_springs,
        per_metre_springs=with_springs / row.distance,
        cost_of_transport_springs=sprung["cost_of_transport"][METRIC],
        saving=1.0 - with_springs / energy, springs=best.magnitudes)


def table_header(first: str = "pattern") -> str:
    """The column heads of :func:`table_line`; ``first`` heads the first column."""
    return (f"{first:7s} {'v [m/s]':>7s} {'slope':>6s} {'J/m':>7s} {'CoT':>6s} "
            f"{'J/m spr':>8s} {'CoT spr':>8s} {'saving':>7s}")


def table_line(row: GaitEnergy) -> str:
    """One row of the study as a line: pattern, speed m/s, slope °, J/m and cost of transport
    without and with the springs, the saving %; a row with an error shows the error's type."""
    head = f"{row.pattern:7s} {row.speed:7.3f} {math.degrees(row.slope):+5.0f}°"
    if row.error is not None:
        return f"{head}  {row.error.split(':')[0]}"
    assert row.saving is not None  # a row without an error has every number
    return (f"{head} {row.per_metre:7.2f} {row.cost_of_transport:6.2f} "
            f"{row.per_metre_springs:8.2f} {row.cost_of_transport_springs:8.2f} "
            f"{100 * row.saving:6.1f}%")
