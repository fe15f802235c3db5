"""Tests of hexaleg.dynamics.draw, the whole draw (issue #40): motors, servos at rest and
electronics over one cycle, the saving on it and the battery's hours — by hand on made-up
numbers, from the catalogue's standby currents, and through the report and its page."""

from __future__ import annotations

import json
import math

import pytest

from hexaleg.dynamics.draw import WH, whole_draw
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.catalogue import CATALOGUE
from hexaleg.robot.description import RobotDescription
from hexaleg.robot.motor import generic_actuator
from hexaleg.robot.motor_set import MotorSet


def test_the_whole_draw_by_hand():
    """18 XM540-W150 at 12 V, 40 mA each: 8.64 W at rest; 5 W of electronics; motors 3 J and
    2 J a cycle of 0.5 s (6 W and 4 W); 0.05 m a cycle."""
    motor = CATALOGUE["XM540-W150"]
    draw = whole_draw(2.0, 3.0, 0.5, 0.05, motor, 18, electronics=5.0, battery_wh=22.2)
    assert draw.idle == pytest.approx(18 * 0.040 * 12.0, rel=1e-12) and draw.complete
    assert draw.motors == 4.0 and draw.motors_baseline == 6.0
    assert draw.total_baseline == pytest.approx(6.0 + 8.64 + 5.0, rel=1e-12)
    assert draw.saving == pytest.approx(2.0 / (6.0 + 8.64 + 5.0), rel=1e-12)
    assert draw.per_metre() == pytest.approx((4.0 + 8.64 + 5.0) / 0.1, rel=1e-12)
    assert draw.hours() == pytest.approx(22.2 * WH / (4.0 + 8.64 + 5.0) / 3600.0, rel=1e-12)
    data = draw.as_dict()
    assert data["idle_power"] == {"value": pytest.approx(8.64), "unit": "W"}
    assert data["bound"] is None and data["hours"]["unit"] == "h"
    json.dumps(data)


def test_an_unknown_term_makes_a_bound_and_says_which():
    """The MX-64 publishes no standby current and no electronics power is given: the draw counts
    the motors only, is a lower bound, its saving an upper bound, and names both gaps."""
    draw = whole_draw(2.0, 3.0, 0.5, 0.0, CATALOGUE["MX-64"], 18)
    assert draw.idle is None and draw.idle_missing == ("MX-64",) and not draw.complete
    assert draw.saving == pytest.approx(1.0 / 3.0) and draw.per_metre() is None
    assert draw.hours() is None and draw.saving_range() is None
    assert "MX-64" in draw.line() and "electronics_power" in draw.line()
    assert "at least" in draw.line() and "at most" in draw.line()
    assert "lower bound" in draw.as_dict()["bound"]
    assert draw.as_dict()["idle_range"] is None


def test_the_hexapods_idle_draw_is_the_ax_familys_by_hand():
    """18 AX-18A: no figure of its own; the AX-12A's 50 mA at the AX-18A's 12 V is
    18 × 0.050 × 12 = 10.8 W, the family's 17–60 mA 3.672–12.96 W, and the saving on the whole
    draw over that range is the motors' 2 W over 6 + idle W."""
    draw = whole_draw(2.0, 3.0, 0.5, 0.0, CATALOGUE["AX-18A"], 18)
    assert CATALOGUE["AX-18A"].voltage == 12.0
    assert draw.idle == pytest.approx(10.8, rel=1e-12)
    assert (draw.idle_low, draw.idle_high) == (pytest.approx(3.672, rel=1e-12),
                                               pytest.approx(12.96, rel=1e-12))
    assert draw.idle_family == ("AX-18A",)
    assert draw.saving == pytest.approx(2.0 / (6.0 + 10.8), rel=1e-12)
    assert draw.saving_range() == (pytest.approx(2.0 / (6.0 + 12.96), rel=1e-12),
                                   pytest.approx(2.0 / (6.0 + 3.672), rel=1e-12))
    assert "its family's standby current" in draw.line()
    data = draw.as_dict()
    assert data["idle_range"] == {"low": {"value": pytest.approx(3.672), "unit": "W"},
                                  "high": {"value": pytest.approx(12.96), "unit": "W"}}
    assert data["idle_family"] == ["AX-18A"]
    assert "not the AX-18A's own" in data["idle_sources"]["AX-18A"]
    own = whole_draw(2.0, 3.0, 0.5, 0.0, CATALOGUE["AX-12A"], 18)
    assert own.idle == own.idle_low == own.idle_high == pytest.approx(10.8)
    assert own.idle_family == ()


def test_the_whole_draw_takes_the_actuators_idle_power():
    """The draw's idle figures are its actuator's ``idle_power`` over the joints, a set's
    joint by joint (tests/robot/test_standby.py checks the sums themselves)."""
    xm, mx = CATALOGUE["XM540-W150"], CATALOGUE["MX-64"]
    both = MotorSet.per_class({"a": ("j0", "j1"), "b": ("j2",)}, ("j0", "j1", "j2"),
                              {"a": xm, "b": CATALOGUE["AX-18A"]})
    draw = whole_draw(2.0, 3.0, 0.5, 0.0, both, 3)
    idle = both.idle_power(3)
    assert (draw.idle, draw.idle_low, draw.idle_high) == (idle.power, idle.low, idle.high)
    assert draw.idle == pytest.approx(2 * 0.48 + 0.6) and draw.idle_family == ("AX-18A",)
    mixed = MotorSet.per_class({"a": ("j0", "j1"), "b": ("j2",)}, ("j0", "j1", "j2"),
                               {"a": xm, "b": mx})
    draw = whole_draw(2.0, 3.0, 0.5, 0.0, mixed, 3)
    assert draw.idle is None and draw.idle_missing == ("MX-64",)


@pytest.mark.parametrize(("key", "value"), [("electronics_power", -1.0),
                                            ("electronics_power", math.nan),
                                            ("battery_wh", 0.0), ("battery_wh", "big")])
def test_the_description_refuses_a_bad_power_or_battery(key, value):
    with pytest.raises(InvalidParameterError, match=key):
        RobotDescription(name="r", urdf="r.urdf", **{key: value})


def test_the_report_states_the_whole_draw(report_written):
    """The default hexapod's report.json has the whole draw, the answer's saving on it, and the
    page leads with it (AX-18A: a lower bound that says why)."""
    report, out = report_written
    data = json.loads((out / "report.json").read_text())
    draw = data["whole_draw"]
    assert 3.0 <= draw["idle_power"]["value"] <= 15.0 and draw["idle_family"] == ["AX-18A"]
    assert draw["idle_power"]["value"] == pytest.approx(18 * 0.050 * 12.0, rel=1e-12)
    assert "not the AX-18A's own" in draw["idle_sources"]["AX-18A"]
    assert draw["motors_baseline"]["unit"] == "W" and not draw["complete"]
    period = data["gait"]["period"]["value"]
    assert draw["motors_baseline"]["value"] == pytest.approx(
        data["energy"]["totals"]["electrical"]["baseline"]["value"] / period, rel=1e-12)
    assert draw["total_baseline"]["value"] == pytest.approx(
        draw["motors_baseline"]["value"] + draw["idle_power"]["value"], rel=1e-12)
    low, high = (draw["saving_range"][k]["value"] for k in ("low", "high"))
    assert low < draw["saving"]["value"] < high
    answer = data["design"]["whole_draw"]
    assert answer["saving"]["unit"] == "%"
    page = (out / "report.html").read_text()
    assert 'id="whole-draw"' in page and "its servo family's standby current" in page
    assert "whole draw" in report.summary()


def test_a_draw_on_assumed_constants_is_never_called_a_bound():
    """#59: ANYmal's 383 W rested on a generic actuator and was called 'a lower bound'. With
    the motors' draw on assumed constants the draw is an estimate, whatever else is missing."""
    generic = generic_actuator(80.0, 15.0)
    draw = whole_draw(230.1, 230.1, 0.6, 0.3, generic, 12)
    assert draw.assumed and not draw.is_bound and not draw.complete
    assert "at least" not in draw.line() and "at most" not in draw.line()
    assert "an estimate, not a bound" in draw.line()
    data = draw.as_dict()
    assert data["is_bound"] is False and data["bound"].startswith("an estimate, not a bound")
    named = whole_draw(2.0, 3.0, 0.5, 0.0, CATALOGUE["MX-64"], 18)
    assert named.is_bound and not named.assumed and named.as_dict()["is_bound"] is True


def test_docs_quote_the_hexapods_idle_draw():
    """docs/energy.md's idle figures are the default robot's 18 AX-18A's idle power."""
    from pathlib import Path

    text = " ".join((Path(__file__).resolve().parents[2] / "docs" / "energy.md").read_text()
                    .split())
    idle = CATALOGUE["AX-18A"].idle_power(18)
    assert idle.power is not None and idle.low is not None and idle.high is not None
    quoted = (f"18 × 0.050 A × 12 V = {idle.power:.3g} W ({idle.low:.3g}–{idle.high:.4g} W "
              "over the family's range)")
    assert quoted in text
