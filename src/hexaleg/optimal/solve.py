"""Solve the optimal-control problem by box-FDDP and read the answer as a hexaleg Motion.

Crocoddyl's box-FDDP (Mastalli et al., "A feasibility-driven approach to control-limited DDP",
Autonomous Robots 46, 2022) from the warm start's states and the quasi-static controls of its
knots (Crocoddyl's ``ShootingProblem.quasiStatic``). What the solver stops on is stated, not
assumed: ``stationarity`` is Crocoddyl's stopping criterion (the squared norm of the expected
improvement's gradient term, ``solver.stop``, met when ≤ ``solver.th_stop``, set from
``OptimalParams.stop``), ``dynamic_gap`` the
largest defect between a knot's integration and the next state (``solver.ffeas``, 0 for a
feasible trajectory), ``periodicity_gap`` :func:`~hexaleg.optimal.periodic.periodicity_gap`.

Box-FDDP closes the dynamics gap only as fast as its line search takes full steps (a step of
length α leaves ``(1 − α)`` of each gap, Mastalli et al. 2022, §IV); an iterate whose gap is
still open is not a trajectory of the dynamics, and its Newton–Euler residual shows it. So
the solve does not end with a gap above ``OptimalParams.gap``: past ``OptimalParams.iterations``
it goes on, :data:`CLOSING` iterations a call from the iterate and regularisation where it
stopped (the same iterates as one longer call), until the gap is closed or
``OptimalParams.closing`` more iterations are spent; ``dynamic_gap`` states where it ended.

Runge–Kutta knots (``OptimalParams.integrator`` ``"rk2"`` … ``"rk4"``) are solved by
continuation in the knots' order (Allgower & Georg, *Introduction to Numerical Continuation
Methods*, SIAM 2003, §1: a problem reached through a sequence of easier ones, each solved from
the last's answer): from a fresh start (no ``warm``) the same problem is solved first on the
lower rungs of :data:`RUNGS` — Euler's knots from the start's states and their quasi-static
controls, then RK2's from Euler's optimum — each from the states and controls the rung before
ended on, each to ``OptimalParams.iterations`` and its gap closed; then on the asked knots.
An RK4 solve from the command's start cannot take one step (its first line search rolls every
step length out to non-finite states on the default robot's tripod and wave), nor from Euler's
optimum on the tripod; from RK2's it solves both (analysis/bench_optimal_integrator.py). A warm
start (``warm``: the alternation's rounds, from the previous cycle on the same knots) goes
straight to the asked knots. A line search's trial step whose rollout leaves the finite
numbers is a failed step (:meth:`~hexaleg.optimal.actuation.SpringActuation.calc`; NumPy's
warnings of it are silenced inside the solver); a solve that still ends on non-finite states
raises :class:`~hexaleg.errors.DivergedSolveError`.

A start can be moved (``move``): the base's height raised by ``move`` metres at every knot of
the start, the rest of it unchanged — how the co-design's rows measure the spread of a solve's
figures under starts a hair apart (:func:`~hexaleg.design.codesign.alternation.spreads`).

The energy is the project's exact model (:meth:`~hexaleg.optimal.energy.JointPower.exact`) over
the knots' motor torques and joint speeds, left Riemann sum, ``Σ_k dt Σ_j P_j`` — the integral
the cost's Euler steps take, with the smoothing removed.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg.checks import integer, real
from hexaleg.errors import DivergedSolveError, InfeasibleForcesError, UnreachableTargetError
from hexaleg.motion.trajectory import SEMI_IMPLICIT, Motion
from hexaleg.optimal.backend import crocoddyl_module
from hexaleg.optimal.periodic import periodicity_gap
from hexaleg.optimal.problem import OptimalProblem
from hexaleg.optimal.residual import EULER_STEP, KNOT_ACCELERATION, dynamics_residual, rnea_residual
from hexaleg.optimal.task_space import task_space_motion
from hexaleg.robot.model import Robot

crocoddyl = crocoddyl_module()
_CallbackAbstract: Any = crocoddyl.CallbackAbstract
"""Crocoddyl's callback base class (typed Any: Crocoddyl ships no type information)."""


@dataclass(frozen=True)
class OptimalResult:
    """An optimal cycle.

    Attributes:
        motion: The solver's knots as a Motion (N samples ``dt`` apart, ``info["source"] =
            "optimal"``, ``info["integrator"]`` semi-implicit, absent for a Runge–Kutta knot):
            what the solver planned and booked, not a motion to play (between its knots the
            stance feet are not held).
        task_space: The cycle rebuilt in task space (:mod:`~hexaleg.optimal.task_space`,
            :data:`PER_KNOT` samples a knot): the optimal motion that hexaleg's pipeline predicts,
            a simulation plays and a motion file holds; None where it cannot be rebuilt
            (:attr:`unbuilt` says why).
        torques: Motor torque of every joint at every knot, (N, nj), N·m.
        spring_torques: Spring torque of every joint at every knot, (N, nj), N·m.
        forces: Each leg's foot force in world axes, (N, n_legs, 3), N (zero in swing).
        x: The states at the knots and the final one, (N + 1, nq + nv).
        energy: Electrical energy of the cycle by the exact model, J.
        energy_per_metre: ``energy / distance``, J/m.
        residual: Largest Newton–Euler residual (:mod:`~hexaleg.optimal.residual`) by the
            knots' own check, :attr:`residual_check`, N·m.
        residual_check: Which: :data:`~hexaleg.optimal.residual.EULER_STEP` on Euler knots,
            :data:`~hexaleg.optimal.residual.KNOT_ACCELERATION` on Runge–Kutta knots (with
            :attr:`defect`, their other half).
        defect: The knots' largest defect stepped by their own integrator (:func:`knot_defect`),
            in the state's tangent units (m, rad, m/s, rad/s).
        iterations: Box-FDDP iterations run, those that closed the gap and those of the
            continuation's lower rungs (module docstring) included.
        converged: Whether the solver met its stopping criterion (``stationarity ≤ threshold``).
        stationarity: The stopping criterion's value at the end (module docstring).
        threshold: The solver's stopping threshold ``th_stop``.
        dynamic_gap: Largest integration defect at the end.
        periodicity: ``‖x_N ⊖ H·x_0‖∞`` at the end.
        friction_use: Largest ``‖λ_t‖ / (μ λ_z)`` of a stance foot (1 is the cone's edge).
        slip: Largest speed of a stance foot, m/s: its velocity at a knot or its travel from one
            stance knot to the next over ``dt`` (what a servo tracking the knots sees), whichever
            is larger (0 for feet that hold).
        drift: Largest distance of a stance foot from its foothold at a knot, m
            (:attr:`~hexaleg.optimal.problem.OptimalProblem.footholds`).
        seconds: Wall time of the solve, s.
        unbuilt: Why :attr:`task_space` is None (the rebuild's error: a foot out of reach
            between knots, a two-point phase it cannot balance), else ``""``.
    """

    motion: Motion
    task_space: Motion | None
    torques: np.ndarray
    spring_torques: np.ndarray
    forces: np.ndarray
    x: np.ndarray
    energy: float
    energy_per_metre: float
    residual: float
    residual_check: str
    defect: float
    iterations: int
    converged: bool
    stationarity: float
    threshold: float
    dynamic_gap: float
    periodicity: float
    friction_use: float
    slip: float
    drift: float
    seconds: float
    unbuilt: str = ""


PER_KNOT = 8
"""Samples a knot of :attr:`OptimalResult.task_space` (5.6 ms on the default robot's 40 knots:
finer than the gaits' 200 samples a cycle; the simulation's reference interpolates between
them)."""


CLOSING = 10
"""Iterations of each call that closes the dynamics gap past ``OptimalParams.iterations``
(module docstring)."""


class _Progress(_CallbackAbstract):
    """One line every ``every`` box-FDDP iterations to ``say``, the iterations of earlier calls
    of the same solve (``done``) counted in."""

    def __init__(self, say: Callable[[str], None], every: int = 1) -> None:
        _CallbackAbstract.__init__(self)
        self.say, self.every, self.done = say, every, 0

    def __call__(self, solver: Any) -> None:
        count = self.done + solver.iter
        if count % self.every:
            return
        self.say(f"iteration {count}: cost {solver.cost:.6g}, stop {solver.stop:.3g}, "
                 f"gap {solver.ffeas:.3g}")


def _forces(robot: Robot, built: OptimalProblem) -> np.ndarray:
    """Each leg's foot force in world axes at every running knot, (N, n_legs, 3): the contact
    data's ``f``, the force in the contact's own coordinates — world-aligned axes at the foot
    for the ``LOCAL_WORLD_ALIGNED`` contacts of :mod:`~hexaleg.optimal.problem`; of a
    Runge–Kutta knot, its first stage's (the dynamics at the knot's state)."""
    n = len(built.problem.runningModels)
    out = np.zeros((n, len(robot.legs), 3))
    for k, data in enumerate(built.problem.runningDatas):
        differential = (data.differential if built.params.integrator == "euler"
                        else data.differential[0])
        contacts = differential.multibody.contacts.contacts.todict()
        for j, leg in enumerate(robot.legs):
            if leg.name in contacts:
                out[k, j] = contacts[leg.name].f.linear
    return out


RUNGS = {"euler": (), "rk2": ("euler",), "rk3": ("euler", "rk2"), "rk4": ("euler", "rk2")}
"""The knots a fresh start is solved on first, in order, before each integrator's own (module
docstring)."""


def _box_fddp(built: OptimalProblem, xs: list[np.ndarray], us: list[np.ndarray],
              progress: _Progress | None) -> tuple[Any, int, bool]:
    """Box-FDDP on ``built`` from ``xs``, ``us``: ``OptimalParams.iterations``, then the
    closing calls while the gap is open (module docstring). Returns the solver, the iterations
    run and whether it met its stopping criterion; ``progress`` counts on from its ``done``."""
    params = built.params
    solver = crocoddyl.SolverBoxFDDP(built.problem)
    solver.th_stop = params.stop
    if progress is not None:
        solver.setCallbacks([progress])
    before = 0 if progress is None else progress.done
    with np.errstate(invalid="ignore", over="ignore"):  # a trial step's non-finite rollout
        converged = bool(solver.solve(xs, us, params.iterations, False))
        done = int(solver.iter)
        budget = params.iterations + params.closing
        while solver.ffeas > params.gap and done < budget:
            if progress is not None:
                progress.done = before + done
            converged = bool(solver.solve(list(solver.xs), list(solver.us),
                                          min(CLOSING, budget - done), False, solver.preg))
            if not solver.iter:  # a call that took no step would take none again
                break
            done += int(solver.iter)
    if progress is not None:
        progress.done = before + done
    if not (np.isfinite(np.array(solver.xs)).all() and np.isfinite(np.array(solver.us)).all()):
        raise DivergedSolveError(f"the optimal-control solve on {params.integrator} knots "
                                 f"ended on non-finite states or controls after {done} "
                                 "iterations; a Runge–Kutta solve starts from Euler's optimum "
                                 "(solve without warm)")
    return solver, done, converged


def knot_defect(built: OptimalProblem, x: np.ndarray, u: np.ndarray) -> float:
    """The largest defect ``‖x_{k+1} ⊖ f(x_k, u_k)‖∞`` of the knots' states ``x`` (N + 1, nx)
    and controls ``u`` (N, nu), each knot stepped by ``built``'s own integrator (Crocoddyl's
    ``calc`` of the knot; ``⊖`` the state's difference): what the solver's ``ffeas`` measures,
    computed again on the answer; 0 for a trajectory of the knots' dynamics."""
    problem = built.problem
    worst = 0.0
    for k, (model, data) in enumerate(zip(problem.runningModels, problem.runningDatas,
                                          strict=True)):
        model.calc(data, x[k], u[k])
        worst = max(worst, float(np.abs(built.state.diff(data.xnext, x[k + 1])).max()))
    return worst


def solve(robot: Robot, built: OptimalProblem, *, say: Callable[[str], None] | None = None,
          warm: tuple[np.ndarray, np.ndarray] | None = None, every: int = 1,
          move: float = 0.0) -> OptimalResult:
    """Solve ``built`` by box-FDDP (module docstring): from a fresh start on Runge–Kutta knots,
    by continuation through :data:`RUNGS`.

    Args:
        robot: The robot the problem was built for.
        built: The problem (:func:`~hexaleg.optimal.problem.build_problem`).
        say: Where the iterations' progress lines go (None: nowhere).
        every: One line every this many iterations (≥ 1).
        warm: States (N + 1, nx) and controls (N, nu) on ``built``'s knots to start from
            instead of the warm start's states and their quasi-static controls (and the
            continuation's rungs).
        move: The start's base height raised by this much at every knot, m (module docstring;
            the quasi-static controls of a fresh start are those of the moved states).

    Raises:
        DivergedSolveError: the solve ended on non-finite states or controls.
    """
    problem = built.problem
    params = built.params
    progress = None if say is None else _Progress(say, integer("every", every, low=1))
    lift = real("move", move)
    xs = [np.array(x) for x in (built.x_warm if warm is None else warm[0])]
    for x in xs:
        x[2] += lift  # the free flyer's z
    start = time.perf_counter()
    done = 0
    if warm is None:
        us = None
        for rung in RUNGS[params.integrator]:
            lower = built.on_knots(rung)
            lower_us = list(lower.problem.quasiStatic(xs[:-1])) if us is None else us
            solver, n, _ = _box_fddp(lower, xs, lower_us, progress)
            done += n
            xs, us = [np.array(x) for x in solver.xs], [np.array(u) for u in solver.us]
            if say is not None:
                say(f"solved on {rung} knots ({n} iterations, gap {solver.ffeas:.3g}): the "
                    f"start of the next")
        if us is None:
            us = list(problem.quasiStatic(xs[:-1]))
    else:
        us = [np.array(u) for u in warm[1]]
    solver, n, converged = _box_fddp(built, xs, us, progress)
    done += n
    seconds = time.perf_counter() - start
    x, u = np.array(solver.xs), np.array(solver.us)
    problem.calc(list(x), list(u))
    nq = robot.model.nq
    springs = np.array([built.actuation.spring_torques(xk) for xk in x[:-1]])
    forces = _forces(robot, built)
    if params.integrator == "euler":
        check = EULER_STEP
        residual = dynamics_residual(robot, x[:, :nq], x[:, nq:], built.dt, u + springs, forces)
    else:  # each knot's own acceleration: its first stage's, the dynamics at its state
        check = KNOT_ACCELERATION
        a = np.array([data.differential[0].xout for data in problem.runningDatas])
        residual = rnea_residual(robot, x[:-1, :nq], x[:-1, nq:], a, u + springs, forces)
    defect = knot_defect(built, x, u)
    energy = float(sum(built.power.exact(uk, xk[nq + 6:]).sum() for uk, xk in
                       zip(u, x[:-1], strict=True)) * built.dt)
    mu = built.params.mu
    stance = np.linalg.norm(forces, axis=2) > 0
    tangential = np.linalg.norm(forces[..., :2], axis=2)
    use = np.where(stance, tangential / np.maximum(mu * forces[..., 2], 1e-12), 0.0)
    n = len(u)
    feet = np.zeros((n, len(robot.legs), 3))
    speed = np.zeros((n, len(robot.legs)))
    world = pin.LOCAL_WORLD_ALIGNED
    for k in range(n):
        pin.forwardKinematics(robot.model, robot.data, x[k, :nq], x[k, nq:])
        pin.updateFramePlacements(robot.model, robot.data)
        feet[k] = [robot.data.oMf[leg.foot_frame_id].translation for leg in robot.legs]
        speed[k] = [np.linalg.norm(pin.getFrameVelocity(robot.model, robot.data,
                                                        leg.foot_frame_id, world).linear)
                    for leg in robot.legs]
    motion = Motion(t=np.arange(n) * built.dt, q=x[:-1, :nq].copy(), v=x[:-1, nq:].copy(),
                    a=np.diff(x[:, nq:], axis=0) / built.dt, stance=built.stance.copy(),
                    feet=feet, period=built.period, distance=built.distance,
                    info={"source": "optimal", "cycle": built.displacement.tolist(),
                          **({"integrator": SEMI_IMPLICIT} if params.integrator == "euler"
                             else {}),
                          "knots": n, "energy_per_metre": energy / built.distance
                          if built.distance > 0 else float("nan")})
    try:  # a cycle that is not rebuilt is still the solver's answer: the caller says why
        rebuilt: Motion | None = task_space_motion(robot, motion, built.footholds,
                                                   per_knot=PER_KNOT)
        unbuilt = ""
    except (UnreachableTargetError, InfeasibleForcesError) as err:
        rebuilt, unbuilt = None, str(err)
    return OptimalResult(
        motion=motion,
        task_space=rebuilt, unbuilt=unbuilt,
        torques=u, spring_torques=springs, forces=forces, x=x, energy=energy,
        energy_per_metre=energy / built.distance if built.distance > 0 else float("inf"),
        residual=float(np.abs(residual).max()), residual_check=check, defect=defect,
        iterations=done,
        converged=converged, stationarity=float(solver.stop), threshold=float(solver.th_stop),
        dynamic_gap=float(solver.ffeas),
        periodicity=periodicity_gap(x, built.displacement, built.state.diff),
        friction_use=float(use.max()), slip=_slip(feet, speed, built.stance, built.dt),
        drift=float(np.max(np.linalg.norm(feet - built.footholds, axis=2) * built.stance)),
        seconds=seconds)


def _slip(feet: np.ndarray, speed: np.ndarray, stance: np.ndarray, dt: float) -> float:
    """The largest speed of a stance foot (:attr:`OptimalResult.slip`): ``speed`` (N, n_legs)
    at the knots, and the travel of ``feet`` (N, n_legs, 3) between two consecutive stance knots
    of one stance over ``dt`` (the cycle's last knot and its first belong to different cycles,
    so that pair is left out)."""
    held = stance[1:] & stance[:-1]
    travel = np.linalg.norm(np.diff(feet, axis=0), axis=2) / dt
    return float(max(np.max(speed * stance), np.max(travel * held, initial=0.0)))
