"""Tests of hexaleg.sweep.runner: resumable sweeps (interrupted runs; pool sweeps SIGKILLed
at random points resume exactly and leave no process; a truncated part recomputed), one writer
per directory, a different spec refused, identical tables on every executor, the manifest, the
summary and the CLI, and a gait axis."""

from __future__ import annotations

import dataclasses
import json
import os
import random
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import pandas as pd
import pytest
from processes import HAS_PROC, children, wait_gone

from hexaleg.cli import main
from hexaleg.errors import (
    ConfigError,
    DirectoryLockedError,
    ExecutorError,
    HexalegWarning,
    InvalidParameterError,
    OutputError,
    UnknownNameError,
)
from hexaleg.sweep.runner import run_sweep
from hexaleg.sweep.spec import SweepSpec
from hexaleg.sweep.store import MANIFEST, read_table
from hexaleg.sweep.summary import summary


def small_spec(**kw):
    springs = kw.pop("springs", {"coxa": {"k": (0.0, 0.05, 0.1, 0.2, 0.4), "theta_k": (0.005,
                                                                                       0.03)}})
    return SweepSpec(gait=kw.pop("gait", {"samples": 50}), springs=springs,
                     chunk_size=kw.pop("chunk_size", 3), **kw)


def test_unknown_group_lists_classes_and_joints(tmp_path):
    spec = small_spec(springs={"femurs": {"k": 1.0, "theta_k": 0.1}})
    with pytest.raises(UnknownNameError, match=r"'femurs'.*LF_femur.*coxa, femur, tibia"):
        run_sweep(spec, tmp_path / "out", executor="serial")
    assert not (tmp_path / "out").exists()


# --------------------------------------------------------------------------- running and resuming


def test_interrupted_sweep_resumes_without_recomputing(tmp_path):
    spec = small_spec()
    full = run_sweep(spec, tmp_path / "full", executor="serial")
    assert full.computed == spec.n_points == 10 and full.reused == 0
    assert list(full.table["point"]) == list(range(10))
    assert (full.table["status"] == "ok").all()

    class Stop(Exception):
        pass

    seen = []

    def stop_after_two(rows):
        seen.append(len(rows))
        if len(seen) == 2:
            raise Stop

    with pytest.raises(Stop):
        run_sweep(spec, tmp_path / "cut", executor="serial", on_chunk=stop_after_two)
    again = run_sweep(spec, tmp_path / "cut", executor="serial")
    assert seen == [3, 3] and again.reused == 6 and again.computed == 4
    pd.testing.assert_frame_equal(again.table, full.table)
    third = run_sweep(spec, tmp_path / "cut", executor="serial")
    assert third.computed == 0 and third.reused == 10


KILL_SPEC = """
[sweep]
chunk_size = 1
[gait]
samples = 60
[springs.tibia]
k = {start = 0.0, stop = 0.5, num = 12}
theta_k = 0.02
"""
# The sweep a trial kills: a 2-worker pool; the writer pauses after each part so that a kill
# lands anywhere between the first part and the last, and stalls after part argv[3] so that the
# sweep cannot finish before the kill, however loaded the machine.
KILLED_SWEEP = """
import sys, time
from hexaleg.sweep import SweepSpec, run_sweep
written = []
def pace(rows):
    written.append(len(rows))
    time.sleep(120 if len(written) >= int(sys.argv[3]) else 0.03)
run_sweep(SweepSpec.from_toml(sys.argv[1]), sys.argv[2], executor="process", workers=2,
          on_chunk=pace)
"""


@pytest.fixture(scope="module")
def kill_spec(tmp_path_factory):
    """The killed sweep's spec file and its uninterrupted table."""
    spec_file = tmp_path_factory.mktemp("kill") / "spec.toml"
    spec_file.write_text(KILL_SPEC)
    full = run_sweep(SweepSpec.from_toml(spec_file), spec_file.parent / "full",
                     executor="serial")
    return spec_file, full.table


def _on_disk(out):
    """Part name → (inode, mtime) of the parts in ``out``, and the points they hold."""
    parts = {p.name: (p.stat().st_ino, p.stat().st_mtime_ns) for p in out.glob("part-*")}
    points = sum(len(pd.read_parquet(out / name)) for name in parts)
    return parts, points


@pytest.mark.skipif(not HAS_PROC, reason="finds the pool's workers in Linux /proc")
@pytest.mark.parametrize("trial", range(4))
def test_sigkilled_sweep_resumes_exactly_and_leaves_no_process(kill_spec, tmp_path, trial):
    """SIGKILL at a random point of a pool sweep: the workers end with it, the resumed sweep
    reuses every part on disk untouched, computes only the rest, and equals the uninterrupted
    table."""
    spec_file, full = kill_spec
    rng = random.Random(trial)
    target, extra = rng.randrange(0, 10), rng.uniform(0.0, 0.03)
    out = tmp_path / "killed"
    proc = subprocess.Popen([sys.executable, "-c", KILLED_SWEEP, str(spec_file), str(out),
                             str(target + 2)], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 120  # a hang guard
    pool = set()
    while time.monotonic() < deadline and proc.poll() is None and (
            len(pool) < 2 or len(list(out.glob("part-*.parquet"))) < target):
        pool = children(proc.pid)
        time.sleep(0.005)
    time.sleep(extra)
    pool |= children(proc.pid)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    assert proc.returncode == -signal.SIGKILL, proc.stderr.read() if proc.stderr else ""
    assert len(pool) == 2 and wait_gone(pool) == set()  # no orphan workers
    before, points = _on_disk(out)
    assert target <= points < 12  # killed on the way
    with pytest.warns(HexalegWarning, match=rf"took over the lock .*pid {proc.pid}"):
        resumed = run_sweep(SweepSpec.from_toml(spec_file), out, executor="serial")
    assert (resumed.reused, resumed.computed) == (points, 12 - points)
    after, _ = _on_disk(out)
    assert {name: after[name] for name in before} == before  # no finished point recomputed
    pd.testing.assert_frame_equal(resumed.table, full)
    assert not list(out.glob(".*tmp")) and not (out / ".lock").exists()


def test_two_sweeps_into_one_directory_one_runs_the_other_is_refused(kill_spec, tmp_path,
                                                                       capsys):
    spec_file, full = kill_spec
    out = tmp_path / "shared"
    started, go_on = threading.Event(), threading.Event()

    def first_chunk_waits(rows):
        started.set()
        assert go_on.wait(60)  # a hang guard

    result = {}
    first = threading.Thread(target=lambda: result.update(table=run_sweep(
        SweepSpec.from_toml(spec_file), out, executor="serial",
        on_chunk=first_chunk_waits).table))
    first.start()
    try:
        assert started.wait(60)
        code = main(["sweep", str(spec_file), "--out", str(out), "--executor", "serial"])
        err = capsys.readouterr().err
        assert code == 2
        assert f"another sweep (pid {os.getpid()} on host {socket.gethostname()}, started" in err
        with pytest.raises(DirectoryLockedError):
            run_sweep(SweepSpec.from_toml(spec_file), out, executor="serial")
    finally:
        go_on.set()
        first.join(60)
    pd.testing.assert_frame_equal(result["table"], full)
    assert len(pd.read_parquet(out)) == 12  # not twice as many rows as points
    assert run_sweep(SweepSpec.from_toml(spec_file), out, executor="serial").computed == 0


def test_a_truncated_part_is_recomputed_with_a_warning(kill_spec, tmp_path):
    spec_file, full = kill_spec
    spec = dataclasses.replace(SweepSpec.from_toml(spec_file), chunk_size=5)
    run_sweep(spec, tmp_path / "out", executor="serial")
    part = tmp_path / "out" / "part-0000005-0000009.parquet"
    part.write_bytes(part.read_bytes()[:100])
    with pytest.raises(OutputError, match="part-0000005-0000009"):
        read_table(tmp_path / "out")
    with pytest.warns(HexalegWarning, match=r"part-0000005-0000009\.parquet cannot be read"):
        again = run_sweep(spec, tmp_path / "out", executor="serial")
    assert (again.reused, again.computed) == (7, 5)
    pd.testing.assert_frame_equal(again.table, full)


def test_different_spec_in_existing_directory_is_refused(tmp_path):
    run_sweep(small_spec(), tmp_path / "out", executor="serial")
    other = small_spec(springs={"coxa": {"k": (0.0, 0.05), "theta_k": (0.005, 0.03)}})
    with pytest.raises(ConfigError, match=r"springs\.coxa\.k: \[0\.0, 0\.05, 0\.1, 0\.2, 0\.4\] "
                                          r"→ \[0\.0, 0\.05\]"):
        run_sweep(other, tmp_path / "out", executor="serial")


def test_same_table_on_serial_process_and_dask_executors(tmp_path):
    distributed = pytest.importorskip("distributed")
    spec = small_spec(gait={"samples": 50, "period": (0.8, 1.0)})
    # the pool first: its (forked) workers must build these gaits' analyses themselves
    pool = run_sweep(spec, tmp_path / "pool", executor="process", workers=2).table
    serial = run_sweep(spec, tmp_path / "serial", executor="serial").table
    pd.testing.assert_frame_equal(pool, serial, check_exact=True)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        dask = run_sweep(spec, tmp_path / "dask", executor="dask",
                         scheduler=cluster.scheduler_address).table
    pd.testing.assert_frame_equal(dask, serial, check_exact=True)


def test_unreachable_scheduler_names_the_address_and_loses_nothing(tmp_path, monkeypatch):
    pytest.importorskip("distributed")
    monkeypatch.setattr("hexaleg.sweep.executors.CONNECT_TIMEOUT", 1.0)
    spec = small_spec()
    def ctrl_c(rows):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_sweep(spec, tmp_path / "out", executor="serial", on_chunk=ctrl_c)
    before = sorted(p.name for p in (tmp_path / "out").glob("part-*"))
    assert len(before) == 1
    address = "tcp://127.0.0.1:1"
    with pytest.raises(ExecutorError, match=r"tcp://127\.0\.0\.1:1"):
        run_sweep(spec, tmp_path / "out", executor="dask", scheduler=address)
    assert sorted(p.name for p in (tmp_path / "out").glob("part-*")) == before
    assert run_sweep(spec, tmp_path / "out", executor="serial").reused == 3


def test_executor_arguments_are_checked(tmp_path):
    with pytest.raises(InvalidParameterError, match=r"executor.*process, serial, dask"):
        run_sweep(small_spec(), tmp_path / "a", executor="threads")
    with pytest.raises(InvalidParameterError, match=r"scheduler"):
        run_sweep(small_spec(), tmp_path / "b", executor="dask")


def test_manifest_records_spec_robot_and_versions(tmp_path):
    run_sweep(small_spec(), tmp_path / "out", executor="serial")
    manifest = json.loads((tmp_path / "out" / MANIFEST).read_text())
    assert manifest["spec"]["springs"]["coxa"]["theta_k"] == [0.005, 0.03]
    assert manifest["robot"]["nv"] == 24 and manifest["motor"] == "AX-18A"
    assert set(manifest["versions"]) >= {"hexaleg", "pinocchio", "numpy", "python"}
    assert manifest["n_points"] == 10


# --------------------------------------------------------------------------- summary


def test_summary_reports_saving_against_no_springs(tmp_path):
    result = run_sweep(small_spec(), tmp_path / "s", executor="serial")
    text = summary(result.table)
    best = result.table.loc[result.table["electrical"].idxmin()]
    assert f"saving {100 * best['saving.electrical']:+.2f} %" in text
    assert Path(result.directory) == tmp_path / "s"


def test_gait_axis_faster_gait_gains_more_from_coxa_springs(tmp_path):
    """Sweeping the period: the coxa joints swing the legs back and forth, so their inertial
    torques grow like ω² while the steady load does not; a spring that stores that swing energy
    saves a larger fraction at a faster gait."""
    spec = SweepSpec(gait={"samples": 100, "period": (0.5, 1.0)},
                     springs={"coxa": {"k": (0.05, 0.1, 0.2, 0.3), "theta_k": 0.002}})
    table = run_sweep(spec, tmp_path / "gait", executor="serial").table
    assert len(table) == 8 and list(table["gait.period"]) == [0.5] * 4 + [1.0] * 4
    best = table.groupby("gait.period")["saving.electrical"].max()
    assert best[0.5] > 2 * best[1.0] > 0
    # each gait has its own baseline: the mean Joule power grows with the inertial torques
    base = table.groupby("gait.period")["baseline.joule"].first()
    assert base[0.5] / 0.5 > base[1.0] / 1.0
