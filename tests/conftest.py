"""Shared fixtures: the built-in robot and its default tripod gait, loaded once per test session.

Tests must not mutate these objects (a :class:`hexaleg.Robot` carries Pinocchio ``data`` that
kinematics calls overwrite, which is harmless; its model and the motion's arrays are never
written). A test that needs another gait or robot builds its own.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pytest
from hypothesis import settings
from hypothesis.configuration import set_hypothesis_home_dir

import hexaleg
from hexaleg.design.search.optimal import OptimalSprings, optimal_springs
from hexaleg.dynamics.prepare import Prepared, analyze, prepare
from hexaleg.paper.forward import ForwardStudy, forward_study
from hexaleg.paper.joint import PaperJoint
from hexaleg.paper.reproduce import reproduce
from hexaleg.simulation.run import Settings, Simulation, simulate

if TYPE_CHECKING:
    from hexaleg.commands.design.write import WrittenDesign
    from hexaleg.report.build import Report
    from hexaleg.robot.springs import SpringSet

set_hypothesis_home_dir(Path(tempfile.gettempdir()) / "hexaleg-hypothesis")
settings.register_profile("hexaleg", database=None)
settings.load_profile("hexaleg")
"""No example database and hypothesis's cache outside the checkout: the property tests' examples
are drawn afresh each run (their budgets are fixed), and nothing is written into the checkout
(hypothesis would make ``.hypothesis/`` in the directory pytest starts in, before any fixture
moves the tests elsewhere)."""


LONG_FIRST = ("test_examples.py", "test_notebooks.py")
"""Modules whose tests each run a whole study (a kept example, a notebook: up to ~100 s)."""

SHARING = ("tests/design/search/test_tolerance.py", "tests/test_docs_motion.py",
           "tests/test_faults.py", "tests/commands/design/test_logged_walks.py")
"""Modules whose slow tests share a module fixture (the tolerance module's default design: ~30 s;
the motion page's commands: ~20 s; the reports and designs the fault tests interrupt; a
simulated walk log): in the slow studies their tests go to one worker together, after the
whole studies and before the rest (each a minute or so of work)."""


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config: pytest.Config, log: Any) -> Any:
    """The slow studies (``pytest -m slow``: ~130 tests of 1–35 s) are handed to the xdist
    workers a test at a time, in the order :func:`pytest_collection_modifyitems` gives them, a
    worker holding at most three (pytest-xdist's scope scheduler, each test its own scope but
    those of a :data:`SHARING` module one). The default load scheduler sends each worker a
    quarter of its share at once and more only when it has run out: the worker that started
    a 200-s example (the co-design's, now run by hand) also held the next 14 whole studies,
    which the other worker could not take; and it splits a module's tests between the
    workers, each then building its module fixture. The README's suite (3000 short tests)
    keeps the default, whose chunks of one module share its fixtures."""
    if config.option.markexpr != "slow":
        return None  # the default (load) scheduler
    from xdist.scheduler import LoadScopeScheduling

    # in collection order: the scope scheduler otherwise puts the scopes of most tests first
    # (the fault module's twelve short tests ran before the 200-s example)
    config.option.loadscopereorder = False

    class OneAtATime(LoadScopeScheduling):
        def _split_scope(self, nodeid: str) -> str:
            module = nodeid.split("::", 1)[0]
            return module if module in SHARING else nodeid

    return OneAtATime(config, log)


def pytest_collection_modifyitems(items: list[pytest.Item]) -> None:
    """The whole-study tests first, then the modules that share a fixture (:data:`SHARING`),
    the rest in their order:
    pytest-xdist hands tests to its workers in collection order, and these come last
    alphabetically, so one worker ran a 100-s example while the other had finished
    (longest-processing-time-first scheduling, Graham, "Bounds on multiprocessing timing
    anomalies", SIAM J. Appl. Math. 17, 1969)."""
    items.sort(key=lambda item: (item.path.name not in LONG_FIRST,
                                 item.nodeid.split("::", 1)[0] not in SHARING))


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
    """The built-in hexapod (``hexaleg.load()``)."""
    return hexaleg.load()


@pytest.fixture(scope="session")
def walk(robot: hexaleg.Robot) -> hexaleg.Motion:
    """The default tripod gait, 1000 samples per cycle."""
    return hexaleg.gait(robot)


@pytest.fixture(scope="session")
def walk200(robot: hexaleg.Robot) -> hexaleg.Motion:
    """The default tripod gait at 200 samples per cycle (where a reference solves every sample)."""
    return hexaleg.gait(robot, hexaleg.GaitParams(samples=200))


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


# The simulation's fixtures (tests/simulation and tests/commands/simulate): the built-in robot's
# default gait prepared with its own servo, its optimal linear femur springs, and one short
# simulation of each controller, computed once per session.

SHORT = Settings(cycles=3, evaluate=1, force_samples=40)
"""Three cycles, the last one evaluated: the runs are periodic after the first."""


@pytest.fixture(scope="session")
def prepared(robot: hexaleg.Robot, walk: hexaleg.Motion) -> Prepared:
    """The default gait with the robot's own servo (the AX-18A)."""
    return prepare(robot, walk, motor=hexaleg.Scenario.load("hexaleg").actuator)


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


# The paper's joint (tests/paper, tests/commands/paper): one reproduction and one forward study
# on a coarse grid, made once.

@pytest.fixture(scope="session")
def paper_result() -> dict[str, Any]:
    """:func:`reproduce` of the default joint at 256 samples per period (``paper.json``)."""
    return reproduce(PaperJoint(), n=256)


FORWARD_GRID = (600.0, 800.0, 1000.0, 1300.0, 1400.0, 1500.0, 1600.0)
"""A coarse grid (eq. 19 units) that still brackets the forward optima of mean |M| (1350, 829
with friction) and ε (1473); ε with friction (about 300) lies below it, at the grid's end."""
FORWARD_SAMPLES = 512


@pytest.fixture(scope="session")
def forward(request: pytest.FixtureRequest) -> ForwardStudy:
    """:func:`forward_study` of the default joint on :data:`FORWARD_GRID` (about 3 s of CPU,
    :func:`once_per_run`: tests of 23 files use it)."""
    return once_per_run(request, "forward",
                        lambda: forward_study(PaperJoint(), FORWARD_GRID, FORWARD_SAMPLES))


# One small design (tests/design/chain, tests/commands/design), computed once per session.

DESIGN_SMALL = {
    "gait": {"samples": 120},
    "design": {"samples": 120, "families": ["linear", "one_sided"],
               "map_period": [0.7, 1.0, 1.4], "map_stride": [0.75, 1.0],
               "map_payload": [0.0, 0.4], "map_mu": [0.3, 0.6],
               "map_slope": [0.0, 0.2617993877991494],  # level and 15° up × the robot's patterns
               "robust_period": [0.8, 1.25], "robust_stride": [1.0, 1.0],
               "robust_payload": [0.0, 0.2], "robust_mu": [0.6, 0.6],
               "pareto_fractions": [0.5]},
}
"""A design at 120 samples per cycle, two families, 3 × 2, 2 × 2 and 2 × 3 (slope × the hexapod's
three patterns) maps, a box of 4 corners."""


@pytest.fixture(scope="session")
def design_written(request: pytest.FixtureRequest,
                   tmp_path_factory: pytest.TempPathFactory) -> tuple[WrittenDesign, Path]:
    """The small design, written once for the run (:func:`once_per_run`: ~9 s of CPU, which
    both workers of the README's suite spent, its tests being in 14 files), and its directory
    (the tests read it, none writes into it)."""
    from hexaleg.commands.design.write import write_design

    def make() -> tuple[WrittenDesign, Path]:
        out = tmp_path_factory.mktemp("design")
        return write_design(out, hexaleg.Scenario.from_tables("hexaleg", DESIGN_SMALL),
                            progress=None), out

    return once_per_run(request, "design_written", make)


# One co-design of the default robot at 0.06 m/s (tests/design/codesign, tests/commands/codesign):
# ~9 s on a quiet machine (50 samples a cycle in the search, 100 in the rows, 30 evaluations a
# search, 2 restarts, the search's answer alone), and the same result with the full spring rules
# on its chosen gait at a reduced cost (60 samples a cycle, the one-sided family alone: ~8 s).
# The full-size run is analysis/codesign_hexaleg.py (tests/test_examples.py).

BUDGET = {"samples": 50, "final_samples": 100, "max_evaluations": 30, "restarts": 2,
          "rules": False}
"""The reduced search of the shared co-design (the default: 100, 200, 100, 3, with the rules)."""
RULES_SAMPLES = 60
"""Samples a cycle of the reduced full rules (the default: the rows' 200)."""


def once_per_run(request: pytest.FixtureRequest, name: str, make: Callable[[], Any]) -> Any:
    """``make()``, computed once for the whole run: under pytest-xdist the first worker that asks
    computes it and pickles it into the run's shared temporary directory while it holds a lock
    there; the others wait on the lock and read it back (the pattern of pytest-xdist's docs,
    "Making session-scoped fixtures execute only once"). A session fixture is otherwise built
    by every worker that runs one of its tests: the co-design below was built twice in the slow
    studies (31.9 s and 40.8 s of setup in one CI run). Without xdist: ``make()``."""
    import fcntl
    import pickle

    worker = os.environ.get("PYTEST_XDIST_WORKER")
    if worker is None:
        return make()
    # popen-gw0/… share the run's directory (pytest-N/), new for every run: two runs never mix
    shared = request.getfixturevalue("tmp_path_factory").getbasetemp().parent
    path = shared / f"{name}.pickle"
    with open(shared / f"{name}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # released when the file closes
        if path.is_file():
            return pickle.loads(path.read_bytes())
        value = make()
        path.with_suffix(f".{worker}").write_bytes(pickle.dumps(value))
        path.with_suffix(f".{worker}").replace(path)  # whole or absent
        return value


@pytest.fixture(scope="session")
def codesigned(request: pytest.FixtureRequest):
    from hexaleg.design.codesign.build import codesign

    return once_per_run(request, "codesigned", lambda: codesign("hexaleg", 0.06, **BUDGET))


@pytest.fixture(scope="session")
def ruled(request: pytest.FixtureRequest):
    """``codesigned`` with the full spring rules (one-sided family) on its chosen gait (a
    worker that reads it back does not build ``codesigned``)."""
    import dataclasses

    from hexaleg.design.codesign.full_rules import full_rules, rule_params

    def make():
        codesigned = request.getfixturevalue("codesigned")
        chosen = dataclasses.replace(codesigned.chosen, samples=RULES_SAMPLES)
        rules = full_rules("hexaleg", chosen, codesigned.constraints, lambda _m: None,
                           rule_params(families=["one_sided"]))
        return dataclasses.replace(codesigned, rules=rules)

    return once_per_run(request, "ruled", make)


# One small report (tests/report, tests/commands/report), written once per session, and the same
# gait analysed through the public API without the report's modules.

REPORT_SMALL = """
[gait]
samples = 200

[report]
title = "test report"
stiffness_points = 5

[view]
fps = 30
"""
"""The report's config: the 200-sample default gait (the ``walk200`` fixture's), 5 curve
points."""


@pytest.fixture(scope="session")
def report_written(tmp_path_factory: pytest.TempPathFactory,
            robot: hexaleg.Robot) -> tuple[Report, Path]:
    """The report of a 200-sample default gait and its directory, written once for the session
    (the paper's single-joint numbers at the default samples are cached for the other runs)."""
    from hexaleg.commands.report.write import write_report
    from hexaleg.report.config import ReportConfig

    out = tmp_path_factory.mktemp("report")
    (out / "small.toml").write_text(REPORT_SMALL)
    r = write_report(out / "out", ReportConfig.from_toml(out / "small.toml"), robot=robot,
                     progress=None)
    return r, out / "out"


TINY_DESIGN = {"design": {"samples": 100, "families": ["linear"], "map_period": [1.0],
                          "map_stride": [1.0], "map_payload": [0.0], "map_mu": [0.6],
                          "map_slope": [0.0], "map_pattern": ["tripod"],
                          "robust_period": [1.0, 1.25], "robust_stride": [1.0, 1.0],
                          "robust_payload": [0.0, 0.0], "robust_mu": [0.6, 0.6],
                          "pareto_fractions": []}}
"""``hexaleg design`` at its smallest: linear springs on the 100-sample default gait, one-cell
maps, a two-corner robust box."""


@pytest.fixture(scope="session")
def design_json(request: pytest.FixtureRequest, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A ``design.json`` (and ``design.html``) of :data:`TINY_DESIGN`, written once for the run
    (:func:`once_per_run`; the tests read it)."""
    from hexaleg.commands.design.write import write_design

    def make() -> Path:
        out = tmp_path_factory.mktemp("design")
        write_design(out, hexaleg.Scenario.from_tables("hexaleg", TINY_DESIGN), progress=None)
        return out / "design.json"

    return once_per_run(request, "design_json", make)


@pytest.fixture(scope="session")
def data(report_written: tuple[Report, Path]) -> dict[str, Any]:
    """The written ``report.json``."""
    import json

    return json.loads((report_written[1] / "report.json").read_text())


@pytest.fixture(scope="session")
def analysed(robot: hexaleg.Robot, walk200: hexaleg.Motion, data: dict[str, Any]
             ) -> tuple[SpringSet, hexaleg.Analysis]:
    """The springs report.json says the page analyses (the answer's: their laws read back with
    design.json's reader) and the same gait analysed with them through the public API, without
    the report modules."""
    from hexaleg.design.springs.law_json import spring_from_entry
    from hexaleg.robot.catalogue import DEFAULT_MOTOR
    from hexaleg.robot.springs import SpringSet

    springs = SpringSet({j: spring_from_entry({**row, "joint": j})
                         for j, row in data["springs"]["joints"].items()})
    return springs, analyze(robot, walk200, springs, motor=DEFAULT_MOTOR, objective="joule")


@pytest.fixture(scope="session")
def independent(robot: hexaleg.Robot, walk200: hexaleg.Motion
                ) -> tuple[hexaleg.Motion, SpringSet, hexaleg.Analysis]:
    """The same gait analysed through the public API with the reference springs (the paper's
    design on the femurs), without the report modules."""
    from hexaleg.design.rules import paper_style_springs
    from hexaleg.robot.catalogue import DEFAULT_MOTOR

    springs = paper_style_springs(robot, walk200, "femur")
    a = analyze(robot, walk200, springs, motor=DEFAULT_MOTOR, objective="joule")
    return walk200, springs, a


def held_loop_radius(r: float, gains: Any, period: float) -> float:
    """The spectral radius of the error loop ``ë = −r (k_p e + k_d ė)`` with the correction held
    over ``period`` and integrated exactly in between (zero-order hold: ``e ← e + T ė + T²/2 u``,
    ``ė ← ė + T u``; Franklin, Powell & Workman, *Digital Control of Dynamic Systems*, 1998,
    §4.3) — not the explicit step :func:`hexaleg.simulation.control_rate.control_period` bounds
    (``gains``: a :class:`hexaleg.simulation.balance.Gains`)."""
    u = -r * np.array([gains.kp, gains.kd])
    step = np.array([[1.0, period], [0.0, 1.0]]) + np.outer([period**2 / 2, period], u)
    return float(np.max(np.abs(np.linalg.eigvals(step))))
