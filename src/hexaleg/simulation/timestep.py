"""The simulation's timestep and the steps a run may take.

A run steps MuJoCo at one fixed timestep (:func:`automatic_timestep` unless the user gives one),
rounded down to divide the gait's period (:func:`cycle_timestep`), and its steps are bounded
before anything is allocated (:func:`check_steps`): by hexaleg's memory budget at what a step
costs (:func:`step_bytes`) and by :data:`~hexaleg.simulation.stepping.MAX_STEPS`.
"""

from __future__ import annotations

import math
from typing import Any

from hexaleg.checks import MEMORY_BUDGET
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.simulation import stepping
from hexaleg.simulation.controllers import Servo
from hexaleg.simulation.ground import Ground
from hexaleg.simulation.model import TIMESTEP, SimModel, build_model, timestep_limit

STEP_MARGIN = 2
"""Margin on the memory one simulation step costs (:func:`step_bytes`)."""


def step_bytes(robot: Robot) -> int:
    """Memory one simulation step of ``robot`` costs while it runs, B: the reference, the
    controls, MuJoCo's states and sensors and their copies, ``6 nj + 2 (nq + nv) + nj + 3 n_legs``
    floats (1936 B on the default robot, where 1860 B was measured with tracemalloc over a
    whole run), times :data:`STEP_MARGIN`."""
    floats = 7 * robot.nj + 2 * (robot.model.nq + robot.model.nv) + 3 * len(robot.legs)
    return STEP_MARGIN * 8 * floats


def check_steps(robot: Robot, cycles: int, period: float, timestep: float, *,
                given: bool) -> int:
    """The steps of a run, checked against the memory budget and
    :data:`~hexaleg.simulation.stepping.MAX_STEPS` before anything is allocated.

    Args:
        robot: The robot (the cost of a step, :func:`step_bytes`).
        cycles: Cycles simulated (``[simulate] cycles``).
        period: The gait's period, s.
        timestep: The simulation's timestep, s.
        given: The user set the timestep (the refusal names it; else it names the cycles).

    Raises:
        InvalidParameterError: naming the timestep (or the cycles) and the bound: the fewest
            steps it allows and the smallest timestep that fits.
    """
    cost = step_bytes(robot)
    high = min(MEMORY_BUDGET // cost, stepping.MAX_STEPS)
    per_cycle = period / timestep
    if cycles * per_cycle <= high:
        return cycles * round(per_cycle)
    smallest = cycles * period / high
    why = (f"at most {high} steps a run ({cost / 1024:.2f} kB a step of {robot.name} fill "
           f"hexaleg's memory budget of {MEMORY_BUDGET / 1024**3:g} GiB at "
           f"{MEMORY_BUDGET // cost}; {stepping.MAX_STEPS} bound the time)")
    name, value = ("timestep", timestep) if given else ("cycles", cycles)
    fix = (f"a timestep >= {smallest:.3g} s or fewer cycles" if name == "timestep" else
           f"at most {int(high // math.ceil(per_cycle))} cycles at this timestep")
    raise InvalidParameterError(
        name, value, f"{why}; {cycles} cycles of {period:g} s at {timestep:g} s are "
        f"{cycles * per_cycle:.3g} steps: {fix}")


def cycle_timestep(timestep: float, period: float) -> float:
    """The largest timestep ≤ ``timestep`` that divides the period, s."""
    return period / math.ceil(period / timestep - 1e-9)


def automatic_timestep(robot: Robot, motion: Motion, motor: Any, servo: Servo,
                       ground: Ground, probe: SimModel | None = None) -> float:
    """The default timestep: the least of :data:`~hexaleg.simulation.model.TIMESTEP`,
    half the gait's sample spacing and 80 % of the explicit-stability limit
    (:func:`hexaleg.simulation.model.timestep_limit`), s; ``probe`` a model of the robot with
    this motor, servo and ground already built (any springs and timestep: the limit depends on
    neither), else one is built."""
    probe = probe or build_model(robot, motion, motor, servo=servo, ground=ground, check=False)
    limit, _ = timestep_limit(probe, motion)
    return min(TIMESTEP, motion.dt / 2, 0.8 * limit)
