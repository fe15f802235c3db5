"""Tests of hexaleg.report.build: the report's stiffness curve against evaluations at
that stiffness, physical invariants of the report, infeasible curve points and friction usage."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from hexaleg.commands.report.write import PLOTS
from hexaleg.design.rules import PAPER_ALPHA, k_M
from hexaleg.dynamics.contact import friction_usage
from hexaleg.dynamics.prepare import analyze
from hexaleg.outputs.html import render_html
from hexaleg.report.build import build_report
from hexaleg.report.config import ReportConfig
from hexaleg.robot.catalogue import DEFAULT_MOTOR
from hexaleg.robot.springs import SpringSet

SAMPLES = 200


def _v(q):
    assert set(q) == {"value", "unit"}, q
    return q["value"]


def test_stiffness_curve_points_equal_evaluations_at_that_stiffness(data, independent, robot):
    motion, springs, _ = independent
    c = data["stiffness_curve"]
    ks = _v(c["stiffness"])
    assert ks[0] == 0 and ks[-1] == pytest.approx(10 * _v(c["k_M"]))  # default range
    assert len(ks) == 5 and np.all(np.diff(ks) > 0)
    for i in (0, 3):
        trial = SpringSet({j: s.with_stiffness(ks[i]) for j, s in springs.items()})
        a = analyze(robot, motion, trial, motor=DEFAULT_MOTOR)
        for m, row in c["metrics"].items():
            assert _v(row["values"])[i] == pytest.approx(a.metrics["total"][m], rel=1e-10)
    for row in c["metrics"].values():
        # k = 0 is the gait without springs: saving exactly 0
        assert _v(row["values"])[0] == pytest.approx(_v(row["baseline"]), rel=1e-12)
        assert _v(row["saving"])[0] == pytest.approx(0.0, abs=1e-9)
        best = row["best"]
        assert _v(best["value"]) == min(_v(row["values"]))
        assert _v(best["stiffness"]) == ks[int(np.argmin(_v(row["values"])))]
    assert c["k_M_per_joint"]["LF_femur"]["value"] == pytest.approx(
        k_M(robot, motion, "LF_femur", alpha=PAPER_ALPHA))



def test_report_invariants(data, report_written, robot):
    r, _ = report_written
    # the feet carry the weight on average over a periodic cycle (Newton, z)
    fz = r.analysis.forces[..., 2].sum(1)
    assert fz.mean() == pytest.approx(_v(data["forces"]["weight"]), rel=2e-3)
    assert _v(data["forces"]["weight"]) == pytest.approx(robot.mass * 9.81)
    assert _v(data["forces"]["peak_friction_usage"]) <= 1 + 1e-6  # inside the friction cone
    # per-joint energies add up to the totals, with and without springs
    for key, joints in data["energy"]["joints"].items():
        if key in ("peak_torque", "rms_torque", "mean_abs_torque"):
            continue
        for side in ("with_springs", "baseline"):
            assert sum(_v(j[side]) for j in joints.values()) == pytest.approx(
                _v(data["energy"]["totals"][key][side]), rel=1e-9)
    # the net work of a conservative periodic cycle is ~0 compared with the absolute work
    assert abs(_v(data["energy"]["net_work"]["with_springs"])) < 1e-6 * _v(
        data["energy"]["totals"]["absolute_work"]["with_springs"])
    # the answer's linear springs store U = ½ k (q − q_r)² − τ₀ (q − q_r) (Hooke)
    s = r.analysis.springs["LF_femur"]
    c = robot.column("LF_femur")
    d = r.analysis.q[:, c] - s.reference
    np.testing.assert_allclose(r.analysis.spring_energy[:, c], 0.5 * s.stiffness * d**2
                               - s.torque_at_reference * d, atol=1e-15)
    u = friction_usage(r.analysis.forces, r.motion.stance.astype(bool), 0.6)
    assert np.all(u[~r.motion.stance.astype(bool)] == 0)



def test_infeasible_curve_points_are_listed_not_hidden(robot):
    cfg = ReportConfig.from_toml({"gait": {"samples": SAMPLES},
                                  "report": {"stiffness_points": 3, "stiffness_max": 20.0}})
    r = build_report(cfg, robot=robot)
    c = r.data["stiffness_curve"]
    assert [_v(p["stiffness"]) for p in c["infeasible"]] == [20.0]  # beyond the stall torque
    assert "torque limit" in c["infeasible"][0]["error"]
    row = c["metrics"]["electrical"]
    assert _v(row["values"])[2] is None and _v(row["saving"])[2] is None
    assert _v(row["best"]["stiffness"]) == 0.0  # the centred femur springs only cost energy
    assert r.curve.feasible.tolist() == [True, True, False]
    html = render_html(r.data | {"files": []}, dict.fromkeys(PLOTS, "data:,"))
    assert "1 points infeasible" in html and "torque limit" in html


def _crawl_config(tmp_path) -> tuple[Path, dict]:
    """The crawl config of docs/gaits.md, as a file and parsed."""
    import re

    import tomllib

    page = (Path(__file__).resolve().parents[2] / "docs" / "gaits.md").read_text()
    text = re.search(r"```toml\n(# crawl\.toml.*?)```", page, re.S)
    assert text, "docs/gaits.md has no crawl.toml block"
    path = tmp_path / "crawl.toml"
    path.write_text(text.group(1))
    return path, tomllib.loads(text.group(1))


def test_solo12_crawls_through_the_report_with_the_docs_config(tmp_path):
    """``hexaleg report --robot solo12 --config crawl.toml``, the file of docs/gaits.md."""
    import json

    from hexaleg.cli import main

    path, _ = _crawl_config(tmp_path)
    assert main(["report", "--robot", "solo12", "--config", str(path),
                 "--out", str(tmp_path / "out")]) == 0
    data = json.loads((tmp_path / "out" / "report.json").read_text())
    gait = data["gait"]
    assert gait["pattern"] == "crawl" and gait["min_stance_feet"] == 3
    assert _v(gait["static_margin"]) >= _v(gait["shift"]["target"]) > 0.02
    assert _v(data["forces"]["peak_friction_usage"]) <= 1 + 1e-6
    assert "crawl" in (tmp_path / "out" / "report.html").read_text()


@pytest.mark.parametrize("name", ["anymal", "anymal_c", "go2", "a1"])
def test_the_other_registry_quadrupeds_crawl_through_the_report(name, tmp_path):
    from hexaleg.robot.registry import description

    _, table = _crawl_config(tmp_path)
    table["gait"]["samples"] = 60
    table["report"].update(stiffness_points=2, paper_samples=16)
    desc = description(name)
    robot = desc.load()
    report = build_report(ReportConfig.for_robot(desc, robot, table), robot=robot)
    gait = report.data["gait"]
    assert gait["pattern"] == "crawl" and gait["shift"] is not None
    assert _v(gait["static_margin"]) >= _v(gait["shift"]["target"])
    assert np.all(report.analysis.forces[..., 2][report.motion.stance] > 0)
    assert np.isfinite(_v(report.data["energy"]["totals"]["electrical"]["baseline"]))
