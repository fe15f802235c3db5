"""No answer is called proven that no run backs (issues #54, #57): the design's answer line, its
page and design.json say "unproven" and why wherever the recommendation's runs under the servo the
robot runs did not walk or saved nothing; the worse servo leads; "short" and the other verdicts are
defined on the page."""

from __future__ import annotations

import dataclasses
import re
from collections import defaultdict
from html import unescape

import pytest

from hexaleg.outputs.html import render_design_html


def _rows(result, **by_controller):
    """The result's simulation rows with ``simulated`` (and a verdict) replaced per controller."""
    out = []
    for row in result.simulation:
        change = by_controller.get(row["controller"])
        out.append(row if change is None else {**row, **change})
    return tuple(out)


def _answer(html: str) -> str:
    start = html.index('<p class="answer')
    return " ".join(unescape(re.sub(r"<[^>]+>", " ", html[start:html.index("</p>", start)]))
                    .split())


def test_the_small_design_is_proven_under_both_servos(design_written):
    r = design_written[0].result
    assert r.pays and r.unproven == ""
    assert {row["controller"] for row in r.simulation} == {"feedforward", "position"}
    assert all(row["simulated"] is not None and row["simulated"] > 0 for row in r.simulation)
    assert r.summary().startswith("fit ")
    data = design_written[0].data
    assert data["proof"]["proven"] is True and data["proof"]["why"] is None
    assert _answer(render_design_html(data, defaultdict(str))).startswith("Fit these springs:")


def test_a_run_that_falls_short_makes_the_answer_unproven_everywhere(design_written):
    r = design_written[0].result
    short = dataclasses.replace(r, simulation=_rows(
        r, position={"simulated": None, "verdict": "with springs short; baseline short"}))
    why = "under position only the runs did not walk (with springs short; baseline short)"
    assert short.unproven == why
    assert short.summary().startswith(f"unproven ({why}): the analysis would fit ")
    data = short.to_dict(**{k: design_written[0].data[k]
                                 for k in ("warnings", "gait_defaults", "files")})
    assert data["proof"] == {**data["proof"], "proven": False, "why": why}
    assert data["simulation"][0]["label"] == "position only"  # the worse leads
    html = render_design_html(data, defaultdict(str))
    answer = _answer(html)
    assert answer.startswith("Unproven: no simulation under feedforward and position servos "
                             f"backs this answer ({why}).")
    assert "Fit these springs" not in html
    note = " ".join(unescape(re.sub(r"<[^>]+>", " ", html[html.index('id="verdicts"'):]))
                    .split())
    assert "short : it covered 50% to 90% of the planned distance per cycle" in note


def test_a_fall_the_gait_explains_is_named_in_the_answer(design_written):
    """A run that fell for a reason of the gait itself (a sensitivity row's ``why``: a stand on
    one point foot, hexaleg.simulation.falls.PointFoot) says so in the answer line."""
    r = design_written[0].result
    why = "on one point foot for 0.709 s, an inverted pendulum (an error ×125) that feedback " \
          "without foot placement cannot hold"
    fell = dataclasses.replace(r, simulation=_rows(
        r, feedforward={"simulated": None, "verdict": "springs fell; baseline fell", "why": why}))
    assert fell.unproven == ("under feedforward + PD the runs did not walk (springs fell; "
                             f"baseline fell: {why})")
    assert fell.summary().startswith(f"unproven ({fell.unproven}): the analysis would fit ")


def test_a_negative_simulated_saving_is_no_proof(design_written):
    r = design_written[0].result
    worse = dataclasses.replace(r, simulation=_rows(r, feedforward={"simulated": -0.01}))
    assert worse.unproven == "under feedforward + PD the simulated saving is -1.00 %"
    assert [row["label"] for row in worse.simulated()] == ["feedforward + PD", "position only"]


def test_only_the_servo_the_robot_runs_counts(design_written):
    """A robot that runs position servos is proven by its position runs, whatever the
    feedforward runs did, and the other way round."""
    r = design_written[0].result
    broken = _rows(r, feedforward={"simulated": None, "verdict": "with springs fell"})
    for servo, proven in (("position", True), ("feedforward", False), ("both", False)):
        x = dataclasses.replace(r, design=dataclasses.replace(r.design, controller=servo),
                                simulation=broken)
        assert (x.unproven == "") is proven, servo
        assert [row["controller"] for row in x.simulated()] == (
            ["position"] if servo == "position" else
            ["feedforward"] if servo == "feedforward" else ["feedforward", "position"])


def test_without_runs_the_answer_is_unproven_and_says_why(design_written):
    r = design_written[0].result
    bare = dataclasses.replace(r, simulation=(), stages=tuple(s for s in r.stages
                                                              if s != "proof"))
    assert bare.unproven == "not simulated (the proof stage did not run)"
    assert bare.summary().startswith("unproven (not simulated")


@pytest.mark.parametrize("servo", ["feedforward", "position"])
def test_the_worse_servo_leads_the_answer_line(design_written, servo):
    r = design_written[0].result
    low = dataclasses.replace(r, simulation=_rows(r, **{servo: {"simulated": 0.001}}))
    label = {"feedforward": "feedforward + PD", "position": "position only"}[servo]
    line = low.summary()
    assert line.index(f"{label} +0.10 %") < line.index(
        "position only" if servo == "feedforward" else "feedforward + PD")


def test_the_page_tells_one_story_of_the_numbers(design_written):
    """Issue #57: the figures a user meets for one gait — the quick answer, each family, the
    springs to buy, net, at worst, simulated, over the maps — each with why it differs, and
    the same numbers as design.json's other keys."""
    data = design_written[0].data
    m = data["settings"]["metric"]
    story = {row["figure"]: row for row in data["story"]}
    rec = data["recommended"]
    assert story["the springs to buy"]["saving"] == rec["saving"][m]
    assert story["the springs to buy, net of their mass"]["saving"]["value"] == \
        pytest.approx(rec["net_saving"][m]["value"])
    for c in data["candidates"]:
        assert story[f"the {c['family']} family's optimum"]["saving"] == c["saving"][m]
    if "hexaleg report's quick answer" in story:
        linear = next(c for c in data["candidates"] if c["family"] == "linear")
        assert story["hexaleg report's quick answer"]["saving"] == linear["saving"][m]
    worse = data["simulation"][0]
    assert story[f"simulated in MuJoCo, {worse['label']} (the worse servo)"]["saving"] == \
        worse["simulated_saving"]
    assert all(row["why"] and row["saving"]["unit"] == "%" for row in data["story"])
    html = render_design_html(data, defaultdict(str))
    table = html[html.index('<table id="story">'):]
    table = table[:table.index("</table>")]
    assert table.count("<tr><td") == len(data["story"])
