"""ROS 2 bags (rosbags' writer in the test, no ROS): a hexaleg gait written as JointState and
Odometry (or Imu) messages reads back to the CSV's columns and analysis; a missing reader, an
unknown joint and a bag without joint states are named."""

from __future__ import annotations

import sys

import numpy as np
import pytest

import hexaleg
from hexaleg.errors import ConfigError, UnknownNameError
from hexaleg.motion.recorded.load import load_motion
from hexaleg.motion.recorded.read import read_log
from hexaleg.motion.recorded.write import log_columns

pytest.importorskip("rosbags")  # the test extra installs it (pyproject: test, ros)


def write_bag(path, robot, cols, *, pose="odometry", names=None):
    """``cols`` (log columns, SI) as a ROS 2 bag: JointState at every row, the base as
    Odometry, PoseStamped or (orientation only) Imu, stamped from 100 s on."""
    from rosbags.rosbag2 import Writer
    from rosbags.typesys import Stores, get_typestore

    store = get_typestore(Stores.LATEST)
    T = store.types
    names = list(robot.joint_names) if names is None else names
    kinds = {"odometry": "nav_msgs/msg/Odometry", "pose": "geometry_msgs/msg/PoseStamped",
             "imu": "sensor_msgs/msg/Imu"}
    with Writer(path, version=9) as writer:
        joints = writer.add_connection("/joint_states", "sensor_msgs/msg/JointState",
                                       typestore=store)
        base = writer.add_connection(f"/{pose}", kinds[pose], typestore=store)
        for k, t in enumerate(cols["time"]):
            ns = 100_000_000_000 + round(t * 1e9)
            header = T["std_msgs/msg/Header"](
                stamp=T["builtin_interfaces/msg/Time"](sec=ns // 10**9, nanosec=ns % 10**9),
                frame_id="base")
            q = np.array([cols[n][k] for n in robot.joint_names])
            msg = T["sensor_msgs/msg/JointState"](header=header, name=names, position=q,
                                                   velocity=np.zeros(0), effort=np.zeros(0))
            writer.write(joints, ns, store.serialize_cdr(msg, msg.__msgtype__))
            p = T["geometry_msgs/msg/Point"](x=cols["base_x"][k], y=cols["base_y"][k],
                                             z=cols["base_z"][k])
            o = T["geometry_msgs/msg/Quaternion"](
                x=cols["base_qx"][k], y=cols["base_qy"][k], z=cols["base_qz"][k],
                w=cols["base_qw"][k])
            body = T["geometry_msgs/msg/Pose"](position=p, orientation=o)
            vec = T["geometry_msgs/msg/Vector3"](x=0.0, y=0.0, z=0.0)
            if pose == "odometry":
                msg = T["nav_msgs/msg/Odometry"](
                    header=header, child_frame_id="base",
                    pose=T["geometry_msgs/msg/PoseWithCovariance"](pose=body,
                                                                   covariance=np.zeros(36)),
                    twist=T["geometry_msgs/msg/TwistWithCovariance"](
                        twist=T["geometry_msgs/msg/Twist"](linear=vec, angular=vec),
                        covariance=np.zeros(36)))
            elif pose == "pose":
                msg = T["geometry_msgs/msg/PoseStamped"](header=header, pose=body)
            else:
                msg = T["sensor_msgs/msg/Imu"](
                    header=header, orientation=o, orientation_covariance=np.zeros(9),
                    angular_velocity=vec, angular_velocity_covariance=np.zeros(9),
                    linear_acceleration=vec, linear_acceleration_covariance=np.zeros(9))
            writer.write(base, ns, store.serialize_cdr(msg, msg.__msgtype__))
    return path


def _columns(robot, motion):
    cols = log_columns(robot, motion, derivatives=False)
    return {k: v for k, v in cols.items() if not k.startswith("stance_")}


def _write_csv(path, cols):
    rows = np.stack(list(cols.values()), axis=1)
    path.write_text(",".join(cols) + "\n" + "\n".join(",".join(repr(float(x)) for x in r)
                                                      for r in rows) + "\n")
    return path


def _energy(robot, motion):
    value = hexaleg.prepare(robot, motion).evaluate().metrics["total"]["electrical"]
    return value["value"] if isinstance(value, dict) else value


@pytest.mark.parametrize("pose", ["odometry", "pose"])
def test_bag_round_trip_gives_the_csv_analysis(robot, gait_100hz, tmp_path, pose):
    """The bag reads to the CSV's columns (1e-9: stamps in integer ns) and load_motion gives the
    same analysis (energies to 1e-9 relative, forces to 1e-9 N); without contact columns or
    derivatives, that analysis is within 2 % of the generated gait's energy."""
    cols = _columns(robot, gait_100hz)
    bag = write_bag(tmp_path / "walk", robot, cols, pose=pose)
    csv = _write_csv(tmp_path / "walk.csv", cols)
    a, b = read_log(robot, bag), read_log(robot, csv)
    assert a.t == pytest.approx(b.t, abs=1e-9) and set(a.columns) == set(b.columns)
    for name, values in b.columns.items():
        assert a.columns[name] == pytest.approx(values, abs=1e-12)
    x = load_motion(robot, bag, cycle="whole", periodic=True)
    y = load_motion(robot, csv, cycle="whole", periodic=True)
    rx, ry = (hexaleg.prepare(robot, m).evaluate() for m in (x, y))
    for key in ("electrical", "joule"):
        u, v = (r.metrics["total"][key] for r in (rx, ry))
        u, v = (w["value"] if isinstance(w, dict) else w for w in (u, v))
        assert abs(u - v) <= 1e-9 * abs(v)
    assert np.max(np.abs(rx.forces - ry.forces)) <= 1e-9
    assert x.info["report"].base_source == "log"
    truth = _energy(robot, gait_100hz)
    assert abs(_energy(robot, x) - truth) <= 0.02 * truth


def test_imu_orientation_turns_the_odometry(robot, gait_100hz, tmp_path):
    bag = write_bag(tmp_path / "imu", robot, _columns(robot, gait_100hz), pose="imu")
    log = read_log(robot, bag)
    assert "base_qw" in log.columns and "base_x" not in log.columns
    motion = load_motion(robot, bag, cycle="whole", periodic=True)
    assert motion.info["report"].base_source == "leg odometry + IMU orientation"


def test_without_rosbags_the_extra_is_named(robot, gait_100hz, tmp_path, monkeypatch):
    bag = write_bag(tmp_path / "walk", robot, _columns(robot, gait_100hz))
    monkeypatch.setitem(sys.modules, "rosbags.highlevel", None)
    with pytest.raises(ConfigError, match=r'pip install "hexaleg\[ros\]"'):
        read_log(robot, bag)


def test_unknown_joint_and_no_joint_states_are_named(robot, gait_100hz, tmp_path):
    cols = _columns(robot, gait_100hz)
    names = ["LF_knee", *robot.joint_names[1:]]
    bag = write_bag(tmp_path / "knee", robot, cols, names=names)
    with pytest.raises(UnknownNameError, match="LF_coxa"):
        read_log(robot, bag)
    assert "LF_coxa" not in read_log(robot, bag, ignore=("LF_knee",)).columns
    with pytest.raises(ConfigError, match="no sensor_msgs/msg/JointState topic"):
        read_log(robot, bag, ignore=("/joint_states",))
