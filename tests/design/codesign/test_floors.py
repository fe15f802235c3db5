"""The springs to buy on floors of other friction (issue #41)."""

from __future__ import annotations

import pytest

import hexaleg
from hexaleg.design.codesign.floors import FLOORS, Floor, over_floors, worst
from hexaleg.robot.registry import description


def test_on_the_planning_cone_the_floor_gives_the_search_s_own_saving(codesigned):
    """The search planned its forces inside friction_margin · μ (0.42 of a μ 0.6 floor): a floor
    of that μ, analysed afresh, gives the inner program's saving (another path: the co-design's
    evaluation of its chosen gait)."""
    c = codesigned.constraints
    robot = hexaleg.load()
    motor = description("hexaleg").actuator(robot)
    planning = over_floors(robot, codesigned.chosen, motor, codesigned.springs, c.torque_limits,
                           floors=(c.friction_margin * c.mu,))[0]
    assert planning.saving == pytest.approx(codesigned.inner_saving, abs=1e-6)


def test_the_result_states_every_floor_and_the_worst(codesigned):
    assert [f.mu for f in codesigned.floors] == list(FLOORS)
    low = worst(codesigned.floors)
    assert low is not None and low.saving == min(f.saving for f in codesigned.floors
                                                 if f.saving is not None)
    data = codesigned.to_dict()["floors"]
    assert data["worst"]["mu"]["value"] == low.mu
    assert "on other floors" in codesigned.summary()


def test_a_floor_too_slippery_for_the_gait_is_a_row_not_an_error(codesigned):
    robot = hexaleg.load()
    rows = over_floors(robot, codesigned.chosen, description("hexaleg").actuator(robot),
                       codesigned.springs, floors=(0.01, 0.6))
    assert rows[0].saving is None and "Error" in (rows[0].error or "")
    assert rows[1].saving is not None and worst(rows) is rows[1]
    assert worst([Floor(0.4, None, "none")]) is None
    assert worst([Floor(0.4, 0.1), Floor(0.6, 0.1)]).mu == 0.4  # the first of equals
