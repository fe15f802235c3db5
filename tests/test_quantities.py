"""Tests of hexaleg.quantities: ``{"value", "unit"}`` numbers of report.json."""

from __future__ import annotations

import json

import numpy as np

from hexaleg.dynamics.energy import metric_unit
from hexaleg.quantities import NON_FINITE, comparison, file_data, json_text, quantity


def test_quantity_of_scalars_and_arrays_keeps_floats_for_json_text():
    """A quantity holds floats (an array flattened), a non-finite one too: the one JSON writer
    (json_text) writes it null and notes where — one policy, not a silent None here."""
    assert quantity(np.float64(1.5), "J") == {"value": 1.5, "unit": "J"}
    assert quantity(None, "J") == {"value": None, "unit": "J"}
    q = quantity(np.array([[1.0, np.inf], [2.0, 3.0]]), "N")
    assert q["value"][0] == 1.0 and q["value"][1] == np.inf and len(q["value"]) == 4
    assert all(type(x) is float for x in q["value"])
    written = json.loads(json_text({"force": q, "saving": quantity(float("nan"), "%")}))
    assert written["force"]["value"] == [1.0, None, 2.0, 3.0]
    assert written["saving"]["value"] is None
    assert written[NON_FINITE]["paths"] == ["force.value[1]", "saving.value"]
    assert file_data({"saving": quantity(float("nan"), "%")}) == {
        "saving": {"value": None, "unit": "%"},
        NON_FINITE: written[NON_FINITE] | {"paths": ["saving.value"]}}


def test_comparison_keys_and_saving_in_percent():
    c = comparison(0.9, 1.0, 0.1, "J")
    assert c == {"with_springs": {"value": 0.9, "unit": "J"},
                 "baseline": {"value": 1.0, "unit": "J"},
                 "saving": {"value": 10.0, "unit": "%"}}


def test_metric_units():
    assert metric_unit("peak_torque") == "N·m" and metric_unit("rms_torque") == "N·m"
    assert metric_unit("electrical") == "J" and metric_unit("net_work") == "J"
