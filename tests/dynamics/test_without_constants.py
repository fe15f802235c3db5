"""Tests of hexaleg.dynamics.without_constants: a run with generic actuators gets the figures
that hold whatever its motor — positive work, ∫τ² — and the catalogue's actuators of its torque
class, each equal to the energy metrics computed here; a run with named motors gets none; the
report asks for the motor first."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from hexaleg.dynamics import energy
from hexaleg.dynamics.prepare import prepare
from hexaleg.dynamics.without_constants import (
    SCALE_CLASS,
    TORQUE_CLASS,
    scaled,
    without_constants,
)
from hexaleg.errors import InvalidParameterError
from hexaleg.report.config import ReportConfig
from hexaleg.robot.catalogue import CATALOGUE
from hexaleg.scenario.scenario import Scenario


@pytest.fixture(scope="module")
def go2():
    """Go2 on a 100-sample trot: every joint's actuator generic (its URDF limits)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s = Scenario.from_tables("go2", {"gait": {"samples": 100}}, "test")
        cfg = ReportConfig.from_scenario(s)
        baseline = prepare(s.model, s.motion(), motor=cfg.motor,
                           contact=cfg.contact).evaluate(None, "joule")
    return baseline


def test_the_figures_are_the_energy_metrics_of_the_generic_joints(go2):
    w = without_constants(go2)
    assert w is not None and len(w.joints) == 12
    tau, qdot = go2.tau_motor, go2.qdot
    dt = go2.motion.t[1] - go2.motion.t[0]
    assert w.positive_work == pytest.approx(np.maximum(tau * qdot, 0).sum() * dt, rel=1e-12)
    assert w.torque_squared == pytest.approx((tau**2).sum() * dt, rel=1e-12)
    assert w.stated == pytest.approx(go2.metrics["total"]["electrical"], rel=1e-12)
    assert w.effort == pytest.approx(45.43)  # the knee's, the largest
    lo, hi = TORQUE_CLASS
    expected = {n for n, m in CATALOGUE.items() if lo * 45.43 <= m.stall_torque <= hi * 45.43}
    assert set(w.catalogue) == expected and expected  # A1's model is of that class
    for name, e in w.catalogue.items():
        assert e == pytest.approx(energy.metrics(tau, qdot, dt, CATALOGUE[name])["total"][
            "electrical"], rel=1e-12)
    assert w.stated > max(w.catalogue.values())  # the generic figure: above every real one
    line = w.line()
    assert line.startswith("name the motor of 12 joints first")
    assert f"positive mechanical work {w.positive_work:.4g} J" in line
    d = w.as_dict()
    assert d["torque_squared"]["unit"] == "N²·m²·s" and d["line"] == line


def test_the_sourced_band_by_hand(go2):
    """#59: each in-class actuator with c' = c (τ_peak/E_j)² per joint, η kept, no
    regeneration, against a hand sum of max(0, max(P/η, ηP) + c' τ²) dt; its low and high name
    the actuators; nothing called a bound."""
    w = without_constants(go2)
    assert w is not None
    robot = go2.robot
    tau, qdot = go2.tau_motor, go2.qdot
    dt = go2.motion.t[1] - go2.motion.t[0]
    efforts = np.array([robot.model.effortLimit[6 + robot.column(j)] for j in w.joints])
    assert set(efforts.round(2)) == {23.7, 45.43}
    lo, hi = SCALE_CLASS
    names = {n for n, m in CATALOGUE.items() if lo * 45.43 <= m.stall_torque <= hi * 45.43}
    assert set(w.band) == names and {"A1-Yang2021", "MiniCheetah-hip"} <= names
    for name in names:
        m = CATALOGUE[name]
        c = m.joule_coefficient * (m.stall_torque / efforts) ** 2
        p = tau * qdot
        eta = m.gearbox_efficiency
        power = np.maximum(np.maximum(p / eta, eta * p) + c * tau**2, 0.0)
        assert w.band[name] == pytest.approx(power.sum() * dt, rel=1e-9), name
    d = w.as_dict()["sourced_band"]
    assert d["low"]["value"] == min(w.band.values()) and d["high"]["value"] == max(w.band.values())
    assert w.band[d["low_actuator"]] == d["low"]["value"] and d["is_bound"] is False
    period = go2.motion.period
    assert d["power"]["high"] == {"value": pytest.approx(max(w.band.values()) / period),
                                  "unit": "W"}
    assert "not a bound" in w.band_line() and w.as_dict()["band_line"] == w.band_line()


def test_scaling_keeps_the_motor_and_changes_its_gearbox():
    m = CATALOGUE["MiniCheetah-hip"]
    s = scaled(m, 36.0)
    assert s.gear_ratio == pytest.approx(12.0) and s.stall_torque == 36.0
    assert s.joule_coefficient == pytest.approx(m.joule_coefficient / 4.0, rel=1e-12)
    assert s.resistance == m.resistance and s.gearbox_efficiency == m.gearbox_efficiency
    with pytest.raises(InvalidParameterError, match="effort"):
        scaled(m, 0.0)


def test_named_motors_need_no_such_figures(walk200, robot):
    analysis = prepare(robot, walk200).evaluate(None, "joule")
    assert without_constants(analysis) is None


def test_the_report_asks_for_the_motor_first(tmp_path, capsys):
    from hexaleg.cli import main

    config = tmp_path / "c.toml"
    config.write_text("[gait]\nsamples = 100\n[report]\nstiffness_points = 3\n")
    assert main(["report", "--robot", "go2", "--config", str(config), "--out",
                 str(tmp_path / "out")]) == 0
    out = capsys.readouterr().out
    lines = out.strip().splitlines()
    first = next(i for i, line in enumerate(lines) if line.startswith("wrote "))
    assert lines[first + 1].startswith("name the motor of 12 joints first")
    html = (tmp_path / "out" / "report.html").read_text()
    assert html.index('id="name-a-motor"') < html.index('id="design"')
    assert "Name the motor first." in html
    assert 'id="sourced-band"' in html and "not a bound" in html
    assert lines[first + 2].startswith("sourced band") and "not a bound" in lines[first + 2]
    # #59: the scaling law beside the band, labelled assumed; the measured robots of Go2's mass
    # class with costs of transport; no float exponent or other glitch on the page or the lines
    # (the glitch scan's own runs are the hexapod's)
    from test_glitches import glitches, visible

    assert 'id="scaling-law"' in html and "assumed constants, an estimate, not a bound" in html
    assert "cost of transport 0.381 (computed here from the quoted power" in html
    assert "the Joule scaling law (Wensing et al. 2017" in lines[first + 2]
    assert glitches(visible(html)) == [] and glitches(out) == []


def test_docs_quote_go2_s_own_trot():
    """docs/energy.md's Go2 figures are ``hexaleg report --robot go2``'s (its own 1000-sample
    trot), at the digits it prints."""
    import re
    from pathlib import Path

    text = " ".join((Path(__file__).resolve().parents[2] / "docs" / "energy.md").read_text()
                    .split())
    m = re.search(r"\): ([\d.]+) J per cycle stated by the generic actuator, ([\d.]+) J positive "
                  r"work, ([\d.]+) N²·m²·s, and ([\d.]+) J with the A1's", text)
    assert m, "docs/energy.md no longer quotes Go2's figures without constants"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s = Scenario.load("go2")
        cfg = ReportConfig.from_scenario(s)
        w = without_constants(prepare(s.model, s.motion(), motor=cfg.motor,
                                      contact=cfg.contact).evaluate(None, "joule"))
    assert w is not None
    got = (f"{w.stated:.4g}", f"{w.positive_work:.4g}", f"{w.torque_squared:.4g}",
           f"{w.catalogue['A1-Yang2021']:.4g}")
    assert got == m.groups()
    assert f"({w.catalogue['MiniCheetah-knee']:.4g} J with the Mini Cheetah's knee" in text
    band = f"{min(w.band.values()):.4g}–{max(w.band.values()):.4g} J"
    assert f"the sourced band below gives {band}" in text


def _band_on(robot: str, gait: dict) -> tuple[dict, float, float]:
    """The band (with the law's figures) of ``robot``'s gait, its mass and its predicted mean
    draw without springs, W."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s = Scenario.from_tables(robot, {"gait": gait, "contact": {"mu": 1.0}}, "test")
        cfg = ReportConfig.from_scenario(s)
        a = prepare(s.model, s.motion(), motor=cfg.motor, contact=cfg.contact).evaluate(
            None, "joule")
        w = without_constants(a)
    assert w is not None
    band = w.band_dict()
    assert band is not None and band["power"] is not None
    return band, s.model.mass, a.metrics["total"]["electrical"] / s.motion().period


def test_docs_quote_the_issues_bands():
    """docs/energy.md's tables of #59's trots (`[contact] mu = 1`, 200 samples): ANYmal B at
    0.5 m/s and Go2 at 0.4 m/s, each band's mean power at the digits the report prints, the low
    end at most the published figure the issue names (280 W, 120 W), the scaling law's figures
    beside it, and the costs of transport P / (m g v) of the prediction, the band and the law;
    ANYmal's published 1.27 within the law's range."""
    import re
    from pathlib import Path

    from hexaleg.units import G

    text = (Path(__file__).resolve().parents[2] / "docs" / "energy.md").read_text()
    cases = {"ANYmal B, 0.5 m/s": ("anymal", {"pattern": "trot", "period": 0.6,
                                              "stride_length": 0.30, "samples": 200}, 280.0),
             "Go2, 0.4 m/s": ("go2", {"pattern": "trot", "period": 0.4, "stride_length": 0.16,
                                      "samples": 200}, 120.0)}
    for row, (robot, gait, published) in cases.items():
        m = re.search(re.escape(row) + r"[^|]*\| [^|]* \| ([\d.]+)–([\d.]+) W \(low ([^,]+), "
                      r"high (\S+)\)", text)
        assert m, row
        band, mass, predicted = _band_on(robot, gait)
        low, high = band["power"]["low"]["value"], band["power"]["high"]["value"]
        assert (f"{low:.4g}", f"{high:.4g}", band["low_actuator"],
                band["high_actuator"]) == m.groups(), row
        assert low <= published, row
        law = {end: band["law"]["power"][end]["value"] for end in ("low", "central", "high")}
        assert band["from_law"] == [] and band["law"]["assumed"] is True
        assert (f"| {law['low']:.4g}–{law['high']:.4g} W ({law['central']:.4g} W at the law) |"
                in text), row
        per = 1.0 / (mass * G * gait["stride_length"] / gait["period"])
        cot = (f"| {row.split(',')[0]}, {row.split(', ')[1]}, {mass:.4g} kg | "
               f"{predicted * per:.3g} | {low * per:.3g}–{high * per:.3g} | "
               f"{law['low'] * per:.3g}–{law['high'] * per:.3g} ({law['central'] * per:.3g} at "
               "the law) |")
        assert cot in text, cot
        if robot == "anymal":
            assert law["low"] * per <= 1.27 <= law["high"] * per


def test_a_class_no_catalogue_actuator_covers_gets_the_law_s_band(go2):
    """#59: with a catalogue of servos only (none within 0.25–4 × Go2's 45.43 N·m), the band is
    the scaling law's three figures, each the energy metrics with the law's actuator of each
    joint's own effort, and says it came from the law, on assumed constants, not a bound."""
    from hexaleg.robot.scaling_law import LAW_MARK, catalogue_law

    servos = {n: m for n, m in CATALOGUE.items() if m.stall_torque < 11.0}
    w = without_constants(go2, catalogue=servos)
    assert w is not None and w.catalogue == {}
    assert w.from_law == ("scaling law (low)", "scaling law (central)", "scaling law (high)")
    assert w.band == w.law
    robot, law = go2.robot, catalogue_law()
    dt = go2.motion.t[1] - go2.motion.t[0]
    for end in ("low", "central", "high"):
        total = 0.0
        for i, j in enumerate(w.joints):
            k = 6 + robot.column(j)
            m = law.motor(robot.model.effortLimit[k], robot.model.velocityLimit[k], end)
            assert m.notes.startswith(LAW_MARK)
            total += energy.metrics(go2.tau_motor[:, [i]], go2.qdot[:, [i]], dt, m)["total"][
                "electrical"]
        assert w.law[f"scaling law ({end})"] == pytest.approx(total, rel=1e-12)
    assert w.law["scaling law (low)"] < w.law["scaling law (central)"] < w.law[
        "scaling law (high)"]
    d = w.band_dict()
    assert d is not None and d["from_law"] == list(w.from_law) and d["is_bound"] is False
    assert "scaling law's" in d["note"] and d["law"]["assumed"] is True
    assert d["law"]["fit"]["exponent"]["value"] == pytest.approx(law.exponent)
    line = w.band_line()
    assert "the band is the scaling law's (assumed constants)" in line
    assert "a band on assumed constants, not a bound" in line
    full = without_constants(go2)
    assert full is not None and full.from_law == () and full.law == w.law  # beside, not in


def test_the_law_fitted_without_the_ax_family_brackets_the_hexapod_s_ax_18a(robot, walk200):
    """Leave-one-out on a gait: the hexapod with a generic actuator of the AX-18A's limits
    (1.8 N·m, its no-load speed), the law fitted on the catalogue without the AX family: its
    low and high figures bracket the electrical energy the AX-18A itself gives on the same
    torques and speeds."""
    from hexaleg.robot.motor import generic_actuator
    from hexaleg.robot.scaling_law import family, fit

    ax = CATALOGUE["AX-18A"]
    analysis = prepare(robot, walk200, motor=generic_actuator(
        ax.stall_torque, ax.no_load_speed)).evaluate(None, "joule")
    rest = {n: m for n, m in CATALOGUE.items() if family(n) != "AX"}
    w = without_constants(analysis, catalogue=rest, law=fit(rest))
    assert w is not None and len(w.joints) == 18
    dt = walk200.t[1] - walk200.t[0]
    own = energy.metrics(analysis.tau_motor, analysis.qdot, dt, ax)["total"]["electrical"]
    assert w.law["scaling law (low)"] <= own <= w.law["scaling law (high)"]
    full = without_constants(analysis)
    assert full is not None
    from pathlib import Path

    text = " ".join((Path(__file__).resolve().parents[2] / "docs" / "energy.md").read_text()
                    .split())
    lo, mid, hi = (full.law[f"scaling law ({end})"] for end in ("low", "central", "high"))
    assert (f"the AX-18A itself draws {own:.4g} J per cycle. The law's 1.8 N·m actuator gives "
            f"{lo:.4g}–{hi:.4g} J ({mid:.4g} J at the law). Fitted without the AX family (leave "
            f"one out) it gives {w.law['scaling law (low)']:.4g}–"
            f"{w.law['scaling law (high)']:.4g} J") in text
