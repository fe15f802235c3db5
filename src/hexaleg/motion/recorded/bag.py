"""Reading a ROS 2 bag as a motion log, with ``rosbags`` (pure Python, no ROS install).

A bag (its directory with ``metadata.yaml``, or one of its ``.db3``/``.mcap`` files) is read into
the same SI columns as a CSV log (:mod:`hexaleg.motion.recorded.columns`):

* ``sensor_msgs/msg/JointState`` — every message's ``position`` by ``name`` (the robot's joint
  names, rad: REP 103); the rows are the union of the messages' stamps (several topics, e.g. one
  per leg, fill their joints of the same row; a joint a message lacks is NaN, filled by the
  resampling within ``max_gap``);
* ``nav_msgs/msg/Odometry`` or ``geometry_msgs/msg/PoseStamped`` — the base position (m) and
  orientation quaternion, interpolated to the joint rows (positions linearly; quaternions
  component-wise on one hemisphere, then normalised: the chordal approximation of slerp, exact
  to O(Δθ³) between samples);
* ``sensor_msgs/msg/Imu`` — without a pose topic, its ``orientation`` as the base orientation
  (not when ``orientation_covariance[0] = -1``, ROS's "no orientation").

Stamps are the messages' ``header.stamp``, or the bag's receive time where a header stamp is
zero; the time column starts at the first joint row. Contacts are not in these messages: stance
comes from the feet's motion (:mod:`~hexaleg.motion.recorded.stance`).
"""

from __future__ import annotations

from collections import defaultdict
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np

from hexaleg.errors import ConfigError
from hexaleg.motion.recorded.columns import (
    BASE_POSITION,
    BASE_QUATERNION,
    MAX_LOG_BYTES,
    Log,
    column_kind,
)
from hexaleg.robot.model import Robot

JOINTS = "sensor_msgs/msg/JointState"
POSES = ("nav_msgs/msg/Odometry", "geometry_msgs/msg/PoseStamped")
IMU = "sensor_msgs/msg/Imu"
INSTALL = 'pip install "hexaleg[ros]"'
"""What installs the bag reader (the optional ``ros`` extra: ``rosbags``)."""


def bag_directory(path: Path) -> Path | None:
    """The ROS 2 bag ``path`` is (a directory with ``metadata.yaml``, or a ``.db3``/``.mcap``
    file in one), or None."""
    if path.is_dir() and (path / "metadata.yaml").is_file():
        return path
    if path.suffix.lower() in (".db3", ".mcap") and (path.parent / "metadata.yaml").is_file():
        return path.parent
    return None


def _stamp(msg: Any, received: int) -> float:
    """A message's header stamp, s, or the bag's receive time (ns) when the stamp is zero."""
    stamp = msg.header.stamp
    ns = int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)
    return (ns if ns else received) * 1e-9


def _one(topics: list[str], kind: str, where: str) -> str | None:
    if len(topics) > 1:
        raise ConfigError(f"{where}: {len(topics)} {kind} topics ({', '.join(topics)}); keep "
                          "one: pass the others in ignore (load_motion(..., ignore=[...]))")
    return topics[0] if topics else None


def _pose_columns(t: np.ndarray, stamps: np.ndarray, position: np.ndarray | None,
                  quat: np.ndarray) -> dict[str, np.ndarray]:
    """Base columns at the joint rows ``t`` (N,) from poses at ``stamps`` (M,): positions (M, 3)
    or None, quaternions (M, 4) x y z w (module docstring); NaN outside the poses' span."""
    order = np.argsort(stamps, kind="stable")
    stamps, quat = stamps[order], quat[order]
    flip = np.cumprod(np.where(np.sum(quat[1:] * quat[:-1], axis=1) < 0, -1.0, 1.0))
    quat[1:] *= flip[:, None]  # one hemisphere: q and -q are the same rotation
    out = {}
    q = np.stack([np.interp(t, stamps, quat[:, i], left=np.nan, right=np.nan)
                  for i in range(4)], axis=1)
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    out.update({name: q[:, i] for i, name in enumerate(BASE_QUATERNION)})
    if position is not None:
        position = position[order]
        out.update({name: np.interp(t, stamps, position[:, i], left=np.nan, right=np.nan)
                    for i, name in enumerate(BASE_POSITION)})
    return out


def read_bag(robot: Robot, path: Path, *, ignore: Iterable[str] = ()) -> Log:
    """A ROS 2 bag as a motion log of ``robot`` (module docstring).

    Args:
        robot: The robot (its joint names name the JointState entries).
        path: The bag directory, or a ``.db3``/``.mcap`` file in it.
        ignore: Topics, and joint names of the JointState messages, to skip.

    Raises:
        ConfigError: ``rosbags`` not installed (names :data:`INSTALL`), an unreadable bag, a bag
            larger than :data:`~hexaleg.motion.recorded.columns.MAX_LOG_BYTES`, no JointState
            topic, two pose or IMU topics.
        UnknownNameError: a joint name that is not the robot's (the valid names listed).
    """
    where = f"motion log {path}"
    directory = bag_directory(path)
    if directory is None:
        raise ConfigError(f"{where}: not a ROS 2 bag (a directory with metadata.yaml)")
    size = sum(f.stat().st_size for f in directory.iterdir() if f.is_file())
    if size > MAX_LOG_BYTES:
        raise ConfigError(f"{where}: {size / 1024**2:.0f} MB, more than the "
                          f"{MAX_LOG_BYTES / 1024**2:.0f} MB a log may have; cut the bag "
                          "(ros2 bag convert) to the topics and time span to analyse")
    try:
        from rosbags.highlevel import AnyReader, AnyReaderError
        from rosbags.rosbag2 import ReaderError
        from rosbags.typesys import Stores, get_typestore
    except ImportError:
        raise ConfigError(f"{where} is a ROS 2 bag; reading it needs the rosbags package: "
                          f"{INSTALL} (or save the log as CSV or NPZ)") from None
    skip = set(ignore)
    joints: dict[float, dict[str, float]] = defaultdict(dict)
    poses: list[tuple[float, list[float] | None, list[float]]] = []
    imu: list[tuple[float, list[float] | None, list[float]]] = []
    try:
        with AnyReader([directory], default_typestore=get_typestore(Stores.LATEST)) as reader:
            kept = [c for c in reader.connections if c.topic not in skip]
            pose = _one(sorted({c.topic for c in kept if c.msgtype in POSES}), "pose", where)
            orient = _one(sorted({c.topic for c in kept if c.msgtype == IMU}), "IMU", where)
            wanted = [c for c in kept if c.msgtype == JOINTS or c.topic in (pose, orient)]
            if not any(c.msgtype == JOINTS for c in wanted):
                raise ConfigError(f"{where} has no {JOINTS} topic (topics: "
                                  f"{', '.join(sorted({c.topic for c in reader.connections}))})")
            for conn, received, raw in reader.messages(connections=wanted):
                msg: Any = reader.deserialize(raw, conn.msgtype)  # a message dataclass
                t = _stamp(msg, received)
                if conn.msgtype == JOINTS:
                    row = joints[t]
                    for name, value in zip(msg.name, msg.position, strict=False):
                        if name not in skip:
                            column_kind(robot, name)  # the robot's joints, or named
                            row[name] = float(value)
                elif conn.topic == pose:
                    p = msg.pose.pose if conn.msgtype == POSES[0] else msg.pose
                    o = p.orientation
                    poses.append((t, [p.position.x, p.position.y, p.position.z],
                                  [o.x, o.y, o.z, o.w]))
                elif msg.orientation_covariance[0] != -1.0:
                    o = msg.orientation
                    imu.append((t, None, [o.x, o.y, o.z, o.w]))
    except (AnyReaderError, ReaderError) as e:  # a corrupt or unsupported bag
        raise ConfigError(f"{where}: cannot read the bag ({type(e).__name__}: {e})") from None
    stamps = np.array(sorted(joints))
    names = [j for j in robot.joint_names if any(j in row for row in joints.values())]
    columns = {j: np.array([joints[s].get(j, np.nan) for s in stamps]) for j in names}
    base = poses or imu
    if base:
        position = np.array([b[1] for b in base]) if poses else None
        columns.update(_pose_columns(stamps, np.array([b[0] for b in base]), position,
                                     np.array([b[2] for b in base])))
    units = {name: ("m" if name in BASE_POSITION else "" if name in BASE_QUATERNION else "rad")
             for name in columns}
    return Log(t=stamps - stamps[0], columns=columns, units=units, path=str(path))
