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
"""

from __future__ import annotations

import dataclasses
import math
import threading
import time
from concurrent.futures import FIRST_EXCEPTION, ThreadPoolExecutor, wait
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from hexaleg.checks import integer, one_of, real
from hexaleg.config import from_mapping
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.energy import saving
from hexaleg.dynamics.prepare import Analysis, Prepared, prepare
from hexaleg.errors import InvalidParameterError, SimulationError
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet
from hexaleg.simulation import balance, falls, measures, pressure, stepping
from hexaleg.simulation.controllers import COMPLIANCE, Servo, controls, reference
from hexaleg.simulation.ground import Ground
from hexaleg.simulation.model import SimModel, build_model
from hexaleg.simulation.timestep import automatic_timestep, check_steps, cycle_timestep

VERDICTS: tuple[str, ...] = ("walks", "stalled", "short", "overran", "untracked", "tipped",
                              "fell", "diverged")
"""How a run ended (:func:`hexaleg.simulation.measures.verdict`): it walked — the planned distance
within :data:`~hexaleg.simulation.measures.DISTANCE_TOLERANCE` and the RMS tracking error within
:data:`~hexaleg.simulation.measures.TRACKING_BOUND`; it stood but covered less than
:data:`STALL` of the planned distance; it fell short of or overran the tolerance; it covered the
distance without following the joints' gait; it walked, but on soles the robot rolled about
the edge of its one sole on the ground (:func:`hexaleg.simulation.pressure.tipping`); the base
fell; the integration diverged."""
STALL = measures.STALL
"""A run that covers less than this fraction of the planned distance per cycle stalled."""
GROUND_MASS = 1.36366
"""kg: the built-in robot's mass, whose ground :data:`GROUND_STIFFNESS` and
:data:`GROUND_DAMPING` are (:meth:`Settings.sized` scales them to another robot's)."""
GROUND_STIFFNESS = 2e4
"""N/m per contact: a rubber-tipped foot on a hard floor, 0.2 mm under the 4.5 N of a tripod foot
of the built-in robot (:class:`~hexaleg.simulation.ground.Ground`)."""
GROUND_DAMPING = 100.0
"""N·s/m per contact: damping ratio ≈ 0.5 for the third of the built-in robot's mass a tripod
foot carries."""


def verdict_meanings() -> dict[str, str]:
    """What each verdict of :data:`VERDICTS` means (:func:`hexaleg.simulation.measures.verdict`,
    and the runs that did not reach the end), in words with the bounds, for the pages."""
    tol, bound = measures.DISTANCE_TOLERANCE, measures.TRACKING_BOUND * 1e3
    return {
        "walks": (f"it covered the planned distance per cycle within ±{tol:.0%} and followed "
                  f"the joints' gait (RMS tracking error at most {bound:.0f} mrad)"),
        "stalled": f"it stood but covered less than {STALL:.0%} of the planned distance per cycle",
        "short": f"it covered {STALL:.0%} to {1 - tol:.0%} of the planned distance per cycle",
        "overran": f"it covered more than {1 + tol:.0%} of the planned distance per cycle",
        "untracked": (f"it covered the distance, but its joints did not follow the gait (RMS "
                      f"tracking error over {bound:.0f} mrad)"),
        "tipped": (f"it covered the distance and followed the joints, but in single support "
                   f"its sole's centre of pressure came within {pressure.TIP_MARGIN * 1e3:g} mm "
                   "of the sole's edge: the robot rolled about the edge instead of standing "
                   "on the sole"),
        "fell": (f"the body fell: its height under {stepping.FALL_HEIGHT:.0%} of the planned "
                 f"or its roll or pitch beyond ±{np.degrees(stepping.FALL_TILT):.0f}°"),
        "diverged": "the integration diverged",
    }


@dataclass(frozen=True)
class Settings:
    """How to simulate (the ``[simulate]`` table of a config file; SI).

    Attributes:
        controller: ``"feedforward"`` or ``"position"``
            (:data:`hexaleg.simulation.controllers.CONTROLLERS`).
        timestep: s, > 0, below the gait's sample spacing; None (default): automatic, the least
            of :data:`~hexaleg.simulation.model.TIMESTEP`, half the gait's sample spacing
            and 80 % of the explicit-stability limit
            (:func:`hexaleg.simulation.timestep.automatic_timestep`). Rounded down so that a
            cycle is a whole number of steps.
        cycles: Cycles simulated, ≥ 2.
        evaluate: The last cycles evaluated, in [1, cycles − 1] (the others settle).
        stiffness: Ground contact stiffness K, N/m, > 0; None (default): sized to the robot,
            ``K₀ m / m₀`` (:meth:`sized`: the built-in robot's 2·10⁴ N/m scaled by the mass, so
            a foot sinks as far under its share of any robot's weight).
        damping: Ground contact damping B, N·s/m, ≥ 0; None (default): ``B₀ m / m₀`` (100
            N·s/m scaled: B ∝ √(K m) keeps the contact's damping ratio).
        mu: Friction coefficient, > 0; None: the analysis' (``ContactParams.mu``).
        noslip: MuJoCo's no-slip pass (no creep inside the friction cone).
        incline: Ground slope, rad (uphill along the heading > 0).
        feedback: Balance feedback (:mod:`hexaleg.simulation.balance`): ``"auto"`` (default)
            where the gait needs it — fewer than three planned stance feet at some instant, or
            an open-loop run that fell (both runs are then simulated again with it) —
            ``"on"`` or ``"off"`` (open loop: the servos track the plan alone).
        compliance: Servo compliance angle θ_c (kp = τ_s/θ_c), rad, > 0.
        kp_scale: Factor on kp, > 0.
        kd_scale: Factor on kd, > 0.
        force_samples: Steps at which the foot forces are compared with the analysis' (0: none).

    Raises:
        InvalidParameterError: a value out of range (named).
        UnknownNameError: an unknown controller (lists them).
    """

    controller: str = "feedforward"
    timestep: float | None = None
    cycles: int = 4
    evaluate: int = 2
    stiffness: float | None = None
    damping: float | None = None
    mu: float | None = None
    noslip: bool = False
    incline: float = 0.0
    feedback: str = "auto"
    compliance: float = COMPLIANCE
    kp_scale: float = 1.0
    kd_scale: float = 1.0
    force_samples: int = 200

    def __post_init__(self) -> None:
        if self.timestep is not None:
            real("timestep", self.timestep, low=0.0, low_open=True,
                 allowed="a finite timestep > 0 s (e.g. 0.0005), or none for the automatic one")
        self.servo()
        one_of("feedback", self.feedback, balance.MODES)
        self.ground(ContactParams().mu)
        integer("cycles", self.cycles, low=2, high=10_000)
        integer("evaluate", self.evaluate, low=1, high=self.cycles - 1)
        integer("force_samples", self.force_samples, low=0)

    def servo(self) -> Servo:
        """The servo of these settings."""
        return Servo(self.controller, self.compliance, self.kp_scale, self.kd_scale)

    def sized(self, mass: float) -> Settings:
        """These settings with the ground sized to a robot of ``mass`` kg where they leave it
        unset: ``K = K₀ m / m₀``, ``B = B₀ m / m₀`` with :data:`GROUND_STIFFNESS`,
        :data:`GROUND_DAMPING` for the built-in robot's :data:`GROUND_MASS` (the same sink
        ``m g / (n K)`` under the same feet, the same damping ratio ``B / (2 √(K m / n))``:
        Hunt–Crossley's linear limit, the spring-damper ground of MuJoCo's ``solref``)."""
        ratio = mass / GROUND_MASS
        return dataclasses.replace(
            self, stiffness=GROUND_STIFFNESS * ratio if self.stiffness is None else self.stiffness,
            damping=GROUND_DAMPING * ratio if self.damping is None else self.damping)

    def ground(self, mu: float) -> Ground:
        """The ground of these settings (``mu`` unless :attr:`mu` is set; an unsized stiffness
        or damping the built-in robot's, :meth:`sized` first for another robot)."""
        return Ground(GROUND_STIFFNESS if self.stiffness is None else self.stiffness,
                      GROUND_DAMPING if self.damping is None else self.damping,
                      mu if self.mu is None else self.mu, self.noslip, self.incline)

    @classmethod
    def from_mapping(cls, table: Any, where: str = "simulate") -> Settings:
        """From a TOML table (unknown keys are an error listing the valid ones)."""
        return from_mapping(cls, table, where)


@dataclass(frozen=True, eq=False)
class Run:
    """One simulation of the gait (with the springs or without: the baseline).

    Attributes:
        name: ``"springs"`` or ``"baseline"``.
        sim: The model.
        trajectory: The recorded run.
        verdict: One of :data:`VERDICTS`.
        message: When and how a run that did not walk ended.
        cycles: :func:`hexaleg.dynamics.energy.metrics` of each evaluated cycle (empty when it
            fell or diverged).
        metrics: Their totals averaged per cycle (J, N·m; empty when it fell or diverged).
        walk: Distance, drift, tracking, slip, contacts (None when it fell or diverged).
        forces: Foot forces against the analysis' (:func:`measures.foot_forces`), or empty.
        wall: Wall-clock time of the stepping (MuJoCo's steps and, closed loop, the balance
            controller's updates between them), s.
        cpu: CPU time of the thread that stepped, over the same span, s: ``wall`` less the
            time the machine gave to other processes (:attr:`cpu_share`).
        started: When its stepping began, s on :func:`time.perf_counter`'s clock (two runs
            that stepped at once overlap: :attr:`Simulation.stepping_wall`).
        feedback: Whether the balance controller ran (:mod:`hexaleg.simulation.balance`).
        constrained: Of its updates, the fraction at which a friction cone bound the force
            correction (0 open loop).
        reason: Why it fell in one clause where the gait alone explains it (a stand on one
            point foot, or on two longer than the balance controller holds, that the
            controller ran on: :class:`~hexaleg.simulation.falls.PointFoot`), else "".
        cop_margin: On soles, how close the centre of pressure came to a sole's edge over the
            evaluated window (:func:`hexaleg.simulation.pressure.cop_margins`); None on point
            feet or when it did not run to the end.
        alone_margin: The same over the single supports only, the robot's own
            tipping margin (:func:`hexaleg.simulation.pressure.tipping`); None also when the
            gait has no single support.
    """

    name: str
    sim: SimModel
    trajectory: stepping.Trajectory
    verdict: str
    message: str
    cycles: list[dict[str, Any]] = field(default_factory=list)
    metrics: dict[str, float] = field(default_factory=dict)
    walk: measures.Walk | None = None
    forces: dict[str, float] = field(default_factory=dict)
    wall: float = 0.0
    feedback: bool = False
    constrained: float = 0.0
    cpu: float = 0.0
    started: float = 0.0
    reason: str = ""
    cop_margin: pressure.CopMargin | None = None
    alone_margin: pressure.CopMargin | None = None

    @property
    def walks(self) -> bool:
        """Whether the robot walked the whole run."""
        return self.verdict == "walks"

    @property
    def simulated_time(self) -> float:
        """Time the run covered (its recorded steps), s."""
        return self.trajectory.n * self.sim.timestep

    @property
    def realtime_factor(self) -> float:
        """Simulated time per wall-clock time of the stepping (the model's building, the
        analysis and the measures left out: :attr:`Simulation.wall` holds them)."""
        return self.simulated_time / self.wall if self.wall > 0 else math.inf

    @property
    def cpu_share(self) -> float:
        """The stepping thread's CPU time over its wall time: 1 on a core of its own, ½ where
        another process shared it (the real-time factor is then halved by the machine, not by
        the simulation)."""
        return self.cpu / self.wall if self.wall > 0 else 1.0


@dataclass(frozen=True, eq=False)
class Simulation:
    """The gait simulated with and without the springs, beside the analysis.

    Attributes:
        robot: The robot. motion: The gait. settings: How it was simulated.
        springs: The springs simulated.
        analysis: The analysis with the springs (its ``baseline`` metrics are without).
        baseline_analysis: The analysis without springs.
        with_springs: The run with the springs. baseline: The run without.
        prepared: The prepared gait (reused by reruns with other settings).
        wall: Wall-clock time of :func:`simulate`, s: the analysis with and without the
            springs, the timestep's probe, building the models, both runs and their measures
            (and the gait's inverse dynamics where ``prepared`` was not given); not MuJoCo's
            import, which a process's first simulation loads before the clock starts.
    """

    robot: Robot
    motion: Motion
    settings: Settings
    springs: SpringSet
    analysis: Analysis
    baseline_analysis: Analysis
    with_springs: Run
    baseline: Run
    prepared: Prepared
    wall: float = 0.0

    @property
    def walks(self) -> bool:
        """Whether both runs walked."""
        return self.with_springs.walks and self.baseline.walks

    @property
    def stepping_wall(self) -> float:
        """Wall-clock time in which one of the two runs stepped, s: the union of their
        stepping spans (:func:`side_by_side` steps them at once; a baseline reused from
        another simulation stepped apart, its span its own)."""
        spans = sorted((r.started, r.started + r.wall) for r in (self.with_springs, self.baseline))
        (a0, a1), (b0, b1) = spans
        return (a1 - a0) + max(0.0, b1 - max(a1, b0))

    def predicted(self, metric: str = "electrical") -> tuple[float, float, float]:
        """The analysis' ``(with springs, baseline, saving)`` of a metric (J or N·m per cycle,
        saving a fraction)."""
        a = self.analysis
        return (a.metrics["total"][metric], a.baseline["total"][metric],
                a.savings["total"][metric])

    def simulated(self, metric: str = "electrical") -> tuple[float, float, float]:
        """The simulation's ``(with springs, baseline, saving)`` of a metric per cycle.

        Raises:
            SimulationError: a run did not walk (its verdict and message).
        """
        for r in (self.with_springs, self.baseline):
            if not r.walks:
                raise SimulationError(f"the {r.name} run {r.verdict}: {r.message}")
        w, b = self.with_springs.metrics[metric], self.baseline.metrics[metric]
        return w, b, saving(w, b)


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
