"""Tests of hexaleg.design.studies.placement: the global optimum of every set of sprung groups, and
the gap the old grid + Nelder–Mead search left."""

from __future__ import annotations

import pytest

from hexaleg.design.studies.placement import placement
from hexaleg.robot.springs import SpringSet

CLASSES = ("coxa", "femur", "tibia")


@pytest.fixture(scope="module")
def dead_zones(prepared200):
    return placement(prepared200, list(CLASSES), "dead_zone")


def test_every_set_is_jointly_optimal_and_never_worse_than_its_parts(prepared200, dead_zones):
    table, optima = dead_zones.table, dead_zones.optima
    assert len(table) == 7 and set(table["springs"]) == set(optima)
    assert table["saving"].is_monotonic_decreasing
    assert (table["benefits"] == (table["saving"] > 0)).all()
    for name, res in optima.items():
        row = table[table["springs"] == name].iloc[0]
        assert row["value"] == res.value and tuple(res.groups) == tuple(name.split("+"))
        assert set(res.springs) == {j for g in res.groups for j in prepared200.robot.joints(g)}
    parts = SpringSet({j: s for g in CLASSES for j, s in optima[g].springs.items()})
    combined = prepared200.evaluate(parts).metrics["total"]["joule"]
    assert optima["coxa+femur+tibia"].value <= combined * (1 + 1e-9)
    # a set may leave a group unsprung: it never saves less than any of its subsets
    for name, res in optima.items():
        for sub, other in optima.items():
            if set(sub.split("+")) < set(name.split("+")):
                assert res.value <= other.value * (1 + 1e-9), (name, sub)


def test_the_old_search_is_never_better(dead_zones):
    """The dead-zone family contains the old offset dead zone and each group's search starts at
    the old optimum: the global optimum of the magnitudes is never worse there."""
    table, old = dead_zones.table, dead_zones.old
    assert set(old) == set(CLASSES)
    for g, o in old.items():
        row = table[table["springs"] == g].iloc[0]
        assert row["old_value"] == o.value
        assert row["value"] <= o.value * (1 + 1e-9)
    assert (table["gap"] >= -1e-9).all()
    assert list(table["gap"]) == pytest.approx(list(table["saving"] - table["old_saving"]))


def test_without_comparison_no_old_columns(prepared200):
    res = placement(prepared200, {"hind_tibiae": ["LH_tibia", "RH_tibia"]}, "linear",
                    compare=False)
    assert list(res.table["springs"]) == ["hind_tibiae"] and not res.old
    assert "gap" not in res.table.columns
