"""The alternation of the optimal motion and its springs never raises the energy per metre."""

from __future__ import annotations

import dataclasses
import itertools
from types import SimpleNamespace

import numpy as np
import pytest

import hexaleg
from hexaleg.design.codesign.alternation import (
    MOVES,
    Alternation,
    Round,
    Spread,
    alternate,
    decimals,
    least,
    predicted_per_metre,
    shown,
)
from hexaleg.dynamics.contact import ContactParams
from hexaleg.errors import InvalidParameterError, UnknownNameError


def test_the_best_energy_never_rises():
    """The bookkeeping, by hexaleg's predictions (the solver's own figures are not judged): a
    rejected round leaves the best where it was, a round without a prediction too."""
    start = SimpleNamespace(energy_per_metre=10.0)
    rounds = (Round(hexaleg.SpringSet(), 8.0, 7.0, 9.0, True, 1.0),
              Round(hexaleg.SpringSet(), 8.5, 6.0, 9.5, False, 1.0),
              Round(hexaleg.SpringSet(), 8.5, 6.0, None, False, 1.0),
              Round(hexaleg.SpringSet(), 8.0, 9.9, 8.5, True, 1.0))
    alt = Alternation(None, 11.0, start, 10.0, start, hexaleg.SpringSet(), rounds, 0.0, False)
    assert alt.energies == [11.0, 10.0, 9.0, 9.0, 9.0, 8.5] and alt.predicted == 8.5
    assert Alternation(None, None, start, None, start, hexaleg.SpringSet(), rounds[:1], 0.0,
                       False).energies == [None, None, 9.0]


class _Solver:
    """Stands in for Crocoddyl: each solve returns the next of ``cycles`` (the solver's own
    figure and the motion its cycle rebuilds to, None: not rebuilt), so the alternation's
    verdicts can be checked against hexaleg's predictions of given motions."""

    def __init__(self, cycles: list[tuple[float, hexaleg.Motion | None]]) -> None:
        self.cycles = list(cycles)
        self.built: list[hexaleg.SpringSet] = []
        self.moves: list[float] = []

    def build_problem(self, _robot, _gait, _actuator, springs, _params):
        self.built.append(springs)
        return SimpleNamespace(actuation=SimpleNamespace(spring_torques=lambda _x: np.zeros(18)))

    def solve(self, _robot, _built, **kwargs):
        self.moves.append(kwargs.get("move", 0.0))
        figure, played = self.cycles.pop(0)
        return SimpleNamespace(energy_per_metre=figure, task_space=played, x=np.zeros((3, 43)),
                               torques=np.zeros((2, 18)), spring_torques=np.zeros((2, 18)),
                               iterations=1, seconds=0.0,
                               unbuilt="" if played is not None else "leg RH out of reach")


@pytest.fixture
def solver(monkeypatch):
    pytest.importorskip("crocoddyl")
    import hexaleg.optimal.problem
    import hexaleg.optimal.solve

    def make(cycles):
        fake = _Solver(cycles)
        monkeypatch.setattr(hexaleg.optimal.problem, "build_problem", fake.build_problem)
        monkeypatch.setattr(hexaleg.optimal.solve, "solve", fake.solve)
        return fake
    return make


@pytest.fixture(scope="module")
def motions(robot):
    """The default tripod and a costlier one (step height 60 mm: more work lifting the legs),
    both at 100 samples a cycle, and the springs designed on the tripod (the "co-design's")."""
    run = hexaleg.Scenario.load("hexaleg")
    walk = hexaleg.gait(robot, hexaleg.GaitParams(samples=100))
    high = hexaleg.gait(robot, hexaleg.GaitParams(samples=100, step_height=0.06))
    design = hexaleg.optimal_springs(
        hexaleg.prepare(robot, walk, motor=run.actuator, contact=run.contact),
        list(robot.joint_classes), family="linear", metric="electrical")
    return walk, high, design.springs


def test_a_round_is_judged_by_the_prediction_of_its_rebuilt_cycle(robot, motions, solver):
    """A round whose solver figure halves (10 → 5 J/m) but whose rebuilt cycle hexaleg predicts
    costlier (the high-stepping one: 30.5 against 23.7 J/m) is rejected: the answer stays the
    start. The round's springs are designed on the start's rebuilt cycle (the tripod)."""
    walk, high, springs = motions
    run = hexaleg.Scenario.load("hexaleg")
    fake = solver([(10.0, walk), (5.0, high)])
    result = alternate(robot, walk, run.actuator, run.contact, springs=springs, rounds=1)
    (only,) = result.rounds
    assert not only.accepted and only.energy_per_metre == 5.0
    assert result.springs is springs and result.best is result.start
    assert only.predicted > result.start_predicted == result.baseline  # the start is the walk
    assert fake.built[1] == only.springs == springs  # designed on the tripod again
    assert result.energies == [result.baseline] * 3 and result.motion is walk


def test_it_never_ends_worse_than_the_gait_it_starts_from(robot, motions, solver):
    """Optimal cycles whose rebuilt motion hexaleg predicts costlier than the gait with its
    springs (the high-stepping one: 30.5, then 29.2 with springs designed on it — a round
    accepted — against 23.7 J/m) are not the answer: the gait with the starting springs is, and
    the rows play it."""
    walk, high, springs = motions
    run = hexaleg.Scenario.load("hexaleg")
    solver([(10.0, high), (5.0, high)])
    lines: list[str] = []
    result = alternate(robot, walk, run.actuator, run.contact, springs=springs, rounds=1,
                       say=lines.append)
    (only,) = result.rounds
    assert only.accepted and result.best is not result.start
    assert result.baseline < only.predicted < result.start_predicted
    assert result.kept_gait and result.motion is walk and result.springs is springs
    assert result.predicted == result.baseline == result.energies[-1]
    assert "the gait and its springs kept" in lines[-1]


def test_a_cycle_not_rebuilt_leaves_the_gait_and_its_springs(robot, motions, solver):
    """A start whose cycle cannot be rebuilt in task space has no prediction (its why says
    not rebuilt), no springs are designed on it, and the answer is the gait with the starting
    springs: the command goes on. Catches an alternation that designs on a missing cycle
    (AttributeError) or answers with a motion it cannot play."""
    from hexaleg.design.codesign.alternation import judged

    walk, _, springs = motions
    run = hexaleg.Scenario.load("hexaleg")
    solver([(10.0, None)])
    lines: list[str] = []
    result = alternate(robot, walk, run.actuator, run.contact, springs=springs, rounds=2,
                       say=lines.append)
    assert result.rounds == () and result.start_predicted is None
    assert result.kept_gait and result.motion is walk and result.springs is springs
    assert result.predicted == result.baseline
    assert any("no springs designed: the cycle is not rebuilt" in line for line in lines)
    said = judged(robot, result.start, walk, run.actuator, springs, run.contact, 0.7)
    assert said.value is None and said.why == "not rebuilt: leg RH out of reach"


def test_a_cycle_short_of_its_stride_is_not_judged(robot, motions):
    """A rebuilt cycle that covers 90 % of its gait's stride walks slower than the required
    speed: its energy per metre is another task's, so it gets no verdict (and its why)."""
    from hexaleg.design.codesign.alternation import judged

    walk, _, springs = motions
    run = hexaleg.Scenario.load("hexaleg")
    short = hexaleg.gait(robot, hexaleg.GaitParams(samples=100, stride_length=0.9 * walk.distance,
                                                   speed=None))
    said = judged(robot, SimpleNamespace(task_space=short), walk, run.actuator, springs,
                  run.contact, 0.7)
    assert said.value is None and "covers 90.0% of the gait's" in said.why
    said = judged(robot, SimpleNamespace(task_space=walk), walk, run.actuator, springs,
                  run.contact, 0.7)
    assert said.why == "" and said.value == predicted_per_metre(
        robot, walk, run.actuator, springs,
        dataclasses.replace(run.contact, mu=0.7 * run.contact.mu))[0]


def test_bad_options_are_named(robot, walk):
    run = hexaleg.Scenario.load("hexaleg")
    with pytest.raises(UnknownNameError, match="one_sided"):
        alternate(robot, walk, run.actuator, run.contact, family="one_sided")
    with pytest.raises(InvalidParameterError, match="rounds"):
        alternate(robot, walk, run.actuator, run.contact, rounds=0)


@pytest.mark.slow
def test_the_alternation_lowers_the_energy_and_never_raises_it():
    pytest.importorskip("crocoddyl")
    from hexaleg.optimal.problem import OptimalParams

    run = hexaleg.Scenario.load("hexaleg")
    lines: list[str] = []
    result = alternate(run.model, run.motion(), run.actuator, run.contact,
                       params=OptimalParams(nodes=20, iterations=60), rounds=1, say=lines.append)
    energies = result.energies
    assert all(b <= a for a, b in itertools.pairwise(energies))
    assert result.predicted == energies[-1] and not result.kept_gait
    assert energies[-1] < 0.9 * energies[1]  # the springs pay on the optimal cycle
    assert result.best.residual <= 1e-6
    solves = [line for line in lines if line.startswith(("start", "round"))]
    assert len(solves) == 1 + len(result.rounds)
    shown = [int(line.split()[1][:-1]) for line in lines if line.startswith("iteration")]
    assert shown and all(k % 20 == 0 for k in shown)  # progress, one line in 20 iterations


def test_the_springs_are_designed_on_the_given_groups(solver):
    """Solo-12's front and hind legs bend opposite ways, so one linear spring per joint class
    nearly cancels; designed per mirrored pair (the co-design's ``grouping``), front and hind
    get their own springs and pay. On the trot itself (the stand-in solver's rebuilt cycle):
    94.1 J/m without springs, 90.2 with one design a class, 58.1 one a mirrored pair."""
    from hexaleg.design.chain.groups import design_groups
    from hexaleg.design.codesign.build import default_gait

    run = hexaleg.Scenario.load("solo12")
    robot = run.model
    trot = hexaleg.gait(robot, default_gait(robot, "solo12", 0.3, None, 100))
    groups = design_groups(robot, tuple(robot.joint_classes), "mirrored")
    solver([(10.0, trot), (5.0, trot)])
    result = alternate(robot, trot, run.actuator, run.contact, groups=groups, rounds=1)
    springs = result.rounds[0].springs
    assert springs["FL_HFE"].stiffness == springs["FR_HFE"].stiffness  # one design a pair
    assert springs["FL_HFE"].stiffness != springs["HL_HFE"].stiffness  # front ≠ hind
    assert result.rounds[0].designed < 0.7 * result.baseline  # a class design: 0.96×
    assert result.rounds[0].accepted and result.predicted == result.rounds[0].predicted


def test_the_least_prediction_wins_a_tie_and_none_keep_the_earlier():
    """``least``, the timing search's and the starts' choice: the least prediction; a tie keeps
    the earlier in the lattice's order, a missing prediction never wins, and with none at all
    the first (the gait itself) is kept."""
    assert least([9.0, 8.0, 8.5]) == 1
    assert least([9.0, 8.0, 8.0]) == 1
    assert least([None, 9.0, None, 8.9]) == 3
    assert least([None, None]) == 0
    assert least([8.0, None, 8.0]) == 0


@pytest.mark.parametrize("workers", [1, 2])
def test_side_by_side_solves_are_kept_as_they_end_and_resume(tmp_path, monkeypatch, workers):
    """:func:`apart` on one and on two workers: the results in the jobs' order with the work
    after each; a job that fails after another ended leaves that one kept (by this process, in
    the run's stage files), and the next run computes only the others (a map that kept nothing
    until the end, or kept in the workers' copies of the stage files, fails here)."""
    import os

    from hexaleg.design.chain.checkpoint import StageFiles
    from hexaleg.design.codesign.alternation import apart
    from hexaleg.design.codesign.optimal_stage import KeptSolves
    from hexaleg.parallel import workers as workers_module

    monkeypatch.setattr(workers_module, "default_workers", lambda: workers)
    robot = hexaleg.load()
    stages = tmp_path / "stages"
    computes = tmp_path / "computes"
    computes.mkdir()

    def job(k: int, fail: bool) -> tuple[tuple[object, ...], object]:
        def compute() -> np.ndarray:
            (computes / f"{k}-{os.getpid()}-{len(list(computes.iterdir()))}").touch()
            if fail:
                for _ in range(10**6):  # job 0 kept first (else the test fails, not hangs)
                    if any(stages.glob("optimal-solve-*.pickle")):
                        break
                    os.sched_yield()
                raise RuntimeError("killed")
            return np.arange(3.0) * k
        return ("round", k), compute

    files: list[StageFiles] = []

    def run(fail: bool) -> list:
        files.append(StageFiles(stages, "k"))
        return apart([job(0, False), job(1, fail), job(2, False)], robot,
                     KeptSolves(files[-1], robot, lambda _line: None),
                     lambda index, result: float(result.sum()) + index)

    with pytest.raises(RuntimeError, match="killed"):
        run(True)
    assert len(list(stages.glob("optimal-solve-*.pickle"))) >= 1
    first = {p.name.split("-")[0] for p in computes.iterdir()}
    for p in computes.iterdir():
        p.unlink()
    out = run(False)
    assert [r.tolist() for r, _ in out] == [[0.0, 0.0, 0.0], [0.0, 1.0, 2.0], [0.0, 2.0, 4.0]]
    assert [after for _, after in out] == [0.0, 4.0, 8.0]
    again = {p.name.split("-")[0] for p in computes.iterdir()}
    assert "0" in first and "0" not in again and "1" in again
    assert len(files[-1].written) == 3  # read back or kept by this process's stage files
    for p in computes.iterdir():
        p.unlink()
    run(False)
    assert not list(computes.iterdir())  # every solve read back


def test_a_moved_alternation_moves_its_start_only(robot, motions, solver):
    """``move`` reaches the start's solve (the rows' spread repeats the whole alternation from
    its start moved), not the rounds' warm-started solves; without it no solve is moved.
    Catches a spread whose alternation ignores the move (its figures all the answer's)."""
    walk, high, springs = motions
    run = hexaleg.Scenario.load("hexaleg")
    fake = solver([(10.0, high), (5.0, walk)])
    alternate(robot, walk, run.actuator, run.contact, springs=springs, rounds=1, move=2e-9)
    assert fake.moves == [2e-9, 0.0]
    fake = solver([(10.0, high), (5.0, walk)])
    alternate(robot, walk, run.actuator, run.contact, springs=springs, rounds=1)
    assert fake.moves == [0.0, 0.0]


def test_a_spread_is_its_judged_figures_largest_less_least():
    """The spread of the judged figures (not the solver's own), the solves without a figure
    counted apart; the digits a figure keeps are those whose last unit covers its spread.
    Catches a spread of zero when the solves differ, or one taken from the solver's figures."""
    spread = Spread(MOVES, (9.627, 9.6267, None, 9.6301, 9.6262), (9.33, 9.32, 9.31, 9.2, 9.3),
                    (2e-3, 3e-2, 1e-3, 2e-3, 2e-3))
    assert spread.value == pytest.approx(9.6301 - 9.6262) and spread.unjudged == 1
    assert spread.solver_value == pytest.approx(0.13)
    assert Spread(MOVES, (9.6, None, None, None, None), (9.0,) * 5, (1e-3,) * 5).value is None
    # the last digit's unit at least MARGIN (4) times the spread
    assert [decimals(v) for v in (None, 0.0, 4e-4, 0.002, 0.0026, 0.004, 0.02, 0.026, 3.0)] == [
        2, 2, 2, 2, 1, 1, 1, 0, 0]
    assert decimals(2e-4, 3) == 3 and decimals(4e-4, 3) == 2
    data = spread.data()
    assert data["value"]["unit"] == "J/m" and data["moves"] == {"value": list(MOVES), "unit": "m"}
    assert data["judged"][2] == {"value": None, "unit": "J/m"} and data["unjudged"] == 1


@pytest.mark.slow
def test_the_spread_repeats_the_solve_from_its_start_moved():
    """A short solve (16 knots, 40 iterations) repeated by :func:`spreads` from its start moved
    by each of :data:`MOVES` on the workers: the first figure is the answer's own, the moved
    answers come back in the moves' order, the moved solves land elsewhere (the solver parts
    them: a ``move`` ignored gives five equal figures and a spread of zero), and the same solve
    repeated unmoved lands on the answer to the bit (deterministic)."""
    pytest.importorskip("crocoddyl")
    from hexaleg.design.codesign.alternation import spreads
    from hexaleg.optimal.problem import OptimalParams, build_problem
    from hexaleg.optimal.solve import solve

    run = hexaleg.Scenario.load("hexaleg")
    robot, motor = run.model, run.actuator
    walk = hexaleg.gait(robot, hexaleg.GaitParams(samples=100))
    params = OptimalParams(nodes=16, iterations=40)
    answer = solve(robot, build_problem(robot, walk, motor, hexaleg.SpringSet(), params))

    def moved(move):
        return solve(robot, build_problem(robot, walk, motor, hexaleg.SpringSet(), params),
                     move=move)

    def read(result):
        value, _ = predicted_per_metre(robot, result.task_space, motor, hexaleg.SpringSet(),
                                       run.contact)
        return value, result.energy_per_metre, result.stationarity

    ((spread, answers),) = spreads(robot, [(read(answer), ("test",), moved, read)])
    assert spread.moves == MOVES and spread.judged[0] == read(answer)[0]
    assert [a.energy_per_metre for a in answers] == list(spread.solver[1:])
    assert spread.solver[0] == answer.energy_per_metre
    assert len(set(spread.solver)) == len(MOVES) + 1 and spread.value > 0.0
    again = solve(robot, build_problem(robot, walk, motor, hexaleg.SpringSet(), params),
                  move=0.0)
    assert np.array_equal(again.x, answer.x)


def test_a_prediction_is_inside_the_friction_margin_or_says_it_is_not(robot, motions):
    """On a floor of μ 0.1 the default tripod's forces lean on the cone: inside 0.7 of it the
    prediction is the force program's at 0.07 (35.3 J/m, friction use 0.7 of the floor's
    cone), not the whole cone's (33.3). On μ 0.02 there are no forces inside 0.7 of it: the
    prediction is the whole cone's, said (``beyond``, friction use 1) and never a verdict
    (``judged`` None); on μ 0.015 none at all, each cone's error said. Catches a prediction
    made at the floor's full μ, and a friction use stated at the narrowed cone's μ."""
    from hexaleg.design.codesign.alternation import predict

    run = hexaleg.Scenario.load("hexaleg")
    walk = motions[0]

    def floor(mu: float) -> ContactParams:
        return dataclasses.replace(run.contact, mu=mu)

    bare = hexaleg.SpringSet()
    said = predict(robot, walk, run.actuator, bare, floor(0.1), 0.7)
    narrowed, _ = predicted_per_metre(robot, walk, run.actuator, bare, floor(0.7 * 0.1))
    whole, _ = predicted_per_metre(robot, walk, run.actuator, bare, floor(0.1))
    assert said.within and not said.beyond and said.why == ""
    assert said.value == narrowed and said.judged == narrowed and whole < 0.97 * narrowed
    assert said.friction_use == pytest.approx(0.7, abs=1e-9)
    said = predict(robot, walk, run.actuator, bare, floor(0.02), 0.7)
    assert said.beyond and said.judged is None and said.friction_use == pytest.approx(1.0)
    assert said.value == predicted_per_metre(robot, walk, run.actuator, bare, floor(0.02))[0]
    assert said.why.startswith("no admissible forces within 0.7 of the friction cone "
                               "(InfeasibleForcesError")
    said = predict(robot, walk, run.actuator, bare, floor(0.015), 0.7)
    assert said.value is None and said.friction_use is None and not said.beyond
    assert "; nor in the whole cone (InfeasibleForcesError" in said.why
    with pytest.raises(InvalidParameterError, match="friction margin"):
        predict(robot, walk, run.actuator, bare, floor(0.6), 1.5)


def test_the_springs_are_designed_and_judged_inside_the_friction_margin(robot, motions, solver,
                                                                        monkeypatch):
    """The alternation's springs are designed by the force program inside ``margin · μ`` (as
    the parametric co-design's inner program plans), and the gait, the start and each round
    are judged there; on a floor where the gait has forces only beyond the margin (μ 0.02) no
    cycle gets a verdict and no springs are designed. Catches a design or a verdict in the
    whole cone."""
    from hexaleg.design.codesign import alternation as module
    from hexaleg.design.codesign.alternation import predict

    walk, _, springs = motions
    run = hexaleg.Scenario.load("hexaleg")
    floor = dataclasses.replace(run.contact, mu=0.1)
    designed: list[float] = []
    real = module.optimal_springs

    def design(prepared, *args, **kwargs):
        designed.append(prepared.contact.mu)
        return real(prepared, *args, **kwargs)

    monkeypatch.setattr(module, "optimal_springs", design)
    solver([(10.0, walk), (5.0, walk)])
    result = alternate(robot, walk, run.actuator, floor, springs=springs, rounds=1, margin=0.7)
    assert designed == [pytest.approx(0.07)]
    inside = predict(robot, walk, run.actuator, springs, floor, 0.7)
    assert inside.within and result.baseline == inside.value == result.start_predicted
    solver([(10.0, walk)])
    lines: list[str] = []
    slippery = alternate(robot, walk, run.actuator, dataclasses.replace(run.contact, mu=0.02),
                         rounds=1, margin=0.7, say=lines.append)
    assert slippery.energies == [None, None] and slippery.rounds == ()
    assert any("no springs designed on the rebuilt cycle (InfeasibleForcesError" in line
               for line in lines)


def test_progress_lines_show_no_digit_the_spread_moves():
    """A progress line's J/m is printed before the row's spread is measured: the five starts'
    figures of the kept command (codesign_motion_optimal_spread.log: the start as given and
    moved by MOVES) print alike. Fails on the old four significant digits, which printed the
    solver's figure with springs as 9.527 from the start as given and 9.524 from the start
    moved by -1e-9 m."""
    for figures in ((16.38369, 16.38345, 16.38332, 16.38751, 16.38747),  # judged, no springs
                    (10.43899, 10.43394, 10.43353, 10.43014, 10.43021),  # judged, its springs
                    (15.36681, 15.36443, 15.36293, 15.37410, 15.37355),  # the solver's
                    (9.52677, 9.52363, 9.52373, 9.52214, 9.52234)):
        assert len({shown(v) for v in figures}) == 1, figures
    assert shown(9.52677) == "9.5" and shown(None) == "—"


def test_the_alternations_lines_print_through_shown(robot, motions, solver):
    """Every J/m of the alternation's own progress lines has one decimal (:func:`shown`), the
    solver's figures too (they were printed to four digits beside the predictions)."""
    import re

    walk, high, springs = motions
    run = hexaleg.Scenario.load("hexaleg")
    solver([(10.04321, walk), (5.06789, high)])
    lines: list[str] = []
    alternate(robot, walk, run.actuator, run.contact, springs=springs, rounds=1,
              say=lines.append)
    own = [line for line in lines if line.startswith(("start:", "round", "no optimal"))]
    assert len(own) >= 2 and "the solver's 10.0 at its knots" in own[0]
    assert "(the solver's 5.1; rejected)" in own[1]
    figures = [f for line in own for f in re.findall(r"\d+\.\d+", line)]
    assert figures and all(len(f.split(".")[1]) == 1 for f in figures), own
