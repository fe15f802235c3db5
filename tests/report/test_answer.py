"""Tests of hexaleg.report.answer: the report leads with which springs to fit — a given
design.json, else hexaleg-design/design.json of the same robot and gait, else the design's quick
core — and its last line says the saving."""

from __future__ import annotations

import json
import math
import shutil

import pytest

import hexaleg
from hexaleg.design.search.optimal import optimal_springs
from hexaleg.report.answer import DESIGN_JSON, answer_line
from hexaleg.report.build import build_report
from hexaleg.report.config import ReportConfig
from hexaleg.robot.mirror import mirror

SMALL = {"gait": {"samples": 100}, "report": {"stiffness_points": 2, "paper_samples": 16}}
"""The report on the 100-sample default gait (the tiny design's), the rest at its smallest."""


def _config(**report) -> ReportConfig:
    return ReportConfig.from_mapping({**SMALL, "report": {**SMALL["report"], **report}})


@pytest.fixture(scope="module")
def quick(tmp_path_factory, robot):
    """The report made where there is no hexaleg-design/ (the quick answer)."""
    import os

    here = os.getcwd()
    os.chdir(tmp_path_factory.mktemp("empty"))
    try:
        return build_report(_config(), robot=robot)
    finally:
        os.chdir(here)


def test_the_quick_answer_is_the_global_linear_optimum(quick, robot):
    """Without a design.json the answer is the linear family's global optimum of the energy the
    servos draw, computed independently here through the public optimiser on the same gait and
    groups (coxa left out: it adds under one point), within the design's deflection bound."""
    g = quick.data["design"]
    assert g["origin"] == "quick" and g["source"] is None and g["family"] == "linear"
    assert g["metric"] == "electrical" and g["samples"] == 100 and g["pays"]
    assert g["groups"] == ["femur", "tibia"] and set(g["dropped_groups"]) == {"coxa"}
    motion = hexaleg.gait(robot, hexaleg.GaitParams(samples=100))
    prepared = hexaleg.prepare(robot, motion)
    best = optimal_springs(prepared, ["femur", "tibia"], "linear", metric="electrical",
                           max_deflection=math.pi, mirrored=mirror(robot).mirrored)
    saving = 100 * best.analysis.savings["total"]["electrical"]
    assert g["saving"] == {"value": pytest.approx(saving, abs=1e-6), "unit": "%"}
    assert g["saving"]["value"] > 10  # the springs save; the paper's design costs
    assert quick.data["reference"]["energy"]["electrical"]["saving"]["value"] < 0
    # the page analyses the answer's springs: its energy table is theirs
    assert quick.data["springs"]["design"] == "answer"
    assert quick.data["energy"]["totals"]["electrical"]["saving"]["value"] == pytest.approx(
        saving, abs=1e-6)
    # the same springs on the report's gait: here the same 100 samples, so the same saving
    assert g["report_gait"]["samples"] == 100
    assert g["report_gait"]["saving"]["value"] == pytest.approx(saving, abs=1e-6)
    assert g["net_saving"]["electrical"]["value"] < g["saving"]["value"]  # their mass costs
    assert [p["group"] for p in g["parts"]] == ["femur", "tibia"]
    assert all(p["torsion_spring"]["mass"]["unit"] == "kg" for p in g["parts"])


def test_the_last_line_is_the_answer(quick):
    lines = quick.summary().splitlines()
    g = quick.data["design"]
    assert lines[0].startswith("the paper's design (the reference)") and "saving -" in lines[0]
    assert lines[-1].startswith("quick answer: optimal linear springs on femur, tibia save "
                                f"{g['saving']['value']:+.2f} % of the electrical energy")
    # predicted only: no simulation backs it within the report's budget, and the line says so
    assert lines[-1].endswith("; unproven (predicted, not simulated: hexaleg design simulates "
                              "its answer)")
    assert "100 samples a cycle" in lines[-1]


def test_a_design_json_in_hexaleg_design_is_read_when_it_fits(design_json, robot, tmp_path,
                                                                monkeypatch):
    """hexaleg-design/design.json of the same robot and gait (other samples) leads the report;
    of another gait it is passed over with a note naming the difference, and the quick answer
    leads."""
    monkeypatch.chdir(tmp_path)
    DESIGN_JSON.parent.mkdir()
    shutil.copy(design_json, DESIGN_JSON)
    shutil.copy(design_json.with_name("design.html"), DESIGN_JSON.with_name("design.html"))
    data = json.loads(design_json.read_text())
    r = build_report(ReportConfig.from_mapping({**SMALL, "gait": {"samples": 120}}),
                     robot=robot)
    g = r.data["design"]
    assert g["origin"] == "found" and g["source"] == str(DESIGN_JSON)
    assert g["saving"] == data["recommended"]["saving"]["electrical"]
    assert g["report_gait"]["samples"] == 120 and g["simulation"] == data["simulation"]
    assert r.summary().splitlines()[-1].startswith(
        f"from {DESIGN_JSON}: linear springs on femur, tibia save "
        f"{g['saving']['value']:+.2f} %")

    other = build_report(ReportConfig.from_mapping({**SMALL, "gait": {"samples": 100,
                                                                      "period": 1.2}}),
                         robot=robot)
    assert other.data["design"]["origin"] == "quick"
    assert any(n.startswith(f"{DESIGN_JSON} not used") and "period 1.0 (this report: 1.2)" in n
               for n in other.data["notes"]), other.data["notes"]


def test_a_given_design_json_comes_first(design_json, robot, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    r = build_report(_config(design=str(design_json)), robot=robot)
    g = r.data["design"]
    assert g["origin"] == "given" and g["source"] == str(design_json)
    assert r.summary().splitlines()[-1].startswith(f"from {design_json}: linear springs")
    assert "hexaleg design for the full answer" not in r.summary()


def test_a_payload_gets_no_answer_and_says_why(robot, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    cfg = ReportConfig.from_mapping({**SMALL, "payload": {"mass": 0.2}})
    r = build_report(cfg, robot=robot)
    assert r.data["design"] is None
    assert any("no quick answer: this report carries a payload" in n for n in r.data["notes"])
    assert r.summary().splitlines()[-1] == answer_line(None)
    assert "hexaleg design answers it" in answer_line(None)


def test_a_logged_motion_gets_no_quick_answer(robot):
    """A report of a logged motion (``--motion``) has no gait parameters a design could be
    matched against or made on: no answer, a note saying how to get one."""
    from types import SimpleNamespace

    from hexaleg.report.answer import answer_section

    cfg = SimpleNamespace(report=SimpleNamespace(design=None), motion=object())
    section, springs, notes = answer_section(cfg, robot, None)  # type: ignore[arg-type]
    assert section is None and springs is None and "hexaleg design --motion LOG" in notes[0]
