"""Fixtures of the simulation tests: the built-in robot's default gait prepared with its own
servo, its optimal linear femur springs, and one short simulation of each controller, computed
once per session."""

from __future__ import annotations

import pytest

import hexaleg
from hexaleg.design.codesign import OptimalSprings, optimal_springs
from hexaleg.design.evaluator import RunSpec
from hexaleg.dynamics.prepare import Prepared, prepare
from hexaleg.studies.simulate.run import Settings, Simulation, simulate

SHORT = Settings(cycles=3, evaluate=1, force_samples=40)
"""Three cycles, the last one evaluated: the runs are periodic after the first."""


@pytest.fixture(scope="session")
def prepared(robot: hexaleg.Robot, walk: hexaleg.Motion) -> Prepared:
    """The default gait with the robot's own servo (the AX-18A)."""
    return prepare(robot, walk, motor=RunSpec("hexaleg").actuator())


@pytest.fixture(scope="session")
def optimal(prepared: Prepared) -> OptimalSprings:
    """The globally optimal linear springs on the femurs (``hexaleg simulate``'s default)."""
    return optimal_springs(prepared, ["femur"], "linear")


@pytest.fixture(scope="session")
def feedforward(prepared: Prepared, optimal: OptimalSprings) -> Simulation:
    """The gait simulated with the feedforward servo, with and without the optimal springs."""
    return simulate(prepared.robot, prepared.motion, prepared.motor, optimal.springs, SHORT,
                    prepared=prepared)


@pytest.fixture(scope="session")
def position(prepared: Prepared, optimal: OptimalSprings) -> Simulation:
    """The same with the position-only servo."""
    import dataclasses

    return simulate(prepared.robot, prepared.motion, prepared.motor, optimal.springs,
                    dataclasses.replace(SHORT, controller="position"), prepared=prepared)
