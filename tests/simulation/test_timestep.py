"""The simulation's timestep divides the period, and a run's steps are bounded before anything is
allocated, the refusal naming what the user set."""

from __future__ import annotations

import pytest

from hexaleg.checks import MEMORY_BUDGET
from hexaleg.errors import InvalidParameterError
from hexaleg.simulation.stepping import MAX_STEPS
from hexaleg.simulation.timestep import STEP_MARGIN, check_steps, cycle_timestep, step_bytes


def test_the_timestep_divides_the_period():
    assert cycle_timestep(5e-4, 1.0) == pytest.approx(5e-4)
    dt = cycle_timestep(3e-4, 1.0)
    assert dt <= 3e-4 and round(1.0 / dt) * dt == pytest.approx(1.0)


def test_steps_are_checked_against_the_budget(robot):
    """--timestep 1e-8 and --cycles 10000 used to allocate gigabytes before any bound; the
    refusal names the timestep when the user gave it, else the cycles."""
    cost = step_bytes(robot)
    assert 1860 < cost / STEP_MARGIN < 2100  # 1860 B a step measured on this robot
    high = min(MEMORY_BUDGET // cost, MAX_STEPS)
    assert check_steps(robot, 4, 1.0, 5e-4, given=False) == 8000
    with pytest.raises(InvalidParameterError, match=rf"invalid timestep = 1e-08; allowed: at most "
                                                    rf"{high} steps .*a timestep >= "):
        check_steps(robot, 4, 1.0, 1e-8, given=True)
    with pytest.raises(InvalidParameterError, match=r"invalid cycles = 10000; .*at most \d+ "
                                                    r"cycles at this timestep"):
        check_steps(robot, 10_000, 1.0, 5e-4, given=False)

