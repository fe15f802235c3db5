"""Tests of hexaleg.dynamics.draw, the whole draw (issue #40): motors, servos at rest and
electronics over one cycle, the saving on it and the battery's hours — by hand on made-up
numbers, from the catalogue's standby currents, and through the report and its page."""

from __future__ import annotations

import json
import math

import pytest

from hexaleg.dynamics.draw import WH, idle_power, whole_draw
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.catalogue import CATALOGUE, STANDBY, standby
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
    """AX-18A publishes no standby current and no electronics power is given: the draw counts
    the motors only, is a lower bound, its saving an upper bound, and names both gaps."""
    draw = whole_draw(2.0, 3.0, 0.5, 0.0, CATALOGUE["AX-18A"], 18)
    assert draw.idle is None and draw.idle_missing == ("AX-18A",) and not draw.complete
    assert draw.saving == pytest.approx(1.0 / 3.0) and draw.per_metre() is None
    assert draw.hours() is None
    assert "AX-18A" in draw.line() and "electronics_power" in draw.line()
    assert "at least" in draw.line() and "at most" in draw.line()
    assert "lower bound" in draw.as_dict()["bound"]


def test_idle_power_sums_per_joint_and_names_the_servos_without_a_figure():
    xm, ax = CATALOGUE["XM540-W150"], CATALOGUE["AX-18A"]
    both = MotorSet.per_class({"a": ("j0", "j1"), "b": ("j2",)}, ("j0", "j1", "j2"),
                              {"a": xm, "b": xm})
    assert idle_power(both, 3)[0] == pytest.approx(3 * 0.48)
    mixed = MotorSet.per_class({"a": ("j0", "j1"), "b": ("j2",)}, ("j0", "j1", "j2"),
                               {"a": xm, "b": ax})
    power, missing, sources = idle_power(mixed, 3)
    assert power is None and missing == ("AX-18A",) and set(sources) == {"XM540-W150", "AX-18A"}
    generic = generic_actuator(3.0, 5.0)
    assert idle_power(generic, 2)[1] == ("generic",)
    assert "not a catalogue servo" in standby("generic").source


def test_every_catalogue_servo_says_where_its_standby_figure_comes_from():
    assert set(STANDBY) == set(CATALOGUE)
    for name, entry in STANDBY.items():
        assert entry.source and (entry.current is None or 0.0 < entry.current < 1.0), name
        if entry.current is not None:
            assert "emanual.robotis.com" in entry.source


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
    assert draw["idle_power"] is None and draw["idle_missing"] == ["AX-18A"]
    assert draw["motors_baseline"]["unit"] == "W" and not draw["complete"]
    period = data["gait"]["period"]["value"]
    assert draw["motors_baseline"]["value"] == pytest.approx(
        data["energy"]["totals"]["electrical"]["baseline"]["value"] / period, rel=1e-12)
    answer = data["design"]["whole_draw"]
    assert answer["saving"]["unit"] == "%"
    page = (out / "report.html").read_text()
    assert 'id="whole-draw"' in page and "not\npublished for AX-18A" in page
    assert "whole draw" in report.summary()
