"""``load_motion``: a robot's own log → a :class:`~hexaleg.motion.trajectory.Motion`.

The pipeline (each step its module): read (CSV/NPZ or a ROS 2 bag, units to SI) → resample
(uniform grid) → cycle (period by autocorrelation, cycles averaged; or a window, or the whole
log) → smooth and differentiate (Savitzky–Golay, cut-off from the noise) → stance (planned
stance columns, contact columns or feet kinematics) → base (logged pose, or leg odometry) →
checks (limits, stance, feet above ground) and a
:class:`~hexaleg.motion.recorded.quality.MotionQuality` report in ``motion.info``.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from hexaleg.checks import real, typed
from hexaleg.errors import HexalegError, HexalegWarning, InvalidParameterError
from hexaleg.motion.limits import MIN_SAMPLES
from hexaleg.motion.recorded import base as _base
from hexaleg.motion.recorded import stance as _stance
from hexaleg.motion.recorded.checks import (
    attitude_note,
    centre_of_mass,
    check_attitude,
    check_columns,
    check_ground,
    check_limits,
    check_stance,
    check_whole,
    feet_world,
    ground_tilt,
)
from hexaleg.motion.recorded.columns import MEASURED, contact_columns, stance_columns
from hexaleg.motion.recorded.cycle import average_cycles, find_period, steady_start
from hexaleg.motion.recorded.integrator import integrator_of
from hexaleg.motion.recorded.quality import MotionQuality
from hexaleg.motion.recorded.read import BASE_POSITION, BASE_QUATERNION, BASE_VELOCITY, read_log
from hexaleg.motion.recorded.resample import resample
from hexaleg.motion.recorded.smooth import cutoff_frequency, noise_level, smooth
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot

Cycle = str | tuple[float, float]


def _window(t: np.ndarray, cycle: Cycle, where: str) -> tuple[str, slice]:
    if cycle in ("auto", "whole"):
        return str(cycle), slice(None)
    if isinstance(cycle, str) or not isinstance(cycle, Sequence) or len(cycle) != 2:
        raise InvalidParameterError("cycle", cycle, "'auto', 'whole' or a window (t0, t1) in s")
    t0, t1 = (float(c) for c in cycle)
    if not (0.0 <= t0 < t1 <= t[-1] + 1e-9):
        raise InvalidParameterError("cycle", cycle, f"a window 0 <= t0 < t1 <= {t[-1]:.4f} s "
                                    f"(the {where} from its first stamp)")
    lo, hi = int(np.searchsorted(t, t0 - 1e-9)), int(np.searchsorted(t, t1 + 1e-9))
    if hi - lo < MIN_SAMPLES:
        raise InvalidParameterError("cycle", cycle, f"a window of at least {MIN_SAMPLES} rows of "
                                    f"the {where} (this one holds {hi - lo})")
    return "window", slice(lo, hi)


def _period(x: np.ndarray, dt: float, where: str) -> tuple[float, float]:
    """The period of the joints ``x`` (:func:`~hexaleg.motion.recorded.cycle.find_period`), or
    — where the whole log does not repeat because it starts with a settle, a stand or a
    transient — of its second half.

    Raises:
        InvalidParameterError: neither repeats (the whole log's error).
    """
    try:
        return find_period(x, dt, where)
    except InvalidParameterError as whole:
        try:
            return find_period(x[len(x) // 2:], dt, where)
        except InvalidParameterError:
            raise whole from None


def _cycles_in_whole(x: np.ndarray, dt: float, where: str) -> list[str]:
    """A note when a log taken whole (``cycle="whole"``) holds several cycles of a repeating
    motion (the period found by :func:`~hexaleg.motion.recorded.cycle.find_period`): its
    energy per "cycle" is then several cycles' and its distance several strides."""
    try:
        period, _ = find_period(x, dt, where)
    except HexalegError:  # nothing repeats: the whole log is one motion
        return []
    n = len(x) * dt / period
    if n < 1.5:
        return []
    return [f"{where} holds about {n:.1f} cycles of {period:.4g} s, and cycle='whole' takes "
            "all of it as one cycle (its energy and distance per cycle are those of the whole "
            "log); cycle='auto' averages them into one"]


def _drift(t: np.ndarray, x: np.ndarray) -> np.ndarray:
    """Least-squares slope of each column of x (N, n) against t (N,)."""
    tc = t - t.mean()
    return (tc @ (x - x.mean(axis=0))) / max(float(tc @ tc), 1e-300)


@typed
def load_motion(robot: Robot, path: str | Path, *, cycle: Cycle = "auto",
                contacts: bool | None = None, periodic: bool | None = None,
                max_gap: float = 0.05, ignore: Sequence[str] = ()) -> Motion:
    """The motion a robot walked, from its log (docs/motion.md).

    Args:
        robot: The robot of the log.
        path: A CSV or NPZ log (:mod:`hexaleg.motion.recorded.read` for the columns), or a ROS 2
            bag (:mod:`hexaleg.motion.recorded.bag`).
        cycle: ``"auto"`` (the period found and the log's cycles averaged into one periodic
            cycle), ``"whole"`` (the log as it is) or ``(t0, t1)`` (a window, s from the first
            stamp).
        contacts: Use the log's stance columns — ``stance_<LEG>`` (a plan's, the stance as it
            is) or else ``contact_<LEG>`` (a switch's, refined at its edges by the feet's
            motion, :mod:`~hexaleg.motion.recorded.stance`) — (True: required; False: ignored,
            stance from the feet's motion; None: when the log has them).
        periodic: Whether the result is periodic; default True for ``"auto"``, else False (a
            window of exactly one cycle may say True).
        max_gap: Longest gap (dropped rows, NaN run) interpolated, s.
        ignore: Columns of the log to skip.

    Returns:
        The motion (q, v, a, stance, feet, period, distance); ``info["quality"]`` holds the
        :class:`~hexaleg.motion.recorded.quality.MotionQuality` report as a dict,
        ``info["report"]`` the dataclass and ``info["measured"]`` the log's actuator
        measurements (``current_<joint>``, ``torque_<joint>``, ``power_<joint>``: column →
        values at the motion's samples, SI, cycle-averaged as the joints are; empty without);
        ``info["integrator"]`` is :data:`~hexaleg.motion.trajectory.SEMI_IMPLICIT` when the
        log gives its derivatives and its samples are the knots of that integration (an
        optimal motion's file: :func:`~hexaleg.motion.recorded.integrator.integrator_of`).

    Raises:
        ConfigError, UnknownNameError, InvalidParameterError: the named bad input (a column
            missing or unknown, time not increasing, a NaN run, a log shorter than two cycles,
            joints beyond their limits, feet underground, a sample with no foot down).
    """
    max_gap = real("max_gap", max_gap, low=0.0, allowed="a gap >= 0 (s) to fill by interpolation")
    if isinstance(ignore, (str, bytes)) or not isinstance(ignore, Sequence) \
            or not all(isinstance(c, str) for c in ignore):
        raise InvalidParameterError("ignore", ignore, "a list of column names, e.g. "
                                    "['temperature_LF_femur'] (a string alone would be read "
                                    "letter by letter)")
    path = Path(path)
    where = f"motion log {path}"
    caught: list[str] = []
    log = read_log(robot, path, ignore=tuple(ignore))
    rows = len(log.t)
    res = resample(log, max_gap=max_gap)
    log, dt = res.log, res.dt
    joints = list(robot.joint_names)
    given = check_columns(robot, log, contacts, where)
    planned = contacts is not False and log.has(stance_columns(robot))
    legs = stance_columns(robot) if planned else contact_columns(robot)
    has_base, has_quat = log.has(BASE_POSITION), log.has(BASE_QUATERNION)
    mode, span = _window(log.t, cycle, where)
    t = log.t[span]
    periodic = (mode == "auto") if periodic is None else bool(periodic)
    check_limits(robot, log.matrix(joints)[span], t, log.units, where)
    if has_quat:
        check_attitude(log.matrix(list(BASE_QUATERNION))[span], where)
    if mode == "whole":
        if len(t) < MIN_SAMPLES:
            raise InvalidParameterError(f"{where} rows", len(t), f"at least {MIN_SAMPLES} rows "
                                        "for cycle='whole' (one cycle of the gait)")
        if periodic:
            check_whole(log.matrix(joints)[span], joints, where)
        caught += _cycles_in_whole(log.matrix(joints)[span], dt, where)

    # The signals averaged or windowed together: joints, base pose (drift removed), contacts.
    signals = [log.matrix(joints)[span]]
    rot = _base.rotation_from_quaternion(log.matrix(list(BASE_QUATERNION))[span]) \
        if has_quat else None
    base_cols = 0
    if has_base or has_quat:
        pose = np.zeros((len(t), 6))
        if has_base:
            pose[:, :3] = log.matrix(list(BASE_POSITION))[span]
        if rot is not None:
            pose[:, 3:] = _base.euler_from_rotation(rot)
        signals.append(pose)
        base_cols = 6
    use_contacts = contacts is not False and log.has(legs)
    if use_contacts:
        signals.append(log.matrix(legs)[span])
    if given:
        derivative_names = [p + n for p in ("v_", "a_") for n in (*BASE_VELOCITY, *joints)]
        signals.append(log.matrix(derivative_names)[span])
    measured = [f"{kind}_{j}" for kind in MEASURED for j in joints
                if f"{kind}_{j}" in log.columns]  # averaged with the joints, for identification
    signals.append(log.matrix(measured)[span])
    x = np.concatenate(signals, axis=1)
    nj = len(joints)
    correlation: float | None = None
    steady = 0.0  # where the steady gait begins (a settle, a stand or a transient left out)
    found = 1.0  # the autocorrelation at the period
    if mode == "auto":
        period, found = _period(x[:, :nj], dt, where)
        steady = steady_start(t, x[:, :nj], period, dt)
        if steady > 0.0:  # the period of the steady part alone
            period, found = find_period(x[t >= steady - 1e-9, :nj], dt, where)
        correlation = found
    kept = t >= steady - 1e-9
    drift = np.zeros(x.shape[1])
    if base_cols and periodic:
        drift[nj:nj + base_cols] = _drift(t[kept], x[kept, nj:nj + base_cols])
    x = x - drift * t[:, None]
    sigma = noise_level(x[kept, :nj + base_cols])
    if mode == "auto":
        cycles = average_cycles(t, x, period, dt, correlation=found, start=steady)
        x, count = cycles.mean, cycles.count
        spread = float(cycles.spread[:nj].max())
        dt_c = period / cycles.samples
        sigma = sigma / math.sqrt(count)
    else:
        count, spread, dt_c = 1, 0.0, dt
        period = len(t) * dt if periodic else (len(t) - 1) * dt
    n = x.shape[0]
    tc = np.arange(n) * dt_c

    # Smoothed joints and base pose (or the derivatives as logged).
    position_cutoff = attitude_cutoff = None  # the logged base pose's (the joints': cutoff)
    if given:
        cutoff = window = None
        d0 = nj + base_cols + (len(legs) if use_contacts else 0)
        nv = robot.model.nv
        q_j, v_all, a_all = x[:, :nj], x[:, d0:d0 + nv], x[:, d0 + nv:d0 + 2 * nv]
        pose_s = x[:, nj:nj + base_cols] + drift[nj:nj + base_cols] * tc[:, None]
        dpose = ddpose = None
    else:  # each group its own cut-off from its own noise: joints, base position, attitude
        groups = [slice(0, nj)] + ([slice(nj, nj + 3), slice(nj + 3, nj + 6)] if base_cols
                                   else [])
        parts = [smooth(x[:, g], dt_c, cutoff_frequency(x[:, g], dt_c, sigma[g],
                                                          periodic=periodic), periodic=periodic)
                 for g in groups]
        cutoff, window = parts[0].cutoff, parts[0].window
        if has_base:
            position_cutoff = parts[1].cutoff
        if has_quat:
            attitude_cutoff = parts[2].cutoff
        q_j, v_all, a_all = parts[0].x, np.zeros((n, 6 + nj)), np.zeros((n, 6 + nj))
        v_all[:, 6:], a_all[:, 6:] = parts[0].xd, parts[0].xdd
        pose_s = np.zeros((n, 0))
        dpose = ddpose = np.zeros((n, 0))
        if base_cols:
            pose_s = np.hstack([p.x for p in parts[1:]]) + drift[nj:nj + base_cols] * tc[:, None]
            dpose = np.hstack([p.xd for p in parts[1:]]) + drift[nj:nj + base_cols]
            ddpose = np.hstack([p.xdd for p in parts[1:]])
    contact = x[:, nj + base_cols:nj + base_cols + len(legs)] if use_contacts else None
    actuators = dict(zip(measured, x[:, x.shape[1] - len(measured):].T, strict=True))

    q = np.zeros((n, robot.model.nq))
    q[:, 7:] = q_j
    feet_b = feet_world(robot, q_j, None)
    stance_rot = _base.rotation_from_euler(pose_s[:, 3:6]) if has_quat else None
    com_b = centre_of_mass(robot, q_j, None)
    if has_base:  # the feet over the logged ground: its z noise moves their heights
        if not has_quat:
            pose_s[:, 3:] = 0.0
        q[:, :3] = pose_s[:, :3]
        q[:, 3:7] = _base.quaternion_from_euler(pose_s[:, 3:6])
        level, com_l = feet_world(robot, q_j, q[:, :7]), centre_of_mass(robot, q_j, q[:, :7])
        height_noise, moving = float(sigma[nj + 2]), True
    else:  # in the base frame, turned by the IMU's roll and pitch
        level, com_l, height_noise, moving = feet_b, com_b, 0.0, False
        if stance_rot is not None:
            level = np.einsum("tij,tlj->tli", stance_rot, feet_b)
            com_l = np.einsum("tij,tj->ti", stance_rot, com_b)
            # the IMU's roll and pitch noise moves a foot's height by its lever arm
            reach = float(np.median(np.linalg.norm(feet_b[..., :2], axis=2)))
            height_noise = float(np.hypot(sigma[nj + 3], sigma[nj + 4])) * reach
    if stance_rot is not None:  # the logged attitude against the one the stance feet imply
        plain = _stance.detect(feet_b, _velocity(feet_b, dt_c, periodic), com_b,
                               periodic=periodic)
        tilted = attitude_note(ground_tilt(feet_b, plain.stance, stance_rot), where)
        if tilted:  # stance on the ground the feet define, not on the attitude's
            caught += tilted
            level, com_l, height_noise, moving = feet_b, com_b, 0.0, False
    if planned and contact is not None:
        stance = _stance.from_plan(contact)
    elif contact is not None:
        stance = _stance.from_contacts(contact, level, com_l, periodic=periodic,
                                       noise_height=height_noise)
    else:  # world feet walk on: their velocity is not periodic
        stance = _stance.detect(level, _velocity(level, dt_c, periodic and not moving), com_l,
                                periodic=periodic, noise_height=height_noise)
    base_source = "log"
    if not has_base:
        odo = _base.leg_odometry(feet_b, stance.stance, dt_c, periodic=periodic,
                                 rotation=stance_rot)
        base_source = "leg odometry" + (" + IMU orientation" if has_quat else "")
        pose_o = np.concatenate([odo.position, _base.euler_from_rotation(odo.rotation)], 1)
        drift_o = (pose_o[n] - pose_o[0]) / (n * dt_c) if periodic else np.zeros(6)
        residual = pose_o[:n] - drift_o * tc[:, None]
        sm_b = smooth(residual, dt_c, cutoff or 0.5 / dt_c, periodic=periodic)
        pose_s = sm_b.x + drift_o * tc[:, None]
        dpose, ddpose = sm_b.xd + drift_o, sm_b.xdd
        q[:, :3] = pose_s[:, :3]
        q[:, 3:7] = _base.quaternion_from_euler(pose_s[:, 3:6])
    if dpose is not None and ddpose is not None:
        v_all[:, :6], a_all[:, :6] = _base.twist(pose_s[:, 3:6], dpose[:, 3:6], ddpose[:, 3:6],
                                                 dpose[:, :3], ddpose[:, :3])
    feet = feet_world(robot, q_j, q[:, :7])
    caught += check_stance(robot, stance.stance, tc, where)
    for message in caught:  # before a ground error: a tilted attitude may be its cause
        warnings.warn(message, HexalegWarning, stacklevel=2)
    if has_base:
        check_ground(robot, feet, tc, where, stance.stance)
    world_speed = np.linalg.norm(_velocity(feet, dt_c, False), axis=2)[stance.stance]
    slip = float(np.sqrt(np.mean(world_speed**2))) if world_speed.size else 0.0
    quality = MotionQuality(
        path=str(path), rows=rows, rate=1.0 / dt, resampled=res.resampled,
        filled=int(sum(res.filled.values())), derivatives="given" if given else "smoothed",
        noise=float(sigma[:nj].max() * (math.sqrt(count))), cutoff=cutoff, window=window,
        position_cutoff=position_cutoff, attitude_cutoff=attitude_cutoff,
        cycle=mode, period=float(period), cycles=count, correlation=correlation, spread=spread,
        steady_from=steady,
        stance_source=stance.source, stance_height=stance.height, stance_speed=stance.speed,
        stance_fractions=dict(zip(robot.leg_names, stance.fractions.round(4).tolist(),
                                  strict=True)),
        touch_fractions=dict(zip(robot.leg_names, stance.touch_fractions.round(4).tolist(),
                                 strict=True)),
        base_source=base_source, slip=slip,
        slip_max=float(world_speed.max()) if world_speed.size else 0.0, warnings=tuple(caught))
    travel = (q[-1, :2] - q[0, :2]) * (n / max(n - 1, 1) if periodic else 1.0)
    # knots of a semi-implicit integration (an optimal motion's log) say so by their numbers
    integrator = integrator_of(robot.model, q, v_all, a_all, dt_c) if given else None
    return Motion(t=tc, q=q, v=v_all, a=a_all, stance=stance.stance, feet=feet,
                  period=float(period), distance=float(np.linalg.norm(travel)),
                  periodic=periodic, info={"source": "load_motion", "log": str(path),
                                           "quality": quality.to_dict(), "report": quality,
                                           "measured": actuators,
                                           **({"integrator": integrator} if integrator else {})})


def _velocity(p: np.ndarray, dt: float, periodic: bool) -> np.ndarray:
    """Central differences of p (T, …) along time (wrapping around when periodic)."""
    if periodic:
        return (np.roll(p, -1, axis=0) - np.roll(p, 1, axis=0)) / (2.0 * dt)
    return np.gradient(p, dt, axis=0)
