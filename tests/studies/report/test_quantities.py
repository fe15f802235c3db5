"""Tests of hexaleg.studies.report.quantities: ``{"value", "unit"}`` numbers of report.json."""

from __future__ import annotations

import json

import numpy as np

from hexaleg.studies.report.quantities import comparison, metric_unit, quantity


def test_quantity_of_scalars_and_arrays_is_json_with_none_for_non_finite():
    assert quantity(np.float64(1.5), "J") == {"value": 1.5, "unit": "J"}
    assert quantity(float("nan"), "%") == {"value": None, "unit": "%"}
    q = quantity(np.array([[1.0, np.inf], [2.0, 3.0]]), "N")
    assert q == {"value": [1.0, None, 2.0, 3.0], "unit": "N"}
    assert json.loads(json.dumps(q)) == q
    assert all(type(x) is float for x in q["value"] if x is not None)


def test_comparison_keys_and_saving_in_percent():
    c = comparison(0.9, 1.0, 0.1, "J")
    assert c == {"with_springs": {"value": 0.9, "unit": "J"},
                 "baseline": {"value": 1.0, "unit": "J"},
                 "saving": {"value": 10.0, "unit": "%"}}


def test_metric_units():
    assert metric_unit("peak_torque") == "N·m" and metric_unit("rms_torque") == "N·m"
    assert metric_unit("electrical") == "J" and metric_unit("net_work") == "J"
