"""Shared fixtures: the built-in robot and its default tripod gait, loaded once per test session.

Tests must not mutate these objects (a :class:`hexaleg.Robot` carries Pinocchio ``data`` that
kinematics calls overwrite, which is harmless; its model and the motion's arrays are never
written). A test that needs another gait or robot builds its own.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest
from hypothesis import settings
from hypothesis.configuration import set_hypothesis_home_dir

import hexaleg
from hexaleg.design.codesign import OptimalSprings, optimal_springs
from hexaleg.design.evaluator import RunSpec
from hexaleg.dynamics.prepare import Prepared, prepare
from hexaleg.simulation.run import Settings, Simulation, simulate

set_hypothesis_home_dir(Path(tempfile.gettempdir()) / "hexaleg-hypothesis")
settings.register_profile("hexaleg", database=None)
settings.load_profile("hexaleg")
"""No example database and hypothesis's cache outside the checkout: the property tests' examples
are drawn afresh each run (their budgets are fixed), and nothing is written into the checkout
(hypothesis would make ``.hypothesis/`` in the directory pytest starts in, before any fixture
moves the tests elsewhere)."""


LONG_FIRST = ("test_examples.py", "test_notebooks.py")
"""Modules whose tests each run a whole study (a kept example, a notebook: up to ~100 s)."""


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The whole-study tests first, the rest in their order: pytest-xdist hands tests to its
    workers in collection order, and these come last alphabetically, so one worker ran a
    100-s example while the other had finished (longest-processing-time-first scheduling,
    Graham, "Bounds on multiprocessing timing anomalies", SIAM J. Appl. Math. 17, 1969)."""
    items.sort(key=lambda item: item.path.name not in LONG_FIRST)


@pytest.fixture(scope="session", autouse=True)
def _outside_the_checkout(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Path]:
    """Every test runs in a temporary working directory, so what a library writes into the
    current directory stays out of the checkout: MuJoCo's ``MUJOCO_LOG.TXT`` (written on a
    simulation warning, e.g. "Nan, Inf or huge value in QACC"), a command's default output
    folder (``hexaleg-report/`` …). Paths of the repository come from ``__file__``."""
    previous = Path.cwd()
    cwd = tmp_path_factory.mktemp("cwd")
    os.chdir(cwd)
    try:
        yield cwd
    finally:
        os.chdir(previous)


@pytest.fixture(scope="session")
def robot() -> hexaleg.Robot:
    """The built-in hexapod (``hexaleg.load_robot()``)."""
    return hexaleg.load_robot()


@pytest.fixture(scope="session")
def walk(robot: hexaleg.Robot) -> hexaleg.Motion:
    """The default tripod gait, 1000 samples per cycle."""
    return hexaleg.tripod_gait(robot)


@pytest.fixture(scope="session")
def walk200(robot: hexaleg.Robot) -> hexaleg.Motion:
    """The default tripod gait at 200 samples per cycle (where a reference solves every sample)."""
    return hexaleg.tripod_gait(robot, hexaleg.GaitParams(samples=200))


SPIDER = Path(__file__).resolve().parent / "data" / "spider.toml"
"""A robot made for the tests: a hexapod URDF without foot frames, SRDF or body mesh, facing +y,
described in five lines of TOML."""


@pytest.fixture(scope="session")
def spider() -> hexaleg.Robot:
    """The test hexapod of :data:`SPIDER`, loaded from its TOML (legs and feet found)."""
    from hexaleg.robot.registry import load

    return load(str(SPIDER))


def flipped_spider(where: Path, joints: tuple[str, ...]) -> hexaleg.Robot:
    """The test hexapod of :data:`SPIDER` with the named joints' axes reversed (a mirrored
    URDF's convention), written to and loaded from ``where``."""
    import xml.etree.ElementTree as ET

    from hexaleg.robot.registry import load

    tree = ET.parse(SPIDER.parent / "spider.urdf")
    for j in tree.getroot().iter("joint"):
        if j.get("name") in joints:
            axis = j.find("axis")
            assert axis is not None
            axis.set("xyz", " ".join(str(-float(v)) for v in axis.get("xyz", "").split()))
    tree.write(where / "spider.urdf")
    (where / "spider.toml").write_text(SPIDER.read_text())
    return load(str(where / "spider.toml"))


RIGHT_PITCH = ("d_j2", "d_j3", "e_j2", "e_j3", "f_j2", "f_j3")
"""The test hexapod's right legs' femur and tibia joints (reversed in a mirrored variant)."""


@pytest.fixture
def urdf_with_limit(tmp_path):
    """A copy of the built-in URDF with one joint's ``<limit>`` attribute changed, loaded with
    the built-in SRDF: ``urdf_with_limit("RF_tibia", "effort", "0")``."""
    import xml.etree.ElementTree as ET

    from hexaleg.robot.model import DEFAULT_SRDF, DEFAULT_URDF, load_robot

    def make(joint: str, key: str, value: str) -> hexaleg.Robot:
        tree = ET.parse(DEFAULT_URDF)
        element = next(j for j in tree.getroot().iter("joint") if j.get("name") == joint)
        limit = element.find("limit")
        assert limit is not None
        limit.set(key, value)
        path = tmp_path / f"{joint}_{key}.urdf"
        tree.write(path)
        return load_robot(path, DEFAULT_SRDF)

    return make


# The simulation's fixtures (tests/simulation and tests/studies/simulate): the built-in robot's
# default gait prepared with its own servo, its optimal linear femur springs, and one short
# simulation of each controller, computed once per session.

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
