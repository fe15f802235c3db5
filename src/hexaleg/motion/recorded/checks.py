"""The checks of a log against its robot: columns, joint limits, stance, feet above the ground,
the base's attitude (quaternion order), a log given as one whole cycle.

Each failure is a named error (or, where the motion can still be analysed, a warning) that says
what was found and what to change.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from hexaleg.errors import InvalidParameterError
from hexaleg.motion.recorded.columns import contact_columns, stance_columns
from hexaleg.motion.recorded.read import BASE_POSITION, BASE_QUATERNION, BASE_VELOCITY, Log
from hexaleg.robot.model import Robot
from hexaleg.units import DEG

LIMIT_TOLERANCE = 0.02
"""How far a logged joint may pass its URDF limit (servo overshoot, calibration), rad."""
GROUND_TOLERANCE = 0.005
"""How far below the ground (z = 0 of the logged world) a foot may seem to go, m."""
STANCE_TOLERANCE = 0.02
"""How far above the logged world's z = 0 the stance feet may stand (their median height), m:
a foot's radius and the floor's unevenness, not an origin off the floor."""
TILT_TOLERANCE = 5.0 * DEG
"""The logged attitude may tilt the stance feet's ground by at most this much, rad, on
flat ground before the loader warns (:func:`attitude_note`): more than an IMU's error and the
legs' compliance."""
WRAP_STEPS = 4.0
"""A log taken as one whole cycle (``cycle='whole'``) may jump from its last row to its first by
this many times a joint's largest step between rows, at most."""


def check_columns(robot: Robot, log: Log, contacts: bool | None, where: str) -> bool:
    """Whether the log gives exact derivatives; checks that every joint has its column, that
    the base's position and quaternion are whole, that derivatives are all given or none, that
    the planned stance's columns are all given or none, and that contact or stance columns
    exist when ``contacts`` is True.

    Raises:
        InvalidParameterError: the missing columns named, with the robot's joints listed.
    """
    joints = robot.joint_names
    missing = [j for j in joints if j not in log.columns]
    if missing:
        raise InvalidParameterError(f"{where} columns", f"missing {', '.join(missing)}",
                                    f"one column per joint of {robot.name}: {', '.join(joints)}")
    for group in (BASE_POSITION, BASE_QUATERNION):
        present = [c for c in group if c in log.columns]
        if present and len(present) != len(group):
            raise InvalidParameterError(f"{where} columns", ", ".join(present),
                                        f"all of {', '.join(group)} or none")
    derivatives = [p + n for p in ("v_", "a_") for n in (*BASE_VELOCITY, *joints)]
    present = [c for c in derivatives if c in log.columns]
    if present and len(present) != len(derivatives):
        absent = [c for c in derivatives if c not in log.columns]
        raise InvalidParameterError(f"{where} derivative columns", f"missing {absent[0]} "
                                    f"(and {len(absent) - 1} more)", "every v_ and a_ column "
                                    "of the base and the joints, or none (then smoothed)")
    planned = stance_columns(robot)
    given = [c for c in planned if c in log.columns]
    if given and len(given) != len(planned):
        raise InvalidParameterError(f"{where} stance columns", ", ".join(given),
                                    f"all of {', '.join(planned)} or none")
    legs = contact_columns(robot)
    if contacts is True and not log.has(legs) and not given:
        raise InvalidParameterError(
            f"{where} contact columns", f"missing {[c for c in legs if c not in log.columns]}",
            "a contact_<LEG> (or stance_<LEG>) column for every leg with contacts=True; or "
            "contacts=None to find stance from the feet's motion")
    return bool(present)


def check_limits(robot: Robot, q: np.ndarray, t: np.ndarray, units: dict[str, str],
                 where: str) -> None:
    """Every joint within its URDF limits (± :data:`LIMIT_TOLERANCE`).

    Raises:
        InvalidParameterError: the joint, its value, the time and its limits; a hint at the
            column's unit when the values would fit in another.
    """
    low = robot.model.lowerPositionLimit[7:]
    high = robot.model.upperPositionLimit[7:]
    over = np.maximum(low - LIMIT_TOLERANCE - q, q - high - LIMIT_TOLERANCE)
    if not np.any(over > 0):
        return
    k, j = (int(i) for i in np.unravel_index(np.argmax(over), over.shape))
    name = robot.joint_names[j]
    unit = units.get(name, "rad")
    hint = ""
    if unit == "rad" and np.all((q[:, j] * DEG >= low[j]) & (q[:, j] * DEG <= high[j])):
        hint = f"; the values fit in degrees: write the header '{name} [deg]'"
    elif unit == "deg":
        hint = f"; the values fit in radians: write the header '{name}' or '{name} [rad]'"
    raise InvalidParameterError(
        f"{where} joint {name} at t = {t[k] - t[0]:.4f} s",
        f"{q[k, j]:.4f} rad" if abs(q[k, j]) < 1e6 else f"{q[k, j]:.4g} rad",
        f"within its limits [{low[j]:.4f}, {high[j]:.4f}] rad{hint} (check the column's unit "
        "and the servo's zero offset)")


def check_stance(robot: Robot, stance: np.ndarray, t: np.ndarray, where: str) -> list[str]:
    """Warnings for legs never in stance.

    Raises:
        InvalidParameterError: a sample with no foot down (nothing carries the robot).
    """
    none = ~stance.any(axis=1)
    if none.any():
        k = int(np.flatnonzero(none)[0])
        raise InvalidParameterError(
            f"{where}: stance at t = {t[k]:.4f} s", "no foot on the ground",
            f"at least one foot down at every sample ({int(none.sum())} samples have none): "
            "check the contact_<LEG> columns (1 = down), or log them if the robot jumps")
    out = []
    for i, leg in enumerate(robot.leg_names):
        if not stance[:, i].any():
            out.append(f"{where}: leg {leg} is never in stance; if it walks, give a "
                       f"contact_{leg} column (1 = down) or check its joints' units")
    return out


def check_ground(robot: Robot, feet: np.ndarray, t: np.ndarray, where: str,
                 stance: np.ndarray | None = None) -> None:
    """No foot below the logged world's ground z = 0 by more than :data:`GROUND_TOLERANCE`, and
    the stance feet on it: their median height within :data:`STANCE_TOLERANCE` of z = 0.

    Args:
        robot: The robot. feet: Foot positions in the logged world, shape (T, n_legs, 3), m.
        t: Sample times, shape (T,), s. where: The log, for messages.
        stance: Stance flags, shape (T, n_legs), or None (the depth check alone).

    Raises:
        InvalidParameterError: the foot, the depth and the time, and what to change; or the
            stance feet's height above z = 0 and the ``base_z`` offset that would put them on
            the floor (a motion-capture origin off the floor: the simulation would drop the
            robot from that height).
    """
    if stance is not None and stance.any():
        height = float(np.median(feet[..., 2][stance]))
        if height > STANCE_TOLERANCE:
            raise InvalidParameterError(
                f"{where}: base_z", f"stance feet {height:.3f} m above the log's z = 0 (median "
                "over the stance samples)", f"the log's world z = 0 on the floor the stance "
                f"feet stand on: subtract {height:.3f} m from base_z (a motion-capture origin "
                "off the floor), or check its unit (base_z [mm])")
    k, i = (int(v) for v in np.unravel_index(np.argmin(feet[..., 2]), feet.shape[:2]))
    depth = -float(feet[k, i, 2])
    if depth > GROUND_TOLERANCE:
        raise InvalidParameterError(
            f"{where}: base pose at t = {t[k]:.4f} s", f"{robot.leg_names[i]} foot "
            f"{depth * 1e3:.1f} mm underground", "feet on or above z = 0: the log's world "
            "z = 0 must be the floor — add the offset to base_z, check its unit (base_z [mm]) "
            "or the quaternion's order (x, y, z, w)")


def feet_world(robot: Robot, q_joints: np.ndarray, base: np.ndarray | None) -> np.ndarray:
    """Foot positions (T, n_legs, 3), m, for joint angles (T, nj) and base poses (T, 7) (the
    base frame itself for None)."""
    n = q_joints.shape[0]
    q = np.zeros((n, robot.model.nq))
    q[:, 6] = 1.0
    q[:, 7:] = q_joints
    if base is not None:
        q[:, :7] = base
    data = robot.model.createData()
    frames = [leg.foot_frame_id for leg in robot.legs]
    out = np.empty((n, len(frames), 3))
    for k in range(n):
        pin.framesForwardKinematics(robot.model, data, q[k])
        for i, f in enumerate(frames):
            out[k, i] = data.oMf[f].translation
    return out


def centre_of_mass(robot: Robot, q_joints: np.ndarray, base: np.ndarray | None) -> np.ndarray:
    """The robot's centre of mass (T, 3), m, for joint angles (T, nj) and base poses (T, 7)
    (the base frame itself for None)."""
    q = np.zeros((q_joints.shape[0], robot.model.nq))
    q[:, 6] = 1.0
    q[:, 7:] = q_joints
    if base is not None:
        q[:, :7] = base
    data = robot.model.createData()
    return np.array([pin.centerOfMass(robot.model, data, qk) for qk in q])


def check_attitude(quat: np.ndarray, where: str) -> None:
    """The base quaternions ``quat`` (N, 4: x, y, z, w) of a robot that walks upright: the body's
    z axis points up in most rows (its world z component ``1 − 2 (x² + y²)``, > 0).

    Raises:
        InvalidParameterError: the body upside down as read; when the same columns read w-first
            (w, x, y, z) give an upright body, the message says the order is wrong.
    """
    up = np.median(1.0 - 2.0 * (quat[:, 0] ** 2 + quat[:, 1] ** 2))
    if up > 0.0:
        return
    w_first = np.median(1.0 - 2.0 * (quat[:, 1] ** 2 + quat[:, 2] ** 2))
    shown = ", ".join(f"{v:.3f}" for v in quat[0])
    if w_first > 0.5:
        raise InvalidParameterError(
            f"{where} base quaternion", f"({shown}) in base_qx, base_qy, base_qz, base_qw: the "
            "body upside down as read, upright if read w-first", "x, y, z, w in base_qx, "
            "base_qy, base_qz, base_qw (w last, as ROS and Pinocchio write it): the log's "
            "columns hold w first; rename them (w is base_qw)")
    raise InvalidParameterError(
        f"{where} base quaternion", f"({shown}): the body upside down in most rows (its z "
        f"axis {up:+.2f} up)", "the attitude of the robot's base in the world, z up (a walking "
        "robot is upright); check the IMU's frame and the columns' order (x, y, z, w)")


def ground_tilt(feet: np.ndarray, stance: np.ndarray, rotation: np.ndarray) -> np.ndarray:
    """How far the logged attitude tilts the ground the stance feet define, per sample, rad
    (NaN where fewer than three stance feet span a plane).

    On flat ground the stance feet lie in a plane whose normal, in the base frame, is the
    world's up as the joints see it; the logged attitude says it is ``Rᵀ e_z``. Their angle is
    the joint-implied attitude's disagreement with the log's (a sensor frame other than the
    base's, a quaternion of another convention, a slope).

    Args:
        feet: Foot positions in the base frame, shape (T, n_legs, 3), m.
        stance: Stance flags, shape (T, n_legs).
        rotation: The logged attitude (base to world), shape (T, 3, 3).
    """
    tilt = np.full(len(feet), np.nan)
    for k in range(len(feet)):
        down = feet[k, stance[k]]
        if len(down) < 3:
            continue
        centred = down - down.mean(axis=0)
        _, spread, vt = np.linalg.svd(centred)
        if spread[1] < 0.2 * spread[0]:  # (nearly) on a line: no plane
            continue
        up = rotation[k][2]  # the world's z in the base frame: row 2 of R
        tilt[k] = float(np.arccos(min(abs(float(vt[2] @ up)), 1.0)))
    return tilt


def attitude_note(tilt: np.ndarray, where: str) -> list[str]:
    """The warning when the logged attitude disagrees with the stance feet's ground by more than
    :data:`TILT_TOLERANCE` in most samples that define one (:func:`ground_tilt`)."""
    seen = tilt[np.isfinite(tilt)]
    if not seen.size or np.median(seen) <= TILT_TOLERANCE:
        return []
    return [f"{where}: the logged attitude tilts the ground the stance feet define by "
            f"{np.degrees(np.median(seen)):.1f}° (median of {seen.size} samples; at most "
            f"{np.degrees(TILT_TOLERANCE):.0f}° on flat ground): the IMU's frame may not be the "
            "base's (rotate its quaternion into the base frame) or the ground is not flat"]


def check_whole(q: np.ndarray, names: list[str], where: str) -> None:
    """The joints ``q`` (N, nj) of a log taken as one whole periodic cycle end where they start:
    each joint's jump from the last row to the first is at most :data:`WRAP_STEPS` times its
    largest step between rows.

    Raises:
        InvalidParameterError: the joint that jumps most, by how much (not one whole cycle).
    """
    steps = np.abs(np.diff(q, axis=0)).max(axis=0)
    wrap = np.abs(q[0] - q[-1])
    ratio = wrap / np.maximum(steps, 1e-12)
    j = int(np.argmax(ratio))
    if ratio[j] > WRAP_STEPS:
        raise InvalidParameterError(
            f"{where}: cycle='whole'", f"the log ends {wrap[j]:.3g} rad from where it starts "
            f"on {names[j]} ({ratio[j]:.1f} times its largest step between rows)",
            "a log of exactly one cycle, each joint ending about a step from its start; give "
            "cycle='auto' (a log of two cycles or more) or the window of one cycle, (t0, t1)")

