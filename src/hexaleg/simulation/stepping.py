"""Running a compiled model under a control sequence: the recorded trajectory and its verdict.

The servos' controls are a function of time only (:mod:`hexaleg.simulation.controllers`), so
a run is an open-loop control sequence. When the springs are all native
(:attr:`hexaleg.simulation.springs.SpringPlan.native`) it runs in MuJoCo's rollout (its C loop:
``mj_step`` then copy the state and the sensors), a chunk of :data:`CHUNK` at a time (or of the
balance controller's period, closed loop: :func:`closed_loop`) with the warm start carried, so
the steps are one call's to the bit; otherwise a Python loop does the same with the non-native
spring torques added to ``qfrc_applied`` before each step. Both record, per step k, the state
*before* the step (at ``t_k = k dt``) and the sensors of that state (MuJoCo computes them in
``mj_forward`` before it integrates), so the recorded servo torque ``τ_k`` acts over
``[t_k, t_{k+1}]`` at the recorded speed ``q̇_k`` — the rectangle rule of the symplectic-Euler
step.

A run stops early, with its verdict, when MuJoCo flags a bad acceleration (a diverged state), or
when the base falls (:data:`FALL_HEIGHT` of the planned height, :data:`FALL_TILT` roll or pitch):
the arrays then end there, never with NaN; the stepping stops after the chunk in which it fell.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from hexaleg.errors import InvalidParameterError
from hexaleg.simulation.mjcf import contact_sites
from hexaleg.simulation.model import SimModel
from hexaleg.simulation.timers import untimed

FALL_HEIGHT = 0.5
"""A base below this fraction of its planned height has fallen."""
FALL_TILT = float(np.deg2rad(45.0))
"""rad: a base rolled or pitched beyond this has fallen."""
Feedback = Callable[[float, np.ndarray, np.ndarray, np.ndarray], np.ndarray]
"""A controller closing the loop: ``(t, qpos, qvel, contact points (n_points, 3)) → Δcontrols
(nj,)`` (the points a foot site's or a sole's four corner sites,
:func:`~hexaleg.simulation.mjcf.contact_sites`),
held until its next update (:meth:`hexaleg.simulation.balance.Balance.correction`)."""
MAX_STEPS = 5_000_000
"""Steps a run may take (a bound: a long run is an error, never a hang)."""
CHUNK = 0.25
"""s: an open-loop run steps in chunks of this much simulated time and stops after the chunk in
which the base fell (a fallen robot's contacts with the ground cost up to 5× a walking step's,
and its rows are cut anyway); the chunks carry MuJoCo's warm start, so the steps are the
one-call rollout's to the bit (``tests/simulation/test_stepping.py``)."""


@dataclass(frozen=True)
class Trajectory:
    """A recorded run, one row per step (the state before the step).

    Attributes:
        t: Times, shape (n,), s.
        qpos: MuJoCo configurations, shape (n, nq_mj).
        qvel: MuJoCo velocities, shape (n, nv).
        servo: Servo actuator forces u (the voltage as a torque, clamped), shape (n, nj), N·m.
        tau_motor: Motor torques at the joints ``u − D q̇``, shape (n, nj), N·m.
        feet: Foot positions (world), shape (n, n_legs, 3), m.
        controls: The servo controls applied, shape (n, nj).
        verdict: ``"ran"``, ``"fell"`` or ``"diverged"``.
        message: When and how a run that did not finish ended ('' when it ran).
    """

    t: np.ndarray
    qpos: np.ndarray
    qvel: np.ndarray
    servo: np.ndarray
    tau_motor: np.ndarray
    feet: np.ndarray
    controls: np.ndarray
    verdict: str = "ran"
    message: str = ""

    @property
    def n(self) -> int:
        """Recorded steps."""
        return int(self.t.shape[0])


def tilt(qpos: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Roll and pitch (rad) of the base, from MuJoCo ``qpos`` (…, nq_mj): the z-y-x Euler angles
    of the base orientation (yaw left out), from the third row of its rotation matrix,
    ``R₂ = (2(xz − wy), 2(yz + wx), 1 − 2(x² + y²))`` of the normalised quaternion (w, x, y, z)
    (:func:`~hexaleg.motion.recorded.base.rotation_from_quaternion`'s third row, the same
    arithmetic: the other six entries are not needed)."""
    quat = np.concatenate([qpos[..., 4:7], qpos[..., 3:4]], axis=-1)  # x y z w, as normalised
    x, y, z, w = np.moveaxis(quat / np.linalg.norm(quat, axis=-1, keepdims=True), -1, 0)
    roll = np.arctan2(2 * (y * z + x * w), 1 - 2 * (x * x + y * y))
    pitch = np.arcsin(np.clip(-(2 * (x * z - y * w)), -1.0, 1.0))
    return roll, pitch


def _fallen(qpos: np.ndarray, height: float,
            angles: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """Whether the base has fallen or diverged at each row of ``qpos`` (n, nq_mj), (n,) bool
    (``angles``: its :func:`tilt`, when already known)."""
    roll, pitch = tilt(qpos) if angles is None else angles
    return ~np.all(np.isfinite(qpos), axis=1) | (qpos[:, 2] < FALL_HEIGHT * height) | \
        (np.abs(roll) > FALL_TILT) | (np.abs(pitch) > FALL_TILT)


def _down(qpos: np.ndarray, height: float) -> bool:
    """Whether the base of one MuJoCo configuration (nq_mj,) has fallen or diverged, as
    :func:`_fallen` judges a row, in scalars (a closed loop asks it at each update): roll and
    pitch from the quaternion's third rotation row, ``R₂ = (2(xz − wy), 2(yz + wx),
    1 − 2(x² + y²))`` of the unit quaternion (w, x, y, z)."""
    z, w, x, y, k = qpos[2:7].tolist()
    norm = math.sqrt(w * w + x * x + y * y + k * k)
    if not (math.isfinite(z) and math.isfinite(norm) and norm > 0):
        return True
    w, x, y, k = w / norm, x / norm, y / norm, k / norm
    roll = math.atan2(2 * (y * k + w * x), 1 - 2 * (x * x + y * y))
    pitch = math.asin(min(1.0, max(-1.0, -2 * (x * k - w * y))))
    return z < FALL_HEIGHT * height or abs(roll) > FALL_TILT or abs(pitch) > FALL_TILT


def _fall(qpos: np.ndarray, height: float, t: np.ndarray) -> tuple[int, str]:
    """The first step at which the base has fallen (and how), or (n, '')."""
    roll, pitch = tilt(qpos)
    z = qpos[:, 2]
    bad = _fallen(qpos, height, (roll, pitch))
    if not bad.any():
        return len(qpos), ""
    k = int(np.argmax(bad))
    if not np.all(np.isfinite(qpos[k])):
        return k, f"the state diverged (non-finite) at t = {t[k]:.4f} s"
    how = (f"base height {z[k] * 1e3:.1f} mm < {FALL_HEIGHT:.0%} of the planned "
           f"{height * 1e3:.1f} mm" if z[k] < FALL_HEIGHT * height else
           f"base roll {np.degrees(roll[k]):+.1f}°, pitch {np.degrees(pitch[k]):+.1f}° beyond "
           f"±{np.degrees(FALL_TILT):.0f}°")
    return k, f"the robot fell at t = {t[k]:.4f} s: {how}"


class Stopped(Exception):
    """A run stopped from outside between two of its chunks (its ``stop`` event set: the run
    stepped beside it failed, or Ctrl-C reached the thread that waits for both,
    :func:`hexaleg.simulation.run.side_by_side`)."""


def run(sim: SimModel, controls: np.ndarray, qpos0: np.ndarray, qvel0: np.ndarray,
        height: float, feedback: Feedback | None = None, every: int = 1,
        stop: threading.Event | None = None) -> Trajectory:
    """Step ``sim`` from ``(qpos0, qvel0)`` under ``controls``, one row per step.

    Args:
        sim: The model.
        controls: Servo controls, shape (n, nj) (one row per step).
        qpos0: Initial MuJoCo configuration, shape (nq_mj,).
        qvel0: Initial MuJoCo velocity, shape (nv,).
        height: Planned base height, m (for the fall check).
        feedback: A controller closing the loop (:func:`closed_loop`), or None (open loop).
        every: Steps between its updates, ≥ 1.
        stop: Set from another thread, the run ends at its next chunk (:data:`CHUNK` of
            simulated time open loop, ``every`` steps closed loop) with :class:`Stopped`.

    Returns:
        The trajectory, cut where the run diverged or fell (its verdict says so); its
        controls are those applied (the feedback's included).

    Raises:
        Stopped: ``stop`` was set.
    """
    import mujoco

    m = sim.model
    assert isinstance(m, mujoco.MjModel)
    n, nj = controls.shape
    if n > MAX_STEPS:
        raise InvalidParameterError("simulation steps", n, f"≤ {MAX_STEPS} (fewer cycles or a "
                                    "larger timestep)")
    data = mujoco.MjData(m)
    data.qpos[:], data.qvel[:] = qpos0, qvel0
    ctrl = np.zeros((n, m.nu))
    ctrl[:, :nj] = controls
    chunk = every if feedback is not None else max(1, round(CHUNK / m.opt.timestep))
    with untimed():  # MuJoCo's stage timers: 7 % of a step, and never read
        qpos, qvel, sensors = closed_loop(sim, data, ctrl, feedback, chunk, height, stop)
    controls = ctrl[:, :nj]
    stopped = n
    message = ""
    bad_acc = int(data.warning[mujoco.mjtWarning.mjWARN_BADQACC].number)
    if bad_acc:  # the step at which MuJoCo stopped integrating
        stopped = min(n, round(data.time / m.opt.timestep))
        message = f"MuJoCo flagged a diverging acceleration at t = {data.time:.4f} s"
    t = np.arange(n) * m.opt.timestep
    fall, how = _fall(qpos[:stopped], height, t[:stopped])
    verdict = "ran"
    if fall < stopped or bad_acc:
        verdict = "fell" if how.startswith("the robot fell") else "diverged"
        message = how or message
        stopped = min(stopped, fall)
    forces, feet = sim.sensor_slices()
    servo = sensors[:stopped, forces]
    dq = sim.joints.joints_mj(qvel[:stopped], velocity=True)
    return Trajectory(t=t[:stopped], qpos=qpos[:stopped], qvel=qvel[:stopped], servo=servo,
                      tau_motor=servo - sim.damping * dq,
                      feet=sensors[:stopped, feet].reshape(stopped, -1, 3),
                      controls=controls[:stopped], verdict=verdict, message=message)


def _python_loop(sim: SimModel, data: object, ctrl: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pre-step states and their sensors, step by step, with the non-native spring torques
    (what MuJoCo's rollout records, :func:`closed_loop`)."""
    import mujoco

    m = sim.model
    assert isinstance(m, mujoco.MjModel) and isinstance(data, mujoco.MjData)
    n = len(ctrl)
    qpos, qvel = np.empty((n, m.nq)), np.empty((n, m.nv))
    sensors = np.empty((n, m.nsensordata))
    qadr, dof = sim.joints.qpos, sim.joints.dof
    for k in range(n):
        qpos[k], qvel[k] = data.qpos, data.qvel
        data.ctrl[:] = ctrl[k]
        data.qfrc_applied[dof] = sim.springs.python_torque(data.qpos[qadr], data.qvel[dof])
        mujoco.mj_step(m, data)
        sensors[k] = data.sensordata
        if data.warning[mujoco.mjtWarning.mjWARN_BADQACC].number:
            qpos[k + 1:], qvel[k + 1:], sensors[k + 1:] = qpos[k], qvel[k], sensors[k]
            break
    return qpos, qvel, sensors


def closed_loop(sim: SimModel, data: object, ctrl: np.ndarray, feedback: Feedback | None,
                every: int, height: float, stop: threading.Event | None = None
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pre-step states and their sensors, ``every`` steps at a time: with ``feedback`` closing
    the loop at each chunk's start — the state and the contact sites (``mj_kinematics``) are
    read, the controls of the next ``every`` steps move by the feedback's change (``ctrl`` is
    updated in place: the controls applied) — or open loop without. MuJoCo's rollout (or the
    Python loop, for non-native springs) runs each chunk, its constraint warm start carried
    over. A base that has fallen (below :data:`FALL_HEIGHT` of its height, or rolled or pitched
    beyond :data:`FALL_TILT`, in a row the chunk recorded: :func:`run` then finds it there) or
    diverged stops the loop (the rest of the rows repeat its last state, as
    :func:`_python_loop` leaves a diverged run); ``stop`` set raises :class:`Stopped` before
    the next chunk."""
    import mujoco
    import mujoco.rollout

    m = sim.model
    assert isinstance(m, mujoco.MjModel) and isinstance(data, mujoco.MjData)
    n, nj = len(ctrl), sim.robot.nj
    every = max(1, int(every))
    spec = mujoco.mjtState.mjSTATE_FULLPHYSICS
    # row k: the state before step k (row n: after the last), written in place by the rollout
    # (no chunk allocates or copies its states); qpos and qvel are views of its columns
    states = np.empty((n + 1, mujoco.mj_stateSize(m, spec)))
    mujoco.mj_getState(m, data, states[0], spec)
    sensors = np.empty((n, m.nsensordata))
    sites = [mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_SITE, name)
             for name in contact_sites(sim.robot)]
    roller = mujoco.rollout.Rollout(nthread=0) if hasattr(mujoco.rollout, "Rollout") else None
    control = int(mujoco.mjtState.mjSTATE_CTRL)
    nq, nv, dt = m.nq, m.nv, m.opt.timestep
    qpos, qvel = states[:n, 1:1 + nq], states[:n, 1 + nq:1 + nq + nv]
    bad = mujoco.mjtWarning.mjWARN_BADQACC
    k = 0
    while k < n:
        if stop is not None and stop.is_set():
            raise Stopped(f"stopped from outside at t = {k * dt:.4f} s")
        mujoco.mj_setState(m, data, states[k], spec)
        end = min(n, k + every)
        if feedback is not None:
            mujoco.mj_kinematics(m, data)
            ctrl[k:end, :nj] += feedback(k * dt, data.qpos.copy(), data.qvel.copy(),
                                         data.site_xpos[sites])
        if sim.springs.native:
            warm = data.qacc_warmstart.copy()
            if roller is not None:  # outputs written in place, no checks: the shapes are ours
                roller.rollout([m], [data], states[k:k + 1], ctrl[None, k:end], nstep=end - k,
                               control_spec=control, initial_warmstart=warm[None],
                               state=states[None, k + 1:end + 1],
                               sensordata=sensors[None, k:end], skip_checks=True)
            else:
                states[None, k + 1:end + 1], sensors[None, k:end] = mujoco.rollout.rollout(
                    m, data, states[k:k + 1], ctrl[None, k:end], initial_warmstart=warm[None])
        else:
            qpos[k:end], qvel[k:end], sensors[k:end] = _python_loop(sim, data, ctrl[k:end])
            mujoco.mj_getState(m, data, states[end], spec)
        first, k = k, end
        if (_down(qpos[k - 1], height) and _fallen(qpos[first:k], height).any()) or \
                not np.isfinite(states[k]).all() or data.warning[bad].number:
            states[k:n], sensors[k:] = states[k - 1], sensors[k - 1]
            break
    return qpos, qvel, sensors
