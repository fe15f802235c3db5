"""Tests of hexaleg.studies.design.data: design.json has every number with its unit and springs
other tools rebuild exactly."""

from __future__ import annotations

import json

import numpy as np

from hexaleg.design.spring_json import spring_from_entry


def _numbers_have_units(node, path="design"):
    """Every float in the document sits in a {value, unit} quantity."""
    if isinstance(node, dict):
        if "value" in node and "unit" in node:
            return
        for k, v in node.items():
            if k in ("solver",):  # the solver's bookkeeping, counts and its own value
                continue
            _numbers_have_units(v, f"{path}.{k}")
    elif isinstance(node, list):
        for i, v in enumerate(node):
            _numbers_have_units(v, f"{path}[{i}]")
    else:
        assert not isinstance(node, float), f"{path} = {node} has no unit"


def test_design_json_numbers_and_springs(written):
    w, out = written
    data = json.loads((out / "design.json").read_text())
    _numbers_have_units(data)
    rec = w.result.recommended
    springs = data["recommended"]["springs"]
    assert {e["joint"] for e in springs} == set(rec.optimum.springs)
    q = w.result.recommended.optimum.analysis.q
    robot = rec.optimum.analysis.robot
    for e in springs:
        law = spring_from_entry(e)
        col = robot.column(e["joint"])
        np.testing.assert_allclose(law.torque(q[:, col]),
                                   rec.optimum.springs[e["joint"]].torque(q[:, col]), rtol=1e-12)
        assert e["family"] == rec.family
    assert data["recommended"]["saving"]["electrical"]["unit"] == "%"
    part = data["recommended"]["parts"][0]["torsion_spring"]
    assert part["rate_nmm_per_deg"]["unit"] == "N·mm/deg" and part["mass"]["unit"] == "kg"


def test_design_json_says_whether_the_baseline_energy_is_plausible(written):
    """The default hexapod (AX-18A) walks at a plausible cost of transport: design.json says so
    with the band and the rule, and the summary line carries no warning."""
    result, out = written
    doc = json.loads((out / "design.json").read_text())["plausibility"]
    assert doc["plausible"] is True and doc["flag"] is None
    assert doc["low"]["value"] < doc["cost_of_transport"]["value"] < doc["high"]["value"]
    assert "Taylor" in doc["rule"] and doc["message"].startswith("plausible")
    assert "WARNING" not in result.result.summary()
