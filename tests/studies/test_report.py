"""Tests of hexaleg.studies.report.build: the numbers of report.json against the analysis API
computed here independently, physical invariants of the report, the self-contained HTML, what a
browser shows, the default CLI run and bad input."""

from __future__ import annotations

import base64
import json
import re
import subprocess
import tempfile

import numpy as np
import pytest
from browser import CHROMIUM_FLAGS, chromium, finish, page_requests, start_screenshot
from PIL import Image

from hexaleg import GaitParams, analyze, tripod_gait
from hexaleg.cli import main
from hexaleg.design.rules import PAPER_ALPHA, k_M, paper_style_springs
from hexaleg.dynamics.forces import ContactParams
from hexaleg.errors import ConfigError, InvalidParameterError, OutputError, UnknownNameError
from hexaleg.robot.motor import DEFAULT_MOTOR, motor
from hexaleg.robot.springs import SpringSet
from hexaleg.studies.paper.model import PAPER_K_M, PaperJoint, k_M_paper_number
from hexaleg.studies.report.build import (
    PLOTS,
    ReportConfig,
    ReportParams,
    SpringDesign,
    build_report,
    friction_usage,
    render_html,
    write_report,
)

SAMPLES = 200
SMALL = f"""
[gait]
samples = {SAMPLES}

[report]
title = "test report"
stiffness_points = 5

[view]
fps = 30
"""
SECTIONS = ("summary", "angles", "torques", "power", "forces", "energy", "cot", "transform",
            "curve", "paper")


@pytest.fixture(scope="module")
def written(tmp_path_factory, robot):
    """The report of a 200-sample default gait, written once for the module (the paper's
    single-joint numbers at the default samples are cached for the other runs)."""
    out = tmp_path_factory.mktemp("report")
    (out / "small.toml").write_text(SMALL)
    r = write_report(out / "out", ReportConfig.from_toml(out / "small.toml"), robot=robot,
                     progress=None)
    return r, out / "out"


@pytest.fixture(scope="module")
def data(written):
    return json.loads((written[1] / "report.json").read_text())


@pytest.fixture(scope="module")
def independent(robot):
    """The same gait analysed through the public API, without the report module."""
    motion = tripod_gait(robot, GaitParams(samples=SAMPLES))
    springs = paper_style_springs(robot, motion, "femur")
    a = analyze(robot, motion, springs, motor=DEFAULT_MOTOR, objective="joule")
    return motion, springs, a


def _v(q):
    assert set(q) == {"value", "unit"}, q
    return q["value"]


# --------------------------------------------------------------------------- numbers = the API's


def test_energy_numbers_equal_the_analysis_api(data, independent, robot):
    _, _, a = independent
    totals = data["energy"]["totals"]
    assert set(totals) == set(a.savings["total"])
    for key, row in totals.items():
        assert _v(row["with_springs"]) == pytest.approx(a.metrics["total"][key], rel=1e-12)
        assert _v(row["without_springs"]) == pytest.approx(a.baseline["total"][key], rel=1e-12)
        assert _v(row["saving"]) == pytest.approx(100 * a.savings["total"][key], rel=1e-9,
                                                  abs=1e-12)
        assert row["saving"]["unit"] == "%"
        assert row["with_springs"]["unit"] == ("N·m" if "torque" in key else "J")
    for key, joints in data["energy"]["joints"].items():
        for j, name in enumerate(robot.joint_names):
            assert _v(joints[name]["with_springs"]) == pytest.approx(
                a.metrics["joint"][key][j], rel=1e-12, abs=1e-15)
            assert _v(joints[name]["without_springs"]) == pytest.approx(
                a.baseline["joint"][key][j], rel=1e-12, abs=1e-15)
    cot = data["cost_of_transport"]["metrics"]
    assert set(cot) == set(a.metrics["cost_of_transport"])
    for key, row in cot.items():
        assert _v(row["with_springs"]) == pytest.approx(a.metrics["cost_of_transport"][key])
        assert _v(row["without_springs"]) == pytest.approx(a.baseline["cost_of_transport"][key])
    assert _v(data["cost_of_transport"]["distance"]) == pytest.approx(0.06)


def test_joint_force_and_spring_numbers_equal_the_api(data, independent, robot):
    motion, springs, a = independent
    for j, name in enumerate(robot.joint_names):
        row = data["joints"][name]
        assert _v(row["peak_motor_torque"]) == pytest.approx(np.abs(a.tau_motor[:, j]).max())
        assert _v(row["peak_spring_torque"]) == pytest.approx(np.abs(a.tau_spring[:, j]).max(),
                                                              abs=1e-15)
        assert _v(row["angle_min"]) == pytest.approx(motion.q[:, 7 + j].min())
        assert _v(row["peak_power"]) == pytest.approx(np.abs(a.power[:, j]).max())
    assert set(data["springs"]["joints"]) == set(springs) == set(robot.joints("femur"))
    for name, s in springs.items():
        row = data["springs"]["joints"][name]
        assert _v(row["stiffness"]) == pytest.approx(s.stiffness)
        assert _v(row["k_M"]) == pytest.approx(k_M(robot, motion, name))  # eq. 19, α = 1.05
        assert _v(row["stiffness_over_k_M"]) == pytest.approx(1.0)
        assert _v(row["theta_plus"]) == pytest.approx(s.theta_k)
    mu = ContactParams().mu
    stance = motion.stance.astype(bool)
    for i, leg in enumerate(robot.leg_names):
        f = a.forces[:, i]
        ft, fn = np.hypot(f[:, 0], f[:, 1]), f[:, 2]
        use = np.where(stance[:, i] & (fn > 0), ft / (mu * np.where(fn > 0, fn, 1.0)), 0.0)
        row = data["forces"]["legs"][leg]
        assert _v(row["peak_normal_force"]) == pytest.approx(fn.max())
        assert _v(row["peak_friction_usage"]) == pytest.approx(use.max())


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


def test_paper_reference_numbers_come_from_the_paper_module(data):
    p = data["paper"]
    assert _v(p["k_M_printed"]) == PAPER_K_M
    assert _v(p["k_M_paper_number"]) == pytest.approx(k_M_paper_number())
    assert _v(p["k_M"]) == pytest.approx(PaperJoint().k_M())
    assert p["k_M"]["unit"] == "N·m/rad"
    lo, hi = _v(p["peak_flat_interval"])
    assert lo == pytest.approx(PaperJoint().k_M())  # k_M is the lower end of the flat optimum
    assert hi > lo
    assert _v(p["peak_saving"]) == pytest.approx(100 * PaperJoint().closed_form_peak_saving())
    assert p["k_E_verdict"].startswith(("reproduced", "not reproduced"))
    assert p["saving_verdict"].startswith(("reproduced", "not reproduced"))


# --------------------------------------------------------------------------- physical invariants


def test_report_invariants(data, written, robot):
    r, _ = written
    # the feet carry the weight on average over a periodic cycle (Newton, z)
    fz = r.analysis.forces[..., 2].sum(1)
    assert fz.mean() == pytest.approx(_v(data["forces"]["weight"]), rel=2e-3)
    assert _v(data["forces"]["weight"]) == pytest.approx(robot.mass * 9.81)
    assert _v(data["forces"]["peak_friction_usage"]) <= 1 + 1e-6  # inside the friction cone
    # per-joint energies add up to the totals, with and without springs
    for key, joints in data["energy"]["joints"].items():
        if key in ("peak_torque", "rms_torque", "mean_abs_torque"):
            continue
        for side in ("with_springs", "without_springs"):
            assert sum(_v(j[side]) for j in joints.values()) == pytest.approx(
                _v(data["energy"]["totals"][key][side]), rel=1e-9)
    # the net work of a conservative periodic cycle is ~0 compared with the absolute work
    assert abs(_v(data["energy"]["net_work"]["with_springs"])) < 1e-6 * _v(
        data["energy"]["totals"]["absolute_work"]["with_springs"])
    # the paper-style femur springs (eq. 14 convention) store U = ½ k α Δ² beyond ±θ_k
    s = r.analysis.springs["LF_femur"]
    c = robot.column("LF_femur")
    d = r.analysis.q[:, c] - s.neutral
    beyond = np.maximum(np.abs(d) - s.theta_k, 0.0)
    np.testing.assert_allclose(r.analysis.spring_energy[:, c], 0.5 * s.alpha * s.stiffness
                               * beyond**2, atol=1e-15)
    u = friction_usage(r.analysis.forces, r.motion.stance.astype(bool), 0.6)
    assert np.all(u[~r.motion.stance.astype(bool)] == 0)


def test_transform_numbers_equal_the_analysis_api(data, independent, robot):
    """The stand → sphere section: the public API's numbers for the same springs, and the
    joints' net work equal to the rise of potential energy (both ways, springs conservative)."""
    from hexaleg.motion.gait import transform_motion

    _, springs, _ = independent
    fold = transform_motion(robot)
    a = analyze(robot, fold, springs, motor=DEFAULT_MOTOR, objective="joule")
    section = data["transform"]
    assert set(section["totals"]) == set(a.savings["total"])
    for key, row in section["totals"].items():
        assert _v(row["with_springs"]) == pytest.approx(a.metrics["total"][key], rel=1e-12)
        assert _v(row["without_springs"]) == pytest.approx(a.baseline["total"][key], rel=1e-12)
    rise = _v(section["potential_energy_rise"])
    assert _v(section["net_work"]["without_springs"]) == pytest.approx(rise, rel=1e-6)
    assert rise > 0.05 and section["rest_height"] == {"value": 0.0835, "unit": "m"}
    # Springs store energy while folding, so the motors' net work is the rise plus that energy.
    stored = a.spring_energy[-1].sum() - a.spring_energy[0].sum()
    assert _v(section["net_work"]["with_springs"]) == pytest.approx(rise + stored, rel=1e-6)


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


def test_friction_usage_of_known_forces():
    f = np.array([[[3.0, 4.0, 10.0], [0.0, 0.0, 0.0], [1.0, 0.0, 5.0]]])
    stance = np.array([[True, True, False]])
    np.testing.assert_allclose(friction_usage(f, stance, 0.5), [[1.0, 0.0, 0.0]])


# --------------------------------------------------------------------------- the HTML page


def test_html_has_every_section_and_embeds_every_plot(written, data):
    r, out = written
    html = (out / "report.html").read_text()
    for sid in SECTIONS:
        assert re.search(rf'<section id="{sid}">\s*<h2>', html), sid
    for heading in ("Robot and gait", "Joint angles", "motor vs spring", "Power per joint",
                    "friction usage", "with and without springs", "Cost of transport",
                    "energy of transforming",
                    "Stiffness curve", "single joint"):
        assert heading in html
    imgs = re.findall(r'<img[^>]*id="plot-(\w+)"[^>]*src="data:image/png;base64,([^"]+)"', html)
    assert sorted(n for n, _ in imgs) == sorted(PLOTS)
    for name, b64 in imgs:  # the embedded image is the PNG file written next to the page
        assert base64.b64decode(b64) == (out / f"{name}.png").read_bytes()
        assert (out / f"{name}.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert data["title"] == "test report" and "<title>test report</title>" in html
    assert sorted(data["files"]) == sorted(p.name for p in r.files)


def test_html_needs_no_external_url(written):
    html = (written[1] / "report.html").read_text()
    refs = re.findall(r'(?:src|href)\s*=\s*"([^"]*)"', html)
    assert refs and all(u.startswith(("data:", "#")) for u in refs), refs
    assert not re.search(r"url\(|@import|<script|<link|<iframe", html)
    assert "http" not in re.sub(r"<p class=\"note\">Motor data:.*?</p>", "", html, flags=re.S)


def test_html_numbers_are_the_json_numbers(written, data):
    html = (written[1] / "report.html").read_text()
    e = data["energy"]["totals"]["electrical"]
    for q in (e["with_springs"], e["without_springs"], e["saving"],
              data["stiffness_curve"]["k_M"], data["robot"]["mass"],
              data["forces"]["peak_friction_usage"]):
        assert f"{q['value']:.4g}" in html, q


# --------------------------------------------------------------------------- in the browser

needs_chromium = pytest.mark.skipif(chromium() is None,
                                    reason="chromium not on PATH (apt-get install chromium)")


@needs_chromium
def test_browser_loads_every_plot_and_fetches_nothing(written, tmp_path):
    """Chromium opens a copy of report.html with a probe script that lists the decoded images
    (naturalWidth > 0) in the DOM; the net log shows that the page requested nothing."""
    page = tmp_path / "probe.html"
    probe = ("<script>window.addEventListener('load', () => { const ok = [...document.images]"
             ".filter(i => i.complete && i.naturalWidth > 0).map(i => i.id + ':' + "
             "i.naturalWidth + 'x' + i.naturalHeight); document.body.setAttribute("
             "'data-loaded', ok.join(' ')); });</script>")
    page.write_text((written[1] / "report.html").read_text().replace("</body>", probe + "</body>"))
    profile = tempfile.mkdtemp(prefix="hexaleg-chromium-", dir=tmp_path)
    net = tmp_path / "net.json"
    dom = subprocess.run([chromium(), *CHROMIUM_FLAGS, f"--user-data-dir={profile}",
                          "--virtual-time-budget=3000", f"--log-net-log={net}", "--dump-dom",
                          page.as_uri()], capture_output=True, text=True, timeout=120).stdout
    loaded = re.search(r'data-loaded="([^"]*)"', dom)
    assert loaded, dom[:500]
    sizes = dict(item.split(":") for item in loaded.group(1).split())
    assert sorted(sizes) == sorted(f"plot-{n}" for n in PLOTS)
    for name in PLOTS:
        w, h = Image.open(written[1] / f"{name}.png").size
        assert sizes[f"plot-{name}"] == f"{w}x{h}"
    assert page_requests(net) == []


@needs_chromium
def test_browser_screenshot_shows_coloured_plots(written, tmp_path):
    png = tmp_path / "shot.png"
    finish(start_screenshot((written[1] / "report.html").as_uri(), png, size=(1000, 1800)),
           timeout=120)
    rgb = np.asarray(Image.open(png).convert("RGB"), dtype=float) / 255
    sat = rgb.max(2) - rgb.min(2)
    # the plots' coloured lines (six leg colours) cover a visible part of the page; text, tables
    # and a blank page are grey or white
    assert (sat > 0.3).mean() > 0.005
    assert rgb.std() > 0.1  # not a blank page


# --------------------------------------------------------------------------- CLI and bad input


def test_default_cli_run_writes_the_report(tmp_path, capsys):
    out = tmp_path / "default"
    assert main(["report", "--out", str(out)]) == 0
    printed = capsys.readouterr()
    assert "saving" in printed.out and "stiffness curve 41/41" in printed.err
    d = json.loads((out / "report.json").read_text())
    assert d["springs"]["design"] == "paper" and d["gait"]["samples"] == 1000
    assert d["motor"]["name"] == DEFAULT_MOTOR
    assert len(d["stiffness_curve"]["stiffness"]["value"]) == 41
    assert {f"{n}.png" for n in PLOTS} <= {p.name for p in out.iterdir()}
    assert (out / "report.html").stat().st_size > 100_000


def test_unwritable_output_directory_is_an_output_error(tmp_path, capsys):
    blocker = tmp_path / "file"
    blocker.write_text("not a directory")
    with pytest.raises(OutputError, match=re.escape(str(blocker / "out"))):
        write_report(blocker / "out", progress=None)
    assert main(["report", "--out", str(blocker / "out")]) == 2
    assert str(blocker / "out") in capsys.readouterr().err


def _config(tmp_path, text):
    path = tmp_path / "c.toml"
    path.write_text(text)
    return path


def test_unknown_key_names_the_key_and_the_valid_ones(tmp_path):
    with pytest.raises(UnknownNameError, match=r"'titel'.*paper_samples.*title"):
        ReportConfig.from_toml(_config(tmp_path, '[report]\ntitel = "x"\n'))
    with pytest.raises(UnknownNameError, match=r"'reprot'.*contact.*gait.*motor.*report.*springs"):
        ReportConfig.from_toml(_config(tmp_path, "[reprot]\n"))
    with pytest.raises(UnknownNameError, match=r"'stiffnes'.*dead_zone.*design.*joints"):
        ReportConfig.from_toml(_config(tmp_path, "[springs]\nstiffnes = 1.0\n"))
    with pytest.raises(UnknownNameError, match=r"'mu_'.*cone.*mu"):
        ReportConfig.from_toml(_config(tmp_path, "[contact]\nmu_ = 0.5\n"))
    with pytest.raises(UnknownNameError, match=r"'stride'.*stride_length"):
        ReportConfig.from_toml(_config(tmp_path, "[gait]\nstride = 0.1\n"))


def test_wrong_type_names_the_key_and_the_type(tmp_path, capsys):
    path = _config(tmp_path, '[gait]\nperiod = "slow"\n')
    with pytest.raises(ConfigError, match=r"gait\]\.period = 'slow'.*expected a number"):
        ReportConfig.from_toml(path)
    assert main(["report", "--config", str(path), "--out", str(tmp_path / "o")]) == 2
    assert "period" in capsys.readouterr().err
    with pytest.raises(ConfigError, match=r"stiffness_points = 2.5.*integer"):
        ReportConfig.from_toml(_config(tmp_path, "[report]\nstiffness_points = 2.5\n"))
    with pytest.raises(ConfigError, match=r"regeneration"):
        ReportConfig.from_toml(_config(tmp_path, '[motor]\nbase = "AX-18A"\n'
                                                 'regeneration = "yes"\n'))


def test_out_of_range_values(tmp_path):
    for text, match in (('[report]\nobjective = "fast"\n', "joule"),
                        ('[report]\ncurve_metrics = ["joules"]\n', "electrical"),
                        ("[report]\nstiffness_min = 1.0\nstiffness_max = 0.5\n", "stiffness_max"),
                        ('[springs]\ndesign = "centred"\n', "stiffness"),
                        ('[springs]\ndesign = "paper"\nstiffness = 1.0\n', "centred"),
                        ('[springs]\ndesign = "linear"\n', "paper")):
        with pytest.raises((InvalidParameterError, UnknownNameError), match=match):
            ReportConfig.from_toml(_config(tmp_path, text))


def test_direct_construction_rejects_wrong_types():
    for kwargs, name in (({"title": 5}, "title"), ({"stiffness_points": "x"}, "stiffness_points"),
                         ({"stiffness_min": float("nan")}, "stiffness_min"),
                         ({"curve_metrics": "joule"}, "curve_metrics"),
                         ({"paper_samples": 4}, "paper_samples")):
        with pytest.raises(InvalidParameterError, match=name):
            ReportParams(**kwargs)
    with pytest.raises(InvalidParameterError, match="stiffness"):
        SpringDesign("centred", stiffness="1")
    with pytest.raises(InvalidParameterError, match="dead_zone"):
        SpringDesign("centred", stiffness=1.0, dead_zone=1.0)


def test_spring_tables_build_the_configured_springs(tmp_path, robot):
    cfg = ReportConfig.from_toml(_config(tmp_path, """
[springs.LF_femur]
stiffness = 0.5
theta_k = 0.1
neutral = 0.5
"""))
    assert isinstance(cfg.springs, SpringSet) and cfg.springs["LF_femur"].stiffness == 0.5
    cfg = ReportConfig.from_toml(_config(tmp_path, """
[springs]
design = "centred"
joints = "tibia"
stiffness = 0.2
dead_zone = 0.25
[motor]
base = "MX-28"
"""))
    assert cfg.springs == SpringDesign("centred", "tibia", 0.2, 0.25)
    assert cfg.motor == motor("MX-28")
    motion = tripod_gait(robot, GaitParams(samples=40))
    s = cfg.spring_set(robot, motion)
    assert set(s) == set(robot.joints("tibia"))
    q = motion.q[:, 7 + robot.column("LF_tibia")]
    assert s["LF_tibia"].neutral == pytest.approx((q.max() + q.min()) / 2)
    assert s["LF_tibia"].stiffness == 0.2
    assert s["LF_tibia"].theta_k == pytest.approx(0.25 * (q.max() - q.min()) / 2)
    assert not ReportConfig.from_toml(_config(tmp_path, '[springs]\ndesign = "none"\n')
                                      ).spring_set(robot, motion)
    with pytest.raises(UnknownNameError, match="femur"):
        ReportConfig.from_toml(_config(tmp_path, '[springs]\ndesign = "paper"\njoints = "knee"\n'
                                       )).spring_set(robot, motion)
