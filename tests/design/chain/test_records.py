"""Tests of hexaleg.design.chain.records: a candidate's springs rebuild exactly from its record,
a robustness map's record is its grids and worst cases in %, a ranked run that did not walk has
no simulated saving."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pytest

from hexaleg.design.chain.records import (
    AXIS_UNITS,
    candidate_data,
    map_data,
    ranking_data,
    robust_data,
)
from hexaleg.design.springs.law_json import spring_from_entry
from hexaleg.quantities import file_data


def test_a_candidate_record_is_design_json_s_and_rebuilds_its_springs(design_written):
    """design.json's ``recommended`` is the recommendation's record; each spring entry rebuilds
    the spring's law to the last digit, and the parts carry their units."""
    w, out = design_written
    r = w.result
    rec = r.recommended
    record = file_data(candidate_data(rec, r.outer))
    assert json.loads((out / "design.json").read_text())["recommended"] == record
    springs = record["springs"]
    assert {e["joint"] for e in springs} == set(rec.optimum.springs)
    q = rec.optimum.analysis.q
    robot = rec.optimum.analysis.robot
    for e in springs:
        law = spring_from_entry(e)
        col = robot.column(e["joint"])
        np.testing.assert_allclose(law.torque(q[:, col]),
                                   rec.optimum.springs[e["joint"]].torque(q[:, col]), rtol=1e-12)
        assert e["family"] == rec.family
    assert record["saving"]["electrical"]["unit"] == "%"
    part = record["parts"][0]
    assert part["max_outer_diameter_source"] == r.outer[part["group"]][1]
    assert part["torsion_spring"]["rate_nmm_per_deg"]["unit"] == "N·mm/deg"
    assert part["torsion_spring"]["mass"]["unit"] == "kg"


def test_a_map_record_holds_its_grids_and_worst_cases_in_percent(design_written):
    """Each map's saving grid is the map's in %, its axes with their units (a pattern axis as
    names), and its worst case the map's own."""
    maps = design_written[0].result.maps
    assert any("pattern" in m.axes for m in maps)
    for m in maps:
        d = map_data(m)
        assert d["axes"] == list(m.axes)
        for axis, values in zip(m.axes, m.values, strict=True):
            if axis == "pattern":
                assert d["values"][axis] == [str(v) for v in values]
            else:
                assert d["values"][axis]["unit"] == AXIS_UNITS[axis]
        for k, grid in m.saving.items():
            np.testing.assert_array_equal(d["saving"][k]["value"], 100 * np.asarray(grid))
            s, cond = m.worst(k)
            assert d["worst"][k]["saving"]["value"] == pytest.approx(100 * s, rel=1e-15)
            assert d["worst"][k]["condition"] == (cond.label() if cond else None)


def test_a_ranked_run_that_did_not_walk_has_no_simulated_saving(design_written):
    row = design_written[0].result.ranking[0]
    fell = dataclasses.replace(row, simulated=None, verdict="fell")
    d = ranking_data(fell)
    assert d["simulated_saving"] is None and d["verdict"] == "fell"
    assert d["predicted_saving"]["value"] == pytest.approx(100 * row.predicted, rel=1e-15)
    assert ranking_data(row)["simulated_saving"]["value"] == pytest.approx(
        100 * row.simulated, rel=1e-15)


def test_the_robust_record_is_the_robust_designs_worst_cases(design_written):
    r = design_written[0].result
    assert r.robust is not None
    d = robust_data(r.robust, r.outer)
    assert d["conditions"] == [c.label() for c in r.robust.conditions]
    for m, s in r.robust.savings.items():
        for k in s:
            assert d["worst"][m][k]["value"] == pytest.approx(100 * r.robust.worst(m, k),
                                                              rel=1e-15)
    assert d["design"]["label"] == r.robust.candidate.label
