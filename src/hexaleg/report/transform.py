"""The report's stand → sphere section: the energy of folding the hexapod into a sphere.

The motion is :func:`hexaleg.motion.transform.transform_motion`; its energies are
:func:`hexaleg.dynamics.energy.metrics` with the gait's springs and in the baseline (no springs),
and its joints' net work is checked against the rise of potential energy m g Δz_com (Pinocchio's
centre of mass).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg.dynamics.energy import metric_unit
from hexaleg.dynamics.prepare import prepare
from hexaleg.errors import HexalegError
from hexaleg.motion.transform import transform_motion
from hexaleg.quantities import comparison, quantity
from hexaleg.report.config import ReportConfig
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet


def transform_section(robot: Robot, cfg: ReportConfig, springs: SpringSet,
                      objective: str) -> dict[str, Any] | None:
    """The energy of folding from ``stand`` into ``sphere``, with the gait's springs and without.

    The motion is :func:`hexaleg.motion.transform.transform_motion` at its defaults (sit down on the
    feet, then fold with the body on the ground), analysed with the report's motor, contact
    settings and objective. Its joints' net work is the rise of the robot's potential energy
    m g Δz_com (at rest at both ends; the ground under the body does no work), reported
    alongside.

    Returns:
        The section's numbers; ``{"error": …}`` when the springs make it infeasible (e.g. a
        torque limit while folding); None for a robot without both poses.
    """
    if not {"stand", "sphere"} <= set(robot.poses):
        return None
    motion = transform_motion(robot)
    try:
        a = prepare(robot, motion, motor=cfg.motor, contact=cfg.contact).evaluate(springs,
                                                                                  objective)
    except HexalegError as e:
        return {"error": str(e)}
    data = robot.model.createData()
    z0, z1 = (pin.centerOfMass(robot.model, data, motion.q[k])[2] for k in (0, -1))
    g = float(np.linalg.norm(robot.model.gravity.linear))
    met, base, sav = a.metrics["total"], a.baseline["total"], a.savings["total"]
    info = motion.info
    return {
        "duration": quantity(motion.period, "s"), "sit_time": quantity(info["sit_time"], "s"),
        "stand_height": quantity(info["stand_height"], "m"),
        "rest_height": quantity(info["rest_height"], "m"),
        "potential_energy_rise": quantity(robot.mass * g * (z1 - z0), "J"),
        "net_work": {"with_springs": quantity(met["net_work"], "J"),
                     "baseline": quantity(base["net_work"], "J")},
        "totals": {k: comparison(met[k], base[k], sav[k], metric_unit(k)) for k in sav},
    }
