"""The springs to buy come from the full spring rules on the chosen gait: the summary, the JSON
and the page say so and show their figures; codesign.json's springs load and simulate."""

from __future__ import annotations

import dataclasses
import json

import pytest
from conftest import RULES_SAMPLES

import hexaleg
from hexaleg.cli import main
from hexaleg.commands.codesign.write import write_result
from hexaleg.design.chain.stages import UNMAPPED
from hexaleg.design.codesign.rules import RULES, per_metre
from hexaleg.report.design_section import design_section


def test_the_springs_to_buy_are_the_rules_recommendation(ruled):
    d = ruled.rules
    springs, source = ruled.recommended
    assert d.pays and springs is d.recommended.optimum.springs
    assert all(rule in source for rule in RULES)
    assert d.maps == () and d.robust is None and UNMAPPED in d.notes  # not rules: left out
    assert d.tolerance is not None and d.envelope and len(d.envelope) == len(d.fatigue)
    assert d.design.families == ("one_sided",) and d.gait.samples == RULES_SAMPLES


def test_their_energy_per_metre_is_reproduced(ruled):
    """The J/m the co-design reports for the springs to buy is what they do on the chosen gait
    (``hexaleg.gait`` + ``Prepared.evaluate`` at the rules' sampling)."""
    robot = hexaleg.load()
    chosen = dataclasses.replace(ruled.chosen, samples=RULES_SAMPLES)
    prepared = hexaleg.prepare(robot, hexaleg.gait(robot, chosen),
                               contact=ruled.constraints.contact())
    springs = ruled.rules.recommended.optimum.springs
    energy = prepared.evaluate(springs, "joule").metrics["total"]["electrical"]
    assert energy / chosen.stride == pytest.approx(per_metre(ruled.rules, chosen.stride),
                                                   rel=1e-9)


def test_summary_and_json_show_the_rules_figures(ruled):
    d = ruled.rules
    text = ruled.summary()
    for words in ("springs to buy (full spring rules", "stops within ±1°", "parsimony",
                  "S_y/σ", "fatigue n_f", "arbor", "simulated electrical saving"):
        assert words in text, words
    f = ruled.to_dict()["full_rules"]
    assert f["rules"] == list(RULES) and f["pays"] and f["settings"]["robustness"] is False
    worst = f["stop_tolerance"]["tolerant"]["worst_saving"]
    assert worst == {"value": pytest.approx(100 * d.tolerance.worst["tolerant"]), "unit": "%"}
    assert [e["group"] for e in f["envelope"]] == [p.group for p, _ in d.fatigue]
    assert all(x["safety_factor"]["unit"] == "1" for x in f["fatigue"])
    assert set(f["recommended"]["groups"]) == set(d.recommended.optimum.groups)
    assert f["per_metre"]["value"] == pytest.approx(per_metre(d, ruled.chosen.stride))


def test_codesign_json_springs_load_and_simulate(ruled, tmp_path, capsys):
    data, _ = write_result(ruled, tmp_path / "out")
    page = (tmp_path / "out" / "codesign.html").read_text()
    assert "Springs to buy" in page and "fatigue safety" in page and "arbor" in page
    # the design page's standard (issue #43): an answer box, the wire to buy, mm/°/%, the
    # hard stops; no code names, no fractions
    assert 'class="answer"' in page and "music wire" in page and "d / D / OD" in page
    for code in ("theta_minus", "stiffness_minus", "(fractions)", "N·m/rad", "_clearance"):
        assert code not in page, code
    stops = [e for e in data["full_rules"]["envelope"] if e["hard_stop"]]
    assert ("Hard stops needed" in page) == bool(stops)
    path = tmp_path / "out" / "codesign.json"
    loaded = hexaleg.load_design(path)
    bought = ruled.rules.recommended.optimum.springs
    assert set(loaded.springs) == set(bought)
    assert all(type(loaded.springs[j]) is type(s) for j, s in bought.items())
    assert loaded.gait is not None and loaded.gait.period == pytest.approx(ruled.chosen.period)
    out = tmp_path / "sim"
    assert main(["simulate", "--springs", str(path), "--cycles", "2", "--out", str(out)]) == 0
    sim = json.loads((out / "simulate.json").read_text())
    assert sim["verdict"] == "walks" and str(path) in sim["design"]
    assert data["recommended"]["springs"] == data["full_rules"]["recommended"]["springs"]
    capsys.readouterr()
    # the rules' own design.json beside it, which hexaleg report --design leads its page with
    lead = design_section(tmp_path / "out" / "design.json", hexaleg.load())
    assert lead is not None and lead["label"] == ruled.rules.recommended.label
    assert lead["savings"]["electrical"]["value"] == pytest.approx(
        data["full_rules"]["recommended"]["saving"]["electrical"]["value"])


def test_rules_that_cannot_run_leave_the_inner_springs(codesigned):
    failed = dataclasses.replace(codesigned, rules="InfeasibleForcesError: no forces")
    springs, source = failed.recommended
    assert springs is codesigned.springs and "inner program" in source
    assert failed.to_dict()["full_rules"]["error"].startswith("InfeasibleForcesError")
    assert "could not run" in failed.summary()
