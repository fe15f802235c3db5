"""Tests of hexaleg.studies.sweep.runner: sweep points agree with the core analysis, physical
invariants of the spring designs, the optimiser against a fine grid, placement and robustness
studies, resumable results (interrupted and SIGKILLed runs), identical tables on every executor, and
bad input."""

from __future__ import annotations

import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from hexaleg.cli import main
from hexaleg.design.rules import joint_range
from hexaleg.dynamics.prepare import analyze
from hexaleg.errors import (
    ConfigError,
    ExecutorError,
    InvalidParameterError,
    UnknownNameError,
)
from hexaleg.motion.gait import GaitParams
from hexaleg.robot.springs import DeadZoneSpring
from hexaleg.studies.sweep.runner import (
    METRICS,
    SAVING_METRICS,
    RunSpec,
    SweepSpec,
    evaluator,
    optimise,
    parse_range,
    placement,
    robustness,
    run_sweep,
    summary,
)
from hexaleg.units import deg_to_rad, nmm_per_deg_to_nm_per_rad

SAMPLES = 200
RUN = RunSpec()


@pytest.fixture(scope="module")
def ev():
    return evaluator(RUN, {"samples": SAMPLES})


@pytest.fixture(scope="module")
def classes(ev):
    return {c: ev.robot.joints(c) for c in ("coxa", "femur", "tibia")}


def small_spec(**kw):
    springs = kw.pop("springs", {"coxa": {"k": (0.0, 0.05, 0.1, 0.2, 0.4), "theta_k": (0.005,
                                                                                       0.03)}})
    return SweepSpec(gait=kw.pop("gait", {"samples": 50}), springs=springs,
                     chunk_size=kw.pop("chunk_size", 3), **kw)


# --------------------------------------------------------------------------- points = analysis


def test_row_equals_fresh_analysis_of_the_centred_design(ev, classes):
    """A sweep point's metrics are those of analyze() with the same springs, neutral at the centre
    of each joint's range of motion plus the offset."""
    design = {"femur": {"k": 0.3, "theta_k": 0.04, "offset": -0.05},
              "tibia": {"k": 0.2, "k_minus": 0.5, "theta_minus": -0.03, "theta_plus": 0.08}}
    row = ev.row(classes, design)
    springs = {}
    for j in classes["femur"]:
        lo, hi = joint_range(ev.robot, ev.motion, j)
        springs[j] = DeadZoneSpring(0.3, theta_k=0.04, neutral=(lo + hi) / 2 - 0.05)
    for j in classes["tibia"]:
        lo, hi = joint_range(ev.robot, ev.motion, j)
        springs[j] = DeadZoneSpring(0.2, theta_minus=-0.03, theta_plus=0.08, stiffness_minus=0.5,
                                    neutral=(lo + hi) / 2)
    ref = analyze(ev.robot, ev.motion, springs)
    assert row["status"] == "ok"
    for key in METRICS:
        assert row[key] == pytest.approx(ref.metrics["total"][key], rel=1e-12, abs=1e-15)
        assert row[f"baseline.{key}"] == ref.baseline["total"][key]
    for key in SAVING_METRICS:
        assert row[f"saving.{key}"] == pytest.approx(ref.savings["total"][key], rel=1e-10,
                                                     abs=1e-13)
    # the cached torque basis reproduces the springs' own torques
    tau = ev.spring_torques(classes, design)
    np.testing.assert_allclose(tau, ref.tau_spring, rtol=1e-14, atol=1e-15)


def test_no_spring_and_never_engaged_spring_save_nothing(ev, classes):
    """k = 0, or a dead zone wider than the joint's whole motion, leaves the gait's energy as it
    is: every metric equals the baseline and every saving is exactly 0."""
    wide = 1.01 * max(ev.half_range[j] for j in classes["femur"])
    for design in ({"femur": {"k": 0.0, "theta_k": 0.05}}, {"femur": {"k": 5.0, "theta_k": wide}}):
        row = ev.row(classes, design)
        for key in METRICS:
            assert row[key] == pytest.approx(row[f"baseline.{key}"], rel=1e-13, abs=1e-16)
        for key in SAVING_METRICS:
            assert abs(row[f"saving.{key}"]) < 1e-12


def test_joule_loss_is_quadratic_in_stiffness(ev, classes):
    """With the force program on its unconstrained branch, motor torque is affine in k for a fixed
    dead zone, so the Joule loss ∫ c τ² is exactly quadratic in k: third differences vanish."""
    ks = [0.0, 0.1, 0.2, 0.3]
    joule = [ev.metrics(classes, {"coxa": {"k": k, "theta_k": 0.01}})["total"]["joule"]
             for k in ks]
    third = joule[3] - 3 * joule[2] + 3 * joule[1] - joule[0]
    assert abs(third) < 1e-12 * joule[0]
    assert joule[1] != joule[0]  # the spring does act


def test_dead_zone_fraction_scales_with_each_joints_range(ev, classes):
    design = {"tibia": {"k": 0.5, "dead_zone": 0.4}}
    springs = ev.springs(classes, design)
    for j in classes["tibia"]:
        assert springs[j].theta_k == pytest.approx(0.4 * ev.half_range[j])
        assert springs[j].neutral == pytest.approx(ev.centre[j])


# --------------------------------------------------------------------------- specs


def test_spec_from_toml_tables_ranges_and_paper_units(tmp_path):
    path = tmp_path / "spec.toml"
    path.write_text("""
[sweep]
metric = "joule"
motor = "AX-12A"
chunk_size = 7
[gait]
samples = 40
period = [0.8, 1.0]
[springs.femur]
k_nmm_per_deg = {start = 1, stop = 100, num = 3, scale = "log"}
theta_k_deg = 7.32
offset_deg = [-5, 0]
[springs.front]
joints = ["LF_coxa", "RF_coxa"]
k = 0.2
dead_zone = 0.3
""")
    spec = SweepSpec.from_toml(path)
    assert spec.metric == "joule" and spec.run.motor == "AX-12A" and spec.chunk_size == 7
    np.testing.assert_allclose(spec.springs["femur"]["k"],
                               nmm_per_deg_to_nm_per_rad([1.0, 10.0, 100.0]))
    assert spec.springs["femur"]["theta_k"] == pytest.approx(deg_to_rad(7.32))
    assert spec.joints == {"front": ("LF_coxa", "RF_coxa")}
    assert spec.n_points == 2 * 3 * 2
    assert len(spec.gaits()) == 2 and len(spec.designs()) == 6
    each = SweepSpec(springs=spec.springs, joints=spec.joints, layout="each")
    assert len(each.designs()) == 6 + 1
    assert [list(d) for d in each.designs()] == [["femur"]] * 6 + [["front"]]


def test_parse_range():
    assert parse_range("k", "0.5") == 0.5
    assert parse_range("k", "0.1,0.2") == (0.1, 0.2)
    np.testing.assert_allclose(parse_range("k", "0.1:10:3:log"), [0.1, 1.0, 10.0])
    np.testing.assert_allclose(parse_range("k", "0:1:5"), np.linspace(0, 1, 5))
    with pytest.raises(InvalidParameterError, match=r"num"):
        parse_range("k", "0:1:0")
    with pytest.raises(InvalidParameterError, match=r"start:stop:num"):
        parse_range("k", "a:b")


@pytest.mark.parametrize("springs, error, match", [
    ({"femur": {"k": (), "theta_k": 0.1}}, InvalidParameterError, "non-empty"),
    ({"femur": {"k": 1.0, "stiffnes": 2.0, "theta_k": 0.1}}, UnknownNameError,
     "stiffnes.*valid spring parameters are:.*dead_zone.*k_nmm_per_deg.*theta_k"),
    ({"femur": {"theta_k": 0.1}}, InvalidParameterError, "femur.k"),
    ({"femur": {"k": 1.0}}, InvalidParameterError, "exactly one of theta_k, dead_zone"),
    ({"femur": {"k": 1.0, "theta_k": 0.1, "dead_zone": 0.2}}, InvalidParameterError,
     "exactly one"),
    ({"femur": {"k": -1.0, "theta_k": 0.1}}, InvalidParameterError, "femur.k"),
    ({"femur": {"k": 1.0, "dead_zone": 1.2}}, InvalidParameterError, r"\(0, 1\)"),
    ({"femur": {"k": 1.0, "dead_zone": (0.0, 0.5)}}, InvalidParameterError, r"\(0, 1\)"),
    ({"femur": {"k": 1.0, "theta_k": (0.0, 0.1)}}, InvalidParameterError, "femur.theta_k"),
    ({"femur": {"k": 1.0, "theta_minus": 0.1, "theta_plus": (0.2, 0.05)}}, InvalidParameterError,
     "theta_minus"),
])
def test_bad_spring_grids(springs, error, match):
    with pytest.raises(error, match=match):
        SweepSpec(springs=springs)


def test_bad_spec_tables():
    with pytest.raises(InvalidParameterError, match=r"empty grid"):
        SweepSpec.from_mapping({"springs": {"femur": {"k": [], "theta_k": 0.1}}})
    with pytest.raises(InvalidParameterError, match=r"num"):
        SweepSpec.from_mapping({"springs": {"femur": {"k": {"start": 0, "stop": 1, "num": 0},
                                                      "theta_k": 0.1}}})
    with pytest.raises(UnknownNameError, match=r"gait parameter 'perod'.*period"):
        SweepSpec.from_mapping({"gait": {"perod": [1.0]}})
    with pytest.raises(UnknownNameError, match=r"table.*'spring'.*springs"):
        SweepSpec.from_mapping({"spring": {}})
    with pytest.raises(UnknownNameError, match=r"metric 'energy'.*electrical"):
        SweepSpec(metric="energy")
    with pytest.raises(InvalidParameterError, match=r"period"):
        SweepSpec(gait={"period": (1.0, -1.0)})
    with pytest.raises(ConfigError, match=r"k_nmm_per_deg|given twice"):
        SweepSpec.from_mapping({"springs": {"femur": {"k": 1.0, "k_nmm_per_deg": 2.0,
                                                      "theta_k": 0.1}}})


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
    import json

    run_sweep(small_spec(), tmp_path / "out", executor="serial")
    manifest = json.loads((tmp_path / "out" / "manifest.json").read_text())
    assert manifest["spec"]["springs"]["coxa"]["theta_k"] == [0.005, 0.03]
    assert manifest["robot"]["nv"] == 24 and manifest["motor"] == "AX-18A"
    assert set(manifest["versions"]) >= {"hexaleg", "pinocchio", "numpy", "python"}
    assert manifest["n_points"] == 10


# --------------------------------------------------------------------------- optimisation


def test_optimum_matches_a_fine_grid_minimum():
    """Coxa springs at a 0.5 s period: the optimiser's (k, θ_k) is at least as good as the best of
    a fine 40 × 12 grid over the same box, and lies next to it."""
    ev = evaluator(RUN, {"samples": 100, "period": 0.5})
    joints = ev.robot.joints("coxa")
    k_bounds, t_bounds = (0.01, 1.0), (0.002, 0.05)
    opt = optimise(ev, "coxa", joints, k_bounds=k_bounds, theta_bounds=t_bounds, grid=(6, 3))
    ks, ts = np.geomspace(*k_bounds, 40), np.linspace(*t_bounds, 12)
    grid = np.array([[ev.value({"coxa": joints}, {"coxa": {"k": k, "theta_k": t}}) for t in ts]
                     for k in ks])
    i, j = np.unravel_index(np.argmin(grid), grid.shape)
    assert opt.value <= grid[i, j] + 1e-9 * grid[i, j]
    # …and not much better: the grid's minimum is the same valley, within 2 % of the saving
    assert grid[i, j] - opt.value < 0.02 * (opt.baseline - opt.value)
    assert abs(math.log(opt.k / ks[i])) <= 1.5 * math.log(ks[1] / ks[0])
    assert abs(opt.theta_k - ts[j]) <= 1.5 * (ts[1] - ts[0])
    assert opt.saving > 0.01 and opt.value < opt.grid_value


def test_placement_combines_per_class_optima(ev, classes):
    optima, table = placement(ev, classes, k_bounds=(0.01, 1.0), grid=(4, 2))
    assert len(table) == 7 and set(table["springs"]) >= {"coxa", "femur+tibia",
                                                         "coxa+femur+tibia"}
    for g, o in optima.items():
        row = table[table["springs"] == g].iloc[0]
        assert row["value"] == o.value and row["saving"] == pytest.approx(o.saving)
        assert o.value <= o.grid_value  # the search never ends worse than its start
    both = table[table["springs"] == "coxa+tibia"].iloc[0]
    direct = ev.value(classes, {"coxa": optima["coxa"].design(),
                                "tibia": optima["tibia"].design()})
    assert both["value"] == direct
    assert (table["benefits"] == (table["saving"] > 0)).all()
    assert table["saving"].is_monotonic_decreasing


def test_robustness_at_nominal_equals_the_design_and_varies_off_it(ev, classes):
    design = {"coxa": {"k": 0.1, "theta_k": 0.005}}
    table = robustness(RUN, GaitParams(samples=SAMPLES), classes, design,
                       factors=(0.8, 1.0, 1.2))
    assert len(table) == 6 and (table["status"] == "ok").all()
    nominal = ev.row(classes, design)["saving.electrical"]
    at_one = table[table["factor"] == 1.0]["saving"]
    np.testing.assert_allclose(at_one, nominal, rtol=1e-9)
    period = table[table["parameter"] == "period"]
    np.testing.assert_allclose(period["gait value"], [0.8, 1.0, 1.2])
    assert period["saving"].nunique() == 3
    with pytest.raises(UnknownNameError, match=r"duty_factor.*period, stride_length"):
        robustness(RUN, GaitParams(samples=SAMPLES), classes, design, parameters=("duty_factor",))


# --------------------------------------------------------------------------- CLI


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


def test_free_offset_preload_beats_the_centred_design_on_the_tibia():
    """On the slow default gait the tibia motors mostly hold the body up: a centred dead-zone
    spring (zero mean torque over a symmetric motion) can barely help, while a spring whose
    neutral is moved off the motion carries part of that steady load."""
    ev = evaluator(RUN, {"samples": 100})
    joints = ev.robot.joints("tibia")
    centred = optimise(ev, "tibia", joints, k_bounds=(0.01, 1.0), grid=(4, 3))
    free = optimise(ev, "tibia", joints, k_bounds=(0.01, 1.0), offset_bounds=(-1.0, 1.0),
                    grid=(4, 3, 3))
    assert centred.offset == 0.0 and -1.0 <= free.offset <= 1.0
    assert centred.saving < 0.01 < 0.05 < free.saving
    row = ev.row({"tibia": joints}, {"tibia": free.design()})
    assert row["electrical"] == free.value
    with pytest.raises(InvalidParameterError, match="offset_bounds"):
        optimise(ev, "tibia", joints, offset_bounds=(0.5, -0.5))
    with pytest.raises(InvalidParameterError, match="start"):
        optimise(ev, "tibia", joints, offset_bounds=(-1.0, 1.0), start=(0.1, 0.01))  # no offset


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


def test_clear_cache_forgets_built_evaluators():
    from hexaleg.studies.sweep.runner import clear_cache, evaluator

    gait = {"samples": 40}
    first = evaluator(RunSpec(), gait)
    assert evaluator(RunSpec(), gait) is first  # built once per process
    clear_cache()
    again = evaluator(RunSpec(), gait)
    assert again is not first and evaluator(RunSpec(), gait) is again
    assert again.baseline["total"]["electrical"] == first.baseline["total"]["electrical"]
