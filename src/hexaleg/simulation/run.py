"""Simulate a gait with and without springs and compare the energy with the analysis' prediction.

:func:`simulate` analyses the gait (:func:`hexaleg.dynamics.prepare.prepare`, the springs' and the
baseline's motor torques — the feedforward of the ``"feedforward"`` controller), builds the MuJoCo
model twice (:func:`hexaleg.simulation.model.build_model`, with and without the springs),
runs each for :attr:`Settings.cycles` cycles from the planned initial state, lets the first
cycles settle and evaluates the last :attr:`Settings.evaluate`
(:mod:`hexaleg.simulation.measures`). The energy per cycle comes from the simulated motor
torques and speeds through :func:`hexaleg.dynamics.energy.metrics`, the module the prediction uses,
so the two differ only by what the simulation adds: contact compliance and friction, servo
dynamics and saturation, the load handover taking time instead of one sample.

How to simulate is :class:`~hexaleg.simulation.settings.Settings`; what it returns, both runs
(:class:`~hexaleg.simulation.result.Run`) in one :class:`~hexaleg.simulation.result.Simulation`.
"""

from __future__ import annotations

import threading
import time
from concurrent.futures import FIRST_EXCEPTION, ThreadPoolExecutor, wait
from typing import Any

import numpy as np

from hexaleg.dynamics.analysis import Analysis
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import Prepared, prepare
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet
from hexaleg.simulation import balance, falls, measures, pressure, stepping
from hexaleg.simulation.controllers import controls, reference
from hexaleg.simulation.model import SimModel, build_model
from hexaleg.simulation.result import Run, Simulation
from hexaleg.simulation.settings import Settings
from hexaleg.simulation.timestep import automatic_timestep, check_steps, cycle_timestep


def simulate_run(name: str, sim: SimModel, motion: Motion, analysis: Analysis,
                 settings: Settings, feedback: bool = False,
                 stop: threading.Event | None = None) -> Run:
    """Run one model for :attr:`Settings.cycles` cycles and measure the last ones.

    Args:
        name: ``"springs"`` or ``"baseline"``.
        sim: The model (with or without the springs).
        motion: The gait.
        analysis: Its analysis with the same springs (feedforward torques, predicted forces).
        settings: The settings.
        feedback: Close the loop on the body (:class:`~hexaleg.simulation.balance.Balance`,
            every :func:`~hexaleg.simulation.control_rate.control_period`).
        stop: Set from another thread, the stepping ends at its next chunk
            (:class:`~hexaleg.simulation.stepping.Stopped`).
    """
    dt = sim.timestep
    steps = round(motion.period / dt)
    t = np.arange(settings.cycles * steps) * dt
    ref = reference(motion, analysis.tau_motor, t)
    ctrl = controls(sim.servo, ref, sim.kp, sim.kd, torques=feedback)
    qpos0, qvel0 = sim.joints.to_mujoco(motion.q[0], motion.v[0])
    controller = (balance.Balance(sim, motion, analysis.forces, analysis.tau_motor)
                  if feedback else None)
    import mujoco.rollout  # noqa: F401  # the stepping's (1.4–14 ms the first time): in no timing
    start, cpu = time.perf_counter(), time.thread_time()
    traj = stepping.run(sim, ctrl, qpos0, qvel0, float(np.mean(motion.q[:, 2])),
                        None if controller is None else controller.correction,
                        max(1, round(controller.gains.period / dt)) if controller else 1, stop)
    wall, cpu = time.perf_counter() - start, time.thread_time() - cpu
    bound = controller.constrained / max(controller.updates, 1) if controller else 0.0
    if traj.verdict == "fell":
        cause = falls.fall_cause(sim, motion, traj, feedback, analysis.tau_motor)
        return Run(name, sim, traj, traj.verdict, f"{traj.message}; {cause.message}",
                   wall=wall, feedback=feedback, constrained=bound, cpu=cpu, started=start,
                   reason="" if cause.stand is None else cause.stand.reason)
    if traj.verdict != "ran":
        return Run(name, sim, traj, traj.verdict, traj.message, wall=wall, feedback=feedback,
                   constrained=bound, cpu=cpu, started=start)
    window = slice((settings.cycles - settings.evaluate) * steps, settings.cycles * steps)
    cycles = measures.cycle_energies(sim, traj, window, settings.evaluate, analysis.motor)
    forces = (measures.foot_forces(sim, motion, traj, window, analysis.forces,
                                   settings.force_samples) if settings.force_samples else {})
    walked = measures.walk(sim, motion, traj, window, settings.evaluate, ref.q)
    verdict, message = measures.verdict(walked, motion.distance)
    margin, alone = pressure.cop_margins(sim, motion, traj, window)
    tipped = pressure.tipping(alone)
    if verdict == "walks" and tipped is not None:
        verdict, message = "tipped", tipped
    return Run(name, sim, traj, verdict, message, cycles, measures.mean_metrics(cycles),
               walked, forces, wall, feedback, bound, cpu, start, cop_margin=margin,
               alone_margin=alone)


def side_by_side(jobs: dict[str, tuple[SimModel, Analysis]], motion: Motion,
                 settings: Settings, feedback: bool) -> dict[str, Run]:
    """:func:`simulate_run` of each ``name → (model, analysis)``, on a thread each: MuJoCo's
    rollout releases Python's lock while it steps, so the springs' run and the baseline step on
    two cores at once (closed loop, one steps while the other's controller updates). Each run
    has its own model, MuJoCo data and controller, so its steps are the same to the bit as
    alone (``tests/simulation/test_run.py``); its ``wall`` and ``cpu`` are its own thread's.
    Where one run fails, or Ctrl-C (a kill) reaches this thread while it waits, the other
    stops at its next chunk (:class:`~hexaleg.simulation.stepping.Stopped`), not at its end,
    and the first error is raised."""
    if len(jobs) < 2:
        return {name: simulate_run(name, sim, motion, a, settings, feedback)
                for name, (sim, a) in jobs.items()}
    stop = threading.Event()
    with ThreadPoolExecutor(max_workers=len(jobs)) as pool:
        futures = {name: pool.submit(simulate_run, name, sim, motion, a, settings, feedback,
                                     stop) for name, (sim, a) in jobs.items()}
        try:
            wait(futures.values(), return_when=FIRST_EXCEPTION)
            for future in sorted(futures.values(), key=lambda f: not f.done()):
                future.result()  # a failed run's error first, the other may still step
            return {name: future.result() for name, future in futures.items()}
        except BaseException:
            stop.set()
            raise


def simulate(robot: Robot, motion: Motion, motor: Any, springs: SpringSet | None = None,
             settings: Settings | None = None, *, contact: ContactParams | None = None,
             objective: str = "joule", prepared: Prepared | None = None,
             baseline: Simulation | None = None) -> Simulation:
    """Simulate ``motion`` with ``springs`` and without, and analyse both (module docstring).

    Args:
        robot: The robot.
        motion: A periodic gait of the robot.
        motor: The motor model of every joint (a Motor or a per-joint set), as for
            :func:`hexaleg.dynamics.prepare.prepare`.
        springs: The springs (SI), or None for none.
        settings: How to simulate (default :class:`Settings`).
        contact: The analysis' contact settings (its μ is the ground's unless the settings set
            one).
        objective: The analysis' force objective.
        prepared: The gait already prepared with ``motor`` and ``contact`` (saves the RNEA).
        baseline: A simulation of the same gait, motor, contact, objective and settings whose
            baseline run (the robot without springs) is reused instead of simulated again: a
            design that simulates many candidate springs runs the baseline once.

    Returns:
        Both runs and the analyses.

    Raises:
        InvalidParameterError: bad settings, a timestep too large for the gait or for explicit
            stability, a run of more steps than the memory budget allows (a timestep too small
            or too many cycles, :func:`hexaleg.simulation.timestep.check_steps`: refused
            before the analysis when the timestep is given), a non-periodic motion.
        UnknownNameError: springs on joints the robot does not have.
        InfeasibleForcesError: the analysis has no admissible contact forces.
        TorqueLimitError: the analysis needs more than the motor's stall torque.
    """
    import mujoco.rollout  # noqa: F401  # loaded before the clock: imports are in no timing

    start = time.perf_counter()
    settings = (settings or Settings()).sized(robot.mass)
    springs = springs if springs is not None else SpringSet()
    contact = contact or ContactParams()
    if not motion.periodic or motion.fixed_base:
        raise InvalidParameterError("motion", "a fixed-base or non-periodic motion",
                                    "a periodic gait (hexaleg.gait)")
    if settings.timestep is not None:  # before the analysis and any model: nothing allocated
        check_steps(robot, settings.cycles, motion.period, settings.timestep, given=True)
    prepared = prepared or prepare(robot, motion, motor=motor, contact=contact)
    analysis = prepared.evaluate(springs, objective)
    base = prepared.evaluate(None, objective)
    if baseline is not None and (baseline.settings != settings or baseline.motion is not motion
                                 or baseline.prepared.motor is not prepared.motor):
        raise InvalidParameterError(
            "baseline", "a simulation of another gait, motor or settings",
            "a simulation of this gait with this motor and these settings")
    servo, ground = settings.servo(), settings.ground(contact.mu)
    like: SimModel | None = None  # a model built: the others take its bodies and contacts
    if baseline is not None:
        dt, like = baseline.baseline.sim.timestep, baseline.baseline.sim
    elif settings.timestep is not None:
        dt = cycle_timestep(settings.timestep, motion.period)
    else:
        like = build_model(robot, motion, prepared.motor, servo=servo, ground=ground,
                           check=False)
        dt = cycle_timestep(automatic_timestep(robot, motion, prepared.motor, servo, ground,
                                               like), motion.period)
    check_steps(robot, settings.cycles, motion.period, dt,
                given=settings.timestep is not None)
    closed = settings.feedback == "on" or (settings.feedback == "auto" and balance.needed(motion))
    runs = {} if baseline is None or baseline.baseline.feedback != closed else {
        "baseline": baseline.baseline}
    models: dict[str, SimModel] = {}
    for name, s in (("springs", springs), ("baseline", SpringSet())):
        if name not in runs:
            models[name] = build_model(robot, motion, prepared.motor, springs=s, servo=servo,
                                       ground=ground, timestep=dt, like=like)
            like = like or models[name]
    analyses = {"springs": analysis, "baseline": base}
    runs |= side_by_side({name: (sim, analyses[name]) for name, sim in models.items()},
                         motion, settings, closed)
    if settings.feedback == "auto" and not closed and any(r.verdict == "fell"
                                                          for r in runs.values()):
        closed = True  # fell: close it
        runs = side_by_side({name: (models.get(name) or runs[name].sim, analyses[name])
                             for name in analyses}, motion, settings, closed)
    return Simulation(robot, motion, settings, springs, analysis, base, runs["springs"],
                      runs["baseline"], prepared, time.perf_counter() - start)
