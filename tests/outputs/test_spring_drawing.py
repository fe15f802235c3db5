"""Tests of the drawing of each spring to mount (hexaleg.outputs.spring_drawing): the angles drawn
are design.json's, each ray points where its angle says, and every label says from what its
angle is measured."""

from __future__ import annotations

import json
import math
import re
from html import unescape

import pytest

from hexaleg.outputs.html import format_degrees
from hexaleg.outputs.spring_drawing import CENTRE, drawings, spring_svg


def _entry(**over):
    rad = {"value": 0.0, "unit": "rad"}
    e = {"part": 0, "group": "femur", "role": "one-sided", "joint": "LF_femur", "side": "above",
         "mirrored": False, "centre": {**rad, "value": 0.5}, "low": {**rad, "value": 0.3},
         "high": {**rad, "value": 0.7}, "contact": {**rad, "value": 0.25},
         "contact_from_centre": {**rad, "value": -0.25}, "engaged_throughout": True,
         "free": {**rad, "value": -2.4}, "free_from_centre": {**rad, "value": -2.9},
         "hard_stop": {**rad, "value": 1.2}, "hard_stop_from_centre": {**rad, "value": 0.7}}
    e.update(over)
    return e


def _rays(svg: str) -> dict[str, tuple[float, float, float]]:
    """class → (data-angle, x2, y2) of each line."""
    out = {}
    for m in re.finditer(r'<line class="(\w+)" data-angle="([^"]+)" x1="[^"]+" y1="[^"]+" '
                         r'x2="([^"]+)" y2="([^"]+)"', svg):
        out[m[1]] = (float(m[2]), float(m[3]), float(m[4]))
    return out


def test_each_ray_points_at_its_angle_counter_clockwise_from_the_joint_zero():
    e = _entry()
    rays = _rays(spring_svg(e, "t"))
    assert set(rays) == {"zero", "low", "high", "centre", "free", "contact", "hard_stop"}
    for key in ("low", "high", "centre", "free", "contact", "hard_stop"):
        angle, x, y = rays[key]
        assert angle == e[key]["value"]  # the file's number, to the last digit
        # counter-clockwise positive: y grows downward in SVG
        assert math.atan2(CENTRE[1] - y, x - CENTRE[0]) == pytest.approx(
            math.atan2(math.sin(angle), math.cos(angle)), abs=2e-3)
    assert rays["zero"][0] == 0.0 and rays["zero"][2] == pytest.approx(CENTRE[1])


def test_labels_give_each_angle_from_the_joint_zero_and_from_the_centre():
    text = unescape(re.sub(r"<[^>]+>", "\n", spring_svg(_entry(), "t")))
    assert "joint LF_femur: angles from its zero" in text
    assert "spring stop (leg rests here, preloaded): +14.3° (-14.3° from the centre of motion)" \
        in text
    assert "hard stop on the spring's leg: +68.8° (+40.1° from the centre of motion)" in text
    assert "preload wind-up at the stop: 151.8°" in text
    assert "pushes the joint towards lower angles" in text
    below = unescape(re.sub(r"<[^>]+>", "\n", spring_svg(_entry(side="below"), "t")))
    assert "towards higher angles" in below


def test_a_spring_without_stop_is_drawn_without_one():
    e = _entry(contact=None, contact_from_centre=None, hard_stop=None,
               hard_stop_from_centre=None, role="single", engaged_throughout=False)
    svg = spring_svg(e, "t")
    assert set(_rays(svg)) == {"zero", "low", "high", "centre", "free"}
    assert "spring stop" not in svg and "hard stop" not in svg


def test_one_drawing_per_part_named_by_group_and_side():
    a, b = _entry(), _entry(joint="RF_femur")
    c = _entry(part=1, side="below", group="tibia")
    d = _entry(part=2, side="below", group="tibia")
    assert list(drawings([a, b, c, d])) == ["spring_femur_above", "spring_tibia_below",
                                            "spring_tibia_below_2"]
    # a group named by its joints' legs (Solo-12: "hfe LH/RH") is a file name, not a path
    assert list(drawings([_entry(group="hfe LH/RH", side="below")])) == \
        ["spring_hfe_LH_RH_below"]


def test_degrees_never_read_minus_zero():
    assert format_degrees(-1e-9) == "+0.0°"
    assert format_degrees({"value": math.radians(-12.79), "unit": "rad"}) == "-12.8°"
    with pytest.raises(ValueError, match="not an angle in rad"):
        format_degrees({"value": 1.0, "unit": "deg"})


def test_design_page_angles_under_absolute_equal_design_json(design_written):
    """Issue #57: under any heading of design.html that says "absolute", each angle is
    design.json's joint angle (from the joint's zero), and one drawing per spring to buy."""
    out = design_written[1]
    data = json.loads((out / "design.json").read_text())
    html = (out / "design.html").read_text()
    heads = [m for m in re.finditer(r"<h(\d)[^>]*>(.*?)</h\1>", html, flags=re.S)
             if "absolute" in m[2]]
    assert len(heads) == 1  # the mounting section, and no other heading says absolute
    table = html[html.index('<table id="mounting">', heads[0].end()):]
    table = table[:table.index("</table>")]
    rows = re.findall(r"<tr><td class=\"name\">(\w+)</td>(.*?)</tr>", table, flags=re.S)
    assert [j for j, _ in rows] == [m["joint"] for m in data["mounting"]]
    for (_, cells), m in zip(rows, data["mounting"], strict=True):
        shown = re.findall(r"([+-]\d+\.\d)°", unescape(cells))
        expected = [format_degrees(m[k])[:-1] for k in ("centre", "low", "high")]
        expected += [format_degrees(m["contact"])[:-1],
                     format_degrees(m["contact_from_centre"])[:-1]]
        assert shown[:5] == expected
    parts = {m["part"] for m in data["mounting"]}
    assert html.count('<svg xmlns="http://www.w3.org/2000/svg" class="spring-drawing"') \
        == len(parts)
    for name in drawings(data["mounting"]):
        assert (out / f"{name}.svg").read_text() in html
    assert "angles absolute" not in html
