"""A walk simulated in MuJoCo, written as a robot's own log: a log with a known answer.

A log that :func:`hexaleg.load_motion` did not write and whose energy is known, to check the
log path end to end (docs/motion.md): the robot is dropped from :attr:`WalkLog`'s ``drop`` above
its planned stand, settles for ``settle`` seconds under the servos holding the gait's first
pose, then walks the gait for ``cycles`` cycles under the feedforward servo
(:mod:`hexaleg.simulation.controllers`) — the settle and the first cycles are the transient a
real log starts with. The simulated state is sampled at ``rate`` and passed through a sensor
model (:class:`Sensors`): joint encoders quantised to a tick after Gaussian noise, a
motion-capture base position with Gaussian noise, an IMU attitude turned by a small Gaussian
rotation; optionally contact switches (``contact_<LEG>``: the foot's contact force non-zero)
and the actuators' measurements (``current_<joint>``, ``torque_<joint>``, ``power_<joint>``: the
simulated motor torque, and the current and electrical power of a given actuator model at that
torque and the simulated joint speed, :mod:`hexaleg.robot.motor`).

What the log must give back (:class:`WalkLog`): the simulated electrical energy per cycle over
the last ``evaluate`` cycles (:func:`hexaleg.simulation.measures.cycle_energies`, the
simulation's own motor torques and speeds through :func:`hexaleg.dynamics.energy.metrics`) and
each foot's fraction of those cycles on the ground (MuJoCo's contact force non-zero).
"""

from __future__ import annotations

import io
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from scipy.spatial.transform import Rotation

from hexaleg.checks import integer, real
from hexaleg.config import write_file
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import prepare
from hexaleg.errors import InvalidParameterError, SimulationError
from hexaleg.motion.recorded.columns import BASE_POSITION, BASE_QUATERNION, MEASURED
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.actuator import Actuator
from hexaleg.robot.model import Robot
from hexaleg.simulation import measures, stepping
from hexaleg.simulation.controllers import controls, reference
from hexaleg.simulation.model import build_model
from hexaleg.simulation.settings import Settings
from hexaleg.simulation.timestep import automatic_timestep, cycle_timestep

MEASURED_PREFIXES = tuple(f"{kind}_" for kind in MEASURED)
"""Column prefixes of the actuators' measurements."""
DYNAMIXEL_TICK = math.radians(300.0) / 1024
"""A Dynamixel AX/MX position tick, rad (300° over 1024 counts: ROBOTIS AX-12A e-Manual)."""
PARTS: tuple[str, ...] = ("joints", "base", "imu", "contacts", "actuators")
"""What a log may hold: the joint encoders, the base position (motion capture), the IMU's
attitude quaternion, the feet's contact switches, the actuators' currents, torques and powers."""


@dataclass(frozen=True)
class Sensors:
    """The sensors of a simulated log (SI).

    Attributes:
        tick: Joint encoder resolution, rad, ≥ 0 (0: not quantised).
        joint_noise: Joint angle noise σ before quantisation, rad, ≥ 0.
        base_noise: Base position noise σ per axis, m, ≥ 0 (motion capture: ~0.1–1 mm).
        imu_noise: Attitude noise σ per axis, rad, ≥ 0 (a small rotation about a Gaussian
            axis-angle vector).
        seed: The noise generator's seed.
    """

    tick: float = DYNAMIXEL_TICK
    joint_noise: float = 0.5 * DYNAMIXEL_TICK
    base_noise: float = 0.5e-3
    imu_noise: float = math.radians(0.2)
    seed: int = 0

    def __post_init__(self) -> None:
        for name in ("tick", "joint_noise", "base_noise", "imu_noise"):
            real(name, getattr(self, name), low=0.0, allowed="a finite value >= 0")
        integer("seed", self.seed, low=0)


@dataclass(frozen=True, eq=False)
class WalkLog:
    """A simulated walk as log columns, and what it must give back.

    Attributes:
        robot: The robot's name.
        joints: Its actuated joints (their columns), hexaleg's order.
        columns: Log column → values, shape (K,) each, SI (:mod:`hexaleg.motion.recorded.read`
            names: ``time``, the base position and quaternion x, y, z, w, one column per joint,
            ``contact_<LEG>`` 0/1, ``current_<joint>`` A, ``torque_<joint>`` N·m,
            ``power_<joint>`` W).
        electrical: Simulated electrical energy per cycle over the evaluated cycles, J.
        metrics: All of :func:`hexaleg.dynamics.energy.metrics`' totals per cycle (J, N·m).
        touch: Leg → fraction of the evaluated cycles its foot touches the ground.
        walk_from: When the gait starts (after the settle), s.
        evaluated_from: Where the evaluated cycles start, s.
    """

    robot: str
    joints: tuple[str, ...]
    columns: dict[str, np.ndarray]
    electrical: float
    metrics: dict[str, float]
    touch: dict[str, float]
    walk_from: float
    evaluated_from: float

    def write(self, path: str | Path, parts: tuple[str, ...] = ("joints", "base", "imu"), *,
              degrees: bool = False) -> Path:
        """Write the log as CSV (a header row of names, one row a sample).

        Args:
            path: The ``.csv`` file.
            parts: Which of :data:`PARTS` it holds (always the joints; by default no contacts).
            degrees: Joint angles in degrees (``name [deg]`` headers).

        Raises:
            InvalidParameterError: a part not in :data:`PARTS`, or no joints.
        """
        for part in parts:
            if part not in PARTS:
                raise InvalidParameterError("parts", part, f"some of {', '.join(PARTS)}")
        if "joints" not in parts:
            raise InvalidParameterError("parts", parts, "the joints and optionally base, imu")
        names = ["time", *(BASE_POSITION if "base" in parts else ()),
                 *(BASE_QUATERNION if "imu" in parts else ()), *self.joints,
                 *(name for name in self.columns if name.startswith("contact_")
                   and "contacts" in parts),
                 *(name for name in self.columns if name.startswith(MEASURED_PREFIXES)
                   and "actuators" in parts)]
        scale = {name: (180.0 / math.pi if degrees and name in self.joints else 1.0)
                 for name in names}
        header = [f"{name} [deg]" if scale[name] != 1.0 else name for name in names]
        table = np.stack([self.columns[name] * scale[name] for name in names], axis=1)
        text = io.StringIO()
        np.savetxt(text, table, delimiter=",", header=",".join(header), comments="",
                   fmt="%.9g")
        return write_file(path, text.getvalue(), "simulated log")


def walk_log(robot: Robot, motion: Motion, motor: Any = None, *, rate: float = 100.0,
             settle: float = 1.0, drop: float = 0.02, cycles: int = 10, evaluate: int = 6,
             sensors: Sensors | None = None, contact: ContactParams | None = None,
             settings: Settings | None = None,
             actuator: Actuator | None = None) -> WalkLog:
    """Simulate ``motion`` after a drop and a settle and write what sensors would log (module
    docstring).

    Args:
        robot: The robot. motion: A periodic gait of it.
        motor: Its servos (as :func:`hexaleg.dynamics.prepare.prepare`; None: the default).
        rate: Log rate, Hz, > 0 (rounded to a whole number of simulation steps per row).
        settle: Standing time before the gait, s, ≥ 0. drop: Height dropped from, m, ≥ 0.
        cycles: Gait cycles walked, ≥ 2. evaluate: The last cycles evaluated, in [1, cycles).
        sensors: The sensor model (default :class:`Sensors`).
        contact: The analysis' contact settings (the feedforward torques; the ground's μ).
        settings: The simulation's ground and servo (default :class:`Settings`).
        actuator: The actuator model whose current ``τ / (k_t G)`` and electrical power
            (:meth:`~hexaleg.robot.motor.Motor.electrical_power`) at the simulated motor torque
            and joint speed the log's measurement columns hold, exact (default: the servos
            simulated; one model for every joint).

    Raises:
        InvalidParameterError: a value out of range, a non-periodic motion.
        SimulationError: the robot fell or the integration diverged (when and how).
    """
    real("rate", rate, low=0.0, low_open=True, allowed="a log rate > 0 Hz")
    real("settle", settle, low=0.0, allowed="a standing time >= 0 s")
    real("drop", drop, low=0.0, allowed="a drop height >= 0 m")
    integer("cycles", cycles, low=2)
    integer("evaluate", evaluate, low=1, high=cycles - 1)
    if not motion.periodic or motion.fixed_base:
        raise InvalidParameterError("motion", "a fixed-base or non-periodic motion",
                                    "a periodic gait (hexaleg.gait)")
    sensors = sensors or Sensors()
    settings = (settings or Settings()).sized(robot.mass)
    contact = contact or ContactParams()
    prepared = prepare(robot, motion, motor=motor, contact=contact)
    analysis = prepared.evaluate(None, "joule")
    servo, ground = settings.servo(), settings.ground(contact.mu)
    dt = cycle_timestep(automatic_timestep(robot, motion, prepared.motor, servo, ground),
                        motion.period)
    sim = build_model(robot, motion, prepared.motor, servo=servo, ground=ground, timestep=dt)
    steps, standing = round(motion.period / dt), round(settle / dt)
    ref = reference(motion, analysis.tau_motor, np.arange(cycles * steps) * dt)
    ctrl = controls(sim.servo, ref, sim.kp, sim.kd)
    ctrl = np.concatenate([np.repeat(ctrl[:1], standing, axis=0), ctrl])
    q0 = motion.q[0].copy()
    q0[2] += drop
    qpos0, qvel0 = sim.joints.to_mujoco(q0, np.zeros_like(motion.v[0]))
    traj = stepping.run(sim, ctrl, qpos0, qvel0, float(np.mean(motion.q[:, 2])))
    if traj.verdict != "ran":
        raise SimulationError(f"the simulated walk {traj.verdict}: {traj.message}")
    window = slice(standing + (cycles - evaluate) * steps, standing + cycles * steps)
    energies = measures.mean_metrics(
        measures.cycle_energies(sim, traj, window, evaluate, prepared.motor))
    stride = max(1, round(1.0 / (rate * dt)))
    rows = np.arange(0, traj.n, stride)
    q, _ = sim.joints.to_pinocchio(traj.qpos[rows], traj.qvel[rows])
    evaluated = np.arange(window.start, window.stop)
    down = np.array([np.linalg.norm(measures.contact_forces(sim, data), axis=-1) > 0.0
                     for data in measures.forward_states(sim, traj, evaluated)])
    switches = np.array([np.linalg.norm(measures.contact_forces(sim, data), axis=-1) > 0.0
                         for data in measures.forward_states(sim, traj, rows)])
    rng = np.random.default_rng(sensors.seed)
    k = len(rows)
    cols: dict[str, np.ndarray] = {"time": traj.t[rows]}
    for i, name in enumerate(BASE_POSITION):
        cols[name] = q[:, i] + rng.normal(0.0, sensors.base_noise, k)
    turned = (Rotation.from_quat(q[:, 3:7])  # x, y, z, w; a body-frame turn: q ⊗ exp(θ/2)
              * Rotation.from_rotvec(rng.normal(0.0, sensors.imu_noise, (k, 3)))).as_quat()
    for i, name in enumerate(BASE_QUATERNION):
        cols[name] = turned[:, i]
    for j, name in enumerate(robot.joint_names):
        angle = q[:, 7 + j] + rng.normal(0.0, sensors.joint_noise, k)
        cols[name] = np.round(angle / sensors.tick) * sensors.tick if sensors.tick else angle
    for i, leg in enumerate(robot.leg_names):
        cols[f"contact_{leg}"] = switches[:, i].astype(float)
    measured = actuator or prepared.motor
    tau = traj.tau_motor[rows]
    qdot = sim.joints.joints_mj(traj.qvel[rows], velocity=True)
    for name, values in (("torque", tau), ("current", measured.current(tau)),
                         ("power", measured.electrical_power(tau, qdot))):
        for j, joint in enumerate(robot.joint_names):
            cols[f"{name}_{joint}"] = values[:, j]
    return WalkLog(robot=robot.name, joints=tuple(robot.joint_names), columns=cols,
                   electrical=energies["electrical"], metrics=energies,
                   touch=dict(zip(robot.leg_names, down.mean(axis=0).tolist(), strict=True)),
                   walk_from=standing * dt, evaluated_from=window.start * dt)
