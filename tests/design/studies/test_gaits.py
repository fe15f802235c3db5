"""Tests of hexaleg.design.studies.gaits: a row of the gait study equals the analyses it reports
(energy per cycle, per metre, cost of transport, with the recommended springs), and a gait that
cannot be made is a row with its error; the table's lines show both."""

from __future__ import annotations

import math

import pytest

import hexaleg
from hexaleg.design.studies.gaits import gait_energy, table_header, table_line
from hexaleg.units import G


def test_a_row_is_what_the_analyses_say(robot):
    gait = hexaleg.GaitParams(pattern="ripple", period=1.5, samples=40, slope=math.radians(5))
    row = gait_energy(robot, gait, ["femur"])
    assert row.error is None and row.pattern == "ripple" and row.slope == gait.slope
    assert row.speed == pytest.approx(0.04) and row.distance == pytest.approx(0.06)
    motion = hexaleg.gait(robot, gait)
    prepared = hexaleg.prepare(robot, motion)
    baseline = prepared.evaluate().metrics["total"]["electrical"]
    assert row.energy == pytest.approx(baseline, rel=1e-12)
    assert row.per_metre == pytest.approx(baseline / 0.06, rel=1e-12)
    assert row.cost_of_transport == pytest.approx(baseline / (robot.mass * G * 0.06), rel=1e-12)
    best = hexaleg.optimal_springs(prepared, ["femur"], "preloaded")
    sprung = prepared.evaluate(best.springs).metrics["total"]["electrical"]
    assert row.energy_springs == pytest.approx(sprung, rel=1e-9)
    assert row.per_metre_springs == pytest.approx(sprung / 0.06, rel=1e-9)
    assert row.saving == pytest.approx(1 - sprung / baseline, rel=1e-9)
    assert 0.0 < row.saving < 1.0 and row.springs == best.magnitudes
    line = table_line(row)
    assert len(line) == len(table_header())  # the columns line up under their heads
    cells = line.split()
    assert cells[:3] == ["ripple", "0.040", "+5°"] and cells[-1] == f"{100 * row.saving:.1f}%"
    numbers = [row.per_metre, row.cost_of_transport, row.per_metre_springs,
               row.cost_of_transport_springs]
    assert [float(c) for c in cells[3:7]] == pytest.approx(numbers, abs=5e-3)


def test_a_gait_that_cannot_be_made_is_a_row_with_its_error(robot):
    row = gait_energy(robot, hexaleg.GaitParams(pattern="trot", samples=40), ["femur"])
    assert row.error is not None and row.error.startswith("InvalidParameterError: ")
    assert "tripod, ripple, wave" in row.error
    assert row.energy is None and row.saving is None and row.speed == pytest.approx(0.06)
    assert table_line(row) == "trot      0.060    +0°  InvalidParameterError"
