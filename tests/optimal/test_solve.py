"""The optimal cycle of the default robot: it obeys Newton–Euler to round-off, stays in its
friction cones, repeats, stops on its stated criterion, and is a Motion the dynamics takes."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import hexaleg

pytest.importorskip("crocoddyl")

from hexaleg.optimal.problem import OptimalParams, build_problem
from hexaleg.optimal.solve import solve


@pytest.fixture(scope="module")
def run():
    return hexaleg.Scenario.load("hexaleg")


@pytest.fixture(scope="module")
def optimal(run):
    built = build_problem(run.model, run.motion(), run.actuator, hexaleg.SpringSet(),
                          OptimalParams(nodes=20, iterations=200, stop=5e-5))
    lines: list[str] = []
    return solve(run.model, built, say=lines.append), lines


@pytest.mark.slow
def test_the_optimum_obeys_newton_euler(optimal):
    result, lines = optimal
    assert result.residual <= 1e-6
    assert result.dynamic_gap <= 1e-9
    assert lines and lines[0].startswith("iteration")


@pytest.mark.slow
def test_the_solver_states_where_it_stopped(optimal):
    result, _ = optimal
    assert result.converged == (result.stationarity <= result.threshold)
    assert result.converged, (result.stationarity, result.iterations)


@pytest.mark.slow
def test_the_feet_stay_in_their_cones_and_the_cycle_repeats(optimal):
    result, _ = optimal
    assert result.friction_use <= 0.7 + 1e-3  # the pyramid inside 0.7 μ
    assert result.periodicity <= 1e-2
    # The stance feet hold their footholds (0.37 mm, 7.3 mm/s measured: the dead-beat gain
    # pulling back what a knot's curvature moves). Without the contacts' position gain they
    # drift 0.64 mm; without the foothold cost at touch-down a foot lands off its point and is
    # dragged onto it (20 mm, 0.39 m/s), which the model books as energy saved.
    assert result.drift <= 4.5e-4  # m
    assert result.slip <= 0.01  # m/s
    swing = ~result.motion.stance
    assert np.all(result.forces[swing] == 0.0)


@pytest.mark.slow
def test_the_swing_feet_stay_above_the_ground(optimal):
    """The clearance barrier: no swing foot below the level floor (its stance feet's height) at
    a knot by more than 10 µm (this cycle without the barrier: 0.65 mm; Solo-12's optimal trot
    1.5 mm)."""
    result, _ = optimal
    knots = result.motion
    floor = knots.feet[..., 2][knots.stance].min()
    assert (~knots.stance).any()
    assert knots.feet[..., 2][~knots.stance].min() >= floor - 1e-5


@pytest.mark.slow
def test_the_energy_is_the_motors_exact_model(run, optimal):
    result, _ = optimal
    m = result.motion
    speeds = m.v[:, 6:]
    expected = run.actuator.electrical_power(result.torques, speeds).sum() * m.dt
    assert result.energy == pytest.approx(expected, rel=1e-12)
    assert result.energy_per_metre == pytest.approx(expected / m.distance)


@pytest.mark.slow
def test_the_optimal_cycle_is_a_motion_the_dynamics_takes(run, optimal):
    result, _ = optimal
    """hexaleg's own pipeline (RNEA, its force program) reads the cycle; its energy, with the
    force program's own foot forces, is of the size of the optimum's (the force program may share
    the load more cheaply than the solver's contact forces, never by a factor)."""
    prepared = hexaleg.prepare(run.model, result.motion, motor=run.actuator, contact=run.contact)
    electrical = prepared.evaluate(hexaleg.SpringSet()).metrics["total"]["electrical"]
    assert 0.5 * result.energy < electrical < 1.5 * result.energy


@pytest.mark.slow
def test_a_gait_parameter_moved_by_1e_9_gives_the_same_cycle(run, optimal):
    """Same answer on any machine (RULES.md): the period moved by 1e-9 s — through the gait's own
    sampling, knots and contact timing — gives the same optimum to the digits the table prints
    (J/m to 4 significant digits; the solver is deterministic, no random start)."""
    moved = hexaleg.gait(run.model, dataclasses.replace(run.gait, period=run.gait.period + 1e-9))
    built = build_problem(run.model, moved, run.actuator, hexaleg.SpringSet(),
                          OptimalParams(nodes=20, iterations=200, stop=5e-5))
    again = solve(run.model, built)
    result, _ = optimal
    assert f"{again.energy_per_metre:.4g}" == f"{result.energy_per_metre:.4g}"
    assert again.iterations == result.iterations


@pytest.mark.slow
def test_the_cycle_closes_at_the_solvers_last_knot(run, optimal):
    """The balance feedback's closing sample of an optimal motion is the solver's x_N."""
    import pinocchio as pin

    from hexaleg.simulation.balance import cycle_end

    result, _ = optimal
    end, position = cycle_end(run.model.model, result.motion)
    assert np.abs(position - result.x[-1, :3]).max() < 1e-12
    want = pin.Quaternion(result.x[-1, 3:7]).toRotationMatrix()
    assert np.abs(end - want).max() < 1e-12


def test_a_cycle_that_cannot_be_rebuilt_is_still_the_solvers_answer(run, monkeypatch):
    """The rebuild's out-of-reach error does not lose the solve: the result has no task-space
    cycle and says why (the error's message); the solver's knots are kept. Catches a solve that
    raises (the command stopped there) or drops the why."""
    import hexaleg.optimal.solve as solve_module
    from hexaleg.errors import UnreachableTargetError

    def unreachable(*_args, **_kwargs):
        raise UnreachableTargetError("leg RH out of reach between knots 26 and 27", leg="RH")

    monkeypatch.setattr(solve_module, "task_space_motion", unreachable)
    built = build_problem(run.model, run.motion(), run.actuator, hexaleg.SpringSet(),
                          OptimalParams(nodes=20, iterations=1, closing=0))
    result = solve(run.model, built)
    assert result.task_space is None
    assert result.unbuilt == "leg RH out of reach between knots 26 and 27"
    assert result.motion.n_samples == 20 and np.isfinite(result.energy_per_metre)


def test_the_solve_does_not_end_with_its_dynamics_gap_open(run):
    """Three iterations leave the hexapod's gap open (1.03, Newton–Euler residual 0.13 N·m):
    the solve goes on until the gap is under ``OptimalParams.gap`` and the residual with it,
    its iterations counted and its progress lines numbered on. Catches a solve that stops at
    ``iterations`` whatever its gap (as ``closing=0`` does, checked here too)."""
    motion = run.motion()
    params = OptimalParams(nodes=20, iterations=3)
    open_ = solve(run.model, build_problem(run.model, motion, run.actuator, hexaleg.SpringSet(),
                                           dataclasses.replace(params, closing=0)))
    assert open_.iterations == 3 and open_.dynamic_gap > 0.1 and open_.residual > 1e-2
    lines: list[str] = []
    closed = solve(run.model, build_problem(run.model, motion, run.actuator, hexaleg.SpringSet(),
                                            params), say=lines.append)
    assert closed.dynamic_gap <= params.gap and closed.residual <= 1e-6
    assert 3 < closed.iterations <= 3 + params.closing
    numbers = [int(line.split(":")[0].split()[1]) for line in lines]
    assert numbers == list(range(closed.iterations))


def test_closing_the_gap_takes_the_iterates_of_one_longer_solve(run):
    """The calls that close the gap go on from the iterate and the regularisation where the
    last stopped: the states and torques are those of one box-FDDP call of as many iterations,
    bit for bit. Six iterations end at a regularisation (0.1) above the first call's (0.01).
    Catches a continuation that restarts the regularisation or the warm start."""
    from hexaleg.optimal.backend import crocoddyl_module

    motion = run.motion()
    closed = solve(run.model, build_problem(run.model, motion, run.actuator,
                                            hexaleg.SpringSet(),
                                            OptimalParams(nodes=20, iterations=6, gap=1e-300)))
    built = build_problem(run.model, motion, run.actuator, hexaleg.SpringSet(),
                          OptimalParams(nodes=20, iterations=closed.iterations))
    solver = crocoddyl_module().SolverBoxFDDP(built.problem)
    solver.th_stop = built.params.stop
    xs = [np.array(x) for x in built.x_warm]
    solver.solve(xs, list(built.problem.quasiStatic(xs[:-1])), closed.iterations, False)
    assert closed.iterations > 6 + 1  # more than one call
    assert np.array_equal(np.array(solver.xs), closed.x)
    assert np.array_equal(np.array(solver.us), closed.torques)


@pytest.fixture(scope="module")
def stepped(run):
    """A short RK4 problem with a spring in its dynamics (12 knots, 30 iterations a rung, no
    gap closing) solved from the gait's start twice: by the continuation (Euler's knots, then
    RK2's, then RK4's) and directly on RK4's knots (the gait's states, their quasi-static
    controls as ``warm``); and on Euler's knots alone."""
    springs = hexaleg.SpringSet({"LF_femur": hexaleg.LinearSpring(0.5, reference=0.3)})
    params = OptimalParams(nodes=12, iterations=30, closing=0, integrator="rk4")
    built = build_problem(run.model, run.motion(), run.actuator, springs, params)
    xs = np.array(built.x_warm)
    direct = solve(run.model, built, warm=(xs, np.array(built.problem.quasiStatic(list(xs[:-1])))))
    lines: list[str] = []
    continued = solve(run.model, built, say=lines.append, every=1000)
    euler = solve(run.model, built.on_knots("euler"))
    return built, direct, continued, euler, lines


def test_a_runge_kutta_solve_steps_up_from_eulers_optimum(stepped):
    """From the gait's start an RK4 solve goes nowhere (its gap 28 after 30 iterations, where
    the continuation's is 8e-4; before the actuation let a line search's non-finite trial step
    fail as a step, it raised ``InvalidParameterError: invalid v = nan`` at the first); the
    continuation reaches RK4 knots whose defect stepped by RK4 is small, where Euler's optimum's
    stepped by RK4 is 1.9 (its own Euler defect 0), and books less energy. Catches a solve on
    RK knots that skips the lower rungs (the direct solve), or starts a rung from the start's
    states instead of the last rung's states and controls."""
    from hexaleg.optimal.solve import knot_defect

    built, direct, continued, euler, lines = stepped
    rungs = [line.split(" (")[0] for line in lines if line.startswith("solved")]
    assert rungs == ["solved on euler knots", "solved on rk2 knots"]
    assert continued.iterations == 3 * 30 and direct.iterations == 30
    assert direct.dynamic_gap > 1.0 and direct.defect > 1.0
    assert continued.defect < 1e-2 and continued.dynamic_gap < 1e-2
    assert euler.defect < 1e-12 and knot_defect(built, euler.x, euler.torques) > 0.5
    assert continued.energy_per_metre < 0.6 * direct.energy_per_metre
    assert np.isfinite(continued.x).all()


def test_runge_kutta_knots_are_checked_at_their_own_accelerations(run, stepped):
    """On RK4 knots the residual is Newton–Euler at each knot's own acceleration
    (``knot_acceleration``, round-off), not Euler's ``(v_{k+1} − v_k)/dt``, which reads
    their stages' mean (tenths of N·m here); on Euler knots it is Euler's. Catches a solve that
    checks RK knots by Euler's step (or Euler's by the knots' accelerations: the names)."""
    from hexaleg.optimal.residual import EULER_STEP, KNOT_ACCELERATION, dynamics_residual

    _, _, continued, euler, _ = stepped
    nq = run.model.model.nq
    assert continued.residual_check == KNOT_ACCELERATION and continued.residual <= 1e-9
    by_step = dynamics_residual(run.model, continued.x[:, :nq], continued.x[:, nq:],
                                continued.motion.dt,
                                continued.torques + continued.spring_torques, continued.forces)
    assert np.abs(by_step).max() > 1e-2
    assert euler.residual_check == EULER_STEP and euler.residual <= 1e-9


def test_a_non_finite_trial_state_is_a_failed_step_not_an_error(run):
    """The actuation inside the solver's rollouts gives non-finite torques at a non-finite
    state (Crocoddyl's line search then rejects that step length), while its public
    ``spring_torques`` still names the bad value."""
    from hexaleg.errors import InvalidParameterError

    springs = hexaleg.SpringSet({"LF_femur": hexaleg.LinearSpring(0.5, reference=0.3)})
    built = build_problem(run.model, run.motion(), run.actuator, springs,
                          OptimalParams(nodes=8))
    x = np.array(built.x_warm[0])
    x[built.actuation.sprung[0].iq] = np.nan
    data = built.actuation.createData()
    built.actuation.calc(data, x, np.zeros(built.actuation.nu))
    assert np.isnan(data.tau).any()
    with pytest.raises(InvalidParameterError, match="nan"):
        built.actuation.spring_torques(x)
