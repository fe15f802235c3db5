"""Tests of hexaleg.studies.sweep.runner: resumable sweeps (interrupted and SIGKILLed runs), a
different spec refused, identical tables on every executor, the manifest, the summary and the CLI,
and a gait axis."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pandas as pd
import pytest

from hexaleg.cli import main
from hexaleg.errors import ConfigError, ExecutorError, InvalidParameterError, UnknownNameError
from hexaleg.studies.sweep.runner import run_sweep, summary
from hexaleg.studies.sweep.spec import SweepSpec


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


def test_sigkilled_cli_sweep_resumes_to_the_same_table(tmp_path):
    spec_file = tmp_path / "spec.toml"
    spec_file.write_text("""
[sweep]
chunk_size = 2
[gait]
samples = 200
[springs.tibia]
k = {start = 0.0, stop = 0.5, num = 40}
theta_k = 0.02
""")
    out = tmp_path / "killed"
    args = [sys.executable, "-c", "import sys; from hexaleg.cli import main; "
            "sys.exit(main(sys.argv[1:]))", "sweep", str(spec_file), "--out", str(out),
            "--executor", "serial"]
    proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 60
    while len(list(out.glob("part-*.parquet"))) < 3 and time.monotonic() < deadline:
        time.sleep(0.005)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    assert proc.returncode == -signal.SIGKILL
    n_parts = len(list(out.glob("part-*.parquet")))
    assert 3 <= n_parts < 20  # killed half-way
    spec = SweepSpec.from_toml(spec_file)
    resumed = run_sweep(spec, out, executor="serial")
    assert resumed.reused >= 6 and resumed.reused + resumed.computed == 40
    fresh = run_sweep(spec, tmp_path / "fresh", executor="serial")
    pd.testing.assert_frame_equal(resumed.table, fresh.table)


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
    monkeypatch.setattr("hexaleg.studies.sweep.executors.CONNECT_TIMEOUT", 1.0)
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
    manifest = json.loads((tmp_path / "out" / "manifest.json").read_text())
    assert manifest["spec"]["springs"]["coxa"]["theta_k"] == [0.005, 0.03]
    assert manifest["robot"]["nv"] == 24 and manifest["motor"] == "AX-18A"
    assert set(manifest["versions"]) >= {"hexaleg", "pinocchio", "numpy", "python"}
    assert manifest["n_points"] == 10


# --------------------------------------------------------------------------- summary and CLI


def test_cli_sweep_prints_summary_and_path(tmp_path, capsys):
    out = tmp_path / "cli"
    code = main(["sweep", "--joints", "coxa", "--k", "0,0.1,0.2", "--theta-k", "0.01",
                 "--samples", "40", "--executor", "serial", "--out", str(out)])
    text = capsys.readouterr().out
    assert code == 0
    assert "3 points" in text and "coxa: electrical =" in text and str(out) in text
    table = pd.read_parquet(next(out.glob("part-*.parquet")))
    assert summary(table).splitlines()[1] in text
    assert main(["sweep", "--joints", "coxas", "--k", "0.1", "--theta-k", "0.01",
                 "--executor", "serial", "--out", str(tmp_path / "bad")]) == 2
    assert "coxa, femur, tibia" in capsys.readouterr().err
    assert main(["sweep", "--joints", "coxa", "--k", "0.1", "--theta-k", "0.01",
                 "--executor", "serial", "--out", str(tmp_path / "bad"),
                 "--metric", "nope"]) == 2
    assert "electrical" in capsys.readouterr().err


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
