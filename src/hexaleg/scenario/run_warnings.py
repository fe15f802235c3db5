"""The warnings that apply to a run, said the same way by every command that uses the run.

A run — a robot, its gait (generated or logged) and its actuators — can carry caveats that make
its numbers less trustworthy. ``hexaleg gait``, ``report``, ``design`` and ``simulate`` call
:func:`run_warnings` on their run, print each line as ``warning: …``, show the lines on their page
and write them into their JSON as ``"warnings"`` (what the sized defaults chose also as
``"gait_defaults"``, :func:`gait_defaults`). In this order:

1. the gait parameters the robot's description leaves unset, sized to it by dynamic similarity
   (:mod:`hexaleg.motion.scaling`): what they chose, unless a config file set them;
2. every joint whose peak speed exceeds its URDF velocity limit, with the period that would
   bring it within (:func:`hexaleg.motion.sanity.speed_findings`); every joint without a URDF
   effort limit (:func:`hexaleg.dynamics.sanity.torque_findings`' ``effort_limit_missing``: its
   torques cannot be checked);
3. joints driven by a generic actuator built from the URDF's effort and velocity limits
   (:func:`hexaleg.robot.motor.generic_actuator`): the energies rest on assumed constants and
   on limits that may be placeholders, by the factors :func:`~hexaleg.robot.motor.
   generic_energy_range` states and more;
4. link inertias repaired at load (``inertias = "repair"``, :mod:`hexaleg.robot.inertials`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from hexaleg.dynamics.sanity import torque_findings
from hexaleg.motion.params import GaitParams
from hexaleg.motion.sanity import speed_findings
from hexaleg.motion.scaling import chosen_defaults
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.actuator import Actuator
from hexaleg.robot.description import RobotDescription
from hexaleg.robot.inertials import REPAIRED_MARK
from hexaleg.robot.meshes import MISSING_COLLISION
from hexaleg.robot.model import Robot
from hexaleg.robot.motor import GENERIC_MARK, generic_energy_range

GENERIC_NAMED = 8
"""Classes the generic-actuator warning names before it counts the rest (a humanoid's arms,
torso and head are a class each: 20 more on Talos)."""


def generic_warning(motor: Actuator) -> str | None:
    """One line when some joint's actuator is generic (module docstring, 3), else None."""
    generic = [kind for kind, m in motor.models.items() if m.notes.startswith(GENERIC_MARK)]
    if not generic:
        return None
    lo, hi = generic_energy_range()
    named = ", ".join(generic[:GENERIC_NAMED]) + (
        f" and {len(generic) - GENERIC_NAMED} more" if len(generic) > GENERIC_NAMED else "")
    return (f"generic actuator on {named}: its energies come from the URDF's effort "
            f"and velocity limits with assumed constants (×{lo:.2f}–×{hi:.2f} for the "
            "catalogue's range of gearbox efficiencies, further if the limits are "
            "placeholders); name a catalogue motor (hexaleg motors) or identified constants "
            "for energies to trust")


def gait_defaults(desc: RobotDescription | None, gait: GaitParams | None
                  ) -> dict[str, Any] | None:
    """What the run's sized gait defaults chose, for a command's JSON (``"gait_defaults"``:
    :meth:`hexaleg.motion.scaling.SizedDefaults.as_dict` with ``"kept"``, the sized keys no
    config file replaced), or None when nothing was sized or there is no generated gait."""
    sized = chosen_defaults(desc, gait) if desc is not None and gait is not None else None
    if sized is None or gait is None:
        return None
    return {**sized.as_dict(), "kept": list(sized.kept(gait))}


def run_warnings(robot: Robot, motion: Motion, motor: Actuator | None, *,
                 desc: RobotDescription | None = None,
                 gait: GaitParams | None = None) -> tuple[str, ...]:
    """The warnings of one run (module docstring).

    Args:
        robot: The robot as run (its loading notes).
        motion: The motion run (generated or logged): ``v`` (T, nv), ``t`` (T,).
        motor: The actuators, or None where the command uses none (``hexaleg gait``).
        desc: The robot's description, for what its gait's defaults chose; None leaves that
            line out (a logged motion has no generated gait).
        gait: The run's gait after any config file (which keys still hold the sized values).

    Returns:
        One line per warning, empty when there is none.
    """
    out: list[str] = []
    sized = chosen_defaults(desc, gait) if desc is not None and gait is not None else None
    if sized is not None and gait is not None:
        kept = sized.kept(gait)
        note = sized.note(overridden=[k for k in sized.keys if k not in kept])
        if note is not None:
            out.append(note)
    out += [f.message for f in speed_findings(robot, motion) if f.check == "joint_speed"]
    out += [f.message for f in torque_findings(robot, np.zeros((0, robot.nj)))
            if f.check == "effort_limit_missing"]
    generic = generic_warning(motor) if motor is not None else None
    if generic is not None:
        out.append(generic)
    out += [n for n in robot.notes if n.startswith(REPAIRED_MARK)]
    # a collision mesh not found was replaced: a foot found on that link, its contact and the
    # springs' fit limits are the replacement's, so every command says so, not only robot
    out += [f"{n}: a foot found on this link, and the springs' fit limits, are the "
            "replacement's; give the mesh's directory to find the robot's own"
            for n in robot.notes if MISSING_COLLISION in n]
    return tuple(out)
