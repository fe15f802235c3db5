"""Tests of hexaleg.report.design_section: the report leads with hexaleg design's answer
when given its design.json, and says how to get one otherwise."""

from __future__ import annotations

import json
import os

import pytest

from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.outputs.html import render_html
from hexaleg.report.answer import answer_line
from hexaleg.report.build import build_report
from hexaleg.report.config import ReportConfig
from hexaleg.report.design_section import UNPROVEN_FILE, design_section


def test_the_section_carries_design_json_numbers(design_json):
    data = json.loads(design_json.read_text())
    s = design_section(design_json)
    assert s["label"] == data["recommended"]["label"] == "linear"
    assert s["origin"] == "given" and s["source"] == str(design_json)
    metric = data["settings"]["metric"]
    assert s["saving"] == data["recommended"]["saving"][metric]  # the headline, {value, unit}
    assert s["savings"] == data["recommended"]["saving"]
    assert s["parts"] == data["recommended"]["parts"]  # as design.json writes them
    assert s["actuator"] == data["actuator"]
    assert s["robust"] == data["robust"]["worst"]
    assert s["simulation"] == data["simulation"]
    assert [row["controller"] for row in s["simulation"]] == ["feedforward", "position"]
    assert s["html"] == str(design_json.with_name("design.html"))
    assert design_section(None) is None


PLOTS = ("joint_angles", "joint_torques", "joint_power", "foot_forces", "energy_per_joint",
         "stiffness_curve")


@pytest.fixture(scope="module")
def report(design_json):
    cfg = ReportConfig.from_mapping({"gait": {"samples": 100},
                                     "report": {"stiffness_points": 2, "paper_samples": 16,
                                                "design": str(design_json)}})
    return build_report(cfg)


def test_the_report_page_leads_with_the_design(report):
    r = report
    assert r.data["design"]["label"] == "linear"
    html = render_html({**r.data, "files": []}, dict.fromkeys(PLOTS, ""))
    assert html.index("Fit these springs") < html.index("Robot and gait")
    ff = r.data["design"]["simulation"][0]
    simulated = f'{ff["simulated_saving"]["value"]:+.2f} %'
    assert html.index("Predicted and simulated") < html.index(simulated) < html.index(
        "Robot and gait")


def test_a_design_json_without_its_simulation_says_so(design_json, report, tmp_path):
    """A design.json of an older hexaleg (no ``simulation``) still leads the page, which says
    that its recommendation was not simulated."""
    data = json.loads(design_json.read_text())
    del data["simulation"], data["proof"]  # as an older hexaleg wrote it
    old = tmp_path / "design.json"
    old.write_text(json.dumps(data))
    s = design_section(old)
    assert s["simulation"] == []
    html = render_html({**report.data, "design": s, "files": []}, dict.fromkeys(PLOTS, ""))
    assert "has no forward simulation of its recommendation" in html
    # and no proof: the page does not call it fit to buy
    assert s["proof"] == {"proven": False, "why": UNPROVEN_FILE}
    assert "Fit these springs" not in html and f"Unproven ({UNPROVEN_FILE})" in html


def test_an_unproven_design_json_leads_unproven(design_json, report, tmp_path):
    """A design.json whose runs did not walk under the robot's servo: the report's page and
    last line say "unproven" with the design's reason, never "fit these springs"."""
    data = json.loads(design_json.read_text())
    why = "under position only the runs did not walk (with springs short)"
    data["proof"] = {**data["proof"], "proven": False, "why": why}
    path = tmp_path / "design.json"
    path.write_text(json.dumps(data))
    s = design_section(path)
    assert s["proof"] == {"proven": False, "why": why}
    html = render_html({**report.data, "design": s, "files": []}, dict.fromkeys(PLOTS, ""))
    assert f"Unproven ({why})" in html and "Fit these springs" not in html
    assert answer_line(s).startswith(f"unproven ({why}): from ")
    data["proof"] = {**data["proof"], "why": None}
    path.write_text(json.dumps(data))
    with pytest.raises(ConfigError, match="an unproven design says why"):
        design_section(path)


def test_a_missing_design_says_how_to_make_one(tmp_path):
    with pytest.raises(ConfigError, match="hexaleg design --out DIR"):
        design_section(tmp_path / "nope.json")
    for text in ("{}", "[1]", '{"recommended": {"parts": [{"group": "femur"}]}}',
                 '{"recommended": {"label": "linear", "parts": []}}'):
        (tmp_path / "bad.json").write_text(text)
        with pytest.raises(ConfigError, match=r"not a design\.json"):
            design_section(tmp_path / "bad.json")
    steps: list[str] = []  # the report refuses it before any work
    cfg = ReportConfig.from_mapping({"report": {"design": str(tmp_path / "nope.json")}})
    with pytest.raises(ConfigError, match=r"nope\.json"):
        build_report(cfg, progress=steps.append)
    assert steps == []


def _hand_made(robot_name="hexaleg", joint="LF_femur", saving=12.5):
    """The keys the section reads, as hexaleg design writes them (no design run needed)."""
    q = {"value": saving, "unit": "%"}
    return {"robot": {"name": robot_name}, "settings": {"metric": "electrical"},
            "gait": {"samples": 100}, "worst": {"electrical": {"saving": q, "condition": None}},
            "recommended": {"label": "linear", "groups": ["femur"], "parts": [],
                            "saving": {"electrical": q}, "net_saving": {"electrical": q},
                            "spring_mass": {"value": 0.01, "unit": "kg"},
                            "springs": [{"family": "linear", "joint": joint, "parameters": {
                                "stiffness": {"value": 0.01, "unit": "N·m/rad"}}}]}}


def test_a_design_for_another_robot_is_refused(tmp_path, robot):
    """A solo12 design used to lead a hexaleg report with "Fit these springs … on haa, hfe"."""
    path = tmp_path / "design.json"
    path.write_text(json.dumps(_hand_made()))
    assert design_section(path, robot)["label"] == "linear"
    path.write_text(json.dumps(_hand_made("solo12", "FL_HFE")))
    with pytest.raises(InvalidParameterError, match=r"robot\.name = 'solo12'; allowed: a design "
                                                    r"of the report's robot, 'hexaleg'"):
        design_section(path, robot)
    path.write_text(json.dumps(_hand_made("hexaleg", "FL_HFE")))
    with pytest.raises(UnknownNameError, match=r"'FL_HFE'; valid joints in .*LF_femur"):
        design_section(path, robot)


@pytest.mark.parametrize(("text", "error", "says"), [
    ("NaN", ConfigError, "NaN is not a JSON number"),
    ("Infinity", ConfigError, "Infinity is not a JSON number"),
    ("1e400", ConfigError, "1e400 is beyond the largest float"),
    ('"12 %"', InvalidParameterError, r"worst\.electrical\.saving = '12 %'")])
def test_non_finite_numbers_are_not_copied_into_the_report(tmp_path, robot, text, error, says):
    """NaN/inf in design.json used to reach report.json and the headline ("saving nan %")."""
    path = tmp_path / "design.json"
    path.write_text(json.dumps(_hand_made()).replace('"value": 12.5', f'"value": {text}', 1))
    with pytest.raises(error, match=says):
        design_section(path, robot)


def test_a_design_device_or_pipe_is_refused(tmp_path):
    os.mkfifo(tmp_path / "design.json")
    for path in ("/dev/zero", tmp_path / "design.json"):
        with pytest.raises(ConfigError, match=r"not a regular file.*hexaleg design --out DIR"):
            design_section(path)


@pytest.mark.parametrize(("key", "value"), [("wire_diameter", -0.0007), ("body_turns", 0),
                                            ("mass", None)])
def test_a_part_of_no_size_is_not_copied_into_the_parts_to_buy(design_json, tmp_path, key,
                                                               value):
    """A negative wire diameter in design.json went into the report's parts to buy (#42)."""
    data = json.loads(design_json.read_text())
    parts = [p for p in data["recommended"]["parts"] if p.get("torsion_spring")]
    assert parts, "the tiny design buys a spring"
    parts[0]["torsion_spring"][key]["value"] = value
    path = tmp_path / "design.json"
    path.write_text(json.dumps(data))
    with pytest.raises(ConfigError, match=rf"torsion_spring\.{key} = {value}; a part to buy "
                                          r"needs it > 0"):
        design_section(path)
