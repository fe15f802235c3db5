"""Tests of hexaleg.design.placement: per-group optima and every combination of groups."""

from __future__ import annotations

import pytest

from hexaleg.design.evaluator import RunSpec, evaluator
from hexaleg.design.placement import placement

SAMPLES = 200
RUN = RunSpec()


@pytest.fixture(scope="module")
def ev():
    return evaluator(RUN, {"samples": SAMPLES})


@pytest.fixture(scope="module")
def classes(robot):
    return {c: robot.joints(c) for c in ("coxa", "femur", "tibia")}


def test_placement_combines_per_class_optima(ev, classes):
    optima, table = placement(ev, classes, k_bounds=(0.01, 1.0), grid=(4, 2))
    assert len(table) == 7 and set(table["springs"]) >= {"coxa", "femur+tibia",
                                                         "coxa+femur+tibia"}
    for g, o in optima.items():
        row = table[table["springs"] == g].iloc[0]
        assert row["value"] == o.value and row["saving"] == pytest.approx(o.saving)
        assert o.value <= o.grid_value  # the search never ends worse than its start
    both = table[table["springs"] == "coxa+tibia"].iloc[0]
    direct = ev.value(classes, {"coxa": optima["coxa"].design(),
                                "tibia": optima["tibia"].design()})
    assert both["value"] == direct
    assert (table["benefits"] == (table["saving"] > 0)).all()
    assert table["saving"].is_monotonic_decreasing
