"""The motion files of ``hexaleg simulate``: what a row holds (checked against MuJoCo's own
numbers, not through the mapping that wrote it), the round trip, and files that are refused."""

from __future__ import annotations

import dataclasses
import os
import zipfile

import numpy as np
import pytest

from hexaleg.errors import ConfigError, InvalidParameterError, OutputError, UnknownNameError
from hexaleg.simulation import motion_file
from hexaleg.simulation.motion_file import (
    FILES,
    RECORD_FPS,
    motion_path,
    read_motion,
    record,
    write_motion,
    write_motions,
)


@pytest.fixture(scope="module")
def written(feedforward, tmp_path_factory):
    """Both runs of the short feedforward simulation written into one directory."""
    out = tmp_path_factory.mktemp("motions")
    paths = write_motions(out, feedforward)
    assert [p.name for p in paths] == [FILES["springs"], FILES["baseline"]]
    return out


def test_a_row_is_the_simulated_step(feedforward, written):
    """Every stride-th step at RECORD_FPS: Pinocchio's feet at the written configurations are
    MuJoCo's foot sites (a wrong quaternion order or joint column would move them), the torques
    are the run's, the spring torque is hexaleg's spring law, the contact forces carry the
    weight."""
    run = feedforward.with_springs
    m = read_motion(written / FILES["springs"])
    traj, robot = run.trajectory, feedforward.robot
    rows = np.arange(0, traj.n, m.stride)
    assert m.rate == pytest.approx(RECORD_FPS) and m.stride == 20 and m.timestep == 5e-4
    assert len(m.t) == len(rows) == 300  # 3 cycles of 1 s
    np.testing.assert_array_equal(m.t, traj.t[rows])
    feet = np.array([robot.foot_positions(q) for q in m.q])
    np.testing.assert_allclose(feet, traj.feet[rows], atol=1e-12)
    np.testing.assert_array_equal(m.feet, traj.feet[rows])
    np.testing.assert_array_equal(m.tau_motor, traj.tau_motor[rows])
    qdot = traj.qvel[rows][:, run.sim.joints.dof]
    np.testing.assert_allclose(m.power, traj.tau_motor[rows] * qdot, rtol=1e-15)
    np.testing.assert_allclose(m.v[:, 6:], qdot, rtol=1e-15)
    np.testing.assert_allclose(m.tau_spring, feedforward.springs.torques(robot, m.q, m.v),
                               atol=1e-12)
    assert np.abs(m.tau_spring).max() > 0.05
    weight = robot.mass * 9.81
    assert m.forces[..., 2].sum(axis=1).mean() == pytest.approx(weight, rel=0.02)
    assert (m.forces[..., 2] >= 0).all()
    assert (np.linalg.norm(m.forces, axis=-1) > 0).any(axis=0).all()  # every foot pushed
    assert (m.robot, m.run, m.verdict) == (robot.name, "springs", "ran")
    assert m.joint_names == robot.joint_names and m.legs == tuple(robot.leg_names)


def test_the_file_round_trips(feedforward, written, tmp_path):
    kept = record(feedforward.baseline)
    back = read_motion(written / FILES["baseline"])
    for f in dataclasses.fields(kept):
        mine, theirs = getattr(kept, f.name), getattr(back, f.name)
        if isinstance(mine, np.ndarray):
            assert mine.dtype == theirs.dtype == float and mine.shape == theirs.shape
            np.testing.assert_array_equal(mine, theirs)
        else:
            assert mine == theirs, f.name
    assert np.abs(back.tau_spring).max() == 0.0  # the baseline has no springs
    # ≈ 1 kB a row compressed: 3 s of the hexapod in about 0.3 MB
    assert (written / FILES["baseline"]).stat().st_size < 1100 * len(back.t)
    motion = back.motion()
    assert motion.n_samples == 300 and not motion.periodic
    assert motion.stance.sum() > 0.4 * motion.stance.size


def test_a_motion_file_of_another_robot_is_refused(written, robot, spider):
    m = read_motion(written / FILES["springs"])
    with pytest.raises(InvalidParameterError, match=r"robot = 'hexaleg'.*'spider'"):
        m.check(spider, "f.npz")
    renamed = dataclasses.replace(m, joint_names=("LF_hip", *m.joint_names[1:]))
    with pytest.raises(InvalidParameterError, match=r"f\.npz: joint_names = 'LF_hip, "):
        renamed.check(robot, "f.npz")
    short = dataclasses.replace(m, q=m.q[:, :-1])
    with pytest.raises(InvalidParameterError, match=r"q = 'an array of shape \(300, 24\)'"):
        short.check(robot, "f.npz")


def test_a_directory_without_the_motion_file_is_named(written, tmp_path):
    assert motion_path(written, "baseline") == written / "motion-baseline.npz"
    with pytest.raises(InvalidParameterError, match=rf"{tmp_path}'.*has no motion-springs\.npz"):
        motion_path(tmp_path)
    with pytest.raises(InvalidParameterError, match="does not exist"):
        motion_path(tmp_path / "nowhere")
    with pytest.raises(UnknownNameError, match=r"'with_springs' \(did you mean 'springs'\?\); "
                                               "valid simulated runs are: baseline, springs"):
        motion_path(written, "with_springs")


def test_other_files_are_refused(written, tmp_path):
    text = tmp_path / "motion-springs.npz"
    text.write_text("not a zip")
    with pytest.raises(ConfigError, match=f"cannot read the motion file {text}"):
        read_motion(text)
    other = tmp_path / "other.npz"
    np.savez(other, q=np.zeros((2, 25)))
    with pytest.raises(ConfigError, match="not a motion file of hexaleg simulate"):
        read_motion(other)
    with np.load(written / FILES["springs"]) as npz:
        entries = {k: npz[k] for k in npz.files if k != "forces"}
    np.savez(other, **entries)
    with pytest.raises(ConfigError, match="no forces"):
        read_motion(other)
    entries["forces"] = np.zeros((3, 6, 3))
    np.savez(other, **entries)
    with pytest.raises(ConfigError, match="rows of different lengths"):
        read_motion(other)
    with pytest.raises(ConfigError, match="not found"):
        read_motion(tmp_path / "missing.npz")


def test_an_unwritable_file_is_named(written, tmp_path):
    m = read_motion(written / FILES["springs"])
    with pytest.raises(OutputError, match=r"no/m\.npz"):
        write_motion(tmp_path / "no" / "m.npz", m)


def test_empty_special_and_inflated_motion_files_are_named(written, tmp_path):
    """view --simulation with an empty .npz used to end in an EOFError traceback."""
    empty = tmp_path / "motion-springs.npz"
    empty.write_bytes(b"")
    with pytest.raises(ConfigError, match=r"motion-springs\.npz: it is empty \(0 bytes\)"):
        read_motion(empty)
    os.mkfifo(tmp_path / "pipe.npz")
    for path in (tmp_path / "pipe.npz", "/dev/zero", tmp_path):
        with pytest.raises(ConfigError, match="is not a regular file"):
            read_motion(path)
    bomb = tmp_path / "bomb.npz"  # 4 MB of zeros compress to a few kB
    with zipfile.ZipFile(bomb, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("q.npy", b"\0" * 4_000_000)
    original = motion_file.MAX_MOTION_BYTES
    motion_file.MAX_MOTION_BYTES = 1_000_000
    try:
        with pytest.raises(ConfigError, match=r"4000000 bytes decompressed; allowed: at most "
                                              r"1000000"):
            read_motion(bomb)
    finally:
        motion_file.MAX_MOTION_BYTES = original


def test_a_motion_file_with_nan_is_refused(written, tmp_path):
    m = read_motion(written / FILES["springs"])
    q = m.q.copy()
    q[1, 3] = np.nan
    path = write_motion(tmp_path / "nan.npz", dataclasses.replace(m, q=q))
    with pytest.raises(ConfigError, match=r"nan\.npz: q holds nan at index \[1, 3\]; allowed: "
                                          r"finite numbers only"):
        read_motion(path)


def test_a_motion_file_replaces_a_link_instead_of_writing_through_it(written, tmp_path):
    target = tmp_path / "precious.txt"
    target.write_text("keep me")
    (tmp_path / "m.npz").symlink_to(target)
    write_motion(tmp_path / "m.npz", read_motion(written / FILES["springs"]))
    assert target.read_text() == "keep me" and not (tmp_path / "m.npz").is_symlink()
