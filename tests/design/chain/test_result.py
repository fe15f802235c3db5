"""Tests of hexaleg.design.chain.result: design.json has every number with its unit and springs
other tools rebuild exactly."""

from __future__ import annotations

import json
import re

import pytest


def _numbers_have_units(node, path="design"):
    """Every float in the document sits in a {value, unit} quantity."""
    if isinstance(node, dict):
        if "value" in node and "unit" in node:
            return
        for k, v in node.items():
            if k in ("solver",):  # the solver's bookkeeping, counts and its own value
                continue
            _numbers_have_units(v, f"{path}.{k}")
    elif isinstance(node, list):
        for i, v in enumerate(node):
            _numbers_have_units(v, f"{path}[{i}]")
    else:
        assert not isinstance(node, float), f"{path} = {node} has no unit"


def test_design_json_numbers_have_units(design_written):
    """Every number of design.json sits in a {value, unit} quantity (its records' too:
    tests/design/chain/test_records.py)."""
    _, out = design_written
    _numbers_have_units(json.loads((out / "design.json").read_text()))


def test_design_json_says_whether_the_baseline_energy_is_plausible(design_written):
    """The default hexapod (AX-18A) walks at a plausible cost of transport: design.json says so
    with the band and the rule, and the summary line carries no warning."""
    result, out = design_written
    doc = json.loads((out / "design.json").read_text())["plausibility"]
    assert doc["plausible"] is True and doc["flag"] is None
    assert doc["low"]["value"] < doc["cost_of_transport"]["value"] < doc["high"]["value"]
    assert "Taylor" in doc["rule"] and doc["message"].startswith("plausible")
    assert "WARNING" not in result.result.summary()


def test_design_json_and_page_state_the_whole_draw(design_written):
    """design.json's whole draw (issue #40): the baseline motors' mean power is the baseline
    electrical energy over the period, the recommendation's saving on it is its predicted
    electrical saving in watts over the baseline motors plus the servos at rest (#59: the AX
    family's 50 mA × 12 V each), and the electronics, not given, make it a bound the page
    names."""
    result, out = design_written
    doc = json.loads((out / "design.json").read_text())
    draw = doc["whole_draw"]
    period = doc["gait"]["period"]["value"]
    assert draw["motors_baseline"]["value"] == pytest.approx(
        doc["baseline"]["electrical"]["value"] / period, rel=1e-12)
    saving = doc["recommended"]["saving"]["electrical"]["value"] / 100
    motors = draw["motors_baseline"]["value"]
    idle = draw["idle_power"]["value"]
    assert idle == pytest.approx(18 * 0.050 * 12.0, rel=1e-12)
    assert draw["saving"]["value"] == pytest.approx(saving * motors / (motors + idle), rel=1e-9)
    assert draw["idle_family"] == ["AX-18A"] and draw["complete"] is False
    page = (out / "design.html").read_text()
    assert 'id="whole-draw"' in page and "electronics_power" in page
    assert "its servo family's standby current" in page
    assert result.result.whole_draw is not None
    assert result.result.whole_draw.line().startswith("whole draw at least")


def _reads_back(result, path):
    """``result.to_json()`` written to ``path`` and read back by the one reader: the
    recommended springs exactly, the gait, the metric and its saving, whether it pays."""
    from hexaleg.design.chain.design_file import load_design

    text = result.to_json()
    assert not re.search(r"[:\[,]\s*-?(?:NaN|Infinity)\b", text)  # no such JSON token
    path.write_text(text)
    back = load_design(path)
    assert dict(back.springs) == dict(result.recommended.optimum.springs)
    metric = result.design.metric
    assert back.metric == metric and back.pays == result.pays
    assert back.saving == pytest.approx(result.recommended.row[f"saving.{metric}"], rel=1e-12)
    return back


def test_every_design_a_command_writes_reads_back(design_written, ruled, tmp_path):
    """One writer (DesignResult.to_json) and one reader (load_design): hexaleg design's design
    and hexaleg codesign's (the spring rules on its chosen gait) read back as themselves."""
    result = design_written[0].result
    assert _reads_back(result, tmp_path / "design.json").gait == result.gait
    assert (design_written[1] / "design.json").read_text() == result.to_json(
        **{k: design_written[0].data[k] for k in ("warnings", "gait_defaults", "files")})
    rules = ruled.rules
    back = _reads_back(rules, tmp_path / "codesign-design.json")
    assert back.gait is not None and back.gait.period == pytest.approx(rules.gait.period)


def test_a_design_with_an_unbuildable_part_has_no_infinity(tmp_path):
    """A part no wire fits (an outer diameter of 0.6 mm), with a free angle at infinity (as a
    constant-torque spring has): null in design.json with its path noted, never ``Infinity``;
    the file reads back. A chain of the candidates alone says so in ``stages``."""
    import dataclasses

    from hexaleg import DesignChain, DesignParams, Scenario
    from hexaleg.quantities import NON_FINITE

    params = DesignParams(families=("linear",), classes=("femur",), samples=100,
                          max_outer_diameter={"femur": 6e-4})
    result = DesignChain(Scenario.load(), design=params).run(stages=("candidates",))
    part = result.recommended.parts[0]
    assert not result.recommended.buildable and part.spring is None and part.problem
    rec = dataclasses.replace(result.recommended, parts=(
        dataclasses.replace(part, free=float("inf")), *result.recommended.parts[1:]))
    result = dataclasses.replace(result, recommended=rec)
    _reads_back(result, tmp_path / "design.json")
    data = json.loads((tmp_path / "design.json").read_text())
    assert data["recommended"]["parts"][0]["free"]["value"] is None
    assert data[NON_FINITE]["paths"] == ["recommended.parts[0].free.value"]
    assert data["stages"] == ["candidates"] and data["ranking"] == [] and data["maps"] == []


def test_the_closing_line_and_the_report_name_every_hard_stop(design_written, tmp_path):
    """Issue #43: a spring that needs a hard stop said so in red on design.html only. The
    closing line a user copies and the report led by the design name each stop (its group,
    side, angle) — and say nothing of stops a design does not need."""
    import json
    import math

    from hexaleg.cli import main

    written, out = design_written
    r = written.result
    stops = [e for e in r.envelope if e.stop is not None]
    line = r.summary()
    assert ("hard stops needed" in line) == bool(stops)
    for e in stops:
        assert f"{e.group} ({e.side}) at {math.degrees(e.stop.angle_from_centre):+.1f}°" in line
    config = tmp_path / "r.toml"
    config.write_text("[gait]\nsamples = 60\n[report]\nstiffness_points = 3\npaper_samples = 8\n")
    assert main(["report", "--design", str(out / "design.json"), "--config", str(config),
                 "--out", str(tmp_path / "report")]) == 0
    html = (tmp_path / "report" / "report.html").read_text(encoding="utf-8")
    data = json.loads((tmp_path / "report" / "report.json").read_text(encoding="utf-8"))
    assert len(data["design"]["hard_stops"]) == len(stops)
    assert ("Hard stops needed" in html) == bool(stops)
    for e in stops:
        assert f"{e.group} ({e.side}) at\n{math.degrees(e.stop.angle_from_centre):+.1f}°" in html
