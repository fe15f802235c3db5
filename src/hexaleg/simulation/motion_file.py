"""The simulated motion of a run, written by ``hexaleg simulate`` for ``hexaleg view`` to replay.

One NumPy ``.npz`` file per run in the out directory, :data:`FILES`: ``motion-springs.npz`` (the
run with the springs) and ``motion-baseline.npz`` (without), every ``stride``-th simulation step
so that the rows come at :data:`RECORD_FPS` per second of simulated time or a little more (the
state before the step, as the run records it, :mod:`~hexaleg.simulation.stepping`).
Read with ``numpy.load(path)`` (no pickles) or :func:`read_motion`. Keys (K rows, SI):

==============  ==================  ===================================================
key             shape               what
==============  ==================  ===================================================
``format``      ()                  :data:`FORMAT`
``robot``       ()                  the robot's name (``Robot.name``)
``run``         ()                  ``"springs"`` or ``"baseline"`` (:data:`RUNS`)
``verdict``     ()                  how the run ended (``"ran"``, ``"fell"``, ``"diverged"``)
``message``     ()                  when and how a run that did not finish ended, or ''
``joint_names`` (nj,)               the actuated joints, hexaleg's order (columns below)
``legs``        (n_legs,)           the legs, the robot's order
``timestep``    ()                  the simulation's timestep, s
``stride``      ()                  simulation steps between rows
``t``           (K,)                time, s
``q``           (K, nq)             Pinocchio configuration: base position (m), base
                                    quaternion (x, y, z, w), joint angles (rad)
``v``           (K, nv)             Pinocchio velocity: base (m/s, rad/s, base frame),
                                    joints (rad/s)
``tau_motor``   (K, nj)             motor torque at the joint ``u − D q̇``, N·m
``power``       (K, nj)             motor mechanical power ``τ_motor q̇``, W
``tau_spring``  (K, nj)             spring torque on the joint, N·m
``feet``        (K, n_legs, 3)      foot positions (MuJoCo's foot sites), world, m
``forces``      (K, n_legs, 3)      the ground's force on each foot (MuJoCo's contact
                                    force), world, N; zero off the ground
==============  ==================  ===================================================

MuJoCo's configurations are mapped to Pinocchio's by
:meth:`~hexaleg.simulation.state.JointMap.to_pinocchio`. The contact forces and spring
torques are computed at the kept rows only (``mj_forward`` of the recorded state). Reading needs
neither MuJoCo nor the model: :meth:`SimulatedMotion.check` compares the file with a robot.
"""

from __future__ import annotations

import io
import math
import zipfile
from dataclasses import dataclass, fields
from pathlib import Path

import numpy as np

from hexaleg.checks import MEMORY_BUDGET, one_of
from hexaleg.config import read_bytes, write_file
from hexaleg.errors import ConfigError, InvalidParameterError
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.simulation.measures import contact_forces, forward_states
from hexaleg.simulation.result import Run, Simulation

FORMAT = "hexaleg simulated motion 1"
"""The ``format`` entry of a motion file (a reader refuses other files)."""
RUNS: tuple[str, ...] = ("springs", "baseline")
"""The runs of ``hexaleg simulate``: with the springs and without (the keys of
``simulate.json``'s ``runs``)."""
FILES = {run: f"motion-{run}.npz" for run in RUNS}
"""Run → file name in the out directory."""
RECORD_FPS = 100.0
"""Rows kept per second of simulated time, at least: ≥ 3 per keyframe of the viewer's default
30 per second (it interpolates between rows); a row of the hexapod is 1.1 kB, 0.8 kB
compressed."""
ARRAYS: tuple[str, ...] = ("t", "q", "v", "tau_motor", "power", "tau_spring", "feet", "forces")
"""The per-row entries of a motion file (module docstring)."""


@dataclass(frozen=True, eq=False)
class SimulatedMotion:
    """A run's motion as kept in its file (module docstring: the keys, shapes and units)."""

    robot: str
    run: str
    verdict: str
    message: str
    joint_names: tuple[str, ...]
    legs: tuple[str, ...]
    timestep: float
    stride: int
    t: np.ndarray
    q: np.ndarray
    v: np.ndarray
    tau_motor: np.ndarray
    power: np.ndarray
    tau_spring: np.ndarray
    feet: np.ndarray
    forces: np.ndarray

    @property
    def rate(self) -> float:
        """Rows per second of simulated time."""
        return 1.0 / (self.stride * self.timestep)

    def check(self, robot: Robot, where: str) -> None:
        """Refuse a file of another robot (its name, joints, legs or array shapes).

        Args:
            robot: The robot to replay it on.
            where: The file, for the message.

        Raises:
            InvalidParameterError: naming the file's value and what the robot needs.
        """
        if self.robot != robot.name:
            raise InvalidParameterError(f"{where}: robot", self.robot,
                                        f"a simulation of {robot.name!r}, the robot it is "
                                        "replayed on")
        for name, mine, theirs in (("joint_names", self.joint_names, robot.joint_names),
                                   ("legs", self.legs, tuple(robot.leg_names))):
            if mine != tuple(theirs):
                raise InvalidParameterError(f"{where}: {name}", ", ".join(mine),
                                            f"those of {robot.name}: {', '.join(theirs)}")
        k, nj, legs = len(self.t), robot.nj, len(robot.legs)
        shapes = {"t": (k,), "q": (k, robot.model.nq), "v": (k, robot.model.nv),
                  "tau_motor": (k, nj), "power": (k, nj), "tau_spring": (k, nj),
                  "feet": (k, legs, 3), "forces": (k, legs, 3)}
        for name, shape in shapes.items():
            if getattr(self, name).shape != shape or k == 0:
                raise InvalidParameterError(f"{where}: {name}",
                                            f"an array of shape {getattr(self, name).shape}",
                                            f"shape {shape} for {robot.name}, K ≥ 1 rows")

    def motion(self) -> Motion:
        """The kept rows as a (non-periodic) :class:`~hexaleg.motion.trajectory.Motion`: a foot
        is in stance where the ground pushes on it; ``a`` is the finite difference of ``v`` (the
        file keeps no accelerations)."""
        n = len(self.t)
        a = np.gradient(self.v, self.t, axis=0) if n > 1 else np.zeros_like(self.v)
        return Motion(t=self.t, q=self.q, v=self.v, a=a,
                      stance=np.linalg.norm(self.forces, axis=-1) > 0.0, feet=self.feet,
                      period=n / self.rate, distance=0.0, periodic=False,
                      info={"simulated": self.run, "verdict": self.verdict})


def record(run: Run, fps: float = RECORD_FPS) -> SimulatedMotion:
    """A run's motion at ``fps`` rows per second of simulated time (or a little more: every
    ``floor(1 / (fps dt))``-th step, at least every step).

    Args:
        run: A run of :func:`hexaleg.simulation.run.simulate`.
        fps: Rows per second, > 0.
    """
    sim, traj = run.sim, run.trajectory
    stride = max(1, math.floor(1.0 / (fps * sim.timestep) + 1e-9))
    rows = np.arange(0, traj.n, stride)
    forces, springs = [], []
    for data in forward_states(sim, traj, rows):
        forces.append(contact_forces(sim, data))
        springs.append(sim.spring_torque(data))
    q, v = sim.joints.to_pinocchio(traj.qpos[rows], traj.qvel[rows])
    tau = traj.tau_motor[rows]
    robot = sim.robot
    return SimulatedMotion(
        robot=robot.name, run=run.name, verdict=traj.verdict, message=traj.message,
        joint_names=robot.joint_names, legs=tuple(robot.leg_names), timestep=sim.timestep,
        stride=stride, t=traj.t[rows], q=q, v=v, tau_motor=tau,
        power=tau * sim.joints.joints_mj(traj.qvel[rows], velocity=True),
        tau_spring=np.array(springs).reshape(len(rows), robot.nj), feet=traj.feet[rows],
        forces=np.array(forces).reshape(len(rows), len(robot.legs), 3))


def write_motion(path: str | Path, motion: SimulatedMotion) -> Path:
    """Write a motion file (compressed ``.npz``).

    Raises:
        OutputError: the file cannot be written (named).
    """
    path = Path(path)
    entries = {f.name: getattr(motion, f.name) for f in fields(motion)}
    for name in ("joint_names", "legs"):
        entries[name] = np.array(entries[name], dtype=str)
    buffer = io.BytesIO()
    np.savez_compressed(buffer, format=FORMAT, **entries)
    return write_file(path, buffer.getvalue(), "the simulated motion")


def write_motions(out: str | Path, s: Simulation, fps: float = RECORD_FPS) -> list[Path]:
    """Both runs' motion files (:data:`FILES`) in ``out`` (which must exist).

    Raises:
        OutputError: a file cannot be written (named).
    """
    return [write_motion(Path(out) / FILES[r.name], record(r, fps))
            for r in (s.with_springs, s.baseline)]


def motion_path(directory: str | Path, run: str = "springs") -> Path:
    """The motion file of ``run`` in a ``hexaleg simulate`` out directory.

    Raises:
        UnknownNameError: ``run`` is not one of :data:`RUNS`.
        InvalidParameterError: the directory does not hold the file (named, with the fix).
    """
    one_of("simulated run", run, RUNS)
    path = Path(directory) / FILES[run]
    if not path.is_file():
        where = ("does not exist" if not Path(directory).is_dir() else
                 f"has no {FILES[run]}")
        raise InvalidParameterError("simulation", str(directory), f"the out directory of "
                                    f"'hexaleg simulate', holding {' and '.join(FILES.values())}"
                                    f" (this one {where}; run hexaleg simulate --out "
                                    f"{directory})")
    return path


MAX_MOTION_BYTES = MEMORY_BUDGET // 4
"""Largest motion file read, and the most its arrays may hold once decompressed, B: a quarter of
hexaleg's memory budget (:data:`hexaleg.checks.MEMORY_BUDGET`); a run's file at
:data:`RECORD_FPS` holds about 110 kB per simulated second of the hexapod."""


def read_motion(path: str | Path) -> SimulatedMotion:
    """Read a motion file written by :func:`write_motion`, through the one bounded reader
    (:func:`hexaleg.config.read_bytes`: a regular file of at most :data:`MAX_MOTION_BYTES`),
    its entries' decompressed sizes checked before any is inflated, every number finite.

    Raises:
        ConfigError: the file is missing, not a regular file, too large (on disk or
            decompressed), empty, not an ``.npz`` of :data:`FORMAT`, lacks a key, has rows of
            different lengths or a value that is not finite (named).
    """
    path = Path(path)
    names = [f.name for f in fields(SimulatedMotion)]
    raw = read_bytes(path, "motion file", MAX_MOTION_BYTES)
    if not raw:
        raise ConfigError(f"cannot read the motion file {path}: it is empty (0 bytes); run "
                          "hexaleg simulate again to write it")
    try:
        with zipfile.ZipFile(io.BytesIO(raw)) as archive:
            inflated = sum(info.file_size for info in archive.infolist())
        if inflated > MAX_MOTION_BYTES:
            raise ConfigError(f"{path}: its arrays hold {inflated} bytes decompressed; allowed: "
                              f"at most {MAX_MOTION_BYTES} (is it the right file?)")
        with np.load(io.BytesIO(raw), allow_pickle=False) as npz:
            entries = {k: npz[k] for k in npz.files}
    except (OSError, ValueError, EOFError, zipfile.BadZipFile) as e:
        raise ConfigError(f"cannot read the motion file {path}: {e}") from e
    if str(entries.get("format", "")) != FORMAT:
        raise ConfigError(f"{path}: not a motion file of hexaleg simulate (format "
                          f"{str(entries.get('format', 'missing'))!r}, expected {FORMAT!r})")
    missing = [k for k in names if k not in entries]
    if missing:
        raise ConfigError(f"{path}: no {', '.join(missing)} (a motion file holds "
                          f"{', '.join(names)})")
    rows = {k: entries[k].shape[0] if entries[k].ndim else None for k in ARRAYS}
    if len(set(rows.values())) != 1 or None in rows.values():
        raise ConfigError(f"{path}: rows of different lengths: {rows}")
    try:
        arrays = {k: np.asarray(entries[k], dtype=float) for k in ARRAYS}
        timestep, stride = float(entries["timestep"]), int(entries["stride"])
    except (TypeError, ValueError) as e:
        raise ConfigError(f"{path}: an entry of the wrong type: {e}") from e
    for k, a in {**arrays, "timestep": np.array(timestep)}.items():
        if not np.all(np.isfinite(a)):
            first = tuple(int(i) for i in np.argwhere(~np.isfinite(a))[0])
            raise ConfigError(f"{path}: {k} holds {float(a[first])!r}"
                              + (f" at index {list(first)}" if first else "")
                              + "; allowed: finite numbers only (a motion file of hexaleg "
                              "simulate has no NaN or inf: run hexaleg simulate again)")
    if timestep <= 0 or stride < 1:
        raise ConfigError(f"{path}: timestep = {timestep!r} s, stride = {stride!r}; a motion file "
                          "has a timestep > 0 and a stride >= 1")
    t, q, v, tau, power, spring, feet, forces = (arrays[k] for k in ARRAYS)
    return SimulatedMotion(
        robot=str(entries["robot"]), run=str(entries["run"]),
        verdict=str(entries["verdict"]), message=str(entries["message"]),
        joint_names=tuple(str(j) for j in entries["joint_names"]),
        legs=tuple(str(leg) for leg in entries["legs"]),
        timestep=timestep, stride=stride, t=t, q=q, v=v,
        tau_motor=tau, power=power, tau_spring=spring, feet=feet, forces=forces)
